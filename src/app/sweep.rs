//! The sweep pane's state: the sweep of the current start's small parameter (issue 12: the
//! rattleback's `k`; the pendulum's `ε`), computed by the
//! worker one rung at a time after the run's own work, restarted with every restart of the run
//! while the pane is shown, stopped when it is hidden.

use crate::physics::Method;
use crate::sim::{Command, SweepSpec};

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
    /// Forgets the points and asks the worker for a sweep of `spec` for run `generation`.
    pub fn start(&mut self, generation: u64, spec: SweepSpec) -> Command {
        *self = Self {
            generation,
            ..Self::default()
        };
        Command::Sweep {
            generation,
            spec: Some(spec),
        }
    }

    /// Stops the worker's sweep.
    #[must_use]
    pub fn stop(&self) -> Command {
        Command::Sweep {
            generation: self.generation,
            spec: None,
        }
    }

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

    /// Takes a rung of run `generation`; whether it was this sweep's.
    pub fn on_point(&mut self, generation: u64, point: SweepPoint) -> bool {
        if generation != self.generation {
            return false;
        }
        self.points.push(point);
        true
    }

    /// The worker finished (or gave up on) run `generation`'s sweep.
    pub fn on_done(&mut self, generation: u64, failed: Option<String>) -> bool {
        if generation != self.generation {
            return false;
        }
        self.done = true;
        self.failed = failed;
        true
    }
}
