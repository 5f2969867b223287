//! Lessons: a TOML file of steps the explorer walks a student through (`rattleback lesson NAME`).
//! Every key, placeholder, pane and condition is documented with an example in docs/guide.md
//! ("Writing a lesson"), and `docs/schemas/lesson.schema.json` describes the file; in short:
//!
//! ```toml
//! [lesson]
//! title = "The first reversal"
//! description = "What the spin does below the critical ratio"   # optional, shown at step 1
//!
//! [[step]]
//! title = "A body that turns back"
//! text = "k = {spring.k}: press space and watch the spin angle."   # placeholders: below
//! preset = "subcritical"             # optional: loaded when the step begins
//! set = ["spring.k=1e6"]             # optional: then these changes, as `--set`
//! pane = "series"                    # optional: the pane the step is about (portrait, series,
//!                                    # sweep, weak, map, body, compare): shown, given room
//! partner = "celt-clockwise"         # optional: drawn beside the step's run (compare pane)
//!
//! [step.question]                    # optional: asked before the run
//! prompt = "Will the spin reverse before t = {time}?"
//! choices = ["yes", "no"]            # a choice (keys 1, 2…) …
//! answer = "yes"
//! # … or a number (key a, then type it): answer = 7, tolerance = 0.5
//!
//! [step.until]                       # optional: what `n` waits for (all that are given)
//! time = 10.0                        # the displayed time reached
//! reversals = 2                      # reversals (the celt: reversals) of the run shown
//! parameter = "spring.k"             # any parameter `--set` takes, of the step's scene …
//! at_least = 1e6                     # … at or above (and/or `at_most`, not below it)
//! ```
//!
//! Placeholders in a step's text and prompt are written by the program, so the number a
//! student reads is the one the step uses: `{time}`, `{reversals}`, `{at_least}`, `{at_most}`
//! from the step's condition, `{section.key}` (`{spring.k}`, `{initial.omega_z}`…) from the
//! step's scenario (its preset and changes, else the one before), `{panel.LABEL}` (a number of
//! the panel: `{panel.critical}`, `{panel.b^2-2a}`) as the panel writes it.
//!
//! Every problem is reported with the file, the line and the key, like presets (`rattleback
//! check FILE` validates lessons too, and reads each step as a student meets it:
//! `crate::explorer::review`).

use std::path::{Path, PathBuf};

use serde::Serialize;
use toml::Value;

use super::error::{PresetError, SourceMap};
use super::preset::{Override, Preset};

pub mod file;
mod placeholders;
mod recorded;
mod skeleton;

pub use placeholders::condition_value;
use placeholders::with_placeholders;
pub use recorded::{RecordedLesson, RecordedQuestion, RecordedStep};
pub use skeleton::SKELETON;

/// The environment-independent folder of the shipped lessons, and their text.
pub const SHIPPED_LESSONS: &[(&str, &str)] = &[
    (
        "first-reversal",
        include_str!("../../../lessons/first-reversal.toml"),
    ),
    (
        "stiff-limit",
        include_str!("../../../lessons/stiff-limit.toml"),
    ),
    ("tapping", include_str!("../../../lessons/tapping.toml")),
    (
        "kapitza-threshold",
        include_str!("../../../lessons/kapitza-threshold.toml"),
    ),
    (
        "kapitza-ripple",
        include_str!("../../../lessons/kapitza-ripple.toml"),
    ),
    ("two-ways", include_str!("../../../lessons/two-ways.toml")),
    (
        "kapitza-chart",
        include_str!("../../../lessons/kapitza-chart.toml"),
    ),
    (
        "celt-chart",
        include_str!("../../../lessons/celt-chart.toml"),
    ),
];

/// A prediction asked before a step's run; the answer is revealed after it.
#[derive(Clone, Debug, PartialEq)]
pub enum Question {
    /// One of a few choices.
    Choice {
        /// The question.
        prompt: String,
        /// The choices, in key order (1, 2, …).
        choices: Vec<String>,
        /// Index of the right one.
        answer: usize,
    },
    /// A number, right within a tolerance.
    Number {
        /// The question.
        prompt: String,
        /// The right value.
        answer: f64,
        /// How far from it still counts as right.
        tolerance: f64,
    },
}

impl Question {
    /// The question's text.
    #[must_use]
    pub fn prompt(&self) -> &str {
        match self {
            Self::Choice { prompt, .. } | Self::Number { prompt, .. } => prompt,
        }
    }

    /// The right answer, as shown.
    #[must_use]
    pub fn answer_text(&self) -> String {
        match self {
            Self::Choice {
                choices, answer, ..
            } => choices[*answer].clone(),
            Self::Number {
                answer, tolerance, ..
            } if *tolerance > 0.0 => format!("{answer} (± {tolerance})"),
            Self::Number { answer, .. } => format!("{answer}"),
        }
    }
}

/// What `n` waits for before moving on (every condition given must hold).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Until {
    /// The displayed time at least this.
    pub time: Option<f64>,
    /// At least this many reversals of the full motion shown.
    pub reversals: Option<usize>,
    /// A parameter (`section.key`) within bounds.
    pub parameter: Option<ParameterBound>,
}

/// A parameter's bounds in a condition.
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterBound {
    /// `section.key`, as in presets.
    pub key: String,
    /// At or above.
    pub at_least: Option<f64>,
    /// At or below.
    pub at_most: Option<f64>,
}

/// One step.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// Its title.
    pub title: String,
    /// What the student reads.
    pub text: String,
    /// A preset loaded when the step begins.
    pub preset: Option<Preset>,
    /// Then these changes.
    pub set: Vec<Override>,
    /// A prediction asked first.
    pub question: Option<Question>,
    /// What `n` waits for.
    pub until: Until,
    /// The pane the step is about (`series`, `sweep`, `weak`, `map`, `body`, `compare`):
    /// opened when the step begins and given room beside the lesson.
    pub pane: Option<String>,
    /// A preset drawn beside the step's own in the compare pane (which opens with it).
    pub partner: Option<Preset>,
}

/// The panes a step may ask for.
pub const STEP_PANES: [&str; 7] = [
    "portrait", "series", "sweep", "weak", "map", "body", "compare",
];

/// A lesson.
#[derive(Clone, Debug, PartialEq)]
pub struct Lesson {
    /// What `rattleback lesson` takes (the file stem).
    pub name: String,
    /// Its title.
    pub title: String,
    /// What it is about.
    pub description: String,
    /// The steps, in order (at least one).
    pub steps: Vec<Step>,
}

/// Shipped or the user's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Source {
    /// Inside the binary.
    Shipped,
    /// In the user's lessons folder.
    User,
}

/// One row of `rattleback lessons`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Entry {
    /// What `rattleback lesson` takes.
    pub name: String,
    /// The lesson's title.
    pub title: String,
    /// What it is about (empty when the file has no `description`).
    pub description: String,
    /// Its number of steps.
    pub steps: usize,
    /// Shipped or user.
    pub source: Source,
    /// The file.
    pub path: String,
}

/// The user's lessons folder (`<config>/lessons`).
#[must_use]
pub fn user_dir() -> Option<PathBuf> {
    super::shipped::config_dir().map(|d| d.join("lessons"))
}

/// Whether a TOML text is a lesson (it has a `[lesson]` table).
#[must_use]
pub fn is_lesson(src: &str) -> bool {
    src.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("lesson"))
}

/// Every lesson, shipped then the user's (same name replaces), with the problems of broken
/// user files.
#[must_use]
pub fn catalogue() -> (Vec<Entry>, Vec<PresetError>) {
    let mut entries = Vec::new();
    let mut problems = Vec::new();
    for (name, src) in SHIPPED_LESSONS {
        match Lesson::parse(src, &format!("lessons/{name}.toml (shipped)"), name) {
            Ok(l) => entries.push(Entry {
                name: (*name).to_owned(),
                title: l.title,
                description: l.description,
                steps: l.steps.len(),
                source: Source::Shipped,
                path: format!("lessons/{name}.toml"),
            }),
            Err(mut e) => problems.append(&mut e),
        }
    }
    if let Some(dir) = user_dir() {
        let (files, mut odd) = super::shipped::toml_files_and_unnameable(&dir);
        problems.append(&mut odd);
        for path in files {
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            match Lesson::load(&path) {
                Ok(l) => {
                    entries.retain(|e| e.name != name);
                    entries.push(Entry {
                        name,
                        title: l.title,
                        description: l.description,
                        steps: l.steps.len(),
                        source: Source::User,
                        path: path.display().to_string(),
                    });
                }
                Err(mut e) => problems.append(&mut e),
            }
        }
    }
    (entries, problems)
}

/// The lesson `name_or_path`: a file, else a user lesson, else a shipped one.
///
/// # Errors
/// Not found, or the file's first problem.
pub fn resolve(name_or_path: &str) -> Result<Lesson, PresetError> {
    let path = Path::new(name_or_path);
    if path.is_file() {
        return Lesson::load(path).map_err(|mut e| e.swap_remove(0));
    }
    if let Some(user) = user_dir().map(|d| d.join(format!("{name_or_path}.toml")))
        && user.is_file()
    {
        return Lesson::load(&user).map_err(|mut e| e.swap_remove(0));
    }
    if let Some((name, src)) = SHIPPED_LESSONS.iter().find(|(n, _)| *n == name_or_path) {
        return Lesson::parse(src, &format!("lessons/{name}.toml (shipped)"), name)
            .map_err(|mut e| e.swap_remove(0));
    }
    let available: Vec<String> = catalogue().0.into_iter().map(|e| e.name).collect();
    Err(PresetError::NotFound {
        noun: "lesson",
        name: name_or_path.to_owned(),
        available: available.join(", "),
    })
}

/// The text of the lesson `name_or_path` (a file, a user lesson, or a shipped one), to copy and
/// edit (`rattleback lessons show NAME`, issue 81).
///
/// # Errors
/// Not found, or not a valid lesson (its first problem).
pub fn source_text(name_or_path: &str) -> Result<String, PresetError> {
    resolve(name_or_path)?;
    let path = Path::new(name_or_path);
    if path.is_file() {
        return PresetError::read(path);
    }
    if let Some(user) = user_dir().map(|d| d.join(format!("{name_or_path}.toml")))
        && user.is_file()
    {
        return PresetError::read(&user);
    }
    Ok(SHIPPED_LESSONS
        .iter()
        .find(|(n, _)| *n == name_or_path)
        .map(|(_, src)| (*src).to_owned())
        .unwrap_or_default())
}

/// The line of step `index` (0-based) in a lesson's text, for a finding's location.
#[must_use]
pub fn step_line(src: &str, index: usize) -> Option<usize> {
    SourceMap::new(src).find_path(&format!("step.{index}"))
}

impl Lesson {
    /// Reads a lesson file.
    ///
    /// # Errors
    /// Every problem, located.
    pub fn load(path: &Path) -> Result<Self, Vec<PresetError>> {
        let src = PresetError::read(path).map_err(|e| vec![e])?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        Self::parse(&src, &path.display().to_string(), &stem)
    }

    /// Parses a lesson; `label` names the file in errors, `name` is what `lesson` takes.
    ///
    /// # Errors
    /// Every problem, each with the line and the key.
    pub fn parse(src: &str, label: &str, name: &str) -> Result<Self, Vec<PresetError>> {
        let map = SourceMap::new(src);
        let table = map.parse_table(label).map_err(|e| vec![e])?;
        let mut problems: Vec<PresetError> = Vec::new();
        let mut at = |path: &str, message: String| {
            let line = map.find_path(path).or_else(|| {
                // A missing key belongs to its table.
                path.rsplit_once('.')
                    .and_then(|(parent, _)| map.find_path(parent))
            });
            problems.push(PresetError::Invalid {
                path: label.to_owned(),
                line: Some(line.unwrap_or(1)),
                key: Some(path.to_owned()),
                message,
            });
        };
        for key in table.keys() {
            if key != "lesson" && key != "step" {
                at(
                    key,
                    format!(
                        "unknown section `{key}`, expected `lesson` or `step`{}",
                        super::text::did_you_mean(key, ["lesson", "step"])
                    ),
                );
            }
        }
        let (mut title, mut description) = (String::new(), String::new());
        match table.get("lesson") {
            Some(Value::Table(t)) => {
                for (k, v) in t {
                    match (k.as_str(), v) {
                        ("title", Value::String(s)) => title.clone_from(s),
                        ("description", Value::String(s)) => description.clone_from(s),
                        ("title" | "description", _) => {
                            at(&format!("lesson.{k}"), "expected text in quotes".to_owned());
                        }
                        _ => at(
                            &format!("lesson.{k}"),
                            format!(
                                "unknown key `{k}`, expected one of `title`, `description`{}",
                                super::text::did_you_mean(k, ["title", "description"])
                            ),
                        ),
                    }
                }
                if title.trim().is_empty() {
                    at(
                        "lesson.title",
                        "missing required value (text in quotes)".to_owned(),
                    );
                }
            }
            Some(_) => at("lesson", "expected a [lesson] table".to_owned()),
            None => at(
                "lesson",
                "missing the [lesson] table (title = \"…\")".to_owned(),
            ),
        }
        let steps = match table.get("step") {
            Some(Value::Array(items)) if !items.is_empty() => items
                .iter()
                .enumerate()
                .scan(None, |scene, (i, item)| {
                    Some(step(item, &format!("step.{i}"), scene, &mut at))
                })
                .flatten()
                .collect(),
            Some(_) => {
                at("step", "expected [[step]] tables, at least one".to_owned());
                Vec::new()
            }
            None => {
                at("step", "a lesson needs at least one [[step]]".to_owned());
                Vec::new()
            }
        };
        if problems.is_empty() {
            Ok(Self {
                name: name.to_owned(),
                title,
                description,
                steps,
            })
        } else {
            Err(problems)
        }
    }
}

/// The keys a step takes.
const STEP_KEYS: [&str; 8] = [
    "title", "text", "preset", "set", "question", "until", "pane", "partner",
];

fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Float(f) if f.is_finite() => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// The parameters a condition may watch: every parameter of every scene, as `--set` names
/// it (`section.key`), and the run's `t_end` and `tolerance`.
#[must_use]
pub fn watchable() -> Vec<String> {
    let mut keys: Vec<String> = Vec::new();
    for kind in crate::physics::ModelKind::ALL {
        for p in kind.params() {
            let key = format!("{}.{}", p.section, p.key);
            if !keys.contains(&key) {
                keys.push(key);
            }
        }
    }
    keys.extend(["run.t_end".to_owned(), "run.tolerance".to_owned()]);
    keys
}

/// Step `path` of a lesson; `scene` is the scenario the step before left (its preset and
/// changes), and becomes this step's.
#[allow(clippy::too_many_lines)] // one step's keys, each checked in the file's order
fn step(
    item: &Value,
    path: &str,
    scene: &mut Option<Preset>,
    at: &mut dyn FnMut(&str, String),
) -> Option<Step> {
    let Value::Table(t) = item else {
        at(path, "expected a [[step]] table".to_owned());
        return None;
    };
    let text_of = |k: &str, at: &mut dyn FnMut(&str, String)| match t.get(k) {
        Some(Value::String(s)) => Some(s.clone()),
        Some(_) => {
            at(&format!("{path}.{k}"), "expected text in quotes".to_owned());
            None
        }
        None => None,
    };
    for k in t.keys() {
        if !STEP_KEYS.contains(&k.as_str()) {
            at(
                &format!("{path}.{k}"),
                format!(
                    "unknown key `{k}`, expected one of {}{}",
                    STEP_KEYS.map(|s| format!("`{s}`")).join(", "),
                    super::text::did_you_mean(k, STEP_KEYS)
                ),
            );
        }
    }
    let title = text_of("title", at);
    if title.is_none() && !t.contains_key("title") {
        at(
            &format!("{path}.title"),
            "missing required value (text in quotes)".to_owned(),
        );
    }
    let text = text_of("text", at).unwrap_or_default();
    let named = |key: &str, at: &mut dyn FnMut(&str, String)| match text_of(key, at) {
        Some(name) => match super::shipped::resolve(&name, &[]) {
            Ok(p) => Some(p),
            Err(e) => {
                at(&format!("{path}.{key}"), e.to_string());
                None
            }
        },
        None => None,
    };
    let preset = named("preset", at);
    let partner = named("partner", at);
    let set = step_set(t.get("set"), preset.as_ref(), path, at);
    let question = match t.get("question") {
        None => None,
        Some(Value::Table(q)) => question(q, &format!("{path}.question"), at),
        Some(_) => {
            at(
                &format!("{path}.question"),
                "expected a [step.question] table".to_owned(),
            );
            None
        }
    };
    let until = match t.get("until") {
        None => Until::default(),
        Some(Value::Table(u)) => until(u, &format!("{path}.until"), at),
        Some(_) => {
            at(
                &format!("{path}.until"),
                "expected a [step.until] table".to_owned(),
            );
            Until::default()
        }
    };
    let pane = step_pane(t.get("pane"), path, at);
    // The step's scenario: its preset (else the one before, else the default) with its changes.
    let base = preset
        .clone()
        .or_else(|| scene.clone())
        .or_else(|| super::shipped::resolve(super::shipped::DEFAULT_PRESET, &[]).ok());
    if let Some(p) =
        base.and_then(|p| Preset::parse(&p.to_toml(), "the step's preset", "step", &set).ok())
    {
        impossible(&until, &p, &format!("{path}.until"), at);
        *scene = Some(p);
    }
    let text = with_placeholders(&text, &until, scene.as_ref(), &format!("{path}.text"), at);
    let question = question.map(|mut q| {
        let written = with_placeholders(
            q.prompt(),
            &until,
            scene.as_ref(),
            &format!("{path}.question.prompt"),
            at,
        );
        match &mut q {
            Question::Choice { prompt, .. } | Question::Number { prompt, .. } => *prompt = written,
        }
        q
    });
    Some(Step {
        title: title.unwrap_or_default(),
        text,
        preset,
        set,
        question,
        until,
        pane,
        partner,
    })
}

fn question(q: &toml::Table, path: &str, at: &mut dyn FnMut(&str, String)) -> Option<Question> {
    const KEYS: [&str; 4] = ["prompt", "choices", "answer", "tolerance"];
    for k in q.keys() {
        if !KEYS.contains(&k.as_str()) {
            at(
                &format!("{path}.{k}"),
                format!(
                    "unknown key `{k}`, expected one of `prompt`, `choices`, `answer`, `tolerance`{}",
                    super::text::did_you_mean(k, KEYS)
                ),
            );
        }
    }
    let Some(Value::String(prompt)) = q.get("prompt") else {
        at(
            &format!("{path}.prompt"),
            "missing required value (text in quotes)".to_owned(),
        );
        return None;
    };
    let answer = q.get("answer");
    match q.get("choices") {
        Some(Value::Array(items)) => {
            let choices: Option<Vec<String>> = items
                .iter()
                .map(|v| v.as_str().map(str::to_owned))
                .collect();
            let Some(choices) = choices.filter(|c| (2..=9).contains(&c.len())) else {
                at(
                    &format!("{path}.choices"),
                    "expected 2 to 9 texts in quotes".to_owned(),
                );
                return None;
            };
            let Some(index) = answer
                .and_then(Value::as_str)
                .and_then(|a| choices.iter().position(|c| c == a))
            else {
                at(
                    &format!("{path}.answer"),
                    format!(
                        "expected one of the choices in quotes: {}",
                        choices
                            .iter()
                            .map(|c| format!("\"{c}\""))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                );
                return None;
            };
            if q.contains_key("tolerance") {
                at(
                    &format!("{path}.tolerance"),
                    "only for a number answer".to_owned(),
                );
            }
            Some(Question::Choice {
                prompt: prompt.clone(),
                choices,
                answer: index,
            })
        }
        Some(_) => {
            at(
                &format!("{path}.choices"),
                "expected 2 to 9 texts in quotes".to_owned(),
            );
            None
        }
        None => {
            let Some(value) = answer.and_then(number) else {
                at(
                    &format!("{path}.answer"),
                    "expected a finite number (or give `choices` and a choice)".to_owned(),
                );
                return None;
            };
            let tolerance = match q.get("tolerance") {
                None => 0.0,
                Some(v) => {
                    let Some(x) = number(v).filter(|x| *x >= 0.0) else {
                        at(
                            &format!("{path}.tolerance"),
                            "expected a finite number ≥ 0".to_owned(),
                        );
                        return None;
                    };
                    x
                }
            };
            Some(Question::Number {
                prompt: prompt.clone(),
                answer: value,
                tolerance,
            })
        }
    }
}

/// A step's `set`: each change checked like `--set` on the step's preset (else the default).
fn step_set(
    v: Option<&Value>,
    preset: Option<&Preset>,
    path: &str,
    at: &mut dyn FnMut(&str, String),
) -> Vec<Override> {
    let mut set = Vec::new();
    match v {
        None => {}
        Some(Value::Array(items)) => {
            for v in items {
                match v.as_str().map(str::parse::<Override>) {
                    Some(Ok(o)) => set.push(o),
                    Some(Err(e)) => at(&format!("{path}.set"), e),
                    None => at(
                        &format!("{path}.set"),
                        "expected \"section.key=value\" texts".to_owned(),
                    ),
                }
            }
            // Names and values checked like `--set` (on the step's preset, else the default).
            let checked = match preset {
                Some(p) => Preset::parse(&p.to_toml(), "the step's preset", "step", &set),
                None => super::shipped::resolve(super::shipped::DEFAULT_PRESET, &set),
            };
            if let Err(e) = checked {
                at(&format!("{path}.set"), e.to_string());
            }
        }
        Some(_) => at(
            &format!("{path}.set"),
            "expected a list of \"section.key=value\" texts".to_owned(),
        ),
    }
    set
}

/// A step's `pane`, checked against [`STEP_PANES`].
fn step_pane(v: Option<&Value>, path: &str, at: &mut dyn FnMut(&str, String)) -> Option<String> {
    match v {
        None => None,
        Some(Value::String(p)) if STEP_PANES.contains(&p.as_str()) => Some(p.clone()),
        Some(v) => {
            at(
                &format!("{path}.pane"),
                format!(
                    "{v}: allowed {}{}",
                    STEP_PANES.join(", "),
                    super::text::did_you_mean(v.as_str().unwrap_or_default(), STEP_PANES)
                ),
            );
            None
        }
    }
}

/// A condition the step's own scenario can never meet: a time after its `t_end`, a parameter of
/// the other model.
fn impossible(until: &Until, preset: &Preset, path: &str, at: &mut dyn FnMut(&str, String)) {
    if let Some(t) = until.time
        && t > preset.run.t_end
    {
        at(
            &format!("{path}.time"),
            format!(
                "{t} is after the step's t_end = {}: the step could never complete",
                preset.run.t_end
            ),
        );
    }
    if let Some(p) = &until.parameter {
        let kind = preset.model.kind();
        let has = |m: crate::physics::ModelKind| {
            m.params()
                .iter()
                .any(|s| format!("{}.{}", s.section, s.key) == p.key)
        };
        // Another scene's parameter: this step's scene never has it.
        let theirs = !has(kind) && crate::physics::ModelKind::ALL.into_iter().any(has);
        if theirs {
            at(
                &format!("{path}.parameter"),
                format!(
                    "'{}' is not a parameter of the step's scene ({}): the step could never complete",
                    p.key,
                    kind.name()
                ),
            );
        }
    }
}

fn until(u: &toml::Table, path: &str, at: &mut dyn FnMut(&str, String)) -> Until {
    const KEYS: [&str; 5] = ["time", "reversals", "parameter", "at_least", "at_most"];
    let mut out = Until::default();
    for (k, v) in u {
        let here = format!("{path}.{k}");
        match k.as_str() {
            "time" => match number(v).filter(|x| *x >= 0.0) {
                Some(x) => out.time = Some(x),
                None => at(&here, "expected a finite number ≥ 0".to_owned()),
            },
            "reversals" => match v.as_integer().and_then(|n| usize::try_from(n).ok()) {
                Some(n) => out.reversals = Some(n),
                None => at(&here, "expected a whole number ≥ 0".to_owned()),
            },
            "parameter" | "at_least" | "at_most" => {}
            _ => at(
                &here,
                format!(
                    "unknown key `{k}`, expected one of `time`, `reversals`, `parameter`, `at_least`, `at_most`{}",
                    super::text::did_you_mean(k, KEYS)
                ),
            ),
        }
    }
    let bound = |k: &str, at: &mut dyn FnMut(&str, String)| match u.get(k) {
        None => None,
        Some(v) => {
            let n = number(v);
            if n.is_none() {
                at(
                    &format!("{path}.{k}"),
                    "expected a finite number".to_owned(),
                );
            }
            n
        }
    };
    let (lo, hi) = (bound("at_least", at), bound("at_most", at));
    match u.get("parameter") {
        Some(Value::String(key)) => {
            let watchable = watchable();
            if !watchable.contains(key) {
                at(
                    &format!("{path}.parameter"),
                    format!(
                        "'{key}' is not a parameter; allowed: {}{}",
                        watchable.join(", "),
                        super::text::did_you_mean(key, watchable.iter().map(String::as_str))
                    ),
                );
            } else if lo.is_none() && hi.is_none() {
                at(
                    &format!("{path}.parameter"),
                    "give `at_least` or `at_most` (or both)".to_owned(),
                );
            } else if let (Some(l), Some(h)) = (lo, hi)
                && l > h
            {
                // No value is both at least `l` and at most `h`: the step could never end.
                at(
                    &format!("{path}.at_least"),
                    format!(
                        "{l} is above `at_most` ({h}): no value meets both, so the step could never end"
                    ),
                );
            }
            // Kept even when refused: the text's placeholders are written from the bounds
            // given, so one problem is reported once (the lesson is refused anyway).
            out.parameter = Some(ParameterBound {
                key: key.clone(),
                at_least: lo,
                at_most: hi,
            });
        }
        Some(_) => at(
            &format!("{path}.parameter"),
            "expected \"section.key\" in quotes".to_owned(),
        ),
        None if lo.is_some() || hi.is_some() => at(
            &format!("{path}.parameter"),
            "`at_least`/`at_most` need a `parameter`".to_owned(),
        ),
        None => {}
    }
    out
}
