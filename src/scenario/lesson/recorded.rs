//! A lesson as a recording carries it (format 10 on): what a replay, a follower and the cast
//! need to show the lesson's pane as the lecturer saw it.

use serde::Serialize;

use super::{Lesson, ParameterBound, Question, Step, Until};

/// A lesson as a recording carries it in its header (format 10 on), so a replay, a follower and
/// the cast show the lesson's pane as the lecturer saw it: each step's words, its question and
/// its condition. The presets and changes a step applies are in the recording's own lines.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RecordedLesson {
    /// The lesson's title.
    pub title: String,
    /// What it is about (format 13 on; shown above its first step).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// Its steps.
    pub steps: Vec<RecordedStep>,
}

/// A step as recorded (see [`RecordedLesson`]).
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RecordedStep {
    /// Its title.
    pub title: String,
    /// Its text, as shown (placeholders written).
    pub text: String,
    /// Its question: `{"choices": [...], "answer": index}` or `{"answer": x, "tolerance": t}`
    /// with a `prompt`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub question: Option<RecordedQuestion>,
    /// Its condition's time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
    /// Its condition's count of reversals.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reversals: Option<usize>,
    /// Its condition's parameter (`section.key`), with `at_least` and `at_most`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parameter: Option<String>,
    /// The parameter's lower bound.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_least: Option<f64>,
    /// The parameter's upper bound.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_most: Option<f64>,
    /// The pane it opens.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pane: Option<String>,
}

/// A question as recorded.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RecordedQuestion {
    /// The question.
    pub prompt: String,
    /// The choices (a choice question), else empty.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub choices: Vec<String>,
    /// The right choice's index, or the right number.
    pub answer: f64,
    /// How far from a number still counts (a number question).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
}

impl Lesson {
    /// The lesson as a recording carries it.
    #[must_use]
    pub fn recorded(&self) -> RecordedLesson {
        RecordedLesson {
            title: self.title.clone(),
            description: self.description.clone(),
            steps: self
                .steps
                .iter()
                .map(|s| RecordedStep {
                    title: s.title.clone(),
                    text: s.text.clone(),
                    question: s.question.as_ref().map(|q| match q {
                        Question::Choice {
                            prompt,
                            choices,
                            answer,
                        } => RecordedQuestion {
                            prompt: prompt.clone(),
                            choices: choices.clone(),
                            answer: *answer as f64,
                            tolerance: None,
                        },
                        Question::Number {
                            prompt,
                            answer,
                            tolerance,
                        } => RecordedQuestion {
                            prompt: prompt.clone(),
                            choices: Vec::new(),
                            answer: *answer,
                            tolerance: Some(*tolerance),
                        },
                    }),
                    time: s.until.time,
                    reversals: s.until.reversals,
                    parameter: s.until.parameter.as_ref().map(|p| p.key.clone()),
                    at_least: s.until.parameter.as_ref().and_then(|p| p.at_least),
                    at_most: s.until.parameter.as_ref().and_then(|p| p.at_most),
                    pane: s.pane.clone(),
                })
                .collect(),
        }
    }
}

impl RecordedLesson {
    /// The lesson a replay shows: every step's words, question and condition, no preset (the
    /// recording's lines load them). `None` when a step is not a step any more (an answer out
    /// of its choices, no step at all).
    #[must_use]
    pub fn lesson(&self) -> Option<Lesson> {
        if self.steps.is_empty() {
            return None;
        }
        let steps = self
            .steps
            .iter()
            .map(|s| {
                let question = match &s.question {
                    None => None,
                    Some(q) if !q.choices.is_empty() => {
                        let answer = q.answer;
                        (answer >= 0.0
                            && answer.fract() == 0.0
                            && (answer as usize) < q.choices.len())
                        .then(|| Question::Choice {
                            prompt: q.prompt.clone(),
                            choices: q.choices.clone(),
                            answer: answer as usize,
                        })
                        .map(Some)?
                    }
                    Some(q) => Some(Question::Number {
                        prompt: q.prompt.clone(),
                        answer: q.answer,
                        tolerance: q.tolerance.unwrap_or(0.0),
                    }),
                };
                Some(Step {
                    title: s.title.clone(),
                    text: s.text.clone(),
                    preset: None,
                    set: Vec::new(),
                    question,
                    until: Until {
                        time: s.time,
                        reversals: s.reversals,
                        parameter: s.parameter.as_ref().map(|key| ParameterBound {
                            key: key.clone(),
                            at_least: s.at_least,
                            at_most: s.at_most,
                        }),
                    },
                    pane: s.pane.clone(),
                    partner: None,
                })
            })
            .collect::<Option<Vec<Step>>>()?;
        Some(Lesson {
            name: String::new(),
            title: self.title.clone(),
            description: self.description.clone(),
            steps,
        })
    }
}
