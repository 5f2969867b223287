//! Spin-reversal detection: a reversal is a sign change of `α̇` at `t > 0`.
//!
//! The tracker remembers the last nonzero sign of `α̇`, so a start with `α̇0 = 0` is not a
//! reversal and a step ending exactly on zero is neither missed nor counted twice. At most one
//! reversal is reported per step; its time comes from the method's own locator.

use super::Integrator;
use crate::physics::flow::sign;

/// Follows the sign of `α̇` from step to step.
#[derive(Clone, Copy, Debug, Default)]
pub struct ReversalTracker {
    last_sign: f64,
}

impl ReversalTracker {
    /// Starts from the initial `α̇` (zero means no sign yet).
    #[must_use]
    pub fn new(alpha_dot0: f64) -> Self {
        Self {
            last_sign: sign(alpha_dot0),
        }
    }

    /// Checks the step just taken; returns the reversal time inside it, if any.
    pub fn after_step(&mut self, integrator: &mut dyn Integrator) -> Option<f64> {
        let now = sign(integrator.alpha_dot());
        if now == 0.0 {
            return None;
        }
        // Signs are exactly -1, 0 or 1.
        #[allow(clippy::float_cmp)]
        let reversed = self.last_sign != 0.0 && now != self.last_sign;
        self.last_sign = now;
        reversed.then(|| integrator.locate_alpha_dot_zero())
    }
}
