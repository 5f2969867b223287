//! The sweep pane's state: the sweep of the current start's small parameter (issue 12: the
//! rattleback's `k`; the pendulum's `ε`), computed by the
//! worker one rung at a time after the run's own work, restarted with every restart of the run
//! while the pane is shown, stopped when it is hidden.

use super::{ComputedPane, Cx};
use crate::physics::Method;
use crate::sim::jobs::SweepSpec;
use crate::sim::{Command, JobData, JobKind, JobSpec};

/// One rung received.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepPoint {
    /// The rung's parameter (`k`, or `ε`).
    pub parameter: f64,
    /// `sup |α_k − α_eff|` (`sup |θ_ε − θ|`) over `[0, T]`.
    pub sup_error: f64,
    /// What `auto` ran.
    pub method: Method,
}

/// What the pane shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweepState {
    /// The run the points belong to.
    pub generation: u64,
    /// The rungs so far, in ladder order.
    pub points: Vec<SweepPoint>,
    /// All rungs are in.
    pub done: bool,
    /// Why the sweep stopped short.
    pub failed: Option<String>,
}

impl SweepState {
    /// The fitted log–log slope of the points so far (two at least).
    #[must_use]
    pub fn slope(&self) -> Option<f64> {
        let pts: Vec<(f64, f64)> = self
            .points
            .iter()
            .map(|p| (p.parameter, p.sup_error))
            .collect();
        crate::study::log_log_slope(&pts)
    }
}

impl ComputedPane for SweepState {
    fn kind(&self) -> JobKind {
        JobKind::Sweep
    }

    /// Forgets the points and asks for the sweep of the current start.
    fn start(&mut self, cx: &mut Cx) -> Option<Command> {
        let s = cx.settings;
        *self = Self {
            generation: cx.generation,
            ..Self::default()
        };
        let spec = SweepSpec {
            model: s.model,
            t_end: s.t_end,
            tolerance: s.tolerance,
        };
        Some(Command::start_job(cx.generation, JobSpec::Sweep(spec)))
    }

    fn stop(&mut self) -> Command {
        Command::stop_job(JobKind::Sweep, self.generation)
    }

    /// A rung, or the end of the sweep (or why it stopped short).
    fn take(&mut self, stamp: u64, data: JobData, _: &mut Cx) -> bool {
        if stamp != self.generation {
            return false;
        }
        match data {
            JobData::SweepPoint {
                parameter,
                sup_error,
                method,
            } => self.points.push(SweepPoint {
                parameter,
                sup_error,
                method,
            }),
            JobData::SweepDone { failed } => {
                self.done = true;
                self.failed = failed;
            }
            _ => return false,
        }
        true
    }
}
