//! `rattleback check`: presets, themes and lessons checked without running them.

use crate::commands::failure::{Failure, Outcome};

use super::json_text;
use crate::commands::cli::{CheckArgs, ListFormat};
use crate::scenario::PresetError;
use crate::scenario::preset;
use crate::scenario::theme::ThemeSpec;

/// `rattleback check FILE...`.
pub fn check(args: &CheckArgs) -> Outcome {
    let mut problems = Vec::new();
    for path in &args.files {
        let label = crate::scenario::write::label(path);
        // Bounded, regular files only (a FIFO or /dev/zero is refused, not read), and an
        // encoding error names its line.
        match PresetError::read(path) {
            Err(e) => problems.push(e),
            Ok(src) if crate::scenario::lesson::is_lesson(&src) => {
                match crate::scenario::lesson::Lesson::parse(&src, &label, &label) {
                    Err(mut e) => {
                        problems.append(&mut e);
                        // Said, not left to be guessed: the steps were not run.
                        problems.push(PresetError::Invalid {
                            path: label.clone(),
                            line: None,
                            key: None,
                            message: "its steps were not walked (each run as a student meets \
                                      it at 80×24) because of the problems above: fix them and \
                                      check again"
                                .to_owned(),
                        });
                    }
                    // Read as a student meets it, step by step at 80×24.
                    Ok(lesson) => {
                        problems.extend(crate::explorer::review::review(&lesson).into_iter().map(
                            |f| PresetError::Invalid {
                                path: label.clone(),
                                line: crate::scenario::lesson::step_line(&src, f.step),
                                // Said as the explorer counts it (`step 4: "Title": …`,
                                // issue 81, L7); JSON keeps the key `step.3`.
                                key: Some(format!("step.{}", f.step)),
                                message: format!(
                                    "\"{}\": {}",
                                    lesson.steps[f.step].title, f.message
                                ),
                            },
                        ));
                    }
                }
            }
            Ok(src) if is_theme(&src) => {
                if let Err(mut e) = ThemeSpec::parse(&src, &label, &label) {
                    problems.append(&mut e);
                }
            }
            Ok(src) => problems.extend(preset::check(&src, &label)),
        }
    }
    if args.format == ListFormat::Json {
        let out = crate::commands::outputs::Check {
            schema_version: crate::commands::outputs::SCHEMA_VERSION,
            model: None,
            files: args
                .files
                .iter()
                .map(|p| crate::scenario::write::label(p))
                .collect(),
            problems: problems
                .iter()
                .map(crate::commands::outputs::Problem::of)
                .collect(),
        };
        say_raw!("{}", json_text(&out));
        return if problems.is_empty() {
            Ok(())
        } else {
            Err(Failure::said(2))
        };
    }
    if problems.is_empty() {
        say!("{} file(s) ok", args.files.len());
    }
    report(&problems)
}

pub(crate) fn report(problems: &[PresetError]) -> Outcome {
    if problems.is_empty() {
        Ok(())
    } else {
        Err(Failure::inputs(problems))
    }
}

/// Whether a file is a theme rather than a preset.
pub(crate) fn is_theme(src: &str) -> bool {
    src.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("theme") || t.contains_key("colors"))
}
