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
    /// No file at that path and no preset (theme, lesson) of that name.
    #[error("no {noun} named or at '{name}'; available: {available}{}", crate::scenario::text::did_you_mean(name, available.split(", ")))]
    NotFound {
        /// What was looked for: `preset`, `theme` or `lesson`.
        noun: &'static str,
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
    /// Every problem of one file, one a line, as `check` lists them (issue 68: `simulate`
    /// said only the first).
    #[error("{}", crate::scenario::text::bounded(&.0.iter().map(ToString::to_string).collect::<Vec<_>>()).join("\n"))]
    Several(Vec<PresetError>),
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
            write!(f, "{}: ", counted(&clean(key)))?;
        }
        write!(f, "{}", clean(self.3))
    }
}

/// A lesson's key as a person counts its steps: `step.3.until.parameter` is `step 4,
/// until.parameter` (issue 81, L7: the file's 0-based index stood beside the explorer's
/// "step 4"); any other key as it is.
fn counted(key: &str) -> String {
    let Some(rest) = key.strip_prefix("step.") else {
        return key.to_owned();
    };
    let (index, tail) = rest
        .split_once('.')
        .map_or((rest, None), |(i, t)| (i, Some(t)));
    match index.parse::<usize>() {
        Ok(i) => match tail {
            Some(t) => format!("step {}, {t}", i + 1),
            None => format!("step {}", i + 1),
        },
        Err(_) => key.to_owned(),
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
                path: super::write::label(path),
                source,
            })?;
        String::from_utf8(bytes).map_err(|e| {
            let bytes = e.as_bytes();
            let at = e.utf8_error().valid_up_to();
            let line = super::text::line_at(bytes, at);
            let column = at - bytes[..at].iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1) + 1;
            Self::Invalid {
                path: super::write::label(path),
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
            Self::Several(all) => return all.first().map(Self::file_name).unwrap_or_default(),
            Self::NotFound { .. } => "",
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
            Self::Several(all) => all.first().and_then(Self::key),
            _ => None,
        }
    }

    /// The 1-based line the error points at, if any.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        match self {
            Self::Invalid { line, .. } => *line,
            Self::Several(all) => all.first().and_then(Self::line),
            _ => None,
        }
    }
}

/// Where things are in a TOML source: lines, section headers and keys, from the spans the
/// `toml` parser gives every key (so a comment after a header, an inline table, a dotted key or
/// a quoted key all point at their own line).
pub(crate) struct SourceMap<'a> {
    src: &'a str,
    /// Dotted path → byte offset of the key's first mention, e.g. `"body.ix" → 42`.
    keys: std::collections::HashMap<String, usize>,
    /// Byte offset of every newline, in order: a line is found by bisection, so a file of a
    /// hundred thousand keys is located in linear time, not quadratic (issue 56).
    newlines: Vec<usize>,
}

impl<'a> SourceMap<'a> {
    pub(crate) fn new(src: &'a str) -> Self {
        let mut found = Vec::new();
        if let Ok(table) = toml::de::DeTable::parse(src) {
            index(table.get_ref(), "", &mut found);
        }
        let mut keys = std::collections::HashMap::with_capacity(found.len());
        for (path, at) in found {
            keys.entry(path).or_insert(at);
        }
        let newlines = src
            .bytes()
            .enumerate()
            .filter(|&(_, b)| b == b'\n')
            .map(|(i, _)| i)
            .collect();
        Self {
            src,
            keys,
            newlines,
        }
    }

    /// 1-based line of a byte offset.
    pub(crate) fn line_of(&self, offset: usize) -> usize {
        let end = offset.min(self.src.len());
        self.newlines.partition_point(|&n| n < end) + 1
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

    /// The line where the dotted `path` (`fps`, `keys.zoom_in`) is written.
    pub(crate) fn find_path(&self, path: &str) -> Option<usize> {
        self.find(path)
    }

    fn find(&self, path: &str) -> Option<usize> {
        self.keys.get(path).map(|at| self.line_of(*at))
    }

    /// The line where `[section]` (or the first key under it) is written.
    pub(crate) fn find_section(&self, section: &str) -> Option<usize> {
        self.find(section)
    }

    /// The line where `key` of `[section]` is set, however it is written.
    pub(crate) fn find_key(&self, section: &str, key: &str) -> Option<usize> {
        self.find(&format!("{section}.{key}"))
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

/// Every key of `table` under `prefix`, with where it is first written.
fn index(table: &toml::de::DeTable<'_>, prefix: &str, out: &mut Vec<(String, usize)>) {
    for (key, value) in table {
        let path = if prefix.is_empty() {
            key.get_ref().to_string()
        } else {
            format!("{prefix}.{}", key.get_ref())
        };
        out.push((path.clone(), key.span().start));
        match value.get_ref() {
            toml::de::DeValue::Table(inner) => index(inner, &path, out),
            // `[[step]]`: each table is `step.0`, `step.1`… from its own header.
            toml::de::DeValue::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    if let toml::de::DeValue::Table(inner) = item.get_ref() {
                        out.push((format!("{path}.{i}"), item.span().start));
                        index(inner, &format!("{path}.{i}"), out);
                    }
                }
            }
            _ => {}
        }
    }
}
