//! The fast phase `τ = t/ε` of the pendulum's lifts (the ripple added back to a slow motion),
//! and its harmonics `(sin kτ, cos kτ)`.
//!
//! The ripple in `θ̇` is O(b), not O(ε): `θ̇ = Θ̇ + b sin τ sin Θ + …`. An error `δ` in the phase
//! moves `θ̇` by up to `b δ`. Rounded in double, `t/ε` is off by up to half an ulp of itself,
//! `ε_mach t/(2ε)`: 1.1e-7 rad at `t = 5`, `ε = 1e-9`. That was the floor of every estimate below
//! `ε = 1e-6` (issue 27: measured errors 9e-10 … 1.1e-7 at ε = 1e-7 … 1e-9, `met = false` at any
//! tolerance under 2e-6).
//!
//! [`FastPhase::Exact`] carries what the division dropped: `q = t/ε` rounded, the exact remainder
//! `r = t − q ε` by a fused multiply-add (exact for a correctly rounded quotient), `τ = q + r/ε`.
//! Each harmonic `k τ` is `p + d` with `p = k q` rounded, `d` its exact product error (another
//! fused multiply-add) plus `k r/ε`; then `sin(p + d) = sin p (1 − d²/2) + cos p · d` (|d| is at
//! most an ulp of `p`, 4e-6 at `6 τ = 3e10`, so the next term is below 1e-17). `sin p` itself is
//! exact to an ulp whatever `p`: the C library reduces large arguments exactly.
//!
//! [`FastPhase::Rounded`] is the phase as it was computed up to session format 7: `τ` rounded,
//! `(k τ).e_sin_cos()`. A replay of such a file uses it, so the file's bits come back
//! (`crate::physics::method::Arithmetic`). The full model's own right-hand side keeps the rounded
//! phase: its runs are resolved only where `t/ε` is small enough for the rounding to sit far
//! below their tolerance, and their estimates count it (`super::plan::rounding_floor`).
use crate::physics::numerics::elementary::Elementary;

/// How the lifts take the fast phase `t/ε`: a rule of the arithmetic, declared with the
/// others (`physics::method`); its harmonics are the pendulum's, here.
pub use crate::physics::method::FastPhase;

impl FastPhase {
    /// `(sin kτ, cos kτ)` for `k = 1 … N`, `τ = t/ε`.
    #[must_use]
    #[inline]
    pub fn harmonics<const N: usize>(self, t: f64, epsilon: f64) -> [(f64, f64); N] {
        let q = t / epsilon;
        let mut out = [(0.0, 0.0); N];
        match self {
            Self::Rounded => {
                // `1.0 * q` is `q`: the first harmonic is the phase's own, as before.
                for (k, h) in (1_u32..).zip(out.iter_mut()) {
                    *h = (f64::from(k) * q).e_sin_cos();
                }
            }
            Self::Exact => {
                // τ = q + lo exactly (to rounding of lo, an ulp of an ulp of q).
                let lo = (-q).mul_add(epsilon, t) / epsilon;
                for (k, h) in (1_u32..).zip(out.iter_mut()) {
                    let k = f64::from(k);
                    let p = k * q;
                    let d = k.mul_add(q, -p) + k * lo;
                    let (s, c) = p.e_sin_cos();
                    let half_d2 = 0.5 * d * d;
                    *h = (
                        c.mul_add(d, s - s * half_d2),
                        (-s).mul_add(d, c - c * half_d2),
                    );
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Rounded` is bit for bit what the lifts computed before (old recordings replay on it).
    #[test]
    #[allow(clippy::float_cmp)]
    fn rounded_is_the_old_arithmetic() {
        for (t, e) in [(0.37, 1e-3), (5.0, 1e-9), (17.25, 0.013)] {
            let h = FastPhase::Rounded.harmonics::<4>(t, e);
            let phase = t / e;
            assert_eq!(h[0], phase.e_sin_cos());
            assert_eq!(h[1], (2.0 * t / e).e_sin_cos());
            assert_eq!(h[2], (3.0 * phase).e_sin_cos());
            assert_eq!(h[3], (4.0 * phase).e_sin_cos());
        }
    }

    /// Against the phase in exact rational arithmetic: `t` and `ε` are doubles, so `t/ε` is a
    /// ratio of integers times a power of two; its fractional turns, reduced exactly, give
    /// sin and cos to double precision. `Exact` is within a few ulps at phases up to 3e10, where
    /// `Rounded` is off by up to 1e-6.
    #[test]
    fn exact_matches_the_phase_reduced_in_integers() {
        let mut worst_exact: f64 = 0.0;
        let mut worst_rounded: f64 = 0.0;
        for (t, e) in [
            (5.0, 1e-9),
            (4.75, 1e-8),
            (3.3, 1e-7),
            (0.123_456, 3e-9),
            (2.5, 1e-2),
        ] {
            let exact = FastPhase::Exact.harmonics::<6>(t, e);
            let rounded = FastPhase::Rounded.harmonics::<6>(t, e);
            for (k, (x, r)) in (1_u32..).zip(exact.iter().zip(&rounded)) {
                let truth = reference(t, e, k);
                worst_exact = worst_exact
                    .max((x.0 - truth.0).abs())
                    .max((x.1 - truth.1).abs());
                worst_rounded = worst_rounded
                    .max((r.0 - truth.0).abs())
                    .max((r.1 - truth.1).abs());
            }
        }
        eprintln!("exact {worst_exact:e}, rounded {worst_rounded:e}");
        assert!(worst_exact < 4e-15, "exact phase off by {worst_exact:e}");
        assert!(
            worst_rounded > 1e-8,
            "the test sees the rounding: {worst_rounded:e}"
        );
    }

    /// `(sin kτ, cos kτ)` with `kτ = k t/ε` reduced modulo 2π in 128-bit integers: `k t/ε =
    /// n 2π + f` with `f` found from the exact quotient's integer and fractional parts (`t` and
    /// `ε` as integer mantissas and exponents), `π` to 38 digits.
    fn reference(t: f64, e: f64, k: u32) -> (f64, f64) {
        // k t / ε as an exact fraction num / den, both below 2^127.
        let (mt, et) = split(t);
        let (me, ee) = split(e);
        let shift = et - ee; // k t/ε = k mt / me · 2^shift
        let (mut num, mut den) = (u128::from(k) * u128::from(mt), u128::from(me));
        if shift >= 0 {
            num <<= shift;
        } else {
            den <<= -shift;
        }
        // Turns: (num/den) / 2π; reduce num/den modulo 2π via the integer part of num/den
        // (at most 3e10, so an f64 of its remainder mod 2π keeps 1e-16 relative accuracy
        // when the integer is reduced with π to 38 digits).
        let whole = num / den;
        let frac = (num % den) as f64 / den as f64;
        let two_pi_hi = std::f64::consts::TAU;
        let two_pi_lo = 2.449_293_598_294_706_4e-16;
        let w = whole as f64;
        let n = (w / two_pi_hi).floor();
        // w − n 2π, in two parts (w and n exact in double below 2^53).
        let r = (-n).mul_add(two_pi_hi, w) - n * two_pi_lo + frac;
        r.e_sin_cos()
    }

    fn split(x: f64) -> (u64, i32) {
        let bits = x.to_bits();
        let exp = i32::try_from((bits >> 52) & 0x7ff).unwrap() - 1075;
        let mant = (bits & ((1 << 52) - 1)) | (1 << 52);
        (mant, exp)
    }
}
