//! Weak-* convergence (the paper's remark after its `cos²(x/n)` example): `q_k = γ̇² g^{3/2}`
//! converges to `θ` only weakly-*. Pointwise it swings between 0 and about `2θ` at every `k`;
//! its moving averages over a window `w` much longer than the fast period settle on `θ`
//! (to O(1/√k): with `γ̇² ≈ (2Iω/g) cos²φ` and `ω √g = √k`, `q ≈ 2 I √k cos²φ`, whose mean is
//! the adiabatic constant).
//!
//! The full model is resolved (blanes-moan4 at `ω_max h = 0.5`) and sampled 24 times per
//! fastest period, so the pointwise curve is the motion's own, not a reconstruction.

use crate::physics::rattleback::model::{ALPHA, GAMMA_DOT};
use serde::Serialize;

use crate::physics::rattleback::effective::Effective;
use crate::physics::rattleback::run::run_cancellable;
use crate::physics::rattleback::{Problem, RunSpec};
use crate::physics::{Method, StepError};

/// Samples per fastest fast period.
pub const PER_PERIOD: f64 = 24.0;

/// One stiffness of the weak-* view.
#[derive(Clone, Debug, Serialize)]
pub struct WeakStar {
    /// Hooke constant.
    pub k: f64,
    /// The limit's `θ`.
    pub theta: f64,
    /// Sample times.
    pub t: Vec<f64>,
    /// `γ̇² g(α)^{3/2}` at the sample times.
    pub pointwise: Vec<f64>,
    /// Its average over `[t − w/2, t + w/2]`, where that window lies in `[0, T]` (else NaN).
    pub average: Vec<f64>,
    /// The window.
    pub window: f64,
}

impl WeakStar {
    /// `(min, max)` of the pointwise values.
    #[must_use]
    pub fn pointwise_range(&self) -> (f64, f64) {
        self.pointwise
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &q| {
                (lo.min(q), hi.max(q))
            })
    }

    /// The largest `|average/θ − 1|` over the times where the window fits.
    #[must_use]
    pub fn worst_average_deviation(&self) -> f64 {
        self.average
            .iter()
            .filter(|a| a.is_finite())
            .map(|a| (a / self.theta - 1.0).abs())
            .fold(0.0, f64::max)
    }
}

/// `γ̇² g^{3/2}` and its moving average over `window` for `problem` at its own `k`, to `t_end`.
///
/// # Errors
/// When the integration fails or `go_on` stops it.
pub fn weak_star(
    problem: &Problem,
    t_end: f64,
    window: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<WeakStar, StepError> {
    let (t, pointwise) = pointwise(problem, t_end, go_on)?;
    let average = moving_average(&t, &pointwise, window);
    Ok(WeakStar {
        k: problem.params().k,
        theta: Effective::new(problem).theta(),
        t,
        pointwise,
        average,
        window,
    })
}

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

/// The trapezoidal average of `y` over `[t − w/2, t + w/2]` at each sample (evenly spaced `t`),
/// NaN where the window leaves the samples.
#[must_use]
pub fn moving_average(t: &[f64], y: &[f64], window: f64) -> Vec<f64> {
    let n = y.len();
    if n < 2 {
        return vec![f64::NAN; n];
    }
    let dt = t[1] - t[0];
    let half = ((0.5 * window / dt).round() as usize).max(1);
    // Prefix sums of the trapezoid areas.
    let mut area = vec![0.0; n];
    for i in 1..n {
        area[i] = area[i - 1] + 0.5 * (y[i] + y[i - 1]) * dt;
    }
    (0..n)
        .map(|i| {
            if i < half || i + half >= n {
                f64::NAN
            } else {
                #[allow(clippy::cast_precision_loss)]
                let span = (2 * half) as f64 * dt;
                (area[i + half] - area[i - half]) / span
            }
        })
        .collect()
}

/// Fast periods the pendulum's view covers at most (its slow motion is slower against the fast
/// period than the rattleback's, so the view spans more of them).
pub const PENDULUM_VIEW_PERIODS: f64 = 4000.0;

/// The pendulum's view horizon: `t_end`, or [`PENDULUM_VIEW_PERIODS`] fast periods.
#[must_use]
pub fn pendulum_view_horizon(problem: &crate::physics::kapitza::Problem, t_end: f64) -> f64 {
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
    problem: &crate::physics::kapitza::Problem,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<PendulumView, StepError> {
    use crate::physics::kapitza::run::{RunSpec, run};
    let periods = t_end / (std::f64::consts::TAU * problem.params().epsilon);
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let samples = ((periods * PER_PERIOD).ceil() as usize).clamp(64, 2_000_000) + 1;
    let spec = |method, tolerance| RunSpec {
        method,
        tolerance,
        step: None,
        t_end,
        samples,
    };
    let full = run(problem, &spec(Method::Dop853, 1e-10), go_on)?;
    let limit = run(problem, &spec(Method::Effective, 1e-12), go_on)?;
    let t = full.samples.iter().map(|s| s.t).collect();
    let pointwise = full.samples.iter().map(|s| s.theta_dot).collect();
    let reference = limit.samples.iter().map(|s| s.theta_dot).collect();
    Ok((t, pointwise, reference))
}
