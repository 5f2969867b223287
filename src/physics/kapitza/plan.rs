//! `auto` for the pendulum: the limit with its ripple (`effective-corrected`) when its model
//! error is predicted below the tolerance, else the full model resolved by `dop853`; when
//! neither can meet the tolerance, the one predicted closer, with `met = false` and its
//! estimate (`simulate` reports both, the explorer's status bar shows `✗ tol missed`).
//!
//! - **The limit's model error** after the ripple is added back is O(ε²) and grows with the
//!   horizon like a phase error: predicted `ε² (b² + |a| + 1)² (1 + t_end)`, which bounds what
//!   `tests/it/kapitza.rs` measures against the Taylor-series references (measured/predicted 0.03 to
//!   0.24 there). It is integrated at 1e-4 of the tolerance (DOP853's tolerance is per step;
//!   the global error of the slow limit reaches 100 times it on a growing motion), and that
//!   integration error is added to the estimate.
//! - **The resolved run**: DOP853's tolerance is per step and the global error grows with the
//!   number of fast periods `n` (measured: 90× the tolerance after 80 periods of an unstable
//!   start, an error that growing motions amplify), so it is asked for `tol / (100 sqrt(1 + n))`. Rounding sets a floor that no
//!   tolerance lowers: measured 1.2e-9 after 8 000 periods and 1.2e-8 after 80 000 (`rattleback
//!   bench --only kapitza`) on a stable start, 5.5e-9 after 8 000 on an unstable one; predicted
//!   `1e-12 n`.
//!
//! The full model's cost grows like `1/ε` and the limit's does not: as `ε` shrinks `auto`
//! switches to the limit and its cost stops growing.

use super::Problem;
use crate::physics::method::{Method, Settings};

/// What `auto` chose, and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The concrete method.
    pub method: Method,
    /// Its settings.
    pub settings: Settings,
    /// The limit's predicted model error over the run.
    pub predicted_model_error: f64,
    /// The error the chosen run is expected to stay within (its target, or its floor).
    pub estimate: f64,
    /// Whether `estimate` meets the tolerance.
    pub met: bool,
}

/// Rounding floor of a resolved run, per fast period.
pub const ROUNDING_PER_PERIOD: f64 = 1e-12;

/// The limit's predicted model error (see the module's documentation).
#[must_use]
pub fn model_error(problem: &Problem, t_end: f64) -> f64 {
    let p = problem.params();
    let scale = p.b * p.b + p.a.abs() + 1.0;
    (p.epsilon * scale).powi(2) * (1.0 + t_end)
}

/// Fast periods over `[0, t_end]`.
fn periods(problem: &Problem, t_end: f64) -> f64 {
    t_end / (2.0 * std::f64::consts::PI * problem.params().epsilon)
}

/// Resolves `auto` for `problem` at `tolerance` over `[0, t_end]`.
#[must_use]
pub fn resolve(problem: &Problem, tolerance: f64, t_end: f64) -> Choice {
    let model = model_error(problem, t_end);
    let n = periods(problem, t_end);
    let floor = ROUNDING_PER_PERIOD * n;
    // The limit integrated at 1e-4 of the tolerance: its global error stays below 1e-2 of it
    // (at most 100× DOP853's per-step tolerance, which growing motions reach).
    let limit_tolerance = (tolerance * 1e-4).max(1e-14);
    let limit_estimate = model + 100.0 * limit_tolerance;
    let limit = |met| Choice {
        method: Method::EffectiveCorrected,
        settings: Settings {
            tolerance: limit_tolerance,
            step: None,
        },
        predicted_model_error: model,
        estimate: limit_estimate,
        met,
    };
    if limit_estimate <= tolerance {
        return limit(true);
    }
    if floor > tolerance && limit_estimate < floor {
        return limit(false);
    }
    Choice {
        method: Method::Dop853,
        settings: Settings {
            tolerance: (tolerance / (100.0 * (1.0 + n).sqrt())).max(1e-14),
            step: None,
        },
        predicted_model_error: model,
        estimate: tolerance.max(floor),
        met: floor <= tolerance,
    }
}
