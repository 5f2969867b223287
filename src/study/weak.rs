//! Weak-* convergence (the paper's remark after its `cos²(x/n)` example): `q_k = γ̇² g^{3/2}`
//! converges to `θ` only weakly-*. Pointwise it swings between 0 and about `2θ` at every `k`;
//! its moving averages over a window `w` much longer than the fast period settle on `θ`
//! (to O(1/√k): with `γ̇² ≈ (2Iω/g) cos²φ` and `ω √g = √k`, `q ≈ 2 I √k cos²φ`, whose mean is
//! the adiabatic constant).
//!
//! The observables themselves are the models' own (`physics::rattleback::weak`,
//! `physics::kapitza::weak`, reached through `Model::weak_view`); this is the study of them.

use serde::Serialize;

use crate::physics::StepError;
use crate::physics::rattleback::Problem;
use crate::physics::rattleback::effective::Effective;
use crate::physics::rattleback::weak::pointwise;

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
                let span = (2 * half) as f64 * dt;
                (area[i + half] - area[i - half]) / span
            }
        })
        .collect()
}
