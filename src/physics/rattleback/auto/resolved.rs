//! The resolved plans (DOP853, the series, the Blanes–Moan splitting) at a tolerance, the
//! cheapest of them, and the refinement of a plan whose verification missed.
use crate::physics::numerics::elementary::Elementary;

use super::super::policy::POLICY;
use crate::physics::method::Asked;
use std::fmt::Write as _;

use super::super::budget::{dop853_evaluations, fastest_rate};
use super::super::params::Problem;
use crate::physics::method::Method;

use super::super::policy::BLANES_MOAN_MAX_NU_H;
use super::measure::{
    Plan, blanes_moan_error, blanes_moan_rate, conditioned_round_off, dop853_local, round_off,
    splitting_drift, taylor_local, with_companion,
};

/// The cheapest plan that resolves the fast motion (taylor, dop853 or blanes-moan4) among those
/// whose coarser companion should still meet `tolerance` (or, when none can, the most accurate).
///
/// # Panics
/// Never: there are always three candidates.
#[must_use]
pub fn best_resolved(problem: &Problem, tolerance: f64, t_end: f64) -> Plan {
    let plans = resolved_plans(problem, tolerance, t_end);
    let meeting = plans.iter().filter(|p| p.predicted_error <= tolerance);
    meeting
        .min_by(|a, b| a.predicted_seconds.total_cmp(&b.predicted_seconds))
        .or_else(|| {
            plans
                .iter()
                .min_by(|a, b| a.predicted_error.total_cmp(&b.predicted_error))
        })
        .expect("three candidates")
        .clone()
}

pub(super) fn resolved_plans(problem: &Problem, tolerance: f64, t_end: f64) -> [Plan; 3] {
    let nu = fastest_rate(problem);
    let periods = nu * t_end / std::f64::consts::TAU;
    let (taylor_local, taylor_error) = taylor_local(tolerance, periods);
    let taylor_steps = super::super::budget::taylor_steps(taylor_local, periods);
    let taylor = Plan {
        method: Method::Taylor,
        tolerance: taylor_local,
        step: None,
        predicted_error: taylor_error + round_off(problem, taylor_steps, t_end),
        predicted_seconds: with_companion(
            problem,
            &Asked::new(Method::Taylor, taylor_local, None, t_end),
        ),
        reason: "resolved Taylor series, verified by a companion 1024x looser".to_owned(),
    };
    let (local, dop_error) = dop853_local(tolerance, periods);
    // Accepted steps: 12 evaluations each.
    let dop_steps = dop853_evaluations(local, periods) / 12.0;
    let dop_error = dop_error + round_off(problem, dop_steps, t_end);
    let dop = Plan {
        method: Method::Dop853,
        tolerance: local,
        step: None,
        predicted_error: dop_error,
        predicted_seconds: with_companion(problem, &Asked::new(Method::Dop853, local, None, t_end)),
        reason: "resolved adaptive integration".to_owned(),
    };
    // The companion at 2h should meet the tolerance: error(2h) ≤ tolerance / 2.
    let per_time = tolerance / (2.0 * t_end.max(1e-300));
    let h_companion = (per_time / blanes_moan_rate(problem)).e_powf(0.25);
    let h = (0.5 * h_companion).min(BLANES_MOAN_MAX_NU_H / nu);
    let bm = Plan {
        method: Method::BlanesMoan4,
        tolerance,
        step: Some(h),
        predicted_error: blanes_moan_error(problem, 2.0 * h, t_end)
            + conditioned_round_off(t_end / h, 1.0)
            + splitting_drift(t_end / h),
        predicted_seconds: with_companion(
            problem,
            &Asked::new(Method::BlanesMoan4, tolerance, Some(h), t_end),
        ),
        reason: format!("resolved exact-flow splitting at ν·h = {:.2}", nu * h),
    };
    [dop, bm, taylor]
}

/// The next plan after `plan` missed with `estimate`; `None` when nothing is predicted to do
/// better: the averaged model's own error misses and resolving would not beat it, or DOP853 is
/// at its tightest tolerance and the splitting's round-off floor is no lower.
pub(super) fn refine(
    problem: &Problem,
    plan: &Plan,
    model_error: f64,
    estimate: f64,
    tolerance: f64,
    t_end: f64,
) -> Option<Plan> {
    if plan.method.is_averaged() && model_error > 0.5 * tolerance {
        let mut resolved = best_resolved(problem, tolerance, t_end);
        if resolved.predicted_error >= estimate {
            return None;
        }
        let _ = write!(
            resolved.reason,
            "; the averaged model missed ({estimate:.1e}), resolved instead"
        );
        return Some(resolved);
    }
    let share = (tolerance - model_error).max(0.1 * tolerance);
    // How far the estimate is over what the integration may spend: at least what the policy's
    // least refinement answers (2: a factor 4), and what its blind one answers when infinite.
    let excess = if estimate.is_finite() {
        ((estimate - model_error).max(0.0) / share).max(0.5 / POLICY.refine)
    } else {
        0.5 / POLICY.blind_refine
    };
    if matches!(plan.method, Method::Dop853 | Method::Taylor)
        && plan.tolerance / (2.0 * excess) < POLICY.tightest
    {
        // DOP853 or the series cannot be tightened that far: the splitting, whose error does not
        // stall at a tolerance clamp, at the step its model asks for this tolerance, then
        // refined as needed.
        let [_, mut bm, _] = resolved_plans(problem, tolerance, t_end);
        if bm.predicted_error >= estimate {
            // Its round-off floor over this horizon is no better than what DOP853 reached.
            return None;
        }
        let _ = write!(
            bm.reason,
            "; {} missed ({estimate:.1e}) at its tightest tolerance, resolved by the splitting instead",
            plan.method
        );
        return Some(bm);
    }
    let mut next = plan.clone();
    if let Some(h) = plan.step {
        let p = f64::from(plan.method.order().max(1));
        next.step = Some(h / (POLICY.step_safety * excess.e_powf(1.0 / p)));
    } else {
        // Twice the excess (at least 4: the excess is at least 2), at least the series' least
        // refinement for the series.
        let factor = (2.0 * excess).max(super::super::policy::of(plan.method).refine.recip());
        next.tolerance = (plan.tolerance / factor).max(POLICY.tightest);
    }
    next.predicted_seconds = with_companion(
        problem,
        &Asked::new(next.method, next.tolerance, next.step, t_end),
    );
    next.predicted_error = plan.predicted_error / excess;
    let _ = write!(next.reason, "; refined ×{excess:.1}");
    Some(next)
}
