//! Gauss–Legendre quadrature, fixed and adaptive.
//!
//! Used for the limit motion's half period and first reversal time (docs/physics.md §3), whose
//! integrands are made smooth by a change of variable; near the separatrix they develop a
//! logarithmic peak, which the adaptive rule resolves by bisection.
use crate::physics::numerics::elementary::Elementary;

/// Nodes and weights of the `n`-point Gauss–Legendre rule on `[-1, 1]`.
///
/// Computed by Newton's method on the Legendre polynomial, accurate to rounding.
///
/// # Panics
/// When `n` is 0.
#[must_use]
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n > 0, "a quadrature rule needs at least one node");
    let mut rule = Vec::with_capacity(n);
    let nf = n as f64;
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).e_cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // Three-term recurrence for P_n and its derivative.
            let (mut p0, mut p1) = (1.0, x);
            for j in 2..=n {
                let jf = j as f64;
                let p2 = ((2.0 * jf - 1.0) * x * p1 - (jf - 1.0) * p0) / jf;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { x } else { p1 };
            let pn1 = if n == 1 { 1.0 } else { p0 };
            dp = nf * (x * pn - pn1) / (x * x - 1.0);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        rule.push((x, w));
    }
    rule
}

/// Applies a rule from [`gauss_legendre`] on `[a, b]`.
pub fn integrate_fixed(rule: &[(f64, f64)], a: f64, b: f64, f: &mut impl FnMut(f64) -> f64) -> f64 {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    half * rule
        .iter()
        .map(|&(x, w)| w * f(mid + half * x))
        .sum::<f64>()
}

/// Most integrand evaluations one adaptive integral may spend (issue 29: a report's number is
/// bounded work). 20-point rule, 40 evaluations per bisection: about 5,000 bisections, well past
/// what a logarithmic peak needs (tens) and a small fraction of a millisecond per thousand.
pub const MAX_EVALUATIONS: usize = 200_000;

/// An adaptive integral with what it cost and how far it is from converged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Integral {
    /// The best value found.
    pub value: f64,
    /// The sum over the accepted pieces of `|two halves − whole|`: an estimate of the absolute
    /// error (conservative for a smooth integrand, the only honest one for rounding noise).
    pub error: f64,
    /// Integrand evaluations spent (at most [`MAX_EVALUATIONS`] plus one bisection of each piece
    /// still waiting when the cap is reached, at most 41 of them).
    pub evaluations: usize,
}

impl Integral {
    /// The value when its estimated relative error is at most `rel`, else `None`.
    #[must_use]
    pub fn within(&self, rel: f64) -> Option<f64> {
        (self.value.is_finite() && self.error <= rel * self.value.abs()).then_some(self.value)
    }
}

/// Integrates `f` over `[a, b]` to relative accuracy `rel_tol` by recursive bisection with a
/// 20-point rule, stopping at depth 40 or after [`MAX_EVALUATIONS`] evaluations (returning the
/// best estimate), so it always terminates in bounded time. See [`integrate_bounded`] for the
/// accuracy reached.
pub fn integrate_adaptive(a: f64, b: f64, rel_tol: f64, f: &mut impl FnMut(f64) -> f64) -> f64 {
    integrate_bounded(a, b, rel_tol, f).value
}

/// [`integrate_adaptive`] with the accuracy it reached and the work it spent.
///
/// Depth first, left to right, so the result is the same bits on every run. Once the cap is
/// reached each remaining piece is accepted as its two halves and its discrepancy is added to
/// the error.
pub fn integrate_bounded(a: f64, b: f64, rel_tol: f64, f: &mut impl FnMut(f64) -> f64) -> Integral {
    let rule = gauss_legendre(20);
    let whole = integrate_fixed(&rule, a, b, f);
    let mut out = Integral {
        value: 0.0,
        error: 0.0,
        evaluations: rule.len(),
    };
    // (a, b, whole, depth); popped from the end, right half pushed first.
    let mut stack = vec![(a, b, whole, 0_u32)];
    while let Some((lo, hi, whole, depth)) = stack.pop() {
        let mid = 0.5 * (lo + hi);
        let left = integrate_fixed(&rule, lo, mid, f);
        let right = integrate_fixed(&rule, mid, hi, f);
        out.evaluations += 2 * rule.len();
        let both = left + right;
        let gap = (both - whole).abs();
        let met = gap <= rel_tol * both.abs().max(f64::MIN_POSITIVE);
        if met || depth >= 40 || out.evaluations >= MAX_EVALUATIONS {
            out.value += both;
            out.error += gap;
            continue;
        }
        stack.push((mid, hi, right, depth + 1));
        stack.push((lo, mid, left, depth + 1));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rule_integrates_polynomials_exactly() {
        let rule = gauss_legendre(5);
        // Degree 9 is the highest a 5-point rule integrates exactly.
        let got = integrate_fixed(&rule, 0.0, 2.0, &mut |x: f64| x.powi(9));
        assert!((got - 2f64.powi(10) / 10.0).abs() < 1e-12, "{got}");
        let wsum: f64 = gauss_legendre(33).iter().map(|p| p.1).sum();
        assert!((wsum - 2.0).abs() < 1e-14);
    }

    #[test]
    fn adaptive_handles_log_peak() {
        // ∫_0^1 −ln(x) dx = 1 has an integrable singularity at 0.
        let got = integrate_adaptive(0.0, 1.0, 1e-13, &mut |x: f64| -x.e_ln());
        assert!((got - 1.0).abs() < 1e-10, "{got}");
        let full = integrate_bounded(0.0, 1.0, 1e-13, &mut |x: f64| -x.e_ln());
        // The piece at 0 reaches the depth cap with a negligible error.
        assert!(
            full.error < 1e-14 && full.evaluations < MAX_EVALUATIONS,
            "{full:?}"
        );
        assert_eq!(full.within(1e-9), Some(full.value));
    }

    #[test]
    fn rounding_noise_is_bounded_work_and_reported() {
        // An integrand that is pure noise never converges by bisection: the old recursion
        // spent up to 2^40 pieces on it (issue 29). Now it stops at the cap and says so.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut noise = |_x: f64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let u = (state >> 11) as f64 / (1u64 << 53) as f64;
            1.0 + 1e-3 * (u - 0.5)
        };
        let got = integrate_bounded(0.0, 1.0, 1e-12, &mut noise);
        assert!(got.evaluations <= MAX_EVALUATIONS + 41 * 40, "{got:?}");
        assert!((got.value - 1.0).abs() < 1e-3, "{got:?}");
        assert!(got.error > 1e-9, "{got:?}");
        assert_eq!(got.within(1e-12), None);
    }
}
