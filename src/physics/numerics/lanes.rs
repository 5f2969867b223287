//! Arithmetic on one number or on [`LANES`] of them at once (issue 84: a chart's cells advanced
//! side by side). [`Real`] is what a right-hand side and the DOP853 stages and error need: the
//! four operations, negation, the square root and the absolute value, each exact or correctly
//! rounded by IEEE 754, so a lane of [`F64x4`] gives, operation for operation, the bits `f64`
//! gives. Nothing here fuses a
//! multiplication into an addition (Rust never contracts), so the same expression written once
//! for `R: Real` is the same computation at either width, in every build.
// Inlined into the caller compiled for the machine's vector unit (`multiversion`): a call
// that is not inlined runs at the baseline's width.
#![allow(clippy::inline_always)]

use std::ops::{Add, Div, Mul, Neg, Sub};

/// How many cells a batched integration advances at once: four `f64`, one 256-bit register
/// (two 128-bit ones where the machine has no AVX).
pub const LANES: usize = 4;

/// A number, or a pack of numbers operated on lane by lane.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// The square root, lane by lane.
    #[must_use]
    fn sqrt(self) -> Self;
    /// `|x|`, lane by lane.
    #[must_use]
    fn abs(self) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
}

/// [`LANES`] numbers operated on lane by lane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct F64x4(pub [f64; LANES]);

impl F64x4 {
    /// [`f64::max`], lane by lane.
    #[inline(always)]
    #[must_use]
    pub fn max(self, o: Self) -> Self {
        self.zip(o, f64::max)
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Self([f(self.0[0]), f(self.0[1]), f(self.0[2]), f(self.0[3])])
    }
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Self([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
            f(self.0[3], o.0[3]),
        ])
    }
}

macro_rules! lanewise {
    ($($trait:ident $method:ident $op:tt),*) => {$(
        impl $trait for F64x4 {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                self.zip(o, |a, b| a $op b)
            }
        }
    )*};
}
lanewise!(Add add +, Sub sub -, Mul mul *, Div div /);

impl Neg for F64x4 {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
}

impl Real for F64x4 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Self([x; LANES])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f64::abs)
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A 64-bit generator (`SplitMix64`) for the lanes' tests' numbers, from a printed seed.
    pub(in super::super) fn next(state: &mut u64) -> u64 {
        *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// The same bits, or both NaN.
    pub(in super::super) fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    /// Each lane of every operation is the scalar operation's bits, on numbers of every size
    /// and sign (subnormals, zeros of both signs, infinities and NaN included).
    #[test]
    fn every_lane_is_the_scalar_operation() {
        let seed = 84;
        eprintln!("seed {seed}");
        let mut rng = seed;
        let special = [
            0.0,
            -0.0,
            1e-310,
            -1e-310,
            f64::INFINITY,
            f64::NAN,
            1.0,
            -3.5,
        ];
        let mut pick = || {
            let r = next(&mut rng);
            if r.is_multiple_of(5) {
                special[(r >> 8) as usize % special.len()]
            } else {
                f64::from_bits(next(&mut rng))
            }
        };
        for _ in 0..10_000 {
            let x: [f64; LANES] = std::array::from_fn(|_| pick());
            let y: [f64; LANES] = std::array::from_fn(|_| pick());
            let (a, b) = (F64x4(x), F64x4(y));
            for l in 0..LANES {
                assert!(same((a + b).0[l], x[l] + y[l]), "seed {seed}");
                assert!(same((a - b).0[l], x[l] - y[l]), "seed {seed}");
                assert!(same((a * b).0[l], x[l] * y[l]), "seed {seed}");
                assert!(same((a / b).0[l], x[l] / y[l]), "seed {seed}");
                assert!(same((-a).0[l], -x[l]), "seed {seed}");
                assert!(same(a.sqrt().0[l], x[l].sqrt()), "seed {seed}");
                assert!(same(a.abs().0[l], x[l].abs()), "seed {seed}");
                assert!(same(a.max(b).0[l], x[l].max(y[l])), "seed {seed}");
            }
        }
    }
}
