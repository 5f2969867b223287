//! `effective`: the `k → ∞` model `α̈ = θ g' g^{−3/2} / (2 iz)` with the fast phase
//! `φ̇ = ω(α)` carried along, integrated by the DOP853 core.
//!
//! Order 8 in the step, not symplectic; 12 evaluations per step. Its cost does not depend on
//! `k` except through `φ`, which only feeds the reconstructed `γ, γ̇`. Its error against the
//! full model is the model error, O(1/k) in `α` (physics.md §2).

use nalgebra::Vector3;

use super::dop853::{Dop853, Field, Stats};
use super::roots::find_root;
use super::{Integrator, Method, StepError};
use crate::physics::effective::Effective;
use crate::physics::model::State;
use crate::physics::params::Problem;

/// The effective field on `(α, α̇, φ)`.
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

/// DOP853 on `(α, α̇, φ)`.
pub struct EffectiveDop853 {
    model: Effective,
    core: Dop853<3, EffectiveField>,
}

impl EffectiveDop853 {
    /// Starts at the problem's initial values with tolerance `tol`.
    pub fn new(problem: &Problem, tol: f64) -> Self {
        let model = Effective::new(problem);
        let s = problem.start();
        let y0 = Vector3::new(s.alpha, s.alpha_dot, model.phase0());
        Self {
            model,
            core: Dop853::new(EffectiveField(model), 0.0, y0, tol),
        }
    }

    fn lift(&self, y: &Vector3<f64>) -> State {
        self.model.to_full_state(y[0], y[1], y[2])
    }
}

impl Integrator for EffectiveDop853 {
    fn method(&self) -> Method {
        Method::Effective
    }
    fn time(&self) -> f64 {
        self.core.time()
    }
    fn time_prev(&self) -> f64 {
        self.core.time_prev()
    }
    fn state(&self) -> State {
        self.lift(&self.core.state())
    }
    fn alpha_dot(&self) -> f64 {
        self.core.state()[1]
    }
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        self.core.step(t_limit)
    }
    fn interpolate(&mut self, t: f64) -> State {
        let y = self.core.interpolate(t);
        self.lift(&y)
    }
    fn locate_alpha_dot_zero(&mut self) -> f64 {
        let (a, b) = (self.core.time_prev(), self.core.time());
        find_root(|t| self.core.interpolate(t)[1], a, b)
    }
    fn energy(&self, y: &State) -> f64 {
        self.model.energy_of(y[1], y[3])
    }
    fn stats(&self) -> Stats {
        self.core.stats()
    }
}
