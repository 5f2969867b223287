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
    /// Report the exact state at simulated time `t` (integrating there first).
    Checkpoint {
        /// Run this applies to.
        generation: u64,
        /// The time.
        t: f64,
    },
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
    /// The exact state asked by [`Command::Checkpoint`].
    Checkpoint {
        /// Run stamp.
        generation: u64,
        /// Its time.
        t: f64,
        /// `(gamma, alpha, gamma_dot, alpha_dot)` at `t`.
        state: [f64; 4],
        /// Reversals of the full motion up to `t`.
        reversals: usize,
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

/// Runs worker commands synchronously on `session`, handing the events to `on_event`: the
/// worker's behaviour without a thread (replay verification, cast export, tests).
pub fn drive(
    session: &mut Option<Session>,
    commands: Vec<Command>,
    on_event: &mut dyn FnMut(SimEvent),
) {
    for c in commands {
        match c {
            Command::Restart { generation, spec } => {
                let s = Session::new(generation, spec);
                on_event(SimEvent::Started {
                    generation,
                    method: s.method(),
                });
                *session = Some(s);
            }
            Command::AdvanceTo {
                generation,
                t,
                sample_dt,
            } => {
                if let Some(s) = session.as_mut().filter(|s| s.generation() == generation) {
                    s.advance(t, sample_dt, usize::MAX)
                        .0
                        .into_iter()
                        .for_each(&mut *on_event);
                }
            }
            Command::Checkpoint { generation, t } => {
                if let Some(s) = session.as_mut().filter(|s| s.generation() == generation) {
                    s.advance(t, 1.0, usize::MAX)
                        .0
                        .into_iter()
                        .for_each(&mut *on_event);
                    if let Some((state, reversals)) = s.checkpoint(t) {
                        on_event(SimEvent::Checkpoint {
                            generation,
                            t,
                            state,
                            reversals,
                        });
                    }
                }
            }
            Command::SetEffective(on) => {
                if let Some(s) = session.as_mut() {
                    s.set_effective(on);
                }
            }
            Command::Quit => {}
        }
    }
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
