//! Themes: the colours of the interface, from TOML (`[theme]` name and description, `[colors]`
//! by role). A colour is an ANSI name (`red`, `dark_gray`, `light_blue`, `default`, …) or
//! `#rrggbb`. No terminal types here: the UI maps [`Colour`] to its own.

use serde::Serialize;
use toml::Value;

use super::error::{PresetError, SourceMap};
use super::shipped::config_dir;

/// A colour as written in a theme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Colour {
    /// The terminal's own foreground.
    Default,
    /// One of the 16 ANSI colours, by index 0–15.
    Ansi(u8),
    /// One of the 256-colour palette's colours beyond the 16, by index 16–255.
    Indexed(u8),
    /// 24-bit colour.
    Rgb(u8, u8, u8),
}

impl Colour {
    /// A palette index 0–255: the ANSI colours below 16, the 256-colour palette above.
    #[must_use]
    pub fn index(i: u8) -> Self {
        if i < 16 {
            Self::Ansi(i)
        } else {
            Self::Indexed(i)
        }
    }
}

/// ANSI names, in index order; `grey` spellings are accepted too.
pub const ANSI_NAMES: [&str; 16] = [
    "black",
    "red",
    "green",
    "yellow",
    "blue",
    "magenta",
    "cyan",
    "gray",
    "dark_gray",
    "light_red",
    "light_green",
    "light_yellow",
    "light_blue",
    "light_magenta",
    "light_cyan",
    "white",
];

/// Why a text is not a colour (issue 83: typed; each says itself, with what is allowed).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ColourError {
    /// `#` and not six or three hex digits.
    #[error("'{0}' is not a colour: hex colours are #rrggbb or #rgb")]
    Hex(String),
    /// A palette index over 255, written as text.
    #[error("'{0}' is not a colour: a palette index is a whole number from 0 to 255")]
    Index(String),
    /// A bare palette index (a TOML integer) out of 0 to 255.
    #[error("{0} is not a colour: a palette index is a whole number from 0 to 255")]
    BareIndex(i64),
    /// No colour of that name.
    #[error(
        "unknown colour '{text}'; allowed: {}, default, a palette index 0–255, or #rrggbb{hint}",
        ANSI_NAMES.join(", ")
    )]
    Name {
        /// As written.
        text: String,
        /// A near name, if any (`did_you_mean`).
        hint: String,
    },
}

impl std::str::FromStr for Colour {
    type Err = ColourError;
    fn from_str(s: &str) -> Result<Self, ColourError> {
        let t = s
            .trim()
            .to_ascii_lowercase()
            .replace(['-', ' '], "_")
            .replace("grey", "gray");
        if t == "default" || t == "reset" {
            return Ok(Self::Default);
        }
        if let Some(hex) = t.strip_prefix('#') {
            let digits = |h: &str| h.chars().all(|c| c.is_ascii_hexdigit());
            if hex.len() == 6
                && digits(hex)
                && let Ok(v) = u32::from_str_radix(hex, 16)
            {
                let [_, r, g, b] = v.to_be_bytes();
                return Ok(Self::Rgb(r, g, b));
            }
            if hex.len() == 3 && digits(hex) {
                // #rgb is #rrggbb with each digit doubled, as in CSS.
                let d = |i: usize| u8::from_str_radix(&hex[i..=i], 16).unwrap_or(0) * 17;
                return Ok(Self::Rgb(d(0), d(1), d(2)));
            }
            return Err(ColourError::Hex(s.to_owned()));
        }
        if !t.is_empty() && t.chars().all(|c| c.is_ascii_digit()) {
            return t
                .parse::<u8>()
                .map(Self::index)
                .map_err(|_| ColourError::Index(s.to_owned()));
        }
        ANSI_NAMES
            .iter()
            .position(|n| *n == t)
            .map(|i| Self::Ansi(u8::try_from(i).unwrap_or(0)))
            .ok_or_else(|| ColourError::Name {
                text: s.to_owned(),
                hint: super::text::did_you_mean(&t, ANSI_NAMES),
            })
    }
}

/// A colour as a TOML value: text (a name, `#rrggbb`, `#rgb`, an index) or a bare palette
/// index (`trail = 114`); `None` for any other type.
fn colour_value(v: &toml::Value) -> Option<Result<Colour, ColourError>> {
    match v {
        toml::Value::String(text) => Some(text.parse::<Colour>()),
        toml::Value::Integer(n) => Some(
            u8::try_from(*n)
                .map(Colour::index)
                .map_err(|_| ColourError::BareIndex(*n)),
        ),
        _ => None,
    }
}

/// The roles a theme colours. Names are a contract: add, never rename. Roles from
/// [`FIRST_OPTIONAL`] on may be left out (they default to the terminal's own colours), so
/// adding a role never breaks a user's theme file.
pub const ROLES: [&str; 11] = [
    "contour",
    "separatrix",
    "start_level",
    "trail",
    "effective",
    "current",
    "reversal",
    "error",
    "dim",
    "background",
    "text",
];

/// Index of the first role a theme may leave out.
pub const FIRST_OPTIONAL: usize = 9;

/// A validated theme.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThemeSpec {
    /// Display name.
    pub name: String,
    /// When to use it.
    pub description: String,
    /// Colour of each role, in [`ROLES`] order.
    pub colours: [Colour; 11],
}

impl ThemeSpec {
    /// The colour of a role from [`ROLES`].
    ///
    /// # Panics
    /// On a role name not in [`ROLES`] (a programming error).
    #[must_use]
    pub fn colour(&self, role: &str) -> Colour {
        let i = ROLES.iter().position(|r| *r == role).expect("known role");
        self.colours[i]
    }

    /// Parses and validates a theme; `label` names it in errors.
    ///
    /// # Errors
    /// Every problem, each with file, line and key.
    pub fn parse(src: &str, label: &str, fallback_name: &str) -> Result<Self, Vec<PresetError>> {
        let map = SourceMap::new(src);
        let table = map.parse_table(label).map_err(|e| vec![e])?;
        let mut problems = Vec::new();
        let mut problem = |section: &str, key: &str, message: String| {
            problems.push(PresetError::Invalid {
                path: label.to_owned(),
                line: Some(map.locate(section, key)),
                key: Some(if key.is_empty() {
                    section.to_owned()
                } else {
                    format!("{section}.{key}")
                }),
                message,
            });
        };
        let mut name = fallback_name.to_owned();
        let mut description = String::new();
        let mut colours = [Colour::Default; 11];
        let mut seen = [false; 11];
        for (section, value) in &table {
            let Some(t) = value.as_table() else {
                problem(section, "", format!("`{section}` must be a table"));
                continue;
            };
            match section.as_str() {
                "theme" => {
                    for (k, v) in t {
                        match (k.as_str(), v) {
                            ("name", Value::String(s)) => name.clone_from(s),
                            ("description", Value::String(s)) => description.clone_from(s),
                            ("name" | "description", _) => {
                                problem(section, k, "expected text in quotes".to_owned());
                            }
                            _ => problem(
                                section,
                                k,
                                format!(
                                    "unknown key `{k}`, expected one of `name`, `description`{}",
                                    super::text::did_you_mean(k, ["name", "description"])
                                ),
                            ),
                        }
                    }
                }
                "colors" => {
                    for (k, v) in t {
                        let Some(i) = ROLES.iter().position(|r| r == k) else {
                            let allowed = ROLES.map(|r| format!("`{r}`")).join(", ");
                            problem(
                                section,
                                k,
                                format!(
                                    "unknown key `{k}`, expected one of {allowed}{}",
                                    super::text::did_you_mean(k, ROLES)
                                ),
                            );
                            continue;
                        };
                        // Present, even if invalid: reported once, as invalid, not also missing.
                        seen[i] = true;
                        let parsed = colour_value(v);
                        match parsed {
                            Some(Ok(c)) => colours[i] = c,
                            Some(Err(e)) => problem(section, k, e.to_string()),
                            None => problem(
                                section,
                                k,
                                "expected a colour name, \"#rrggbb\" in quotes, or a palette index 0–255".to_owned(),
                            ),
                        }
                    }
                }
                other => problem(
                    other,
                    "",
                    format!(
                        "unknown section `{other}`, expected `theme` or `colors`{}",
                        super::text::did_you_mean(other, ["theme", "colors"])
                    ),
                ),
            }
        }
        for (i, role) in ROLES.iter().enumerate().take(FIRST_OPTIONAL) {
            if !seen[i] {
                problem("colors", role, "missing colour".to_owned());
            }
        }
        if problems.is_empty() {
            Ok(Self {
                name,
                description,
                colours,
            })
        } else {
            Err(problems)
        }
    }
}

/// `(name, TOML text)` of the shipped themes; the first is the default.
pub const SHIPPED_THEMES: &[(&str, &str)] = &[
    ("default", include_str!("../../themes/default.toml")),
    ("dark", include_str!("../../themes/dark.toml")),
    ("light", include_str!("../../themes/light.toml")),
    (
        "high-contrast",
        include_str!("../../themes/high-contrast.toml"),
    ),
];

/// Every theme, shipped then the user's (`<config>/themes/*.toml`; same name replaces), with
/// the problems of invalid user files.
#[must_use]
pub fn themes() -> (Vec<(String, ThemeSpec)>, Vec<PresetError>) {
    let mut out: Vec<(String, ThemeSpec)> = Vec::new();
    let mut problems = Vec::new();
    for (name, src) in SHIPPED_THEMES {
        match ThemeSpec::parse(src, &format!("themes/{name}.toml (shipped)"), name) {
            Ok(t) => out.push(((*name).to_owned(), t)),
            Err(mut e) => problems.append(&mut e),
        }
    }
    if let Some(dir) = config_dir().map(|d| d.join("themes")) {
        let (files, mut odd) = super::shipped::toml_files_and_unnameable(&dir);
        problems.append(&mut odd);
        for path in files {
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let label = path.display().to_string();
            match PresetError::read(&path) {
                Ok(src) => match ThemeSpec::parse(&src, &label, &stem) {
                    Ok(t) => {
                        out.retain(|(n, _)| *n != stem);
                        out.push((stem, t));
                    }
                    Err(mut e) => problems.append(&mut e),
                },
                Err(e) => problems.push(e),
            }
        }
    }
    (out, problems)
}

/// The theme called `name` (a path, a user theme or a shipped one).
///
/// # Errors
/// An unknown name or an invalid file (its first problem).
pub fn theme(name: &str) -> Result<ThemeSpec, PresetError> {
    theme_with_text(name).map(|(t, _)| t)
}

/// The text of the theme `name` (a file, a user theme, or a shipped one), to copy and edit
/// (`rattleback themes show NAME`, issue 81).
///
/// # Errors
/// As [`theme`].
pub fn source_text(name: &str) -> Result<String, PresetError> {
    theme_with_text(name).map(|(_, text)| text)
}

/// [`theme`] and its file's text.
fn theme_with_text(name: &str) -> Result<(ThemeSpec, String), PresetError> {
    let path = std::path::Path::new(name);
    if path.exists() && !path.is_dir() {
        let label = path.display().to_string();
        let src = PresetError::read(path)?;
        let spec = ThemeSpec::parse(&src, &label, name).map_err(|mut e| e.swap_remove(0))?;
        return Ok((spec, src));
    }
    let (all, mut problems) = themes();
    if let Some((_, t)) = all.into_iter().find(|(n, _)| n == name) {
        let user = crate::scenario::shipped::config_dir()
            .map(|d| d.join("themes").join(format!("{name}.toml")))
            .filter(|p| p.is_file());
        let text = match user {
            Some(p) => PresetError::read(&p)?,
            None => SHIPPED_THEMES
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, src)| (*src).to_owned())
                .unwrap_or_default(),
        };
        return Ok((t, text));
    }
    if !problems.is_empty() {
        return Err(problems.swap_remove(0));
    }
    Err(PresetError::NotFound {
        noun: "theme",
        name: name.to_owned(),
        available: SHIPPED_THEMES
            .iter()
            .map(|(n, _)| *n)
            .collect::<Vec<_>>()
            .join(", "),
    })
}
