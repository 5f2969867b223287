//! The choice: the cheapest plan that meets the tolerance among the resolved ones and the
//! averaged model, given its probes and the conditioning.

use crate::physics::method::Asked;
use std::fmt::Write as _;

use serde::Serialize;

use super::super::params::Problem;
use crate::physics::method::Method;
use crate::physics::method::StepError;

use super::super::policy::{AVERAGED, SECOND_ORDER_MODEL_SHARE};
use super::measure::{Plan, averaged_local, with_companion};
use super::probe::{ModelProbe, averaged_is_exact, considers_averaged, probe_averaged};
use super::resolved::best_resolved;

/// What [`plan_cancellable`] decided: the plan, the probed model error it carries (0 for a
/// resolved plan) and the probes, when they ran.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Decision {
    /// The plan.
    pub plan: Plan,
    /// The averaged model's predicted error at this `k` (0 unless the plan is the averaged model).
    pub model_error: f64,
    /// The probes, when `k` called for them.
    pub probe: Option<ModelProbe>,
}

/// Chooses the method for `problem` over `[0, t_end]` at `tolerance` (no verification).
///
/// # Errors
/// [`StepError::Cancelled`] when `go_on` says stop during a probe.
pub fn plan_cancellable(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Decision, StepError> {
    let resolved = best_resolved(problem, tolerance, t_end);
    if !considers_averaged(problem, tolerance, t_end) {
        return Ok(Decision {
            plan: resolved,
            model_error: 0.0,
            probe: None,
        });
    }
    let probe = if averaged_is_exact(problem) {
        None
    } else {
        Some(probe_averaged(problem, t_end, go_on)?)
    };
    let model_error = probe.map_or(0.0, |p| p.predict(problem.params().k));
    let averaged = averaged_plan(
        problem,
        AVERAGED,
        model_error,
        tolerance,
        t_end,
        probe.map_or_else(
            || "the averaged model is exact here (ix = iy, or no fast action)".to_owned(),
            |probe| {
                format!(
                    "k large enough: the averaged model's error, probed at k = {:.0} and {:.0} \
                     (slope {:.2}), scales to {model_error:.1e}",
                    probe.k[0],
                    probe.k[1],
                    probe.slope()
                )
            },
        ),
    );
    // `averaged2` where its model error is a small share of the tolerance, when it is cheaper.
    let second = probe.and_then(|probe| {
        let error2 = probe.predict2(problem.params().k);
        (error2 <= SECOND_ORDER_MODEL_SHARE * tolerance).then(|| {
            let reason = format!(
                "k large enough: the second-order averaged model's error, probed at k = {:.0} \
                 and {:.0} (slope {:.2}), scales to {error2:.1e}",
                probe.k[0],
                probe.k[1],
                probe.slope2()
            );
            let plan = averaged_plan(problem, Method::Averaged2, error2, tolerance, t_end, reason);
            (plan, error2)
        })
    });
    let (averaged, model_error) = match second {
        Some((plan, error2)) if plan.predicted_seconds < averaged.predicted_seconds => {
            (plan, error2)
        }
        _ => (averaged, model_error),
    };
    let meets = |p: &Plan| p.predicted_error <= tolerance;
    let take_averaged = match (meets(&averaged), meets(&resolved)) {
        (true, true) => averaged.predicted_seconds < resolved.predicted_seconds,
        (true, false) => true,
        (false, true) => false,
        // Neither can: the more accurate.
        (false, false) => averaged.predicted_error < resolved.predicted_error,
    };
    if take_averaged {
        return Ok(Decision {
            plan: averaged,
            model_error,
            probe,
        });
    }
    let mut plan = resolved;
    let _ = write!(
        plan.reason,
        "; the averaged model's probed error here is {model_error:.1e}"
    );
    Ok(Decision {
        plan,
        model_error: 0.0,
        probe,
    })
}

/// An averaged model's plan with its probed `model_error`: the integration gets what the model
/// error leaves of the tolerance, at least half of it.
pub(super) fn averaged_plan(
    problem: &Problem,
    method: Method,
    model_error: f64,
    tolerance: f64,
    t_end: f64,
    reason: String,
) -> Plan {
    let share = (tolerance - model_error).max(0.5 * tolerance);
    let local = averaged_local(share, t_end);
    Plan {
        method,
        tolerance: local,
        step: None,
        predicted_error: model_error + 0.5 * share,
        predicted_seconds: with_companion(problem, &Asked::new(method, local, None, t_end)),
        reason,
    }
}

/// Chooses the method for `problem` (see [`plan_cancellable`]), never cancelled.
#[must_use]
pub fn plan(problem: &Problem, tolerance: f64, t_end: f64) -> Plan {
    plan_cancellable(problem, tolerance, t_end, &mut |_| true)
        .map_or_else(|_| best_resolved(problem, tolerance, t_end), |d| d.plan)
}
