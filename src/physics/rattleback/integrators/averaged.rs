//! `averaged2` and `averaged3`: the second- and third-order averaged models
//! (`physics::rattleback::averaged`, docs/physics.md §4c; `physics::rattleback::averaged3`), their
//! slow flow on `(ᾱ, P̄, ψ̄)` integrated by the DOP853 core.
//!
//! Order 8 in the step, not symplectic; 12 evaluations per step, each a `sin_cos` and a
//! `sqrt`; the cost does not depend on `k`. The error against the full model is the model
//! error, O(k⁻²) (`averaged2`) or O(k⁻³) (`averaged3`) in `α`, `α̇` and the reversal times
//! (`tests/it/averaged.rs`), plus the integration error of the slow flow, which the tolerance
//! controls. The reported state is reconstructed (the fast ripple included); reversals are
//! zeros of the reconstructed `α̇`, located on the dense output.

use super::Method;
use super::dop853::{Dop853, Field};
use super::roots::find_root;
use crate::physics::flow::Flow;
use crate::physics::rattleback::averaged::{Averaged2, SlowState};
use crate::physics::rattleback::averaged3::Averaged3;
use crate::physics::rattleback::model::State;
use crate::physics::rattleback::params::Problem;

/// What the integrator needs of an averaged model.
pub trait SlowModel: Clone + Copy + Send + Sync + 'static {
    /// The method that integrates it.
    const METHOD: Method;
    /// The model of a problem's start and its averaged initial state.
    fn start(problem: &Problem) -> (Self, SlowState);
    /// The slow flow.
    fn rhs(&self, y: &SlowState) -> SlowState;
    /// `K̄(ᾱ, P̄)`.
    fn kbar(&self, alpha_bar: f64, p_bar: f64) -> f64;
    /// The reconstructed `α̇`.
    fn spin_rate(&self, y: &SlowState) -> f64;
    /// The full-model-shaped state.
    fn to_full_state(&self, y: &SlowState) -> State;
    /// The averaged fast action.
    fn ibar(&self) -> f64;
}

macro_rules! slow_model {
    ($t:ty, $m:expr) => {
        impl SlowModel for $t {
            const METHOD: Method = $m;
            fn start(problem: &Problem) -> (Self, SlowState) {
                <$t>::new(problem)
            }
            #[inline]
            fn rhs(&self, y: &SlowState) -> SlowState {
                <$t>::rhs(self, y)
            }
            fn kbar(&self, alpha_bar: f64, p_bar: f64) -> f64 {
                <$t>::kbar(self, alpha_bar, p_bar)
            }
            #[inline]
            fn spin_rate(&self, y: &SlowState) -> f64 {
                <$t>::spin_rate(self, y)
            }
            fn to_full_state(&self, y: &SlowState) -> State {
                <$t>::to_full_state(self, y)
            }
            fn ibar(&self) -> f64 {
                <$t>::ibar(self)
            }
        }
    };
}
slow_model!(Averaged2, Method::Averaged2);
slow_model!(Averaged3, Method::Averaged3);

/// The slow field of `K̄`.
#[derive(Clone)]
pub struct AveragedField<M> {
    model: M,
    /// Natural size of `P̄`, the momentum scale of the start.
    momentum_unit: f64,
}

impl<M: SlowModel> Field<3> for AveragedField<M> {
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
pub struct AveragedDop853<M> {
    model: M,
    core: Dop853<3, AveragedField<M>>,
}

/// `averaged2`.
pub type Averaged2Dop853 = AveragedDop853<Averaged2>;
/// `averaged3`.
pub type Averaged3Dop853 = AveragedDop853<Averaged3>;

impl<M: SlowModel> AveragedDop853<M> {
    /// Starts at the problem's initial values (mapped to averaged variables) with local
    /// tolerance `tol`.
    pub fn new(problem: &Problem, tol: f64) -> Self {
        let (model, y0) = M::start(problem);
        let p = problem.params();
        // P̄ moves on the scale of iz·α̇ and of the potential's force, whichever is larger.
        let potential_max = crate::physics::rattleback::averaged::potential_max(p, model.ibar());
        let momentum_unit = (p.iz * problem.start().alpha_dot.abs())
            .max((p.iz * potential_max).sqrt())
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

impl<M: SlowModel> AveragedDop853<M> {
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

impl<M: SlowModel> Flow for AveragedDop853<M> {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        M::METHOD
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
