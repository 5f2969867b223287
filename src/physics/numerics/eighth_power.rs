//! `x^(−1/8)` in [`LANES`] at once: the DOP853 controller's power (issue 84: computed lane by
//! lane by the scalar `pow`, it was an eighth of a celt chart's time).
//!
//! Each lane is the bits [`Elementary::e_powf`]`(x, −1/8)` gives. For the thread's portable
//! functions that is the `libm` crate's `pow`, a port of FreeBSD's `e_pow.c`; for a positive
//! normal `x` between 2^−1000 and 2^1000 (not 1), and `y = −1/8`, that `pow` takes one path, with
//! no branch on a floating-point value but the choice of a table entry and of a rounding to an
//! integer power of two. This module follows that path, its floating-point operations in its
//! order (so the same bits: each is correctly rounded by IEEE 754, and Rust fuses none), in
//! lanes of [`F64x4`], and its integer steps lane by lane. Any other `x` (zero, subnormal,
//! huge, not finite, negative, 1), and every lane on a thread that follows the platform's
//! functions (an old recording's replay), takes the scalar function itself. A test holds every
//! lane to the scalar function on generated numbers of every kind.

// Inlined into the lanes' caller, compiled for the machine's vector unit (`multiversion`).
#![allow(
    clippy::inline_always,
    clippy::excessive_precision,
    clippy::unreadable_literal
)]

use super::elementary::{Elementary, Functions, current};
use super::lanes::{F64x4, LANES, Real};

/// The power.
const Y: f64 = -0.125;
/// The range the lanes' path holds for (the scalar function is taken outside it).
const LOWEST: f64 = f64::from_bits(23 << 52); // 2^−1000
const HIGHEST: f64 = f64::from_bits(2023 << 52); // 2^1000

// `e_pow.c`'s constants, written as the `libm` crate writes them.
const BP: [f64; 2] = [1.0, 1.5];
const DP_H: [f64; 2] = [0.0, 5.84962487220764160156e-01];
const DP_L: [f64; 2] = [0.0, 1.35003920212974897128e-08];
const L1: f64 = 5.99999999999994648725e-01;
const L2: f64 = 4.28571428578550184252e-01;
const L3: f64 = 3.33333329818377432918e-01;
const L4: f64 = 2.72728123808534006489e-01;
const L5: f64 = 2.30660745775561754067e-01;
const L6: f64 = 2.06975017800338417784e-01;
const P1: f64 = 1.66666666666666019037e-01;
const P2: f64 = -2.77777777770155933842e-03;
const P3: f64 = 6.61375632143793436117e-05;
const P4: f64 = -1.65339022054652515390e-06;
const P5: f64 = 4.13813679705723846039e-08;
const LG2: f64 = std::f64::consts::LN_2; // e_pow.c's lg2, 0x3fe62e42_fefa39ef
const LG2_H: f64 = 6.93147182464599609375e-01;
const LG2_L: f64 = -1.90465429995776804525e-09;
const CP: f64 = 9.61796693925975554329e-01;
const CP_H: f64 = 9.61796700954437255859e-01;
const CP_L: f64 = -7.02846165095275826516e-09;

/// `x` with its low 32 bits cleared (`SET_LOW_WORD(x, 0)`).
#[inline(always)]
fn high_only(x: F64x4) -> F64x4 {
    F64x4(x.0.map(|v| f64::from_bits(v.to_bits() & 0xFFFF_FFFF_0000_0000)))
}

/// `x` with its high 32 bits set to `high` (`SET_HIGH_WORD(x, high)`).
#[inline(always)]
fn with_high(x: f64, high: u32) -> f64 {
    f64::from_bits((x.to_bits() & 0xFFFF_FFFF) | (u64::from(high) << 32))
}

/// The high 32 bits of `x`, signed (`GET_HIGH_WORD`).
#[inline(always)]
#[allow(clippy::cast_possible_wrap)]
fn high(x: f64) -> i32 {
    (x.to_bits() >> 32) as u32 as i32
}

/// `x^(−1/8)` in every lane, each lane the bits `x.e_powf(-0.125)` gives on this thread.
#[inline(always)]
#[must_use]
#[allow(
    clippy::cast_sign_loss,
    clippy::similar_names,
    clippy::many_single_char_names,
    clippy::too_many_lines
)]
pub fn eighth_power(x: [f64; LANES]) -> [f64; LANES] {
    let scalar = |v: f64| v.e_powf(Y);
    let inside = x.map(|v| (LOWEST..=HIGHEST).contains(&v) && v.to_bits() != 1f64.to_bits());
    if current() == Functions::Platform || !inside.contains(&true) {
        return x.map(scalar);
    }
    // A lane outside the range computes 2's power, and is not read.
    let ax_in: [f64; LANES] = std::array::from_fn(|l| if inside[l] { x[l] } else { 2.0 });
    // log2(x) = n + log2(ax), ax in [sqrt(3)/2, sqrt(3)), relative to bp[k].
    let (mut ax, mut th, mut bp, mut dph, mut dpl, mut nf) = (
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
        [0.0; LANES],
    );
    for l in 0..LANES {
        let ix = high(ax_in[l]) & 0x7fff_ffff;
        let mut n = (ix >> 20) - 0x3ff;
        let j = ix & 0x000f_ffff;
        let mut ix = j | 0x3ff0_0000;
        let k = if j <= 0x3988E {
            0
        } else if j < 0xBB67A {
            1
        } else {
            n += 1;
            ix -= 0x0010_0000;
            0
        };
        ax[l] = with_high(ax_in[l], ix as u32);
        th[l] = with_high(
            0.0,
            ((ix as u32 >> 1) | 0x2000_0000) + 0x0008_0000 + ((k as u32) << 18),
        );
        (bp[l], dph[l], dpl[l]) = (BP[k], DP_H[k], DP_L[k]);
        nf[l] = f64::from(n);
    }
    let c = F64x4::splat;
    let (ax, t_h, bp, dp_h, dp_l, t) = (
        F64x4(ax),
        F64x4(th),
        F64x4(bp),
        F64x4(dph),
        F64x4(dpl),
        F64x4(nf),
    );
    // ss = s_h + s_l = (ax − bp) / (ax + bp).
    let u = ax - bp;
    let v = c(1.0) / (ax + bp);
    let ss = u * v;
    let s_h = high_only(ss);
    let t_l = ax - (t_h - bp);
    let s_l = v * ((u - s_h * t_h) - s_h * t_l);
    // log(ax).
    let s2 = ss * ss;
    let mut r =
        s2 * s2 * (c(L1) + s2 * (c(L2) + s2 * (c(L3) + s2 * (c(L4) + s2 * (c(L5) + s2 * c(L6))))));
    r = r + s_l * (s_h + ss);
    let s2 = s_h * s_h;
    let t_h = high_only(c(3.0) + s2 + r);
    let t_l = r - ((t_h - c(3.0)) - s2);
    let u = s_h * t_h;
    let v = s_l * t_h + t_l * ss;
    let p_h = high_only(u + v);
    let p_l = v - (p_h - u);
    let z_h = c(CP_H) * p_h;
    let z_l = c(CP_L) * p_h + p_l * c(CP) + dp_l;
    // log2(x) = t1 + t2.
    let t1 = high_only(((z_h + z_l) + dp_h) + t);
    let t2 = z_l - (((t1 - t) - dp_h) - z_h);
    // y · log2(x) = p_h + p_l (y's low word is zero: y1 = y).
    let (y, y1) = (c(Y), high_only(c(Y)));
    let p_l = (y - y1) * t1 + y * t2;
    let mut p_h = y1 * t1;
    let z = p_l + p_h;
    // 2^(p_h + p_l) = 2^n · 2^(the rest).
    let (mut n, mut sub) = ([0i32; LANES], [0.0; LANES]);
    for l in 0..LANES {
        let j = high(z.0[l]);
        let i = j & 0x7fff_ffff;
        if i > 0x3fe0_0000 {
            let k = (i >> 20) - 0x3ff;
            let mut m = j + (0x0010_0000 >> (k + 1));
            let k = ((m & 0x7fff_ffff) >> 20) - 0x3ff;
            sub[l] = with_high(0.0, (m & !(0x000f_ffff >> k)) as u32);
            m = ((m & 0x000f_ffff) | 0x0010_0000) >> (20 - k);
            n[l] = if j < 0 { -m } else { m };
        }
    }
    // A lane that does not round subtracts +0, which leaves every number as it is.
    p_h = p_h - F64x4(sub);
    let t = high_only(p_l + p_h);
    let u = t * c(LG2_H);
    let v = (p_l - (t - p_h)) * c(LG2) + t * c(LG2_L);
    let z = u + v;
    let w = v - (z - u);
    let t = z * z;
    let t1 = z - t * (c(P1) + t * (c(P2) + t * (c(P3) + t * (c(P4) + t * c(P5)))));
    let r = (z * t1) / (t1 - c(2.0)) - (w + z * w);
    let z = c(1.0) - (r - z);
    std::array::from_fn(|l| {
        let j = high(z.0[l]).wrapping_add(n[l] << 20);
        if !inside[l] || (j >> 20) <= 0 {
            // Outside the range, or a result below the normal numbers (`scalbn`'s case).
            scalar(x[l])
        } else {
            // The sign is +1 (`s * z`).
            1.0 * with_high(z.0[l], j as u32)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::numerics::elementary::following;
    use crate::physics::numerics::lanes::tests::{next, same};

    /// Numbers of every kind: log-uniform over the whole range and over the controller's
    /// (1e−12 to 1e6), random bit patterns, the table's two boundaries and the rounding's (x
    /// near 2^±4, where |y log2 x| crosses 1/2) with random low bits, the range's ends, 1 and
    /// its neighbours, zeros, subnormals, infinities, NaN and negative numbers.
    fn draw(rng: &mut u64) -> f64 {
        let r = next(rng);
        let unit = (next(rng) >> 11) as f64 / (1u64 << 53) as f64;
        let low = next(rng) & 0xFFFF_FFFF;
        match r % 9 {
            0 => f64::from_bits(next(rng)),
            1 => 2f64.e_powf(2100.0 * unit - 1050.0),
            2 => 10f64.e_powf(18.0 * unit - 12.0),
            3 => {
                // A mantissa at one of the table's boundaries, any exponent near 0.
                let j = [0x3988E_u64, 0x3988F, 0xBB679, 0xBB67A][(r >> 8) as usize % 4];
                let e = 1023 + (r >> 16) % 41 - 20;
                f64::from_bits((e << 52) | (j << 32) | low)
            }
            4 => {
                let base: f64 = [16.0, 1.0 / 16.0, 256.0, 1.0 / 256.0, 1.0][(r >> 8) as usize % 5];
                let ulps = ((r >> 16) % 2001).cast_signed() - 1000;
                f64::from_bits(base.to_bits().wrapping_add_signed(ulps))
            }
            5 => {
                let base = [LOWEST, HIGHEST, f64::MIN_POSITIVE][(r >> 8) as usize % 3];
                let ulps = ((r >> 16) % 21).cast_signed() - 10;
                f64::from_bits(base.to_bits().wrapping_add_signed(ulps))
            }
            6 => [
                0.0,
                -0.0,
                1e-310,
                f64::INFINITY,
                f64::NAN,
                -1.0,
                -16.0,
                f64::MAX,
            ][(r >> 8) as usize % 8],
            7 => 0.43 + 0.57 * unit,
            _ => 1.0 + 168_150.0 * unit,
        }
    }

    /// Issue 84: every lane is the scalar power's bits, on 2 million generated numbers (a
    /// printed seed; `RATTLEBACK_SEED` draws others), with lanes of mixed kinds, on the
    /// portable functions and on the platform's.
    #[test]
    fn every_lane_is_the_scalar_power() {
        let seed = std::env::var("RATTLEBACK_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(8_484_125_u64);
        eprintln!("seed {seed} (RATTLEBACK_SEED)");
        let mut rng = seed;
        for round in 0..500_000 {
            let x: [f64; LANES] = std::array::from_fn(|_| draw(&mut rng));
            let lanes = eighth_power(x);
            for l in 0..LANES {
                let want = x[l].e_powf(Y);
                assert!(
                    same(lanes[l], want),
                    "seed {seed} round {round}: {:e} ({:#x}) gives {:e}, the scalar power {:e}",
                    x[l],
                    x[l].to_bits(),
                    lanes[l],
                    want
                );
            }
        }
        following(Functions::Platform, || {
            for _ in 0..10_000 {
                let x: [f64; LANES] = std::array::from_fn(|_| draw(&mut rng));
                let lanes = eighth_power(x);
                for l in 0..LANES {
                    assert!(
                        same(lanes[l], x[l].e_powf(Y)),
                        "seed {seed}: platform, {:e}",
                        x[l]
                    );
                }
            }
        });
    }
}
