//! What the commands below share: the look a command draws with (theme, marker, colours,
//! character set), the configuration, the refusals of an output or a terminal.

use crate::app::user_keys::UserKeys;
use crate::commands;
use crate::commands::cli::{LookArgs, MarkerChoice};
use crate::commands::failure::{Failure, Outcome};
use crate::scenario::config::Config;
use crate::terminal::Depth;
use crate::ui::UiOptions;

/// `-` (standard input) where the explorer opens: it reads its keys from standard input.
pub(crate) fn refuse_stdin(what: &str) -> Outcome {
    Err(Failure::input(format!(
        "{what}: the explorer reads its keys from standard input, so it cannot read a file from it; save it to a file, or use - with simulate, study, check, presets show or replay --verify/--chapters/--export-cast"
    )))
}

/// Refuses an output that exists (unless `force`) or that is `input` itself.
pub(crate) fn check_output(
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
    crate::scenario::write::replaceable(out).map_err(|e| format!("{flag} {e}"))
}

/// How a cast, an exported page and `serve` draw: `--theme` or the default, no key footer, and
/// ASCII only when asked (a cast is played elsewhere, not on this terminal).
pub(crate) fn cast_options(look: &LookArgs) -> Result<UiOptions, Failure> {
    let theme = crate::scenario::theme::theme(look.theme.as_deref().unwrap_or("default"))
        .map_err(Failure::input)?;
    let all: Vec<_> = crate::scenario::theme::themes()
        .0
        .into_iter()
        .map(|(_, t)| t)
        .collect();
    let charset = if look.ascii {
        crate::ui::glyphs::Charset::Ascii
    } else {
        crate::ui::glyphs::Charset::Unicode
    };
    Ok(
        UiOptions::new(marker(look.marker), &theme, &all, no_color(look.color))
            .with_charset(charset)
            .without_footer(),
    )
}

/// The configuration and the user's keys, or the exit of an invalid `config.toml` (its error
/// said on stderr).
pub fn config_or_exit() -> Result<(Config, UserKeys), Failure> {
    commands::load_config().map_err(Failure::inputs)
}

/// The look asked on the command line, completed by the configuration.
pub(crate) fn with_config(look: &LookArgs, config: &Config) -> LookArgs {
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

pub(crate) fn marker(choice: Option<MarkerChoice>) -> ratatui::symbols::Marker {
    match choice.unwrap_or(MarkerChoice::Braille) {
        MarkerChoice::Braille => ratatui::symbols::Marker::Braille,
        MarkerChoice::Halfblock => ratatui::symbols::Marker::HalfBlock,
        MarkerChoice::Dot => ratatui::symbols::Marker::Dot,
    }
}

/// Checks a `--record` file before the terminal is touched: new, or `force` (then the old one
/// is removed, since the recorder itself never replaces a file).
pub(crate) fn prepare_record(out: Option<&std::path::Path>, force: bool) -> Outcome {
    let Some(out) = out else { return Ok(()) };
    if let Err(e) = check_output(out, None, force, "--record") {
        return Err(Failure::input(e));
    }
    if force {
        let _ = std::fs::remove_file(out);
    }
    Ok(())
}

/// An interactive command draws on standard output and reads its keys from standard input: it
/// refuses in one line (exit 2) when either is not a terminal, before the terminal is touched,
/// so no escape code lands in a file and no terminal is left raw (issue 54). Checked after
/// the preset and the configuration, which a user wants to hear about first.
pub(crate) fn needs_terminal(what: &str) -> Outcome {
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
/// [`Charset::detect`]: crate::ui::glyphs::Charset::detect
pub(crate) fn charset(look: &LookArgs) -> crate::ui::glyphs::Charset {
    crate::ui::glyphs::Charset::detect(look.ascii, &|name| std::env::var(name).ok()).charset
}

/// The colours this terminal shows ([`Depth::detect`]: `COLORTERM`, terminfo, `TERM`);
/// `--color always` sends at least the sixteen.
pub(crate) fn depth(choice: crate::commands::cli::ColorChoice) -> Depth {
    let found = Depth::detect(
        &|name| std::env::var(name).ok(),
        &crate::terminal::depth::terminfo_colors,
    )
    .depth;
    if choice == crate::commands::cli::ColorChoice::Always {
        found.max(Depth::Sixteen)
    } else {
        found
    }
}

/// Whether colours are off: `--color`, then the environment ([`ColorChoice::colours_off`]).
///
/// [`ColorChoice::colours_off`]: crate::commands::cli::ColorChoice::colours_off
pub(crate) fn no_color(choice: crate::commands::cli::ColorChoice) -> bool {
    if choice == crate::commands::cli::ColorChoice::Always {
        // crossterm itself leaves colours out under NO_COLOR unless told otherwise.
        ratatui::crossterm::style::force_color_output(true);
    }
    choice.colours_off_here()
}
