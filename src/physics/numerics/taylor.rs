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
use crate::physics::numerics::elementary::Elementary;

use nalgebra::SVector;

use crate::physics::method::StepError;
use crate::physics::numerics::dop853::Stats;

/// The step the series of order `order` allows, `size(n)` being the largest coefficient of order
/// `n` over its component's error scale.
#[must_use]
pub fn natural_step(order: usize, size: impl Fn(usize) -> f64) -> f64 {
    // `min (1/m_n)^{1/n}` as `exp(min −ln(m_n)/n)`: three logarithms and one exponential cost
    // less than three powers.
    let exponent = |n: usize| -size(n).e_ln() / n as f64;
    exponent(order - 2)
        .min(exponent(order - 1))
        .min(exponent(order))
        .e_exp()
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

/// `Σ c_n τ^n` by Horner's rule in `τ²`, the even and the odd orders apart: two independent
/// chains of half the length, `Σ c_{2j} τ^{2j} + τ Σ c_{2j+1} τ^{2j}`.
#[must_use]
pub fn horner(c: &[f64], tau: f64) -> f64 {
    let tau2 = tau * tau;
    let (mut even, mut odd) = (0.0, 0.0);
    let mut pairs = c.chunks_exact(2);
    if let [last] = pairs.remainder() {
        even = *last;
    }
    for pair in pairs.by_ref().rev() {
        even = even * tau2 + pair[0];
        odd = odd * tau2 + pair[1];
    }
    even + tau * odd
}

/// Where a Taylor-series integration is: the time, the last step's start and the work counted.
/// Both Taylor cores step with [`Clock::advance`].
#[derive(Clone, Copy, Debug)]
pub struct Clock {
    /// The current time.
    pub t: f64,
    /// The start of the last step.
    pub t_prev: f64,
    /// Steps and evaluations (each step counts `order` evaluations: one pass of the
    /// recurrences per order).
    pub stats: Stats,
}

impl Clock {
    /// At `t0`, nothing done.
    #[must_use]
    pub fn at(t0: f64) -> Self {
        Self {
            t: t0,
            t_prev: t0,
            stats: Stats::default(),
        }
    }

    /// One step of a series of order `order` expanded at the current time: the step
    /// [`towards`] allows from `natural`, the state `sum` gives at it, and the clock moved there.
    ///
    /// # Errors
    /// [`towards`]'s, or a state that is not finite.
    pub fn advance<const N: usize>(
        &mut self,
        order: usize,
        natural: f64,
        t_limit: f64,
        sum: impl Fn(f64) -> SVector<f64, N>,
    ) -> Result<SVector<f64, N>, StepError> {
        let (h, last) = towards(self.t, natural, t_limit)?;
        let y = sum(h);
        if !y.iter().all(|x| x.is_finite()) {
            return Err(StepError::NonFinite { t: self.t });
        }
        self.t_prev = self.t;
        self.t = if last { t_limit } else { self.t + h };
        self.stats.steps += 1;
        self.stats.rhs_evaluations += order as u64;
        Ok(y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Horner's rule in `τ²` against the plain sum, for odd and even lengths (a missing even or
    /// odd chain would drop a term).
    #[test]
    fn horner_sums_every_order() {
        for len in 0u8..8 {
            let c: Vec<f64> = (0..len).map(|n| 1.0 + 0.5 * f64::from(n)).collect();
            for tau in [0.0f64, 0.3, -1.7] {
                let plain: f64 = c
                    .iter()
                    .enumerate()
                    .map(|(n, x)| x * tau.powi(i32::try_from(n).unwrap()))
                    .sum();
                let got = horner(&c, tau);
                assert!(
                    (got - plain).abs() <= 1e-13 * plain.abs().max(1.0),
                    "len {len}, τ {tau}: {got} against {plain}"
                );
            }
        }
    }

    /// The step is the smallest radius `(1/m_n)^{1/n}` of the last three orders, infinite
    /// where they vanish.
    #[test]
    fn the_step_is_the_smallest_radius_of_the_last_three_orders() {
        let sizes = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.5, 2.0];
        let expected = 3f64.e_powf(-1.0 / 8.0).min(2f64.e_powf(-0.1));
        let got = natural_step(10, |n| sizes[n]);
        assert!(
            (got / expected - 1.0).abs() < 1e-14,
            "{got} against {expected}"
        );
        assert!(natural_step(10, |_| 0.0).is_infinite());
    }
}
