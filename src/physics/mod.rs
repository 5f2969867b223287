//! The numerical heart of the explorer: the holonomic rattleback's full model (finite Hooke
//! constant `k`), its effective limit (`k → ∞`), integrators, spin-reversal location and
//! quadrature.
//!
//! Invariants: everything here is a pure function of its inputs (no clock, no threads, no
//! randomness), so the same inputs and build give bit-identical results; replays depend on it.
//! This layer depends on std, nalgebra and serde only. It must never import a terminal crate:
//! a test fails if a file below `src/physics/` mentions one.

pub mod auto;
pub mod averaged;
pub mod budget;
pub mod effective;
pub mod flow;
pub mod integrators;
pub mod kapitza;
pub mod model;
pub mod models;
pub mod params;
pub mod plan;
pub mod quadrature;
pub mod run;

pub use integrators::{Integrator, Method, StepError};
pub use model::State;
pub use models::{LimitView, Model, ModelKind};
pub use params::{ParamError, Params, Problem, Start};
pub use plan::{DEFAULT_TOLERANCE, Resolved};
pub use run::{RunResult, RunSpec, run};
