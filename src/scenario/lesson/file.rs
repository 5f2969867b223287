//! The lesson file's shape as a JSON Schema (`docs/schemas/lesson.schema.json`), for an
//! editor's completion and for other programs that write lessons. The types here only describe
//! the file: [`super::Lesson::parse`] reads it (with each problem's line and key, the presets,
//! the `--set` changes and the conditions checked against the scenes); a test checks that every
//! key the parser takes is in the schema and every shipped lesson validates.

use schemars::JsonSchema;

/// A lesson file (`rattleback lesson NAME`; docs/guide.md, "Writing a lesson").
#[derive(JsonSchema)]
#[schemars(deny_unknown_fields, title = "rattleback lesson")]
pub struct LessonFile {
    /// The lesson.
    pub lesson: LessonTable,
    /// Its steps, in order (at least one).
    #[schemars(length(min = 1))]
    pub step: Vec<StepTable>,
}

/// `[lesson]`.
#[derive(JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct LessonTable {
    /// The title: the lesson pane's, the exported page's and the cast's.
    pub title: String,
    /// What it is about: in `rattleback lessons`, above the first step, under the page's title.
    pub description: Option<String>,
}

/// `[[step]]`.
#[derive(JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct StepTable {
    /// The step's title.
    pub title: String,
    /// What the student reads; placeholders `{time}`, `{reversals}`, `{at_least}`,
    /// `{at_most}`, `{section.key}` and `{panel.LABEL}` are written by the program.
    pub text: Option<String>,
    /// A preset loaded when the step begins (a shipped or user preset's name, or a path).
    pub preset: Option<String>,
    /// Then these changes, as `--set` takes them: `"section.key=value"`.
    pub set: Option<Vec<String>>,
    /// The pane the step is about: shown in front, with room.
    pub pane: Option<StepPane>,
    /// A preset drawn beside the step's run in the compare pane.
    pub partner: Option<String>,
    /// A prediction asked before the run, answered after it.
    pub question: Option<QuestionTable>,
    /// What `n` waits for (every condition given).
    pub until: Option<UntilTable>,
}

/// The panes a step may be about.
#[derive(JsonSchema)]
#[serde(rename_all = "snake_case")]
#[allow(dead_code)] // a description of the file: read by schemars only
pub enum StepPane {
    /// The phase portrait.
    Portrait,
    /// The time series.
    Series,
    /// The sweep of the small parameter.
    Sweep,
    /// The weak-* pane.
    Weak,
    /// The chart.
    Map,
    /// The body (or the pendulum on its pivot).
    Body,
    /// The comparison with the partner.
    Compare,
}

/// `[step.question]`: a choice (`choices` and `answer` one of them) or a number (`answer` a
/// number, `tolerance`).
#[derive(JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct QuestionTable {
    /// The question (placeholders as in the text).
    pub prompt: String,
    /// Two to nine choices (keys 1…9).
    #[schemars(length(min = 2, max = 9))]
    pub choices: Option<Vec<String>>,
    /// The right choice (one of `choices`), or the right number.
    pub answer: Answer,
    /// How far from a number still counts (≥ 0; numbers only).
    #[schemars(range(min = 0.0))]
    pub tolerance: Option<f64>,
}

/// A question's answer.
#[derive(JsonSchema)]
#[serde(untagged)]
#[allow(dead_code)] // a description of the file: read by schemars only
pub enum Answer {
    /// One of the choices.
    Choice(String),
    /// A number.
    Number(f64),
}

/// `[step.until]`.
#[derive(JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct UntilTable {
    /// The displayed time reached (not after the step's `t_end`).
    #[schemars(range(min = 0.0))]
    pub time: Option<f64>,
    /// This many reversals (or swings) of the run shown.
    #[schemars(range(min = 0))]
    pub reversals: Option<u64>,
    /// A parameter of the step's scene, as `--set` names it (`initial.omega_z`, `spring.k`).
    #[schemars(regex(pattern = r"^[a-z_]+\.[a-z_]+$"))]
    pub parameter: Option<String>,
    /// The parameter at or above this.
    pub at_least: Option<f64>,
    /// The parameter at or below this (not below `at_least`).
    pub at_most: Option<f64>,
}

/// The schema's text, as checked in.
///
/// # Panics
/// Never: a schema always serializes.
#[must_use]
pub fn schema() -> String {
    let mut s = serde_json::to_string_pretty(&schemars::schema_for!(LessonFile))
        .expect("schema serializes");
    s.push('\n');
    s
}
