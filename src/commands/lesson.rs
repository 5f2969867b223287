//! `rattleback lesson`: a guided lesson in the explorer.

use super::explore::{Opening, open_explorer};
use super::shared::refuse_stdin;
use crate::commands;
use crate::commands::failure::{Failure, Outcome};
use crate::scenario::shipped::resolve;

pub fn run_lesson(args: &crate::commands::cli::LessonArgs) -> Outcome {
    if let Some(crate::commands::cli::LessonCommand::New(new)) = &args.new {
        return commands::lesson_new(new);
    }
    let Some(name) = args.lesson.as_deref() else {
        return Err(Failure::input(
            "lesson: give a lesson's NAME or PATH (`rattleback lessons` lists them), or `lesson new NAME`",
        ));
    };
    if name == "-" {
        return refuse_stdin("lesson -");
    }
    let lesson = match crate::scenario::lesson::resolve(name) {
        Ok(l) => l,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    // The first step's preset, else the default, opens the explorer; the lesson takes over.
    let preset = match lesson.steps[0].preset.clone() {
        Some(p) => Ok(p),
        None => resolve(crate::scenario::shipped::DEFAULT_PRESET, &[]),
    };
    let opening = Opening {
        look: &args.look,
        rec: &args.rec,
        mouse: false,
        lesson: Some(lesson),
        partner: None,
    };
    open_explorer(Some(preset), opening)
}
