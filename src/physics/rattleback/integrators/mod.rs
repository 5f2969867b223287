//! Integrators of the full and effective models behind one interface.
//!
//! Every method is deterministic: the same problem, settings and build give bit-identical
//! results. Each file holds one method and states its order, whether it is symplectic and its
//! cost per step. Reversals (sign changes of `α̇`) are located inside a step by each method's
//! own interpolant or closed-form sub-flow (`Flow::locate_event`).
use crate::physics::numerics::elementary::Elementary;

mod averaged;
mod effective;
mod full;
pub mod full_taylor;
mod rk4;
pub mod splitting;

use crate::physics::method::{DEFAULT_STEP_BUDGET, Method, StepError};
pub use averaged::{Ending, together};

use super::model::State;
use super::params::Problem;
use crate::physics::flow::Flow;
use crate::physics::method::{Asked, TimeSum};

/// The [`Flow`] methods every rattleback integrator draws from its own `state()` (now) and
/// `interpolate(t)` (inside the last step), both `(γ, α, γ̇, α̇)`: `q = α`, the fast
/// coordinate `γ`, the state vector in that order.
macro_rules! drawn_from_state {
    () => {
        fn sample(&mut self, t: f64) -> crate::physics::flow::Sample {
            let y = if t >= Flow::time(self) {
                self.state()
            } else {
                self.interpolate(t)
            };
            super::drawn(&y)
        }
        fn state_at(&mut self, t: f64) -> Vec<f64> {
            let y = if t >= Flow::time(self) {
                self.state()
            } else {
                self.interpolate(t)
            };
            y.iter().copied().collect()
        }
    };
}
use drawn_from_state;

/// What is drawn of a state `(γ, α, γ̇, α̇)`.
fn drawn(y: &State) -> crate::physics::flow::Sample {
    use super::model::{ALPHA, ALPHA_DOT, GAMMA};
    crate::physics::flow::Sample {
        q: y[ALPHA],
        q_dot: y[ALPHA_DOT],
        fast: y[GAMMA],
        lean: None,
    }
}

/// Default fixed step for `method` at `tolerance` over `[0, t_end]`: `c · tol^{1/p} / ν` with
/// `ν` the fastest rate of the problem (the fast frequency, or the slow rate at small `k`), but
/// never more than [`DEFAULT_STEP_BUDGET`] steps: a low-order method at a tight tolerance would
/// otherwise ask for billions.
#[must_use]
pub fn default_step(method: Method, problem: &Problem, tolerance: f64, t_end: f64) -> f64 {
    let p = problem.params();
    let s = problem.start();
    let y0 = super::model::initial_state(s);
    let e = super::model::energy(p, &y0);
    let slow = (2.0 * e / p.ix.min(p.iy).min(p.iz)).sqrt();
    let rate = p.omega_max().max(slow).max(1e-3);
    let (c, order) = match method {
        Method::Rk4 => (0.5, 4.0),
        Method::Strang => (0.3, 2.0),
        // Phase-locked steps: error ≈ 0.05 h² whatever k (docs/physics.md §4), so h = sqrt(tol/0.05).
        Method::Locked => return (tolerance / 0.05).sqrt().max(t_end / DEFAULT_STEP_BUDGET),
        Method::Yoshida4 => (0.6, 4.0),
        Method::BlanesMoan4 => (1.2, 4.0),
        Method::Yoshida6 => (1.0, 6.0),
        Method::Suzuki8 => (1.5, 8.0),
        Method::Dop853
        | Method::Dop853Projected
        | Method::Taylor
        | Method::Effective
        | Method::EffectiveCorrected
        | Method::Averaged2
        | Method::Averaged3
        | Method::Auto => (1.0, 8.0),
    };
    (c * tolerance.e_powf(1.0 / order) / rate).max(t_end / DEFAULT_STEP_BUDGET)
}

/// Builds a ready-to-step integrator at `t = 0`; `t_end` is the horizon a default step is
/// budgeted for; `time_sum` is how the fixed-step methods add their steps (the adaptive ones
/// take far fewer steps and add them plainly).
///
/// # Errors
/// [`StepError::Unplanned`] for `auto`, which is resolved above the integrators
/// (`physics::plan`), so this layer never calls back up into the planner.
pub fn build(
    problem: &Problem,
    ask: &Asked,
    time_sum: TimeSum,
) -> Result<Box<dyn Flow>, StepError> {
    let (method, settings, t_end) = (ask.method, ask.settings(), ask.t_end);
    let step = settings
        .step
        .unwrap_or_else(|| default_step(method, problem, settings.tolerance, t_end));
    Ok(match method {
        Method::Rk4 => Box::new(rk4::Rk4::new(problem, step).with_time_sum(time_sum)),
        Method::Dop853 => Box::new(full::FullDop853::new(problem, settings.tolerance)),
        Method::Taylor => Box::new(full::FullTaylor::new(problem, settings.tolerance)),
        Method::Strang
        | Method::Yoshida4
        | Method::BlanesMoan4
        | Method::Yoshida6
        | Method::Suzuki8 => Box::new(
            splitting::Splitting::new(problem, splitting::Composition::of(method), step)
                .with_time_sum(time_sum),
        ),
        Method::Locked => {
            Box::new(splitting::Splitting::phase_locked(problem, step).with_time_sum(time_sum))
        }
        Method::Effective => Box::new(effective::EffectiveDop853::new(
            problem,
            settings.tolerance,
            false,
        )),
        Method::EffectiveCorrected => Box::new(effective::EffectiveDop853::new(
            problem,
            settings.tolerance,
            true,
        )),
        Method::Averaged2 | Method::Averaged3 => {
            let parameter = crate::physics::rattleback::averaged::expansion_parameter(problem);
            let limit = crate::physics::rattleback::averaged::VALIDITY_LIMIT;
            if parameter.is_nan() || parameter > limit {
                return Err(StepError::OutsideModel { parameter, limit });
            }
            if method == Method::Averaged2 {
                Box::new(averaged::Averaged2Dop853::new(problem, settings.tolerance))
            } else {
                Box::new(averaged::Averaged3Dop853::new(problem, settings.tolerance))
            }
        }
        Method::Auto => return Err(StepError::Unplanned),
        Method::Dop853Projected => {
            return Err(StepError::NotOffered {
                method: method.name(),
                model: "rattleback",
            });
        }
    })
}
