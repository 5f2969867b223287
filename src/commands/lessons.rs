//! `rattleback lessons`: the lessons listed, and `lessons new`'s skeleton.

use crate::scenario::text::one_line;

use crate::commands::failure::{Failure, Outcome};

use super::presets::found_at;
use super::presets::show;
use super::study::not_written;
use super::{name_width, print_list};

/// `rattleback lessons`: every lesson, like `presets`; or one (`lessons show NAME`).
pub fn lessons(args: &crate::commands::cli::LessonsArgs) -> Outcome {
    if let Some(crate::commands::cli::ShowAction::Show { name }) = &args.action {
        return show(crate::scenario::lesson::source_text(name));
    }
    let (entries, problems) = crate::scenario::lesson::catalogue();
    let json = crate::commands::outputs::LessonList {
        schema_version: crate::commands::outputs::SCHEMA_VERSION,
        model: None,
        lessons: entries,
    };
    let w = name_width(json.lessons.iter().map(|e| e.name.as_str()));
    let indent = " ".repeat(w + 1);
    print_list(
        &json.lessons,
        &json,
        args.format,
        &|e| {
            let about = if e.description.is_empty() {
                String::new()
            } else {
                format!("{indent}{}\n", one_line(&e.description))
            };
            format!(
                "{:<w$} {:<8} {} ({} steps)\n{about}{indent}{}\n\n",
                e.name,
                format!("{:?}", e.source).to_lowercase(),
                one_line(&e.title),
                e.steps,
                found_at(
                    format!("{:?}", e.source).eq_ignore_ascii_case("shipped"),
                    &e.path,
                    &format!("rattleback lessons show {}", e.name)
                )
            )
        },
        &problems,
    )
}

/// `rattleback lesson new NAME`: the commented skeleton, in the user's lessons folder (or
/// `--out`), never over a file without `--force`.
pub fn lesson_new(args: &crate::commands::cli::LessonNewArgs) -> Outcome {
    let name = &args.name;
    let valid = (1..=64).contains(&name.chars().count())
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        && !name.starts_with('-');
    if !valid {
        return Err(Failure::input(format!(
            "lesson new {}: a name is 1 to 64 letters, digits, `-` and `_` (not first): `rattleback lesson NAME` opens it",
            crate::scenario::text::one_line(name)
        )));
    }
    let path = match (&args.out, crate::scenario::lesson::user_dir()) {
        (Some(p), _) => p.clone(),
        (None, Some(dir)) => {
            if let Err(e) = std::fs::create_dir_all(&dir) {
                return Err(Failure::failed(format!("{}: {e}", dir.display())));
            }
            dir.join(format!("{name}.toml"))
        }
        (None, None) => {
            return Err(Failure::input(
                "no lessons folder (no home folder): give --out PATH, or set RATTLEBACK_CONFIG_DIR",
            ));
        }
    };
    let text = crate::scenario::lesson::SKELETON
        .replace("@NAME@", name)
        .replace("@TITLE@", &name.replace(['-', '_'], " "))
        .replace("@PATH@", &path.display().to_string());
    if let Err(e) = crate::scenario::write::write_atomic(&path, text.as_bytes(), args.force) {
        return Err(not_written(&path, &e));
    }
    say!(
        "wrote {}: edit it, check it with `rattleback check {}`, open it with `rattleback lesson {}`",
        path.display(),
        path.display(),
        if args.out.is_some() {
            path.display().to_string()
        } else {
            name.clone()
        }
    );
    Ok(())
}
