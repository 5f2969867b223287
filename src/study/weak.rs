//! Weak-* convergence (the paper's remark after its `cos²(x/n)` example): `q_k = γ̇² g^{3/2}`
//! converges to `θ` only weakly-*. Pointwise it swings between 0 and about `2θ` at every `k`;
//! its moving averages over a window `w` much longer than the fast period settle on `θ`
//! (to O(1/√k): with `γ̇² ≈ (2Iω/g) cos²φ` and `ω √g = √k`, `q ≈ 2 I √k cos²φ`, whose mean is
//! the adiabatic constant).
//!
//! The full model is resolved (blanes-moan4 at `ω_max h = 0.5`) and sampled 24 times per
//! fastest period, so the pointwise curve is the motion's own, not a reconstruction.

use crate::physics::model::{ALPHA, GAMMA_DOT};
use serde::Serialize;

use crate::physics::effective::Effective;
use crate::physics::run::run_cancellable;
use crate::physics::{Method, Problem, RunSpec, StepError};

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
