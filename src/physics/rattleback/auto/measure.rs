//! What a plan is and what it costs: the [`Plan`] `auto` chooses, the local error models of
//! the resolved methods, the round-off a run of so many steps gathers, the difference of two
//! runs and the budget check.
use crate::physics::numerics::elementary::Elementary;

use super::super::policy::{POLICY, TAYLOR};
use crate::physics::method::Asked;

use serde::Serialize;

use super::super::budget::{cost_seconds, fastest_rate, slow_rate};
use super::super::effective::Effective;
use super::super::params::Problem;
use super::super::run::RunResult;
use crate::physics::method::Method;
use crate::physics::method::Settings;
use crate::physics::method::StepError;

use super::super::policy::{
    AVERAGED_GROWTH, C_BM, C_FAST, CONDITIONED_GAIN, DOP853_GROWTH, ROUND_OFF_GAIN, TAYLOR_GROWTH,
};

/// What `auto` decided, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Plan {
    /// The method chosen.
    pub method: Method,
    /// Tolerance handed to it (adaptive methods).
    pub tolerance: f64,
    /// Step handed to it (fixed-step methods).
    pub step: Option<f64>,
    /// The error the models predict for the returned run (model error included).
    pub predicted_error: f64,
    /// Predicted seconds of the run and its companion on the calibration machine.
    pub predicted_seconds: f64,
    /// One sentence on the choice.
    pub reason: String,
}

impl Plan {
    /// The integrator settings of the plan (the run that is returned).
    #[must_use]
    pub fn settings(&self) -> Settings {
        Settings {
            tolerance: self.tolerance,
            step: self.step,
        }
    }

    /// The coarser companion that verifies it: twice the step, or a looser tolerance
    /// (`POLICY.companion_looser`, `TAYLOR.companion_looser` for the series).
    #[must_use]
    pub fn companion(&self) -> Settings {
        companion_of(self.method, self.tolerance, self.step)
    }
}

/// The coarser companion of a run of `method` with these settings.
pub(super) fn companion_of(method: Method, tolerance: f64, step: Option<f64>) -> Settings {
    match step {
        Some(h) => Settings {
            tolerance,
            step: Some(2.0 * h),
        },
        None => Settings {
            tolerance: super::super::policy::of(method).companion(tolerance),
            step: None,
        },
    }
}

/// The largest difference in `α(T)`, `α̇(T)` and reversal times (infinite when the reversal
/// counts differ).
#[must_use]
pub fn difference(a: &RunResult, b: &RunResult) -> f64 {
    if a.reversal_count != b.reversal_count {
        return f64::INFINITY;
    }
    let mut d = (a.final_state[1] - b.final_state[1])
        .abs()
        .max((a.final_state[3] - b.final_state[3]).abs());
    for (x, y) in a.reversals.iter().zip(&b.reversals) {
        d = d.max((x - y).abs());
    }
    d
}

/// The round-off floor of the phase for a run of `steps` steps over `[0, t_end]` (the planner's
/// whole prediction of round-off, before the start's conditioning is measured): a random walk
/// of one rounding per step (`ε √N`) in the energy, which the slow phase integrates, so that
/// reversal times (which feel it most: a crossing of `α̇` moves by `δα̇ / α̈`) drift like
/// `(s T)^{3/2}` in slow time (`s` the slow rate), times [`ROUND_OFF_GAIN`].
#[must_use]
pub fn round_off(problem: &Problem, steps: f64, t_end: f64) -> f64 {
    ROUND_OFF_GAIN
        * f64::EPSILON
        * steps.max(1.0).sqrt()
        * (slow_rate(problem) * t_end).max(1.0).e_powf(1.5)
}

/// The round-off floor of a run of `steps` steps from a start of condition number `kappa`
/// ([`Conditioning::of_run`]): a few roundings per step, each amplified by at most `κ` by the
/// end, adding up like a random walk, `CONDITIONED_GAIN · ε · √steps · max(κ, 1)`.
///
/// [`Conditioning::of_run`]: super::Conditioning::of_run
#[must_use]
pub fn conditioned_round_off(steps: f64, kappa: f64) -> f64 {
    CONDITIONED_GAIN * f64::EPSILON * steps.max(1.0).sqrt() * kappa.max(1.0)
}

pub(super) fn over_budget(what: &str, predicted: f64, budget: f64) -> Result<(), StepError> {
    crate::physics::budget::check(predicted, budget).map_err(|over| StepError::OverBudget {
        what: what.to_owned(),
        over,
    })
}

pub(super) fn with_companion(problem: &Problem, ask: &Asked) -> f64 {
    let (method, tolerance, step, t_end) = (ask.method, ask.tolerance, ask.step, ask.t_end);
    let c = companion_of(method, tolerance, step);
    cost_seconds(problem, &Asked::new(method, tolerance, step, t_end))
        + cost_seconds(problem, &Asked::new(method, c.tolerance, c.step, t_end))
}

/// The drift a fixed-step splitting's rounding builds over `steps` steps, before the start's
/// conditioning is known: the exact fast rotation by a nearly constant small angle rounds its
/// cosine the same way at every step, so the rounding adds up linearly, `ε · steps` (measured on
/// a body with `iy/ix = 1000` at `k = 1e4`, started at `α = 1.5`: `ν h = 5e-5`, 6.3e7 steps, the
/// run and its companion at `2h` differed by 4e-7 where the series at 1e-14 agrees with DOP853
/// to 1e-11; 3.2e7 steps erred by 1.6e-8). Not in the measured floor: an estimate reads it.
pub(super) fn splitting_drift(steps: f64) -> f64 {
    f64::EPSILON * steps
}

pub(super) fn blanes_moan_error(problem: &Problem, h: f64, t_end: f64) -> f64 {
    blanes_moan_rate(problem) * h.powi(4) * t_end
}

/// `blanes-moan4`'s error per unit time and per `h⁴`.
pub(super) fn blanes_moan_rate(problem: &Problem) -> f64 {
    let p = problem.params();
    let nu = fastest_rate(problem);
    let g_min = p.ix.min(p.iy);
    let c_max = (p.iy - p.ix).abs() / (4.0 * g_min);
    C_BM * Effective::new(problem).spin_scale().e_powf(2.5) * c_max.powi(4) * nu * nu / g_min
        + C_FAST * nu.powi(4)
}

/// DOP853's local tolerance for `tolerance` over `periods` fast periods, so that its companion
/// still meets it, and the error the companion is then predicted to have (above `tolerance`
/// when the local tolerance would have to go below the clamp).
pub(super) fn dop853_local(tolerance: f64, periods: f64) -> (f64, f64) {
    let growth = DOP853_GROWTH * periods.max(20.0);
    let wanted = tolerance / (2.0 * POLICY.companion_error * growth);
    let local = wanted.max(POLICY.tightest);
    (local, 0.5 * tolerance * local / wanted)
}

/// The series' local tolerance for `tolerance` over `periods` fast periods: its companion,
/// `TAYLOR.companion_looser` times looser, should still meet it. With the error the companion
/// is then predicted to have (what the estimate will read: above `tolerance` when the run's
/// tolerance would have to go below the clamp).
pub(super) fn taylor_local(tolerance: f64, periods: f64) -> (f64, f64) {
    let growth = TAYLOR_GROWTH * periods.max(20.0);
    let companion = tolerance / (2.0 * growth);
    let local = (companion / TAYLOR.companion_looser).max(POLICY.tightest);
    (
        local,
        0.5 * tolerance * local * TAYLOR.companion_looser / companion,
    )
}

/// The averaged model's local tolerance for the integration share `share` of the tolerance.
pub(super) fn averaged_local(share: f64, t_end: f64) -> f64 {
    let growth = AVERAGED_GROWTH * (t_end / 30.0).max(1.0);
    (share / (2.0 * POLICY.companion_error * growth)).max(POLICY.tightest)
}
