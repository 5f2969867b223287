//! `averaged2`: the second-order averaged model (`physics::rattleback::averaged`, docs/physics.md §4c), its slow
//! flow on `(ᾱ, P̄, ψ̄)` integrated by the DOP853 core.
//!
//! Order 8 in the step, not symplectic; 12 evaluations per step, each a `sin_cos` and a
//! `sqrt`; the cost does not depend on `k`. The error against the full model is the model
//! error, O(k⁻²) in `α`, `α̇` and the reversal times (measured exponents 1.9–2.1,
//! `tests/it/averaged.rs`), plus the integration error of the slow flow, which the tolerance
//! controls. The reported state is reconstructed (the fast ripple included); reversals are
//! zeros of the reconstructed `α̇`, located on the dense output.

use super::Method;
use super::dop853::{Dop853, Field};
use super::roots::find_root;
use crate::physics::flow::Flow;
use crate::physics::rattleback::averaged::{Averaged2, SlowState};
use crate::physics::rattleback::model::State;
use crate::physics::rattleback::params::Problem;

/// The slow field of `K̄`.
#[derive(Clone)]
pub struct AveragedField {
    model: Averaged2,
    /// Natural size of `P̄`, the momentum scale of the start.
    momentum_unit: f64,
}

impl Field<3> for AveragedField {
    #[inline]
    fn eval(&self, y: &SlowState) -> SlowState {
        self.model.rhs(y)
    }
    fn unit(&self, i: usize) -> f64 {
        if i == 1 { self.momentum_unit } else { 1.0 }
    }
    fn is_angle(&self, i: usize) -> bool {
        i != 1
    }
}

/// DOP853 on the averaged slow flow.
#[derive(Clone)]
pub struct Averaged2Dop853 {
    model: Averaged2,
    core: Dop853<3, AveragedField>,
}

impl Averaged2Dop853 {
    /// Starts at the problem's initial values (mapped to averaged variables) with local
    /// tolerance `tol`.
    pub fn new(problem: &Problem, tol: f64) -> Self {
        let (model, y0) = Averaged2::new(problem);
        let p = problem.params();
        // P̄ moves on the scale of iz·α̇ and of the potential's force, whichever is larger.
        let momentum_unit = (p.iz * problem.start().alpha_dot.abs())
            .max((p.iz * model.potential_max()).sqrt())
            .max(f64::MIN_POSITIVE);
        let field = AveragedField {
            model,
            momentum_unit,
        };
        Self {
            model,
            core: Dop853::new(field, 0.0, y0, tol),
        }
    }
}

impl Averaged2Dop853 {
    /// The current state `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn state(&self) -> State {
        self.model.to_full_state(&self.core.state())
    }
    /// The state at `t` inside the last step.
    pub fn interpolate(&mut self, t: f64) -> State {
        let y = self.core.interpolate(t);
        self.model.to_full_state(&y)
    }
}

impl Flow for Averaged2Dop853 {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        Method::Averaged2
    }
    fn event_value(&self) -> f64 {
        self.model.spin_rate(&self.core.state())
    }
    fn locate_event(&mut self) -> f64 {
        // The full α̇ is monotone across a reversal (α̈ = g'γ̇²/(2iz) keeps the sign of g' near
        // a turning point), and so is its reconstruction: one bracketed zero per step.
        let (a, b) = (self.core.time_prev(), self.core.time());
        find_root(
            |t| {
                let y = self.core.interpolate(t);
                self.model.spin_rate(&y)
            },
            a,
            b,
        )
    }
    fn energy(&self) -> f64 {
        let y = self.core.state();
        self.model.kbar(y[0], y[1])
    }

    super::drawn_from_state!();
}
