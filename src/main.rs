//! Entry point: parse arguments, dispatch, and turn errors into messages and exit codes
//! (2 for bad input, 1 for a failed run).

use std::io::Write as _;
use std::process::ExitCode;

use rattleback::app::user_keys::UserKeys;
use rattleback::commands;
use rattleback::commands::cli::{
    Cli, Command, LookArgs, MarkerChoice, RecordArgs, ReplayArgs, SimulateArgs,
};
use rattleback::commands::failure::{self, Failure, Outcome};
use rattleback::explorer::{self, ExplorerOptions};
use rattleback::physics::StepError;
use rattleback::record;
use rattleback::scenario::config::Config;
use rattleback::scenario::shipped::resolve;
use rattleback::simulate::{Failure as Stopped, resolve as resolve_run, simulate_to};
use rattleback::terminal::Depth;
use rattleback::ui::UiOptions;

/// Untrusted text (names, descriptions, echoed values) never reaches a terminal raw: every line
/// printed goes through `clean`.
macro_rules! say {
    ($($t:tt)*) => { rattleback::commands::say(&format!($($t)*)) };
}
macro_rules! say_err {
    ($($t:tt)*) => { rattleback::scenario::text::warn(&format!($($t)*)) };
}

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
        config_or_exit()?;
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
        Some(Command::Simulate(args)) => run_simulate(&args),
        Some(Command::Presets(args)) => commands::presets(&args),
        Some(Command::Check(args)) => commands::check(&args),
        Some(Command::Replay(ref args)) => run_replay(args),
        Some(Command::Themes(args)) => commands::themes(&args),
        Some(Command::Lessons(args)) => commands::lessons(&args),
        Some(Command::Lesson(ref args)) => run_lesson(args),
        Some(Command::Compare(ref args)) => run_compare(args),
        Some(Command::Follow(ref args)) => run_follow(args),
        Some(Command::Serve(ref args)) => run_serve(args),
        Some(Command::Completions(args)) => {
            commands::completions(args.shell, args.binary.as_deref())
        }
        Some(Command::Man) => commands::man(),
        Some(Command::Keygen(ref args)) => keygen(args),
        Some(Command::Config(ref c)) => commands::config(c),
        Some(Command::Doctor(ref args)) => commands::doctor(args),
        Some(Command::Web(ref args)) => commands::web::web(args),
        Some(Command::Bench(ref args)) => commands::bench(args),
        Some(Command::Study(ref command)) => commands::study(command),
        None => run_explorer(&cli),
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

/// `-` (standard input) where the explorer opens: it reads its keys from standard input.
fn refuse_stdin(what: &str) -> Outcome {
    Err(Failure::input(format!(
        "{what}: the explorer reads its keys from standard input, so it cannot read a file from it; save it to a file, or use - with simulate, study, check, presets show or replay --verify/--chapters/--export-cast"
    )))
}

/// Refuses an output that exists (unless `force`) or that is `input` itself.
fn check_output(
    out: &std::path::Path,
    input: Option<&std::path::Path>,
    force: bool,
    flag: &str,
) -> Result<(), String> {
    let same = |a: &std::path::Path, b: &std::path::Path| {
        a == b || matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
    };
    if input.is_some_and(|i| same(out, i)) {
        return Err(format!(
            "{flag} {}: that is the session being read; choose another file",
            out.display()
        ));
    }
    if !force && std::fs::symlink_metadata(out).is_ok() {
        return Err(format!(
            "{flag} {}: the file exists; choose another name or add --force to replace it",
            out.display()
        ));
    }
    rattleback::scenario::write::replaceable(out).map_err(|e| format!("{flag} {e}"))
}

/// `cast::export_cast` and `page::export_html`: a session written into a file.
type Export = fn(
    &record::Recording,
    &str,
    &std::path::Path,
    &UiOptions,
    rattleback::cast::CastSize,
    bool,
    &mut dyn FnMut(usize),
) -> Result<usize, record::RecordError>;

/// How a cast, an exported page and `serve` draw: `--theme` or the default, no key footer, and
/// ASCII only when asked (a cast is played elsewhere, not on this terminal).
fn cast_options(look: &LookArgs) -> Result<UiOptions, Failure> {
    let theme = rattleback::scenario::theme::theme(look.theme.as_deref().unwrap_or("default"))
        .map_err(Failure::input)?;
    let all: Vec<_> = rattleback::scenario::theme::themes()
        .0
        .into_iter()
        .map(|(_, t)| t)
        .collect();
    let charset = if look.ascii {
        rattleback::ui::glyphs::Charset::Ascii
    } else {
        rattleback::ui::glyphs::Charset::Unicode
    };
    Ok(
        UiOptions::new(marker(look.marker), &theme, &all, no_color(look.color))
            .with_charset(charset)
            .without_footer(),
    )
}

fn run_serve(args: &rattleback::commands::cli::ServeArgs) -> Outcome {
    // The status bar as the lecturer saw it, recording.
    let options = cast_options(&args.look)?.as_recorded();
    commands::serve::serve(args, options)
}

/// `replay --export-cast` and `--export-html`: the session drawn into an asciicast file and
/// into a page that plays it, without the key footer.
fn export_files(
    args: &ReplayArgs,
    rec: &record::Recording,
    path: &str,
    look: &LookArgs,
) -> Outcome {
    let options = cast_options(look)?;
    let size = rattleback::cast::CastSize {
        cols: args.cols,
        rows: args.rows,
        fps: f64::from(look.fps.unwrap_or(10)),
    };
    let outputs: [(Option<&std::path::Path>, &str, Export); 2] = [
        (
            args.export_cast.as_deref(),
            "export-cast",
            rattleback::cast::export_cast,
        ),
        (
            args.export_html.as_deref(),
            "export-html",
            rattleback::commands::page::export_html,
        ),
    ];
    for (out, what, export) in outputs {
        let Some(out) = out else { continue };
        let mut progress =
            rattleback::commands::progress::Progress::count(what, rec.lines.len(), "lines");
        let written = export(rec, path, out, &options, size, args.force, &mut |n| {
            progress.tick(n as f64);
        });
        progress.finish();
        if let (Err(_), Some(n)) = (&written, rattleback::interrupt::requested()) {
            return Err(Failure::signalled(n)
                .saying(format!("interrupted: {} was not written", out.display())));
        }
        match written {
            Ok(frames) => say!("{}: {frames} frames", out.display()),
            Err(e) => {
                return Err(Failure::input(e));
            }
        }
    }
    Ok(())
}

/// Whether two paths name one file (written alike, or the same file name in the same folder
/// however the folder is written).
fn same_place(a: &std::path::Path, b: &std::path::Path) -> bool {
    let place = |p: &std::path::Path| {
        let folder = match p.parent() {
            Some(f) if !f.as_os_str().is_empty() => f.to_path_buf(),
            _ => std::path::PathBuf::from("."),
        };
        (
            std::fs::canonicalize(&folder).unwrap_or(folder),
            p.file_name().map(ToOwned::to_owned),
        )
    };
    a == b || place(a) == place(b)
}

fn run_replay(args: &ReplayArgs) -> Outcome {
    let exporting = args.export_cast.is_some() || args.export_html.is_some();
    if args.file.as_os_str() == "-" && !args.verify && !args.chapters && !exporting {
        return refuse_stdin("replay -");
    }
    let path = rattleback::scenario::write::label(&args.file);
    let json = args.format == rattleback::commands::cli::ListFormat::Json;
    if json && (args.chapters == args.verify || exporting) {
        return Err(Failure::input(
            "--format json goes with one of --chapters or --verify (and not --export-cast or --export-html)",
        ));
    }
    // A bad `--theme` is an error whatever else is asked (it would be when drawing).
    if let Some(name) = &args.look.theme
        && let Err(e) = rattleback::scenario::theme::theme(name)
    {
        return Err(Failure::input(format!("--theme: {e}")));
    }
    // One file cannot be both: the page would replace the cast (issue 56).
    if let (Some(cast), Some(page)) = (&args.export_cast, &args.export_html)
        && same_place(cast, page)
    {
        return Err(Failure::input(format!(
            "--export-cast and --export-html name the same file ({}); give each its own",
            rattleback::scenario::write::label(cast)
        )));
    }
    for (out, flag) in [
        (&args.export_cast, "--export-cast"),
        (&args.export_html, "--export-html"),
    ] {
        if let Some(out) = out
            && let Err(e) = check_output(out, Some(&args.file), args.force, flag)
        {
            return Err(Failure::input(e));
        }
    }
    let rec = match record::read(&args.file) {
        Ok(r) => r,
        Err(e) => {
            let failure = Failure::input(&e);
            if json && args.verify {
                let failed = record::VerifyError::Record(e);
                let v = rattleback::commands::outputs::Verification::of(None, &path, Err(&failed));
                print!("{}", commands::json_text(&v));
            }
            return Err(failure);
        }
    };
    for w in &rec.warnings {
        say_err!("rattleback: warning: {w}");
    }
    if json && args.chapters {
        print!(
            "{}",
            commands::json_text(&rattleback::commands::outputs::Chapters::of(&rec, &path))
        );
        return Ok(());
    }
    if args.chapters {
        say!("{}", record::chapters(&rec));
        if !args.verify && !exporting {
            return Ok(());
        }
    }
    let (config, keys) = config_or_exit()?;
    let asked = with_config(&args.look, &config);
    let look = LookArgs {
        // The replay's own theme wins over the configuration's, not over `--theme`.
        theme: Some(replay_theme(args.look.theme.as_deref(), &rec.header.theme)),
        ..asked
    };
    if args.verify {
        commands::replay_verify(args, &rec, &path)?;
    }
    if exporting {
        return export_files(args, &rec, &path, &look);
    }
    if args.verify {
        return Ok(());
    }
    let preset = match rattleback::scenario::Preset::parse(
        &rec.header.preset,
        &format!("{path} (header)"),
        "recorded",
        &[],
    ) {
        Ok(p) => p,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let setup = Setup {
        look,
        sessions_dir: config.sessions_dir(),
        mouse: false,
        keys,
        lesson: None,
        partner: None,
        follow: None,
        sign: None,
        serve: None,
    };
    explore(&setup, &preset, None, Some(rec))
}

fn keygen(args: &rattleback::commands::cli::KeygenArgs) -> Outcome {
    match record::sign::keygen(&args.name) {
        Ok((secret, public)) => {
            say!(
                "{}: private key (mode 0600): record with --sign {}",
                secret.display(),
                secret.display()
            );
            say!(
                "{}: public key: verify with replay FILE --verify --key {}",
                public.display(),
                public.display()
            );
            Ok(())
        }
        Err(e) => Err(Failure::input(format!("keygen: {e}"))),
    }
}

/// The theme of a replay: `--theme` when given, else the recorded one when this machine has a
/// theme of that name or title, else `default` (an older header has only an index).
fn replay_theme(asked: Option<&str>, recorded: &record::ThemeRef) -> String {
    if let Some(name) = asked {
        return name.to_owned();
    }
    let Some(name) = recorded.name() else {
        return "default".to_owned();
    };
    let (all, _) = rattleback::scenario::theme::themes();
    if let Some((key, _)) = all
        .iter()
        .find(|(key, spec)| key == name || rattleback::scenario::text::clean(&spec.name) == name)
    {
        return key.clone();
    }
    say_err!(
        "rattleback: warning: the recorded theme '{name}' is not on this machine; using default"
    );
    "default".to_owned()
}

/// The configuration and the user's keys, or the exit of an invalid `config.toml` (its error
/// said on stderr).
fn config_or_exit() -> Result<(Config, UserKeys), Failure> {
    commands::load_config().map_err(Failure::inputs)
}

/// The look asked on the command line, completed by the configuration.
fn with_config(look: &LookArgs, config: &Config) -> LookArgs {
    let marker = config.marker.as_deref().map(|m| match m {
        "halfblock" => MarkerChoice::Halfblock,
        "dot" => MarkerChoice::Dot,
        _ => MarkerChoice::Braille,
    });
    LookArgs {
        fps: look.fps.or(config.fps),
        theme: look.theme.clone().or_else(|| config.theme.clone()),
        marker: look.marker.or(marker),
        color: look.color,
        ascii: look.ascii || config.ascii,
    }
}

fn marker(choice: Option<MarkerChoice>) -> ratatui::symbols::Marker {
    match choice.unwrap_or(MarkerChoice::Braille) {
        MarkerChoice::Braille => ratatui::symbols::Marker::Braille,
        MarkerChoice::Halfblock => ratatui::symbols::Marker::HalfBlock,
        MarkerChoice::Dot => ratatui::symbols::Marker::Dot,
    }
}

/// Checks a `--record` file before the terminal is touched: new, or `force` (then the old one
/// is removed, since the recorder itself never replaces a file).
fn prepare_record(out: Option<&std::path::Path>, force: bool) -> Outcome {
    let Some(out) = out else { return Ok(()) };
    if let Err(e) = check_output(out, None, force, "--record") {
        return Err(Failure::input(e));
    }
    if force {
        let _ = std::fs::remove_file(out);
    }
    Ok(())
}

fn run_follow(args: &rattleback::commands::cli::FollowArgs) -> Outcome {
    if args.file.as_os_str() == "-" {
        return refuse_stdin("follow -");
    }
    // Before waiting for the lecturer's file: a follower with nowhere to draw would wait for
    // nothing.
    needs_terminal("follow")?;
    // Students often start first: wait for the file (and its header) to appear, saying so.
    let mut said = false;
    while !args
        .file
        .metadata()
        .is_ok_and(|m| m.is_file() && m.len() > 0)
    {
        if !said {
            say_err!(
                "rattleback: note: waiting for {} to appear (the lecturer has not started recording yet; Ctrl-C stops)",
                args.file.display()
            );
            said = true;
        }
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
    // Read once here: a file that is not a session is refused before the terminal is touched.
    let rec = match rattleback::record::tail::Tail::open(&args.file) {
        Ok((_, rec)) => rec,
        Err(record::RecordError::Io { path, source })
            if source.kind() == std::io::ErrorKind::PermissionDenied =>
        {
            return Err(Failure::input(format!(
                "{path}: permission denied: the lecturer's file is not readable by you (recorded under umask 077?); the lecturer can run `chmod a+r {path}`, or record with `umask 022`"
            )));
        }
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let (config, keys) = config_or_exit()?;
    let preset = match rattleback::scenario::Preset::parse(
        &rec.header.preset,
        &format!("{} (header)", args.file.display()),
        "recorded",
        &[],
    ) {
        Ok(p) => p,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let asked = with_config(&args.look, &config);
    let setup = Setup {
        look: LookArgs {
            theme: Some(replay_theme(args.look.theme.as_deref(), &rec.header.theme)),
            ..asked
        },
        sessions_dir: config.sessions_dir(),
        mouse: false,
        keys,
        lesson: None,
        partner: None,
        follow: Some(args.file.clone()),
        sign: None,
        serve: None,
    };
    explore(&setup, &preset, None, Some(rec))
}

fn run_lesson(args: &rattleback::commands::cli::LessonArgs) -> Outcome {
    if let Some(rattleback::commands::cli::LessonCommand::New(new)) = &args.new {
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
    let lesson = match rattleback::scenario::lesson::resolve(name) {
        Ok(l) => l,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    // The first step's preset, else the default, opens the explorer; the lesson takes over.
    let preset = match lesson.steps[0].preset.clone() {
        Some(p) => Ok(p),
        None => resolve(rattleback::scenario::shipped::DEFAULT_PRESET, &[]),
    };
    let opening = Opening {
        look: &args.look,
        rec: &args.rec,
        mouse: false,
        lesson: Some(lesson),
        partner: None,
    };
    open_explorer(Some(preset.map_err(|e| e.to_string())), opening)
}

/// `compare A B`: the explorer on `A` with `B` beside it on one time axis.
fn run_compare(args: &rattleback::commands::cli::CompareArgs) -> Outcome {
    if args.a == "-" || args.b == "-" {
        return refuse_stdin("compare -");
    }
    let (preset, partner) = match (resolve(&args.a, &[]), resolve(&args.b, &[])) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            return Err(Failure::input(format!("compare: {e}")));
        }
    };
    let opening = Opening {
        look: &args.look,
        rec: &args.rec,
        mouse: false,
        lesson: None,
        partner: Some(partner),
    };
    open_explorer(Some(Ok(preset)), opening)
}

fn run_explorer(cli: &Cli) -> Outcome {
    if cli.preset.as_deref() == Some("-") {
        return refuse_stdin("--preset -");
    }
    let opening = Opening {
        look: &cli.look,
        rec: &cli.rec,
        mouse: cli.mouse,
        lesson: None,
        partner: None,
    };
    let preset = cli
        .preset
        .as_deref()
        .map(|name| resolve(name, &[]).map_err(|e| e.to_string()));
    open_explorer(preset, opening)
}

/// How an interactive command opens the explorer.
struct Opening<'a> {
    look: &'a LookArgs,
    rec: &'a RecordArgs,
    mouse: bool,
    lesson: Option<rattleback::scenario::lesson::Lesson>,
    partner: Option<rattleback::scenario::Preset>,
}

/// The one way the explorer opens from the command line: the configuration, the preset (`None`:
/// the configured default, else the shipped one), the recording's file, then the loop.
fn open_explorer(
    preset: Option<Result<rattleback::scenario::Preset, String>>,
    o: Opening<'_>,
) -> Outcome {
    let (config, keys) = config_or_exit()?;
    let preset = preset.unwrap_or_else(|| {
        let name = config.preset.as_deref();
        resolve(
            name.unwrap_or(rattleback::scenario::shipped::DEFAULT_PRESET),
            &[],
        )
        .map_err(|e| e.to_string())
    });
    let preset = match preset {
        Ok(p) => p,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    prepare_record(o.rec.record.as_deref(), o.rec.force)?;
    let setup = Setup {
        look: with_config(o.look, &config),
        sessions_dir: config.sessions_dir(),
        mouse: o.mouse || config.mouse,
        keys,
        lesson: o.lesson,
        partner: o.partner,
        follow: None,
        sign: o.rec.sign.clone(),
        serve: o.rec.serve,
    };
    explore(&setup, &preset, o.rec.record.clone(), None)
}

/// What the explorer needs from the command line and the configuration.
struct Setup {
    look: LookArgs,
    sessions_dir: Option<std::path::PathBuf>,
    mouse: bool,
    keys: UserKeys,
    lesson: Option<rattleback::scenario::lesson::Lesson>,
    partner: Option<rattleback::scenario::Preset>,
    follow: Option<std::path::PathBuf>,
    sign: Option<std::path::PathBuf>,
    /// `--serve`: where the recording is served to browsers as it is written.
    serve: Option<std::net::SocketAddr>,
}

fn explore(
    setup: &Setup,
    preset: &rattleback::scenario::Preset,
    record: Option<std::path::PathBuf>,
    replay: Option<record::Recording>,
) -> Outcome {
    if let Some(key) = &setup.sign
        && let Err(e) = record::sign::Signer::read(key)
    {
        return Err(Failure::input(format!("--sign: {e}")));
    }
    let look = &setup.look;
    let marker = marker(look.marker);
    let theme = match rattleback::scenario::theme::theme(look.theme.as_deref().unwrap_or("default"))
    {
        Ok(t) => t,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let (all, problems) = rattleback::scenario::theme::themes();
    let all: Vec<_> = all.into_iter().map(|(_, t)| t).collect();
    let depth = depth(look.color);
    let mut options = ExplorerOptions {
        fps: f64::from(look.fps.unwrap_or(30)),
        ui: UiOptions::new(
            marker,
            &theme,
            &all,
            no_color(look.color) || depth == Depth::None,
        )
        .with_charset(charset(look)),
        startup_problems: problems.iter().map(ToString::to_string).collect(),
        record,
        replay,
        sessions_dir: setup.sessions_dir.clone(),
        mouse: setup.mouse,
        keys: setup.keys.clone(),
        lesson: setup.lesson.clone(),
        partner: setup.partner.clone(),
        follow: setup.follow.clone(),
        sign: setup.sign.clone(),
        depth,
        served: None,
    };
    needs_terminal(if setup.follow.is_some() {
        "follow"
    } else if options.replay.is_some() {
        "replay"
    } else if setup.lesson.is_some() {
        "lesson"
    } else if setup.partner.is_some() {
        "compare"
    } else {
        "the explorer"
    })?;
    // Started once the terminal is known to draw; stopped when the explorer ends.
    let beside = match (setup.serve, &options.record) {
        (Some(listen), Some(file)) => Some(commands::serve::Beside::start(file, listen)?),
        _ => None,
    };
    options.served = beside.as_ref().map(|b| b.url.clone());
    match explorer::run(preset, &options) {
        Ok(None) => Ok(()),
        // Ended by a signal: the terminal is restored; exit as the convention says.
        Ok(Some(n)) => Err(Failure::signalled(n)),
        Err(e) => Err(Failure::failed(format!(
            "the explorer needs an interactive terminal ({e}); for headless runs use `rattleback simulate`"
        ))),
    }
}

/// An interactive command draws on standard output and reads its keys from standard input: it
/// refuses in one line (exit 2) when either is not a terminal, before the terminal is touched,
/// so no escape code lands in a file and no terminal is left raw (issue 54). Checked after
/// the preset and the configuration, which a user wants to hear about first.
fn needs_terminal(what: &str) -> Outcome {
    use std::io::IsTerminal as _;
    if std::env::var_os("TERM").is_some_and(|t| t == "dumb") {
        // A dumb terminal shows escape codes as text. Exit 2, as every refusal of a terminal
        // that cannot draw (before issue 68's review: 1).
        return Err(Failure::input(
            "TERM=dumb cannot show the explorer (it moves the cursor and draws); set TERM to the terminal's name (xterm-256color, screen, linux, …), or use `rattleback simulate` for text",
        ));
    }
    // Over ssh without `-t` neither is a terminal: the fix is ssh's flag, not a redirection.
    let over_ssh = std::env::var_os("SSH_CONNECTION").is_some_and(|v| !v.is_empty())
        || std::env::var_os("SSH_CLIENT").is_some_and(|v| !v.is_empty());
    let (stdout, stdin) = (
        std::io::stdout().is_terminal(),
        std::io::stdin().is_terminal(),
    );
    if over_ssh && !(stdout && stdin) {
        return Err(Failure::input(format!(
            "{what} draws on a terminal, and ssh gave it none: ask for one with `ssh -t HOST rattleback …` (or `RequestTTY yes` in ~/.ssh/config); `rattleback simulate` prints a report without one"
        )));
    }
    if !stdout {
        return Err(Failure::input(format!(
            "{what} draws on a terminal, and standard output is not one (redirected to a file or a pipe); run it without `>` or `|`, or use `rattleback simulate` for a report"
        )));
    }
    if !stdin {
        return Err(Failure::input(format!(
            "{what} reads its keys from a terminal, and standard input is not one (`<` a file, a pipe, or none); run it from a terminal"
        )));
    }
    Ok(())
}

/// What this terminal shows: `--ascii`, the locale, `TERM` ([`Charset::detect`]).
///
/// [`Charset::detect`]: rattleback::ui::glyphs::Charset::detect
fn charset(look: &LookArgs) -> rattleback::ui::glyphs::Charset {
    rattleback::ui::glyphs::Charset::detect(look.ascii, &|name| std::env::var(name).ok()).charset
}

/// The colours this terminal shows ([`Depth::detect`]: `COLORTERM`, terminfo, `TERM`);
/// `--color always` sends at least the sixteen.
fn depth(choice: rattleback::commands::cli::ColorChoice) -> Depth {
    let found = Depth::detect(
        &|name| std::env::var(name).ok(),
        &rattleback::terminal::depth::terminfo_colors,
    )
    .depth;
    if choice == rattleback::commands::cli::ColorChoice::Always {
        found.max(Depth::Sixteen)
    } else {
        found
    }
}

/// Whether colours are off: `--color`, then the environment ([`ColorChoice::colours_off`]).
fn no_color(choice: rattleback::commands::cli::ColorChoice) -> bool {
    if choice == rattleback::commands::cli::ColorChoice::Always {
        // crossterm itself leaves colours out under NO_COLOR unless told otherwise.
        ratatui::crossterm::style::force_color_output(true);
    }
    choice.colours_off_here()
}

fn run_simulate(args: &SimulateArgs) -> Outcome {
    let preset = match resolve(&args.preset, &args.set) {
        Ok(p) => p,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let request = args.request();
    let resolved = resolve_run(&preset, &request);
    let kind = preset.model.kind();
    if !kind.offers(resolved.spec.method) {
        return Err(Failure::input(format!(
            "--method {}: not offered for the {} model ({}); allowed: {}",
            resolved.spec.method,
            kind.name(),
            args.preset,
            kind.method_names()
        )));
    }
    if let Some(h) = resolved.spec.step
        && let Err(e) = rattleback::physics::method::check_step(h, resolved.spec.t_end)
    {
        return Err(Failure::input(format!("--step: {e}")));
    }
    let format = request.format;
    let mut progress =
        rattleback::commands::progress::Progress::stderr("simulate", resolved.spec.t_end);
    let outcome = if format == rattleback::simulate::Format::Table {
        // The table holds the preset's own text: cleaned of control characters first.
        simulate_to_text(&preset, &resolved, &mut progress)
    } else {
        // JSON escapes control characters itself; the CSV holds numbers only. Streamed.
        let mut out = std::io::BufWriter::new(std::io::stdout().lock());
        simulate_to(&preset, &resolved, format, &mut out, &mut |t| {
            progress.tick(t)
        })
    };
    progress.finish();
    match outcome {
        Ok(None) => Ok(()),
        Ok(Some(missed)) => {
            say_err!("rattleback: warning: {missed}");
            if args.strict {
                Err(Failure::said(1))
            } else {
                Ok(())
            }
        }
        // A closed pipe (e.g. `| head`) ends the output early; not an error worth a message.
        Err(Stopped::Output(e)) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(Stopped::Output(e)) => Err(Failure::failed(format!("writing the output: {e}"))),
        Err(Stopped::Run(e @ StepError::OverBudget { .. })) => Err(Failure::input(format!(
            "{e}; shorten --t-end, loosen --tolerance or choose another --method (`rattleback simulate --help`), or pass --force to run it anyway"
        ))),
        Err(Stopped::Run(e @ StepError::OutsideModel { .. })) => Err(Failure::input(format!(
            "--method {}: {e}",
            resolved.spec.method
        ))),
        Err(Stopped::Run(e)) => Err(Failure::failed(format!("integration failed: {e}"))),
    }
}

fn simulate_to_text(
    preset: &rattleback::scenario::Preset,
    resolved: &rattleback::simulate::Resolved,
    progress: &mut rattleback::commands::progress::Progress,
) -> Result<Option<rattleback::simulate::Missed>, Stopped> {
    let mut text = Vec::new();
    let missed = simulate_to(
        preset,
        resolved,
        rattleback::simulate::Format::Table,
        &mut text,
        &mut |t| progress.tick(t),
    )?;
    progress.finish();
    let text = rattleback::commands::wrap::for_stdout(&rattleback::scenario::text::shown(
        &String::from_utf8_lossy(&text),
    ));
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(missed)
}
