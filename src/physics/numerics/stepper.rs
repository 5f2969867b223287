//! What a full model's flow needs of its integrator, whichever it is (DOP853 on any field, the
//! Taylor series of a scene): it steps, interpolates inside its last step and counts its work.
//! [`FullCore`] adds how to start it on a scene's model (one trait for every scene, issue 69:
//! each scene had its own copy).

use nalgebra::SVector;

use super::dop853::{Dop853, Field, Stats};
use crate::physics::method::{Method, StepError};

/// The integrator of a scene's full-model flow (DOP853, or the Taylor series) on the scene's
/// parameters `P`, and how it starts.
pub trait FullCore<const N: usize, P>: Stepper<N> {
    /// The method it is.
    const METHOD: Method;
    /// Starts the full model of `params` at `(0, y0)` with tolerance `tol`.
    fn start(params: &P, y0: SVector<f64, N>, tol: f64) -> Self;
}

/// An integrator of an `N`-dimensional state.
pub trait Stepper<const N: usize>: Clone + Send + 'static {
    /// Current time.
    fn time(&self) -> f64;
    /// Start of the last step.
    fn time_prev(&self) -> f64;
    /// Current state.
    fn state(&self) -> SVector<f64, N>;
    /// The last step's interpolant at `t` in `[time_prev, time]`.
    fn interpolate(&mut self, t: f64) -> SVector<f64, N>;
    /// One step, never past `t_limit`.
    ///
    /// # Errors
    /// As the integrator's.
    fn step(&mut self, t_limit: f64) -> Result<(), StepError>;
    /// Work counters.
    fn stats(&self) -> Stats;
}

impl<const N: usize, F: Field<N> + Clone + Send + 'static> Stepper<N> for Dop853<N, F> {
    fn time(&self) -> f64 {
        Dop853::time(self)
    }
    fn time_prev(&self) -> f64 {
        Dop853::time_prev(self)
    }
    fn state(&self) -> SVector<f64, N> {
        Dop853::state(self)
    }
    fn interpolate(&mut self, t: f64) -> SVector<f64, N> {
        Dop853::interpolate(self, t)
    }
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        Dop853::step(self, t_limit)
    }
    fn stats(&self) -> Stats {
        Dop853::stats(self)
    }
}

/// The largest gap between `a`'s dense output at the midpoints of its steps and `b`'s, and
/// between their states at `t_end`, both started alike (the scenes' tests of their series).
///
/// # Panics
/// When a step fails.
#[cfg(test)]
pub fn gaps<const N: usize>(
    a: &mut impl Stepper<N>,
    b: &mut impl Stepper<N>,
    t_end: f64,
) -> (f64, f64) {
    let mut worst: f64 = 0.0;
    while a.time() < t_end {
        a.step(t_end).unwrap();
        let mid = 0.5 * (a.time_prev() + a.time());
        while b.time() < mid {
            b.step(t_end).unwrap();
        }
        worst = worst.max((a.interpolate(mid) - b.interpolate(mid)).abs().max());
    }
    while b.time() < t_end {
        b.step(t_end).unwrap();
    }
    (worst, (a.state() - b.state()).abs().max())
}
