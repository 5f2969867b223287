//! Integrators of the full and effective models behind one interface.
//!
//! Every method is deterministic: the same problem, settings and build give bit-identical
//! results. Each file holds one method and states its order, whether it is symplectic and its
//! cost per step. Reversals (sign changes of `α̇`) are located inside a step by each method's
//! own interpolant or closed-form sub-flow ([`Integrator::locate_alpha_dot_zero`]).

mod averaged;
pub mod dop853;
mod dop853_tableau;
mod effective;
mod full_dop853;
pub mod reversals;
mod rk4;
pub mod roots;
pub mod splitting;

use serde::Serialize;

pub use dop853::Stats;

use super::model::State;
use super::params::Problem;

/// The closed set of methods; names are the ones used in presets and on the command line.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Classical Runge–Kutta, fixed step, order 4.
    Rk4,
    /// Dormand–Prince 8(5,3), adaptive, order 8.
    Dop853,
    /// Strang splitting with exact sub-flows, order 2, symplectic.
    Strang,
    /// Yoshida's triple-jump composition of Strang, order 4, symplectic.
    Yoshida4,
    /// Yoshida's 7-stage composition of Strang, order 6, symplectic.
    Yoshida6,
    /// The 15-stage composition of Strang (Suzuki–Umeno, `McLachlan`), order 8, symplectic.
    Suzuki8,
    /// Blanes & Moan's optimised 6-stage splitting, order 4, symplectic.
    BlanesMoan4,
    /// The effective `k → ∞` model, integrated by DOP853.
    Effective,
    /// Strang splitting with phase-locked steps: no step-size resonance, cost independent of `k`.
    Locked,
    /// The effective model with its first-order correction (the fast ripple of `α̇`).
    EffectiveCorrected,
    /// The second-order averaged model: error O(k⁻²), cost independent of `k`
    /// (physics.md §4c, `physics::averaged`).
    Averaged2,
    /// Chooses the cheapest method that meets the tolerance (see `physics::auto`).
    Auto,
}

impl Method {
    /// Every method, in the order tables list them.
    pub const ALL: [Self; 12] = [
        Self::Auto,
        Self::Rk4,
        Self::Dop853,
        Self::Strang,
        Self::Yoshida4,
        Self::BlanesMoan4,
        Self::Yoshida6,
        Self::Suzuki8,
        Self::Locked,
        Self::Effective,
        Self::EffectiveCorrected,
        Self::Averaged2,
    ];

    /// Every concrete method: [`Method::ALL`] without `auto`, which resolves to one of them.
    pub const CONCRETE: [Self; 11] = {
        let mut out = [Self::Rk4; 11];
        let mut i = 0;
        while i < 11 {
            out[i] = Self::ALL[i + 1];
            i += 1;
        }
        out
    };

    /// The name used in presets, on the command line and in JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Rk4 => "rk4",
            Self::Dop853 => "dop853",
            Self::Strang => "strang",
            Self::Yoshida4 => "yoshida4",
            Self::Yoshida6 => "yoshida6",
            Self::Suzuki8 => "suzuki8",
            Self::BlanesMoan4 => "blanes-moan4",
            Self::Effective => "effective",
            Self::Locked => "locked",
            Self::EffectiveCorrected => "effective-corrected",
            Self::Averaged2 => "averaged2",
            Self::Auto => "auto",
        }
    }

    /// Parses a name from [`Method::name`].
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name.trim()))
    }

    /// Comma-separated list of valid names, for error messages.
    #[must_use]
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// Classical order of accuracy.
    #[must_use]
    pub fn order(self) -> u32 {
        match self {
            Self::Strang | Self::Locked => 2,
            Self::Auto => 0,
            Self::Rk4 | Self::Yoshida4 | Self::BlanesMoan4 => 4,
            Self::Yoshida6 => 6,
            Self::Dop853
            | Self::Suzuki8
            | Self::Effective
            | Self::EffectiveCorrected
            | Self::Averaged2 => 8,
        }
    }

    /// Whether the method takes a fixed step (`step` applies) rather than adapting to `tolerance`.
    #[must_use]
    pub fn is_fixed_step(self) -> bool {
        !matches!(
            self,
            Self::Dop853
                | Self::Effective
                | Self::EffectiveCorrected
                | Self::Averaged2
                | Self::Auto
        )
    }

    /// Whether the method integrates the effective model rather than the full one.
    #[must_use]
    pub fn is_effective(self) -> bool {
        matches!(
            self,
            Self::Effective | Self::EffectiveCorrected | Self::Averaged2
        )
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a step could not be taken.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StepError {
    /// The adaptive step size underflowed.
    #[error("step size underflow at t = {t} (h = {h:e})")]
    StepTooSmall {
        /// Time reached.
        t: f64,
        /// The step size that was too small.
        h: f64,
    },
    /// The solution stopped being finite.
    #[error("the solution is no longer finite at t = {t}")]
    NonFinite {
        /// Time reached.
        t: f64,
    },
    /// The caller cancelled the run (a restart or quit arrived).
    #[error("cancelled at t = {t}")]
    Cancelled {
        /// Time reached.
        t: f64,
    },
    /// The run finished but part of its result is not a finite number (for example the tilt
    /// reconstructed by an effective method at a vanishing `k`).
    #[error(
        "{what} is not a finite number at t = {t}: the method cannot represent this problem; try another method or a larger k"
    )]
    NotFinite {
        /// Which part of the result.
        what: &'static str,
        /// Time reached.
        t: f64,
    },
    /// The averaged model does not apply to this problem: its expansion parameters are not
    /// small (the spin or the slow oscillation is not slow against the fast frequency).
    #[error(
        "the averaged model does not apply here: its expansion parameter is {parameter:.1e} (|α̇|/ω and θ√g/(iz k) must be small; allowed: at most {limit}); use auto or a method that resolves the fast motion"
    )]
    OutsideModel {
        /// The largest expansion parameter of the start.
        parameter: f64,
        /// The largest accepted.
        limit: f64,
    },
    /// `auto` is a planner, not an integrator: resolve it first (`physics::plan`).
    #[error("method auto must be resolved to a concrete method before integrating")]
    Unplanned,
    /// The method belongs to another model.
    #[error("method {method} is not offered for the {model} model")]
    NotOffered {
        /// The method's name.
        method: &'static str,
        /// The model's name.
        model: &'static str,
    },
    /// A run (or `auto`'s next probe, verification or refinement) is predicted to exceed the
    /// work budget it was given; nothing of it was started.
    #[error("{what} is {over}")]
    OverBudget {
        /// What would have run.
        what: String,
        /// The prediction and the budget.
        over: super::budget::OverBudget,
    },
}

/// How a method is to be run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Tolerance of adaptive methods; for fixed-step methods it picks the default step.
    pub tolerance: f64,
    /// Fixed step size; `None` derives one from the tolerance.
    pub step: Option<f64>,
}

/// A running integration of one problem.
pub trait Integrator: Send {
    /// Which method this is.
    fn method(&self) -> Method;
    /// Current time.
    fn time(&self) -> f64;
    /// Start of the last step (equal to [`Integrator::time`] before the first).
    fn time_prev(&self) -> f64;
    /// Current state `(γ, α, γ̇, α̇)`; the effective model reconstructs `γ, γ̇` from its
    /// adiabatic invariant and fast phase.
    fn state(&self) -> State;
    /// Current `α̇`, cheaper than a whole [`Integrator::state`] (no `γ̇` reconstruction).
    fn alpha_dot(&self) -> f64 {
        self.state()[3]
    }
    /// Takes one step, never past `t_limit`, which must exceed the current time.
    ///
    /// # Errors
    /// When the step cannot be completed with a finite result.
    fn step(&mut self, t_limit: f64) -> Result<(), StepError>;
    /// The state at `t` within the last step, from the method's own interpolant.
    fn interpolate(&mut self, t: f64) -> State;
    /// Where `α̇` vanishes within the last step, given that it changes sign over the step.
    fn locate_alpha_dot_zero(&mut self) -> f64;
    /// The quantity the method conserves, at the current state: the energy, or `E_eff` of the
    /// averaged motion for the effective models.
    fn energy(&self) -> f64;
    /// Work counters.
    fn stats(&self) -> Stats;
}

/// Most steps a default step may lead to over the horizon; an explicit step is not capped.
pub const DEFAULT_STEP_BUDGET: f64 = 2e6;

/// Default fixed step for `method` at `tolerance` over `[0, t_end]`: `c · tol^{1/p} / ν` with
/// `ν` the fastest rate of the problem (the fast frequency, or the slow rate at small `k`), but
/// never more than [`DEFAULT_STEP_BUDGET`] steps: a low-order method at a tight tolerance would
/// otherwise ask for billions.
#[must_use]
pub fn default_step(method: Method, problem: &Problem, tolerance: f64, t_end: f64) -> f64 {
    let p = problem.params();
    let s = problem.start();
    let y0 = super::model::initial_state(s);
    let e = super::model::energy(p, &y0);
    let slow = (2.0 * e / p.ix.min(p.iy).min(p.iz)).sqrt();
    let rate = p.omega_max().max(slow).max(1e-3);
    let (c, order) = match method {
        Method::Rk4 => (0.5, 4.0),
        Method::Strang => (0.3, 2.0),
        // Phase-locked steps: error ≈ 0.05 h² whatever k (physics.md §4), so h = sqrt(tol/0.05).
        Method::Locked => return (tolerance / 0.05).sqrt().max(t_end / DEFAULT_STEP_BUDGET),
        Method::Yoshida4 => (0.6, 4.0),
        Method::BlanesMoan4 => (1.2, 4.0),
        Method::Yoshida6 => (1.0, 6.0),
        Method::Suzuki8 => (1.5, 8.0),
        Method::Dop853
        | Method::Effective
        | Method::EffectiveCorrected
        | Method::Averaged2
        | Method::Auto => (1.0, 8.0),
    };
    (c * tolerance.powf(1.0 / order) / rate).max(t_end / DEFAULT_STEP_BUDGET)
}

/// Builds a ready-to-step integrator at `t = 0`; `t_end` is the horizon a default step is
/// budgeted for.
///
/// # Errors
/// [`StepError::Unplanned`] for `auto`, which is resolved above the integrators
/// (`physics::plan`), so this layer never calls back up into the planner.
pub fn build(
    method: Method,
    problem: &Problem,
    settings: Settings,
    t_end: f64,
) -> Result<Box<dyn Integrator>, StepError> {
    let step = settings
        .step
        .unwrap_or_else(|| default_step(method, problem, settings.tolerance, t_end));
    Ok(match method {
        Method::Rk4 => Box::new(rk4::Rk4::new(problem, step)),
        Method::Dop853 => Box::new(full_dop853::FullDop853::new(problem, settings.tolerance)),
        Method::Strang
        | Method::Yoshida4
        | Method::BlanesMoan4
        | Method::Yoshida6
        | Method::Suzuki8 => Box::new(splitting::Splitting::new(
            problem,
            splitting::Composition::of(method),
            step,
        )),
        Method::Locked => Box::new(splitting::Splitting::phase_locked(problem, step)),
        Method::Effective => Box::new(effective::EffectiveDop853::new(
            problem,
            settings.tolerance,
            false,
        )),
        Method::EffectiveCorrected => Box::new(effective::EffectiveDop853::new(
            problem,
            settings.tolerance,
            true,
        )),
        Method::Averaged2 => {
            let parameter = crate::physics::averaged::expansion_parameter(problem);
            let limit = crate::physics::averaged::VALIDITY_LIMIT;
            if parameter.is_nan() || parameter > limit {
                return Err(StepError::OutsideModel { parameter, limit });
            }
            Box::new(averaged::Averaged2Dop853::new(problem, settings.tolerance))
        }
        Method::Auto => return Err(StepError::Unplanned),
    })
}
