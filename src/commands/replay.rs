//! `rattleback replay`: a session played back, verified (`--verify`), listed by chapter, or
//! exported as a cast or a page.

use super::explore::{Setup, explore};
use super::shared::{cast_options, check_output, config_or_exit, refuse_stdin, with_config};
use crate::commands;
use crate::commands::cli::{LookArgs, ReplayArgs};
use crate::commands::failure::{Failure, Outcome};
use crate::record;

/// `cast::export_cast` and `page::export_html`: a session written into a file.
type Export = fn(
    &record::Recording,
    &str,
    &std::path::Path,
    &crate::ui::UiOptions,
    crate::cast::CastSize,
    bool,
    &mut dyn FnMut(usize),
) -> Result<usize, record::RecordError>;

/// `replay --export-cast` and `--export-html`: the session drawn into an asciicast file and
/// into a page that plays it, without the key footer.
pub(crate) fn export_files(
    args: &ReplayArgs,
    rec: &record::Recording,
    path: &str,
    look: &LookArgs,
) -> Outcome {
    let options = cast_options(look)?;
    let size = crate::cast::CastSize {
        cols: args.cols,
        rows: args.rows,
        fps: f64::from(look.fps.unwrap_or(10)),
    };
    let outputs: [(Option<&std::path::Path>, &str, Export); 2] = [
        (
            args.export_cast.as_deref(),
            "export-cast",
            crate::cast::export_cast,
        ),
        (
            args.export_html.as_deref(),
            "export-html",
            crate::commands::page::export_html,
        ),
    ];
    for (out, what, export) in outputs {
        let Some(out) = out else { continue };
        let mut progress =
            crate::commands::progress::Progress::count(what, rec.lines.len(), "lines");
        let written = export(rec, path, out, &options, size, args.force, &mut |n| {
            progress.tick(n as f64);
        });
        progress.finish();
        if let (Err(_), Some(n)) = (&written, crate::interrupt::requested()) {
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
pub(crate) fn same_place(a: &std::path::Path, b: &std::path::Path) -> bool {
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

pub fn run_replay(args: &ReplayArgs) -> Outcome {
    let exporting = args.export_cast.is_some() || args.export_html.is_some();
    if args.file.as_os_str() == "-" && !args.verify && !args.chapters && !exporting {
        return refuse_stdin("replay -");
    }
    let path = crate::scenario::write::label(&args.file);
    let json = args.format == crate::commands::cli::ListFormat::Json;
    if json && (args.chapters == args.verify || exporting) {
        return Err(Failure::input(
            "--format json goes with one of --chapters or --verify (and not --export-cast or --export-html)",
        ));
    }
    // A bad `--theme` is an error whatever else is asked (it would be when drawing).
    if let Some(name) = &args.look.theme
        && let Err(e) = crate::scenario::theme::theme(name)
    {
        return Err(Failure::input(format!("--theme: {e}")));
    }
    // One file cannot be both: the page would replace the cast (issue 56).
    if let (Some(cast), Some(page)) = (&args.export_cast, &args.export_html)
        && same_place(cast, page)
    {
        return Err(Failure::input(format!(
            "--export-cast and --export-html name the same file ({}); give each its own",
            crate::scenario::write::label(cast)
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
                let v = crate::commands::outputs::Verification::of(None, &path, Err(&failed));
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
            commands::json_text(&crate::commands::outputs::Chapters::of(&rec, &path))
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
    let preset = match crate::scenario::Preset::parse(
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

/// The theme of a replay: `--theme` when given, else the recorded one when this machine has a
/// theme of that name or title, else `default` (an older header has only an index).
pub(crate) fn replay_theme(asked: Option<&str>, recorded: &record::ThemeRef) -> String {
    if let Some(name) = asked {
        return name.to_owned();
    }
    let Some(name) = recorded.name() else {
        return "default".to_owned();
    };
    let (all, _) = crate::scenario::theme::themes();
    if let Some((key, _)) = all
        .iter()
        .find(|(key, spec)| key == name || crate::scenario::text::clean(&spec.name) == name)
    {
        return key.clone();
    }
    say_err!(
        "rattleback: warning: the recorded theme '{name}' is not on this machine; using default"
    );
    "default".to_owned()
}
