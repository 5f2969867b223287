//! The pendulum's weak-* observable: `θ̇_ε` keeps its O(1) ripple pointwise at every `ε`;
//! averaged over a window much longer than the fast period it follows the limit's.

use super::Problem;
use super::run::run;
use crate::physics::method::{Asked, RunSpec};
use crate::physics::method::{Method, StepError};

/// Samples per fast period.
pub const PER_PERIOD: f64 = 24.0;

/// Fast periods the pendulum's view covers at most (its slow motion is slower against the fast
/// period than the rattleback's, so the view spans more of them).
pub const PENDULUM_VIEW_PERIODS: f64 = 4000.0;

/// The pendulum's view horizon: `t_end`, or [`PENDULUM_VIEW_PERIODS`] fast periods.
#[must_use]
pub fn pendulum_view_horizon(problem: &Problem, t_end: f64) -> f64 {
    t_end.min(PENDULUM_VIEW_PERIODS * std::f64::consts::TAU * problem.params().epsilon)
}

/// Sample times, `θ̇_ε` at them, and the limit's `θ̇` at them.
pub type PendulumView = (Vec<f64>, Vec<f64>, Vec<f64>);

/// The pendulum's weak-* view: `θ̇_ε` of the full motion pointwise (resolved by `dop853` at
/// 1e-10, 24 samples a fast period) and the limit's `θ̇` at the same times. Pointwise, `θ̇_ε`
/// keeps its O(1) ripple `b sin(t/ε) sin θ` at every `ε`; averaged over a window much longer than
/// the fast period it follows the limit's (averaged the same way) to O(ε).
///
/// # Errors
/// When a run fails or `go_on` cancels.
pub fn pendulum_pointwise(
    problem: &Problem,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<PendulumView, StepError> {
    let periods = t_end / (std::f64::consts::TAU * problem.params().epsilon);
    let samples = ((periods * PER_PERIOD).ceil() as usize).clamp(64, 2_000_000) + 1;
    let spec =
        |method, tolerance| RunSpec::new(Asked::new(method, tolerance, None, t_end), samples);
    let full = run(problem, &spec(Method::Dop853, 1e-10), go_on)?;
    let limit = run(problem, &spec(Method::Effective, 1e-12), go_on)?;
    let t = full.samples.iter().map(|s| s.t).collect();
    let pointwise = full.samples.iter().map(|s| s.theta_dot).collect();
    let reference = limit.samples.iter().map(|s| s.theta_dot).collect();
    Ok((t, pointwise, reference))
}
