//! `rattleback completions`: the shell's completion scripts, and the dynamic answers
//! (preset, theme and lesson names) a shell asks for.

use crate::scenario::text::one_line;

use crate::commands::failure::{Failure, Outcome};

use super::{Candidates, write_stdout};
use crate::scenario::shipped::catalogue;

/// The command line with dynamic completers: preset, theme and lesson names are asked of the
/// program when the shell completes (`clap_complete`'s `CompleteEnv`), so a preset made after the
/// script was sourced completes too; a value that looks like a path completes as a path.
#[must_use]
pub fn command_with_completers() -> clap::Command {
    attach_completers(crate::commands::cli::command())
}

pub(crate) fn attach_completers(cmd: clap::Command) -> clap::Command {
    attach_completers_under(cmd, "")
}

/// [`attach_completers`] for a command under `parent` (`show` completes its parent's names).
pub(crate) fn attach_completers_under(cmd: clap::Command, parent: &str) -> clap::Command {
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

/// Names starting with what is typed (each with its title as help), and paths when what is
/// typed looks like one (or no name matches).
pub(crate) fn named_or_path(current: &std::ffi::OsStr, names: Vec<(String, String)>) -> Candidates {
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

pub(crate) fn complete_presets(current: &std::ffi::OsStr) -> Candidates {
    let names = catalogue()
        .0
        .into_iter()
        .map(|e| (e.name, e.title))
        .collect();
    named_or_path(current, names)
}

pub(crate) fn complete_themes(current: &std::ffi::OsStr) -> Candidates {
    let names = crate::scenario::theme::themes()
        .0
        .into_iter()
        .map(|(n, spec)| (n, spec.name))
        .collect();
    named_or_path(current, names)
}

pub(crate) fn complete_lessons(current: &std::ffi::OsStr) -> Candidates {
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
