//! `rattleback doctor`: what this machine and terminal look like to the program, and what the
//! explorer would choose here (characters, colours, marker, preset, theme, folders), with the
//! reason for each choice. Paste its output into a bug report.

use std::io::IsTerminal as _;

use serde::Serialize;

use crate::scenario::config::{self, Config};
use crate::scenario::shipped;
use crate::ui::glyphs::Charset;

/// What `doctor` found.
#[derive(Debug, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Diagnosis {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// `null`: doctor is about no model.
    pub model: Option<crate::physics::ModelKind>,
    /// `rattleback X.Y.Z`.
    pub version: String,
    /// The platform (`linux x86_64`).
    pub platform: String,
    /// The terminal.
    pub terminal: Terminal,
    /// What the explorer would choose here.
    pub chosen: Chosen,
    /// Where files are read and written.
    pub files: Files,
}

/// The terminal as the program sees it.
#[derive(Debug, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Terminal {
    /// `TERM` (`null` when unset).
    pub term: Option<String>,
    /// The locale in effect for characters: the first of `LC_ALL`, `LC_CTYPE`, `LANG` set.
    pub locale: Option<String>,
    /// Standard input, output and error are terminals.
    pub stdin_tty: bool,
    /// See `stdin_tty`.
    pub stdout_tty: bool,
    /// See `stdin_tty`.
    pub stderr_tty: bool,
    /// Columns × rows, when the output is a terminal.
    pub size: Option<[u16; 2]>,
    /// The colour variables as set (`null` when unset).
    pub no_color: Option<String>,
    /// See `no_color`.
    pub clicolor: Option<String>,
    /// See `no_color`.
    pub clicolor_force: Option<String>,
    /// `COLORTERM` (`truecolor` says 24-bit colours are shown).
    pub colorterm: Option<String>,
}

/// What the explorer would choose, each with why.
#[derive(Debug, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Chosen {
    /// `unicode`, `console` or `ascii`.
    pub characters: &'static str,
    /// Why those characters.
    pub characters_because: String,
    /// Colours on.
    pub colours: bool,
    /// Why colours are on or off.
    pub colours_because: String,
    /// The colours the terminal shows: `none`, `8`, `16`, `256` or `24-bit` (every colour code
    /// is fitted to it).
    pub colour_depth: &'static str,
    /// Why that depth (`COLORTERM`, the terminfo entry, or `TERM`'s name).
    pub colour_depth_because: String,
    /// The canvas marker in effect (`dot` when the characters have no Braille).
    pub marker: String,
    /// The preset `rattleback` opens.
    pub preset: String,
    /// The theme.
    pub theme: String,
    /// Frames per second.
    pub fps: u32,
    /// Mouse reporting on.
    pub mouse: bool,
    /// Whether the explorer can open here, and if not why.
    pub explorer: String,
}

/// Where the program reads and writes.
#[derive(Debug, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Files {
    /// The configuration folder, and whether `RATTLEBACK_CONFIG_DIR` chose it.
    pub config_dir: Option<String>,
    /// `RATTLEBACK_CONFIG_DIR` as set.
    pub config_dir_variable: Option<String>,
    /// config.toml's path.
    pub config_file: Option<String>,
    /// The user's presets folder (`presets/` in the configuration folder).
    pub presets_dir: Option<String>,
    /// `absent`, `valid` or the error.
    pub config_status: String,
    /// User presets, themes, lessons found.
    pub user_presets: usize,
    /// See `user_presets`.
    pub user_themes: usize,
    /// See `user_presets`.
    pub user_lessons: usize,
    /// Where `R` records.
    pub sessions: Option<String>,
}

/// What the command line asked, already decided by the caller (`--ascii`, `--color`).
#[derive(Clone, Debug)]
pub struct Asked {
    /// `--ascii`.
    pub ascii: bool,
    /// Colours off by `--color` and the environment.
    pub colours_off: bool,
    /// `--color`'s value (`auto`, `always`, `never`).
    pub color_flag: String,
    /// `--marker`, if given.
    pub marker: Option<String>,
}

/// Looks at the environment, the terminal and the configuration.
#[must_use]
/// `schema_version` is the outputs' (`crate::commands::outputs::SCHEMA_VERSION`, given by the command
/// layer: the outputs' schemas include this one's). `loaded` is the configuration as every command reads it (`--config FILE` already in
/// effect), or every problem it has, as the commands would refuse it.
pub fn diagnose(
    asked: &Asked,
    loaded: Result<Config, Vec<String>>,
    schema_version: u32,
) -> Diagnosis {
    let var = |name: &str| std::env::var(name).ok();
    let (config, config_status) = match loaded {
        Ok(c) if c.path.is_some() => (c, "valid".to_owned()),
        Ok(c) => (c, "absent: the defaults".to_owned()),
        Err(e) => (
            Config::default(),
            format!("invalid: {}", crate::scenario::text::bounded(&e).join("; ")),
        ),
    };
    let detected = Charset::detect(asked.ascii || config.ascii, &var);
    let depth = crate::terminal::Depth::detect(&var, &crate::terminal::depth::terminfo_colors);
    let depth = if asked.color_flag == "always" {
        crate::terminal::depth::Detected {
            depth: depth.depth.max(crate::terminal::Depth::Sixteen),
            reason: format!("--color always ({})", depth.reason),
        }
    } else {
        depth
    };
    let explorer = if var("TERM").as_deref() == Some("dumb") {
        "refused: TERM=dumb".to_owned()
    } else if !(std::io::stdin().is_terminal() && std::io::stdout().is_terminal()) {
        "needs a terminal on standard input and output (these are not)".to_owned()
    } else {
        "can open".to_owned()
    };
    let colours_because = match asked.color_flag.as_str() {
        "auto" => {
            let set =
                |n: &str| var(n).map_or_else(|| format!("{n} unset"), |v| format!("{n}={v:?}"));
            format!(
                "--color auto: {}, {}, {}",
                set("NO_COLOR"),
                set("CLICOLOR_FORCE"),
                set("CLICOLOR")
            )
        }
        flag => format!("--color {flag}"),
    };
    let marker = if detected.charset == Charset::Unicode {
        asked
            .marker
            .clone()
            .or_else(|| config.marker.clone())
            .unwrap_or_else(|| "braille".to_owned())
    } else {
        "dot (the characters have no Braille)".to_owned()
    };
    let count = |dir: Option<std::path::PathBuf>| {
        dir.and_then(|d| std::fs::read_dir(d).ok()).map_or(0, |r| {
            r.filter_map(Result::ok)
                .filter(|e| e.path().extension().is_some_and(|x| x == "toml"))
                .count()
        })
    };
    let config_dir = shipped::config_dir();
    Diagnosis {
        schema_version,
        model: None,
        version: format!("rattleback {}", env!("CARGO_PKG_VERSION")),
        platform: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
        terminal: terminal(),
        chosen: Chosen {
            characters: detected.charset.name(),
            characters_because: if asked.ascii || !config.ascii {
                detected.reason
            } else {
                "ascii = true in config.toml".to_owned()
            },
            colours: !asked.colours_off && depth.depth != crate::terminal::Depth::None,
            colours_because: if !asked.colours_off && depth.depth == crate::terminal::Depth::None {
                format!("the terminal shows none ({})", depth.reason)
            } else {
                colours_because
            },
            colour_depth: depth.depth.name(),
            colour_depth_because: depth.reason,
            marker,
            preset: config
                .preset
                .clone()
                .unwrap_or_else(|| shipped::DEFAULT_PRESET.to_owned()),
            theme: config.theme.clone().unwrap_or_else(|| "default".to_owned()),
            fps: config.fps.unwrap_or(30),
            mouse: config.mouse,
            explorer,
        },
        files: Files {
            config_dir: config_dir.as_ref().map(|d| d.display().to_string()),
            config_dir_variable: var(shipped::CONFIG_ENV),
            config_file: config::path().map(|p| p.display().to_string()),
            presets_dir: shipped::user_preset_dir().map(|d| d.display().to_string()),
            config_status,
            user_presets: count(shipped::user_preset_dir()),
            user_themes: count(config_dir.as_ref().map(|d| d.join("themes"))),
            user_lessons: count(config_dir.as_ref().map(|d| d.join("lessons"))),
            sessions: config.sessions_dir().map(|d| d.display().to_string()),
        },
    }
}

/// The terminal and its variables.
fn terminal() -> Terminal {
    let var = |name: &str| std::env::var(name).ok();
    let output_tty = std::io::stdout().is_terminal();
    Terminal {
        term: var("TERM"),
        locale: ["LC_ALL", "LC_CTYPE", "LANG"]
            .into_iter()
            .find_map(|n| var(n).filter(|v| !v.is_empty()).map(|v| format!("{n}={v}"))),
        stdin_tty: std::io::stdin().is_terminal(),
        stdout_tty: output_tty,
        stderr_tty: std::io::stderr().is_terminal(),
        size: output_tty
            .then(ratatui::crossterm::terminal::size)
            .and_then(Result::ok)
            .map(|(c, r)| [c, r]),
        no_color: var("NO_COLOR"),
        clicolor: var("CLICOLOR"),
        clicolor_force: var("CLICOLOR_FORCE"),
        colorterm: var("COLORTERM"),
    }
}

impl Diagnosis {
    /// The report as text, one `name  value` line each, in three groups.
    #[must_use]
    pub fn table(&self) -> String {
        let o = |v: &Option<String>| v.clone().unwrap_or_else(|| "(unset)".to_owned());
        let yes = |b: bool| if b { "yes" } else { "no" };
        let t = &self.terminal;
        let c = &self.chosen;
        let f = &self.files;
        let rows: Vec<(&str, String)> = vec![
            ("version", self.version.clone()),
            ("platform", self.platform.clone()),
            ("", String::new()),
            ("TERM", o(&t.term)),
            ("locale", o(&t.locale)),
            (
                "terminals",
                format!(
                    "stdin {}, stdout {}, stderr {}",
                    yes(t.stdin_tty),
                    yes(t.stdout_tty),
                    yes(t.stderr_tty)
                ),
            ),
            (
                "size",
                t.size.map_or_else(
                    || "(not a terminal)".to_owned(),
                    |[w, h]| format!("{w}x{h}"),
                ),
            ),
            ("COLORTERM", o(&t.colorterm)),
            ("", String::new()),
            (
                "characters",
                format!("{} ({})", c.characters, c.characters_because),
            ),
            (
                "colours",
                format!(
                    "{} ({})",
                    if c.colours { "on" } else { "off" },
                    c.colours_because
                ),
            ),
            (
                "colour depth",
                format!("{} ({})", c.colour_depth, c.colour_depth_because),
            ),
            ("marker", c.marker.clone()),
            ("preset", c.preset.clone()),
            ("theme", c.theme.clone()),
            ("fps", c.fps.to_string()),
            ("mouse", if c.mouse { "on" } else { "off" }.to_owned()),
            ("explorer", c.explorer.clone()),
            ("", String::new()),
            (
                "config folder",
                match &f.config_dir_variable {
                    Some(v) => format!("{} (RATTLEBACK_CONFIG_DIR={v})", o(&f.config_dir)),
                    None => o(&f.config_dir),
                },
            ),
            (
                "config file",
                format!("{} ({})", o(&f.config_file), f.config_status),
            ),
            ("presets folder", o(&f.presets_dir)),
            (
                "user files",
                format!(
                    "{} presets, {} themes, {} lessons",
                    f.user_presets, f.user_themes, f.user_lessons
                ),
            ),
            ("sessions", o(&f.sessions)),
        ];
        rows.into_iter()
            .map(|(k, v)| {
                if k.is_empty() {
                    "\n".to_owned()
                } else {
                    format!("{k:<16}{v}\n")
                }
            })
            .collect()
    }
}
