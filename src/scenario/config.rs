//! The user's configuration: `config.toml` in the config folder (`rattleback config path`).
//! Every key is optional; a flag on the command line wins over the file, the file over the
//! defaults. Errors name the file, the line and the key, like presets.
//!
//! ```toml
//! preset = "supercritical"   # what `rattleback` opens
//! theme = "dark"             # a theme name or path
//! fps = 30                   # frame-rate cap, 1 to 240
//! marker = "braille"         # braille, halfblock or dot
//! sessions = "~/lectures"    # where R records (and x exports); ~ is the home folder
//! mouse = true               # click in the portrait sets the start, the wheel zooms
//! ascii = true               # ASCII only (as --ascii), for terminals without UTF-8
//!
//! [keys]                     # extra keys: action = "key" or ["key", "key"]
//! zoom_in = "i"
//! toggle_play = ["p", "ctrl-p"]
//! ```
//!
//! Key bindings are checked against the explorer's actions and keys by the app layer
//! (`app::keys::UserKeys`); this module only reads them, with their lines.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::error::{PresetError, SourceMap};

/// The file's name inside the config folder.
pub const FILE_NAME: &str = "config.toml";

/// The keys of the top level.
pub const KEYS: [&str; 8] = [
    "preset", "theme", "fps", "marker", "sessions", "mouse", "ascii", "keys",
];

/// The markers `marker` takes.
pub const MARKERS: [&str; 3] = ["braille", "halfblock", "dot"];

/// One `[keys]` entry: an action name and its keys, as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KeyEntry {
    /// The action, as named in `[keys]`.
    pub action: String,
    /// The keys, as written (`"i"`, `"ctrl-p"`, `"up"`…).
    pub keys: Vec<String>,
    /// Where it is written.
    pub line: usize,
}

/// The configuration (all optional).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Config {
    /// The file it was read from (`None`: no file, the defaults).
    pub path: Option<PathBuf>,
    /// Default preset.
    pub preset: Option<String>,
    /// Default theme.
    pub theme: Option<String>,
    /// Frame-rate cap.
    pub fps: Option<u32>,
    /// Canvas marker (one of [`MARKERS`]).
    pub marker: Option<String>,
    /// Where recordings and exports go.
    pub sessions: Option<PathBuf>,
    /// Mouse on.
    pub mouse: bool,
    /// ASCII only (`--ascii`).
    pub ascii: bool,
    /// Extra key bindings.
    pub keys: Vec<KeyEntry>,
}

/// The config file's path (it need not exist).
#[must_use]
pub fn path() -> Option<PathBuf> {
    super::shipped::config_dir().map(|d| d.join(FILE_NAME))
}

/// The `[keys]` table's entries, each with its line.
fn key_entries(
    map: &SourceMap,
    label: &str,
    keys: &toml::Table,
) -> Result<Vec<KeyEntry>, PresetError> {
    let mut out = Vec::new();
    for (action, v) in keys {
        let at = map.find_key("keys", action).unwrap_or(1);
        let bad = || PresetError::Invalid {
            path: label.to_owned(),
            line: Some(at),
            key: Some(format!("keys.{action}")),
            message: "expected a key in quotes or a list of them".to_owned(),
        };
        let list = match v {
            toml::Value::String(s) => vec![s.clone()],
            toml::Value::Array(a) => a
                .iter()
                .map(|k| k.as_str().map(str::to_owned))
                .collect::<Option<Vec<_>>>()
                .ok_or_else(bad)?,
            _ => return Err(bad()),
        };
        out.push(KeyEntry {
            action: action.clone(),
            keys: list,
            line: at,
        });
    }
    Ok(out)
}

/// The folder recordings and exports go to by default: the platform's data folder
/// (`~/.local/share/rattleback/sessions` on Linux), or `sessions` in the config folder when
/// `RATTLEBACK_CONFIG_DIR` is set (tests, portable installs).
#[must_use]
pub fn default_sessions_dir() -> Option<PathBuf> {
    if std::env::var_os(super::shipped::CONFIG_ENV).is_some_and(|d| !d.is_empty()) {
        return super::shipped::config_dir().map(|d| d.join("sessions"));
    }
    directories::ProjectDirs::from("", "", "rattleback").map(|d| d.data_dir().join("sessions"))
}

impl Config {
    /// Reads the user's config file; no file is the defaults.
    ///
    /// # Errors
    /// An unreadable or invalid file (its first problem).
    pub fn load() -> Result<Self, PresetError> {
        match path() {
            Some(p) if p.exists() => Self::read(&p),
            _ => Ok(Self::default()),
        }
    }

    /// Reads the config file at `path`.
    ///
    /// # Errors
    /// An unreadable or invalid file (its first problem).
    pub fn read(path: &Path) -> Result<Self, PresetError> {
        let src = PresetError::read(path)?;
        let mut config = Self::parse(&src, &path.display().to_string())?;
        config.path = Some(path.to_path_buf());
        Ok(config)
    }

    /// Parses a config file's text; `label` names it in errors.
    ///
    /// # Errors
    /// The first problem, located.
    pub fn parse(src: &str, label: &str) -> Result<Self, PresetError> {
        let map = SourceMap::new(src);
        let table = map.parse_table(label)?;
        let err = |key: &str, message: String| PresetError::Invalid {
            path: label.to_owned(),
            line: Some(map.find_path(key).unwrap_or(1)),
            key: Some(key.to_owned()),
            message,
        };
        let mut c = Self::default();
        for (key, value) in &table {
            let text = || {
                value
                    .as_str()
                    .map(str::to_owned)
                    .ok_or_else(|| err(key, format!("expected text in quotes, found {value}")))
            };
            match key.as_str() {
                "preset" => c.preset = Some(text()?),
                "theme" => c.theme = Some(text()?),
                "fps" => {
                    let fps = value
                        .as_integer()
                        .filter(|n| (1..=240).contains(n))
                        .ok_or_else(|| {
                            err(
                                key,
                                format!("{value}: allowed a whole number from 1 to 240"),
                            )
                        })?;
                    c.fps = Some(u32::try_from(fps).unwrap_or(30));
                }
                "marker" => {
                    let m = text()?;
                    if !MARKERS.contains(&m.as_str()) {
                        return Err(err(
                            key,
                            format!(
                                "unknown marker '{m}'; allowed: {}{}",
                                MARKERS.join(", "),
                                super::text::did_you_mean(&m, MARKERS)
                            ),
                        ));
                    }
                    c.marker = Some(m);
                }
                "sessions" => c.sessions = Some(expand_home(&text()?)),
                "mouse" | "ascii" => {
                    let on = value
                        .as_bool()
                        .ok_or_else(|| err(key, format!("{value}: allowed true or false")))?;
                    if key == "mouse" {
                        c.mouse = on;
                    } else {
                        c.ascii = on;
                    }
                }
                "keys" => {
                    let Some(keys) = value.as_table() else {
                        return Err(err(key, "expected a [keys] table".to_owned()));
                    };
                    c.keys = key_entries(&map, label, keys)?;
                }
                other => {
                    return Err(err(
                        other,
                        format!(
                            "unknown key `{other}`, expected one of {}{}",
                            KEYS.map(|k| format!("`{k}`")).join(", "),
                            super::text::did_you_mean(other, KEYS)
                        ),
                    ));
                }
            }
        }
        Ok(c)
    }

    /// The folder recordings and exports go to.
    #[must_use]
    pub fn sessions_dir(&self) -> Option<PathBuf> {
        self.sessions.clone().or_else(default_sessions_dir)
    }

    /// The configuration as a TOML file (`config show`): every key, the defaults commented.
    #[must_use]
    pub fn to_toml(&self) -> String {
        let q = |s: &str| toml::Value::String(s.to_owned()).to_string();
        let line = |set: Option<String>, key: &str, default: &str| match set {
            Some(v) => format!("{key} = {v}\n"),
            None => format!("# {key} = {default}\n"),
        };
        let mut out = String::new();
        out += &line(
            self.preset.as_deref().map(q),
            "preset",
            &q(super::shipped::DEFAULT_PRESET),
        );
        out += &line(self.theme.as_deref().map(q), "theme", &q("default"));
        out += &line(self.fps.map(|f| f.to_string()), "fps", "30");
        out += &line(self.marker.as_deref().map(q), "marker", &q("braille"));
        let default_sessions =
            default_sessions_dir().map_or_else(String::new, |d| d.display().to_string());
        out += &line(
            self.sessions.as_ref().map(|p| q(&p.display().to_string())),
            "sessions",
            &q(&default_sessions),
        );
        out += &line(self.mouse.then(|| "true".to_owned()), "mouse", "false");
        out += &line(self.ascii.then(|| "true".to_owned()), "ascii", "false");
        out += "\n[keys]\n";
        if self.keys.is_empty() {
            out += "# zoom_in = \"i\"\n";
        }
        for k in &self.keys {
            let keys: Vec<String> = k.keys.iter().map(|s| q(s)).collect();
            let value = if keys.len() == 1 {
                keys[0].clone()
            } else {
                format!("[{}]", keys.join(", "))
            };
            let _ = writeln!(out, "{} = {value}", k.action);
        }
        out
    }
}

/// `~/x` with the home folder; anything else as written.
fn expand_home(text: &str) -> PathBuf {
    match (text.strip_prefix("~/"), directories::BaseDirs::new()) {
        (Some(rest), Some(base)) => base.home_dir().join(rest),
        _ => PathBuf::from(text),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_is_read_and_errors_are_located() {
        let c = Config::parse(
            "preset = \"supercritical\"\ntheme = \"dark\"\nfps = 60\nmarker = \"dot\"\nsessions = \"/tmp/s\"\nmouse = true\n\n[keys]\nzoom_in = \"i\"\ntoggle_play = [\"p\", \"ctrl-p\"]\n",
            "c.toml",
        )
        .unwrap();
        assert_eq!(c.preset.as_deref(), Some("supercritical"));
        assert_eq!(c.fps, Some(60));
        assert!(c.mouse);
        assert_eq!(c.sessions, Some(PathBuf::from("/tmp/s")));
        assert_eq!(c.keys.len(), 2);
        let play = c.keys.iter().find(|k| k.action == "toggle_play").unwrap();
        assert_eq!(play.keys, ["p", "ctrl-p"]);
        assert_eq!(play.line, 10);
        // The round trip through `config show`.
        let strip = |c: Config| Config {
            keys: c
                .keys
                .into_iter()
                .map(|k| KeyEntry { line: 0, ..k })
                .collect(),
            ..c
        };
        assert_eq!(
            strip(Config::parse(&c.to_toml(), "shown").unwrap()),
            strip(c)
        );

        let e = Config::parse("fps = 30\n\nmarkr = \"dot\"\n", "c.toml").unwrap_err();
        assert_eq!(e.line(), Some(3));
        assert!(e.to_string().contains("did you mean `marker`?"), "{e}");
        let e = Config::parse("fps = 0\n", "c.toml").unwrap_err();
        assert!(
            e.to_string()
                .contains("c.toml:1: fps: 0: allowed a whole number from 1 to 240"),
            "{e}"
        );
        let e = Config::parse("marker = \"brail\"\n", "c.toml").unwrap_err();
        assert!(e.to_string().contains("did you mean `braille`?"), "{e}");
        let e = Config::parse("[keys]\n\nzoom_in = 3\n", "c.toml").unwrap_err();
        assert_eq!(e.line(), Some(3));
        assert_eq!(e.key(), Some("keys.zoom_in"));
    }
}
