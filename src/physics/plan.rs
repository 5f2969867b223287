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

/// What a model is asked to plan: the method (perhaps `auto`), its tolerance and horizon, how
/// `auto` is resolved and the work budget its probes must stay within (predicted seconds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanRequest {
    /// The method asked.
    pub method: Method,
    /// The tolerance asked.
    pub tolerance: f64,
    /// The horizon.
    pub t_end: f64,
    /// How `auto` is resolved.
    pub policy: AutoRules,
    /// The work budget of `auto`'s probes and verification.
    pub budget: f64,
}

impl PlanRequest {
    /// `asked`, verified, within the default budget (what a study asks).
    #[must_use]
    pub const fn verified(asked: &super::method::Asked) -> Self {
        Self {
            method: asked.method,
            tolerance: asked.tolerance,
            t_end: asked.t_end,
            policy: AutoRules::Verified,
            budget: super::budget::BUDGET_SECONDS,
        }
    }
}

/// How `auto` is resolved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AutoRules {
    /// Plan, run, verify against a finer companion and refine until the estimate meets the
    /// tolerance; the finer run's settings are returned (what `simulate` reports).
    #[default]
    Verified,
    /// The first plan, unverified: how session files of format 1 were recorded. Only replay of
    /// such files uses it.
    Legacy,
}

/// Why `auto` stopped short of the tolerance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Shortfall {
    /// The round-off floor: rounding alone is above the tolerance (said after the first run
    /// where a scene measures it), or a refinement no longer halved the estimate (round-off,
    /// or an ill-conditioned start).
    Floor,
    /// The adaptive tolerance reached its clamp (1e-14) and no other method is predicted to do
    /// better.
    Clamped,
    /// The most refinements `auto` allows were not enough.
    Refinements,
    /// The next refinement would take the work past the time `auto` allows itself.
    Time,
    /// The limit's model error (the averaged model's at this `k`, the pendulum's at this `ε`)
    /// is above the tolerance, and resolving the fast motion is predicted to do no better.
    Model,
}

impl Shortfall {
    /// Words for people.
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Self::Floor => {
                "the round-off floor: an ill-conditioned start, or rounding over many steps; a refinement would not lower the estimate"
            }
            Self::Clamped => "the tolerance cannot be tightened further (1e-14)",
            Self::Refinements => "the refinements ran out",
            Self::Time => "a further refinement would take too long",
            Self::Model => {
                "the limit's model error here (the averaged model's at this k, the pendulum's at this epsilon) is above it, and resolving would do no better"
            }
        }
    }
}

/// What resolving a method found, with `auto`'s reasoning when it was asked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resolution {
    /// What to integrate.
    pub plan: Resolved,
    /// `auto`'s error estimate (the verified run's; the pendulum's predicted one), absent for
    /// a concrete method.
    pub estimate: Option<f64>,
    /// Why `auto`'s estimate misses the tolerance, when it does.
    pub shortfall: Option<Shortfall>,
    /// The part of the estimate that rounding alone sets, where the scene measures it (the
    /// rattleback's verified `auto`).
    pub floor: Option<f64>,
}

impl Resolution {
    /// A plan taken as it is, unverified (a method asked by name, or a frozen rule's plan):
    /// no estimate, no shortfall.
    #[must_use]
    pub const fn unverified(plan: Resolved) -> Self {
        Self {
            plan,
            estimate: None,
            shortfall: None,
            floor: None,
        }
    }

    /// A method asked by name at `tolerance`: its own plan.
    #[must_use]
    pub const fn named(method: Method, tolerance: f64) -> Self {
        Self::unverified(Resolved {
            method,
            tolerance,
            step: None,
        })
    }
}
