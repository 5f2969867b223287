//! Recorded events applied again (replay, `replay --verify`, the cast export) and the
//! commands that tie a recording to the run: seeking a recorded time, checkpoints.

use super::fields::Field;
use super::keys::Action;
use super::panes::Pane;
use super::{App, Caption, Effect, Message, Mode, PlanState, RecState, SPEED_RANGE};
use crate::app::journal::{Event, Shown};

/// Wall seconds between two clock lines of a recording while the display moves: a follower
/// lags the lecturer by about this much, and never leads.
pub const CLOCK_EVERY: f64 = 0.05;
use crate::scenario::Preset;
use crate::scenario::text::clean;
use crate::sim::Command;

impl App {
    /// Replays one recorded event (used by `replay`, `follow` and `replay --verify`);
    /// `generation_rose`: its line's run stamp is above the line's before it. A play that
    /// started the run over from its end was recorded by earlier versions as a play alone, in
    /// the new run: such a play starts the replay's run over too (files written now journal a
    /// reset before it, whose line carries the new stamp already).
    pub fn apply_event(&mut self, event: &Event, generation_rose: bool) -> Vec<Effect> {
        if generation_rose && matches!(event, Event::Play) {
            let mut effects = self.carry_out(Action::Reset);
            effects.extend(self.apply_event(event, false));
            return effects;
        }
        match event {
            Event::Set { field, value } => {
                let kind = self.scenario.settings.model.kind();
                let Some(f) = Field::named(kind, field) else {
                    self.status =
                        Message::error(format!("unknown field '{field}' in the recording"));
                    return Vec::new();
                };
                self.scenario.selected = Field::rows(self.scenario.settings.model.kind())
                    .iter()
                    .position(|x| *x == f)
                    .unwrap_or(0);
                self.apply(f.with_text(&self.scenario.settings, value))
            }
            Event::Select { field } => {
                let kind = self.scenario.settings.model.kind();
                if let Some(i) = Field::named(kind, field).and_then(|f| {
                    Field::rows(self.scenario.settings.model.kind())
                        .iter()
                        .position(|x| *x == f)
                }) {
                    self.scenario.selected = i;
                }
                Vec::new()
            }
            Event::Play if self.run.playing => Vec::new(),
            Event::Play => self.carry_out(Action::TogglePlay),
            // At the recorded time (the replay sought it), not where the display has got to.
            Event::Pause => vec![Effect::Sim(self.run.pause_at_goal())],
            Event::Step => self.carry_out(Action::Step),
            Event::Reset => self.carry_out(Action::Reset),
            Event::Speed { value } => {
                self.run.speed = value.clamp(SPEED_RANGE.0, SPEED_RANGE.1);
                Vec::new()
            }
            Event::View {
                zoom,
                pan_x,
                pan_y,
                wrap,
            } => {
                let v = &mut self.view.view;
                (v.zoom, v.pan_x, v.pan_y, v.wrap) = (*zoom, *pan_x, *pan_y, *wrap);
                Vec::new()
            }
            Event::Layout { .. } | Event::Panes { .. } => {
                let (effective, panes) = event.layout().unwrap_or_default();
                self.apply_layout(effective, &panes)
            }
            Event::Partner { toml } => {
                match Preset::parse(toml, "recorded partner", "recorded", &[]) {
                    Ok(p) => self.replay_partner(&p),
                    Err(e) => {
                        self.mode = Mode::Dialog(clean(&e.to_string()));
                        Vec::new()
                    }
                }
            }
            Event::ClearTrail => self.carry_out(Action::ClearTrail),
            Event::MapCursor { .. } | Event::Window { .. } => {
                self.apply_pane_state(event);
                Vec::new()
            }
            Event::Preset { toml } => match Preset::parse(toml, "recorded preset", "recorded", &[])
            {
                Ok(p) => self.load(&p),
                Err(e) => {
                    self.mode = Mode::Dialog(clean(&e.to_string()));
                    Vec::new()
                }
            },
            Event::Note { text } | Event::Chapter { title: text } => {
                self.caption = Some(Caption {
                    chapter: matches!(event, Event::Chapter { .. }),
                    text: clean(text),
                    t: self.run.goal,
                });
                Vec::new()
            }
            Event::LessonStep { .. }
            | Event::Given { .. }
            | Event::Answer { .. }
            | Event::LessonDone => {
                self.apply_lesson_event(event);
                Vec::new()
            }
            Event::Terminal { width, height } => {
                self.lecturer_terminal = Some((*width, *height));
                Vec::new()
            }
            Event::Checkpoint { .. }
            | Event::Plan { .. }
            | Event::End { .. }
            | Event::Clock
            | Event::Screen(_) => Vec::new(),
        }
    }

    /// A pane's own state as recorded: the weak-* window, the map's cursor and focus.
    fn apply_pane_state(&mut self, event: &Event) {
        match event {
            Event::Window { value } => self.computed.weak.set_window(*value),
            Event::MapCursor {
                column,
                row,
                focused,
            } => self.computed.map.replay_cursor((*column, *row), *focused),
            _ => {}
        }
    }

    /// A lesson's event: a recording that carries its lesson (format 10) shows the lesson's
    /// pane as the lecturer did; an older one, a caption.
    fn apply_lesson_event(&mut self, event: &Event) {
        match event {
            Event::LessonStep { .. } | Event::Answer { .. } if self.lesson.is_none() => {
                self.caption = lesson_caption(event, self.run.goal);
            }
            Event::LessonStep { step, .. } => self.replay_step(*step, None, false, false),
            Event::Given { step, given } => self.replay_step(*step, Some(given), false, false),
            Event::Answer { step, given, .. } => {
                self.replay_step(*step, Some(given), true, false);
            }
            Event::LessonDone => {
                if let Some(state) = self.lesson.as_mut() {
                    state.finished = true;
                }
            }
            _ => {}
        }
    }

    /// Shows exactly the recorded panes (those a key toggles) and the overlay.
    fn apply_layout(&mut self, effective: bool, panes: &[Pane]) -> Vec<Effect> {
        let mut effects = Vec::new();
        for pane in Pane::ALL {
            let Some(action) = pane.toggle_action() else {
                continue;
            };
            if self.view.panes.shows(pane) != panes.contains(&pane) {
                effects.extend(self.carry_out(action));
            }
        }
        // Brought to the front as the lecturer had them (the most recent last).
        self.view.panes.order_as(panes);
        // The replay's keys are its own: the map never takes them.
        if self.mode == Mode::Map {
            self.mode = Mode::Normal;
        }
        if effective != self.view.overlay {
            effects.extend(self.carry_out(Action::ToggleEffective));
        }
        effects
    }

    /// What the status bar shows now, as recorded values.
    #[must_use]
    pub fn shown(&self) -> Shown {
        let run = &self.run;
        let s = &self.scenario.settings;
        let (method, estimate) = match run.plan {
            PlanState::Running { plan, estimate } if plan.method != s.method => {
                (format!("{}→{}", s.method, plan.method), estimate)
            }
            PlanState::Running { estimate, .. } => (s.method.to_string(), estimate),
            _ => (s.method.to_string(), None),
        };
        Shown {
            playing: run.playing,
            events: run.reversals_shown(),
            limit_events: (self.view.overlay && s.model.kind().small().is_some())
                .then(|| run.effective_reversals_shown()),
            falls: run.falls_shown(),
            crossings: run.crossings_shown(),
            compare: self
                .view
                .panes
                .shows(Pane::Compare)
                .then(|| self.computed.compare.shown(run.shown))
                .flatten(),
            point: run.current().map(|p| [p.slow, p.rate, p.energy_error]),
            method,
            estimate,
        }
    }

    /// While recording: the screen a pause, step, chapter or note led to, once the display has
    /// got there (with a checkpoint at the same time), and the displayed time every
    /// [`CLOCK_EVERY`] wall seconds while it moves, and when it reaches the end of the run.
    pub(super) fn journal_tick(&mut self, wall_seconds: f64) -> Vec<Effect> {
        if self.journal.state != RecState::On {
            return Vec::new();
        }
        let mut effects = Vec::new();
        let settled = self.screen_settled();
        if self.journal.screen_due && settled {
            self.journal.screen_due = false;
            self.log_screen();
            effects.push(self.checkpoint());
        }
        // `R` closes the recording once its last frame is settled: the frame, a checkpoint at
        // its time, then the end.
        if self.journal.stop_due && settled {
            self.journal.stop_due = false;
            self.log_last_frame();
            effects.push(self.checkpoint());
            effects.push(Effect::StopRecording);
            return effects;
        }
        self.journal.since_clock += wall_seconds;
        // Moved since the last clock line, or a new run since (issue 80: a run started over from
        // its end and ended again at the same `t_end` wrote no clock line, and a replay showed it
        // still playing at its start).
        #[allow(clippy::float_cmp)]
        let moved = self.run.shown != self.journal.clock_t
            || self.run.generation != self.journal.clock_generation;
        // The display reaching the end of the run is said at once: no clock line follows it
        // (the run no longer plays), and a follower would show the last one until the next
        // checkpoint, up to two seconds later.
        let ended = self.run.done() && self.run.failed.is_none();
        if moved && (ended || self.run.playing && self.journal.since_clock >= CLOCK_EVERY) {
            self.journal.since_clock = 0.0;
            self.journal.clock_t = self.run.shown;
            self.journal.clock_generation = self.run.generation;
            self.log(Event::Clock);
        }
        effects
    }

    /// Whether the screen is what a replay will show at the displayed time: the display has got
    /// where it was going, the run's plan is resolved and its first point has arrived (or the
    /// run failed), and the comparison's partner is computed. A lesson step's screen waits for
    /// `auto` to resolve its new preset, as a replay does (issue 55).
    #[must_use]
    pub fn screen_settled(&self) -> bool {
        let run = &self.run;
        let there = run.playing || run.done() || run.shown >= run.goal;
        let resolved = run.failed.is_some()
            || matches!(run.plan, PlanState::Running { .. }) && run.current().is_some();
        there && resolved && self.compare_settled()
    }

    /// Journals the screen now.
    pub fn log_screen(&mut self) {
        let shown = self.shown();
        self.log(Event::Screen(shown));
    }

    /// Journals the last frame of the recording and closes its journal: only the checkpoint at
    /// its time follows (`R`, or whatever else ends it: `q`, a signal).
    pub fn log_last_frame(&mut self) {
        self.log_screen();
        if self.journal.state == RecState::On {
            self.journal.state = RecState::Stopping;
        }
    }

    /// Moves the displayed clock to a recorded time (replay).
    pub fn seek(&mut self, t: f64) -> Vec<Effect> {
        vec![Effect::Sim(self.run.seek(t))]
    }

    /// Asks the worker for the exact state at the displayed time (journaled on arrival): what
    /// is recorded is what the screen shows, never the worker's look-ahead.
    #[must_use]
    pub fn checkpoint(&self) -> Effect {
        Effect::Sim(Command::Checkpoint {
            generation: self.run.generation,
            t: self.run.shown,
        })
    }
}

/// The caption of a recorded lesson step (a chapter) or answer (a note).
fn lesson_caption(event: &Event, t: f64) -> Option<Caption> {
    match event {
        Event::LessonStep {
            lesson,
            step,
            steps,
            title,
            text,
        } => Some(Caption {
            chapter: true,
            text: clean(&format!(
                "{lesson}, step {}/{steps}: {title}. {text}",
                step + 1
            )),
            t,
        }),
        Event::Answer {
            step,
            given,
            correct,
        } => {
            let verdict = if *correct { "right" } else { "not right" };
            Some(Caption {
                chapter: false,
                text: clean(&format!("step {}: answered {given} ({verdict})", step + 1)),
                t,
            })
        }
        _ => None,
    }
}
