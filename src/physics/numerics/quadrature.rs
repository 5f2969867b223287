//! Gauss–Legendre quadrature, fixed and adaptive.
//!
//! Used for the limit motion's half period and first reversal time (physics.md §3), whose
//! integrands are made smooth by a change of variable; near the separatrix they develop a
//! logarithmic peak, which the adaptive rule resolves by bisection.

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
    #[allow(clippy::cast_precision_loss)]
    let nf = n as f64;
    for i in 0..n {
        #[allow(clippy::cast_precision_loss)]
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // Three-term recurrence for P_n and its derivative.
            let (mut p0, mut p1) = (1.0, x);
            for j in 2..=n {
                #[allow(clippy::cast_precision_loss)]
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

/// Integrates `f` over `[a, b]` to relative accuracy `rel_tol` by recursive bisection with a
/// 20-point rule; stops at depth 40 (returning the best estimate) so it always terminates.
pub fn integrate_adaptive(a: f64, b: f64, rel_tol: f64, f: &mut impl FnMut(f64) -> f64) -> f64 {
    let rule = gauss_legendre(20);
    let whole = integrate_fixed(&rule, a, b, f);
    refine(&rule, a, b, whole, rel_tol, 0, f)
}

fn refine(
    rule: &[(f64, f64)],
    a: f64,
    b: f64,
    whole: f64,
    rel_tol: f64,
    depth: u32,
    f: &mut impl FnMut(f64) -> f64,
) -> f64 {
    let mid = 0.5 * (a + b);
    let left = integrate_fixed(rule, a, mid, f);
    let right = integrate_fixed(rule, mid, b, f);
    let both = left + right;
    if depth >= 40 || (both - whole).abs() <= rel_tol * both.abs().max(f64::MIN_POSITIVE) {
        return both;
    }
    refine(rule, a, mid, left, rel_tol, depth + 1, f)
        + refine(rule, mid, b, right, rel_tol, depth + 1, f)
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
        let got = integrate_adaptive(0.0, 1.0, 1e-13, &mut |x: f64| -x.ln());
        assert!((got - 1.0).abs() < 1e-10, "{got}");
    }
}
