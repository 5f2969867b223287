//! The layering rules docs/architecture.md states, checked on the sources:
//! - `physics` is headless: no terminal crate, no threads, no clock;
//! - `scenario` imports only `physics`; `sim` only `physics`; `app` no `ui`, no terminal crate,
//!   no `record`; `record` never `ui` (the cast export, which draws, is `cast.rs`, above both);
//! - `study` imports only `physics` (and rayon, plotters); `sim` may run its per-rung functions;
//! - only `main.rs` and `commands/` (the binary shell) import `cli`.

use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable source dir") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn src() -> PathBuf {
    Path::new(root!()).join("src")
}

/// Every file of `layer` (a folder or a file under `src/`) with its text.
fn layer(name: &str) -> Vec<(PathBuf, String)> {
    let path = src().join(name);
    let mut files = Vec::new();
    if path.is_dir() {
        rust_files(&path, &mut files);
    } else {
        files.push(path.with_extension("rs"));
    }
    assert!(!files.is_empty(), "{name}: no sources");
    files
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(&f).expect("readable");
            (f, text)
        })
        .collect()
}

#[track_caller]
fn forbid(name: &str, banned: &[&str]) {
    for (file, text) in layer(name) {
        for b in banned {
            assert!(!text.contains(b), "{} mentions {b}", file.display());
        }
    }
}

#[test]
fn physics_is_headless() {
    forbid(
        "physics",
        &[
            "ratatui",
            "crossterm",
            "std::thread",
            "std::time",
            "Instant",
            "crate::sim",
            "crate::app",
        ],
    );
}

/// Issue 83: a scene's report is its folder's (`physics/NAME/report.rs`), written with what every
/// report shares (`physics::report`, which names no scene) and hosted by `simulate` (the
/// preset, the clock, the warnings): `simulate/` holds no scene's file, and neither
/// `physics::report` nor a scene's report reaches a layer above `physics`.
#[test]
fn a_scenes_report_is_in_its_folder_and_reaches_nothing_above() {
    for kind in rattleback::physics::ModelKind::ALL {
        let folder = kind.name();
        assert!(
            src().join(format!("physics/{folder}/report.rs")).is_file(),
            "{folder}: no report in its folder"
        );
        assert!(
            !src().join(format!("simulate/{folder}.rs")).exists(),
            "{folder}: a report outside its folder"
        );
    }
    let above = [
        "crate::simulate",
        "crate::scenario",
        "crate::study",
        "crate::commands",
        "crate::record",
        "std::io::stderr",
        "eprintln!",
    ];
    let mut files = layer("physics/report");
    for kind in rattleback::physics::ModelKind::ALL {
        files.extend(layer(&format!("physics/{}/report", kind.name())));
    }
    for (file, text) in &files {
        for b in above {
            assert!(!text.contains(b), "{} mentions {b}", file.display());
        }
    }
    for (file, text) in layer("physics/report") {
        for kind in rattleback::physics::ModelKind::ALL {
            let name = kind.name();
            assert!(
                !text.contains(&format!("physics::{name}")),
                "{} names the {name} scene",
                file.display()
            );
        }
    }
}

#[test]
fn each_layer_imports_only_below_it() {
    let above_physics = ["crate::sim", "crate::app", "crate::ui", "crate::record"];
    forbid("scenario", &above_physics);
    forbid(
        "sim",
        &[
            "crate::app",
            "crate::ui",
            "crate::record",
            "crate::scenario",
            "ratatui::",
        ],
    );
    forbid(
        "app",
        &[
            "crate::ui",
            "crate::record",
            "ratatui::",
            "crossterm::",
            "std::fs",
        ],
    );
    forbid("record", &["crate::ui", "ratatui::", "crate::explorer"]);
    forbid(
        "ui",
        &["crate::record", "crate::explorer", "crate::sim::Worker"],
    );
    // The studies compute from physics alone: no scenario, no terminal, no explorer state.
    forbid(
        "study",
        &[
            "crate::scenario",
            "crate::sim",
            "crate::app",
            "crate::ui",
            "crate::record",
            "crate::commands::cli",
            "ratatui",
            "crossterm",
        ],
    );
}

/// Every file under `src/`, by its path below `src/`, with its text.
fn sources() -> Vec<(String, String)> {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    files
        .into_iter()
        .map(|file| {
            let name = file
                .strip_prefix(src())
                .unwrap()
                .to_string_lossy()
                .into_owned();
            (name, std::fs::read_to_string(&file).unwrap())
        })
        .collect()
}

#[test]
fn only_the_binary_shell_sees_the_command_line() {
    for (name, text) in sources() {
        // The command layer: main.rs and the command files in commands/ (cli.rs among them).
        if name == "main.rs" || name.starts_with("commands/") {
            continue;
        }
        assert!(!text.contains("crate::commands::cli"), "{name} imports cli");
    }
}

/// Issue 25: one exit decision. Commands return `failure::Outcome`; only `main` turns it into an
/// exit status (`failure::exit`), and nothing ends the process on its own, but the watchdog of a
/// signal the command did not answer in time (`Failure::end_now`, issue 56), with the same
/// status.
#[test]
fn the_exit_is_decided_once_in_main() {
    let mut found = Vec::new();
    for (name, text) in sources() {
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            // `Failure::end_now`, the watchdog's (a signal the command did not answer in time).
            let watchdog =
                name == "commands/failure.rs" && code.contains("std::process::exit(i32::from");
            let exits = (code.contains("process::exit(") && !watchdog)
                || (code.contains("ExitCode")
                    && !["main.rs", "commands/failure.rs"].contains(&name.as_str()))
                || (code.contains("ExitCode::") && name == "main.rs");
            if exits {
                found.push(format!("{name}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "exits decided outside main:\n{}",
        found.join("\n")
    );
    let main = std::fs::read_to_string(src().join("main.rs")).unwrap();
    assert!(
        main.contains("failure::exit(run())"),
        "main decides through failure::exit"
    );
}

#[test]
fn physics_has_no_import_cycle_through_auto() {
    // `auto` is resolved in plan.rs, above the integrators: nothing below calls the planner.
    for (file, text) in layer("physics/rattleback/integrators")
        .into_iter()
        .chain(layer("physics/kapitza/flows"))
        .chain(layer("physics/numerics"))
    {
        assert!(
            !text.contains("auto::") && !text.contains("plan::"),
            "{} calls up into the planner",
            file.display()
        );
    }
    for (file, text) in layer("physics/rattleback/run")
        .into_iter()
        .chain(layer("physics/kapitza/run"))
    {
        assert!(!text.contains("auto::"), "{}", file.display());
    }
}

/// Issue 11: each model in its own folder, the generic numerics apart from both, and one door.
#[test]
fn models_live_in_their_folders_and_numerics_belong_to_none() {
    // The numerics never name a model.
    for (file, text) in layer("physics/numerics") {
        for b in [
            "physics::rattleback",
            "physics::kapitza",
            "physics::rattleback::model",
            "physics::params",
            "effective",
        ] {
            assert!(!text.contains(b), "{} mentions {b}", file.display());
        }
    }
    // The models never reach into each other.
    for (file, text) in layer("physics/kapitza") {
        for b in [
            "physics::rattleback",
            "physics::rattleback::model::",
            "physics::rattleback::effective",
            "physics::rattleback::integrators",
            "physics::rattleback::params::Params",
        ] {
            assert!(!text.contains(b), "{} mentions {b}", file.display());
        }
    }
    for (file, text) in layer("physics/rattleback") {
        assert!(
            !text.contains("physics::kapitza"),
            "{} mentions kapitza",
            file.display()
        );
    }
    // The worker reaches a model only through `Model` (and the rattleback-only studies).
    for (file, text) in layer("sim") {
        assert!(!text.contains("kapitza::flows"), "{}", file.display());
        assert!(!text.contains("integrators::build"), "{}", file.display());
    }
}

/// Issue 25: the rattleback's modules and items are reached through its folder
/// (`physics::rattleback::…`), never at the old paths the first model had before the second
/// arrived; `physics/mod.rs` re-exports no model's module or item; the shared vocabulary
/// (`ParamError`, `Resolved`, the budget, `CHECK_EVERY`) lives in `physics/`, so neither model
/// reaches into the other for it.
#[test]
fn no_old_paths_and_no_model_reexports() {
    let root = Path::new(root!());
    let mut files = Vec::new();
    for dir in ["src", "tests", "examples"] {
        rust_files(&root.join(dir), &mut files);
    }
    let old_modules = [
        "auto",
        "averaged",
        "effective",
        "integrators",
        "model",
        "run",
        "quadrature",
    ];
    let old_items = [
        "State",
        "Params",
        "Problem",
        "Start",
        "RunResult",
        "RunSpec",
    ];
    let mut found = Vec::new();
    // This file names the old paths to forbid them.
    for file in files
        .iter()
        .filter(|f| !f.ends_with("tests/it/layering.rs"))
    {
        let text = std::fs::read_to_string(file).unwrap();
        for (n, line) in text.lines().enumerate() {
            let mut rest = line;
            while let Some(i) = rest.find("physics::") {
                let after = &rest[i + "physics::".len()..];
                let word: String = after
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                let is_old = old_modules.contains(&word.as_str())
                    || old_items.contains(&word.as_str())
                    || (word == "params"
                        && ![
                            "ParamError",
                            "ParamSpec",
                            "Scale",
                            "Allowed",
                            "check_derived",
                            "params_and_start",
                            "ANGLE",
                            "{",
                        ]
                        .iter()
                        .any(|shared| after.starts_with(&format!("params::{shared}"))));
                if is_old {
                    found.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
                }
                rest = after;
            }
        }
    }
    assert!(found.is_empty(), "old paths:\n{}", found.join("\n"));
    let face = std::fs::read_to_string(src().join("physics/mod.rs")).unwrap();
    for banned in ["pub use rattleback", "pub use kapitza", "pub use numerics"] {
        assert!(!face.contains(banned), "physics/mod.rs: {banned}");
    }
    for (file, text) in layer("physics/kapitza") {
        assert!(!text.contains("super::rattleback"), "{}", file.display());
    }
    for (file, text) in layer("physics/rattleback") {
        assert!(!text.contains("super::kapitza"), "{}", file.display());
    }
}

/// Issue 25: each model describes itself once (its folder's `scene.rs`); outside `physics/`
/// only the files the recipe in docs/architecture.md lists name a model's variant: the report
/// (`simulate/`, whose JSON sections are a contract) and the recorded plan key
/// (`sim/planner.rs`). The benchmarks measure one model each and may name it. Tests inside a
/// file (`#[cfg(test)]`) are left out.
#[test]
fn a_model_is_dispatched_in_few_places() {
    // Issue 69: outside its folder, the registry (`physics/models.rs`) and files named after it,
    // each scene's variant is named in at most two files, tests included.
    // Generated from the registry (a guard listing scenes by hand missed the third).
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut over = Vec::new();
    for kind in rattleback::physics::ModelKind::ALL {
        let name = kind.name();
        let variants: Vec<String> = ["Model", "ModelKind", "Chart", "PlanKey", "Self"]
            .iter()
            .map(|t| format!("{t}::{kind:?}"))
            .collect();
        let mut naming = Vec::new();
        for file in &files {
            let rel = file
                .strip_prefix(src())
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            let stem = file.file_stem().unwrap().to_string_lossy();
            if rel.starts_with(&format!("physics/{name}/"))
                || rel == "physics/models.rs"
                || stem == name
            {
                continue;
            }
            let text = std::fs::read_to_string(file).unwrap();
            if variants.iter().any(|v| {
                text.match_indices(v.as_str()).any(|(i, _)| {
                    !text[i + v.len()..].starts_with(|c: char| c.is_alphanumeric() || c == '_')
                })
            }) {
                naming.push(rel);
            }
        }
        if naming.len() > 2 {
            over.push((name, naming));
        }
    }
    assert!(
        over.is_empty(),
        "a scene named in more than two files outside its folder and the registry: {over:?}"
    );
    // No silent place: the panel, the panes and the words have no catch-all over the model.
    for (path, banned) in [
        ("app/fields.rs", "_ => f64::NAN"),
        ("ui/params.rs", "_ => {}"),
        ("ui/status.rs", "has_falls"),
        ("app/panes.rs", "rattleback_only"),
    ] {
        let text = std::fs::read_to_string(src().join(path)).unwrap();
        assert!(!text.contains(banned), "{path} has `{banned}`");
    }
}

/// Issue 25: a computed pane is the six files of the recipe in docs/architecture.md. The sweep
/// pane is the example: outside its own two files (`app/computed/sweep.rs`, `ui/sweep.rs`)
/// only the four shared places the recipe lists name it (its variant's arms, its field and
/// `pane_mut` arm, its `draw_column` arm, its job). `app/journal.rs` reads format 4's fixed
/// pane flags (frozen: older files still replay). Tests inside a file are left out.
#[test]
fn a_computed_pane_is_six_files() {
    let names = [
        "Pane::Sweep",
        "Self::Sweep",
        "JobKind::Sweep",
        "JobData::Sweep",
        "JobSpec::Sweep",
        "SweepState",
        "SweepJob",
        "SweepSpec",
        "computed.sweep",
        "computed::sweep",
    ];
    let recipe = [
        "app/panes.rs",
        "app/computed/mod.rs",
        "app/computed/sweep.rs",
        "ui/mod.rs",
        "ui/sweep.rs",
        "sim/jobs.rs",
    ];
    let frozen = ["app/journal.rs"];
    let mut found = Vec::new();
    for (name, text) in sources() {
        let name = name.replace('\\', "/");
        let code = text.split("#[cfg(test)]").next().unwrap_or_default();
        let named = names.iter().any(|n| code.contains(n));
        if named && !recipe.contains(&name.as_str()) && !frozen.contains(&name.as_str()) {
            found.push(name);
        }
    }
    assert!(
        found.is_empty(),
        "the sweep pane is named outside the recipe's files: {found:?}"
    );
}

/// The module paths a text names (`crate::physics::celt::plan`, `super::super::kapitza`), with
/// comments and doc text left out: what is matched is a path's segments, not a substring.
fn paths(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or_default();
        let mut segments: Vec<String> = Vec::new();
        let mut word = String::new();
        let chars: Vec<char> = code.chars().collect();
        let mut i = 0;
        while i <= chars.len() {
            let c = chars.get(i).copied().unwrap_or(' ');
            if c.is_alphanumeric() || c == '_' {
                word.push(c);
                i += 1;
                continue;
            }
            if !word.is_empty() {
                segments.push(std::mem::take(&mut word));
            }
            if c == ':' && chars.get(i + 1) == Some(&':') {
                i += 2;
                continue;
            }
            if segments.len() > 1 {
                out.push(std::mem::take(&mut segments));
            }
            segments.clear();
            i += 1;
        }
    }
    out
}

/// Issue 57: generated from the list of models (`ModelKind::ALL`), so a fourth model is held to
/// the same rules without editing this test. A model's folder names no other model (by path:
/// `physics::kapitza`, `super::kapitza`, `super::super::kapitza`); the shared files of
/// `physics/` name none, but the one dispatch (`models.rs`) and the module list (`mod.rs`); and
/// the shared vocabulary is imported from `physics`, never through a model's folder.
#[test]
fn every_models_folder_and_the_shared_files_keep_to_themselves() {
    use rattleback::physics::ModelKind;
    let models: Vec<&str> = ModelKind::ALL.iter().map(|m| m.name()).collect();
    // A model's folder is named as the model (`physics/celt` for `celt`).
    let folder = |m: &str| m.to_owned();
    let mut found = Vec::new();
    let names_model = |path: &[String], model: &str| {
        path.windows(2)
            .any(|w| (w[0] == "physics" || w[0] == "super") && w[1] == folder(model))
    };
    for model in &models {
        let dir = format!("physics/{}", folder(model));
        assert!(
            src().join(&dir).is_dir(),
            "{dir}: every model has its folder"
        );
        for (file, text) in layer(&dir) {
            let code = text.split("#[cfg(test)]").next().unwrap_or_default();
            for p in paths(code) {
                for other in models.iter().filter(|o| *o != model) {
                    if names_model(&p, other) {
                        found.push(format!("{}: {}", file.display(), p.join("::")));
                    }
                }
            }
        }
    }
    for entry in std::fs::read_dir(src().join("physics")).unwrap() {
        let file = entry.unwrap().path();
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        if file.is_dir() || name == "models.rs" || name == "mod.rs" {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap_or_default();
        for p in paths(code) {
            if models.iter().any(|m| names_model(&p, m)) {
                found.push(format!("{}: {}", file.display(), p.join("::")));
            }
        }
    }
    let shared = [
        "Method",
        "Settings",
        "StepError",
        "Stats",
        "dop853",
        "roots",
    ];
    for (file, text) in layer("") {
        for p in paths(&text) {
            if let Some(i) = p.iter().position(|s| s == "integrators")
                && p.get(i + 1).is_some_and(|s| shared.contains(&s.as_str()))
            {
                found.push(format!("{}: {}", file.display(), p.join("::")));
            }
        }
    }
    assert!(
        found.is_empty(),
        "paths across the models' walls:\n{}",
        found.join("\n")
    );
}
