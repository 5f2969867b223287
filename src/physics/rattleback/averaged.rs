//! The second-order averaged model (`averaged2`, docs/physics.md §4c; the derivation and its
//! measurements are `docs/averaging/second-order.md`): an O(k⁻²) slow model, against
//! O(1/k) for the first-order corrected limit, at the same k-independent cost.
//!
//! Canonical variables of a full state (exact): `I = (½ g γ̇² + ½ k γ²)/ω`,
//! `φ = atan2(ω γ, γ̇)`, `P = iz α̇ − I c sin 2φ`, with `ω = sqrt(k/g)`, `c = g'/(4g)`.
//! A Lie-transform normal form to fourth order in `ε = k^{−1/2}` gives the averaged
//! Hamiltonian, whose fast action `Ī` is an exact constant:
//!
//! `K̄ = Ī ω + P̄²/(2 iz) + c² Ī²/(4 iz) − c² Ī P̄²/(2 iz² ω)`.
//!
//! A run maps the start to averaged variables (the initial map, note §4.1, coefficients at
//! the physical point), integrates the slow flow of `K̄` on `(ᾱ, P̄, ψ̄ = φ̄/√k)` (ψ̄ keeps the
//! step control independent of `k`), and reconstructs `α`, `α̇` (note §4.2, coefficients at the
//! averaged point). Every series is truncated at `ε³`; dropping any term brings back an O(1/k)
//! error (note §5.4). Spin reversals are zeros of the *reconstructed* `α̇`, not of `ᾱ'`: the
//! two differ by the O(ε) ripple `Ī c sin 2φ̄ / iz`.
use crate::physics::numerics::elementary::Elementary;

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::Vector3;

use super::effective::Regime;
use super::model::{State, initial_state, transverse_energy};
use super::params::{Params, Problem};
use crate::physics::numerics::quadrature::integrate_bounded;

/// `c = g'/(4g)` and its first two derivatives in `α` (note §1).
#[derive(Clone, Copy, Debug)]
struct CFun {
    c: f64,
    c1: f64,
    c2: f64,
}

impl CFun {
    #[inline]
    fn at(p: &Params, alpha: f64) -> (f64, Self) {
        let (s2, k2) = (2.0 * alpha).e_sin_cos();
        Self::of_double_angle(p, s2, k2)
    }

    /// [`CFun::at`] given `sin 2α`, `cos 2α`.
    #[inline]
    fn of_double_angle(p: &Params, s2: f64, k2: f64) -> (f64, Self) {
        let d = p.iy - p.ix;
        // g = ix cos²α + iy sin²α = (ix + iy)/2 − (iy − ix)/2 · cos 2α.
        let g = 0.5 * (p.ix + p.iy) - 0.5 * d * k2;
        let g1 = d * s2;
        let g2 = 2.0 * d * k2;
        let g3 = -4.0 * d * s2;
        let r1 = g1 / g;
        let c = 0.25 * r1;
        let c1 = 0.25 * (g2 / g - r1 * r1);
        let c2 = 0.25 * (g3 / g - 3.0 * r1 * g2 / g + 2.0 * r1 * r1 * r1);
        (g, Self { c, c1, c2 })
    }
}

/// One start's averaged motion: the constants of the slow flow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Averaged2 {
    params: Params,
    /// The averaged fast action `Ī` (exactly conserved by the slow flow).
    ibar: f64,
    sqrt_k: f64,
}

/// An averaged state `(ᾱ, P̄, ψ̄ = φ̄/√k)`.
pub type SlowState = Vector3<f64>;

impl Averaged2 {
    /// The averaged motion of a problem's start and its averaged initial state (note §4.1).
    #[must_use]
    pub fn new(problem: &Problem) -> (Self, SlowState) {
        let p = *problem.params();
        let s = problem.start();
        let y0 = initial_state(s);
        let (g, cf) = CFun::at(&p, s.alpha);
        let omega = (p.k / g).sqrt();
        let i0 = transverse_energy(&p, &y0) / omega;
        let phi0 = (omega * s.gamma).e_atan2(s.gamma_dot);
        let (s2, k2) = (2.0 * phi0).e_sin_cos();
        let (s4, k4) = (4.0 * phi0).e_sin_cos();
        let p0 = p.iz * s.alpha_dot - i0 * cf.c * s2;
        let (c, c1, c2) = (cf.c, cf.c1, cf.c2);
        let cc = c * c;
        let u = i0 / (p.iz * omega);
        let v = p0 / (p.iz * omega);
        let ibar = i0
            * (1.0 + c * v * s2 + 0.5 * cc * v * v + (cc * u + (cc + 0.5 * c1) * v * v) * k2
                - 0.25 * cc * u * k4
                - 0.25
                    * ((14.0 * cc * c + 8.0 * c * c1) * u * v
                        + (6.0 * cc * c + 8.0 * c * c1 + c2) * v * v * v)
                    * s2
                + 0.125 * c * (5.0 * cc + c1) * u * v * s4);
        let alpha_bar = s.alpha + 0.5 * c * u * k2 - 0.5 * (2.0 * cc + c1) * u * v * s2;
        let p_bar = p0 - 0.5 * (2.0 * cc + c1) * i0 * v * k2
            + i0 * (0.25
                * ((4.0 * cc * c + 4.0 * c * c1) * u + (8.0 * cc * c + 8.0 * c * c1 + c2) * v * v)
                * s2
                - 0.125 * c * (cc + c1) * u * s4);
        let phi_bar = phi0 + 0.5 * c * v * k2
            - 0.25 * (4.0 * cc * u + (2.0 * cc + c1) * v * v) * s2
            + 0.125 * cc * (u - v * v) * s4;
        let sqrt_k = p.k.sqrt();
        (
            Self {
                params: p,
                ibar,
                sqrt_k,
            },
            SlowState::new(alpha_bar, p_bar, phi_bar / sqrt_k),
        )
    }

    /// The parameters.
    #[must_use]
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The averaged fast action `Ī`.
    #[must_use]
    pub fn ibar(&self) -> f64 {
        self.ibar
    }

    /// The averaged adiabatic constant `θ̄ = Ī √k` (the limit's `θ` to O(1/k)).
    #[must_use]
    pub fn theta_bar(&self) -> f64 {
        self.ibar * self.sqrt_k
    }

    /// The slow flow of `K̄` on `(ᾱ, P̄, ψ̄)` (note §3, Hamilton's equations).
    #[inline]
    #[must_use]
    pub fn rhs(&self, y: &SlowState) -> SlowState {
        self.rhs_turned(y, (2.0 * y[0]).e_sin_cos())
    }

    /// [`Averaged2::rhs`] given `(sin 2ᾱ, cos 2ᾱ)` (from a nearby state's, [`turned`]).
    #[inline]
    #[must_use]
    pub fn rhs_turned(&self, y: &SlowState, (s2, k2): (f64, f64)) -> SlowState {
        let p = &self.params;
        let (g, cf) = CFun::of_double_angle(p, s2, k2);
        let omega = (p.k / g).sqrt();
        let (c, c1) = (cf.c, cf.c1);
        let ib = self.ibar;
        let pb = y[1];
        let m = c * c * ib / (p.iz * omega);
        let alpha_dot = pb / p.iz * (1.0 - m);
        let p_dot = 2.0 * c * omega * ib - c * c1 * ib * ib / (2.0 * p.iz)
            + c * (c1 + c * c) * ib * pb * pb / (p.iz * p.iz * omega);
        let phi_dot =
            omega + c * c * ib / (2.0 * p.iz) - c * c * pb * pb / (2.0 * p.iz * p.iz * omega);
        SlowState::new(alpha_dot, p_dot, phi_dot / self.sqrt_k)
    }

    /// The averaged Hamiltonian `K̄(ᾱ, P̄)`, conserved exactly by the slow flow: the method's
    /// energy diagnostic.
    #[must_use]
    pub fn kbar(&self, alpha_bar: f64, p_bar: f64) -> f64 {
        let p = &self.params;
        let (g, cf) = CFun::at(p, alpha_bar);
        let omega = (p.k / g).sqrt();
        let cc_ibar = cf.c * cf.c * self.ibar;
        let potential = self.ibar * omega + cc_ibar * self.ibar / (4.0 * p.iz);
        potential + p_bar * p_bar / (2.0 * p.iz) * (1.0 - cc_ibar / (p.iz * omega))
    }

    /// The averaged potential `V̄(α) = Ī ω(α) + c² Ī² / (4 iz)` (`K̄` at `P̄ = 0`).
    #[must_use]
    pub fn potential(&self, alpha: f64) -> f64 {
        let p = &self.params;
        let (g, cf) = CFun::at(p, alpha);
        self.ibar * (p.k / g).sqrt() + cf.c * cf.c * self.ibar * self.ibar / (4.0 * p.iz)
    }

    /// `(α, α̇)` of the full motion from an averaged state (note §4.2).
    #[inline]
    #[must_use]
    pub fn reconstruct(&self, y: &SlowState) -> (f64, f64) {
        let (alpha, alpha_dot, _) = self.reconstruct_parts(y);
        (alpha, alpha_dot)
    }

    /// The reconstructed `α̇` alone (the event function of spin reversals).
    #[inline]
    #[must_use]
    pub fn spin_rate(&self, y: &SlowState) -> f64 {
        self.reconstruct_parts(y).1
    }

    fn reconstruct_parts(&self, y: &SlowState) -> (f64, f64, Fast) {
        let p = &self.params;
        let (g, cf) = CFun::at(p, y[0]);
        let omega = (p.k / g).sqrt();
        let (c, c1, c2) = (cf.c, cf.c1, cf.c2);
        let cc = c * c;
        let ib = self.ibar;
        let pb = y[1];
        let phi_bar = y[2] * self.sqrt_k;
        let (s2, k2) = (2.0 * phi_bar).e_sin_cos();
        let (s4, k4) = (4.0 * phi_bar).e_sin_cos();
        let u = ib / (p.iz * omega);
        let v = pb / (p.iz * omega);
        let alpha = y[0] - 0.5 * c * u * k2 + 0.5 * (2.0 * cc + c1) * u * v * s2;
        let p_alpha = pb + ib * c * s2 + ib * v * (0.5 * (2.0 * cc + c1) * k2 - cc)
            - ib * (0.25
                * ((5.0 * cc * c + 4.0 * c * c1) * u + (6.0 * cc * c + 8.0 * c * c1 + c2) * v * v)
                * s2
                - 0.125 * c * (5.0 * cc - c1) * u * s4);
        let fast = Fast {
            action: ib
                * (1.0 - c * v * s2 + 0.5 * cc * v * v - (cc * u + (cc + 0.5 * c1) * v * v) * k2
                    + 0.25 * cc * u * k4),
            phase: phi_bar - 0.5 * c * v * k2
                + 0.25 * (4.0 * cc * u + (2.0 * cc + c1) * v * v) * s2
                - 0.125 * cc * (u + v * v) * s4,
        };
        (alpha, p_alpha / p.iz, fast)
    }

    /// A full-model-shaped state `(γ, α, γ̇, α̇)` from an averaged state: `α`, `α̇` as
    /// [`Averaged2::reconstruct`], the fast variables to relative O(ε³) (note §4.2).
    #[must_use]
    pub fn to_full_state(&self, y: &SlowState) -> State {
        let (alpha, alpha_dot, fast) = self.reconstruct_parts(y);
        full_state(&self.params, alpha, alpha_dot, fast.action, fast.phase)
    }

    /// `V̄_max = Ī √(k / min(ix, iy))` (the `c²` term vanishes where `g' = 0`).
    #[must_use]
    pub fn potential_max(&self) -> f64 {
        potential_max(&self.params, self.ibar)
    }

    /// The regime of the averaged motion started at `y0`: trapped when `K̄ < V̄_max`.
    #[must_use]
    pub fn regime(&self, y0: &SlowState) -> Regime {
        #[allow(clippy::float_cmp)]
        if self.params.ix == self.params.iy || self.ibar == 0.0 {
            return Regime::Uniform;
        }
        Regime::of_energy(self.kbar(y0[0], y0[1]), self.potential_max())
    }

    /// The averaged time between turning points of a trapped start,
    /// `∫ dα [ (2/iz)(K̄ − V̄)(1 − c² Ī/(iz ω)) ]^{−1/2}` between `V̄(α±) = K̄` (note §4.3),
    /// by adaptive Gauss–Legendre after `α = centre + α* sin φ`. `None` unless trapped, and
    /// `None` when the bounded quadrature cannot reach [`HALF_PERIOD_ACCURACY`] (a swing so small
    /// at so large a k that `K̄ − V̄` is rounding noise).
    #[must_use]
    pub fn half_period(&self, y0: &SlowState) -> Option<f64> {
        if self.regime(y0) != Regime::Trapped {
            return None;
        }
        let p = &self.params;
        let k_bar = self.kbar(y0[0], y0[1]);
        let minimum = if p.ix > p.iy { 0.0 } else { FRAC_PI_2 };
        let centre = minimum + PI * ((y0[0] - minimum) / PI).round();
        // V̄ rises from the centre to the maximum a quarter turn away: bisect V̄ = K̄.
        let (mut lo, mut hi) = (0.0_f64, FRAC_PI_2);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.potential(centre + mid) < k_bar {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= f64::EPSILON * hi {
                break;
            }
        }
        let half_width = lo;
        if half_width <= 0.0 {
            return None;
        }
        let mut integrand = |phi: f64| {
            let alpha = centre + half_width * phi.e_sin();
            let (g, cf) = CFun::at(p, alpha);
            let omega = (p.k / g).sqrt();
            let m = cf.c * cf.c * self.ibar / (p.iz * omega);
            let rate_sq = 2.0 / p.iz * (k_bar - self.potential(alpha)).max(0.0) * (1.0 - m);
            if rate_sq > 0.0 {
                half_width * phi.e_cos() / rate_sq.sqrt()
            } else {
                0.0
            }
        };
        // Bounded work (issue 29): where K̄ − V̄ is rounding noise (a small swing at very large k)
        // bisection cannot converge; the cap stops it and an inaccurate value is not reported.
        integrate_bounded(-FRAC_PI_2, FRAC_PI_2, 1e-12, &mut integrand).within(HALF_PERIOD_ACCURACY)
    }
}

/// Relative accuracy below which the averaged half period is reported as `null` (not trapped
/// is the other reason): the quadrature met its 1e-12 almost everywhere else.
pub const HALF_PERIOD_ACCURACY: f64 = 1e-6;

/// Largest [`expansion_parameter`] for which `averaged2` runs at all (its error at 0.2 is
/// already 1e-3 … 1e-5 on the note's starts, k = 1e2; past 0.5 the slow motion is not slow).
pub const VALIDITY_LIMIT: f64 = 0.5;

/// `(sin 2α, cos 2α)` from `(sin 2α₀, cos 2α₀)` = `near` for `α` within 5e-3 of `α₀`, by
/// turning through `2(α − α₀)` with its Taylor series (exact to rounding there): a nudged copy
/// beside its start ([`crate::physics::rattleback::integrators::together`]) then needs no
/// trigonometric function of its own, and the rounding of the start's `sin`, `cos` cancels from
/// their difference. Farther away, `sin_cos` itself.
#[inline]
#[must_use]
pub fn turned(near: (f64, f64), alpha0: f64, alpha: f64) -> (f64, f64) {
    let d = 2.0 * (alpha - alpha0);
    if d.abs() > 1e-2 {
        return (2.0 * alpha).e_sin_cos();
    }
    let d2 = d * d;
    let sd = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0)));
    let cd = 1.0 - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0));
    let (s0, c0) = near;
    (s0 * cd + c0 * sd, c0 * cd - s0 * sd)
}

/// `V̄_max = Ī √(k / min(ix, iy))` of an averaged model with fast action `ibar` (either order).
#[must_use]
pub fn potential_max(p: &Params, ibar: f64) -> f64 {
    ibar * (p.k / p.ix.min(p.iy)).sqrt()
}

/// The full-model state `(γ, α, γ̇, α̇)` of a reconstructed `(α, α̇)` with the fast motion's
/// action and phase (a negative action, a rounding artefact, counts as none).
#[must_use]
pub fn full_state(p: &Params, alpha: f64, alpha_dot: f64, action: f64, phase: f64) -> State {
    let g = p.g(alpha);
    let omega = (p.k / g).sqrt();
    let (s, c) = phase.e_sin_cos();
    let action = action.max(0.0);
    State::new(
        (2.0 * action / (g * omega)).sqrt() * s,
        alpha,
        (2.0 * action * omega / g).sqrt() * c,
        alpha_dot,
    )
}

/// The largest of the averaging's small parameters for a start (note §4.3, "Validity"):
/// `v = |α̇|max (1 + c_max) / ω_min`, the spin against the slowest fast frequency, and
/// `u (1 + c'_max + 2 c²_max)` with `u = θ √g_max / (iz k)`, whose square root is the slow
/// oscillation's frequency against the fast one. Zero where the model is exact (`ix = iy`, or
/// no fast action).
#[must_use]
pub fn expansion_parameter(problem: &Problem) -> f64 {
    let p = problem.params();
    let eff = super::effective::Effective::new(problem);
    let spin = eff.spin_scale();
    let (g_min, g_max) = (p.ix.min(p.iy), p.ix.max(p.iy));
    let d = (p.iy - p.ix).abs();
    if d == 0.0 || eff.theta() == 0.0 {
        // c ≡ 0 or no fast action: every correction vanishes and the averaged model is the
        // exact motion (uniform spin, harmonic tilt), whatever k.
        return 0.0;
    }
    let c_max = d / (4.0 * g_min);
    // |c'| ≤ (|g''|/g + (g'/g)²)/4 ≤ (2d/g_min + (d/g_min)²)/4.
    let c1_max = (2.0 * d / g_min + (d / g_min).powi(2)) / 4.0;
    let omega_min = (p.k / g_max).sqrt();
    let v = spin * (1.0 + c_max) / omega_min;
    let u = eff.theta() * g_max.sqrt() / (p.iz * p.k);
    v.max(u * (1.0 + c1_max + 2.0 * c_max * c_max))
}

/// The reconstructed fast action and phase.
#[derive(Clone, Copy, Debug)]
struct Fast {
    action: f64,
    phase: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn problem(k: f64, gamma: f64, alpha: f64, gamma_dot: f64, alpha_dot: f64) -> Problem {
        crate::physics::rattleback::params::paper_body(k, [gamma, alpha, gamma_dot, alpha_dot])
    }

    /// Note §4.2: the reconstruction composed with the initial map is the identity to O(ε⁴)
    /// in `α`, `α̇` (their 200 random states: 4e-9 → 5e-13 in α, 2e-8 → 5e-12 in α̇ for
    /// k = 1e4 → 1e6). A transcription error in either map is O(ε) or O(ε²) and fails this.
    #[test]
    fn reconstruction_inverts_the_initial_map_to_fourth_order() {
        for k in [1e4, 1e6] {
            let worst = crate::physics::rattleback::params::worst_round_trip(k, |pr| {
                let (m, y0) = Averaged2::new(pr);
                m.reconstruct(&y0)
            });
            let bound = if k < 1e5 { 1e-7 } else { 1e-10 };
            assert!(worst < bound, "k = {k:e}: round trip off by {worst:e}");
        }
    }

    #[test]
    fn turning_a_nearby_angle_is_its_sine_and_cosine() {
        // Within 5e-3 the series turns the start's pair to within a few ulps of `sin_cos`; at
        // the start itself it returns the pair bit for bit (the start's own flow is unchanged
        // beside its copies); farther away it is `sin_cos`.
        for alpha0 in [
            -7.3,
            -0.4,
            0.0,
            1e-12,
            std::f64::consts::FRAC_PI_4,
            2.9,
            41.0,
        ] {
            let near = (2.0_f64 * alpha0).e_sin_cos();
            assert_eq!(super::turned(near, alpha0, alpha0), near);
            for d in [-5e-3, -1e-4, -3e-9, 1e-13, 2e-7, 4.9e-3, 6e-3, 0.3] {
                let alpha = alpha0 + d;
                let (s, c) = super::turned(near, alpha0, alpha);
                let (s_ref, c_ref) = (2.0 * alpha).e_sin_cos();
                assert!(
                    (s - s_ref).abs() <= 4e-16 && (c - c_ref).abs() <= 4e-16,
                    "α0 {alpha0}, d {d}: ({s}, {c}) against ({s_ref}, {c_ref})"
                );
            }
        }
    }

    #[test]
    #[allow(clippy::float_cmp)]
    fn uniform_rotation_is_exact() {
        let pr = problem(1e6, 0.0, 0.3, 0.0, 0.7);
        let (m, y0) = Averaged2::new(&pr);
        assert_eq!(m.ibar(), 0.0);
        assert_eq!(y0[0], 0.3);
        assert_eq!(m.reconstruct(&y0), (0.3, 0.7));
        assert_eq!(m.regime(&y0), Regime::Uniform);
    }

    #[test]
    fn regime_follows_the_papers_threshold_at_large_k() {
        let (m, y0) = Averaged2::new(&problem(1e8, 0.0, 0.0, 1.0, 0.5));
        assert_eq!(m.regime(&y0), Regime::Trapped);
        let eff = crate::physics::rattleback::effective::Effective::new(&problem(
            1e8, 0.0, 0.0, 1.0, 0.5,
        ));
        let (a, b) = (m.half_period(&y0).unwrap(), eff.half_period().unwrap());
        assert!((a - b).abs() < 1e-5 * b, "{a} vs {b}");
        let (m, y0) = Averaged2::new(&problem(1e8, 0.0, 0.0, 1.0, 1.2));
        assert_eq!(m.regime(&y0), Regime::Rotating);
    }
}
