//! Errors of preset files, located by file, line and key.

use std::fmt;

/// A preset that cannot be used, with where and why.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PresetError {
    /// The file could not be read.
    #[error("{path}: cannot read the file: {source}")]
    Unreadable {
        /// The file.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// No file at that path and no preset of that name.
    #[error("no preset named or at '{name}'; available: {available}")]
    NotFound {
        /// What was asked for.
        name: String,
        /// Names that exist.
        available: String,
    },
    /// The content is wrong: syntax, an unknown key, a wrong type, a missing or invalid value.
    #[error("{}", Located(.path, .line, .key, .message))]
    Invalid {
        /// The file (or `--set` for a command-line override).
        path: String,
        /// 1-based line, when the problem has one.
        line: Option<usize>,
        /// `section.key`, when the problem concerns one key.
        key: Option<String>,
        /// What is wrong and what is allowed.
        message: String,
    },
}

struct Located<'a>(
    &'a String,
    &'a Option<usize>,
    &'a Option<String>,
    &'a String,
);

impl fmt::Display for Located<'_> {
    /// Paths, keys and messages may echo what a file holds: control characters are stripped
    /// here, at the source, as well as at every terminal.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let clean = crate::scenario::text::clean;
        write!(f, "{}", clean(self.0))?;
        if let Some(line) = self.1 {
            write!(f, ":{line}")?;
        }
        write!(f, ": ")?;
        if let Some(key) = self.2 {
            write!(f, "{}: ", clean(key))?;
        }
        write!(f, "{}", clean(self.3))
    }
}

impl PresetError {
    /// Reads a preset, theme or lesson file: a regular file of bounded size, else
    /// [`PresetError::Unreadable`] naming it.
    ///
    /// # Errors
    /// Not a regular file, too large, or unreadable.
    pub fn read(path: &std::path::Path) -> Result<String, Self> {
        let bytes = super::write::read_bounded_bytes(path, super::write::MAX_CONFIG_BYTES)
            .map_err(|source| Self::Unreadable {
                path: path.display().to_string(),
                source,
            })?;
        String::from_utf8(bytes).map_err(|e| {
            let bytes = e.as_bytes();
            let at = e.utf8_error().valid_up_to();
            let line = super::text::line_at(bytes, at);
            let column = at - bytes[..at].iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1) + 1;
            Self::Invalid {
                path: path.display().to_string(),
                line: Some(line),
                key: None,
                message: format!(
                    "not valid UTF-8 (byte {column} of the line); presets, themes and lessons are UTF-8 text"
                ),
            }
        })
    }

    /// The file's name without folder and `.toml` (how the picker lists it).
    #[must_use]
    pub fn file_name(&self) -> String {
        let path = match self {
            Self::Unreadable { path, .. } | Self::Invalid { path, .. } => path.as_str(),
            _ => "",
        };
        let name = std::path::Path::new(path)
            .file_stem()
            .map_or_else(|| path.to_owned(), |s| s.to_string_lossy().into_owned());
        crate::scenario::text::clean(&name)
    }

    /// The `section.key` the error concerns, if any.
    #[must_use]
    pub fn key(&self) -> Option<&str> {
        match self {
            Self::Invalid { key, .. } => key.as_deref(),
            _ => None,
        }
    }

    /// The 1-based line the error points at, if any.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        match self {
            Self::Invalid { line, .. } => *line,
            _ => None,
        }
    }
}

/// Where things are in a TOML source: lines, section headers and keys.
pub(crate) struct SourceMap<'a> {
    src: &'a str,
}

impl<'a> SourceMap<'a> {
    pub(crate) fn new(src: &'a str) -> Self {
        Self { src }
    }

    /// 1-based line of a byte offset.
    pub(crate) fn line_of(&self, offset: usize) -> usize {
        let end = offset.min(self.src.len());
        self.src[..end].bytes().filter(|&b| b == b'\n').count() + 1
    }

    /// Parses the text as a TOML table; a syntax error becomes a located problem.
    pub(crate) fn parse_table(&self, label: &str) -> Result<toml::Table, PresetError> {
        self.src
            .parse()
            .map_err(|e: toml::de::Error| PresetError::Invalid {
                path: label.to_owned(),
                line: e.span().map(|s| self.line_of(s.start)),
                key: None,
                message: e.message().trim().to_owned(),
            })
    }

    /// The line of the `[section]` header.
    pub(crate) fn find_section(&self, section: &str) -> Option<usize> {
        self.src
            .lines()
            .position(|l| {
                let t = l.trim();
                t.starts_with('[') && t.trim_matches(|c| c == '[' || c == ']').trim() == section
            })
            .map(|i| i + 1)
    }

    /// The line where `key` is set inside `[section]`: `key = …`, a dotted `key.sub = …`, a
    /// `[section.key]` header, or `section.key = …` at the top.
    pub(crate) fn find_key(&self, section: &str, key: &str) -> Option<usize> {
        let mut current = String::new();
        let first = |k: &str| {
            k.split('.')
                .next()
                .unwrap_or("")
                .trim()
                .trim_matches(|c| c == '"' || c == '\'')
                .to_owned()
        };
        let dotted = format!("{section}.{key}");
        for (i, l) in self.src.lines().enumerate() {
            let t = l.trim();
            if t.starts_with('[') && t.ends_with(']') {
                let header = t.trim_matches(|c| c == '[' || c == ']').trim();
                if header == dotted || header.starts_with(&format!("{dotted}.")) {
                    return Some(i + 1);
                }
                header.clone_into(&mut current);
            } else if let Some((k, _)) = t.split_once('=') {
                let k = k.trim();
                let here = current == section && first(k) == key;
                let top = current.is_empty()
                    && k.replace(['"', '\'', ' '], "")
                        .strip_prefix(&dotted)
                        .is_some_and(|rest| rest.is_empty() || rest.starts_with('.'));
                if here || top {
                    return Some(i + 1);
                }
            }
        }
        None
    }

    /// The best line for a problem with `key` of `section` (`key` empty: the section itself):
    /// where it is set; else the section's header (a missing key belongs there); else the last
    /// line (a missing section is added at the end). Every schema error gets a line.
    pub(crate) fn locate(&self, section: &str, key: &str) -> usize {
        (!key.is_empty())
            .then(|| self.find_key(section, key))
            .flatten()
            .or_else(|| self.find_section(section))
            .unwrap_or_else(|| self.src.lines().count().max(1))
    }
}
