//! The full model `(γ, α, γ̇, α̇)` behind one [`Flow`], on either core: `dop853` (the generic
//! core of [`dop853`] with the Euler–Lagrange right-hand side; order 8, not symplectic,
//! 12 evaluations per step) or `taylor` ([`super::full_taylor`]). Samples, reversals and the
//! energy are the same code for both.
//!
//! [`dop853`]: crate::physics::numerics::dop853

use super::full_taylor::TaylorCore;
use crate::physics::flow::Flow;
use crate::physics::method::Method;
use crate::physics::numerics::dop853::{Dop853, Field};
use crate::physics::numerics::roots::find_root;
use crate::physics::numerics::stepper::FullCore;
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

impl FullCore<4, Params> for Dop853<4, FullField> {
    const METHOD: Method = Method::Dop853;
    fn start(params: &Params, y0: State, tol: f64) -> Self {
        Dop853::new(FullField(*params, 1.0 / params.omega_max()), 0.0, y0, tol)
    }
}

impl FullCore<4, Params> for TaylorCore {
    const METHOD: Method = Method::Taylor;
    fn start(params: &Params, y0: State, tol: f64) -> Self {
        TaylorCore::new(params, 0.0, y0, tol)
    }
}

/// The full model by `dop853`.
pub type FullDop853 = Full<Dop853<4, FullField>>;
/// The full model by `taylor`.
pub type FullTaylor = Full<TaylorCore>;

/// The full model on `core`.
#[derive(Clone)]
pub struct Full<C> {
    params: Params,
    core: C,
}

impl<C: FullCore<4, Params>> Full<C> {
    /// Starts at the problem's initial values with tolerance `tol`.
    #[must_use]
    pub fn new(problem: &Problem, tol: f64) -> Self {
        let params = *problem.params();
        Self {
            params,
            core: C::start(&params, initial_state(problem.start()), tol),
        }
    }

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

impl<C: FullCore<4, Params>> Flow for Full<C> {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        C::METHOD
    }
    fn locate_event(&mut self) -> f64 {
        let (a, b) = (self.core.time_prev(), self.core.time());
        find_root(|t| self.core.interpolate(t)[ALPHA_DOT], a, b)
    }
    fn energy(&self) -> f64 {
        energy(&self.params, &self.state())
    }
    fn event_value(&self) -> f64 {
        self.state()[ALPHA_DOT]
    }
    super::drawn_from_state!();
}
