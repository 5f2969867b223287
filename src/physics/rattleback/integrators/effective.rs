//! `effective` and `effective-corrected`: the `k → ∞` model `α̈ = θ g' g^{−3/2} / (2 iz)` with
//! the fast phase `φ̇ = ω(α)` carried along, integrated by the DOP853 core.
//!
//! Order 8 in the step, not symplectic; 12 evaluations per step. The cost does not depend on
//! `k` (`φ` is measured relative to its size). The error against the full model is the model
//! error: O(1/k) in `α`; in `α̇`, O(1/sqrt(k)) for `effective`, which lacks the fast ripple,
//! and O(1/k) for `effective-corrected`, which adds it back (docs/physics.md §4b):
//! `α̇ ≈ α̇_eff + c(α) I sin 2φ / iz`, `c = g'/(4g)`, `I = θ/sqrt(k)`, with the averaged motion
//! started from `α̇0` minus the same term at `φ0`. The action itself oscillates: each drift of
//! `α` changes it by `δI/I = −(g'/2g) cos 2φ δα`, so `I(t) = Ī − I c α̇ sin 2φ / ω`, and the
//! averaged motion starts from `θ̄ = θ (1 + c α̇0 sin 2φ0 / ω0)` (zero shift when `γ0 = 0`).
use crate::physics::numerics::elementary::Elementary;

use nalgebra::Vector3;

use crate::physics::flow::Flow;
use crate::physics::method::Method;
use crate::physics::numerics::dop853::{Dop853, Field};
use crate::physics::numerics::roots::find_root;
use crate::physics::rattleback::effective::Effective;
use crate::physics::rattleback::model::State;
use crate::physics::rattleback::params::Problem;

/// The effective field on `(α, α̇, φ)`.
#[derive(Clone)]
pub struct EffectiveField(Effective);

impl Field<3> for EffectiveField {
    #[inline]
    fn eval(&self, y: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(y[1], self.0.acceleration(y[0]), self.0.params().omega(y[0]))
    }
    fn is_angle(&self, i: usize) -> bool {
        i == 0
    }
}

/// DOP853 on `(α, α̇_eff, φ)`.
#[derive(Clone)]
pub struct EffectiveDop853 {
    model: Effective,
    core: Dop853<3, EffectiveField>,
    /// The fast action `I = θ/sqrt(k)` when the ripple is added back, else 0.
    ripple_action: f64,
}

impl EffectiveDop853 {
    /// Starts at the problem's initial values with tolerance `tol`; `corrected` adds the
    /// first-order ripple of `α̇`.
    pub fn new(problem: &Problem, tol: f64, corrected: bool) -> Self {
        let mut model = Effective::new(problem);
        let s = problem.start();
        let p = problem.params();
        let ripple_action = if corrected {
            let c = p.g_prime(s.alpha) / (4.0 * p.g(s.alpha));
            let shift = c * s.alpha_dot * (2.0 * model.phase0()).e_sin() / p.omega(s.alpha);
            model = model.with_theta(model.theta() * (1.0 + shift));
            model.theta() / p.k.sqrt()
        } else {
            0.0
        };
        let phase0 = model.phase0();
        let ripple0 = ripple(&model, ripple_action, s.alpha, phase0);
        let y0 = Vector3::new(s.alpha, s.alpha_dot - ripple0, phase0);
        Self {
            model,
            core: Dop853::new(EffectiveField(model), 0.0, y0, tol),
            ripple_action,
        }
    }

    fn spin_rate(&self, y: &Vector3<f64>) -> f64 {
        y[1] + ripple(&self.model, self.ripple_action, y[0], y[2])
    }

    fn lift(&self, y: &Vector3<f64>) -> State {
        self.model.to_full_state(y[0], self.spin_rate(y), y[2])
    }
}

/// The fast ripple of `α̇`, `c(α) I sin 2φ / iz` with `c = g'/(4g)`.
fn ripple(model: &Effective, action: f64, alpha: f64, phase: f64) -> f64 {
    if action == 0.0 {
        return 0.0;
    }
    let p = model.params();
    p.g_prime(alpha) / (4.0 * p.g(alpha)) * action * (2.0 * phase).e_sin() / p.iz
}

impl EffectiveDop853 {
    /// The current state `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn state(&self) -> State {
        self.lift(&self.core.state())
    }
    /// The state at `t` inside the last step.
    pub fn interpolate(&mut self, t: f64) -> State {
        let y = self.core.interpolate(t);
        self.lift(&y)
    }
}

impl Flow for EffectiveDop853 {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        if self.ripple_action == 0.0 {
            Method::Effective
        } else {
            Method::EffectiveCorrected
        }
    }
    fn event_value(&self) -> f64 {
        self.spin_rate(&self.core.state())
    }
    fn locate_event(&mut self) -> f64 {
        let (a, b) = (self.core.time_prev(), self.core.time());
        find_root(
            |t| {
                let y = self.core.interpolate(t);
                self.spin_rate(&y)
            },
            a,
            b,
        )
    }
    fn energy(&self) -> f64 {
        let y = self.core.state();
        self.model.energy_of(y[0], y[1])
    }

    super::drawn_from_state!();
}
