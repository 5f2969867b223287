//! The rattleback's weak-* observable (the paper's remark after its `cos²(x/n)` example):
//! `q_k = γ̇² g^{3/2}` converges to `θ` only weakly-*. The full model is resolved
//! (blanes-moan4 at `ω_max h = 0.5`) and sampled [`PER_PERIOD`] times per fastest period, so the
//! pointwise curve is the motion's own, not a reconstruction.

use super::model::{ALPHA, GAMMA_DOT};
use super::params::Problem;
use super::run::run_cancellable;
use crate::physics::method::RunSpec;
use crate::physics::method::{Method, StepError};

/// Samples per fastest fast period.
pub const PER_PERIOD: f64 = 24.0;

/// `(t, γ̇² g^{3/2})` of the resolved full motion over `[0, t_end]`, [`PER_PERIOD`] samples per
/// fastest period (the explorer averages it itself, for whatever window the user picks).
///
/// # Errors
/// When the integration fails or `go_on` stops it.
pub fn pointwise(
    problem: &Problem,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(Vec<f64>, Vec<f64>), StepError> {
    let p = problem.params();
    let omega = p.omega_max();
    let periods = omega * t_end / std::f64::consts::TAU;
    let samples = ((periods * PER_PERIOD).ceil() as usize).clamp(64, 20_000_000) + 1;
    let r = run_cancellable(
        problem,
        &RunSpec {
            method: Method::BlanesMoan4,
            tolerance: 1e-10,
            step: Some(0.5 / omega),
            t_end,
            samples,
            monitor_energy: false,
        },
        go_on,
    )?;
    Ok(r.samples
        .iter()
        .map(|s| {
            let g = p.g(s.state[ALPHA]);
            (s.t, s.state[GAMMA_DOT] * s.state[GAMMA_DOT] * g * g.sqrt())
        })
        .unzip())
}

/// The explorer's view covers at most this many fastest periods (from `t = 0`): enough for any
/// window to settle, bounded in cost whatever `k`.
pub const VIEW_PERIODS: f64 = 400.0;

/// The horizon the explorer's weak-* view computes for `problem` over `[0, t_end]`.
#[must_use]
pub fn view_horizon(problem: &Problem, t_end: f64) -> f64 {
    t_end.min(VIEW_PERIODS * std::f64::consts::TAU / problem.params().omega_max())
}
