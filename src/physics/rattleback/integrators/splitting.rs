//! `strang`, `yoshida4`, `yoshida6`, `suzuki8`, `blanes-moan4`: splitting with exactly solved
//! sub-flows (docs/physics.md §4), its symmetric compositions and an optimised splitting.
//!
//! `H = H1 + H2`, `H1 = pα²/(2 iz)` (a drift of `α`), `H2 = pγ²/(2 g(α)) + ½ k γ²` (with `α`
//! frozen: a rotation of `(γ, pγ)` at `ω = sqrt(k/g)` and a kick of `pα` by the closed-form
//! integral of `pγ²`). Every method is a symmetric sequence
//! `H1(a_0 h) H2(b_1 h) H1(a_1 h) … H2(b_m h) H1(a_m h)`: Strang is `a = (½, ½)`, `b = (1)`;
//! a composition of Strang steps of sizes `w_i h` merges adjacent drifts; `blanes-moan4` is
//! Blanes & Moan's 6-stage order-4 splitting (2002, `S6`), whose error constant is far smaller
//! than the triple jump's.
//!
//! | method | order | stages (exact fast flows per step) | symplectic |
//! |---|---|---|---|
//! | strang | 2 | 1 | yes |
//! | yoshida4 | 4 | 3 | yes |
//! | yoshida6 | 6 | 7 | yes |
//! | suzuki8 | 8 | 15 | yes |
//! | blanes-moan4 | 4 | 6 | yes |
//!
//! There is no stability limit in `k`: the fast flow is exact for any `ω h`. Its weakness is
//! step-size resonance (`ω h` near a multiple of π), see docs/physics.md §4.
//!
//! Reversals: only `H2` changes `pα`, and inside one `H2` sub-flow `pα(s)` is monotone (its
//! derivative is `g' pγ²/(2g²)`, of fixed sign), so the crossing inside a sub-flow is unique and
//! is found on the closed form itself.
use crate::physics::numerics::elementary::Elementary;

use crate::physics::flow::Flow;
use crate::physics::method::TimeSum;
use crate::physics::method::{Method, StepError};
pub use crate::physics::numerics::compositions::Composition;
use crate::physics::numerics::compositions::Split;
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::roots::find_root;
use std::f64::consts::{FRAC_PI_2, PI};

use crate::physics::rattleback::model::{State, initial_state};
use crate::physics::rattleback::params::{Params, Problem};

/// The rattleback as a [`Split`]: the drift of `α` by `pα/iz`, the exact fast flow.
struct RattlebackSplit<'a> {
    p: &'a Params,
    y: Canonical,
    /// `h / iz`.
    drift: f64,
}

impl Split for RattlebackSplit<'_> {
    #[inline]
    fn drift(&mut self, c: f64, _h: f64) {
        self.y.alpha += c * self.drift * self.y.p_alpha;
    }
    #[inline]
    fn kick(&mut self, c: f64, h: f64) {
        self.y = fast_flow(self.p, &self.y, c * h);
    }
}

/// One step of `composition` of size `h` from `y`.
#[must_use]
pub fn composition_step(composition: &Composition, p: &Params, y: &Canonical, h: f64) -> Canonical {
    let mut s = RattlebackSplit {
        p,
        y: *y,
        drift: h / p.iz,
    };
    composition.apply(&mut s, h);
    s.y
}

/// Canonical state `(γ, α, pγ, pα)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Canonical {
    /// Tilt.
    pub gamma: f64,
    /// Spin angle.
    pub alpha: f64,
    /// `pγ = g(α) γ̇`.
    pub p_gamma: f64,
    /// `pα = iz α̇`.
    pub p_alpha: f64,
}

impl Canonical {
    /// From `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn from_state(p: &Params, y: &State) -> Self {
        Self {
            gamma: y[0],
            alpha: y[1],
            p_gamma: p.g(y[1]) * y[2],
            p_alpha: p.iz * y[3],
        }
    }

    /// To `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn to_state(&self, p: &Params) -> State {
        State::new(
            self.gamma,
            self.alpha,
            self.p_gamma / p.g(self.alpha),
            self.p_alpha / p.iz,
        )
    }
}

/// The exact fast sub-flow `H2` for time `tau`, `α` frozen: returns the new state.
///
/// `pα += g'/(2g²) · J`, `J = ∫₀^τ pγ(s)² ds`
/// `= τ/2 (pγ² + (gωγ)²) + sc/(2ω) (pγ² − (gωγ)²) − pγ gωγ s²/ω` with `s, c = sin, cos ωτ`.
#[must_use]
#[inline]
pub fn fast_flow(p: &Params, y: &Canonical, tau: f64) -> Canonical {
    let fast = FastFlow::new(p, y);
    let (s, c) = (fast.omega * tau).e_sin_cos();
    Canonical {
        gamma: y.gamma * c + y.p_gamma / fast.g_omega * s,
        alpha: y.alpha,
        p_gamma: y.p_gamma * c - fast.g_omega * y.gamma * s,
        p_alpha: y.p_alpha + fast.kick(y, tau, s, c),
    }
}

/// Quantities of one `H2` sub-flow that do not depend on its duration.
struct FastFlow {
    omega: f64,
    g_omega: f64,
    kick_scale: f64,
}

impl FastFlow {
    fn new(p: &Params, y: &Canonical) -> Self {
        let (sa, ca) = y.alpha.e_sin_cos();
        let g = p.ix * ca * ca + p.iy * sa * sa;
        let g_prime = 2.0 * (p.iy - p.ix) * sa * ca;
        let omega = (p.k / g).sqrt();
        Self {
            omega,
            g_omega: g * omega,
            kick_scale: g_prime / (2.0 * g * g),
        }
    }

    /// `g'/(2g²) ∫₀^τ pγ(s)² ds`, given `s, c = sin, cos ωτ`.
    #[inline]
    fn kick(&self, y: &Canonical, tau: f64, s: f64, c: f64) -> f64 {
        let a = y.p_gamma;
        let b = self.g_omega * y.gamma;
        let j = 0.5 * tau * (a * a + b * b) + s * c / (2.0 * self.omega) * (a * a - b * b)
            - a * b * s * s / self.omega;
        self.kick_scale * j
    }
}

/// One step of Strang steps of sizes `w_i h` from `y` (a composition given by its weights).
#[must_use]
pub fn composed_step(p: &Params, weights: &[f64], y: &Canonical, h: f64) -> Canonical {
    composition_step(
        &Composition::of_strang_steps(Method::Strang, weights),
        p,
        y,
        h,
    )
}

/// How the step size is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
enum StepRule {
    /// Always `h` (shortened only to land on `t_limit`).
    Fixed,
    /// `locked`: each step advances the fast phase by exactly `(m + ½)π` at `α` mid-step,
    /// starting from a phase that is a multiple of `π/2`; `aligned` says whether the current
    /// phase is such a multiple.
    PhaseLocked {
        aligned: bool,
        /// `ω` at the previous step's mid-point, Newton's starting guess (0: none yet).
        omega_mid: f64,
    },
}

/// A splitting integrator with a fixed or phase-locked step.
#[derive(Clone)]
pub struct Splitting {
    params: Params,
    composition: Composition,
    rule: StepRule,
    h: f64,
    t: f64,
    y: Canonical,
    t_prev: f64,
    y_prev: Canonical,
    stats: Stats,
    time_sum: TimeSum,
    carry: f64,
}

impl Splitting {
    /// How the steps are added to the time (compensated unless told).
    #[must_use]
    pub fn with_time_sum(mut self, time_sum: TimeSum) -> Self {
        self.time_sum = time_sum;
        self
    }

    /// Starts at the problem's initial values with step `h`.
    #[must_use]
    pub fn new(problem: &Problem, composition: Composition, h: f64) -> Self {
        let params = *problem.params();
        let y = Canonical::from_state(&params, &initial_state(problem.start()));
        Self {
            params,
            composition,
            rule: StepRule::Fixed,
            h,
            t: 0.0,
            y,
            t_prev: 0.0,
            y_prev: y,
            stats: Stats::default(),
            time_sum: TimeSum::default(),
            carry: 0.0,
        }
    }
}

impl Splitting {
    /// `locked`: Strang with phase-locked steps near `h` (docs/physics.md §4). Each drift of `α`
    /// kicks the fast action by `δI/I = −(g'/2g) cos 2φ δα`; with the phase advancing by
    /// `(m + ½)π` per step, `cos 2φ` alternates in sign at successive drifts and the kicks
    /// cancel instead of adding up at a step-size resonance. Order 2 while `ω h < π/2`
    /// (plain Strang); beyond, an error of about `0.05 h²` whatever `k`, at one exact fast flow
    /// per step. Symplectic per step, but the varying step makes the whole map not strictly so.
    #[must_use]
    pub fn phase_locked(problem: &Problem, h: f64) -> Self {
        let mut me = Self::new(problem, Composition::of(Method::Strang), h);
        me.composition = me.composition.named(Method::Locked);
        me.rule = StepRule::PhaseLocked {
            aligned: false,
            omega_mid: 0.0,
        };
        me
    }

    /// The size of the next step under the current rule, at most `remaining`.
    fn next_step(&mut self, remaining: f64) -> f64 {
        let StepRule::PhaseLocked { aligned, omega_mid } = self.rule else {
            return self.h.min(remaining);
        };
        let p = self.params;
        let y = self.y;
        // The previous mid-step frequency is within O(α̇ h) of this one: one Newton step from
        // it reaches rounding, and saves a `sin_cos`.
        let omega = if omega_mid > 0.0 {
            omega_mid
        } else {
            p.omega(y.alpha)
        };
        if omega * self.h < FRAC_PI_2 {
            // Resolved: no resonance to avoid, plain Strang.
            return self.h.min(remaining);
        }
        let drift = y.p_alpha / p.iz;
        // Solves `f(h) = h ω(α + ½ h α̇) − advance = 0` by Newton's method from
        // `advance / ω_guess`; `f' = ω + ½ h α̇ ω'` with `ω' = −ω g'/(2g)`. Returns `h` and `ω` at
        // its mid-point.
        let size_for = |advance: f64, iterations: usize| {
            let mut h = advance / omega;
            let mut w = omega;
            for _ in 0..iterations {
                let mid = y.alpha + 0.5 * h * drift;
                let (s, c) = mid.e_sin_cos();
                let g = p.ix * c * c + p.iy * s * s;
                let g_prime = 2.0 * (p.iy - p.ix) * s * c;
                w = (p.k / g).sqrt();
                let slope = w * (1.0 - 0.25 * h * drift * g_prime / g);
                h -= (h * w - advance) / slope;
            }
            (h, w)
        };
        let iterations = if omega_mid > 0.0 { 1 } else { 2 };
        if !aligned {
            let g = p.g(y.alpha);
            let phase = (g * omega * y.gamma).e_atan2(y.p_gamma);
            let to_quarter = (phase / FRAC_PI_2).ceil() * FRAC_PI_2 - phase;
            self.rule = StepRule::PhaseLocked {
                aligned: true,
                omega_mid,
            };
            if to_quarter > 1e-12 {
                let (h, _) = size_for(to_quarter, 2);
                if h < remaining {
                    return h;
                }
            }
        }
        let m = (omega * self.h / PI - 0.5).round().max(0.0);
        let (h, w) = size_for((m + 0.5) * PI, iterations);
        if h >= remaining {
            // Landing on t_limit breaks the lock; realign on the next step.
            self.rule = StepRule::PhaseLocked {
                aligned: false,
                omega_mid: 0.0,
            };
            return remaining;
        }
        self.rule = StepRule::PhaseLocked {
            aligned: true,
            omega_mid: w,
        };
        h
    }
}

impl Splitting {
    /// The current state `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn state(&self) -> State {
        self.y.to_state(&self.params)
    }
    /// The method's own step of size `t − t_prev` from the step's start: the same order as a
    /// full step, and exact in the fast oscillation.
    pub fn interpolate(&mut self, t: f64) -> State {
        let y = composition_step(
            &self.composition,
            &self.params,
            &self.y_prev,
            t - self.t_prev,
        );
        y.to_state(&self.params)
    }
}

impl Flow for Splitting {
    fn boxed(&self) -> Box<dyn Flow> {
        Box::new(self.clone())
    }
    fn method(&self) -> Method {
        self.composition.method()
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn time_prev(&self) -> f64 {
        self.t_prev
    }
    fn event_value(&self) -> f64 {
        self.y.p_alpha / self.params.iz
    }
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        let remaining = t_limit - self.t;
        let h = self.next_step(remaining);
        let last = h >= remaining;
        let y_new = composition_step(&self.composition, &self.params, &self.y, h);
        if ![y_new.gamma, y_new.alpha, y_new.p_gamma, y_new.p_alpha]
            .iter()
            .all(|v| v.is_finite())
        {
            return Err(StepError::NonFinite { t: self.t });
        }
        self.t_prev = self.t;
        self.y_prev = self.y;
        self.t = if last {
            t_limit
        } else {
            self.time_sum.add(self.t, h, &mut self.carry)
        };
        self.y = y_new;
        self.stats.steps += 1;
        self.stats.rhs_evaluations += self.composition.stages() as u64;
        Ok(())
    }
    fn locate_event(&mut self) -> f64 {
        let p = self.params;
        let h = self.t - self.t_prev;
        // The sign α̇ ends the step with; a stage crosses when it moves p_alpha onto that side.
        let target = self.y.p_alpha > 0.0;
        let mut y = self.y_prev;
        let c = &self.composition;
        let (drifts, kicks) = c.coefficients();
        y.alpha += drifts[0] * h * y.p_alpha / p.iz;
        // Each fast sub-flow advances the fast clock by `b_i h`: its crossing is dated there.
        let mut offset = 0.0;
        let mut fallback = None;
        for (&b, &a) in kicks.iter().zip(&drifts[1..]) {
            let tau = b * h;
            let after = fast_flow(&p, &y, tau);
            let on_target = |v: f64| v != 0.0 && (v > 0.0) == target;
            if !on_target(y.p_alpha) && on_target(after.p_alpha) {
                let before = y;
                let fast = FastFlow::new(&p, &before);
                let p_alpha_at = |s: f64| {
                    let (sn, cs) = (fast.omega * s).e_sin_cos();
                    before.p_alpha + fast.kick(&before, s, sn, cs)
                };
                let s = find_root(p_alpha_at, 0.0, tau);
                let t = (self.t_prev + offset + s).clamp(self.t_prev, self.t);
                if tau > 0.0 {
                    return t;
                }
                fallback.get_or_insert(t);
            }
            y = after;
            y.alpha += a * h * y.p_alpha / p.iz;
            offset += tau;
        }
        fallback.unwrap_or(self.t)
    }
    fn energy(&self) -> f64 {
        let p = &self.params;
        let y = &self.y;
        0.5 * y.p_gamma * y.p_gamma / p.g(y.alpha)
            + 0.5 * y.p_alpha * y.p_alpha / p.iz
            + 0.5 * p.k * y.gamma * y.gamma
    }
    fn stats(&self) -> Stats {
        self.stats
    }

    super::drawn_from_state!();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::numerics::compositions::{SUZUKI8, YOSHIDA4, YOSHIDA6};
    use crate::physics::rattleback::params::Start;

    #[test]
    fn composition_weights_are_consistent_and_symmetric() {
        for w in [&YOSHIDA4[..], &YOSHIDA6[..], &SUZUKI8[..]] {
            let sum: f64 = w.iter().sum();
            assert!((sum - 1.0).abs() < 1e-15, "weights sum to {sum}");
            assert!(w.iter().eq(w.iter().rev()), "composition is not symmetric");
        }
        for m in [
            Method::Strang,
            Method::Yoshida4,
            Method::Yoshida6,
            Method::Suzuki8,
            Method::BlanesMoan4,
        ] {
            let c = Composition::of(m);
            let (drifts, kicks) = c.coefficients();
            let (a, b): (f64, f64) = (drifts.iter().sum(), kicks.iter().sum());
            assert!(
                (a - 1.0).abs() < 1e-15 && (b - 1.0).abs() < 1e-15,
                "{m}: {a} {b}"
            );
            assert!(drifts.iter().eq(drifts.iter().rev()) && kicks.iter().eq(kicks.iter().rev()));
        }
    }

    proptest::proptest! {
    /// A symmetric composition is time-reversible: a step forward then back is the identity.
    /// The tilt is drawn on the energy scale, `γ = a / sqrt(k)` (a tilt energy `½ a²` of order
    /// one): a fixed `γ` at `k = 1e8` would mean a tilt energy in the thousands, whose huge
    /// kicks amplify rounding beyond any fixed bound.
    #[test]
    fn compositions_are_reversible(
        ix in 0.1f64..10.0, iy in 0.1f64..10.0, iz in 0.1f64..10.0, k in 1.0f64..1e8,
        tilt in -1.0f64..1.0, alpha in -3.0f64..3.0, gamma_dot in -2.0f64..2.0,
        alpha_dot in -2.0f64..2.0, h in 1e-4f64..0.1,
    ) {
        let gamma = tilt / k.sqrt();
        let p = Params { ix, iy, iz, k };
        let start = Start { gamma, alpha, gamma_dot, alpha_dot };
        proptest::prop_assume!(Problem::new(p, start).is_ok());
        let y0 = Canonical::from_state(&p, &initial_state(&start));
        for w in [&[1.0][..], &[1.351_207_191_959_657_8, -1.702_414_383_919_315_5, 1.351_207_191_959_657_8][..]] {
            let y1 = composed_step(&p, w, &y0, h);
            let back = composed_step(&p, w, &y1, -h);
            let scale = 1.0 + y0.p_gamma.abs() + y0.p_alpha.abs();
            proptest::prop_assert!((back.alpha - y0.alpha).abs() < 1e-9 * (1.0 + y0.alpha.abs()));
            proptest::prop_assert!((back.p_alpha - y0.p_alpha).abs() < 1e-9 * scale);
            proptest::prop_assert!((back.p_gamma - y0.p_gamma).abs() < 1e-9 * scale);
        }
    }
    }
}
