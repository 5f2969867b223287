//! The numerical heart of the explorer, headless: one folder per model and the numerics they
//! share.
//!
//! - [`models`]: the closed [`Model`] enum, the only door through which the worker, the
//!   explorer, presets and `simulate` reach a model; [`flow`]: the model-generic integration
//!   they drive (a slow coordinate, an event function, a state vector);
//! - [`rattleback`]: the holonomic rattleback (full model at finite `k`, its effective limit, the
//!   averaged model, integrators, `auto`, the cost model);
//! - [`kapitza`]: Kapitza's inverted pendulum (full model, limit, ripple, integrators, `auto`);
//! - [`numerics`]: DOP853, compositions, roots, quadrature; [`method`]: the methods' names.
//!
//! The rattleback came first: its modules are also reachable at their old paths
//! (`physics::effective`, `physics::integrators`, …), which the rest of the crate uses.
//!
//! Invariants: everything here is a pure function of its inputs (no clock, no threads, no
//! randomness), so the same inputs and build give bit-identical results; replays depend on it.
//! This layer depends on std, nalgebra and serde only. It must never import a terminal crate:
//! a test fails if a file below `src/physics/` mentions one.

pub mod flow;
pub mod kapitza;
pub mod method;
pub mod models;
pub mod numerics;
pub mod rattleback;

pub use numerics::quadrature;
pub use rattleback::{auto, averaged, budget, effective, integrators, model, params, plan, run};

pub use method::{Method, StepError};
pub use model::State;
pub use models::{LimitView, Model, ModelKind};
pub use params::{ParamError, Params, Problem, Start};
pub use plan::{DEFAULT_TOLERANCE, Resolved};
pub use run::{RunResult, RunSpec, run};

/// The input farthest from 1 in size (what most likely overflowed a derived quantity).
#[must_use]
pub fn extreme(inputs: &[(&'static str, f64)]) -> (&'static str, f64) {
    inputs
        .iter()
        .copied()
        .filter(|(_, v)| *v != 0.0)
        .max_by(|a, b| a.1.abs().log10().abs().total_cmp(&b.1.abs().log10().abs()))
        .unwrap_or(inputs[0])
}
