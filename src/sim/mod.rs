//! The integration worker: a [`Session`] (synchronous, testable) and a [`Worker`] thread around
//! it. UI to worker: [`Command`]; worker to UI: [`SimEvent`], through a bounded sink so a slow
//! terminal slows the worker instead of growing memory.
//!
//! Invariant: frame pacing never changes the trajectory. Steps are never shortened to land on
//! a frame time (only on `t_end`); samples are interpolated inside steps. The same problem,
//! method and build give the same bits whatever the frame rate, which replays rely on.
//! Imports `physics` only; never the UI.

mod session;
mod worker;

pub use session::{Point, Session, SessionSpec};
pub use worker::Worker;

use crate::physics::Problem;
use crate::physics::integrators::Method;

/// UI to worker.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Start over (cancels in-flight work at once).
    Restart {
        /// Stamp echoed in every event of this run; stale events are ignored.
        generation: u64,
        /// What to run.
        spec: SessionSpec,
    },
    /// Integrate up to simulated time `t`, sampling every `sample_dt`.
    AdvanceTo {
        /// Run this applies to.
        generation: u64,
        /// Target time.
        t: f64,
        /// Spacing of the samples sent back.
        sample_dt: f64,
    },
    /// Integrate the effective overlay too, or stop doing so.
    SetEffective(bool),
    /// Stop the worker.
    Quit,
}

/// Worker to UI.
#[derive(Clone, Debug, PartialEq)]
pub enum SimEvent {
    /// A run started; `method` is what integrates (what `auto` chose).
    Started {
        /// Run stamp.
        generation: u64,
        /// The concrete method.
        method: Method,
    },
    /// New samples of the full (and, if enabled, effective) motion, up to `t`.
    Samples {
        /// Run stamp.
        generation: u64,
        /// Full model samples.
        full: Vec<Point>,
        /// Effective model samples (empty when the overlay is off).
        effective: Vec<Point>,
        /// Time reached by the samples.
        t: f64,
        /// Steps taken so far by the full integrator.
        steps: u64,
    },
    /// A spin reversal.
    Reversal {
        /// Run stamp.
        generation: u64,
        /// Its time.
        t: f64,
        /// Of the effective motion (else the full one).
        effective: bool,
    },
    /// The run reached `t_end`.
    Finished {
        /// Run stamp.
        generation: u64,
    },
    /// The integration failed.
    Failed {
        /// Run stamp.
        generation: u64,
        /// Why.
        message: String,
    },
}

/// Convenience: a session spec for a problem.
#[must_use]
pub fn spec(
    problem: Problem,
    method: Method,
    tolerance: f64,
    t_end: f64,
    effective: bool,
) -> SessionSpec {
    SessionSpec {
        problem,
        method,
        tolerance,
        t_end,
        effective,
    }
}
