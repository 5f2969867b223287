//! The integration worker: a [`Session`] (synchronous, testable) and a [`Worker`] thread around
//! it. UI to worker: [`Command`]; worker to UI: [`SimEvent`], through a bounded sink so a slow
//! terminal slows the worker instead of growing memory.
//!
//! Invariant: frame pacing never changes the trajectory. Steps are never shortened to land on
//! a frame time (only on `t_end`); samples are interpolated inside steps. The same problem,
//! method and build give the same bits whatever the frame rate, which replays rely on.
//! Imports `physics` only; never the UI.

mod engine;
mod jobs;
mod session;
mod worker;

pub use engine::{Engine, PlanBook, PlanKey, drive};
pub use session::{MAX_GRID_SAMPLES, Point, Session, SessionSpec, grid_spacing};
pub use worker::Worker;

use crate::physics::plan::Resolved;
use crate::physics::rattleback::integrators::Method;

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
    /// Compute the stiffness sweep of `problem`'s start (one rung per slice, after the run's own
    /// work), or stop computing it (`spec: None`). A restart stops it too.
    Sweep {
        /// Run this belongs to; its events carry it.
        generation: u64,
        /// What to sweep.
        spec: Option<SweepSpec>,
    },
    /// Compute the weak-* view of `problem`'s start (`γ̇² g^{3/2}` of the resolved full motion
    /// over the view's horizon), or stop (`spec: None`). A restart stops it too.
    Weak {
        /// Run this belongs to.
        generation: u64,
        /// What to compute.
        spec: Option<WeakSpec>,
    },
    /// Compute the regime map of `spec` from cell `from` on (row by row, after the run's own
    /// work), or stop (`spec: None`). A restart stops it too.
    Map {
        /// Stamp of this map, echoed in its events (the map does not depend on the run's start,
        /// so it outlives restarts that keep its spec).
        id: u64,
        /// What to compute.
        spec: Option<MapSpec>,
        /// The first cell to compute (grid order): the cells before it are already known.
        from: usize,
    },
    /// Run the comparison's partner (another preset, on the run's time axis) to its end, or
    /// stop (`spec: None`). Not stopped by a restart: the partner does not depend on the run.
    Compare {
        /// Stamp of this partner run, echoed in its event.
        id: u64,
        /// What to run.
        spec: Option<SessionSpec>,
    },
    /// Stop the worker.
    Quit,
}

/// The comparison's partner, run to its end: what the compare pane draws up to the displayed
/// time.
#[derive(Clone, Debug, PartialEq)]
pub struct PartnerRun {
    /// The plan that integrated it (journaled, so a replay runs the same).
    pub plan: Resolved,
    /// `auto`'s error estimate, when it planned.
    pub estimate: Option<f64>,
    /// Samples on its grid.
    pub samples: Vec<Point>,
    /// Its reversals, at the times a display counts them.
    pub reversals: Vec<f64>,
    /// Its second events (the celt's crossings), when the model has them.
    pub marks: Vec<f64>,
}

/// The regime map's computation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapSpec {
    /// The grid, body and horizon.
    pub grid: crate::study::map::Grid,
    /// From the limit or the full model at a `k`.
    pub source: crate::study::map::Source,
}

/// The weak-* view's computation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeakSpec {
    /// The start (the rattleback's `γ̇² g^{3/2}`, or the pendulum's `θ̇`).
    pub model: crate::physics::Model,
    /// The run's horizon (the view covers a bounded number of fast periods: `Posed::weak_view`).
    pub t_end: f64,
}

/// A sweep of the small parameter (`k`, or the pendulum's `ε`) for the explorer's sweep pane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepSpec {
    /// The start (its `k` or `ε` is replaced by each rung's).
    pub model: crate::physics::Model,
    /// Horizon.
    pub t_end: f64,
    /// `auto`'s tolerance.
    pub tolerance: f64,
}

/// Worker to UI.
#[derive(Clone, Debug, PartialEq)]
pub enum SimEvent {
    /// `auto` is being planned and verified over the whole run before anything is shown.
    Planning {
        /// Run stamp.
        generation: u64,
    },
    /// A run started; `plan` is what integrates (what `auto` resolved to).
    Started {
        /// Run stamp.
        generation: u64,
        /// The concrete plan.
        plan: Resolved,
        /// `auto`'s error estimate of the run (absent for a concrete or recorded plan).
        error_estimate: Option<f64>,
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
    /// A spin reversal (possibly ahead of the samples sent: the display counts it when it
    /// reaches its time).
    Reversal {
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
    /// A rung of the stiffness sweep.
    SweepPoint {
        /// Run stamp.
        generation: u64,
        /// The rung's parameter (`k`, or `ε`).
        parameter: f64,
        /// `sup |α_k − α_eff|` (`sup |θ_ε − θ|`) over `[0, T]`.
        sup_error: f64,
        /// What `auto` ran.
        method: Method,
    },
    /// The sweep is complete (or could not go on: `failed`).
    SweepDone {
        /// Run stamp.
        generation: u64,
        /// Why it stopped short, if it did.
        failed: Option<String>,
    },
    /// The weak-* view's data (or why it could not be computed).
    Weak {
        /// Run stamp.
        generation: u64,
        /// Sample times, evenly spaced.
        t: Vec<f64>,
        /// `γ̇² g^{3/2}` (the pendulum: `θ̇_ε`) at those times.
        pointwise: Vec<f64>,
        /// The limit's `θ` (the rattleback's constant; 0 for the pendulum).
        theta: f64,
        /// The limit's value at those times, when it is not a constant (the pendulum's `θ̇`).
        reference: Vec<f64>,
        /// Why it failed, if it did.
        failed: Option<String>,
    },
    /// Cells of the regime map, in grid order from `first`.
    MapCells {
        /// The map's stamp.
        id: u64,
        /// Index of the first cell.
        first: usize,
        /// Reversals in `(0, T]` of each cell.
        reversals: Vec<usize>,
    },
    /// The regime map is complete (or could not go on: `failed`).
    MapDone {
        /// The map's stamp.
        id: u64,
        /// Why it stopped short, if it did.
        failed: Option<String>,
    },
    /// The comparison's partner ran to its end (or why it could not).
    Partner {
        /// Its stamp.
        id: u64,
        /// The run, or why it failed.
        outcome: Result<Box<PartnerRun>, String>,
    },
    /// The integration (or `auto`'s planning) failed.
    Failed {
        /// Run stamp.
        generation: u64,
        /// Why.
        message: String,
    },
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
