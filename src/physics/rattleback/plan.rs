//! Turning a requested method into the concrete integration that runs: `auto` is resolved
//! here, above [`run`](mod@super::run) and the integrators, so nothing below calls back up into the
//! planner. The explorer and `simulate` both go through [`resolve`], which is what makes them
//! show the same trajectory.
//!
//! A [`Resolved`] plan is plain data (method, tolerance, step): recordings store it, and replay
//! integrates the recorded plan, so a later change of `auto` never breaks an old session.

use super::auto;
use super::budget;
use super::params::Problem;
use super::policy::POLICY;
use crate::physics::method::Asked;
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::method::StepError;
use crate::physics::plan::{AutoRules, Resolution, Resolved};

/// Resolves `method` for `problem` over `[0, t_end]` at `tolerance`; `go_on(t)` is asked every
/// few hundred steps of `auto`'s probes and verification runs whether to continue, and none of
/// them starts if it would take the predicted total over `budget` seconds.
///
/// # Errors
/// When a verification run fails, [`StepError::OverBudget`], or [`StepError::Cancelled`].
pub fn resolve(
    problem: &Problem,
    method: Method,
    tolerance: f64,
    t_end: f64,
    policy: AutoRules,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Resolution, StepError> {
    if method != Method::Auto {
        return Ok(Resolution::named(method, tolerance));
    }
    match policy {
        AutoRules::Legacy => {
            let p = auto::legacy::plan_cancellable(problem, tolerance, t_end, go_on)?;
            Ok(Resolution::unverified(Resolved {
                method: p.method,
                tolerance: p.tolerance,
                step: p.step,
            }))
        }
        AutoRules::Verified => {
            let v = auto::run_auto_cancellable(
                problem,
                &RunSpec {
                    method,
                    tolerance,
                    step: None,
                    t_end,
                    samples: 0,
                    monitor_energy: false,
                },
                budget,
                go_on,
            )?;
            Ok(Resolution {
                plan: Resolved {
                    method: v.plan.method,
                    tolerance: v.run_settings.tolerance,
                    step: v.run_settings.step,
                },
                estimate: Some(v.error_estimate),
                shortfall: v.shortfall,
                floor: Some(v.round_off_floor),
            })
        }
    }
}

/// Predicted seconds of a whole run of `method` (for `auto`: its probes, when `k` calls for
/// them, then its first plan, run and verified by its companion; the averaged model counted as
/// admitted by the probes). Checked against the budget before anything starts; `auto` checks
/// its actual plan again, and stops refining past the time it allows itself.
#[must_use]
pub fn predicted_seconds(problem: &Problem, ask: &Asked) -> f64 {
    let (method, tolerance, step, t_end) = (ask.method, ask.tolerance, ask.step, ask.t_end);
    if method != Method::Auto {
        return budget::cost_seconds(problem, &Asked::new(method, tolerance, step, t_end));
    }
    let resolved = auto::best_resolved(problem, tolerance, t_end).predicted_seconds;
    if auto::considers_averaged(problem, tolerance, t_end) {
        let local = (tolerance / (2.0 * POLICY.companion_error * auto::AVERAGED_GROWTH))
            .max(POLICY.tightest);
        let averaged =
            budget::cost_seconds(problem, &Asked::new(auto::AVERAGED, local, None, t_end))
                * (1.0 + VERIFY_FRACTION);
        auto::probes_cost(problem, t_end) + resolved.min(averaged)
    } else {
        resolved
    }
}

/// What `auto`'s verification adds to a run: a companion at twice the step (half the cost) or
/// at a 16× looser tolerance (about 0.7×).
pub const VERIFY_FRACTION: f64 = 0.7;
