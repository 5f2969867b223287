//! The limit `ε → 0`: `θ̈ = a sin θ − (b²/4) sin 2θ`, its energy, equilibria and separatrix, and
//! the first-order ripple that takes the averaged motion `(Θ, Θ̇)` to the full one.
//!
//! **The ripple.** With `τ = t/ε`, write `θ = Θ + ε ξ1(Θ, τ) + ε² ξ2(Θ, Θ̇, τ)`. The O(1/ε)
//! terms of the full equation give `∂²ξ1/∂τ² = b cos τ sin Θ`, so `ξ1 = −b cos τ sin Θ`. At O(1)
//! the equation reads `Θ̈ + 2 b sin τ cos Θ Θ̇ + ∂²ξ2/∂τ² = a sin Θ − b² cos² τ sin Θ cos Θ`: its
//! average is the limit (`−(b²/2) sin Θ cos Θ = −(b²/4) sin 2Θ`, the shaking's extra force), its
//! oscillating rest gives `ξ2 = (b²/16) cos 2τ sin 2Θ + 2 b sin τ cos Θ Θ̇`. So
//!
//! ```text
//!     θ  = Θ − ε b cos τ sin Θ + ε² [(b²/16) cos 2τ sin 2Θ + 2 b sin τ cos Θ Θ̇]
//!     θ̇  = Θ̇ + b sin τ sin Θ + ε [b cos τ cos Θ Θ̇ − (b²/8) sin 2τ sin 2Θ]
//! ```
//!
//! (the issue's `θ ≈ Θ − ε b cos τ sin Θ`, `θ̇ ≈ Θ̇ + b sin τ sin Θ`, with the next terms: without
//! the O(ε) terms of `θ̇`, the velocity would be only O(ε)-accurate). The averaged equation has no
//! O(ε) term (the forcing is even in `τ`), so the limit started from the averaged start (the
//! inverse map at `τ = 0`) is within O(ε²) of the full motion in `θ` and `θ̇` once the ripple is
//! added back; started from `θ0` itself it is within O(ε). `tests/it/kapitza.rs` measures both
//! orders against the Taylor-series references.
use crate::physics::numerics::elementary::Elementary;

use std::f64::consts::PI;

use super::{FastPhase, Params};

/// The limit of one pendulum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    a: f64,
    b: f64,
}

/// An equilibrium of the limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equilibrium {
    /// Where, in `[0, π]` (the potential is even, so `−θ` is one too).
    pub theta: f64,
    /// Whether it is a minimum of the potential (stable).
    pub stable: bool,
}

impl Limit {
    /// The limit of `params` (it does not depend on `ε`).
    #[must_use]
    pub fn new(params: &Params) -> Self {
        Self {
            a: params.a,
            b: params.b,
        }
    }

    /// `V(θ) = a cos θ − (b²/8) cos 2θ`.
    #[must_use]
    #[inline]
    pub fn potential(&self, theta: f64) -> f64 {
        self.a * theta.e_cos() - self.b * self.b / 8.0 * (2.0 * theta).e_cos()
    }

    /// `θ̈ = −V'(θ) = a sin θ − (b²/4) sin 2θ`.
    #[must_use]
    #[inline]
    pub fn acceleration(&self, theta: f64) -> f64 {
        self.a * theta.e_sin() - self.b * self.b / 4.0 * (2.0 * theta).e_sin()
    }

    /// `E_eff = ½ θ̇² + V(θ)`.
    #[must_use]
    #[inline]
    pub fn energy_of(&self, theta: f64, theta_dot: f64) -> f64 {
        0.5 * theta_dot * theta_dot + self.potential(theta)
    }

    /// The equilibria in `[0, π]`: the upright, the hanging position, and the tilted pair
    /// `cos θ* = 2a/b²` when `b² > 2|a|`.
    #[must_use]
    pub fn equilibria(&self) -> Vec<Equilibrium> {
        let b2 = self.b * self.b;
        // V''(θ) = −a cos θ + (b²/2) cos 2θ.
        let curvature = |t: f64| -self.a * t.e_cos() + b2 / 2.0 * (2.0 * t).e_cos();
        let mut out = vec![Equilibrium {
            theta: 0.0,
            stable: curvature(0.0) > 0.0,
        }];
        if b2 > 0.0 && (2.0 * self.a / b2).abs() < 1.0 {
            let t = (2.0 * self.a / b2).e_acos();
            out.push(Equilibrium {
                theta: t,
                stable: curvature(t) > 0.0,
            });
        }
        out.push(Equilibrium {
            theta: PI,
            stable: curvature(PI) > 0.0,
        });
        out
    }

    /// Highest equilibrium energy: the separatrix's level.
    #[must_use]
    pub fn potential_max(&self) -> f64 {
        self.equilibria()
            .iter()
            .map(|e| self.potential(e.theta))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Lowest potential.
    #[must_use]
    pub fn potential_min(&self) -> f64 {
        self.equilibria()
            .iter()
            .map(|e| self.potential(e.theta))
            .fold(f64::INFINITY, f64::min)
    }

    /// The energy levels of the separatrices: every unstable equilibrium's potential.
    #[must_use]
    pub fn separatrices(&self) -> Vec<f64> {
        self.equilibria()
            .iter()
            .filter(|e| !e.stable)
            .map(|e| self.potential(e.theta))
            .collect()
    }

    /// Angular frequency of small oscillations about the upright, when it is stable:
    /// `sqrt(b²/2 − a)`.
    #[must_use]
    pub fn upright_frequency(&self) -> Option<f64> {
        let w2 = self.b * self.b / 2.0 - self.a;
        (w2 > 0.0).then(|| w2.sqrt())
    }
}

/// The full state `(θ, θ̇)` of the averaged state `(Θ, Θ̇)` at time `t` (the ripple above),
/// the fast phase taken as `phase` says.
#[must_use]
#[inline]
pub fn to_full(p: &Params, phase: FastPhase, t: f64, slow: (f64, f64)) -> (f64, f64) {
    let (theta, theta_dot) = slow;
    let (e, b) = (p.epsilon, p.b);
    let [(s, c), (s2, c2)] = phase.harmonics(t, p.epsilon);
    let (st, ct) = theta.e_sin_cos();
    let sin2 = 2.0 * st * ct;
    let xi2 = b * b / 16.0 * c2 * sin2 + 2.0 * b * s * ct * theta_dot;
    (
        theta - e * b * c * st + e * e * xi2,
        theta_dot + b * s * st + e * (b * c * ct * theta_dot - b * b / 8.0 * s2 * sin2),
    )
}

/// The averaged state `(Θ, Θ̇)` of a full state at time `t`: the inverse of [`to_full`] to the
/// same order, by fixed-point iteration (a contraction when `ε b < 1`).
#[must_use]
#[inline]
pub fn to_slow(p: &Params, phase: FastPhase, t: f64, full: (f64, f64)) -> (f64, f64) {
    let (theta, theta_dot) = full;
    let (e, b) = (p.epsilon, p.b);
    let [(s, c), (s2, c2)] = phase.harmonics(t, p.epsilon);
    let mut slow = (theta, theta_dot - b * s * theta.e_sin());
    for _ in 0..3 {
        let (st, ct) = slow.0.e_sin_cos();
        let sin2 = 2.0 * st * ct;
        let xi2 = b * b / 16.0 * c2 * sin2 + 2.0 * b * s * ct * slow.1;
        let angle = theta + e * b * c * st - e * e * xi2;
        let rate = (theta_dot - b * s * st + e * b * b / 8.0 * s2 * sin2) / (1.0 + e * b * c * ct);
        slow = (angle, rate);
    }
    slow
}

/// The pendulum's limit as the phase portrait draws it (`m = 1`, period 2π).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlowView {
    /// The limit.
    pub limit: Limit,
    /// `E_eff` of the averaged start.
    pub energy: f64,
    /// The start's rate.
    pub q_dot0: f64,
    /// The fast time scale.
    pub epsilon: f64,
}

impl crate::physics::scene::SlowLimit for SlowView {
    fn mass(&self) -> f64 {
        1.0
    }
    fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI
    }
    /// The upright.
    fn wrap_centre(&self) -> f64 {
        0.0
    }
    /// `2π ε`: the explorer's samples could miss it.
    fn fast_period(&self) -> Option<f64> {
        Some(2.0 * std::f64::consts::PI * self.epsilon)
    }
    fn potential(&self, q: f64) -> f64 {
        self.limit.potential(q)
    }
    fn potential_max(&self) -> f64 {
        self.limit.potential_max()
    }
    fn potential_min(&self) -> f64 {
        self.limit.potential_min()
    }
    fn separatrices(&self) -> Vec<f64> {
        self.limit.separatrices()
    }
    fn energy(&self) -> f64 {
        self.energy
    }
    fn rate_hint(&self) -> f64 {
        self.q_dot0.abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(a: f64, b: f64) -> Params {
        Params {
            a,
            b,
            epsilon: 1e-3,
        }
    }

    #[test]
    fn acceleration_is_minus_the_potentials_slope() {
        let l = Limit::new(&params(0.8, 1.9));
        for i in 0..20 {
            let t = -3.0 + 0.31 * f64::from(i);
            let h = 1e-6;
            let slope = (l.potential(t + h) - l.potential(t - h)) / (2.0 * h);
            assert!((l.acceleration(t) + slope).abs() < 1e-8, "at {t}");
        }
    }

    #[test]
    fn the_upright_is_stable_exactly_above_the_threshold() {
        for (b, stable) in [(2.0, true), (1.5, true), (1.4, false), (0.0, false)] {
            let p = params(1.0, b);
            let l = Limit::new(&p);
            assert_eq!(p.stable_upright(), stable, "b = {b}");
            assert_eq!(l.equilibria()[0].stable, stable, "b = {b}");
            assert_eq!(l.upright_frequency().is_some(), stable);
            for e in l.equilibria() {
                assert!(l.acceleration(e.theta).abs() < 1e-12);
            }
        }
        // b² = 4a: the tilted equilibrium at cos θ* = 1/2 is a maximum, the separatrix level.
        let l = Limit::new(&params(1.0, 2.0));
        let tilted = l.equilibria()[1];
        assert!((tilted.theta - PI / 3.0).abs() < 1e-12 && !tilted.stable);
        assert_eq!(l.separatrices(), vec![l.potential(PI / 3.0)]);
        assert!((l.potential_max() - l.potential(PI / 3.0)).abs() < 1e-15);
    }

    #[test]
    fn to_slow_inverts_to_full() {
        let p = Params {
            a: 1.0,
            b: 2.0,
            epsilon: 0.01,
        };
        for (t, th, thd) in [(0.0, 0.3, 0.0), (0.123, -1.2, 0.7), (5.0, 2.9, -1.5)] {
            let phase = FastPhase::default();
            let back = to_slow(&p, phase, t, to_full(&p, phase, t, (th, thd)));
            // The inverse holds to the order kept: (εb)² = 4e-4.
            assert!((back.0 - th).abs() < 4e-4, "{back:?}");
            assert!((back.1 - thd).abs() < 4e-4 * 5.0, "{back:?}");
        }
    }
}
