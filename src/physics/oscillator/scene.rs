//! The oscillator as every layer above `physics/` sees it ([`Scene`], [`Posed`]).
use crate::physics::numerics::elementary::Elementary;

use super::{Params, Problem, Start};
use crate::physics::chart::MapFlag;
use crate::physics::flow::{Flow, GoOn};
use crate::physics::method::{Arithmetic, Asked, Method, RunSpec, StepError};
use crate::physics::params::{Allowed, ParamError, ParamSpec, Scale};
use crate::physics::plan::PlanRequest;
use crate::physics::scene::{
    ChartWords, Drawing, Figure, Ink, Planned, Posed, Scene, Shape, Shown, SlowCurve, Studies,
    SummaryLine, WeakStudy, Words,
};
use crate::physics::scene::{FreeRotor, SlowLimit};

/// The oscillator's figure (issue 83: a body of a new kind, drawn from its folder): a wall at
/// the left, the spring as a zigzag to the mass at `x` (its amplitude `knobs[0]` reaching 0.8
/// of the half-side), the spring's rest position.
fn spring(knobs: &[f64; 4], _t: f64, now: &crate::physics::flow::Sample) -> Vec<Shape> {
    let amplitude = if knobs[0] > 0.0 { knobs[0] } else { 1.0 };
    let mass = (0.8 * now.q / amplitude).clamp(-0.95, 0.95);
    let wall = -1.0;
    let mut shapes = vec![
        Shape::Line {
            from: (wall, -0.5),
            to: (wall, 0.5),
            ink: Ink::Fixed,
        },
        Shape::Line {
            from: (0.0, -0.3),
            to: (0.0, 0.3),
            ink: Ink::Dim,
        },
    ];
    // Eight zigzag segments from the wall to the mass.
    let turns = 8;
    let point = |i: usize| {
        let x = wall + (mass - wall) * i as f64 / turns as f64;
        let y = match i {
            0 => 0.0,
            i if i == turns => 0.0,
            i if i % 2 == 1 => 0.15,
            _ => -0.15,
        };
        (x, y)
    };
    shapes.extend((0..turns).map(|i| Shape::Line {
        from: point(i),
        to: point(i + 1),
        ink: Ink::Body,
    }));
    shapes.push(Shape::Glyph {
        at: (mass, 0.0),
        glyph: '●',
        ink: Ink::Current,
    });
    shapes
}

/// Its parameter table: `[oscillator] omega`, `[initial] x`, `v`.
pub const PARAMS: [ParamSpec; 3] = [
    ParamSpec::required(
        ("oscillator", "omega"),
        Allowed::Between {
            lo: 1e-3,
            hi: 1e3,
            text: "a number in [0.001, 1000] (rad/s)",
        },
        Scale::linear(0.1, 1.0),
        "the angular frequency (rad/s)",
    ),
    ParamSpec::optional(
        ("initial", "x"),
        Allowed::Between {
            lo: -1e6,
            hi: 1e6,
            text: "a number of magnitude at most 1e6",
        },
        1.0,
        Scale::linear(0.1, 1.0),
        "position at t = 0",
    ),
    ParamSpec::optional(
        ("initial", "v"),
        Allowed::Between {
            lo: -1e6,
            hi: 1e6,
            text: "a number of magnitude at most 1e6",
        },
        0.0,
        Scale::linear(0.1, 1.0),
        "velocity at t = 0",
    ),
];

/// The oscillator's fixed facts.
pub static SCENE: Scene = Scene {
    name: "oscillator",
    title: "harmonic oscillator",
    words: Words {
        q_name: "position",
        q_dot_name: "velocity",
        q: "x",
        q_dot: "v",
        fast: "x",
        fast_name: "position",
        event: "crossing",
        events: "crossings",
        event_meaning: "the position changing sign",
        second_events: None,
        monitor: Some(crate::physics::scene::Monitor {
            label: "ΔE",
            column: "energy_error",
            meaning: "the error of the conserved energy",
        }),
    },
    params: &PARAMS,
    model_required: true,
    methods: &super::flows::METHODS,
    limit_tolerance: 1e-10,
    small: None,
    studies: Studies {
        weak: None,
        chart: ChartWords {
            title: "crossing chart (M)",
            curve: "none",
            note: "across: omega; up: v0",
            axes: ("omega", "v0"),
            sources: false,
            pane: super::chart::GRID,
            axis_keys: super::chart::AXES,
            heading: "crossings",
            legend: ". none, 1-9 crossings, + 10 or more",
            pane_legend: [
                "crossings in [0, T]: 1, 2-3, 4-7, 8 or more (blank: none)",
                "undecided (never: each count is exact or verified)",
            ],
            csv: super::chart::COLUMNS,
            flags: &[MapFlag::Columns, MapFlag::Rows, MapFlag::TEnd],
        },
        counterpart: "subcritical",
    },
};

crate::physics::scene::table_order!(Params { omega }, Start { x, v });

impl Posed for Problem {
    fn scene(&self) -> &'static Scene {
        &SCENE
    }
    fn values(&self) -> Vec<f64> {
        self.table_values()
    }
    fn summary(&self) -> Vec<SummaryLine> {
        let s = self.start();
        vec![SummaryLine::new(
            "energy E",
            "the start's energy per unit mass",
            Shown::Number(Some(self.energy(s.x, s.v))),
        )]
    }
    fn slow_start(&self) -> (f64, f64) {
        (self.start().x, self.start().v)
    }
    fn default_step(&self, _method: Method, tolerance: f64, _t_end: f64) -> f64 {
        tolerance.clamp(1e-16, 1.0).e_powf(0.125) / self.params().omega
    }
    fn slow_limit(&self) -> std::sync::Arc<dyn SlowLimit> {
        let s = self.start();
        std::sync::Arc::new(FreeRotor {
            mass: 1.0,
            energy: self.energy(s.x, s.v),
            q_dot0: s.v,
        })
    }
    fn drawing(&self) -> Drawing {
        let s = self.start();
        let w = s.v / self.params().omega;
        let amplitude = (s.x * s.x + w * w).sqrt();
        Drawing::Figure(Figure {
            title: "a mass on a spring",
            knobs: [amplitude, 0.0, 0.0, 0.0],
            shapes: spring,
            legend: &[
                (Ink::Fixed, "the wall"),
                (Ink::Body, "the spring"),
                (Ink::Dim, "where the spring is at rest"),
                (Ink::Current, "the mass, at x"),
            ],
        })
    }
    fn build(&self, ask: &Asked, _: Arithmetic) -> Result<Box<dyn Flow>, StepError> {
        Ok(Box::new(super::flows::build(self, ask)?))
    }
    fn resolve(&self, ask: &PlanRequest, go_on: &mut dyn FnMut(f64) -> bool) -> Planned {
        super::flows::resolve(self, ask, go_on)
    }
    fn predicted_seconds(&self, ask: &Asked) -> f64 {
        super::flows::cost_seconds(self, ask)
    }
    fn chart_point(&self) -> (f64, f64) {
        (self.params().omega, self.start().v)
    }
    fn weak(&self) -> Option<&dyn WeakStudy> {
        None
    }
    fn slow_curve(&self, ask: &Asked, samples: usize, go_on: GoOn) -> Result<SlowCurve, StepError> {
        let r = self.resolve(&PlanRequest::verified(ask), go_on)?;
        let plan = Asked::new(r.plan.method, r.plan.tolerance, None, ask.t_end);
        let run = super::flows::run(self, &RunSpec::new(plan, samples), go_on)?;
        let (t, q) = run.samples.iter().map(|s| (s[0], s[1])).unzip();
        Ok(SlowCurve {
            t,
            q,
            method: r.plan.method,
            estimate: r.estimate.unwrap_or(0.0),
        })
    }
}

/// What a plan of this scene was resolved for (the registry's `PlanKey` holds it) (field names differ from the other scenes': the untagged form stays unambiguous).
#[derive(
    Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[schemars(inline)]
pub struct PlanKey {
    /// `omega`.
    pub oscillator: super::Params,
    /// `x`, `v`.
    pub oscillator_start: super::Start,
    /// Tolerance asked.
    pub tolerance: f64,
    /// Horizon.
    pub t_end: f64,
}

impl PlanKey {
    /// The key of `p` run to `t_end` at `tolerance`.
    #[must_use]
    pub fn of(p: &Problem, tolerance: f64, t_end: f64) -> Self {
        Self {
            oscillator: *p.params(),
            oscillator_start: *p.start(),
            tolerance,
            t_end,
        }
    }
}
