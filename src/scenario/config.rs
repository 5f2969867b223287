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

/// `--config FILE`: read this file instead of the config folder's (set once, at start).
static OVERRIDE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// Makes every later [`Config::load`] (and [`path`]) read `file` instead of the config folder's
/// `config.toml` (`--config FILE`); the first call wins.
pub fn use_file(file: PathBuf) {
    let _ = OVERRIDE.set(file);
}

/// The config file's path (it need not exist): `--config FILE`, else `config.toml` in the
/// config folder.
#[must_use]
pub fn path() -> Option<PathBuf> {
    OVERRIDE
        .get()
        .cloned()
        .or_else(|| super::shipped::config_dir().map(|d| d.join(FILE_NAME)))
}

/// The `[keys]` table's entries, each with its line, and the problems of those that are not a
/// key or a list of keys.
fn key_entries(
    map: &SourceMap,
    label: &str,
    keys: &toml::Table,
) -> (Vec<KeyEntry>, Vec<PresetError>) {
    let (mut out, mut errors) = (Vec::new(), Vec::new());
    for (action, v) in keys {
        let at = map.find_key("keys", action).unwrap_or(1);
        let list = match v {
            toml::Value::String(s) => Some(vec![s.clone()]),
            toml::Value::Array(a) => a.iter().map(|k| k.as_str().map(str::to_owned)).collect(),
            _ => None,
        };
        match list {
            Some(keys) => out.push(KeyEntry {
                action: action.clone(),
                keys,
                line: at,
            }),
            None => errors.push(PresetError::Invalid {
                path: label.to_owned(),
                line: Some(at),
                key: Some(format!("keys.{action}")),
                message: "expected a key in quotes, a list of them, or \"none\"".to_owned(),
            }),
        }
    }
    (out, errors)
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
    /// Reads the user's config file (`--config FILE` when given, which must exist); no file is
    /// the defaults.
    ///
    /// # Errors
    /// An unreadable file, or every problem of an invalid one.
    pub fn load() -> Result<Self, Vec<PresetError>> {
        let (config, errors) = Self::load_all();
        if errors.is_empty() {
            Ok(config)
        } else {
            Err(errors)
        }
    }

    /// What [`Config::load`] reads, with what could be read of an invalid file (its `[keys]`,
    /// to check them too) beside every problem, in the order of the file's lines.
    #[must_use]
    pub fn load_all() -> (Self, Vec<PresetError>) {
        let file = match OVERRIDE.get() {
            Some(p) => p.clone(),
            None => match path() {
                Some(p) if p.exists() => p,
                _ => return (Self::default(), Vec::new()),
            },
        };
        let src = match PresetError::read(&file) {
            Ok(s) => s,
            Err(e) => return (Self::default(), vec![e]),
        };
        let (mut config, mut errors) = Self::parse_all(&src, &file.display().to_string());
        config.path = Some(file);
        errors.sort_by_key(|e| e.line().unwrap_or(0));
        (config, errors)
    }

    /// Reads the config file at `path`.
    ///
    /// # Errors
    /// An unreadable file, or every problem of an invalid one, each located.
    pub fn read(path: &Path) -> Result<Self, Vec<PresetError>> {
        let src = PresetError::read(path).map_err(|e| vec![e])?;
        let mut config = Self::parse(&src, &path.display().to_string())?;
        config.path = Some(path.to_path_buf());
        Ok(config)
    }

    /// Parses a config file's text; `label` names it in errors.
    ///
    /// # Errors
    /// Every problem, each located (a TOML syntax error is one problem: nothing after it can be
    /// read).
    pub fn parse(src: &str, label: &str) -> Result<Self, Vec<PresetError>> {
        let (c, errors) = Self::parse_all(src, label);
        if errors.is_empty() {
            Ok(c)
        } else {
            Err(errors)
        }
    }

    /// What can be read of a config file's text, and every problem.
    fn parse_all(src: &str, label: &str) -> (Self, Vec<PresetError>) {
        let map = SourceMap::new(src);
        let table = match map.parse_table(label) {
            Ok(t) => t,
            Err(e) => return (Self::default(), vec![e]),
        };
        let mut c = Self::default();
        let mut errors = Vec::new();
        for (key, value) in &table {
            let err = |message: String| PresetError::Invalid {
                path: label.to_owned(),
                line: Some(map.find_path(key).unwrap_or(1)),
                key: Some(key.clone()),
                message,
            };
            if key == "keys" {
                match value.as_table() {
                    Some(keys) => {
                        let (entries, bad) = key_entries(&map, label, keys);
                        c.keys = entries;
                        errors.extend(bad);
                    }
                    None => errors.push(err("expected a [keys] table".to_owned())),
                }
            } else if let Err(message) = c.set(key, value) {
                errors.push(err(message));
            }
        }
        (c, errors)
    }

    /// Sets one top-level key; `Err` says what is wrong and what is allowed.
    fn set(&mut self, key: &str, value: &toml::Value) -> Result<(), String> {
        let text = || {
            value
                .as_str()
                .map(str::to_owned)
                .ok_or_else(|| format!("expected text in quotes, found {value}"))
        };
        let flag = || {
            value
                .as_bool()
                .ok_or_else(|| format!("{value}: allowed true or false"))
        };
        match key {
            // Checked here, so a theme or preset that does not exist is said with its line,
            // in the same run as every other problem.
            "preset" => {
                let name = text()?;
                super::shipped::resolve(&name, &[]).map_err(|e| e.to_string())?;
                self.preset = Some(name);
            }
            "theme" => {
                let name = text()?;
                super::theme::theme(&name).map_err(|e| e.to_string())?;
                self.theme = Some(name);
            }
            "fps" => {
                let fps = value
                    .as_integer()
                    .filter(|n| (1..=240).contains(n))
                    .ok_or_else(|| format!("{value}: allowed a whole number from 1 to 240"))?;
                self.fps = Some(u32::try_from(fps).unwrap_or(30));
            }
            "marker" => {
                let m = text()?;
                if !MARKERS.contains(&m.as_str()) {
                    return Err(format!(
                        "unknown marker '{m}'; allowed: {}{}",
                        MARKERS.join(", "),
                        super::text::did_you_mean(&m, MARKERS)
                    ));
                }
                self.marker = Some(m);
            }
            "sessions" => self.sessions = Some(expand_home(&text()?)),
            "mouse" => self.mouse = flag()?,
            "ascii" => self.ascii = flag()?,
            other => {
                return Err(format!(
                    "unknown key `{other}`, expected one of {}{}",
                    KEYS.map(|k| format!("`{k}`")).join(", "),
                    super::text::did_you_mean(other, KEYS)
                ));
            }
        }
        Ok(())
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

        let one = |src: &str| {
            let mut e = Config::parse(src, "c.toml").unwrap_err();
            assert_eq!(e.len(), 1, "{e:?}");
            e.remove(0)
        };
        let e = one("fps = 30\n\nmarkr = \"dot\"\n");
        assert_eq!(e.line(), Some(3));
        assert!(e.to_string().contains("did you mean `marker`?"), "{e}");
        let e = one("fps = 0\n");
        assert!(
            e.to_string()
                .contains("c.toml:1: fps: 0: allowed a whole number from 1 to 240"),
            "{e}"
        );
        let e = one("marker = \"brail\"\n");
        assert!(e.to_string().contains("did you mean `braille`?"), "{e}");
        // Every problem, not the first.
        let all = Config::parse("fps = 0\nmarkr = 1\nmouse = 3\n", "c.toml").unwrap_err();
        assert_eq!(all.len(), 3, "{all:?}");
        let e = one("[keys]\n\nzoom_in = 3\n");
        assert_eq!(e.line(), Some(3));
        assert_eq!(e.key(), Some("keys.zoom_in"));
    }
}
