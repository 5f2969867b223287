//! `rattleback themes`: the colour themes, listed or shown.

use crate::scenario::text::one_line;

use crate::commands::failure::Outcome;

use super::presets::found_at;
use super::presets::show;
use super::{name_width, print_list};

/// `rattleback themes`: every theme, like `presets`; or one (`themes show NAME`).
pub fn themes(args: &crate::commands::cli::ThemesArgs) -> Outcome {
    use crate::scenario::theme::{SHIPPED_THEMES, themes};
    if let Some(crate::commands::cli::ShowAction::Show { name }) = &args.action {
        return show(crate::scenario::theme::source_text(name));
    }
    let (all, problems) = themes();
    let user_dir = crate::scenario::shipped::config_dir().map(|d| d.join("themes"));
    let entries: Vec<crate::commands::outputs::ThemeEntry> = all
        .into_iter()
        .map(|(name, spec)| {
            let user = user_dir
                .as_ref()
                .map(|d| d.join(format!("{name}.toml")))
                .filter(|p| p.is_file());
            let (source, path) = match user {
                Some(p) => ("user", p.display().to_string()),
                None if SHIPPED_THEMES.iter().any(|(n, _)| *n == name) => {
                    ("shipped", format!("themes/{name}.toml"))
                }
                None => ("user", String::new()),
            };
            crate::commands::outputs::ThemeEntry {
                title: spec.name.clone(),
                description: spec.description.clone(),
                name,
                source,
                path,
            }
        })
        .collect();
    let json = crate::commands::outputs::ThemeList {
        schema_version: crate::commands::outputs::SCHEMA_VERSION,
        model: None,
        themes: entries,
    };
    let w = name_width(json.themes.iter().map(|e| e.name.as_str()));
    let indent = " ".repeat(w + 1);
    print_list(
        &json.themes,
        &json,
        args.format,
        &|e| {
            format!(
                "{:<w$} {:<8} {}\n{indent}{}\n{indent}{}\n\n",
                e.name,
                e.source,
                one_line(&e.title),
                found_at(
                    e.source == "shipped",
                    &e.path,
                    &format!("rattleback themes show {}", e.name)
                ),
                one_line(&e.description)
            )
        },
        &problems,
    )
}
