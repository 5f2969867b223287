//! `auto` for the pendulum: the limit with its ripple (`effective-corrected`) when its model
//! error is predicted below the tolerance, else the full model by `dop853`. DOP853's tolerance
//! is per step and the full model's global error grows with the number of fast periods `n`
//! (measured: 90× the tolerance after 80 periods of an unstable start), so the resolved run is
//! asked for `tol / (10 sqrt(1 + n))`; the limit is asked for a tenth of the tolerance.
//!
//! The limit's error after the ripple is added back is O(ε²) (`limit`); it grows with the
//! horizon like a phase error. The prediction `ε² (b² + |a| + 1)² (1 + t_end)` bounds what
//! `tests/kapitza.rs` measures against the Taylor-series references on the shipped and
//! reference cases (measured/predicted below 0.3 there), so `auto` never picks the limit where
//! it would miss the tolerance. The full model's cost grows like `1/ε` and the limit's does not:
//! as `ε` shrinks `auto` switches to the limit and its cost stops growing.

use super::Problem;
use crate::physics::integrators::{Method, Settings};

/// What `auto` chose, and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The concrete method.
    pub method: Method,
    /// Its settings.
    pub settings: Settings,
    /// The limit's predicted model error over the run.
    pub predicted_model_error: f64,
}

/// The limit's predicted model error (see the module's documentation).
#[must_use]
pub fn model_error(problem: &Problem, t_end: f64) -> f64 {
    let p = problem.params();
    let scale = p.b * p.b + p.a.abs() + 1.0;
    (p.epsilon * scale).powi(2) * (1.0 + t_end)
}

/// Resolves `auto` for `problem` at `tolerance` over `[0, t_end]`.
#[must_use]
pub fn resolve(problem: &Problem, tolerance: f64, t_end: f64) -> Choice {
    let predicted = model_error(problem, t_end);
    let (method, asked) = if predicted <= tolerance {
        (Method::EffectiveCorrected, tolerance / 10.0)
    } else {
        let periods = t_end / (2.0 * std::f64::consts::PI * problem.params().epsilon);
        (Method::Dop853, tolerance / (10.0 * (1.0 + periods).sqrt()))
    };
    Choice {
        method,
        settings: Settings {
            tolerance: asked.max(1e-14),
            step: None,
        },
        predicted_model_error: predicted,
    }
}
