//! What a resolved plan is, for every model: plain data (method, tolerance, step) that
//! recordings store and replay integrates. Each model resolves `auto` its own way
//! (`rattleback::plan`, `kapitza::plan`).

use serde::{Deserialize, Serialize};

use super::method::{Method, Settings};

/// Tolerance when neither the command line, the preset nor the explorer gives one: one value
/// for `simulate` and the explorer.
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// The concrete integration of a run: what the integrator is built with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Resolved {
    /// A concrete method (never `auto`).
    pub method: Method,
    /// Tolerance handed to the integrator (adaptive methods; picks the default step of
    /// fixed-step ones when `step` is absent).
    pub tolerance: f64,
    /// Fixed step, if any.
    pub step: Option<f64>,
}

impl Resolved {
    /// The integrator settings.
    #[must_use]
    pub fn settings(&self) -> Settings {
        Settings {
            tolerance: self.tolerance,
            step: self.step,
        }
    }
}

/// How `auto` is resolved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AutoPolicy {
    /// Plan, run, verify against a finer companion and refine until the estimate meets the
    /// tolerance; the finer run's settings are returned (what `simulate` reports).
    #[default]
    Verified,
    /// The first plan, unverified: how session files of format 1 were recorded. Only replay of
    /// such files uses it.
    Legacy,
}
