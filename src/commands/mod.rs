//! The command layer, in a folder of its own (issue 69; `src/main.rs` dispatches to it): each
//! command in its own file (issue 83), and here what they all use: the output (`say`, JSON,
//! lists) and a run's interruption.

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

use crate::commands::failure::{Failure, Outcome};

use crate::commands::cli::ListFormat;
use crate::scenario::PresetError;

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
mod check;
pub mod compare;
pub mod completions;
pub mod config;
pub mod explore;
pub mod follow;
pub mod keygen;
pub mod lesson;
mod lessons;
mod man;
mod presets;
pub mod replay;
pub mod shared;
pub mod simulate;
mod study;
mod themes;
mod verify;
pub use bench::bench;
pub use check::check;
pub use completions::answer_completion;
pub use completions::command_with_completers;
pub use completions::completions;
pub use config::config;
pub use config::load_config;
pub use lessons::lesson_new;
pub use lessons::lessons;
pub use man::man;
pub use presets::presets;
pub use study::study;
pub use themes::themes;
pub use verify::replay_verify;

/// The width of a list's name column: its longest name, at least 16 (every row's columns line
/// up, whatever a user names a file).
fn name_width<'a>(names: impl Iterator<Item = &'a str>) -> usize {
    names.map(|n| n.chars().count()).max().unwrap_or(0).max(16)
}

type Candidates = Vec<clap_complete::engine::CompletionCandidate>;

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
    check::report(problems)
}

/// `rattleback doctor`: the diagnosis (`doctor.rs`, which knows nothing of the outputs: their
/// list names its schema) with the outputs' version, printed.
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
        crate::commands::cli::ListFormat::Json => json_text(&d),
        crate::commands::cli::ListFormat::Table => {
            crate::commands::wrap::for_stdout(&crate::scenario::text::shown(&d.table()))
        }
    };
    write_stdout(text.as_bytes())
}
