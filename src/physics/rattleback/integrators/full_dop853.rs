//! `dop853` on the full model: the generic core of [`super::dop853`] with the Euler–Lagrange
//! right-hand side. Order 8, not symplectic, 12 evaluations per step (see the core's doc).

use super::Method;
use super::dop853::{Dop853, Field};
use super::roots::find_root;
use crate::physics::flow::Flow;
use crate::physics::rattleback::model::{ALPHA_DOT, State, energy, initial_state, rhs};
use crate::physics::rattleback::params::{Params, Problem};

/// The Euler–Lagrange field of one parameter set, with `1/ω_max`, the natural unit of `γ`.
#[derive(Clone)]
pub struct FullField(Params, f64);

impl Field<4> for FullField {
    #[inline]
    fn eval(&self, y: &State) -> State {
        rhs(&self.0, y)
    }
    fn unit(&self, i: usize) -> f64 {
        if i == crate::physics::rattleback::model::GAMMA {
            self.1
        } else {
            1.0
        }
    }
    fn is_angle(&self, i: usize) -> bool {
        i == crate::physics::rattleback::model::ALPHA
    }
}

/// DOP853 on `(γ, α, γ̇, α̇)`.
#[derive(Clone)]
pub struct FullDop853 {
    params: Params,
    core: Dop853<4, FullField>,
}

impl FullDop853 {
    /// Starts at the problem's initial values with tolerance `tol`.
    pub fn new(problem: &Problem, tol: f64) -> Self {
        let params = *problem.params();
        Self {
            params,
            core: Dop853::new(
                FullField(params, 1.0 / params.omega_max()),
                0.0,
                initial_state(problem.start()),
                tol,
            ),
        }
    }
}

impl FullDop853 {
    /// The current state `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn state(&self) -> State {
        self.core.state()
    }
    /// The state at `t` inside the last step.
    pub fn interpolate(&mut self, t: f64) -> State {
        self.core.interpolate(t)
    }
}

impl Flow for FullDop853 {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        Method::Dop853
    }
    fn locate_event(&mut self) -> f64 {
        let (a, b) = (self.core.time_prev(), self.core.time());
        find_root(|t| self.core.interpolate(t)[ALPHA_DOT], a, b)
    }
    fn energy(&self) -> f64 {
        energy(&self.params, &self.state())
    }

    fn event_value(&self) -> f64 {
        self.state()[super::super::model::ALPHA_DOT]
    }
    super::drawn_from_state!();
}
