//! The command layer, in a folder of its own (issue 69; `src/main.rs` dispatches to it), and
//! here the small headless commands `presets` and `check`: stdout, problems on stderr, exit 2.

pub mod cli;
pub mod doctor;
pub mod failure;
pub mod manual;
pub mod outputs;
pub mod page;
pub mod progress;
pub mod serve;
pub mod web;
pub mod wrap;

mod charts;

use crate::scenario::text::one_line;
use std::fmt::Write as _;

use crate::commands::failure::{Failure, Outcome};
use crate::commands::progress::{Progress, counted};

use crate::commands::cli::{CheckArgs, ListFormat, PresetsAction, PresetsArgs};
use crate::scenario::PresetError;
use crate::scenario::preset;
use crate::scenario::shipped::catalogue;
use crate::scenario::theme::ThemeSpec;

/// Untrusted text (names, descriptions, echoed values) never reaches a terminal raw: every line
/// printed goes through `clean`.
macro_rules! say {
    ($($t:tt)*) => { $crate::commands::say(&format!($($t)*)) };
}

/// Prints one cleaned line on stdout (see [`say_raw`]).
pub fn say(text: &str) {
    say_raw(&format!("{text}\n"));
}

pub use crate::commands::failure::{say_raw, stdout_failure};

macro_rules! say_err {
    ($($t:tt)*) => { $crate::scenario::text::warn(&format!($($t)*)) };
}
macro_rules! say_raw {
    ($($t:tt)*) => { $crate::commands::say_raw(&format!($($t)*)) };
}

mod bench;
pub mod compare;
pub mod explore;
pub mod follow;
pub mod keygen;
pub mod lesson;
pub mod replay;
pub mod shared;
pub mod simulate;
mod verify;
pub use bench::bench;
pub use verify::replay_verify;

/// The width of a list's name column: its longest name, at least 16 (every row's columns line
/// up, whatever a user names a file).
fn name_width<'a>(names: impl Iterator<Item = &'a str>) -> usize {
    names.map(|n| n.chars().count()).max().unwrap_or(0).max(16)
}

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
fn found_at(shipped: bool, path: &str, show: &str) -> String {
    if shipped {
        format!("built in ({show})")
    } else {
        one_line(path)
    }
}

/// Prints a shipped or user file's TOML (`themes show`, `lessons show`).
fn show(text: Result<String, crate::scenario::PresetError>) -> Outcome {
    match text {
        Ok(text) => {
            say_raw!("{text}");
            Ok(())
        }
        Err(e) => Err(Failure::input(e)),
    }
}

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

/// The command line with dynamic completers: preset, theme and lesson names are asked of the
/// program when the shell completes (`clap_complete`'s `CompleteEnv`), so a preset made after the
/// script was sourced completes too; a value that looks like a path completes as a path.
#[must_use]
pub fn command_with_completers() -> clap::Command {
    attach_completers(crate::commands::cli::command())
}

fn attach_completers(cmd: clap::Command) -> clap::Command {
    attach_completers_under(cmd, "")
}

/// [`attach_completers`] for a command under `parent` (`show` completes its parent's names).
fn attach_completers_under(cmd: clap::Command, parent: &str) -> clap::Command {
    use clap_complete::engine::ArgValueCompleter;
    let show = (cmd.get_name() == "show").then(|| parent.to_owned());
    let name = cmd.get_name().to_owned();
    cmd.mut_args(move |a| match (a.get_id().as_str(), show.as_deref()) {
        ("preset" | "a" | "b", _) | ("name", Some("presets")) => {
            a.add(ArgValueCompleter::new(complete_presets))
        }
        ("theme", _) | ("name", Some("themes")) => a.add(ArgValueCompleter::new(complete_themes)),
        ("lesson", _) | ("name", Some("lessons")) => {
            a.add(ArgValueCompleter::new(complete_lessons))
        }
        _ => a,
    })
    .mut_subcommands(move |c| attach_completers_under(c, &name))
}

type Candidates = Vec<clap_complete::engine::CompletionCandidate>;

/// Names starting with what is typed (each with its title as help), and paths when what is
/// typed looks like one (or no name matches).
fn named_or_path(current: &std::ffi::OsStr, names: Vec<(String, String)>) -> Candidates {
    use clap_complete::engine::{CompletionCandidate, PathCompleter, ValueCompleter as _};
    let typed = current.to_string_lossy();
    let mut out: Candidates = names
        .into_iter()
        .filter(|(n, _)| n.starts_with(typed.as_ref()))
        .map(|(n, title)| CompletionCandidate::new(n).help(Some(one_line(&title).into())))
        .collect();
    if typed.contains(['/', '.']) || out.is_empty() {
        out.extend(PathCompleter::file().complete(current));
    }
    out
}

fn complete_presets(current: &std::ffi::OsStr) -> Candidates {
    let names = catalogue()
        .0
        .into_iter()
        .map(|e| (e.name, e.title))
        .collect();
    named_or_path(current, names)
}

fn complete_themes(current: &std::ffi::OsStr) -> Candidates {
    let names = crate::scenario::theme::themes()
        .0
        .into_iter()
        .map(|(n, spec)| (n, spec.name))
        .collect();
    named_or_path(current, names)
}

fn complete_lessons(current: &std::ffi::OsStr) -> Candidates {
    let names = crate::scenario::lesson::catalogue()
        .0
        .into_iter()
        .map(|e| (e.name, e.title))
        .collect();
    named_or_path(current, names)
}

/// Answers the shell when it asks for completions (`COMPLETE=SHELL rattleback -- WORDS…`, as
/// the script of `rattleback completions SHELL` does), then exits; otherwise returns at once.
pub fn answer_completion() {
    clap_complete::CompleteEnv::with_factory(command_with_completers)
        .bin("rattleback")
        .complete();
}

/// `rattleback completions SHELL`: the script that registers dynamic completion in that shell
/// (the shell asks the program for every completion, so names are never stale).
pub fn completions(shell: clap_complete::Shell, binary: Option<&std::path::Path>) -> Outcome {
    // The program that answers: `rattleback` by name, found on PATH whenever the shell
    // completes (issue 81, D-9: the absolute path of the binary that printed the script broke
    // every Tab once it moved, and a packager's staged binary would be named); a path only when
    // asked (`--binary`).
    let me = match binary {
        None => "rattleback".to_owned(),
        Some(p) => p
            .to_str()
            .map(str::to_owned)
            .ok_or_else(|| Failure::input(format!("--binary {}: not valid UTF-8", p.display())))?,
    };
    let shells = clap_complete::env::Shells::builtins();
    let Some(completer) = shells.completer(&shell.to_string()) else {
        return Err(Failure::input(format!(
            "completions: {shell} is not supported"
        )));
    };
    let mut out = Vec::new();
    if let Err(e) =
        completer.write_registration("COMPLETE", "rattleback", "rattleback", &me, &mut out)
    {
        return Err(Failure::failed(format!(
            "writing the completion script: {e}"
        )));
    }
    write_stdout(&out)
}

/// `rattleback doctor`.
pub fn doctor(args: &crate::commands::cli::DoctorArgs) -> Outcome {
    let look = &args.look;
    let asked = crate::commands::doctor::Asked {
        ascii: look.ascii,
        colours_off: look.color.colours_off_here(),
        color_flag: look.color.name(),
        marker: look.marker.map(crate::commands::cli::MarkerChoice::name),
    };
    let d = crate::commands::doctor::diagnose(
        &asked,
        load_config().map(|(c, _)| c),
        crate::commands::outputs::SCHEMA_VERSION,
    );
    let text = match args.format {
        ListFormat::Json => json_text(&d),
        ListFormat::Table => {
            crate::commands::wrap::for_stdout(&crate::scenario::text::shown(&d.table()))
        }
    };
    write_stdout(text.as_bytes())
}

/// `rattleback man`.
pub fn man() -> Outcome {
    let cmd = crate::commands::cli::command();
    let mut out = Vec::new();
    if let Err(e) = crate::commands::manual::render(cmd, &mut out) {
        return Err(Failure::failed(format!("rendering the manual: {e}")));
    }
    write_stdout(&out)
}

/// Whether work goes on: no signal has come, and standard output still takes what is printed
/// (a reader gone away, `| head`, ends the work; `main` then exits as [`stdout_failure`] says).
fn go_on() -> bool {
    crate::interrupt::requested().is_none() && stdout_failure().is_none()
}

/// A study's result, or its exit: 128 + the signal that ended it, or 1 when a run failed.
fn finished<T>(result: Result<T, crate::physics::StepError>, what: &str) -> Result<T, Failure> {
    if let Some(failure) = interrupted() {
        return Err(failure);
    }
    result.map_err(|e| Failure::failed(format!("{what} failed: {e}")))
}

/// The end of work stopped by a signal (128 + its number, saying nothing was written); `None`
/// when none came.
fn interrupted() -> Option<Failure> {
    crate::interrupt::requested().map(Failure::interrupted)
}

/// An output as pretty JSON with a final newline, control characters escaped (text from files
/// is untrusted).
#[must_use]
pub fn json_text(value: &impl serde::Serialize) -> String {
    // Outputs are plain data (strings, numbers, vectors): serializing them cannot fail.
    let text = serde_json::to_string_pretty(value).unwrap_or_default();
    let mut s = crate::scenario::text::json_safe(&text);
    s.push('\n');
    s
}

fn write_stdout(bytes: &[u8]) -> Outcome {
    use std::io::Write as _;
    let mut out = std::io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(Failure::failed(format!("writing the output: {e}"))),
    }
}

/// Prints a list as JSON (`json`: the entries under `schema_version` and `model`) or as a
/// table (`row` per entry), then the problems found; exit 2 if any (`presets`, `themes`,
/// `lessons`).
fn print_list<T>(
    entries: &[T],
    json: &impl serde::Serialize,
    format: ListFormat,
    row: &dyn Fn(&T) -> String,
    problems: &[PresetError],
) -> Outcome {
    let out = match format {
        ListFormat::Json => json_text(json),
        // Fitted to the terminal's width when printed on one (issue 81).
        ListFormat::Table => {
            crate::commands::wrap::for_stdout(&entries.iter().map(row).collect::<String>())
        }
    };
    say_raw!("{out}");
    report(problems)
}

fn report(problems: &[PresetError]) -> Outcome {
    if problems.is_empty() {
        Ok(())
    } else {
        Err(Failure::inputs(problems))
    }
}

/// Whether a file is a theme rather than a preset.
fn is_theme(src: &str) -> bool {
    src.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("theme") || t.contains_key("colors"))
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

/// `rattleback study sweep|map`.
pub fn study(command: &crate::commands::cli::StudyCommand) -> Outcome {
    use crate::commands::cli::StudyCommand;
    // Ctrl-C (or any ending signal: `main` installs them) cancels the runs in flight and ends
    // with 128 + the signal, the progress bar erased and no file written.
    match command {
        StudyCommand::Sweep(args) => study_sweep(args),
        StudyCommand::Map(args) => charts::study_map(args),
        StudyCommand::Merge(args) => charts::study_merge(args),
    }
}

/// The preset, horizon and tolerance of a study, or the exit of a bad input.
fn study_setup(
    common: &crate::commands::cli::StudyCommon,
) -> Result<
    (
        crate::scenario::Preset,
        crate::physics::Model,
        f64,
        f64,
        Option<crate::fault::MadeFolder>,
    ),
    Failure,
> {
    let preset =
        crate::scenario::shipped::resolve(&common.preset, &common.set).map_err(Failure::input)?;
    let model = preset.model;
    let t_end = common.t_end.unwrap_or(preset.run.t_end);
    let tolerance = common
        .tolerance
        .or(preset.run.tolerance)
        .unwrap_or(crate::physics::DEFAULT_TOLERANCE);
    // Made now, so that a bad --out is refused before the work; removed again if the run ends
    // without writing into it.
    let folder = match &common.out {
        Some(dir) => Some(
            crate::fault::made_folder(dir)
                .map_err(|e| Failure::input(format!("--out {}: {e}", dir.display())))?,
        ),
        None => None,
    };
    Ok((preset, model, t_end, tolerance, folder))
}

/// Writes `files` (name, contents) into `--out`, refusing to replace without `--force`.
fn write_outputs(common: &crate::commands::cli::StudyCommon, files: &[(&str, String)]) -> Outcome {
    match &common.out {
        Some(dir) => write_files(dir, common.force, files),
        None => Ok(()),
    }
}

/// Why `path` was not written: a file there (`--force` replaces it), something else there that
/// is never replaced (both input, exit 2), or what the system said (exit 1).
fn not_written(path: &std::path::Path, e: &std::io::Error) -> Failure {
    match e.kind() {
        std::io::ErrorKind::AlreadyExists => Failure::input(format!("{e}; --force replaces it")),
        std::io::ErrorKind::InvalidInput => Failure::input(e),
        _ => Failure::failed(format!("{}: {e}", path.display())),
    }
}

/// Writes `files` (name, contents) into `dir`, refusing to replace without `force`.
fn write_files(dir: &std::path::Path, force: bool, files: &[(&str, String)]) -> Outcome {
    for (name, text) in files {
        let path = dir.join(name);
        if let Err(e) = crate::scenario::write::write_atomic(&path, text.as_bytes(), force) {
            return Err(not_written(&path, &e));
        }
    }
    say_err!(
        "wrote {}",
        files
            .iter()
            .map(|(n, _)| dir.join(n).display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

/// Writes `text` to stdout; a closed pipe (`| head`) ends the output quietly (exit 0, the
/// `--out` files are still written), another failure is exit 1.
fn emit(text: &str) -> Outcome {
    use std::io::Write as _;
    let text = crate::scenario::text::shown(text);
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(Failure::failed(format!("writing the output: {e}"))),
    }
}

/// The sweep's cost, asked before it runs: every rung validated, the total within the budget
/// (`--force` lifts the budget).
fn sweep_budget(
    model: &crate::physics::Model,
    ladder: &[f64],
    t_end: f64,
    tolerance: f64,
    force: bool,
) -> Outcome {
    match crate::study::sweep::predicted_seconds(model, ladder, t_end, tolerance) {
        Err(e) => Err(Failure::input(format!("--ladder: {e}"))),
        Ok(predicted) if predicted > crate::physics::budget::BUDGET_SECONDS && !force => {
            Err(Failure::input(format!(
                "this sweep is predicted to take about {} (budget {}); use fewer rungs, a shorter --t-end or a looser --tolerance, or pass --force",
                crate::physics::budget::duration(predicted),
                crate::physics::budget::duration(crate::physics::budget::BUDGET_SECONDS)
            )))
        }
        Ok(_) => Ok(()),
    }
}

fn study_sweep(args: &crate::commands::cli::SweepArgs) -> Outcome {
    use crate::study::sweep::{ladder, sweep};
    let (preset, model, t_end, tolerance, _folder) = study_setup(&args.common)?;
    let kind = model.kind();
    let Some(small) = kind.small() else {
        return Err(Failure::input(format!(
            "the {} has no small parameter to sweep",
            kind.title()
        )));
    };
    let ladder = if args.ladder.is_empty() {
        ladder(kind).to_vec()
    } else {
        args.ladder.clone()
    };
    // Every rung is the model's own parameter: its range is the preset's.
    if let Some(spec) = kind.params().iter().find(|p| p.key == small.key)
        && let Some(bad) = ladder.iter().find(|x| !spec.allowed.contains(**x))
    {
        return Err(Failure::input(format!(
            "--ladder: {} = {bad} is out of range for the {} model; allowed: {}",
            small.key,
            kind.name(),
            spec.allowed.text()
        )));
    }
    sweep_budget(&model, &ladder, t_end, tolerance, args.common.force)?;
    // Progress by runs (the limit is one); Ctrl-C cancels the runs in flight.
    let runs = Progress::count("study sweep", ladder.len() + 1, "runs");
    let swept = counted(runs, &|done| {
        sweep(&model, &ladder, t_end, tolerance, &|_| go_on(), done)
    });
    let s = finished(swept, "study sweep")?;
    // The rattleback's column and field are `stiffness` (a contract); the pendulum's `epsilon`.
    let column = small.column;
    let mut csv = format!("{column},sup_error,method,estimate\n");
    for r in &s.rungs {
        let _ = writeln!(
            csv,
            "{:e},{:e},{},{:e}",
            r.parameter, r.sup_error, r.method, r.estimate
        );
    }
    let printed = match args.common.format {
        crate::commands::cli::StudyFormat::Json => {
            let ladder = s.stiffness();
            emit(&json_text(&crate::commands::outputs::Sweep {
                schema_version: crate::commands::outputs::SCHEMA_VERSION,
                model: model.kind(),
                preset: preset.name.clone(),
                t_end,
                tolerance,
                stiffness: (column == "stiffness").then(|| ladder.clone()),
                epsilon: (column != "stiffness").then_some(ladder),
                sup_error: s.sup_error(),
                slope: s.slope,
                methods: s.rungs.iter().map(|r| r.method.name()).collect(),
                estimates: s.rungs.iter().map(|r| r.estimate).collect(),
            }))
        }
        crate::commands::cli::StudyFormat::Csv => emit(&crate::scenario::text::clean(&csv)),
        crate::commands::cli::StudyFormat::Table => emit(&crate::scenario::text::clean(
            &sweep_table(&preset.name, t_end, tolerance, &s),
        )),
    };
    printed?;
    // The files only when asked for (a scene never computes what it does not need).
    if args.common.out.is_none() {
        return Ok(());
    }
    let curves = sweep_curves(&s);
    let svg = match crate::study::svg::sweep_svg(&s) {
        Ok(svg) => svg,
        Err(e) => {
            return Err(Failure::failed(format!("drawing the sweep: {e}")));
        }
    };
    write_outputs(
        &args.common,
        &[
            ("sweep.csv", csv),
            ("sweep_curves.csv", curves),
            ("sweep.svg", svg),
        ],
    )
}

fn sweep_table(name: &str, t_end: f64, tolerance: f64, s: &crate::study::sweep::Sweep) -> String {
    let mut o = format!(
        "preset        {} (T = {t_end}, tolerance {tolerance:e})\n",
        crate::scenario::text::one_line(name)
    );
    let small = s.small();
    let (parameter, sup) = (small.key, small.sup_short);
    let _ = writeln!(
        o,
        "{:>10}  {:>14}  {:<19} {:>9}",
        parameter, sup, "auto chose", "estimate"
    );
    for r in &s.rungs {
        let _ = writeln!(
            o,
            "{:>10.0e}  {:>14.3e}  {:<19} {:>9.1e}",
            r.parameter,
            r.sup_error,
            r.method.name(),
            r.estimate
        );
    }
    let _ = writeln!(
        o,
        "slope of log sup against log {parameter}: {}",
        s.slope
            .map_or_else(|| "n/a".to_owned(), |x| format!("{x:.3}"))
    );
    o
}

/// `sweep_curves.csv`: `t, limit, alpha_k<k>…`, one row per sample.
fn sweep_curves(s: &crate::study::sweep::Sweep) -> String {
    let mut curves = String::from("t,limit");
    let (q, tag) = (s.model.words().q_name, s.small().tag);
    for r in &s.rungs {
        let _ = write!(curves, ",{q}_{tag}{:e}", r.parameter);
    }
    curves.push('\n');
    for (i, t) in s.t.iter().enumerate() {
        let _ = write!(curves, "{t},{}", s.limit[i]);
        for r in &s.rungs {
            let _ = write!(curves, ",{}", r.alpha[i]);
        }
        curves.push('\n');
    }
    curves
}

/// # Errors
/// The file's first problem, located.
///
/// The configuration for the explorer and replay, with its key bindings checked: an invalid
/// file is an error naming the file, the line and the key.
pub fn load_config() -> Result<
    (
        crate::scenario::config::Config,
        crate::app::user_keys::UserKeys,
    ),
    Vec<String>,
> {
    // The keys that did parse are still checked, so every problem is said at once.
    let (config, problems) = crate::scenario::config::Config::load_all();
    let mut errors: Vec<(usize, String)> = problems
        .iter()
        .map(|e| (e.line().unwrap_or(0), e.to_string()))
        .collect();
    let entries: Vec<(String, Vec<String>)> = config
        .keys
        .iter()
        .map(|k| (k.action.clone(), k.keys.clone()))
        .collect();
    let keys = match crate::app::user_keys::UserKeys::parse(&entries) {
        Ok(k) => k,
        Err(bad) => {
            for (i, message) in bad {
                let entry = &config.keys[i];
                errors.push((
                    entry.line,
                    crate::scenario::PresetError::Invalid {
                        path: config
                            .path
                            .as_ref()
                            .map_or_else(String::new, |p| p.display().to_string()),
                        line: Some(entry.line),
                        key: Some(format!("keys.{}", entry.action)),
                        message,
                    }
                    .to_string(),
                ));
            }
            crate::app::user_keys::UserKeys::default()
        }
    };
    if errors.is_empty() {
        Ok((config, keys))
    } else {
        // In the file's order.
        errors.sort_by_key(|(line, _)| *line);
        Err(errors.into_iter().map(|(_, e)| e).collect())
    }
}

/// `rattleback config path|show`.
pub fn config(command: &crate::commands::cli::ConfigCommand) -> Outcome {
    use crate::commands::cli::ConfigCommand;
    use crate::scenario::config;
    match command {
        ConfigCommand::Path => {
            if let Some(p) = config::path() {
                say!("{}", p.display());
                Ok(())
            } else {
                Err(Failure::input(
                    "no config folder (no home folder); set RATTLEBACK_CONFIG_DIR",
                ))
            }
        }
        ConfigCommand::Show => match load_config() {
            Ok((c, _)) => {
                let origin = c.path.as_ref().map_or_else(
                    || {
                        format!(
                            "# no config file: the defaults ({} would be read)",
                            config::path().map_or_else(String::new, |p| p.display().to_string())
                        )
                    },
                    |p| format!("# from {}", p.display()),
                );
                say_raw!("{origin}\n{}", c.to_toml());
                Ok(())
            }
            Err(errors) => Err(Failure::inputs(errors)),
        },
    }
}
