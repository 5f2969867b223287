//! Recorded events applied again (replay, `replay --verify`, the cast export) and the
//! commands that tie a recording to the run: seeking a recorded time, checkpoints.

use super::fields::Field;
use super::keys::Action;
use super::panes::Pane;
use super::{App, Caption, Effect, Message, Mode, SPEED_RANGE};
use crate::app::journal::Event;
use crate::scenario::Preset;
use crate::scenario::text::clean;
use crate::sim::Command;

impl App {
    /// Replays one recorded event (used by `replay` and `replay --verify`).
    pub fn apply_event(&mut self, event: &Event) -> Vec<Effect> {
        match event {
            Event::Set { field, value } => {
                let Some(f) = Field::named(field) else {
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
            Event::Panes {
                effective,
                series,
                sweep,
                weak,
                map,
                body,
            } => {
                self.view.panes.set(Pane::Series, *series);
                self.view.panes.set(Pane::Body, *body);
                let mut effects = Vec::new();
                for (pane, on) in [(Pane::Sweep, sweep), (Pane::Weak, weak), (Pane::Map, map)] {
                    if self.view.panes.shows(pane) != *on {
                        effects.extend(self.toggle_computed(pane));
                    }
                }
                // The replay's keys are its own: the map never takes them.
                if self.mode == Mode::Map {
                    self.mode = Mode::Normal;
                }
                if *effective != self.view.overlay {
                    effects.extend(self.carry_out(Action::ToggleEffective));
                }
                effects
            }
            Event::ClearTrail => self.carry_out(Action::ClearTrail),
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
            Event::LessonStep { .. } | Event::Answer { .. } => {
                self.caption = lesson_caption(event, self.run.goal);
                Vec::new()
            }
            Event::Checkpoint { .. } | Event::Plan { .. } | Event::End => Vec::new(),
        }
    }

    /// Moves the displayed clock to a recorded time (replay).
    pub fn seek(&mut self, t: f64) -> Vec<Effect> {
        vec![Effect::Sim(self.run.seek(t))]
    }

    /// Asks the worker for the exact state at the time asked of it (journaled on arrival).
    #[must_use]
    pub fn checkpoint(&self) -> Effect {
        Effect::Sim(Command::Checkpoint {
            generation: self.run.generation,
            t: self.run.target(),
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
