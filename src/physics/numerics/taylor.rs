//! What the Taylor-series integrators share (the pendulum's `kapitza::taylor`, the rattleback's
//! `full_taylor`): the step from the series' last coefficients, the step towards a limit with
//! its checks, and Horner's rule for the series and its dense output.
//!
//! **Step size** (after Jorba and Zou, 2005): with each coefficient measured in its component's
//! error scale, the step is the smallest of `(1/m_n)^{1/n}` over the last three orders
//! `n = N−2, N−1, N`, `m_n` the largest scaled coefficient of order `n` (three, not their two: a
//! coefficient that happens to be small, between a sine's and a cosine's, read as a wide radius
//! let an occasional step err far more than the rest). The first neglected term is then about
//! the tolerance times the step over the series' radius.

use crate::physics::method::StepError;
use crate::physics::numerics::dop853::Stats;

/// The step the series of order `order` allows, `size(n)` being the largest coefficient of order
/// `n` over its component's error scale.
#[must_use]
#[allow(clippy::cast_precision_loss)]
pub fn natural_step(order: usize, size: impl Fn(usize) -> f64) -> f64 {
    let radius = |n: usize| {
        let m = size(n);
        if m == 0.0 {
            f64::INFINITY
        } else {
            m.powf(-1.0 / n as f64)
        }
    };
    radius(order - 2).min(radius(order - 1)).min(radius(order))
}

/// The step to take from `t` towards `t_limit` (which must exceed `t`) when the series allows
/// `natural`: `natural`, or what is left when that reaches the limit (then `true`: the step
/// lands on `t_limit` exactly).
///
/// # Errors
/// A step that is not a positive finite number, or one too small to move the time.
pub fn towards(t: f64, natural: f64, t_limit: f64) -> Result<(f64, bool), StepError> {
    let remaining = t_limit - t;
    let last = natural >= remaining;
    let h = if last { remaining } else { natural };
    if h.is_nan() || h <= 0.0 || h.is_infinite() {
        return Err(StepError::NonFinite { t });
    }
    if h <= 16.0 * f64::EPSILON * t.abs() && !last {
        return Err(StepError::StepTooSmall { t, h });
    }
    Ok((h, last))
}

/// `Σ c_n τ^n` by Horner's rule.
#[must_use]
pub fn horner(c: &[f64], tau: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &x| acc * tau + x)
}

/// One step of a series of order `order` expanded at `*t`: the step [`towards`] allows from
/// `natural`, the state `sum` gives at it (`None` when not finite), and the time, the previous
/// step's start and the counts moved there. Both Taylor cores step with it.
///
/// # Errors
/// [`towards`]'s, or a state that is not finite.
pub fn advance<S>(
    t: &mut f64,
    t_prev: &mut f64,
    stats: &mut Stats,
    order: usize,
    natural: f64,
    t_limit: f64,
    sum: impl Fn(f64) -> Option<S>,
) -> Result<S, StepError> {
    let (h, last) = towards(*t, natural, t_limit)?;
    let y = sum(h).ok_or(StepError::NonFinite { t: *t })?;
    *t_prev = *t;
    *t = if last { t_limit } else { *t + h };
    stats.steps += 1;
    stats.rhs_evaluations += order as u64;
    Ok(y)
}
