//! Kapitza's pendulum as every layer above `physics/` sees it: its parameter table, words,
//! small parameter, studies and the facts of a posed problem ([`Scene`], [`Posed`]). Nothing
//! outside this folder names a pendulum parameter.

use super::limit::Limit;
use super::{EPSILON_MAX, EPSILON_MIN, Params, Problem, Start};
use crate::physics::chart::MapFlag;
use crate::physics::flow::Flow;
use crate::physics::flow::GoOn;
use crate::physics::method::Arithmetic;
use crate::physics::method::Asked;
use crate::physics::method::RunSpec;
use crate::physics::method::{Method, StepError};
use crate::physics::params::{Allowed, ParamError, ParamSpec, Scale};
use crate::physics::plan::{PlanRequest, Resolution, Resolved};
use crate::physics::scene::SlowLimit;
use crate::physics::scene::{
    ChartWords, Drawing, Found, Pivot, Planned, Posed, Scene, SecondEvents, Shown, SlowCurve,
    SmallParameter, Studies, SummaryLine, WeakStudy, WeakView, WeakWords, Words,
};

const STRENGTH: Scale = Scale::linear(0.05, 0.5);

/// The pendulum's parameters, in the panel's order. Names are a contract: add, never rename.
pub const PARAMS: [ParamSpec; 5] = [
    ParamSpec::required(
        ("pendulum", "a"),
        Allowed::Finite,
        STRENGTH,
        "gravity over length; the upright is unstable without shaking when a > 0",
    ),
    ParamSpec::required(
        ("pendulum", "b"),
        Allowed::NonNegative,
        STRENGTH,
        "shaking strength: the pivot's acceleration is (b/ε) cos(t/ε)",
    ),
    ParamSpec::required(
        ("pendulum", "epsilon"),
        Allowed::Between {
            lo: EPSILON_MIN,
            hi: EPSILON_MAX,
            text: "a number in [1e-9, 1]",
        },
        Scale::Log,
        "fast time scale: the pivot oscillates with angular frequency 1/ε",
    ),
    ParamSpec::required(
        ("initial", "theta"),
        crate::physics::params::ANGLE,
        Scale::linear(0.05, std::f64::consts::FRAC_PI_8),
        "initial angle from the upright",
    ),
    ParamSpec::optional(
        ("initial", "theta_dot"),
        Allowed::Finite,
        0.0,
        Scale::linear(0.01, 0.1),
        "initial rate",
    ),
];

/// The pendulum's scene.
pub static SCENE: Scene = Scene {
    name: "kapitza",
    title: "Kapitza's pendulum",
    words: Words {
        q_name: "theta",
        q_dot_name: "theta_dot",
        q: "θ",
        q_dot: "θ̇",
        fast: "θ−Θ",
        fast_name: "ripple",
        event: "swing",
        events: "swings",
        event_meaning: "a turning point of the slow motion (the averaged rate changing sign)",
        second_events: Some(SecondEvents {
            name: "falls",
            meaning: "the slow angle passing the horizontal on its way down",
            found: Found::SlowAngleFalls,
        }),
        monitor: Some(crate::physics::scene::Monitor {
            label: "ΔE_eff",
            column: "energy_drift",
            meaning: "the drift of the limit's energy E_eff (the forced motion conserves none)",
        }),
    },
    params: &PARAMS,
    model_required: true,
    methods: &super::flows::METHODS,
    limit_tolerance: 1e-13,
    small: Some(SmallParameter {
        key: "epsilon",
        symbol: "ε",
        limit: "ε → 0",
        column: "epsilon",
        tag: "eps",
        sup: "sup|theta_eps − theta_lim|",
        sup_short: "sup|θ_ε−θ|",
        ladder: &[1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6],
    }),
    studies: Studies {
        weak: Some(WeakWords {
            observable: "the full motion's rate, pointwise (its fast ripple)",
            reference: "the limit's rate, averaged alike (dashed)",
        }),
        chart: ChartWords {
            title: "stability chart (M)",
            curve: "Kapitza's criterion b^2 = 2a (the limit eps -> 0)",
            note: "across: a; up: b (log), at the current eps; Enter loads a and b",
            axes: ("a", "b"),
            sources: false,
            pane: super::chart::PENDULUM_GRID,
            axis_keys: super::chart::AXES,
            heading: "stability of the pendulum",
            legend: "# stable, . unstable, ? too close to call",
            pane_legend: [
                "stable (|tr M| < 2 over one period; blank: unstable)",
                "too close to call (| |tr| - 2 | within its error)",
            ],
            csv: super::chart::COLUMNS,
            flags: &[
                MapFlag::Columns,
                MapFlag::Rows,
                MapFlag::Position,
                MapFlag::Tolerance,
            ],
        },
        counterpart: "subcritical",
    },
};

crate::physics::scene::table_order!(Params { a, b, epsilon }, Start { theta, theta_dot });

impl Posed for Problem {
    fn scene(&self) -> &'static Scene {
        &SCENE
    }
    fn values(&self) -> Vec<f64> {
        self.table_values()
    }
    fn summary(&self) -> Vec<SummaryLine> {
        let p = self.params();
        let limit = Limit::new(p);
        let s = self.start();
        vec![
            SummaryLine::new(
                "b^2-2a",
                "Kapitza's criterion: positive holds the pendulum upright",
                Shown::Number(Some(p.threshold())),
            )
            .prediction(),
            SummaryLine::new(
                "limit E",
                "the limit's energy E_eff at the start",
                Shown::Number(Some(limit.energy_of(s.theta, s.theta_dot))),
            ),
            SummaryLine::new(
                "separatrix E",
                "the energy of the limit's separatrix",
                Shown::Number(Some(limit.potential_max())),
            ),
            SummaryLine::new(
                "upright",
                "whether the averaged upright is stable",
                Shown::verdict(p.stable_upright(), "stable", "unstable"),
            )
            .prediction(),
        ]
    }
    fn slow_start(&self) -> (f64, f64) {
        (self.start().theta, self.start().theta_dot)
    }
    fn default_step(&self, method: Method, tolerance: f64, t_end: f64) -> f64 {
        super::flows::default_step(method, self, tolerance, t_end)
    }
    fn slow_limit(&self) -> std::sync::Arc<dyn SlowLimit> {
        let limit = Limit::new(self.params());
        let s = self.start();
        std::sync::Arc::new(super::limit::SlowView {
            limit,
            // The limit as the theorem states it, from (θ0, θ̇0): the overlay's level.
            energy: limit.energy_of(s.theta, s.theta_dot),
            q_dot0: s.theta_dot,
            epsilon: self.params().epsilon,
        })
    }
    fn drawing(&self) -> Drawing {
        // The pivot's acceleration is (b/ε) cos(t/ε) in rod lengths: its travel is ±b ε.
        let p = self.params();
        Drawing::Pendulum(Pivot {
            stroke: p.b.abs() * p.epsilon,
            epsilon: p.epsilon,
            averaged: true,
        })
    }
    // Its fixed-step methods take the time from the step count, (n + 1) h (flows.rs): no sum to
    // compensate; its lifts take the fast phase as the rules say.
    fn build(&self, ask: &Asked, arithmetic: Arithmetic) -> Result<Box<dyn Flow>, StepError> {
        super::flows::build(self, ask, arithmetic.fast_phase)
    }
    fn resolve(&self, ask: &PlanRequest, go_on: &mut dyn FnMut(f64) -> bool) -> Planned {
        // The pendulum's `auto`: the limit from its predicted model error, or a resolved run
        // verified against a companion (format-1 sessions, which hold no pendulum, aside).
        let (method, tolerance, t_end) = (ask.method, ask.tolerance, ask.t_end);
        let (plan, estimate) = if method == Method::Auto {
            let c = super::plan::verified(self, tolerance, t_end, ask.budget, go_on)?;
            let plan = Resolved {
                method: c.method,
                tolerance: c.settings.tolerance,
                step: None,
            };
            (plan, Some((c.estimate, c.shortfall)))
        } else {
            let plan = Resolved {
                method,
                tolerance,
                step: None,
            };
            (plan, None)
        };
        Ok(Resolution {
            plan,
            estimate: estimate.map(|(e, _)| e),
            shortfall: estimate.and_then(|(_, s)| s),
            floor: None,
        })
    }
    fn predicted_seconds(&self, ask: &Asked) -> f64 {
        super::plan::predicted_seconds(self, ask)
    }
    fn chart_point(&self) -> (f64, f64) {
        (self.params().a, self.params().b)
    }
    fn weak(&self) -> Option<&dyn WeakStudy> {
        Some(self)
    }
    fn slow_curve(&self, ask: &Asked, samples: usize, go_on: GoOn) -> Result<SlowCurve, StepError> {
        let r = self.resolve(&PlanRequest::verified(ask), go_on)?;
        let (method, estimate) = (r.plan.method, r.estimate.unwrap_or(0.0));
        let plan = Asked::new(r.plan.method, r.plan.tolerance, None, ask.t_end);
        let spec = RunSpec::new(plan, samples);
        let r = super::run::run(self, &spec, go_on)?;
        let (t, q) = r.samples.iter().map(|s| (s.t, s.theta)).unzip();
        Ok(SlowCurve {
            t,
            q,
            method,
            estimate,
        })
    }
}

/// The pendulum's weak-* pane: the pointwise square of the fast phase against the
/// averaged reference.
impl WeakStudy for Problem {
    fn seconds(&self, t_end: f64) -> f64 {
        // `weak::pendulum_pointwise`: DOP853 at 1e-10 and the limit at 1e-12.
        let horizon = super::weak::pendulum_view_horizon(self, t_end);
        super::budget::cost_seconds(self, &Asked::new(Method::Dop853, 1e-10, None, horizon))
            + super::budget::cost_seconds(
                self,
                &Asked::new(Method::Effective, 1e-12, None, horizon),
            )
    }
    fn view(&self, t_end: f64, go_on: &mut dyn FnMut(f64) -> bool) -> Result<WeakView, StepError> {
        let horizon = super::weak::pendulum_view_horizon(self, t_end);
        super::weak::pendulum_pointwise(self, horizon, go_on).map(|(t, pointwise, reference)| {
            WeakView {
                t,
                pointwise,
                level: 0.0,
                reference,
            }
        })
    }
}

/// What a plan of this scene was resolved for (the registry's `PlanKey` holds it).
#[derive(
    Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[schemars(inline)]
pub struct PlanKey {
    /// `a`, `b`, `epsilon`.
    pub pendulum: super::Params,
    /// `theta`, `theta_dot`.
    pub initial: super::Start,
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
            pendulum: *p.params(),
            initial: *p.start(),
            tolerance,
            t_end,
        }
    }
}
