//! `rattleback presets`: the shipped and the user's presets, listed or shown.

use crate::scenario::text::one_line;

use crate::commands::failure::{Failure, Outcome};

use super::{name_width, print_list};
use crate::commands::cli::{PresetsAction, PresetsArgs};
use crate::scenario::shipped::catalogue;

/// `rattleback presets`.
pub fn presets(args: &PresetsArgs) -> Outcome {
    if let Some(PresetsAction::Show { name }) = &args.action {
        return match crate::scenario::shipped::source_text(name) {
            Ok(text) => {
                say_raw!("{text}");
                Ok(())
            }
            Err(e) => Err(Failure::input(e)),
        };
    }
    let (entries, problems) = catalogue();
    let json = crate::commands::outputs::PresetList {
        schema_version: crate::commands::outputs::SCHEMA_VERSION,
        model: None,
        presets: entries.clone(),
    };
    let w = name_width(entries.iter().map(|e| e.name.as_str()));
    let indent = " ".repeat(w + 1);
    print_list(
        &entries,
        &json,
        args.format,
        &|e| {
            format!(
                "{:<w$} {:<10} {:<8} {}\n{indent}{}\n{indent}{}\n\n",
                e.name,
                e.model.name(),
                format!("{:?}", e.source).to_lowercase(),
                one_line(&e.title),
                found_at(
                    e.source == crate::scenario::shipped::Source::Shipped,
                    &e.path,
                    &format!("rattleback presets show {}", e.name)
                ),
                one_line(&e.description)
            )
        },
        &problems,
    )
}

/// Where a listed file is, as its text line says it: a user's file by its path; a shipped one
/// is built into the program (its path in the source tree is not on an installed machine), so
/// the line says how to see it instead.
pub(crate) fn found_at(shipped: bool, path: &str, show: &str) -> String {
    if shipped {
        format!("built in ({show})")
    } else {
        one_line(path)
    }
}

/// Prints a shipped or user file's TOML (`themes show`, `lessons show`).
pub(crate) fn show(text: Result<String, crate::scenario::PresetError>) -> Outcome {
    match text {
        Ok(text) => {
            say_raw!("{text}");
            Ok(())
        }
        Err(e) => Err(Failure::input(e)),
    }
}
