//! The manual's own sections, said once: `--help` prints the examples, the environment and the
//! exit status after the options; `rattleback man` renders them, with the keys, the files and
//! every subcommand, as one page (`rattleback.1`) that refers to no other page.

use std::fmt::Write as _;

use clap_mangen::roff::{Roff, bold, italic, roman};

use crate::app::keys::{KEYMAP, MAP_KEYS, REPLAY_KEYMAP};

/// `(command line, what it does)`: `--help`'s examples, and the manual's.
pub const EXAMPLES: &[(&str, &str)] = &[
    (
        "rattleback --preset celt-clockwise",
        "the explorer on a preset; ? keys",
    ),
    (
        "rattleback simulate --format json",
        "one run headless, a JSON report",
    ),
    (
        "rattleback --record lecture.jsonl",
        "record while exploring",
    ),
    ("rattleback lesson first-reversal", "a guided lesson"),
];

/// Each subcommand's examples, shown at the end of its `--help` and in the manual.
pub const SUBCOMMAND_EXAMPLES: &[(&str, &[(&str, &str)])] = &[
    (
        "simulate",
        &[
            ("rattleback simulate", "the default preset, a table"),
            (
                "rattleback simulate --preset supercritical --format json",
                "a report for scripts",
            ),
            (
                "rattleback simulate --set spring.k=1e6 --method auto --tolerance 1e-10",
                "another k, tighter",
            ),
            (
                "rattleback simulate --preset kapitza-upright --format csv > run.csv",
                "the samples",
            ),
        ],
    ),
    (
        "presets",
        &[
            ("rattleback presets", "every preset, shipped and yours"),
            (
                "rattleback presets show just-below > mine.toml",
                "a preset to edit",
            ),
        ],
    ),
    (
        "themes",
        &[("rattleback themes --format json", "every theme, as JSON")],
    ),
    (
        "lesson",
        &[
            ("rattleback lesson first-reversal", "a shipped lesson"),
            (
                "rattleback lesson kapitza-threshold --record class.jsonl",
                "recorded",
            ),
            ("rattleback lesson new mine", "a commented lesson to edit"),
        ],
    ),
    (
        "lessons",
        &[("rattleback lessons", "every lesson, shipped and yours")],
    ),
    (
        "compare",
        &[(
            "rattleback compare subcritical celt-clockwise",
            "holonomic beside rolling",
        )],
    ),
    (
        "serve",
        &[
            (
                "rattleback serve lecture.jsonl",
                "on this machine (an SSH tunnel brings it elsewhere)",
            ),
            (
                "rattleback serve lecture.jsonl --listen 0.0.0.0:8080",
                "on the hall's network, with a token",
            ),
            (
                "rattleback --record lecture.jsonl --serve 0.0.0.0:8080",
                "record and serve at once: the address and its QR code on screen",
            ),
        ],
    ),
    (
        "follow",
        &[(
            "rattleback follow lecture.jsonl",
            "while the lecturer records it",
        )],
    ),
    (
        "check",
        &[
            (
                "rattleback check mine.toml",
                "every problem, with line and key",
            ),
            (
                "rattleback check lessons/*.toml --format json",
                "for scripts",
            ),
        ],
    ),
    (
        "replay",
        &[
            (
                "rattleback replay lecture.jsonl",
                "in the explorer, at its pace",
            ),
            (
                "rattleback replay lecture.jsonl --verify --key me.pub",
                "bit for bit, signed",
            ),
            (
                "rattleback replay lecture.jsonl --export-html lecture.html",
                "one page",
            ),
            (
                "rattleback replay lecture.jsonl --chapters",
                "the chapter list",
            ),
        ],
    ),
    (
        "bench",
        &[
            ("rattleback bench --quick", "a shorter study"),
            ("rattleback bench --only kapitza", "one scene"),
        ],
    ),
    (
        "study",
        &[
            (
                "rattleback study sweep",
                "the distance to the limit against k",
            ),
            (
                "rattleback study map --preset kapitza-upright",
                "the stability chart",
            ),
            (
                "rattleback study map --grid 60x12 --format table",
                "a small map as text",
            ),
        ],
    ),
    (
        "completions",
        &[("source <(rattleback completions bash)", "in ~/.bashrc")],
    ),
    (
        "man",
        &[(
            "rattleback man > rattleback.1 && man -l rattleback.1",
            "read it",
        )],
    ),
    (
        "keygen",
        &[("rattleback keygen me", "me.key (private) and me.pub")],
    ),
    (
        "config",
        &[
            ("rattleback config path", "where config.toml is"),
            (
                "rattleback config show > config.toml",
                "a file to start from",
            ),
        ],
    ),
    (
        "doctor",
        &[("rattleback doctor --format json", "for a bug report")],
    ),
    (
        "web",
        &[(
            "rattleback web site",
            "site/index.html and site/rattleback.wasm, for any static server",
        )],
    ),
];

/// `rows` under an `Examples:` heading, one line each (command, then what it does) where both
/// fit in 80 columns, else the words under the command.
#[must_use]
pub fn examples_text(rows: &[(&str, &str)]) -> String {
    let width = rows
        .iter()
        .map(|(c, _)| c.chars().count())
        .max()
        .unwrap_or(0);
    let mut out = String::from("Examples:\n");
    for (cmd, what) in rows {
        if 2 + width + 2 + what.chars().count() <= 80 {
            let _ = writeln!(out, "  {cmd:<width$}  {what}");
        } else {
            let _ = writeln!(out, "  {cmd}\n      {what}");
        }
    }
    out.trim_end().to_owned()
}

/// `(variable, what it does)`.
pub const ENVIRONMENT: &[(&str, &str)] = &[
    (
        "RATTLEBACK_CONFIG_DIR",
        "the configuration folder instead of the platform's (config.toml, presets/, themes/, lessons/); recordings then go to its sessions/ folder",
    ),
    (
        "NO_COLOR",
        "set and not empty: no colours (under --color auto)",
    ),
    (
        "CLICOLOR_FORCE",
        "set, not empty and not 0: colours even where NO_COLOR is unset and CLICOLOR=0",
    ),
    ("CLICOLOR", "0: no colours (unless CLICOLOR_FORCE)"),
    (
        "LC_ALL, LC_CTYPE, LANG",
        "the first one set: a locale that is not UTF-8 (C, POSIX, en_US.ISO-8859-1) draws in ASCII only (as --ascii)",
    ),
    (
        "TERM",
        "dumb: the explorer, replay, follow, compare and lesson refuse (headless commands work); linux: only the characters the console's fonts have (no Braille); vt100, vt102, vt220, ansi: ASCII only",
    ),
];

/// `(path, what it holds)`, as on Linux.
pub const FILES: &[(&str, &str)] = &[
    (
        "~/.config/rattleback/config.toml",
        "the configuration: default preset, theme, fps, marker, sessions folder, mouse, ascii, extra keys (rattleback config show prints it; rattleback config path says where it is on this platform)",
    ),
    (
        "--config FILE",
        "read FILE instead of config.toml (before or after any command)",
    ),
    (
        "~/.config/rattleback/presets/*.toml",
        "the user's presets, listed beside the shipped ones by rattleback presets",
    ),
    (
        "~/.config/rattleback/themes/*.toml",
        "the user's colour themes (rattleback themes)",
    ),
    (
        "~/.config/rattleback/lessons/*.toml",
        "the user's lessons (rattleback lessons)",
    ),
    (
        "~/.local/share/rattleback/sessions/",
        "where R records and x exports when no path is given",
    ),
];

/// `(code, when)`.
pub const EXIT_STATUS: &[(&str, &str)] = &[
    ("0", "success"),
    (
        "1",
        "a run failed: an integration that could not continue, a recording that did not verify, simulate --strict that missed its tolerance, an output that could not be written, or a terminal the explorer could not open",
    ),
    (
        "2",
        "bad input: an unknown flag or value, an invalid preset, theme, lesson, config or session file (every problem is named with its file, line and key), an output file that exists without --force, work refused as over the budget, or an interactive command (the explorer, lesson, compare, replay, follow) whose standard input or output is not a terminal, or under TERM=dumb",
    ),
    (
        "128+N",
        "ended by signal N (130 for Ctrl-C, 143 for SIGTERM), with the terminal restored and no half-written file",
    ),
];

/// The text `--help` prints after the options: the examples, and where the rest is.
#[must_use]
pub fn after_help() -> String {
    examples_text(EXAMPLES)
        + "\n\nMore: rattleback COMMAND --help; keys, environment, exit status: rattleback man"
}

/// The whole manual page: clap's title, name, synopsis, description and options, then every
/// subcommand with its own options, then KEYS, ENVIRONMENT, FILES, EXIT STATUS and EXAMPLES.
///
/// # Errors
/// Writing into `w`.
pub fn render(cmd: clap::Command, w: &mut dyn std::io::Write) -> std::io::Result<()> {
    let mut page = Vec::new();
    render_page(cmd, &mut page)?;
    w.write_all(roff_safe(&String::from_utf8_lossy(&page)).as_bytes())
}

/// Roff that `man` shows under any locale: groff names most characters the help uses (Greek
/// letters, arrows, `×`, `–`) and shows them as `<alpha>`, `->` under `LANG=C`, but has no
/// name for the ellipsis or a combining dot above (`α̇`), which it drops with a warning
/// (`man --warnings`, issue 54). Those two are written as roff spells them.
fn roff_safe(page: &str) -> String {
    page.replace('…', "...").replace('\u{307}', "\\[a.]")
}

fn render_page(cmd: clap::Command, w: &mut dyn std::io::Write) -> std::io::Result<()> {
    let cmd = cmd.after_help("").after_long_help("");
    let man = clap_mangen::Man::new(cmd.clone());
    man.render_title(w)?;
    man.render_name_section(w)?;
    man.render_synopsis_section(w)?;
    man.render_description_section(w)?;
    man.render_options_section(w)?;
    let mut roff = Roff::new();
    roff.control("SH", ["COMMANDS"]);
    for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
        command(&mut roff, &[cmd.get_name()], sub);
    }
    roff.control("SH", ["KEYS"]);
    roff.text([roman(
        "In the explorer (? shows them with the colours of the curves):",
    )]);
    let key_rows = |roff: &mut Roff, rows: Vec<(&str, &str)>| {
        for (keys, what) in rows {
            roff.control("TP", []);
            roff.text([bold(keys)]);
            roff.text([roman(what)]);
        }
    };
    let explorer = KEYMAP
        .iter()
        .filter(|b| !b.label.is_empty())
        .map(|b| (b.label, b.help));
    key_rows(&mut roff, explorer.collect());
    roff.control("PP", []);
    roff.text([roman("While the regime map (M) has the arrows:")]);
    key_rows(&mut roff, MAP_KEYS.to_vec());
    roff.control("PP", []);
    roff.text([roman("In a replay:")]);
    let replay = REPLAY_KEYMAP
        .iter()
        .filter(|b| !b.label.is_empty())
        .map(|b| (b.label, b.help));
    key_rows(&mut roff, replay.collect());
    roff.control("PP", []);
    roff.text([roman(
        "Keys are added, moved or unbound in the [keys] table of config.toml: action = \"key\" adds one; \"none\" first takes the action's own keys away (presets = [\"none\", \"P\"]), which frees them for another. rattleback config show lists the actions.",
    )]);
    for (title, rows) in [
        ("ENVIRONMENT", ENVIRONMENT),
        ("FILES", FILES),
        ("EXIT STATUS", EXIT_STATUS),
    ] {
        roff.control("SH", [title]);
        for (what, why) in rows {
            roff.control("TP", []);
            roff.text([bold(*what)]);
            roff.text([roman(*why)]);
        }
    }
    roff.control("SH", ["EXAMPLES"]);
    for (line, what) in EXAMPLES {
        roff.control("TP", []);
        roff.text([bold(*line)]);
        roff.text([roman(*what)]);
    }
    roff.to_writer(w)?;
    man.render_version_section(w)
}

/// One subcommand (and its own subcommands): a subsection with its usage, its description and
/// its options.
fn command(roff: &mut Roff, parents: &[&str], cmd: &clap::Command) {
    let mut path = parents.to_vec();
    path.push(cmd.get_name());
    roff.control("SS", [path.join(" ").as_str()]);
    let about = cmd
        .get_long_about()
        .or_else(|| cmd.get_about())
        .map(ToString::to_string)
        .unwrap_or_default();
    let mut usage = vec![bold(path.join(" "))];
    let mut words = Vec::new();
    for arg in cmd.get_arguments().filter(|a| !a.is_hide_set()) {
        let id = arg.get_id().as_str();
        if id == "help" || id == "version" {
            continue;
        }
        let word = usage_word(arg);
        words.push(if arg.is_required_set() || arg.get_long().is_none() {
            word
        } else {
            format!("[{word}]")
        });
    }
    if cmd.has_subcommands() {
        words.push(format!(
            "{{{}}}",
            cmd.get_subcommands()
                .map(clap::Command::get_name)
                .filter(|n| *n != "help")
                .collect::<Vec<_>>()
                .join("|")
        ));
    }
    for w in &words {
        usage.push(roman(" "));
        usage.push(italic(w.as_str()));
    }
    roff.control("PP", []);
    roff.text(usage);
    roff.control("PP", []);
    roff.text([roman(about)]);
    if let Some((_, rows)) = SUBCOMMAND_EXAMPLES
        .iter()
        .find(|(name, _)| parents.len() == 1 && *name == cmd.get_name())
    {
        roff.control("PP", []);
        roff.text([roman("Examples:")]);
        for (line, what) in *rows {
            roff.control("TP", []);
            roff.text([bold(*line)]);
            roff.text([roman(*what)]);
        }
    }
    for arg in cmd.get_arguments().filter(|a| !a.is_hide_set()) {
        let id = arg.get_id().as_str();
        if id == "help" || id == "version" {
            continue;
        }
        roff.control("TP", []);
        roff.text([bold(usage_word(arg))]);
        let help = arg
            .get_long_help()
            .or_else(|| arg.get_help())
            .map(ToString::to_string)
            .unwrap_or_default();
        let values: Vec<String> = arg
            .get_possible_values()
            .iter()
            .filter(|v| !v.is_hide_set())
            .map(|v| v.get_name().to_owned())
            .collect();
        let mut text = help;
        if !values.is_empty() && arg.get_action().takes_values() {
            let _ = write!(text, " [possible values: {}]", values.join(", "));
        }
        let defaults: Vec<String> = arg
            .get_default_values()
            .iter()
            .map(|v| v.to_string_lossy().into_owned())
            .collect();
        if !defaults.is_empty() {
            let _ = write!(text, " [default: {}]", defaults.join(","));
        }
        roff.text([roman(text)]);
    }
    for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
        command(roff, &path, sub);
    }
}

/// `--flag VALUE`, `-f`, or `NAME` for a positional argument.
fn usage_word(arg: &clap::Arg) -> String {
    let value = arg
        .get_value_names()
        .and_then(|v| v.first())
        .map_or_else(|| arg.get_id().as_str().to_uppercase(), ToString::to_string);
    match (arg.get_long(), arg.get_short()) {
        (Some(l), _) if arg.get_action().takes_values() => format!("--{l} {value}"),
        (Some(l), _) => format!("--{l}"),
        (None, Some(s)) => format!("-{s}"),
        (None, None) => value,
    }
}
