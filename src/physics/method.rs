//! What every model's integrators share: the closed set of methods (names as in presets),
//! how a method is to be run, and why a step could not be taken. Which methods a model offers is
//! the model's business ([`super::ModelKind::methods`]).

use serde::Serialize;

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
    /// Taylor series of order 20 with the step from its last coefficients, of a scene's full
    /// model (a driven model's forcing expanded exactly); each scene that offers it has its
    /// own series in its folder.
    Taylor,
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
    /// The second-order averaged model: error O(δ²) in the scene's small parameter δ (its
    /// `1/k`, or `ε²`); cost independent of it (docs/physics.md §4c; each scene's `averaged`).
    Averaged2,
    /// The third-order averaged model (error O(δ³)), at about twice `averaged2`'s cost and
    /// independent of the small parameter (each scene's own expansion).
    Averaged3,
    /// DOP853 with the state projected back onto its constraints after every step (a unit
    /// quaternion, with the up vector taken from it, where a scene has one).
    Dop853Projected,
    /// Chooses the cheapest method that meets the tolerance, verified (`physics::verify`; each
    /// scene's `auto`).
    Auto,
}

impl Method {
    /// Every method, in the order tables list them.
    pub const ALL: [Self; 15] = [
        Self::Auto,
        Self::Rk4,
        Self::Dop853,
        Self::Taylor,
        Self::Dop853Projected,
        Self::Strang,
        Self::Yoshida4,
        Self::BlanesMoan4,
        Self::Yoshida6,
        Self::Suzuki8,
        Self::Locked,
        Self::Effective,
        Self::EffectiveCorrected,
        Self::Averaged2,
        Self::Averaged3,
    ];

    /// Every concrete method: [`Method::ALL`] without `auto`, which resolves to one of them.
    pub const CONCRETE: [Self; 14] = Self::all_but(&[Self::Auto]);

    /// [`Method::ALL`] without `skip`, in its order (a model's menu).
    ///
    /// # Panics
    /// When `N` is not how many are left (at compile time in a `const`).
    #[must_use]
    pub const fn all_but<const N: usize>(skip: &[Self]) -> [Self; N] {
        let mut out = [Self::Auto; N];
        let (mut i, mut n) = (0, 0);
        while i < Self::ALL.len() {
            let m = Self::ALL[i];
            let mut j = 0;
            let mut kept = true;
            while j < skip.len() {
                kept &= skip[j] as u8 != m as u8;
                j += 1;
            }
            if kept {
                assert!(n < N, "more methods left than the menu holds");
                out[n] = m;
                n += 1;
            }
            i += 1;
        }
        assert!(n == N, "fewer methods left than the menu holds");
        out
    }

    /// The name used in presets, on the command line and in JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Rk4 => "rk4",
            Self::Dop853 => "dop853",
            Self::Taylor => "taylor",
            Self::Strang => "strang",
            Self::Yoshida4 => "yoshida4",
            Self::Yoshida6 => "yoshida6",
            Self::Suzuki8 => "suzuki8",
            Self::BlanesMoan4 => "blanes-moan4",
            Self::Effective => "effective",
            Self::Locked => "locked",
            Self::EffectiveCorrected => "effective-corrected",
            Self::Averaged2 => "averaged2",
            Self::Averaged3 => "averaged3",
            Self::Dop853Projected => "dop853-projected",
            Self::Auto => "auto",
        }
    }

    /// Parses a name from [`Method::name`] (any case).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        named(&Self::ALL, Self::name, name)
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
            Self::Taylor => 20,
            Self::Dop853
            | Self::Dop853Projected
            | Self::Suzuki8
            | Self::Effective
            | Self::EffectiveCorrected
            | Self::Averaged2
            | Self::Averaged3 => 8,
        }
    }

    /// Whether the method takes a fixed step (`step` applies) rather than adapting to `tolerance`.
    #[must_use]
    pub fn is_fixed_step(self) -> bool {
        !matches!(
            self,
            Self::Dop853
                | Self::Dop853Projected
                | Self::Taylor
                | Self::Effective
                | Self::EffectiveCorrected
                | Self::Averaged2
                | Self::Averaged3
                | Self::Auto
        )
    }

    /// Whether the method integrates the effective model rather than the full one.
    #[must_use]
    pub fn is_effective(self) -> bool {
        matches!(
            self,
            Self::Effective | Self::EffectiveCorrected | Self::Averaged2 | Self::Averaged3
        )
    }

    /// Whether the method is one of the averaged models (`averaged2`, `averaged3`).
    #[must_use]
    pub fn is_averaged(self) -> bool {
        matches!(self, Self::Averaged2 | Self::Averaged3)
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
    /// A study the model does not offer (the sweep of a model without a limit).
    #[error("the {model} model has no {what}")]
    NoStudy {
        /// What is missing (`small parameter to sweep`).
        what: &'static str,
        /// The model's name.
        model: &'static str,
    },
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
    /// The run took far more steps than its cost model predicted (the problem does not behave
    /// as the model expects, such as a correction expanded in `1/k` at a vanishing `k`): it was
    /// stopped instead of being left to run for hours.
    #[error(
        "stopped at t = {t} after {steps} steps, ten times the work predicted for the whole run; shorten t_end or pick another method"
    )]
    Exceeded {
        /// Time reached.
        t: f64,
        /// Steps taken.
        steps: u64,
    },
}

/// Least time one step of any method takes (a splitting's step is several exact fast flows of
/// 70 ns; DOP853's twelve evaluations take 0.4 µs).
pub const LEAST_SECONDS_PER_STEP: f64 = 5e-8;

/// How many steps a run may take before it is stopped: ten times the predicted work counted in
/// the cheapest steps, and never fewer than 10^5. Counted in steps, not in wall time, so a run
/// stops at the same step on every machine (replays rely on it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StepCap(u64);

impl StepCap {
    /// The cap of a run predicted to take `predicted_seconds`.
    #[must_use]
    pub fn of(predicted_seconds: f64) -> Self {
        let steps = 10.0 * predicted_seconds / LEAST_SECONDS_PER_STEP;
        Self(if steps.is_finite() {
            steps.clamp(1e5, 9e18) as u64
        } else {
            u64::MAX
        })
    }

    /// No cap (integrating again a stretch that already ran).
    pub const NONE: Self = Self(u64::MAX);

    /// `Err` once `steps` (taken so far, at time `t`) is past the cap.
    ///
    /// # Errors
    /// [`StepError::Exceeded`].
    pub fn check(self, steps: u64, t: f64) -> Result<(), StepError> {
        if steps > self.0 {
            Err(StepError::Exceeded { t, steps })
        } else {
            Ok(())
        }
    }
}

/// How a fixed-step integrator adds its steps to the time.
///
/// `Plain` adds `t + h` in double each step: the rounding drifts the time, and with it every
/// reversal time (4.3e-11 after 7·10⁴ steps of `blanes-moan4` at `t` = 29: docs/benchmarks.md,
/// "Issue 29"). `Compensated`
/// carries the rounding (Kahan) and keeps the time within an ulp of the sum of the steps. The
/// states do not depend on it (the models are autonomous), but the last step's length and
/// every interpolated state do, in their last bits: session files of format 5 and older were
/// recorded with `Plain` and replay with it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TimeSum {
    /// Carried rounding (what runs now).
    #[default]
    Compensated,
    /// Plain double addition (session files of format 5 and older).
    Plain,
}

impl TimeSum {
    /// `t + h` with this rule; `carry` holds what `Compensated` carries between steps.
    #[must_use]
    pub fn add(self, t: f64, h: f64, carry: &mut f64) -> f64 {
        match self {
            Self::Plain => t + h,
            Self::Compensated => {
                let y = h - *carry;
                let sum = t + y;
                *carry = (sum - t) - y;
                sum
            }
        }
    }
}

/// How a fast phase `t/ε` is taken where a slow model is lifted back to the full motion.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FastPhase {
    /// Carried exactly (what runs now).
    #[default]
    Exact,
    /// Rounded once to double (session files of format 7 and older).
    Rounded,
}

pub use super::numerics::elementary::Functions;

/// The arithmetic rules that changed between session formats: a replay of an old file follows
/// the ones it was recorded with, so its bits come back (`crate::record::plan_book`); everything
/// else runs the current ones, [`Arithmetic::default`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Arithmetic {
    /// How fixed-step methods add their steps to the time (where a scene sums them; others take
    /// the time from the step count).
    pub time_sum: TimeSum,
    /// How a lift takes a fast phase `t/ε` (a driven scene's).
    pub fast_phase: FastPhase,
    /// Whose elementary functions (sine, logarithm, …) the run takes: the portable ones since
    /// format 15, the platform's before.
    pub functions: Functions,
}

impl Arithmetic {
    /// The rules session files of format `version` were recorded with: the plain sum of the
    /// time up to format 5, the rounded fast phase up to format 7, the platform's elementary
    /// functions up to format 14.
    #[must_use]
    pub fn of_format(version: u32) -> Self {
        Self {
            time_sum: if version < 6 {
                TimeSum::Plain
            } else {
                TimeSum::Compensated
            },
            fast_phase: if version < 8 {
                FastPhase::Rounded
            } else {
                FastPhase::Exact
            },
            functions: if version < 15 {
                Functions::Platform
            } else {
                Functions::Portable
            },
        }
    }
}

/// The member of `all` whose `name_of` is `name` (any case; surrounding spaces ignored).
pub(crate) fn named<T: Copy>(all: &[T], name_of: fn(T) -> &'static str, name: &str) -> Option<T> {
    all.iter()
        .copied()
        .find(|m| name_of(*m).eq_ignore_ascii_case(name.trim()))
}

/// A run as it is asked for and priced: the method, its tolerance (or, for a fixed-step method,
/// its default step's target), its fixed step (`None`: derived from the tolerance), and the
/// horizon. Every cost model prices one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Asked {
    /// The method (`auto` as it would resolve).
    pub method: Method,
    /// Tolerance.
    pub tolerance: f64,
    /// Fixed step, for fixed-step methods.
    pub step: Option<f64>,
    /// Horizon.
    pub t_end: f64,
}

/// What to run, for every model: a concrete method and its settings over `[0, t_end]`, the
/// samples to keep, and whether to follow the energy after every step.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RunSpec {
    /// The integrator (a concrete method: resolve `auto` first).
    pub method: Method,
    /// Tolerance (adaptive methods) or the default step's target (fixed-step methods).
    pub tolerance: f64,
    /// Fixed step, for fixed-step methods; `None` derives it from `tolerance`.
    pub step: Option<f64>,
    /// Final time.
    pub t_end: f64,
    /// Evenly spaced samples over `[0, t_end]` to record (0: none, so none are computed).
    pub samples: usize,
    /// Whether to evaluate the energy after every step for its drift (benchmarks turn it off
    /// to time the integrator alone).
    pub monitor_energy: bool,
}

impl RunSpec {
    /// `asked`, keeping `samples` samples, the energy followed.
    #[must_use]
    pub const fn new(asked: Asked, samples: usize) -> Self {
        Self {
            method: asked.method,
            tolerance: asked.tolerance,
            step: asked.step,
            t_end: asked.t_end,
            samples,
            monitor_energy: true,
        }
    }

    /// What a cost model prices.
    #[must_use]
    pub const fn asked(&self) -> Asked {
        Asked::new(self.method, self.tolerance, self.step, self.t_end)
    }
}

impl Asked {
    /// `method` at `tolerance` (or with `step`) over `[0, t_end]`.
    #[must_use]
    pub const fn new(method: Method, tolerance: f64, step: Option<f64>, t_end: f64) -> Self {
        Self {
            method,
            tolerance,
            step,
            t_end,
        }
    }

    /// Its tolerance and step, as an integrator takes them.
    #[must_use]
    pub const fn settings(&self) -> Settings {
        Settings {
            tolerance: self.tolerance,
            step: self.step,
        }
    }
}

/// How a method is to be run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Tolerance of adaptive methods; for fixed-step methods it picks the default step.
    pub tolerance: f64,
    /// Fixed step size; `None` derives one from the tolerance.
    pub step: Option<f64>,
}

/// Most steps a default step may lead to over the horizon; an explicit step is not capped.
pub const DEFAULT_STEP_BUDGET: f64 = 2e6;

/// Checks that a fixed step advances time all the way to `t_end` (a step below `t_end · 2⁻⁵²`
/// leaves `t + h == t` and would never finish). The one rule for every scene's `step` (issue
/// 69: it lived in the rattleback's folder).
///
/// # Errors
/// What is wrong and the smallest step allowed.
pub fn check_step(step: f64, t_end: f64) -> Result<(), StepTooSmall> {
    let smallest = t_end * f64::EPSILON * 4.0;
    if step.is_finite() && step > 0.0 && step >= smallest {
        Ok(())
    } else {
        Err(StepTooSmall {
            step,
            t_end,
            smallest,
        })
    }
}

/// A fixed step that cannot advance time to the horizon.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "a step of {step:e} cannot advance time to t_end = {t_end} (t + h == t); allowed: at least {smallest:.1e}"
)]
pub struct StepTooSmall {
    /// The step asked.
    pub step: f64,
    /// The horizon.
    pub t_end: f64,
    /// The smallest step allowed.
    pub smallest: f64,
}

#[cfg(test)]
mod step_cap_tests {
    use super::*;

    #[test]
    fn a_run_is_stopped_past_ten_times_its_predicted_work_and_never_before() {
        // Predicted 1 s: 10 s of the cheapest steps.
        let cap = StepCap::of(1.0);
        let limit = (10.0 / LEAST_SECONDS_PER_STEP) as u64;
        assert!(cap.check(limit, 3.0).is_ok());
        assert_eq!(
            cap.check(limit + 1, 3.0),
            Err(StepError::Exceeded {
                t: 3.0,
                steps: limit + 1
            })
        );
        // A cheap run still gets 10^5 steps; an unpriced one is never stopped.
        assert!(StepCap::of(0.0).check(100_000, 0.0).is_ok());
        assert!(StepCap::of(0.0).check(100_001, 0.0).is_err());
        assert!(StepCap::of(f64::INFINITY).check(u64::MAX, 0.0).is_ok());
        assert!(StepCap::NONE.check(u64::MAX, 0.0).is_ok());
    }
}
