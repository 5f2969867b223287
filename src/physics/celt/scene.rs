//! The classical rattleback as every layer above `physics/` sees it: its parameter table,
//! words, studies and the facts of a posed problem ([`Scene`], [`Posed`]). Nothing outside
//! this folder names a celt parameter.
//!
//! What the explorer draws of a state ([`crate::physics::flow::Sample`]): the angle turned
//! about the vertical `φ = ∫ ω·γ dt` as the slow coordinate, the spin `ω·γ` as its rate, the
//! tilt from upright as the fast coordinate. Events are spin reversals (with the band) and
//! raw crossings.
use crate::physics::numerics::elementary::Elementary;

use super::{Params, Problem, Start, TILT_MAX};
use crate::physics::chart::MapFlag;
use crate::physics::flow::Flow;
use crate::physics::flow::GoOn;
use crate::physics::method::Arithmetic;
use crate::physics::method::Asked;
use crate::physics::method::RunSpec;
use crate::physics::method::{Method, StepError};
use crate::physics::params::{Allowed, ParamError, ParamSpec, Scale};
use crate::physics::plan::PlanRequest;
use crate::physics::scene::{
    ChartWords, Drawing, Found, Planned, Posed, Scene, SecondEvents, Shown, SideView, SlowCurve,
    Studies, SummaryLine, WeakStudy, Words,
};
use crate::physics::scene::{FreeRotor, SlowLimit};

const LENGTH: Scale = Scale::linear(0.1, 1.0);
const INERTIA: Scale = Scale::linear(0.1, 1.0);
const ANGLE: Scale = Scale::linear(0.001, 0.01);
const RATE: Scale = Scale::linear(0.1, 1.0);

const TILT: Allowed = Allowed::Between {
    lo: -TILT_MAX,
    hi: TILT_MAX,
    text: "a number in [-1.5, 1.5] (rad)",
};

/// The celt's parameters, in the panel's order. Names are a contract: add, never rename.
pub const PARAMS: [ParamSpec; 16] = [
    ParamSpec::required(
        ("celt", "a"),
        Allowed::Positive,
        LENGTH,
        "semi-axis of the ellipsoidal bottom along body x, the long axis (cm)",
    ),
    ParamSpec::required(
        ("celt", "b"),
        Allowed::Positive,
        LENGTH,
        "semi-axis along body y (cm)",
    ),
    ParamSpec::required(
        ("celt", "c"),
        Allowed::Positive,
        LENGTH,
        "semi-axis along body z, the vertical at rest (cm)",
    ),
    ParamSpec::required(
        ("celt", "offset"),
        Allowed::Finite,
        LENGTH,
        "h: the mass centre lies h below the ellipsoid's centre on the c-axis; must be below c (cm)",
    ),
    ParamSpec::required(
        ("celt", "ix"),
        Allowed::Positive,
        INERTIA,
        "A: moment of inertia about body x through the mass centre, per unit mass (cm^2)",
    ),
    ParamSpec::required(
        ("celt", "iy"),
        Allowed::Positive,
        INERTIA,
        "B: about body y (cm^2)",
    ),
    ParamSpec::required(
        ("celt", "iz"),
        Allowed::Positive,
        INERTIA,
        "C: about body z (cm^2)",
    ),
    ParamSpec::required(
        ("celt", "product"),
        Allowed::Finite,
        Scale::linear(0.01, 0.1),
        "D: the inertia tensor's entry I_xy (Kane's convention), per unit mass; its sign sets the preferred sense of spin, 0 has none (cm^2)",
    ),
    ParamSpec::optional(
        ("celt", "gravity"),
        Allowed::NonNegative,
        DEFAULT_GRAVITY,
        Scale::linear(1.0, 100.0),
        "gravity (cm/s^2)",
    ),
    ParamSpec::optional(
        ("initial", "roll"),
        TILT,
        0.0,
        ANGLE,
        "roll about body x at t = 0 (rad)",
    ),
    ParamSpec::optional(
        ("initial", "pitch"),
        TILT,
        0.0,
        ANGLE,
        "pitch about body y at t = 0 (rad)",
    ),
    ParamSpec::optional(
        ("initial", "yaw"),
        crate::physics::params::ANGLE,
        0.0,
        ANGLE,
        "heading at t = 0 (rad)",
    ),
    ParamSpec::optional(
        ("initial", "omega_x"),
        Allowed::Finite,
        0.0,
        RATE,
        "body-frame angular velocity about x at t = 0 (rad/s)",
    ),
    ParamSpec::optional(
        ("initial", "omega_y"),
        Allowed::Finite,
        0.0,
        RATE,
        "about y (rad/s)",
    ),
    ParamSpec::optional(
        ("initial", "omega_z"),
        Allowed::Finite,
        0.0,
        RATE,
        "about z; negative is clockwise seen from above (rad/s)",
    ),
    ParamSpec::optional(
        ("run", "spin_band"),
        Allowed::NonNegative,
        DEFAULT_BAND,
        Scale::linear(0.05, 0.5),
        "hysteresis band of a reversal: the spin must reach this size with the new sign (rad/s)",
    ),
];

/// The gravity of a preset that gives none.
pub const DEFAULT_GRAVITY: f64 = 981.0;
/// The band of a preset that gives none.
pub const DEFAULT_BAND: f64 = 0.5;

/// The values of a problem, in the order of [`PARAMS`].
#[must_use]
pub fn values_of(p: &Params, s: &Start, band: f64) -> Vec<f64> {
    vec![
        p.a, p.b, p.c, p.offset, p.ix, p.iy, p.iz, p.product, p.gravity, s.roll, s.pitch, s.yaw,
        s.omega[0], s.omega[1], s.omega[2], band,
    ]
}

/// The celt's scene.
pub static SCENE: Scene = Scene {
    name: "celt",
    title: "classical rattleback (celt)",
    words: Words {
        q_name: "turn",
        q_dot_name: "spin",
        q: "φ",
        q_dot: "ω·γ",
        fast: "tilt",
        fast_name: "tilt",
        event: "reversal",
        events: "reversals",
        event_meaning: "the spin changing sign and reaching spin_band with the new sign",
        second_events: Some(SecondEvents {
            name: "crossings",
            meaning: "any sign change of the spin",
            found: Found::Flow,
        }),
        monitor: Some(crate::physics::scene::Monitor {
            label: "ΔE/E",
            column: "energy_error",
            meaning: "the relative error of the conserved energy",
        }),
    },
    params: &PARAMS,
    model_required: true,
    methods: &super::flows::METHODS,
    // No limit: nothing runs at it.
    limit_tolerance: 1e-10,
    small: None,
    studies: Studies {
        weak: None,
        chart: ChartWords {
            title: "reversal chart (M)",
            curve: "linear theory: the tilt reaches 1 rad within T at the steady spin's growth rate",
            note: "across: initial omega_z (both senses); up: product of inertia",
            axes: ("omega_z", "D"),
            sources: false,
            pane: super::chart::CELT_GRID,
            axis_keys: super::chart::AXES,
            heading: "reversals",
            legend: ". none, 1-9 reversals, + 10 or more, ? two tolerances disagree",
            pane_legend: [
                "reversals in [0, T]: 1, 2-3, 4-7, 8 or more (blank: none)",
                "undecided: two tolerances count differently (a chaotic window)",
            ],
            csv: super::chart::COLUMNS,
            flags: &[
                MapFlag::Columns,
                MapFlag::Rows,
                MapFlag::TEnd,
                MapFlag::Tolerance,
            ],
        },
        counterpart: "subcritical",
    },
};

impl Problem {
    /// The problem of `values`, in the order of [`PARAMS`].
    ///
    /// # Errors
    /// The first value outside its range, or a body that cannot be.
    pub fn from_values(values: &[f64]) -> Result<Self, ParamError> {
        let v = |i: usize| values.get(i).copied().unwrap_or(f64::NAN);
        Self::new(
            Params {
                a: v(0),
                b: v(1),
                c: v(2),
                offset: v(3),
                ix: v(4),
                iy: v(5),
                iz: v(6),
                product: v(7),
                gravity: v(8),
            },
            Start {
                roll: v(9),
                pitch: v(10),
                yaw: v(11),
                omega: [v(12), v(13), v(14)],
            },
            v(15),
        )
    }

    /// Whether the upright rest is stable: both radii of curvature of the bottom exceed the
    /// height of the mass centre.
    #[must_use]
    pub fn stable_upright(&self) -> bool {
        let p = self.params();
        let h = p.rest_height();
        p.a * p.a / p.c > h && p.b * p.b / p.c > h
    }
}

impl Posed for Problem {
    fn scene(&self) -> &'static Scene {
        &SCENE
    }
    fn values(&self) -> Vec<f64> {
        values_of(self.params(), self.start(), self.band())
    }
    fn summary(&self) -> Vec<SummaryLine> {
        let p = self.params();
        let y0 = self.initial_state();
        vec![
            SummaryLine::new(
                "skew δ°",
                "the angle between the inertia axes and the bottom's axes",
                Shown::Number(Some(p.skew().to_degrees())),
            ),
            SummaryLine::new(
                "spin ω·γ",
                "the start's spin about the vertical",
                Shown::Number(Some(super::spin(&y0))),
            ),
            SummaryLine::new(
                "energy E",
                "the start's energy",
                Shown::Number(Some(p.energy(&y0))),
            ),
            SummaryLine::new(
                "rest E",
                "the energy at rest, upright",
                Shown::Number(Some(p.gravity * p.rest_height())),
            ),
            SummaryLine::new(
                "upright",
                "whether the upright rest is stable",
                Shown::verdict(self.stable_upright(), "stable at rest", "unstable at rest"),
            ),
        ]
    }
    fn slow_start(&self) -> (f64, f64) {
        (0.0, super::spin(&self.initial_state()))
    }
    fn default_step(&self, _method: Method, tolerance: f64, _t_end: f64) -> f64 {
        // Adaptive methods only; the size of the first step DOP853 would take, about.
        tolerance.clamp(1e-16, 1.0).e_powf(0.125) / super::budget::fastest_rate(self)
    }
    fn slow_limit(&self) -> std::sync::Arc<dyn SlowLimit> {
        // No limit: the free rotor about the vertical (`m = C`), whose level is the largest
        // spin the energy allows, about.
        let params = self.params();
        let y0 = self.initial_state();
        std::sync::Arc::new(FreeRotor {
            mass: params.iz,
            energy: params.energy(&y0) - params.gravity * params.rest_height(),
            q_dot0: super::spin(&y0),
        })
    }
    fn drawing(&self) -> Drawing {
        let p = self.params();
        Drawing::Body {
            plan: [p.a, p.b],
            side: Some(SideView {
                long: p.a,
                cross: p.b,
                height: p.c,
                offset: p.offset,
            }),
        }
    }
    // Adaptive methods only: they add few steps, plainly (no time sum).
    fn build(&self, ask: &Asked, _: Arithmetic) -> Result<Box<dyn Flow>, StepError> {
        Ok(Box::new(super::flows::build(
            self,
            ask.method,
            ask.settings(),
        )?))
    }
    fn resolve(&self, ask: &PlanRequest, go_on: &mut dyn FnMut(f64) -> bool) -> Planned {
        super::plan::resolve(self, ask, go_on)
    }
    fn predicted_seconds(&self, ask: &Asked) -> f64 {
        super::budget::cost_seconds(self, ask)
    }
    fn chart_point(&self) -> (f64, f64) {
        (self.start().omega[2], self.params().product)
    }
    fn weak(&self) -> Option<&dyn WeakStudy> {
        // The rolling rattleback has no fast coordinate whose square converges weakly.
        None
    }
    fn slow_curve(&self, ask: &Asked, samples: usize, go_on: GoOn) -> Result<SlowCurve, StepError> {
        if ask.method == Method::Effective {
            return Err(StepError::NoStudy {
                what: "limit",
                model: "celt",
            });
        }
        let r = self.resolve(&PlanRequest::verified(ask), go_on)?;
        let plan = Asked::new(r.plan.method, r.plan.tolerance, None, ask.t_end);
        let spec = RunSpec::new(plan, samples);
        let run = super::run::run(self, &spec, go_on)?;
        let (t, q) = run.samples.iter().map(|s| (s.t, s.turn)).unzip();
        Ok(SlowCurve {
            t,
            q,
            method: run.method,
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
    /// The body.
    pub celt: super::Params,
    /// Attitude and angular velocity.
    pub celt_start: super::Start,
    /// The reversal band.
    pub spin_band: f64,
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
            celt: *p.params(),
            celt_start: *p.start(),
            spin_band: p.band(),
            tolerance,
            t_end,
        }
    }
}
