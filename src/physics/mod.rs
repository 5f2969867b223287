//! The numerical heart of the explorer, headless: one folder per model and the numerics they
//! share.
//!
//! - [`models`]: the closed [`Model`] enum, the only door through which the worker, the
//!   explorer, presets and `simulate` reach a model; [`flow`]: the model-generic integration
//!   they drive (a slow coordinate, an event function, a state vector);
//! - [`rattleback`]: the holonomic rattleback (full model at finite `k`, its effective limit, the
//!   averaged model, integrators, `auto`, the cost model);
//! - [`kapitza`]: Kapitza's inverted pendulum (full model, limit, ripple, integrators, `auto`);
//! - [`celt`]: the classical rolling rattleback (Kane & Levinson), which has no limit;
//! - [`numerics`]: DOP853, compositions, roots, quadrature; [`method`]: the methods' names;
//!   [`drive`]: the one headless runner every model's `run` goes through.
//!
//! Shared vocabulary lives here, not in a model's folder: [`params::ParamError`],
//! [`plan::Resolved`], [`budget`] (the work budget and its refusal), [`flow::CHECK_EVERY`]. A
//! model's own items are reached through its folder (`physics::rattleback::…`,
//! `physics::kapitza::…`); there are no old paths (`tests/it/layering.rs` forbids them).
//!
//! Invariants: everything here is a pure function of its inputs (no clock, no threads, no
//! randomness), so the same inputs and build give bit-identical results; replays depend on it.
//! This layer depends on std, nalgebra and serde only. It must never import a terminal crate:
//! a test fails if a file below `src/physics/` mentions one.
use crate::physics::numerics::elementary::Elementary;

pub mod budget;
pub mod cell;
pub mod chart;
#[cfg(test)]
pub mod contract;
pub mod drive;
pub mod flow;
pub mod fork;
pub mod json;
pub mod method;
pub mod models;
pub mod numerics;
pub mod params;
pub mod plan;
pub mod report;
pub mod scene;
pub mod verify;

// Each scene's folder (`celt`, `kapitza`, `rattleback`, the tests' `oscillator`), declared by
// its registry line.
models::with_scenes!(scene_modules);
use models::scene_modules;

pub use method::{Method, StepError};
pub use models::{LimitView, Model, ModelKind};
pub use params::ParamError;
pub use plan::{DEFAULT_TOLERANCE, Resolved};
pub use scene::{Posed, Scene, Words};

/// A number as a person reads it: plain between 1e-4 and 1e16, in exponent form outside (never
/// the 300 digits `{}` gives `1e300`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Number(pub f64);

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() || (1e-4..1e16).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

/// The input farthest from 1 in size (what most likely overflowed a derived quantity).
#[must_use]
pub fn extreme(inputs: &[(&'static str, f64)]) -> (&'static str, f64) {
    inputs
        .iter()
        .copied()
        .filter(|(_, v)| *v != 0.0)
        .max_by(|a, b| {
            a.1.abs()
                .e_log10()
                .abs()
                .total_cmp(&b.1.abs().e_log10().abs())
        })
        .unwrap_or(inputs[0])
}
