//! The holonomic rattleback as every layer above `physics/` sees it: its parameter table, words,
//! small parameter, studies and the facts of a posed problem ([`Scene`], [`Posed`]). Nothing
//! outside this folder names a rattleback parameter.

use super::effective::Effective;
use super::integrators;
use super::model::ALPHA;
use super::params::{Params, Problem, Start};
use crate::physics::chart::MapFlag;
use crate::physics::flow::Flow;
use crate::physics::flow::GoOn;
use crate::physics::method::Arithmetic;
use crate::physics::method::Asked;
use crate::physics::method::RunSpec;
use crate::physics::method::{Method, StepError};
use crate::physics::params::ParamError;
use crate::physics::plan::PlanRequest;
use crate::physics::scene::SlowLimit;
use crate::physics::scene::{
    ChartWords, Drawing, Planned, Posed, Scene, Shown, SlowCurve, SmallParameter, Studies,
    SummaryLine, WeakStudy, WeakView, WeakWords, Words,
};

/// The rattleback's parameters (their table lives with them, `params.rs`).
pub use super::params::PARAMS;

/// The methods the rattleback offers, `auto` first: every method but the celt's projected one.
pub const METHODS: [Method; 14] = Method::all_but(&[Method::Dop853Projected]);

/// The rattleback's scene.
pub static SCENE: Scene = Scene {
    name: "rattleback",
    title: "holonomic rattleback",
    words: Words {
        q_name: "alpha",
        q_dot_name: "alpha_dot",
        q: "α",
        q_dot: "α̇",
        fast: "γ",
        fast_name: "gamma",
        event: "reversal",
        events: "reversals",
        event_meaning: "a sign change of the spin rate (a spin reversal)",
        second_events: None,
        monitor: Some(crate::physics::scene::Monitor {
            label: "ΔE/E",
            column: "energy_error",
            meaning: "the relative error of the conserved energy",
        }),
    },
    params: &PARAMS,
    model_required: false,
    methods: &METHODS,
    // The one-degree-of-freedom ODE is cheap: then good to about 1e-12
    // (`tests/it/auto_honest.rs`).
    limit_tolerance: 1e-14,
    small: Some(SmallParameter {
        key: "k",
        symbol: "k",
        limit: "k → ∞",
        column: "stiffness",
        tag: "k",
        sup: "sup|alpha_k − alpha_eff|",
        sup_short: "sup|α_k−α_eff|",
        ladder: &[1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8],
    }),
    studies: Studies {
        weak: Some(WeakWords {
            observable: "gamma_dot^2 g^1.5 of the full motion, pointwise (between 0 and 2 theta)",
            reference: "theta, the adiabatic invariant (dashed)",
        }),
        chart: ChartWords {
            title: "regime map (M)",
            curve: "the critical ratio of the paper's theorems",
            note: "across: alpha_dot0^2/gamma_dot0^2; up: iy/ix (log); f: limit or full model",
            axes: ("alpha_dot0^2/gamma_dot0^2", "iy/ix"),
            sources: true,
            pane: super::chart::PANE_LARGEST,
            axis_keys: super::chart::AXES,
            heading: "reversals",
            legend: ". none, 1-9 reversals, + 10 or more, ? two tolerances disagree",
            pane_legend: [
                "reversals in [0, T]: 1, 2-3, 4-7, 8 or more (blank: none)",
                "undecided: two tolerances count differently (a chaotic window)",
            ],
            csv: super::chart::COLUMNS,
            flags: &[
                MapFlag::RatioMax,
                MapFlag::InertiaMin,
                MapFlag::InertiaMax,
                MapFlag::K,
                MapFlag::TEnd,
                MapFlag::Tolerance,
            ],
        },
        counterpart: "celt-clockwise",
    },
};

crate::physics::scene::table_order!(
    Params { ix, iy, iz, k },
    Start {
        gamma,
        alpha,
        gamma_dot,
        alpha_dot
    }
);

impl Posed for Problem {
    fn scene(&self) -> &'static Scene {
        &SCENE
    }
    fn values(&self) -> Vec<f64> {
        self.table_values()
    }
    fn summary(&self) -> Vec<SummaryLine> {
        let e = Effective::new(self);
        let (ratio, critical) = (e.start_ratio(self), e.critical_ratio(self));
        let side = match (ratio, critical) {
            (Some(r), Some(c)) if c != 0.0 => Some((r - c) / c),
            _ => None,
        };
        vec![
            SummaryLine::new(
                "limit theta",
                "theta, the fast motion's adiabatic invariant, set by the start",
                Shown::Number(Some(e.theta())),
            ),
            SummaryLine::new(
                "ratio",
                "the start's alpha_dot0^2/gamma_dot0^2",
                Shown::Number(ratio),
            ),
            SummaryLine::new(
                "critical",
                "the paper's critical ratio: below it the spin reverses",
                Shown::Number(critical),
            ),
            SummaryLine::new(
                "vs critical",
                "(ratio - critical)/critical: negative reverses",
                Shown::Percent(side),
            )
            .prediction(),
            SummaryLine::new(
                "limit regime",
                "the limit's motion: trapped (reverses) or rotating (does not)",
                Shown::Verdict(e.regime().name()),
            )
            .prediction(),
        ]
    }
    fn slow_start(&self) -> (f64, f64) {
        (self.start().alpha, self.start().alpha_dot)
    }
    fn default_step(&self, method: Method, tolerance: f64, t_end: f64) -> f64 {
        integrators::default_step(method, self, tolerance, t_end)
    }
    fn slow_limit(&self) -> std::sync::Arc<dyn SlowLimit> {
        std::sync::Arc::new(Effective::new(self))
    }
    fn drawing(&self) -> Drawing {
        // The long axis is the body's x axis when ix > iy (the keel); the paper's body has no
        // shape beyond its inertia, so no side view (its tilt is the pane's cross bar).
        Drawing::Body {
            plan: [self.params().ix, self.params().iy],
            side: None,
        }
    }
    fn build(&self, ask: &Asked, arithmetic: Arithmetic) -> Result<Box<dyn Flow>, StepError> {
        integrators::build(self, ask, arithmetic.time_sum)
    }
    fn resolve(&self, ask: &PlanRequest, go_on: &mut dyn FnMut(f64) -> bool) -> Planned {
        let PlanRequest {
            method,
            tolerance,
            t_end,
            policy,
            budget,
        } = *ask;
        super::plan::resolve(self, method, tolerance, t_end, policy, budget, go_on)
    }
    fn predicted_seconds(&self, ask: &Asked) -> f64 {
        super::plan::predicted_seconds(self, ask)
    }
    fn chart_point(&self) -> (f64, f64) {
        let (params, s) = (self.params(), self.start());
        let gamma_dot = if s.gamma_dot == 0.0 { 1.0 } else { s.gamma_dot };
        ((s.alpha_dot / gamma_dot).powi(2), params.iy / params.ix)
    }
    fn weak(&self) -> Option<&dyn WeakStudy> {
        Some(self)
    }
    fn slow_curve(&self, ask: &Asked, samples: usize, go_on: GoOn) -> Result<SlowCurve, StepError> {
        let (method, tolerance, t_end) = (ask.method, ask.tolerance, ask.t_end);
        let spec = RunSpec {
            method,
            tolerance,
            step: None,
            t_end,
            samples,
            monitor_energy: false,
        };
        let (result, method, estimate) = if method == Method::Auto {
            let v = super::auto::run_auto_cancellable(
                self,
                &spec,
                crate::physics::budget::BUDGET_SECONDS,
                go_on,
            )?;
            (v.result, v.plan.method, v.error_estimate)
        } else {
            (
                super::run::run_cancellable(self, &spec, go_on)?,
                method,
                0.0,
            )
        };
        let (t, q) = result.samples.iter().map(|s| (s.t, s.state[ALPHA])).unzip();
        Ok(SlowCurve {
            t,
            q,
            method,
            estimate,
        })
    }
}

/// The rattleback's weak-* pane: the pointwise square of the fast coordinate against the
/// limit's level.
impl WeakStudy for Problem {
    fn seconds(&self, t_end: f64) -> f64 {
        // `weak::pointwise`: BlanesMoan4 at a step of half the fastest period over 2π.
        let omega = self.params().omega_max();
        super::plan::predicted_seconds(
            self,
            &Asked::new(
                Method::BlanesMoan4,
                1e-10,
                Some(0.5 / omega),
                super::weak::view_horizon(self, t_end),
            ),
        )
    }
    fn view(&self, t_end: f64, go_on: &mut dyn FnMut(f64) -> bool) -> Result<WeakView, StepError> {
        let horizon = super::weak::view_horizon(self, t_end);
        super::weak::pointwise(self, horizon, go_on).map(|(t, pointwise)| WeakView {
            t,
            pointwise,
            level: Effective::new(self).theta(),
            reference: Vec::new(),
        })
    }
}

/// What a plan of this scene was resolved for (the registry's `PlanKey` holds it).
#[derive(
    Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[schemars(inline)]
pub struct PlanKey {
    /// Body and spring.
    pub params: super::params::Params,
    /// Start.
    pub start: super::params::Start,
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
            params: *p.params(),
            start: *p.start(),
            tolerance,
            t_end,
        }
    }
}
