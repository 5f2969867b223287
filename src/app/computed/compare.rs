//! The comparison (`C`, `rattleback compare A B`, a lesson's `partner`): a second preset, the
//! partner, run by the worker over the run's own window and drawn beside the run on one time
//! axis, each with its reversal ticks and its own status line. The paper's contrast on one
//! screen: the holonomic rattleback reversing beside the classical rolling celt.
//!
//! The partner is computed to its end at once (it is short: the budget refuses one that is
//! not) and shown up to the displayed time, so what the pane shows depends on the displayed
//! time only, never on how far the worker got: a recording and its replay show the same.

use super::{ComputedPane, Cx};
use crate::app::journal::{Compared, Event};
use crate::app::panes::Pane;
use crate::app::{App, Effect, Message, Scenario};
use crate::scenario::Preset;
use crate::scenario::text::clean;
use crate::sim::jobs::PartnerRun;
use crate::sim::{Command, JobData, JobKind, JobSpec, SessionSpec};

/// The partner chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct Partner {
    /// Its preset.
    pub preset: Preset,
    /// Its scenario (name cleaned, settings).
    pub scenario: Scenario,
}

/// The comparison's state: the partner, its run, and which run that is.
#[derive(Clone, Debug, Default)]
pub struct CompareState {
    /// The partner, once chosen.
    pub partner: Option<Partner>,
    /// What the worker was last asked to run (the partner over the run's window).
    asked: Option<SessionSpec>,
    /// Stamp of the partner run asked last; older answers are ignored.
    id: u64,
    /// The partner's run, or why it failed; `None` while it is computed.
    pub outcome: Option<Result<Box<PartnerRun>, String>>,
}

impl CompareState {
    /// The worker's spec of the partner over `window` (the run's `t_end`).
    fn spec(&self, window: f64) -> Option<SessionSpec> {
        let partner = self.partner.as_ref()?;
        let mut scenario = partner.scenario.clone();
        let mut settings = scenario.settings;
        settings.t_end = window;
        scenario.set(settings);
        Some(scenario.spec(false))
    }

    /// The partner's spec as run (for its plan's journal key).
    #[must_use]
    pub fn asked(&self) -> Option<&SessionSpec> {
        self.asked.as_ref()
    }

    /// What the pane shows of the partner at displayed time `t` (none while it is computed).
    #[must_use]
    pub fn shown(&self, t: f64) -> Option<Compared> {
        let partner = self.partner.as_ref()?;
        let name = partner.scenario.name.clone();
        match self.outcome.as_ref()? {
            Err(_) => Some(Compared {
                partner: name,
                events: 0,
                crossings: None,
                spin: None,
            }),
            Ok(run) => {
                let count = |times: &[f64]| times.partition_point(|x| *x <= t);
                let has_marks = partner
                    .scenario
                    .settings
                    .model
                    .kind()
                    .words()
                    .second_events
                    .is_some_and(|s| s.found == crate::physics::scene::Found::Flow);
                Some(Compared {
                    partner: name,
                    events: count(&run.reversals),
                    crossings: has_marks.then(|| count(&run.marks)),
                    spin: crate::app::run::upto(&run.samples, t)
                        .last()
                        .map(|p| p.rate),
                })
            }
        }
    }
}

impl App {
    /// Sets the comparison's partner and opens the compare pane (`rattleback compare`, a
    /// lesson's step).
    pub fn set_partner(&mut self, preset: &Preset) -> Vec<Effect> {
        let mut effects = self.replay_partner(preset);
        if !self.view.panes.shows(Pane::Compare) {
            effects.extend(self.toggle_pane(Pane::Compare));
            self.log_layout();
        }
        effects
    }

    /// Sets the comparison's partner (journaled inline, so the file stands alone); a shown
    /// pane runs it at once.
    pub(in crate::app) fn replay_partner(&mut self, preset: &Preset) -> Vec<Effect> {
        self.computed.compare.partner = Some(Partner {
            preset: preset.clone(),
            scenario: Scenario::of(preset),
        });
        self.log(Event::Partner {
            toml: preset.to_toml(),
        });
        if !self.view.panes.shows(Pane::Compare) {
            return Vec::new();
        }
        // A new partner: the old run is moot.
        let mut effects: Vec<Effect> = self
            .stop_job(Pane::Compare)
            .map(Effect::Sim)
            .into_iter()
            .collect();
        effects.extend(self.start_job(Pane::Compare).map(Effect::Sim));
        effects
    }

    /// The layout as a recording keeps it: the overlay and the panes a key shows.
    pub(in crate::app) fn layout(&self) -> Event {
        Event::Layout {
            effective: self.view.overlay,
            panes: self.view.panes.ordered(),
        }
    }

    /// Journals the layout now.
    pub(in crate::app) fn log_layout(&mut self) {
        let layout = self.layout();
        self.log(layout);
    }

    /// Whether what the compare pane shows is complete (hidden, or its partner has answered):
    /// a recorded screen waits for it.
    #[must_use]
    pub fn compare_settled(&self) -> bool {
        !self.view.panes.shows(Pane::Compare) || self.computed.compare.outcome.is_some()
    }
}

impl ComputedPane for CompareState {
    fn kind(&self) -> JobKind {
        JobKind::Partner
    }

    /// Asks for the partner's run over the run's window, unless that is what was asked last
    /// (its outcome stands). A scene opened without a partner takes its scene's counterpart
    /// (a shipped preset, journaled inline).
    fn start(&mut self, cx: &mut Cx) -> Option<Command> {
        if self.partner.is_none() {
            let name = cx.settings.model.kind().studies().counterpart;
            match crate::scenario::shipped::resolve(name, &[]) {
                Ok(p) => {
                    cx.log.push(Event::Partner { toml: p.to_toml() });
                    self.partner = Some(Partner {
                        scenario: Scenario::of(&p),
                        preset: p,
                    });
                }
                Err(e) => {
                    cx.status = Message::error(e.to_string());
                    return None;
                }
            }
        }
        let spec = self.spec(cx.settings.t_end)?;
        if self.asked == Some(spec) {
            return None;
        }
        self.id += 1;
        self.asked = Some(spec);
        self.outcome = None;
        Some(Command::start_job(self.id, JobSpec::Partner(spec)))
    }

    /// Stops the partner's run; its outcome is forgotten.
    fn stop(&mut self) -> Command {
        self.id += 1;
        self.asked = None;
        self.outcome = None;
        Command::stop_job(JobKind::Partner, self.id)
    }

    /// The partner's run (its plan is journaled, so a replay runs the same plan), or why it
    /// failed.
    fn take(&mut self, stamp: u64, data: JobData, cx: &mut Cx) -> bool {
        let JobData::Partner(outcome) = data else {
            return false;
        };
        let Some(spec) = self.asked else {
            return false;
        };
        if stamp != self.id {
            return false;
        }
        if let Ok(run) = &outcome {
            cx.log.push(Event::plan(
                crate::sim::PlanKey::of(&spec),
                run.plan,
                run.estimate,
            ));
        }
        self.outcome = Some(outcome.map_err(|e| clean(&e)));
        true
    }
}
