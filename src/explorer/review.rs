//! A lesson read as a student meets it (`rattleback check LESSON.toml`, and the tests on every
//! shipped lesson): the explorer walks the lesson headless, through the worker's interpreter,
//! and draws each step at 80×24 through ratatui's `TestBackend`, as a student's terminal would.
//! At each step's start, and again after a (wrong) answer, before the run:
//!
//! - **words**: the lesson pane's text is not cut;
//! - **room**: the pane the step is about (its `pane`, and any pane its text or question names:
//!   "the portrait", "the trail", "the time series", "the map"…) is drawn with at least
//!   [`ui::ASKED_ROWS`] rows inside its border;
//! - **no answer given away**: nothing on screen but the question itself states the answer: a
//!   number within the question's tolerance (a parameter's own row in the panel aside, which the
//!   student sets), a slope whose tenfold factor is within it, the right choice's words, or a
//!   panel row that predicts the run (`b^2-2a`, `vs critical`, the regime) with its value;
//! - **no run replayed**: a question does not ask about the run the step before has just
//!   played (the same scenario, to the question's time): the student saw its answer;
//! - **keys**: the text names no key that hides the pane the step is about (`M: …` reads as
//!   "press M"), and does not ask to open a pane that is open.
//!
//! Then it meets the step's condition as a student would (the parameter set to its bound, the
//! run played to its end at top speed) and presses `n`.
use crate::physics::numerics::elementary::Elementary;

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::layout::Rect;

use crate::app::panes::Pane;
use crate::app::{App, Effect, Key, Options};
use crate::scenario::lesson::{Lesson, Question};
use crate::sim::{Engine, PlanBook};
use crate::ui::{self, Cache, UiOptions};

/// The size a step is read at: the smallest terminal the explorer is made for.
pub const SIZE: (u16, u16) = (80, 24);

/// What a reading found at a step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Finding {
    /// The step (0-based).
    pub step: usize,
    /// What is wrong, as the lecturer reads it.
    pub message: String,
}

/// The explorer, headless, with its worker's interpreter (the scene contract's test drives it
/// too).
pub(crate) struct Walk {
    pub(crate) app: App,
    engine: Engine,
}

impl Walk {
    /// A paused explorer on `preset`, started as the real one.
    pub(crate) fn of(preset: &crate::scenario::Preset) -> Self {
        let (app, effects) = App::new(preset, Options::at(30.0));
        let mut walk = Self {
            app,
            engine: Engine::new(PlanBook::default()),
        };
        walk.exec(effects);
        walk
    }

    pub(crate) fn exec(&mut self, effects: Vec<Effect>) {
        for e in effects {
            if let Effect::Sim(c) = e {
                let app = &mut self.app;
                crate::sim::drive(&mut self.engine, vec![c], &mut |ev| {
                    app.on_sim(ev);
                });
            }
        }
    }

    pub(crate) fn key(&mut self, key: Key) {
        let effects = self.app.on_key(key);
        self.exec(effects);
    }

    pub(crate) fn tick(&mut self, wall: f64) {
        let effects = self.app.tick(wall);
        self.exec(effects);
    }

    /// The screen as a student's 80×24 terminal shows it, one string per row.
    fn screen(&self) -> Vec<String> {
        self.screen_at(SIZE)
    }

    /// The screen at `width × height`, one string per row.
    pub(crate) fn screen_at(&self, (width, height): (u16, u16)) -> Vec<String> {
        let backend = TestBackend::new(width, height);
        let Ok(mut terminal) = Terminal::new(backend);
        let options = UiOptions::default();
        let mut cache = Cache::default();
        if terminal
            .draw(|f| ui::draw(f, &self.app, &options, &mut cache))
            .is_err()
        {
            return Vec::new();
        }
        let buffer = terminal.backend().buffer();
        (0..buffer.area.height)
            .map(|y| {
                (0..buffer.area.width)
                    .map(|x| buffer[(x, y)].symbol())
                    .collect::<String>()
            })
            .collect()
    }

    /// Plays at top speed until the shown time reaches `t` or the run ends.
    fn play_to(&mut self, t: f64) {
        for _ in 0..16 {
            self.key(Key::Char('+'));
        }
        if !self.app.run.playing && !self.app.run.done() {
            self.key(Key::Char(' '));
        }
        let mut frames = 0;
        while self.app.run.shown < t && !self.app.run.done() && frames < 200_000 {
            self.tick(1.0 / 30.0);
            frames += 1;
        }
        if self.app.run.playing {
            self.key(Key::Char(' '));
        }
    }
}

/// Reads `lesson` as a student meets it; every finding, step by step (empty: it reads well).
#[must_use]
pub fn review(lesson: &Lesson) -> Vec<Finding> {
    let preset = lesson.steps[0].preset.clone().or_else(|| {
        crate::scenario::shipped::resolve(crate::scenario::shipped::DEFAULT_PRESET, &[]).ok()
    });
    let Some(preset) = preset else {
        return Vec::new();
    };
    let mut walk = Walk::of(&preset);
    let effects = walk.app.start_lesson(lesson.clone());
    walk.exec(effects);
    let mut findings = Vec::new();
    // The scenario the step before played, and to which time.
    let mut played: Option<(crate::app::fields::Settings, f64)> = None;
    for (index, step) in lesson.steps.iter().enumerate() {
        walk.tick(0.0);
        let mut found = |message: String| {
            findings.push(Finding {
                step: index,
                message,
            });
        };
        if step.question.is_some()
            && let Some((settings, shown)) = played
            && settings == walk.app.scenario.settings
            && shown
                >= step
                    .until
                    .time
                    .unwrap_or(settings.t_end)
                    .min(settings.t_end)
        {
            found(format!(
                "the question asks about the run step {index} has just played to t = {shown:.2} \
                 (the same scenario): its answer was on screen then"
            ));
        }
        let entry = walk.screen();
        if let Some(m) = cut(&walk.app, &entry) {
            found(m);
        }
        for m in room(&walk.app, step) {
            found(m);
        }
        for m in keys_named(&walk.app, step) {
            found(m);
        }
        if let Some(q) = &step.question {
            for m in given_away(&walk.app, q, &entry, "at the step's start") {
                found(m);
            }
            answer_wrongly(&mut walk, q);
            let answered = walk.screen();
            if let Some(m) = cut(&walk.app, &answered) {
                found(format!("{m} (after an answer)"));
            }
            for m in given_away(&walk.app, q, &answered, "after an answer, before the run") {
                found(m);
            }
        }
        // Meet the condition as the student would, then move on.
        if let Some(p) = &step.until.parameter
            && let Some(v) = p.at_least.or(p.at_most)
        {
            let effects = walk.app.apply_set(&[crate::scenario::preset::Override {
                key: p.key.clone(),
                value: format!("{v:?}"),
            }]);
            walk.exec(effects);
        }
        // Priced before it is played, as `simulate` prices it (issue 80, N7: a step's run of
        // 110 CPU-s that `simulate` refuses was played unbudgeted).
        if let Some(m) = over_budget(&walk.app) {
            found(m);
            break;
        }
        // A student plays the run out (and so sees all it shows before the next step).
        walk.play_to(f64::INFINITY);
        if let Some(m) = tolerance_missed(&walk.app) {
            found(m);
        }
        if step.until.parameter.is_some()
            && let Some(m) = window_bound(&mut walk)
        {
            found(m);
        }
        played = Some((walk.app.scenario.settings, walk.app.run.shown));
        if let Some(m) = cut(&walk.app, &walk.screen()) {
            found(format!("{m} (after the run, the answer shown)"));
        }
        if let Some(missing) = walk.app.lesson_missing() {
            found(format!(
                "n still waits for {missing} after the step's condition was met and its run \
                 played to the end: the step cannot be finished"
            ));
            break;
        }
        walk.key(Key::Char('n'));
    }
    findings
}

/// The step's run as the student's explorer plays it, priced as `simulate` prices a run: over
/// the work budget, said (the explorer would stop it; `simulate` refuses it).
fn over_budget(app: &App) -> Option<String> {
    let s = &app.scenario.settings;
    let predicted = s
        .model
        .predicted_seconds(&crate::physics::method::Asked::new(
            s.method,
            s.tolerance,
            s.step,
            s.t_end,
        ));
    crate::physics::budget::check(predicted, crate::physics::budget::BUDGET_SECONDS)
        .err()
        .map(|over| {
            format!(
                "the run the step leads to ({} to t = {}, tolerance {}) is {over}: the explorer \
                 stops it and `simulate` refuses it; shorten its run.t_end or loosen its tolerance",
                s.method,
                crate::physics::Number(s.t_end),
                crate::physics::Number(s.tolerance)
            )
        })
}

/// The step's run, played out, misses its tolerance (`✗ tol missed` in the status bar), or
/// stops short: said with what it reached.
fn tolerance_missed(app: &App) -> Option<String> {
    let s = &app.scenario.settings;
    if let Some(at) = app.run.stops {
        return Some(format!(
            "the run the step leads to stops at t = {} (the work budget): the student sees \
             `✗ stops at t`; shorten its run.t_end or loosen its tolerance",
            crate::physics::Number(at)
        ));
    }
    let missed =
        app.run
            .segments
            .iter()
            .filter_map(|seg| seg.estimate)
            .chain(match app.run.plan {
                crate::app::run::PlanState::Running { estimate, .. } => estimate,
                crate::app::run::PlanState::Pending
                | crate::app::run::PlanState::Verifying { .. } => None,
            })
            .find(|&e| e.is_nan() || e > s.tolerance)?;
    Some(format!(
        "the run the step leads to cannot meet its tolerance {}: auto's estimate is {} (the \
         student sees `✗ tol missed`); loosen its run.tolerance, or change the values it leads to",
        crate::physics::Number(s.tolerance),
        crate::physics::Number(missed)
    ))
}

/// A step that asks the student to move a parameter until something stops happening (its
/// condition a bound), whose run at that bound shows nothing in its window but shows it in a run
/// twice as long: the "threshold" found is the window's edge, not the physics' (issue 80, L4: a
/// celt "threshold spin" of 3.45 rad/s was where a 20 s window ended; 3.0 reverses at 20.95 s).
/// The run is played again to twice its end and put back.
fn window_bound(walk: &mut Walk) -> Option<String> {
    let t_end = walk.app.scenario.settings.t_end;
    if walk.app.shown().events > 0 {
        return None;
    }
    let set = |walk: &mut Walk, t: f64| {
        let effects = walk.app.apply_set(&[crate::scenario::preset::Override {
            key: "run.t_end".to_owned(),
            value: format!("{t:?}"),
        }]);
        walk.exec(effects);
    };
    set(walk, 2.0 * t_end);
    let later = if over_budget(&walk.app).is_none() {
        walk.play_to(f64::INFINITY);
        (walk.app.shown().events > 0).then_some(walk.app.run.shown)
    } else {
        None
    };
    set(walk, t_end);
    walk.play_to(f64::INFINITY);
    later.map(|_| {
        let kind = walk.app.scenario.settings.model.kind();
        format!(
            "at the bound the step leads to, nothing happens within t = {} but a run twice as long \
             shows its {}: what the step asks the student to find depends on the window, not on \
             the physics; ask about the window, or check the claim on a longer run",
            crate::physics::Number(t_end),
            kind.words().events
        )
    })
}

/// The lesson pane's words cut short at [`SIZE`] (a `…` below its title).
fn cut(app: &App, screen: &[String]) -> Option<String> {
    let (_, column) = areas(app);
    let (_, area) = column.panes.iter().find(|(p, _)| *p == Pane::Lesson)?;
    let inside: String = screen
        .iter()
        .skip(usize::from(area.y) + 1)
        .take(usize::from(area.height.saturating_sub(2)))
        .map(|row| {
            row.chars()
                .skip(usize::from(area.x))
                .take(usize::from(area.width))
                .collect::<String>()
        })
        .collect();
    inside.contains('…').then(|| {
        format!(
            "the step's words are cut at {}x{}: shorten its text (the question and what n waits for stay whole)",
            SIZE.0, SIZE.1
        )
    })
}

/// An answer that is wrong, given as a student gives it (a number key; `a`, digits, Enter).
fn answer_wrongly(walk: &mut Walk, q: &Question) {
    match q {
        Question::Choice {
            choices, answer, ..
        } => {
            let wrong = (0..choices.len()).find(|i| i != answer).unwrap_or(0);
            let key = char::from_digit(wrong as u32 + 1, 10).unwrap_or('1');
            walk.key(Key::Char(key));
        }
        Question::Number {
            answer, tolerance, ..
        } => {
            // Far from the answer (and from its tenfold factors), so "your answer: …" cannot
            // itself look like it.
            let wrong = wrong_number(*answer, *tolerance);
            walk.key(Key::Char('a'));
            for c in format!("{wrong}").chars() {
                walk.key(Key::Char(c));
            }
            walk.key(Key::Enter);
        }
    }
}

/// A number no reading of the screen would take for `answer` (± `tolerance`).
fn wrong_number(answer: f64, tolerance: f64) -> f64 {
    let far = answer.abs() * 3.0 + tolerance * 7.0 + 7.0;
    (far * 1000.0).round() / 1000.0 + 0.123
}

/// The panes `step` is about: its `pane`, and each pane its text or question names.
fn subjects(step: &crate::scenario::lesson::Step) -> Vec<Pane> {
    // Words that name a pane, and the pane's name (as a lesson's `pane` writes it).
    const NAMED: [(&str, &str); 8] = [
        ("portrait", "portrait"),
        ("trail", "portrait"),
        ("rings", "portrait"),
        ("time series", "series"),
        ("sweep", "sweep"),
        ("map", "map"),
        ("body pane", "body"),
        ("compare pane", "compare"),
    ];
    let mut out: Vec<Pane> = step
        .pane
        .as_deref()
        .and_then(Pane::named)
        .into_iter()
        .collect();
    let words = format!(
        "{} {}",
        step.text,
        step.question.as_ref().map_or("", Question::prompt)
    )
    .to_lowercase();
    for (word, name) in NAMED {
        if let Some(pane) = Pane::named(name)
            && has_word(&words, word)
            && !out.contains(&pane)
        {
            out.push(pane);
        }
    }
    out
}

/// Whether `text` holds `word` as a whole word (or words).
fn has_word(text: &str, word: &str) -> bool {
    text.match_indices(word).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + word.len()..].chars().next();
        !before.is_some_and(char::is_alphanumeric) && !after.is_some_and(char::is_alphanumeric)
    })
}

/// The screen's areas at [`SIZE`].
fn areas(app: &App) -> (ui::Screen, ui::ColumnLayout) {
    let screen = ui::screen(app, Rect::new(0, 0, SIZE.0, SIZE.1));
    let column = ui::column_layout(app, screen.right);
    (screen, column)
}

/// Each pane the step is about, drawn with room to be read.
fn room(app: &App, step: &crate::scenario::lesson::Step) -> Vec<String> {
    let (_, column) = areas(app);
    let mut out = Vec::new();
    for pane in subjects(step) {
        if !pane.offered_by(app.scenario.settings.model.kind()) {
            continue;
        }
        let rows = column
            .panes
            .iter()
            .find(|(p, _)| *p == pane)
            .map_or(0, |(_, r)| r.height.saturating_sub(2));
        if rows < ui::ASKED_ROWS {
            let front = column
                .panes
                .iter()
                .filter(|(p, _)| !matches!(p, Pane::Lesson))
                .map(|(p, _)| p.name())
                .collect::<Vec<_>>()
                .join(", ");
            out.push(if rows == 0 {
                format!(
                    "the step is about the {}, which is not on screen at {}x{} (shown: {}); \
                     give the step `pane = \"{}\"`",
                    pane.name(),
                    SIZE.0,
                    SIZE.1,
                    if front.is_empty() { "none" } else { &front },
                    pane_key(pane)
                )
            } else {
                format!(
                    "the step is about the {}, which has {rows} row(s) at {}x{}; it needs {}",
                    pane.name(),
                    SIZE.0,
                    SIZE.1,
                    ui::ASKED_ROWS
                )
            });
        }
    }
    out
}

/// A pane's name in a lesson's `pane`.
fn pane_key(pane: Pane) -> String {
    serde_json::to_value(pane)
        .ok()
        .and_then(|v| v.as_str().map(str::to_owned))
        .unwrap_or_default()
}

/// Keys the text names that hide what the step is about, or open what is open.
fn keys_named(app: &App, step: &crate::scenario::lesson::Step) -> Vec<String> {
    let subjects = subjects(step);
    let mut out = Vec::new();
    for (key, opens) in named_keys(&step.text) {
        let Some(pane) = Pane::KEYED.into_iter().find(|p| {
            p.binding()
                .is_some_and(|b| b.keys.contains(&Key::Char(key)))
        }) else {
            continue;
        };
        if !app.view.panes.shows(pane) {
            continue;
        }
        if subjects.contains(&pane) {
            out.push(format!(
                "the text names the key {key}, which hides the {} the step is about{}",
                pane.name(),
                if opens {
                    ""
                } else {
                    " (a text that begins \"M: …\" reads as \"press M\"; write \"The map: …\")"
                }
            ));
        } else if opens {
            out.push(format!(
                "the text asks to open the {} with {key}, but it is open already",
                pane.name()
            ));
        }
    }
    out
}

/// The keys a text names: `X: …` at a sentence's start, `press X`, `key X`, `X opens`,
/// `X toggles`, `X shows`; and whether it asks to open with it.
fn named_keys(text: &str) -> Vec<(char, bool)> {
    let words: Vec<&str> = text.split_whitespace().collect();
    let mut out = Vec::new();
    let single = |w: &str| {
        let w = w.trim_matches(|c: char| "()\"'`,.;".contains(c));
        let mut chars = w.chars();
        match (chars.next(), chars.next()) {
            (Some(c), None) if c.is_ascii_alphabetic() => Some(c),
            _ => None,
        }
    };
    for (i, w) in words.iter().enumerate() {
        let sentence_start = i == 0 || words[i - 1].ends_with(['.', '!', '?']);
        if sentence_start && let Some(k) = w.strip_suffix(':').and_then(single) {
            out.push((k, false));
            continue;
        }
        let Some(k) = single(w) else { continue };
        let before = i.checked_sub(1).map(|j| words[j].to_lowercase());
        let after = words.get(i + 1).map(|a| a.to_lowercase());
        let pressed = before
            .as_deref()
            .is_some_and(|b| ["press", "key", "(press", "type"].contains(&b));
        let acts = after.as_deref().is_some_and(|a| {
            ["opens", "toggles", "shows", "hides", "closes"]
                .iter()
                .any(|v| a.starts_with(v))
        });
        if pressed || acts {
            let opens = text.to_lowercase().contains("open")
                && after.as_deref().is_none_or(|a| !a.starts_with("hides"));
            out.push((k, opens));
        }
    }
    out
}

/// What on `screen` (besides the question itself) states `q`'s answer; `when` says at which
/// moment it was seen.
fn given_away(app: &App, q: &Question, screen: &[String], when: &str) -> Vec<String> {
    let mut out = Vec::new();
    let (areas, _) = areas(app);
    // The panel's predictions, with their values (not the lesson's `?`).
    for line in &app.scenario.derived.summary {
        if !line.predicts {
            continue;
        }
        let shown = panel_rows(screen, areas.left).into_iter().find_map(|row| {
            row.trim_start()
                .strip_prefix(line.label)
                .map(|rest| rest.trim().to_owned())
        });
        if let Some(value) = shown
            && !value.is_empty()
            && value != ui::HIDDEN
        {
            out.push(format!(
                "{when}, the panel's `{}` row ({value}) predicts the run the question asks about",
                line.label
            ));
        }
    }
    match q {
        Question::Number {
            prompt,
            answer,
            tolerance,
        } => {
            let near = |x: f64| (x - answer).abs() <= tolerance.max(1e-9 * answer.abs());
            // The prompt's own numbers are the question's, not its answer.
            let mut allowed = numbers(prompt);
            let inputs: Vec<&str> =
                crate::app::fields::Field::rows(app.scenario.settings.model.kind())
                    .into_iter()
                    .map(crate::app::fields::Field::label)
                    .collect();
            for row in screen {
                let tokens = tokens(row);
                for (i, t) in tokens.iter().enumerate() {
                    let Some(x) = number(t) else { continue };
                    let before = i.checked_sub(1).map(|j| tokens[j].as_str());
                    // A parameter's row: the student's own setting, not a finding.
                    if before.is_some_and(|b| inputs.contains(&b)) {
                        continue;
                    }
                    if let Some(k) = allowed.iter().position(|a| a.to_bits() == x.to_bits()) {
                        allowed.swap_remove(k);
                        continue;
                    }
                    let t = t.trim_end_matches(['.', '…', '?', '!', '%', '\'', '"']);
                    if near(x) {
                        out.push(format!(
                            "{when}, the screen shows {t}, which is the answer ({}): \"{}\"",
                            q.answer_text(),
                            row.trim()
                        ));
                    } else if before == Some("slope") && near(10f64.e_powf(x.abs())) {
                        out.push(format!(
                            "{when}, the slope {t} on screen gives a tenfold factor of {:.3}, \
                             which is the answer ({}): \"{}\"",
                            10f64.e_powf(x.abs()),
                            q.answer_text(),
                            row.trim()
                        ));
                    }
                }
            }
        }
        Question::Choice {
            prompt,
            choices,
            answer,
        } => {
            let right = choices[*answer].to_lowercase();
            // Short words ("yes", "A") are everywhere: only a phrase of four letters or more.
            if right.chars().filter(char::is_ascii_alphabetic).count() >= 4 {
                let text = screen.join("\n").to_lowercase();
                let seen = text.matches(&right).count();
                let asked = 1 + prompt.to_lowercase().matches(&right).count();
                if seen > asked {
                    out.push(format!(
                        "{when}, the screen states the right choice \"{}\" outside the question",
                        choices[*answer]
                    ));
                }
            }
        }
    }
    out
}

/// The rows of the panel (its columns of `screen`, inside its border).
fn panel_rows(screen: &[String], left: Rect) -> Vec<String> {
    screen
        .iter()
        .skip(usize::from(left.y) + 1)
        .take(usize::from(left.height.saturating_sub(2)))
        .map(|row| {
            row.chars()
                .skip(usize::from(left.x) + 1)
                .take(usize::from(left.width.saturating_sub(2)))
                .collect()
        })
        .collect()
}

/// A row's words: split at spaces, borders and the separators numbers sit between.
fn tokens(row: &str) -> Vec<String> {
    row.split(|c: char| c.is_whitespace() || "│┃|/,;=()[]{}<>≥≤±:".contains(c))
        .filter(|w| !w.is_empty())
        .map(str::to_owned)
        .collect()
}

/// A word as a number, when it is one (`0.9102`, `-1.01`, `1e4`, `1.000e4`, `10.`).
fn number(word: &str) -> Option<f64> {
    let w = word.trim_end_matches(['.', '…', '?', '!', '%', '\'', '"']);
    let w = w.trim_start_matches(['\'', '"', '+']);
    if !w.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '.') {
        return None;
    }
    w.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// The numbers of a text, as [`number`] reads them.
fn numbers(text: &str) -> Vec<f64> {
    tokens(text).iter().filter_map(|t| number(t)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_read_as_a_student_reads_them() {
        assert_eq!(
            numbers("slope -1.01 │ k 1.000e4, t 0.00/30"),
            vec![-1.01, 1e4, 0.0, 30.0]
        );
        assert_eq!(numbers("b^2-2a alpha_dot ×8 10^6"), Vec::<f64>::new());
        assert_eq!(numbers("to 0.9102 or more."), vec![0.9102]);
    }

    #[test]
    fn keys_are_named_at_a_sentence_start_or_pressed() {
        assert_eq!(named_keys("M: gravity a across"), vec![('M', false)]);
        assert_eq!(named_keys("The map: gravity"), vec![]);
        assert_eq!(named_keys("press t to open the series"), vec![('t', true)]);
        assert_eq!(named_keys("(e toggles them)"), vec![('e', false)]);
        assert_eq!(
            named_keys("a is the answer. B: the celt"),
            vec![('B', false)]
        );
    }

    /// A prediction row with its value gives the answer away; with the lesson's `?` it does
    /// not; a parameter's own row is the student's setting.
    #[test]
    fn a_prediction_with_its_value_is_found() {
        let preset =
            crate::scenario::shipped::resolve("kapitza-falls", &[]).expect("a shipped preset");
        let (app, _) = App::new(&preset, Options::at(30.0));
        let q = Question::Number {
            prompt: "At which b?".to_owned(),
            answer: 1.414,
            tolerance: 0.05,
        };
        // One row of the panel's (the second) holds `row`; the others are blank.
        let screen = |row: &str| {
            let mut rows = vec![format!("│{:<78}│", ""); usize::from(SIZE.1)];
            rows[1] = format!("│{row:<78}│");
            rows
        };
        let found = given_away(&app, &q, &screen("  b^2-2a         -0.56"), "now");
        assert!(
            found.iter().any(|f| f.contains("`b^2-2a` row")),
            "{found:?}"
        );
        let hidden = given_away(&app, &q, &screen("  b^2-2a             ?"), "now");
        assert!(hidden.is_empty(), "{hidden:?}");
        let input = given_away(&app, &q, &screen("  b              1.42"), "now");
        assert!(input.is_empty(), "the student's own b: {input:?}");
        let stated = given_away(&app, &q, &screen(" raise b to 1.4143 "), "now");
        assert_eq!(stated.len(), 1, "{stated:?}");
    }

    #[test]
    fn a_wrong_number_is_far_from_the_answer() {
        for (a, t) in [(10.0, 2.0), (0.9102, 0.02), (7.0, 0.0), (-3.0, 1.0)] {
            let w = wrong_number(a, t);
            assert!((w - a).abs() > 3.0 * t + 3.0, "{a} ± {t}: {w}");
        }
    }
}
