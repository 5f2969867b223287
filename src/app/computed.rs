//! The panes the worker computes for (the stiffness sweep, the weak-* view): starting and
//! stopping their computations with the pane and the run.

use super::panes::Pane;
use super::{App, Effect};

impl App {
    /// Shows or hides a pane the worker computes for (sweep, weak-*): shown, its computation
    /// starts; hidden, it stops.
    pub(super) fn toggle_computed(&mut self, pane: Pane) -> Vec<Effect> {
        self.view.panes.toggle(pane);
        let on = self.view.panes.shows(pane);
        let command = match (pane, on) {
            (Pane::Sweep, true) => self.start_sweep(),
            (Pane::Sweep, false) => self.sweep.stop(),
            (_, true) => self.start_weak(),
            (_, false) => self.weak.stop(),
        };
        vec![Effect::Sim(command)]
    }

    /// Asks the worker for the weak-* view of the current settings.
    pub(super) fn start_weak(&mut self) -> crate::sim::Command {
        let s = &self.scenario.settings;
        let spec = crate::sim::WeakSpec {
            problem: s.problem(),
            t_end: s.t_end,
        };
        self.weak.start(self.run.generation, spec)
    }
    /// Asks the worker for the sweep of the current settings.
    pub(super) fn start_sweep(&mut self) -> crate::sim::Command {
        let s = &self.scenario.settings;
        let spec = crate::sim::SweepSpec {
            problem: s.problem(),
            t_end: s.t_end,
            tolerance: s.tolerance,
        };
        self.sweep.start(self.run.generation, spec)
    }
}
