//! Recording on and off, what the loop reports back after executing an effect, and what the
//! worker sends.

use super::mode::{Confirm, Picker, PickerRow};
use super::{App, Effect, Message, Mode, Outcome, RecState};
use crate::app::journal::Event;
use crate::scenario::text::clean;
use crate::sim::SimEvent;

impl App {
    pub(super) fn toggle_recording(&mut self) -> Vec<Effect> {
        match self.journal.state {
            RecState::Off if self.replay.is_some() => {
                self.status = Message::error("a replay cannot be recorded");
                Vec::new()
            }
            RecState::Off => vec![Effect::StartRecording],
            RecState::On => {
                // Closed by the next tick once the last frame is settled (`journal_tick`).
                self.journal.stop_due = true;
                self.status = Message::info("closing the recording…");
                Vec::new()
            }
            RecState::Stopping => Vec::new(),
        }
    }

    /// Takes what came of an effect.
    pub fn on_outcome(&mut self, outcome: Outcome) -> Vec<Effect> {
        let effects = self.outcome(outcome);
        self.remember();
        effects
    }

    fn outcome(&mut self, outcome: Outcome) -> Vec<Effect> {
        match outcome {
            Outcome::Recording(Ok(path)) => {
                self.journal.state = RecState::On;
                self.journal.map_cursor = None;
                self.status = Message::info(format!("recording to {path}"));
                // The plans of the run in progress belong in the file too (every segment
                // verified so far).
                for s in self.run.segments.clone() {
                    self.log_plan(s.until, s.plan, s.estimate);
                }
                // The panes open when the recording starts belong in it too (the header holds
                // the preset, which says only whether the time series is shown), and the
                // comparison's partner with its plan.
                if self.view.panes.shows(super::panes::Pane::Compare)
                    && let Some(p) = self
                        .computed
                        .compare
                        .partner
                        .as_ref()
                        .map(|p| p.preset.to_toml())
                {
                    self.log(Event::Partner { toml: p });
                }
                if self
                    .view
                    .panes
                    .toggled()
                    .iter()
                    .any(|p| *p != super::panes::Pane::Series)
                {
                    self.log_layout();
                    if let Some((spec, Ok(run))) = self
                        .computed
                        .compare
                        .asked()
                        .zip(self.computed.compare.outcome.as_ref())
                    {
                        let plan =
                            Event::plan(crate::sim::PlanKey::of(spec), run.plan, run.estimate);
                        self.log(plan);
                    }
                }
                self.log_lesson_step();
            }
            Outcome::Recording(Err(e)) => {
                // Why, and where the folder comes from (issue 56: a `sessions` of /dev/null).
                self.mode = Mode::Dialog(clean(&format!(
                    "cannot record: {e}\n\nRecordings go to the folder `sessions` names in config.toml (`rattleback doctor` shows it), or to the file --record names."
                )));
            }
            Outcome::RecordingSaved(path) => {
                self.journal.state = RecState::Off;
                self.status = self.noted(format!("recording saved to {path}"));
            }
            Outcome::RecordingFailed(e) => {
                self.journal.state = RecState::Off;
                self.mode = Mode::Dialog(clean(&format!("recording stopped: {e}")));
            }
            Outcome::Saved(Ok(path)) => {
                self.mode = Mode::Normal;
                self.messages
                    .written
                    .push(clean(&format!("preset saved to {}", path.display())));
                self.status = Message::info(format!("saved {}", path.display()));
            }
            Outcome::Saved(Err(crate::scenario::store::SaveError::Exists(path))) => {
                if let Mode::Prompt(p) = &mut self.mode {
                    p.confirm = Confirm::Overwrite;
                }
                self.status = Message::error(format!(
                    "{} exists: Enter replaces it, Esc cancels",
                    path.display()
                ));
            }
            Outcome::Saved(Err(e)) => self.mode = Mode::Dialog(clean(&e.to_string())),
            Outcome::Exported(Ok(paths)) => {
                let names: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
                self.status = self.noted(format!("wrote {}", names.join(" and ")));
            }
            Outcome::Copied { text, tmux, file } => self.copied(&text, tmux, file),
            Outcome::Exported(Err(e)) => {
                self.status = Message::error(format!("export failed: {e}"));
            }
            Outcome::Catalogue(entries, broken) => {
                let selected = entries
                    .iter()
                    .position(|e| e.title == self.scenario.name)
                    .unwrap_or(0);
                let mut rows: Vec<PickerRow> = entries.into_iter().map(PickerRow::Preset).collect();
                rows.extend(broken.into_iter().map(|(name, error)| PickerRow::Broken {
                    name: clean(&name),
                    error: clean(&error),
                }));
                self.mode = Mode::Picker(Picker::new(rows, selected));
            }
            Outcome::Loaded(result) => match *result {
                Ok(preset) => return self.load(&preset),
                Err(e) => {
                    self.mode = Mode::Dialog(clean(&format!(
                        "{e}\n\nThe explorer keeps the current scenario."
                    )));
                }
            },
        }
        Vec::new()
    }

    /// Journals the plan verified for the horizon `until` of the current run.
    pub(super) fn log_plan(
        &mut self,
        until: f64,
        plan: crate::physics::Resolved,
        estimate: Option<f64>,
    ) {
        let mut spec = self.scenario.spec(self.view.overlay);
        spec.t_end = until;
        self.log(Event::plan(crate::sim::PlanKey::of(&spec), plan, estimate));
    }

    /// Takes an event from the worker (stale runs are ignored); whether anything visible
    /// changed.
    pub fn on_sim(&mut self, event: SimEvent) -> bool {
        let changed = self.sim(event);
        self.remember();
        changed
    }

    fn sim(&mut self, event: SimEvent) -> bool {
        match event {
            SimEvent::Checkpoint {
                generation,
                t,
                state,
                reversals,
            } if generation == self.run.generation => {
                if self.journal.state != RecState::Off {
                    let hash = crate::app::journal::state_hash(t, &state, reversals);
                    let checkpoint = Event::Checkpoint {
                        state,
                        reversals,
                        hash,
                    };
                    self.journal.push(t, generation, checkpoint);
                }
                false
            }
            // A plan the run integrates, the first or a later segment's: in the file too.
            SimEvent::Started {
                generation,
                plan,
                error_estimate,
                until,
            }
            | SimEvent::Verified {
                generation,
                until,
                plan,
                error_estimate,
                ..
            } if generation == self.run.generation => {
                self.log_plan(until, plan, error_estimate);
                self.run.on_sim(event, self.view.overlay)
            }
            SimEvent::Failed {
                generation,
                ref message,
            } if generation == self.run.generation => {
                // Says what failed: an integration, or a run refused before it started.
                self.status = Message::error(message.clone());
                self.run.on_sim(event, self.view.overlay)
            }
            SimEvent::Stops {
                generation,
                ref message,
                ..
            } if generation == self.run.generation => {
                // Said at once; the verified part still plays.
                self.status = Message::info(format!("the run stops {message}"));
                self.run.on_sim(event, self.view.overlay)
            }
            SimEvent::Job { stamp, data } => self.on_job(stamp, data),
            other => self.run.on_sim(other, self.view.overlay),
        }
    }
}

impl App {
    /// `said` on the message line, and noted among what the session wrote (printed when the
    /// explorer ends).
    fn noted(&mut self, said: String) -> Option<Message> {
        self.messages.written.push(clean(&said));
        Message::info(said)
    }

    /// Where `y` put the command, said first (the message line shows its start); a file is
    /// also noted among what the session wrote.
    fn copied(
        &mut self,
        text: &str,
        tmux: bool,
        file: Option<Result<std::path::PathBuf, super::ShellError>>,
    ) {
        let said = match (tmux, file) {
            (true, _) => {
                format!("command in tmux's buffer (prefix ] pastes; also sent as OSC 52): {text}")
            }
            (false, Some(Ok(path))) => {
                self.messages
                    .written
                    .push(clean(&format!("command saved to {}", path.display())));
                format!(
                    "command saved to {} (also sent as OSC 52, for a terminal that allows it): {text}",
                    path.display()
                )
            }
            (false, Some(Err(e))) => format!(
                "command sent as OSC 52 only (a terminal that allows it has it); not saved: {e}: {text}"
            ),
            (false, None) => {
                format!("command sent as OSC 52 only (a terminal that allows it has it): {text}")
            }
        };
        self.status = Message::info(said);
    }
}
