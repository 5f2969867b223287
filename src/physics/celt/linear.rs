//! The linear stability of steady upright spin (issue 59; docs/charts.md): the body standing on
//! its lowest point, `γ = (0, 0, 1)`, spinning about its `z` axis at the rate `n` (`ω = (0, 0,
//! n)`) is an equilibrium of the reduced equations (`z` is a principal axis: the product of
//! inertia couples `x` and `y` only). The Jacobian of the field's `(ω, γ)` block there, by
//! central differences, has six eigenvalues: two zero (the spin family and `|γ| = 1`) and two
//! pairs, the rolling and the pitching modes. The largest real part is the growth rate of the
//! spinning motion: positive in a sense where a small tilt grows (and the spin, as the tilt's
//! oscillation feeds back, reverses), negative or zero where it decays. A rolling constraint
//! does no work, yet the steady spin can attract in one sense and repel in the other: the
//! celt's chirality, from the skew of its inertia axes against its geometric ones.
//!
//! On the Kane–Levinson body both senses grow at every spin rate (the preferred sense about ten
//! times slower: 0.20/s against 2.1/s at 5 rad/s), so the sign of the growth rate changes only
//! where the spin or the skew vanishes. What separates the senses on a chart of a finite window
//! is the growth against the window: a tilt `θ0` growing at rate `λ` reaches a radian, where
//! the spin turns over, after about `ln(1/θ0)/λ`. The chart draws where that equals `T`
//! ([`crossings`] at the level `ln(1/θ0)/T`).

use nalgebra::SMatrix;

use super::{Params, State};

/// How far the differences reach, relative to `max(1, |n|)`.
const STEP: f64 = 1e-6;

/// The Jacobian of `(ω̇, γ̇)` at steady spin `n`, by central differences.
#[must_use]
pub fn jacobian(p: &Params, n: f64) -> SMatrix<f64, 6, 6> {
    let mut y0 = State::zeros();
    y0[2] = n;
    y0[5] = 1.0;
    y0[6] = 1.0; // the identity quaternion (nothing above feeds back from it)
    let h = STEP * n.abs().max(1.0);
    let mut j = SMatrix::<f64, 6, 6>::zeros();
    for col in 0..6 {
        let (mut up, mut down) = (y0, y0);
        up[col] += h;
        down[col] -= h;
        let (fu, fd) = (p.field(&up), p.field(&down));
        for row in 0..6 {
            j[(row, col)] = (fu[row] - fd[row]) / (2.0 * h);
        }
    }
    j
}

/// The growth rate of steady spin `n` (1/s): the largest real part among the Jacobian's
/// eigenvalues.
#[must_use]
pub fn growth_rate(p: &Params, n: f64) -> f64 {
    jacobian(p, n)
        .complex_eigenvalues()
        .iter()
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Below this growth rate (1/s) steady spin counts as not growing: the differences' own error
/// (measured: the real parts of the two zero eigenvalues and of a neutral pair stay below
/// 1e-6 on the shipped bodies).
pub const NEUTRAL: f64 = 1e-5;

/// The spin rates in `(lo, hi)` where the growth rate crosses `level` (1/s; [`NEUTRAL`] for the
/// boundary of linear stability itself), found on `samples` evenly spaced rates and refined by
/// bisection to `1e-9` of the span.
#[must_use]
pub fn crossings(p: &Params, lo: f64, hi: f64, samples: usize, level: f64) -> Vec<f64> {
    let grows = |n: f64| growth_rate(p, n) > level;
    let samples = samples.max(2);
    let at = |i: usize| lo + (hi - lo) * i as f64 / (samples - 1) as f64;
    let mut out = Vec::new();
    let (mut x0, mut g0) = (at(0), grows(at(0)));
    for i in 1..samples {
        let x1 = at(i);
        let g1 = grows(x1);
        if g1 != g0 {
            let (mut a, mut b) = (x0, x1);
            while (b - a).abs() > 1e-9 * (hi - lo).abs() {
                let m = 0.5 * (a + b);
                if grows(m) == g0 {
                    a = m;
                } else {
                    b = m;
                }
            }
            out.push(0.5 * (a + b));
        }
        (x0, g0) = (x1, g1);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Kane–Levinson body with another product of inertia.
    fn kane_levinson(product: f64) -> Params {
        Params {
            product,
            ..Params::KANE_LEVINSON
        }
    }

    #[test]
    fn a_skewed_body_is_chiral_and_a_symmetric_one_is_not() {
        let p = kane_levinson(-0.2);
        // The preset's clockwise spin (-5 rad/s) reverses: its steady spin grows.
        assert!(growth_rate(&p, -5.0) > 0.1, "{}", growth_rate(&p, -5.0));
        // Mirrored body, mirrored spin: the same growth.
        let m = kane_levinson(0.2);
        let (g, gm) = (growth_rate(&p, -5.0), growth_rate(&m, 5.0));
        assert!((g - gm).abs() < 1e-6 * g.abs(), "{g} {gm}");
        // No skew: both senses alike.
        let s = kane_levinson(0.0);
        assert!((growth_rate(&s, 3.0) - growth_rate(&s, -3.0)).abs() < 1e-6);
    }
}
