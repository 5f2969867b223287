//! `averaged2` for the pendulum: the averaged equation to O(ε²) and the ripple to O(ε⁴), so
//! that the slow motion lifted back to the full one is within O(ε⁴) of it (the limit with its
//! first ripple, `effective-corrected`, is within O(ε²)).
//!
//! **The expansion** (as [`super::limit`]'s, carried two orders further): with `τ = t/ε`,
//! `θ = Θ + Σₙ εⁿ ξₙ(Θ, Θ̇, τ)` with every `ξₙ` of zero mean in `τ`, and
//! `Θ̈ = F0(Θ) + ε F1 + ε² F2(Θ, Θ̇) + …`. Putting both in `θ̈ = (a + (b/ε) cos τ) sin θ` and
//! collecting powers of `ε`: at each order the `τ`-mean fixes `Fₘ` and the rest fixes
//! `∂²ξₘ₊₂/∂τ²`. It gives `F0 = a sin Θ − (b²/4) sin 2Θ` (the limit), `F1 = 0`, and
//!
//! ```text
//!     F2 = b² [ −(3/2) Θ̇² sin Θ cos Θ + 2a sin Θ cos² Θ − (a/4) sin³ Θ
//!              + (9b²/32) sin³ Θ cos Θ − (25b²/32) sin Θ cos³ Θ ]
//! ```
//!
//! with `ξ1 … ξ4` (harmonics of `τ` up to the fourth) in [`to_full`]. The derivation is
//! `scripts/kapitza_averaged.py` (sympy; it writes the code below, about six minutes); the
//! first two orders agree with the hand derivation in `limit`.
//!
//! **Accuracy**, against resolved DOP853 at 1e-13: `tests/it/kapitza.rs`
//! (`the_second_order_averaged_model_is_fourth_order`) measures the error fall like ε⁴.
use crate::physics::numerics::elementary::Elementary;

use super::averaged3_terms;
use super::{FastPhase, Params};

/// `F2(Θ, Θ̇)`: the averaged equation's `ε²` term (`Θ̈ = F0 + ε² F2`).
#[must_use]
#[inline]
pub fn f2(params: &Params, theta_s: f64, p: f64) -> f64 {
    let (st, ct) = theta_s.e_sin_cos();
    f2_of(params, st, ct, p)
}

/// [`f2`] from `sin Θ`, `cos Θ`.
#[inline]
fn f2_of(params: &Params, st: f64, ct: f64, p: f64) -> f64 {
    let (a, b) = (params.a, params.b);
    let x0 = st.powi(3);
    let x1 = b.powi(2);
    let x2 = b.powi(4);
    -3.0 / 2.0 * ct * st * x1 * p.powi(2) + 2.0 * a * ct.powi(2) * st * x1
        - 1.0 / 4.0 * a * x0 * x1
        - 25.0 / 32.0 * st * x2 * ct.powi(3)
        + (9.0 / 32.0) * ct * x0 * x2
}

/// The full state `(θ, θ̇)` of the averaged state `(Θ, Θ̇)` at time `t`: `θ` to O(ε⁴), `θ̇` to
/// O(ε³) inclusive (generated; see the module's documentation).
#[must_use]
#[allow(clippy::unreadable_literal)]
pub fn to_full(params: &Params, phase: FastPhase, t: f64, slow: (f64, f64)) -> (f64, f64) {
    let (theta_s, p) = slow;
    let (a, b, epsilon) = (params.a, params.b, params.epsilon);
    let (st, ct) = theta_s.e_sin_cos();
    let [(s1, c1), (s2, c2), (s3, c3), (s4, c4)] = phase.harmonics(t, epsilon);
    let x0 = b * st;
    let x1 = c1 * x0;
    let x2 = epsilon.powi(2);
    let x3 = b * ct;
    let x4 = p * s1;
    let x5 = b.powi(2);
    let x6 = (1.0 / 8.0) * x5;
    let x7 = c2 * ct;
    let x8 = st * x7;
    let x9 = epsilon.powi(3);
    let x10 = p.powi(2);
    let x11 = b.powi(3);
    let x12 = st.powi(3);
    let x13 = ct.powi(2);
    let x14 = x13 * x5;
    let x15 = st.powi(2);
    let x16 = st * x13;
    let x17 = x11 * x16;
    let x18 = p.powi(3) * x3;
    let x19 = a * b;
    let x20 = x19 * x4;
    let x21 = ct.powi(3);
    let x22 = x11 * x21;
    let x23 = p * x22;
    let x24 = a * x5;
    let x25 = x12 * x24;
    let x26 = b.powi(4);
    let x27 = x12 * x26;
    let x28 = st * x21 * x26;
    let x29 = ct * x27;
    let x30 = ct * x11 * x15;
    let x31 = p * x30;
    let x32 = x16 * x24;
    let x33 = s1 * x0;
    let x34 = p * c1;
    let x35 = ct * s2 * st * x5;
    let x36 = x11 * x12;
    let x37 = p * c2;
    let x38 = 4.0 * x19 * x34;
    let theta = theta_s
        + epsilon.powi(4)
            * ((5.0 / 32.0) * c2 * x25 + (53.0 / 144.0) * c2 * x28 - 7.0 / 8.0 * c2 * x32
                + (1.0 / 4608.0) * c4 * x28
                - 17.0 / 4608.0 * c4 * x29
                + 4.0 * s1 * x18
                + (11.0 / 432.0) * s3 * x23
                - 43.0 / 432.0 * s3 * x31
                + (5.0 / 4.0) * x10 * x5 * x8
                - 8.0 * x13 * x20
                + 14.0 * x15 * x20
                + (37.0 / 16.0) * x22 * x4
                - 19.0 / 144.0 * x27 * x7
                - 177.0 / 16.0 * x30 * x4)
        - epsilon * x1
        + x2 * (2.0 * x3 * x4 + x6 * x8)
        + x9 * (-3.0 / 8.0 * p * s2 * x14
            + (1.0 / 8.0) * p * s2 * x15 * x5
            + 4.0 * a * b * c1 * ct * st
            + (3.0 / 8.0) * c1 * x11 * x12
            - 25.0 / 16.0 * c1 * x17
            + (1.0 / 72.0) * c3 * x11 * x12
            - 1.0 / 144.0 * c3 * x17
            - 3.0 * x1 * x10);
    let theta_dot = p
        + epsilon * (x3 * x34 - 1.0 / 4.0 * x35)
        + x2 * (-2.0 * a * ct * x33 + (9.0 / 16.0) * s1 * x17 - 3.0 / 8.0 * s1 * x36
            + (1.0 / 48.0) * s3 * x17
            - 1.0 / 24.0 * s3 * x36
            + x10 * x33
            - 5.0 / 8.0 * x14 * x37
            + x15 * x37 * x6)
        + x33
        + x9 * (c1 * x18 + (5.0 / 72.0) * c3 * x23
            - 35.0 / 144.0 * c3 * x31
            - 3.0 / 16.0 * s2 * x25
            - 79.0 / 144.0 * s2 * x28
            + (29.0 / 144.0) * s2 * x29
            + (11.0 / 8.0) * s2 * x32
            - 1.0 / 1152.0 * s4 * x28
            + (17.0 / 1152.0) * s4 * x29
            - 3.0 / 2.0 * x10 * x35
            - x13 * x38
            + x15 * x38
            + (3.0 / 4.0) * x22 * x34
            - 61.0 / 16.0 * x30 * x34);
    (theta, theta_dot)
}

/// The averaged state `(Θ, Θ̇)` of a full state at time `t`: [`to_full`] inverted by
/// Gauss–Seidel iteration (the angle from the angle's residual, then the rate from the rate's),
/// which contracts when `ε b` is small; at most 50 rounds, stopping when a round changes
/// nothing.
#[must_use]
pub fn to_slow(params: &Params, phase: FastPhase, t: f64, full: (f64, f64)) -> (f64, f64) {
    let first = super::limit::to_slow(params, phase, t, full);
    invert(|slow| to_full(params, phase, t, slow), full, first)
}

/// The `slow` state that `lift` takes to `full`, by Gauss–Seidel iteration from `slow`.
fn invert(
    lift: impl Fn((f64, f64)) -> (f64, f64),
    full: (f64, f64),
    mut slow: (f64, f64),
) -> (f64, f64) {
    for _ in 0..50 {
        let before = slow;
        slow.0 += full.0 - lift(slow).0;
        slow.1 += full.1 - lift(slow).1;
        if slow == before {
            break;
        }
    }
    slow
}

/// `(F2, F4)(Θ, Θ̇)`: the `ε²` and `ε⁴` terms of `averaged3`'s equation
/// `Θ̈ = F0 + ε² F2 + ε⁴ F4`, from one `sin_cos` (`F4` is generated by
/// `scripts/kapitza_averaged3.py`, which carries this module's expansion two orders further
/// with an exact polynomial algebra of its own).
#[must_use]
#[inline]
pub fn f2_f4(params: &Params, theta_s: f64, p: f64) -> (f64, f64) {
    let (st, ct) = theta_s.e_sin_cos();
    (
        f2_of(params, st, ct, p),
        averaged3_terms::f4(params.a, params.b, st, ct, p),
    )
}

/// `averaged3`'s lift: the full state `(θ, θ̇)` of the averaged state `(Θ, Θ̇)` at time `t`,
/// `θ` to O(ε⁶) and `θ̇` to O(ε⁵) inclusive.
#[must_use]
pub fn to_full3(params: &Params, phase: FastPhase, t: f64, slow: (f64, f64)) -> (f64, f64) {
    let (theta_s, p) = slow;
    let (st, ct) = theta_s.e_sin_cos();
    averaged3_terms::lift(
        params.a,
        params.b,
        params.epsilon,
        theta_s,
        st,
        ct,
        p,
        &phase.harmonics(t, params.epsilon),
    )
}

/// The averaged state of `averaged3` of a full state at time `t`: [`to_full3`] inverted as
/// [`to_slow`] inverts [`to_full`], starting from `averaged2`'s.
#[must_use]
pub fn to_slow3(params: &Params, phase: FastPhase, t: f64, full: (f64, f64)) -> (f64, f64) {
    invert(
        |slow| to_full3(params, phase, t, slow),
        full,
        to_slow(params, phase, t, full),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lift or its inverse.
    type Map = fn(&Params, FastPhase, f64, (f64, f64)) -> (f64, f64);

    /// Exactly (to rounding), unlike `limit::to_slow`, which inverts its ripple to its order:
    /// over a grid of phases, angles and rates, for both orders and both rules of the phase.
    #[test]
    fn to_slow_inverts_to_full_to_rounding() {
        let p = Params {
            a: 1.0,
            b: 2.0,
            epsilon: 0.01,
        };
        let pairs: [(Map, Map); 2] = [(to_full, to_slow), (to_full3, to_slow3)];
        for (lift, invert) in pairs {
            for i in 0..7 {
                let t = 0.0137 * f64::from(i);
                for j in -3..=3 {
                    let slow = (0.9 * f64::from(j), 0.4 * f64::from(3 - i));
                    for phase in [FastPhase::Exact, FastPhase::Rounded] {
                        let back = invert(&p, phase, t, lift(&p, phase, t, slow));
                        assert!((back.0 - slow.0).abs() < 1e-14, "{slow:?} {back:?}");
                        assert!((back.1 - slow.1).abs() < 1e-13, "{slow:?} {back:?}");
                    }
                }
            }
        }
    }

    /// Each lift agrees with the one below to the lower one's order: `averaged2`'s with
    /// `limit::to_full` to O(ε³) in θ and O(ε²) in θ̇; `averaged3`'s with `averaged2`'s to O(ε⁵)
    /// and O(ε⁴), as the terms it adds are ε⁵ ξ5 + ε⁶ ξ6 (measured: up to 330 ε⁵ and 140 ε⁴ on
    /// these points), and they are there.
    #[test]
    fn each_order_extends_the_one_below() {
        let orders: [(Map, Map, f64, i32); 2] = [
            (to_full, super::super::limit::to_full, 200.0, 3),
            (to_full3, to_full, 1e3, 5),
        ];
        for (upper, lower, c, n) in orders {
            for e in [1e-2, 1e-3] {
                let p = Params {
                    a: 1.0,
                    b: 2.0,
                    epsilon: e,
                };
                for (t, th, thd) in [(0.0, 0.3, 0.0), (0.123, -1.2, 0.7), (5.0, 2.9, -1.5)] {
                    let phase = FastPhase::default();
                    let (x, y) = (
                        upper(&p, phase, t, (th, thd)),
                        lower(&p, phase, t, (th, thd)),
                    );
                    assert!((x.0 - y.0).abs() < c * e.powi(n), "{e}: {x:?} {y:?}");
                    assert!((x.1 - y.1).abs() < c * e.powi(n - 1), "{e}: {x:?} {y:?}");
                    if e >= 1e-2 && t > 0.0 {
                        assert!((x.0 - y.0).abs() > 1e-3 * e.powi(n), "{n}: {e} {t}");
                    }
                }
            }
        }
        // F4 is not zero.
        let p = Params {
            a: 1.0,
            b: 2.0,
            epsilon: 1e-2,
        };
        assert!(f2_f4(&p, 0.7, 0.4).1.abs() > 1.0);
    }
}
