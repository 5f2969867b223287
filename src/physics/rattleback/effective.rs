//! The effective model (`k → ∞`, docs/physics.md §2–3): the adiabatic constant `theta`, the
//! effective potential and energy, the regime of a start, turning points, the half period and
//! the limit's spin-reversal times by quadrature, and the tapping acceleration.
//!
//! Symbols follow the paper: `V(α) = θ g(α)^{−1/2}`, `E_eff = ½ iz α̇² + V(α)`.
use crate::physics::numerics::elementary::Elementary;

use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, PI};

use super::model::{State, initial_state, transverse_energy};
use super::params::{Params, Problem};

/// The most reversal times a run keeps (its count goes on: a long run at a stiff spring
/// reverses billions of times).
pub const MAX_REVERSAL_TIMES: usize = 1_000_000;
/// The most reversals the limit counts (below 2^53, where every count is a float exactly):
/// more saturate.
pub const MAX_REVERSALS: f64 = 9e15;
use crate::physics::numerics::quadrature::integrate_adaptive;

/// Relative closeness of `E_eff` to `V_max` under which a start counts as on the separatrix.
pub const SEPARATRIX_RELATIVE_BAND: f64 = 1e-13;

/// Relative accuracy requested from the quadratures.
const QUADRATURE_TOLERANCE: f64 = 1e-13;

/// The kind of effective motion a start leads to (docs/physics.md §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Regime {
    /// `ix = iy` or no fast energy (`θ = 0`): `V` is constant and the spin is uniform.
    Uniform,
    /// `E_eff < V_max`: `α` swings between two turning points; one reversal per half period.
    Trapped,
    /// `E_eff > V_max`: `α` is monotone; no reversal.
    Rotating,
    /// `E_eff = V_max`: the motion approaches the potential maximum in infinite time.
    Separatrix,
}

impl Regime {
    /// The regime of a (non-uniform) motion of slow energy `energy` in a potential whose
    /// maximum is `potential_max`: trapped below it, rotating above, the separatrix within
    /// [`SEPARATRIX_RELATIVE_BAND`]. Shared by the limit and the averaged model.
    #[must_use]
    pub fn of_energy(energy: f64, potential_max: f64) -> Self {
        let gap = energy - potential_max;
        if gap.abs() <= SEPARATRIX_RELATIVE_BAND * potential_max {
            Self::Separatrix
        } else if gap < 0.0 {
            Self::Trapped
        } else {
            Self::Rotating
        }
    }

    /// The name used in presets, JSON and the interface.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Trapped => "trapped",
            Self::Rotating => "rotating",
            Self::Separatrix => "separatrix",
        }
    }
}

/// The effective motion of one start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effective {
    params: Params,
    theta: f64,
    alpha0: f64,
    alpha_dot0: f64,
    energy: f64,
    phase0: f64,
}

impl Effective {
    /// The effective motion of a problem's start.
    #[must_use]
    pub fn new(problem: &Problem) -> Self {
        let p = *problem.params();
        let s = problem.start();
        let y0 = initial_state(s);
        let g0 = p.g(s.alpha);
        // θ = E⊥(0) · g(α0)^{1/2} (docs/physics.md §2), covers γ0 ≠ 0.
        let theta = transverse_energy(&p, &y0) * g0.sqrt();
        let energy = 0.5 * p.iz * s.alpha_dot * s.alpha_dot + theta / g0.sqrt();
        // Phase of the fast oscillation: γ = a sin φ, γ̇ = a ω cos φ.
        let phase0 = (s.gamma * p.omega(s.alpha)).e_atan2(s.gamma_dot);
        Self {
            params: p,
            theta,
            alpha0: s.alpha,
            alpha_dot0: s.alpha_dot,
            energy,
            phase0,
        }
    }

    /// The same motion with another adiabatic constant (the corrected model's averaged `θ`).
    #[must_use]
    pub fn with_theta(self, theta: f64) -> Self {
        let energy =
            self.energy - self.potential(self.alpha0) + theta / self.params.g(self.alpha0).sqrt();
        Self {
            theta,
            energy,
            ..self
        }
    }

    /// The adiabatic constant `θ = E⊥(0) g(α0)^{1/2}`.
    #[must_use]
    pub fn theta(&self) -> f64 {
        self.theta
    }

    /// The parameters the motion belongs to.
    #[must_use]
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Initial phase of the fast oscillation, `atan2(γ0 ω0, γ̇0)`.
    #[must_use]
    pub fn phase0(&self) -> f64 {
        self.phase0
    }

    /// Effective potential `V(α) = θ g(α)^{−1/2}`.
    #[must_use]
    pub fn potential(&self, alpha: f64) -> f64 {
        self.theta / self.params.g(alpha).sqrt()
    }

    /// Effective energy `½ iz α̇² + V(α)` of any slow state.
    #[must_use]
    pub fn energy_of(&self, alpha: f64, alpha_dot: f64) -> f64 {
        0.5 * self.params.iz * alpha_dot * alpha_dot + self.potential(alpha)
    }

    /// Effective energy of the start.
    #[must_use]
    pub fn energy(&self) -> f64 {
        self.energy
    }

    /// `V_max = θ / sqrt(min(ix, iy))`.
    #[must_use]
    pub fn potential_max(&self) -> f64 {
        self.theta / self.params.ix.min(self.params.iy).sqrt()
    }

    /// The largest spin rate of the limit motion, `sqrt(2 (E_eff − V_min) / iz)`, and at least
    /// the start's `|α̇0|`: the scale of the slow motion.
    #[must_use]
    pub fn spin_scale(&self) -> f64 {
        (2.0 * (self.energy - self.potential_min()) / self.params.iz)
            .max(0.0)
            .sqrt()
            .max(self.alpha_dot0.abs())
    }

    /// `V_min = θ / sqrt(max(ix, iy))`.
    #[must_use]
    pub fn potential_min(&self) -> f64 {
        self.theta / self.params.ix.max(self.params.iy).sqrt()
    }

    /// `α̈ = θ g'(α) g(α)^{−3/2} / (2 iz)`.
    #[must_use]
    #[inline]
    pub fn acceleration(&self, alpha: f64) -> f64 {
        let g = self.params.g(alpha);
        self.theta * self.params.g_prime(alpha) / (g * g.sqrt() * 2.0 * self.params.iz)
    }

    /// The regime of the start.
    #[must_use]
    pub fn regime(&self) -> Regime {
        #[allow(clippy::float_cmp)]
        if self.params.ix == self.params.iy || self.theta == 0.0 {
            return Regime::Uniform;
        }
        Regime::of_energy(self.energy, self.potential_max())
    }

    /// The start's ratio `α̇0² / γ̇0²`, or `None` when `γ̇0 = 0`.
    #[must_use]
    pub fn start_ratio(&self, problem: &Problem) -> Option<f64> {
        let s = problem.start();
        (s.gamma_dot != 0.0).then(|| (s.alpha_dot / s.gamma_dot).powi(2))
    }

    /// The critical value of `α̇0² / γ̇0²` for this start's `α0`, `γ0`, `γ̇0`: the ratio at which
    /// `E_eff = V_max`. Below it the start is trapped and reverses (Theorem 1.1), above it the
    /// spin is monotone (Theorem 1.2). With `α0 = γ0 = 0` and `iy < ix` it is the paper's
    /// `(ix / iz) (sqrt(ix / iy) − 1)`. `None` when `γ̇0 = 0` or the motion is uniform.
    #[must_use]
    pub fn critical_ratio(&self, problem: &Problem) -> Option<f64> {
        let s = problem.start();
        if s.gamma_dot == 0.0 || self.regime() == Regime::Uniform {
            return None;
        }
        let alpha_dot_sq = 2.0 / self.params.iz * (self.potential_max() - self.potential(s.alpha));
        Some(alpha_dot_sq / (s.gamma_dot * s.gamma_dot))
    }

    /// The well the start is trapped in: its centre (a minimum of `V`) and half width `α*`.
    fn well(&self) -> Option<Well> {
        if self.regime() != Regime::Trapped {
            return None;
        }
        let p = &self.params;
        let (g_centre, g_other) = (p.ix.max(p.iy), p.ix.min(p.iy));
        let minimum = if p.ix > p.iy { 0.0 } else { FRAC_PI_2 };
        let centre = minimum + PI * ((self.alpha0 - minimum) / PI).round();
        let g_turn = (self.theta / self.energy).powi(2);
        let sin_sq = ((g_centre - g_turn) / (g_centre - g_other)).clamp(0.0, 1.0);
        let half_width = sin_sq.sqrt().e_asin();
        Some(Well {
            centre,
            half_width,
            g_centre,
            g_other,
        })
    }

    /// The turning points `(centre − α*, centre + α*)` of a trapped start.
    #[must_use]
    pub fn turning_points(&self) -> Option<(f64, f64)> {
        self.well()
            .map(|w| (w.centre - w.half_width, w.centre + w.half_width))
    }

    /// Time between turning points, `∫ dα / sqrt((2/iz)(E_eff − V(α)))` over the well, by
    /// adaptive Gauss–Legendre quadrature after the substitution `α = α* sin φ`.
    #[must_use]
    pub fn half_period(&self) -> Option<f64> {
        let w = self.well()?;
        (w.half_width > 0.0).then(|| self.time_between(&w, -FRAC_PI_2, FRAC_PI_2))
    }

    /// Reversal times of the effective motion in `(0, t_end]`: the first
    /// [`MAX_REVERSAL_TIMES`] of them ([`Effective::reversal_count`] counts all).
    #[must_use]
    pub fn reversal_times(&self, t_end: f64) -> Vec<f64> {
        let Some((first, half)) = self.reversal_schedule() else {
            return Vec::new();
        };
        let count = Self::count_in(first, half, t_end).min(MAX_REVERSAL_TIMES);
        (0..count)
            .map(|n| {
                let n = n as f64;
                first + n * half
            })
            .collect()
    }

    /// How many reversals the limit makes in `(0, t_end]` (all of them, where
    /// [`Effective::reversal_times`] keeps the first [`MAX_REVERSAL_TIMES`]).
    #[must_use]
    pub fn reversal_count(&self, t_end: f64) -> usize {
        self.reversal_schedule()
            .map_or(0, |(first, half)| Self::count_in(first, half, t_end))
    }

    /// The reversals in `(0, t_end]` with the first one's time and the last one's (`None` when
    /// there is none), from the schedule `first + n · half` without stepping through it.
    #[must_use]
    pub fn reversal_window(&self, t_end: f64) -> (usize, Option<f64>, Option<f64>) {
        let Some((first, half)) = self.reversal_schedule() else {
            return (0, None, None);
        };
        let count = Self::count_in(first, half, t_end);
        if count == 0 || count as f64 >= MAX_REVERSALS {
            return (count, None, None);
        }
        // A reversal at t = 0 is not one of the window's.
        let skip = f64::from(u8::from(first <= 0.0));
        let last = first + (skip + count as f64 - 1.0) * half;
        (count, Some(first + skip * half), Some(last))
    }

    /// `first + n · half` in `(0, t_end]`, counted without stepping through them (a loop over
    /// `t += half` would never end where `half` is below the spacing of floats near `t`).
    fn count_in(first: f64, half: f64, t_end: f64) -> usize {
        if !(first.is_finite() && half.is_finite() && half > 0.0) || first > t_end {
            return 0;
        }
        let mut n = ((t_end - first) / half).floor();
        // Beyond 2^53 reversals `n - 1.0 == n`: the loops below would never end (`study map
        // --t-end 1e18` spun forever, issue 56). Such a count saturates.
        if n.is_nan() || n >= MAX_REVERSALS {
            return MAX_REVERSALS as usize;
        }
        // Guard the rounding of the division at both ends.
        while n >= 0.0 && first + n * half > t_end {
            n -= 1.0;
        }
        while first + (n + 1.0) * half <= t_end && n < MAX_REVERSALS {
            n += 1.0;
        }
        let skip = usize::from(first <= 0.0);
        let total = (n + 1.0).min(MAX_REVERSALS) as usize;
        total.saturating_sub(skip)
    }

    /// The first reversal time and the half period between reversals, or `None` when the limit
    /// does not reverse (no well, a flat well, or at rest at its bottom).
    fn reversal_schedule(&self) -> Option<(f64, f64)> {
        let w = self.well()?;
        if w.half_width == 0.0 {
            return None;
        }
        let half = self.time_between(&w, -FRAC_PI_2, FRAC_PI_2);
        let u0 = (self.alpha0 - w.centre).clamp(-w.half_width, w.half_width);
        let phi0 = (u0 / w.half_width).clamp(-1.0, 1.0).e_asin();
        let first = if self.alpha_dot0 > 0.0 {
            self.time_between(&w, phi0, FRAC_PI_2)
        } else if self.alpha_dot0 < 0.0 {
            self.time_between(&w, -FRAC_PI_2, phi0)
        } else if u0 == 0.0 {
            // At rest at the bottom of the well: no motion, no reversal.
            return None;
        } else {
            // At rest at a turning point: the first reversal is at the other one.
            half
        };
        Some((first, half))
    }

    /// `∫ dt` for `φ` from `a` to `b`, with `α = centre + α* sin φ`.
    ///
    /// With `x = α*(1 − sin φ)`, `y = α*(1 + sin φ)`, the identity
    /// `g(α) − g* = (g_c − g_o) sin x sin y` gives a smooth integrand free of cancellation:
    /// `dt/dφ = [ (2/iz) θ (g_c − g_o) sinc x sinc y / D ]^{−1/2}`,
    /// `D = sqrt(g g*) (sqrt g + sqrt g*)`.
    fn time_between(&self, w: &Well, a: f64, b: f64) -> f64 {
        let sin_sq_star = w.half_width.e_sin().powi(2);
        let g_star = w.g_centre - (w.g_centre - w.g_other) * sin_sq_star;
        let scale = 2.0 / self.params.iz * self.theta * (w.g_centre - w.g_other);
        let mut integrand = |phi: f64| {
            let s = phi.e_sin();
            let u = w.half_width * s;
            let x = w.half_width * (1.0 - s);
            let y = w.half_width * (1.0 + s);
            let g = w.g_centre - (w.g_centre - w.g_other) * u.e_sin().powi(2);
            let d = (g * g_star).sqrt() * (g.sqrt() + g_star.sqrt());
            (d / (scale * sinc(x) * sinc(y))).sqrt()
        };
        integrate_adaptive(a, b, QUADRATURE_TOLERANCE, &mut integrand)
    }

    /// A full-model-shaped state from an effective state `(α, α̇, φ)`: the fast oscillation is
    /// reconstructed from the adiabatic invariant, `γ = a sin φ`, `γ̇ = a ω cos φ`, with
    /// `a = sqrt(2 E⊥ / k)` and `E⊥ = θ g(α)^{−1/2}`.
    #[must_use]
    pub fn to_full_state(&self, alpha: f64, alpha_dot: f64, phase: f64) -> State {
        let p = &self.params;
        let e_perp = self.potential(alpha);
        let amplitude = (2.0 * e_perp / p.k).sqrt();
        let (s, c) = phase.e_sin_cos();
        State::new(
            amplitude * s,
            alpha,
            amplitude * p.omega(alpha) * c,
            alpha_dot,
        )
    }
}

#[derive(Clone, Copy, Debug)]
struct Well {
    centre: f64,
    half_width: f64,
    g_centre: f64,
    g_other: f64,
}

fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.e_sin() / x
    }
}

/// The tapping effect (the paper's remark): the spin acceleration at `t = 0`,
/// `α̈(0) = g'(α0) γ̇0² / (2 iz)`, nonzero even for a body at rest in `α`.
#[must_use]
pub fn tapping_acceleration(problem: &Problem) -> f64 {
    let p = problem.params();
    let s = problem.start();
    p.g_prime(s.alpha) * s.gamma_dot * s.gamma_dot / (2.0 * p.iz)
}

impl crate::physics::scene::SlowLimit for Effective {
    fn mass(&self) -> f64 {
        self.params().iz
    }
    fn period(&self) -> f64 {
        std::f64::consts::PI
    }
    /// The potential's minimum.
    fn wrap_centre(&self) -> f64 {
        let p = self.params();
        if p.ix >= p.iy {
            0.0
        } else {
            std::f64::consts::FRAC_PI_2
        }
    }
    /// The fast tilt is drawn only as an envelope.
    fn fast_period(&self) -> Option<f64> {
        None
    }
    fn potential(&self, q: f64) -> f64 {
        Self::potential(self, q)
    }
    fn potential_max(&self) -> f64 {
        Self::potential_max(self)
    }
    fn potential_min(&self) -> f64 {
        Self::potential_min(self)
    }
    fn separatrices(&self) -> Vec<f64> {
        if self.potential_max() > self.potential_min() {
            vec![self.potential_max()]
        } else {
            Vec::new()
        }
    }
    fn energy(&self) -> f64 {
        Self::energy(self)
    }
    fn rate_hint(&self) -> f64 {
        self.spin_scale()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 56 (R1): past 2^53 reversals the rounding guard never moved `n`, and `study map
    /// --t-end 1e18` (or γ̇0 = 1e16) spun forever. Such counts saturate; exact ones stay exact.
    #[test]
    fn a_count_past_two_to_the_53_saturates_at_once() {
        let max = MAX_REVERSALS as usize;
        assert_eq!(Effective::count_in(0.5, 1.0, 1e18), max);
        assert_eq!(Effective::count_in(0.5, 1e-300, 1.0), max);
        assert_eq!(Effective::count_in(0.5, 1.0, f64::MAX), max);
        assert_eq!(Effective::count_in(0.5, 1.0, 10.0), 10);
        assert_eq!(Effective::count_in(0.5, 1.0, 9.5), 10);
        assert_eq!(
            Effective::count_in(0.0, 1.0, 3.0),
            3,
            "t = 0 is not in (0, T]"
        );
        assert_eq!(Effective::count_in(0.5, 1.0, 1e15), 1_000_000_000_000_000);
        // Through the quadratures: a start that reverses, a horizon far past 2^53 periods.
        let eff = Effective::new(&problem(0.5));
        assert_eq!(eff.reversal_count(1e18), max);
        let fast = crate::physics::rattleback::paper_body(1e4, [0.0, 0.0, 1e16, 0.5e16]);
        assert_eq!(Effective::new(&fast).reversal_count(30.0), max);
    }

    fn problem(alpha_dot: f64) -> Problem {
        crate::physics::rattleback::paper_body(1e4, [0.0, 0.0, 1.0, alpha_dot])
    }

    #[test]
    fn critical_ratio_is_the_papers_for_a_zero_start() {
        let pr = problem(0.5);
        let eff = Effective::new(&pr);
        let paper = 2.0 * (2f64.sqrt() - 1.0);
        assert!((eff.critical_ratio(&pr).unwrap() - paper).abs() < 1e-14);
        assert!((eff.theta() - 0.5 * 2f64.e_powf(1.5)).abs() < 1e-15);
        assert_eq!(eff.regime(), Regime::Trapped);
        assert_eq!(Effective::new(&problem(1.0)).regime(), Regime::Rotating);
    }

    #[test]
    fn sinc_is_continuous_at_the_switch() {
        assert!((sinc(1e-4) - sinc(1.000_001e-4)).abs() < 1e-12);
    }
}
