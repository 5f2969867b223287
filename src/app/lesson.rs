//! A lesson in the explorer (`rattleback lesson NAME`): the current step in its pane, its preset
//! and changes applied when it begins, a prediction asked before the run (keys `1`…`9` for a
//! choice, `a` to type a number) and revealed after it, and `n` moving on once the step's
//! condition holds. Every other key works as usual (`n` is the next step, not a note, while a
//! lesson is open). Steps and answers are journaled when recording.
use crate::physics::numerics::elementary::Elementary;

use super::fields::Field;
use super::journal::Event;
use super::mode::{Prompt, PromptFor};
use super::{App, Effect, Key, Message, Mode};
use crate::scenario::lesson::{Lesson, Question, Until};

/// How a refused `n` begins (the message is taken back once the condition holds).
const NOT_YET: &str = "not yet: ";

/// An answer given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Given {
    /// The index of a choice.
    Choice(usize),
    /// A number.
    Number(f64),
}

/// Where a lesson stands.
#[derive(Clone, Debug, PartialEq)]
pub struct LessonState {
    /// The lesson.
    pub lesson: Lesson,
    /// The current step.
    pub step: usize,
    /// The answer given at this step, if any.
    pub given: Option<Given>,
    /// The answer is revealed (after the run).
    pub revealed: bool,
    /// The last step's condition held and `n` was pressed.
    pub finished: bool,
}

impl LessonState {
    /// The current step.
    #[must_use]
    pub fn current(&self) -> &crate::scenario::lesson::Step {
        &self.lesson.steps[self.step]
    }

    /// Whether the answer given is right.
    #[must_use]
    pub fn correct(&self) -> Option<bool> {
        let given = self.given?;
        Some(match (&self.current().question, given) {
            (Some(Question::Choice { answer, .. }), Given::Choice(i)) => *answer == i,
            (
                Some(Question::Number {
                    answer, tolerance, ..
                }),
                Given::Number(x),
            ) => (x - answer).abs() <= *tolerance + 1e-12 * answer.abs(),
            _ => false,
        })
    }

    /// The answer given, as shown.
    #[must_use]
    pub fn given_text(&self) -> Option<String> {
        Some(match (self.given?, &self.current().question) {
            (Given::Choice(i), Some(Question::Choice { choices, .. })) => choices[i].clone(),
            (Given::Number(x), _) => format!("{x}"),
            (Given::Choice(i), _) => format!("{}", i + 1),
        })
    }

    /// Whether the step waits for an answer before the run.
    #[must_use]
    pub fn awaiting_answer(&self) -> bool {
        self.current().question.is_some() && self.given.is_none()
    }

    /// Whether the step's answer is still to be found: a question asked and not yet revealed.
    /// Until then the panel's predictions (`b^2-2a`, `vs critical`, the regime) and the
    /// condition's counts and bounds are shown without their values, which could state it. (A
    /// pane the step opens on purpose, as the sweep and its slope, is the lecturer's to
    /// choose: `rattleback check` says when it gives the answer away.)
    #[must_use]
    pub fn answer_hidden(&self) -> bool {
        self.current().question.is_some() && !self.revealed && !self.finished
    }

    /// How far a wrong number is from the answer (`None`: a choice, or right).
    #[must_use]
    pub fn off_by(&self) -> Option<f64> {
        match (&self.current().question, self.given?) {
            (Some(Question::Number { answer, .. }), Given::Number(x))
                if self.correct() == Some(false) =>
            {
                Some(x - answer)
            }
            _ => None,
        }
    }

    /// The verdict on a number, as the message and the pane write it.
    #[must_use]
    pub fn verdict_text(&self) -> Option<String> {
        let given = self.given_text()?;
        let answer = self.current().question.as_ref()?.answer_text();
        Some(match (self.correct()?, self.off_by()) {
            (true, _) => format!("your answer: {given}, right"),
            (false, Some(d)) => format!(
                "your answer: {given}, wrong: {} by {}; the answer: {answer}",
                if d > 0.0 { "too high" } else { "too low" },
                crate::scenario::lesson::condition_value(round_sig(d.abs(), 3))
            ),
            (false, None) => format!("your answer: {given}, wrong; the answer: {answer}"),
        })
    }
}

/// `x` to `digits` significant digits (how far a wrong answer is, without rounding noise).
fn round_sig(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().e_log10().floor() as i32);
    (x * scale).round() / scale
}

impl App {
    /// Opens `lesson` at its first step; returns the effects that start it.
    pub fn start_lesson(&mut self, lesson: Lesson) -> Vec<Effect> {
        self.show_lesson(lesson);
        self.enter_step(0)
    }

    /// `lesson` at its first step, its pane open; nothing loaded.
    fn show_lesson(&mut self, lesson: Lesson) {
        self.lesson = Some(LessonState {
            lesson,
            step: 0,
            given: None,
            revealed: false,
            finished: false,
        });
        self.view.panes.set(super::panes::Pane::Lesson, true);
    }

    /// A recorded lesson in a replay (its header's, format 10): the pane shows its steps as the
    /// recording's lines move through them; nothing is loaded (the lines do that).
    pub fn replay_lesson(&mut self, lesson: Lesson) {
        self.show_lesson(lesson);
    }

    /// A recorded step, answer or reveal applied to a replay's lesson.
    pub(super) fn replay_step(
        &mut self,
        step: usize,
        given: Option<&str>,
        revealed: bool,
        finished: bool,
    ) {
        let Some(state) = self.lesson.as_mut() else {
            return;
        };
        if step >= state.lesson.steps.len() {
            return;
        }
        if step != state.step || given.is_none() && !revealed {
            state.given = None;
            state.revealed = false;
        }
        state.step = step;
        state.finished = finished;
        if let Some(text) = given {
            state.given = Some(match &state.current().question {
                Some(Question::Choice { choices, .. }) => choices
                    .iter()
                    .position(|c| c == text)
                    .map_or(Given::Number(f64::NAN), Given::Choice),
                _ => Given::Number(text.parse().unwrap_or(f64::NAN)),
            });
        }
        state.revealed |= revealed;
    }

    /// Begins step `index`: its preset, its changes, a paused run.
    fn enter_step(&mut self, index: usize) -> Vec<Effect> {
        let Some(state) = self.lesson.as_mut() else {
            return Vec::new();
        };
        state.step = index;
        state.given = None;
        state.revealed = false;
        let step = state.current().clone();
        let count = state.lesson.steps.len();
        // The lesson's description opens it on the message line too (the pane's first rows
        // go to the step at 80×24; `v` shows it whole).
        let about = Some(state.lesson.description.clone()).filter(|d| index == 0 && !d.is_empty());
        self.log_lesson_step();
        let mut effects = Vec::new();
        if let Some(preset) = &step.preset {
            effects.extend(self.load(preset));
        }
        if !step.set.is_empty() {
            effects.extend(self.apply_set(&step.set));
        }
        if self.run.playing {
            // A step opens paused; said in the file, so a replay and a follower pause too
            // (issue 55: `n` pressed while playing let the replay play the new step alone).
            effects.push(Effect::Sim(self.run.pause()));
            self.log(Event::Pause);
        }
        // The comparison's partner first: a step about the compare pane opens it with it.
        if let Some(partner) = &step.partner {
            effects.extend(self.set_partner(partner));
        }
        if let Some(pane) = step.pane.as_deref().and_then(super::panes::Pane::named)
            && !self.view.panes.shows(pane)
            && self.scene_has(pane)
            && let Some(action) = pane.toggle_action()
        {
            effects.extend(self.update(action));
        }
        // A step about the map gives it the arrows, as opening it does (it may be open
        // already); a step about another pane gives them back to the panel (the map, still
        // open, may have no room left to be drawn).
        match step.pane.as_deref().and_then(super::panes::Pane::named) {
            Some(super::panes::Pane::Map) if self.view.panes.shows(super::panes::Pane::Map) => {
                self.mode = Mode::Map;
            }
            Some(_) if self.mode == Mode::Map => self.mode = Mode::Normal,
            _ => {}
        }
        let hint = if step.question.is_some() {
            "answer first, then space plays"
        } else {
            "space plays; n moves on"
        };
        self.status = Message::info(match about {
            Some(about) => format!("step 1/{count}: {about}"),
            None => format!("step {}/{count}: {hint}", index + 1),
        });
        effects
    }

    /// Applies `set` (`section.key=value` changes, as a step's `set` and `--set` write them)
    /// to the scenario, each journaled, and restarts the run: how a step's changes are made,
    /// and how `rattleback check` meets a step's parameter condition.
    pub fn apply_set(&mut self, set: &[crate::scenario::preset::Override]) -> Vec<Effect> {
        let mut s = self.scenario.settings;
        for o in set {
            let field = Field::keyed(s.model.kind(), &o.key).or_else(|| {
                o.key
                    .rsplit('.')
                    .next()
                    .and_then(|name| Field::named(s.model.kind(), name))
            });
            match field.map(|f| f.with_text(&s, &o.value)) {
                Some(Ok(next)) => {
                    s = next;
                    self.log(Event::Set {
                        field: o.key.rsplit('.').next().unwrap_or_default().to_owned(),
                        value: o.value.clone(),
                    });
                }
                Some(Err(e)) => self.status = Message::error(format!("{}: {e}", o.key)),
                None => {
                    self.status = Message::error(format!("{}: not a parameter here", o.key));
                }
            }
        }
        self.scenario.set(s);
        // A replay moves the highlight to each field set; the lecturer's stays: said.
        self.log(Event::Select {
            field: self.field().label().to_owned(),
        });
        self.restart()
    }

    /// Journals the current step (when it begins, and when a recording starts mid-lesson).
    pub(super) fn log_lesson_step(&mut self) {
        let Some(state) = self.lesson.as_ref() else {
            return;
        };
        let step = state.current();
        let event = Event::LessonStep {
            lesson: state.lesson.title.clone(),
            step: state.step,
            steps: state.lesson.steps.len(),
            title: step.title.clone(),
            text: step.text.clone(),
        };
        self.log(event);
    }

    /// What the step still waits for, as shown (`None`: the condition holds).
    #[must_use]
    pub fn lesson_missing(&self) -> Option<String> {
        let state = self.lesson.as_ref()?;
        let Until {
            time,
            reversals,
            parameter,
        } = &state.current().until;
        let mut missing = Vec::new();
        let written = crate::scenario::lesson::condition_value;
        // While the answer is to be found, a count or a bound could state it (two ways, step
        // 4: "2 reversals" right after the answer "how many reversals?"): said without it.
        let hidden = state.answer_hidden();
        if let Some(t) = time
            && self.run.shown < *t
        {
            missing.push(format!("t ≥ {} (now {:.2})", written(*t), self.run.shown));
        }
        if let Some(n) = reversals {
            let now = self.run.reversals_shown();
            if now < *n {
                missing.push(if hidden {
                    format!(
                        "more {} (now {now})",
                        self.scenario.settings.model.kind().words().events
                    )
                } else {
                    format!(
                        "{n} {} (now {now})",
                        self.scenario.settings.model.kind().words().events
                    )
                });
            }
        }
        if let Some(p) = parameter {
            let label = p.key.rsplit('.').next().unwrap_or_default();
            if let Some(f) = Field::keyed(self.scenario.settings.model.kind(), &p.key) {
                let v: f64 = f.exact(&self.scenario.settings).parse().unwrap_or(f64::NAN);
                let low = p.at_least.is_some_and(|lo| v.is_nan() || v < lo);
                let high = p.at_most.is_some_and(|hi| v.is_nan() || v > hi);
                if low || high {
                    let want = match (p.at_least, p.at_most) {
                        _ if hidden => format!("{label} where you find it"),
                        (Some(lo), Some(hi)) => {
                            format!("{label} in [{}, {}]", written(lo), written(hi))
                        }
                        (Some(lo), None) => format!("{label} ≥ {}", written(lo)),
                        (None, Some(hi)) => format!("{label} ≤ {}", written(hi)),
                        (None, None) => String::new(),
                    };
                    missing.push(format!("{want} (now {})", f.show(&self.scenario.settings)));
                }
            }
        }
        // Before the answer only the answer is asked for: a condition that names a threshold
        // would give the answer away.
        if state.awaiting_answer() {
            return Some("an answer".to_owned());
        }
        (!missing.is_empty()).then(|| missing.join(", "))
    }

    /// Reveals the answer once the run is over or the step's condition holds; journals it.
    pub(super) fn check_lesson(&mut self) {
        // A replay reveals what the recording says, when it says it.
        if self.replay.is_some() {
            return;
        }
        let holds = self.lesson_missing().is_none();
        let ready = self.run.done() || holds;
        // A "not yet" that no longer holds is taken back (it stayed under "n: finish").
        if holds
            && self
                .status
                .as_ref()
                .is_some_and(|m| m.error && m.text.starts_with(NOT_YET))
        {
            self.status = Message::info("the step's condition holds: n moves on");
        }
        let Some(state) = self.lesson.as_mut() else {
            return;
        };
        if state.given.is_none() || state.revealed || !ready {
            return;
        }
        state.revealed = true;
        let correct = state.correct().unwrap_or(false);
        let given = state.given_text().unwrap_or_default();
        let step = state.step;
        let verdict = state.verdict_text().unwrap_or_default();
        self.status = if correct {
            Message::info(verdict)
        } else {
            Message::error(verdict)
        };
        self.log(Event::Answer {
            step,
            given,
            correct,
        });
    }

    /// A key while a lesson is open: `n`, the answer keys and a guard on play; `None` lets the
    /// keymap have it.
    pub(super) fn on_lesson_key(&mut self, key: Key) -> Option<Vec<Effect>> {
        let state = self.lesson.as_ref()?;
        let question = state.current().question.clone();
        match key {
            Key::Char('n') => Some(self.next_step()),
            Key::Char(c @ '1'..='9') => {
                let Some(Question::Choice { choices, .. }) = &question else {
                    return None;
                };
                let i = c as usize - '1' as usize;
                if i >= choices.len() || state.given.is_some() {
                    return Some(Vec::new());
                }
                self.answer(Given::Choice(i));
                Some(Vec::new())
            }
            Key::Char('a') if matches!(question, Some(Question::Number { .. })) => {
                if state.given.is_none() {
                    self.mode = Mode::Prompt(Prompt::new(PromptFor::Answer));
                    self.status = Message::info("type a number and press Enter (Esc cancels)");
                }
                Some(Vec::new())
            }
            Key::Char(' ') if state.awaiting_answer() => {
                self.status = Message::error(match question {
                    Some(Question::Choice { .. }) => "answer first: a key from 1 on",
                    _ => "answer first: a, then type a number",
                });
                Some(Vec::new())
            }
            _ => None,
        }
    }

    /// Records an answer (typed numbers arrive through the prompt); journaled, so a replay
    /// shows it given from then.
    pub(super) fn answer(&mut self, given: Given) {
        if let Some(state) = self.lesson.as_mut() {
            state.given = Some(given);
            let text = state.given_text().unwrap_or_default();
            let step = state.step;
            self.status = Message::info(format!(
                "your answer: {text}; space plays, the answer shows after the run"
            ));
            self.log(Event::Given { step, given: text });
        }
    }

    fn next_step(&mut self) -> Vec<Effect> {
        if let Some(missing) = self.lesson_missing() {
            self.status = Message::error(format!("{NOT_YET}{missing}"));
            return Vec::new();
        }
        let Some(state) = self.lesson.as_mut() else {
            return Vec::new();
        };
        if state.step + 1 < state.lesson.steps.len() {
            let next = state.step + 1;
            self.enter_step(next)
        } else {
            state.finished = true;
            self.status = Message::info(format!("lesson complete: {}", state.lesson.title));
            self.log(Event::LessonDone);
            Vec::new()
        }
    }
}
