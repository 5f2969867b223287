//! Entry point: parse arguments, dispatch, and turn errors into messages and exit codes
//! (2 for bad input, 1 for a failed run).

use std::process::ExitCode;

use rattleback::commands;
use rattleback::commands::cli::Command;
use rattleback::commands::failure::{self, Failure, Outcome};

fn main() -> ExitCode {
    // Text is written in ASCII under a locale that is not UTF-8 (`LANG=C`), as the explorer
    // draws: decided once, before anything is said.
    rattleback::scenario::text::set_ascii_output(
        !rattleback::scenario::text::locale(&|name| std::env::var(name).ok()).0,
    );
    // A shell asking for completions is answered before anything else, then the process exits.
    commands::answer_completion();
    // `auto`'s independent computations (a run's companion, the start's conditioning, the
    // probes) on a second core: same results, bit for bit, in less wall time.
    rattleback::parallel::install();
    // A fault (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGTRAP, SIGSYS) puts the terminal back, removes
    // the temporary files and ends the process by its signal, whatever the command.
    rattleback::fault::install();
    // The one exit decision: every command says why it stopped, `failure` says how that ends.
    failure::exit(run())
}

/// Whether `command` draws the explorer (its signals are its own: `explorer::run`).
fn interactive(command: Option<&Command>) -> bool {
    match command {
        None | Some(Command::Lesson(_) | Command::Compare(_) | Command::Follow(_)) => true,
        Some(Command::Replay(args)) => {
            !(args.verify
                || args.chapters
                || args.export_cast.is_some()
                || args.export_html.is_some())
        }
        Some(_) => false,
    }
}

/// Parses the command line and runs the command it names; then the command is ending on its
/// own (a signal's watchdog leaves the exit to `main`).
fn run() -> Outcome {
    let outcome = command();
    rattleback::interrupt::ending_now();
    outcome
}

/// Parses the command line and runs the command it names.
fn command() -> Outcome {
    let args = config_last(std::env::args_os().collect());
    let cli = match rattleback::commands::cli::parse_from(args.clone()) {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => {
            // One error style: `rattleback: error: …`, as every other message (clap's own
            // text begins with `error: `), then its usage hint; exit 2.
            let mut text = drop_far_suggestion(&e, e.render().to_string());
            if e.kind() == clap::error::ErrorKind::ArgumentConflict
                && let Some(fix) = rattleback::commands::cli::flags_after_command(&args)
            {
                // `rattleback --preset X simulate`: each command takes its own flags.
                text = format!(
                    "{}\n\n  tip: a command's flags go after its name: `{fix}`\n",
                    text.trim_end()
                );
            }
            if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                // The help of a command that needs a subcommand: say so first.
                text = format!("error: a subcommand is needed\n\n{text}");
            }
            rattleback::scenario::text::warn_raw(&format!("rattleback: {text}"));
            if !text.ends_with('\n') {
                rattleback::scenario::text::warn_raw("\n");
            }
            return Err(Failure::said(2));
        }
        // --help and --version in ASCII under a locale that is not UTF-8: printed on stdout,
        // exit 0, as clap does.
        Err(e) if rattleback::scenario::text::ascii_output() => {
            commands::say_raw(&e.render().to_string());
            return Ok(());
        }
        // --help and --version: printed on stdout, exit 0.
        Err(e) => e.exit(),
    };
    if let Some(file) = &cli.config {
        if !file.is_file() {
            return Err(Failure::input(format!(
                "--config {}: no such file (`rattleback config show > FILE` writes one to start from)",
                file.display()
            )));
        }
        rattleback::scenario::config::use_file(file.clone());
    }
    // Every command reads the configuration the same way: an invalid one is refused with
    // every problem (file:line), whatever the command; `doctor` reports it instead, and the
    // manual, the completion scripts and `config path` do not read it.
    let reads_config = !matches!(
        cli.command,
        Some(
            Command::Doctor(_)
                | Command::Man
                | Command::Completions(_)
                | Command::Config(rattleback::commands::cli::ConfigCommand::Path)
        )
    );
    if reads_config {
        commands::shared::config_or_exit()?;
    }
    // Every headless command stops on any ending signal within a step, a frame or a cell, and
    // never later than the watchdog's grace (issue 56); the explorer handles its own, to put
    // the terminal back first.
    if !interactive(cli.command.as_ref())
        && let Err(e) = rattleback::interrupt::install(|n| Failure::interrupted(n).end_now())
    {
        return Err(Failure::failed(e));
    }
    match cli.command {
        Some(Command::Simulate(args)) => commands::simulate::run_simulate(&args),
        Some(Command::Presets(args)) => commands::presets(&args),
        Some(Command::Check(args)) => commands::check(&args),
        Some(Command::Replay(ref args)) => commands::replay::run_replay(args),
        Some(Command::Themes(args)) => commands::themes(&args),
        Some(Command::Lessons(args)) => commands::lessons(&args),
        Some(Command::Lesson(ref args)) => commands::lesson::run_lesson(args),
        Some(Command::Compare(ref args)) => commands::compare::run_compare(args),
        Some(Command::Follow(ref args)) => commands::follow::run_follow(args),
        Some(Command::Serve(ref args)) => commands::serve::command(args),
        Some(Command::Completions(args)) => {
            commands::completions(args.shell, args.binary.as_deref())
        }
        Some(Command::Man) => commands::man(),
        Some(Command::Keygen(ref args)) => commands::keygen::keygen(args),
        Some(Command::Config(ref c)) => commands::config(c),
        Some(Command::Doctor(ref args)) => commands::doctor(args),
        Some(Command::Web(ref args)) => commands::web::web(args),
        Some(Command::Bench(ref args)) => commands::bench(args),
        Some(Command::Study(ref command)) => commands::study(command),
        None => commands::explore::run_explorer(&cli),
    }
}

/// clap's error text without its "a similar argument exists" tip when that argument is not
/// close enough to be a typo by the program's own rule ([`closest`]: one edit away, or
/// Jaro–Winkler ≥ 0.8): `--bogus` is not `--mouse` (issue 54), `--presett` is `--preset`. The
/// usage line clap built around the suggestion becomes the command's own.
///
/// [`closest`]: rattleback::scenario::text::closest
fn drop_far_suggestion(e: &clap::Error, text: String) -> String {
    use clap::error::{ContextKind, ContextValue};
    let (Some(ContextValue::String(asked)), Some(ContextValue::String(suggested))) = (
        e.get(ContextKind::InvalidArg),
        e.get(ContextKind::SuggestedArg),
    ) else {
        return text;
    };
    let suggested = [suggested];
    let close = suggested.iter().any(|s| {
        rattleback::scenario::text::closest(
            asked.trim_start_matches('-'),
            [s.trim_start_matches('-')],
        )
        .is_some()
    });
    if close {
        return text;
    }
    let mut out = Vec::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        if line
            .trim_start()
            .starts_with("tip: a similar argument exists")
        {
            // The tip and the blank line after it.
            if lines.peek().is_some_and(|l| l.trim().is_empty()) {
                lines.next();
            }
            continue;
        }
        if let Some(usage) = line.strip_prefix("Usage: ")
            && let Some(first) = suggested.first()
            && let Some(at) = usage.find(first.as_str())
        {
            out.push(format!("Usage: {}[OPTIONS]", &usage[..at]));
            continue;
        }
        out.push(line.to_owned());
    }
    out.join("\n") + "\n"
}

/// The command line with a leading `--config FILE` (or `--config=FILE`) moved to the end: the
/// explorer's own flags conflict with a subcommand (`rattleback --preset X simulate` is
/// refused), and clap counts a global flag before the subcommand among them.
fn config_last(mut args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let mut moved = Vec::new();
    let mut i = 1;
    while i < args.len() {
        let a = args[i].to_string_lossy();
        if a == "--" || !a.starts_with('-') {
            break;
        }
        if a == "--config" && i + 1 < args.len() {
            moved.extend(args.drain(i..i + 2));
        } else if a.starts_with("--config=") {
            moved.push(args.remove(i));
        } else {
            i += 1;
        }
    }
    args.extend(moved);
    args
}
