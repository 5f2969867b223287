//! The integration worker: a [`Session`] (synchronous, testable) and a [`Worker`] thread around
//! it. UI to worker: [`Command`]; worker to UI: [`SimEvent`], through a bounded sink so a slow
//! terminal slows the worker instead of growing memory.
//!
//! Invariant: frame pacing never changes the trajectory. Steps are never shortened to land on
//! a frame time (only on `t_end`); samples are interpolated inside steps. The same problem,
//! method and build give the same bits whatever the frame rate, which replays rely on.
//! Imports `physics` only; never the UI.

mod engine;
pub mod jobs;
mod planner;
pub mod segments;
mod session;
mod worker;

pub use engine::{Engine, drive};
pub use jobs::{JobData, JobKind, JobSpec};
pub use planner::{PlanBook, PlanKey, Planner};
pub use session::{MAX_GRID_SAMPLES, Point, Segment, Session, SessionSpec, grid_spacing};
pub use worker::Worker;

use crate::physics::method::Method;
use crate::physics::plan::Resolved;
/// UI to worker.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Start over (cancels in-flight work at once, planning included).
    Restart {
        /// Stamp echoed in every event of this run; stale events are ignored.
        generation: u64,
        /// What to run.
        spec: SessionSpec,
    },
    /// Integrate up to simulated time `t` (samples come on the run's own grid).
    AdvanceTo {
        /// Run this applies to.
        generation: u64,
        /// Target time; a target behind the run stops it where it is.
        t: f64,
    },
    /// Integrate the effective overlay too (from `t = 0`, catching up), or stop doing so.
    SetEffective {
        /// On or off.
        on: bool,
        /// Stamp of this life of the overlay, echoed in its samples and reversals.
        epoch: u64,
    },
    /// Report the exact state at simulated time `t` (integrating there first).
    Checkpoint {
        /// Run this applies to.
        generation: u64,
        /// The time.
        t: f64,
    },
    /// Start a pane's job (`spec`), or stop the one of `kind` (`spec: None`). A job of a kind
    /// that [`JobKind::ends_with_run`] also stops when the run restarts.
    Job {
        /// Which job.
        kind: JobKind,
        /// Stamp of this life of the job (the run's generation, or the pane's own stamp),
        /// echoed in its answers; older answers are ignored.
        stamp: u64,
        /// What to compute.
        spec: Option<JobSpec>,
    },
    /// A plan `auto` resolved elsewhere for `key`: a follower passes on the lecturer's plan
    /// lines as they are written. Its verification ahead, which waits for them
    /// ([`PlanBook::awaits`]), takes the plan instead of verifying it again. The same bits come
    /// out: `auto` is deterministic, and the recording is the lecture.
    Book {
        /// What it was resolved for.
        key: PlanKey,
        /// The plan.
        plan: Resolved,
        /// Its error estimate.
        estimate: Option<f64>,
    },
    /// Stop waiting for plans from elsewhere (the lecture ended, or the follower forked): what
    /// is not in the book is verified here again.
    Release,
    /// Stop the worker.
    Quit,
}

/// Worker to UI.
#[derive(Clone, Debug, PartialEq)]
pub enum SimEvent {
    /// `auto` is being planned and verified over the whole run before anything is shown.
    Planning {
        /// Run stamp.
        generation: u64,
    },
    /// How far `auto`'s planning has come: its `run`-th integration (probes, conditioning, the
    /// run and its companions, refinements; counted from 1) has reached `percent` of the
    /// horizon. Sent while planning, at most once per whole percent.
    PlanProgress {
        /// Run stamp.
        generation: u64,
        /// Which of `auto`'s integrations.
        run: u32,
        /// How far it has reached, in whole percent of the horizon.
        percent: u8,
    },
    /// A run started; `plan` is what integrates (what `auto` resolved to).
    Started {
        /// Run stamp.
        generation: u64,
        /// The concrete plan.
        plan: Resolved,
        /// `auto`'s error estimate of the run (absent for a concrete or recorded plan).
        error_estimate: Option<f64>,
        /// The horizon the plan was verified for: the run's end, or the end of its first
        /// segment when `auto` verifies it in segments ([`segments`]).
        until: f64,
    },
    /// `auto` verified, ahead of the display, the plan of the next segment of a run verified in
    /// segments: it is shown after `from`, and covers `[0, until]`.
    Verified {
        /// Run stamp.
        generation: u64,
        /// Where its segment starts.
        from: f64,
        /// Its horizon.
        until: f64,
        /// The plan.
        plan: Resolved,
        /// `auto`'s error estimate over `[0, until]`.
        error_estimate: Option<f64>,
    },
    /// The verification ahead could not verify the run beyond `at` (over the budget, or a
    /// failed run): what is verified is shown, and the run fails when it gets there.
    Stops {
        /// Run stamp.
        generation: u64,
        /// Where the run stops.
        at: f64,
        /// Why, as the failure will say it.
        message: String,
    },
    /// How far the verification ahead has come: its `run`-th integration for the horizon
    /// `until` has reached `percent` of it.
    Ahead {
        /// Run stamp.
        generation: u64,
        /// The horizon being verified.
        until: f64,
        /// Which of `auto`'s integrations.
        run: u32,
        /// How far it has reached, in whole percent of the horizon.
        percent: u8,
    },
    /// New samples of the full (and, if enabled, effective) motion.
    Samples {
        /// Run stamp.
        generation: u64,
        /// Overlay stamp of the effective samples.
        epoch: u64,
        /// Full model samples, on the run's grid.
        full: Vec<Point>,
        /// Effective model samples on the same grid (empty when the overlay is off).
        effective: Vec<Point>,
        /// Time of the last full sample, if any.
        t: Option<f64>,
        /// Steps taken so far by the full integrator.
        steps: u64,
    },
    /// The scene's counted event: a spin reversal (the rattleback's, the celt's), a swing of the
    /// pendulum; possibly ahead of the samples sent: the display counts it when it reaches its
    /// time.
    Counted {
        /// Run stamp.
        generation: u64,
        /// Overlay stamp (for effective reversals).
        epoch: u64,
        /// Its time.
        t: f64,
        /// Of the effective motion (else the full one).
        effective: bool,
    },
    /// A second event of the full motion found by the flow inside a step (the celt's spin
    /// crossings; possibly ahead of the samples sent).
    Mark {
        /// Run stamp.
        generation: u64,
        /// Its time.
        t: f64,
    },
    /// The exact state asked by [`Command::Checkpoint`].
    Checkpoint {
        /// Run stamp.
        generation: u64,
        /// Its time.
        t: f64,
        /// `(gamma, alpha, gamma_dot, alpha_dot)` at `t`.
        state: Vec<f64>,
        /// Reversals of the full motion up to `t`.
        reversals: usize,
    },
    /// The run reached `t_end`.
    Finished {
        /// Run stamp.
        generation: u64,
    },
    /// A pane's job answered.
    Job {
        /// The stamp of the job's order.
        stamp: u64,
        /// What it computed.
        data: JobData,
    },
    /// The integration (or `auto`'s planning) failed.
    Failed {
        /// Run stamp.
        generation: u64,
        /// Why.
        message: String,
    },
}

impl Command {
    /// Starts the job that computes `spec`, stamped `stamp` (it replaces the job of its kind).
    #[must_use]
    pub fn start_job(stamp: u64, spec: JobSpec) -> Self {
        Self::Job {
            kind: spec.kind(),
            stamp,
            spec: Some(spec),
        }
    }

    /// Stops the job of `kind`.
    #[must_use]
    pub fn stop_job(kind: JobKind, stamp: u64) -> Self {
        Self::Job {
            kind,
            stamp,
            spec: None,
        }
    }
}

impl SimEvent {
    /// The method of a `Started` event.
    #[must_use]
    pub fn method(&self) -> Option<Method> {
        match self {
            Self::Started { plan, .. } => Some(plan.method),
            _ => None,
        }
    }
}
