//! Writing and reading session files.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use super::{FORMAT, Header, Line, RecordError, VERSION};
use crate::app::journal::Event;

/// Writes a session as it goes, one flushed line per event.
pub struct Recorder {
    out: Sink,
    path: String,
    /// The chain value of the last line written.
    chain: String,
    /// Lines written, the header included.
    lines: usize,
    /// Signs the end line, when the lecturer asked.
    signer: Option<super::sign::Signer>,
    /// The header's format version: lines are written by its rules (older versions only to
    /// write an old file again, in the tests).
    version: u32,
}

impl Recorder {
    /// Creates the file (never replacing an existing one) and writes the header.
    ///
    /// # Errors
    /// The file exists or cannot be written.
    pub fn create(
        path: &Path,
        header: &Header,
        signer: Option<super::sign::Signer>,
    ) -> Result<Self, RecordError> {
        let label = path.display().to_string();
        let file = File::options()
            .write(true)
            .create_new(true)
            .open(path)
            .map_err(|source| {
                if source.kind() == std::io::ErrorKind::AlreadyExists {
                    RecordError::Exists(label.clone())
                } else {
                    RecordError::Io {
                        path: label.clone(),
                        source,
                    }
                }
            })?;
        Self::around(Sink::File(BufWriter::new(file)), label, header, signer)
    }

    /// A recording kept in memory under the name `name` (the browser's: the page downloads
    /// [`Recorder::bytes`]), its header written.
    ///
    /// # Errors
    /// Never in practice (the header serializes).
    pub fn in_memory(name: &str, header: &Header) -> Result<Self, RecordError> {
        Self::around(Sink::Memory(Vec::new()), name.to_owned(), header, None)
    }

    fn around(
        out: Sink,
        path: String,
        header: &Header,
        signer: Option<super::sign::Signer>,
    ) -> Result<Self, RecordError> {
        let mut me = Self {
            out,
            path,
            chain: String::new(),
            lines: 0,
            signer,
            version: header.version,
        };
        let text = me.to_json(header)?;
        me.write_text(&text)?;
        me.chain = text;
        Ok(me)
    }

    /// What a recording in memory holds so far; `None` for a file.
    #[must_use]
    pub fn bytes(&self) -> Option<&[u8]> {
        match &self.out {
            Sink::File(_) => None,
            Sink::Memory(bytes) => Some(bytes),
        }
    }

    fn to_json<T: serde::Serialize>(&self, value: &T) -> Result<String, RecordError> {
        serde_json::to_string(value).map_err(|e| RecordError::Io {
            path: self.path.clone(),
            source: std::io::Error::other(e),
        })
    }

    /// Writes one line and flushes it.
    fn write_text(&mut self, text: &str) -> Result<(), RecordError> {
        let io = |source| RecordError::Io {
            path: self.path.clone(),
            source,
        };
        self.out.write_all(text.as_bytes()).map_err(io)?;
        self.out.write_all(b"\n").map_err(io)?;
        self.out.flush().map_err(io)?;
        self.lines += 1;
        Ok(())
    }

    /// Appends one event and flushes it: its exact bytes, then its chain value (SHA-256 of the
    /// previous value and those bytes) as the last field. An end line gets the count of the
    /// lines before it and, with a key, the signature.
    ///
    /// # Errors
    /// When the file cannot be written.
    pub fn write(&mut self, line: &Line) -> Result<(), RecordError> {
        let mut bare = Line {
            chain: None,
            ..line.clone()
        };
        if self.version < 4 {
            let text = self.to_json(&bare)?;
            let chain = super::chain_after(&self.chain, &text);
            let text = self.to_json(&Line {
                chain: Some(chain.clone()),
                ..bare
            })?;
            self.write_text(&text)?;
            self.chain = chain;
            return Ok(());
        }
        if let Event::End { .. } = bare.event {
            bare.event = self.end_event();
        }
        let text = self.to_json(&bare)?;
        let chain = super::chain_sha256(&self.chain, &text);
        let body = text.strip_suffix('}').unwrap_or(&text);
        self.write_text(&format!("{body},\"chain\":\"{chain}\"}}"))?;
        self.chain = chain;
        Ok(())
    }

    /// The end line of this file: the count, and the signature when there is a signer.
    fn end_event(&self) -> Event {
        let lines = self.lines;
        let Some(signer) = &self.signer else {
            return Event::End {
                lines: Some(lines),
                signer: None,
                public_key: None,
                signature: None,
            };
        };
        let public = signer.public().hex();
        let message = super::sign::message(&self.chain, lines, &signer.name, &public);
        Event::End {
            lines: Some(lines),
            signer: Some(signer.name.clone()),
            signature: Some(signer.sign(&message)),
            public_key: Some(public),
        }
    }

    /// The file being written.
    #[must_use]
    pub fn path(&self) -> &str {
        &self.path
    }
}

/// Where a recording's lines go.
enum Sink {
    /// A file, each line flushed.
    File(BufWriter<File>),
    /// Memory (the browser's recording).
    Memory(Vec<u8>),
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Self::File(f) => f.write(buf),
            Self::Memory(m) => m.write(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Self::File(f) => f.flush(),
            Self::Memory(_) => Ok(()),
        }
    }
}

/// A session read back.
#[derive(Clone, Debug, PartialEq)]
pub struct Recording {
    /// Its header.
    pub header: Header,
    /// The header line as written (the start of the hash chain).
    pub header_text: String,
    /// `(1-based line number, event)`.
    pub lines: Vec<(usize, Line)>,
    /// The exact text of each of `lines` (what format 4's chain covers).
    pub raw: Vec<String>,
    /// Things tolerated, such as a truncated last line.
    pub warnings: Vec<String>,
}

/// Reads a session file. A truncated last line (no final newline, not valid JSON) is ignored
/// with a warning; any other bad line is an error naming its line.
///
/// # Errors
/// An unreadable file, a bad header, a version or format mismatch, or a corrupt line.
pub fn read(path: &Path) -> Result<Recording, RecordError> {
    read_with(path, crate::scenario::write::Links::Follow)
}

/// Largest session file read (an hour of lectures is a few megabytes).
pub const MAX_SESSION_BYTES: u64 = 256 << 20;

/// [`read`], a link at `path` followed or refused as `links` says (`serve` refuses them).
///
/// # Errors
/// As [`read`].
pub fn read_with(
    path: &Path,
    links: crate::scenario::write::Links,
) -> Result<Recording, RecordError> {
    let label = crate::scenario::write::label(path);
    let bytes = crate::scenario::write::read_bounded_bytes_with(path, MAX_SESSION_BYTES, links)
        .map_err(|source| RecordError::Io {
            path: label.clone(),
            source,
        })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        RecordError::Corrupt {
            path: label.clone(),
            line: crate::scenario::text::line_at(e.as_bytes(), at),
            message: "not valid UTF-8; a session file is UTF-8 JSON lines".to_owned(),
        }
    })?;
    parse(&text, &label)
}

/// A session from its text, named `label` in errors (the browser's fork reads the served
/// lecture's lines so).
///
/// # Errors
/// As [`read`], but for reading.
pub fn parse(text: &str, label: &str) -> Result<Recording, RecordError> {
    if text.len() > MAX_SESSION_BYTES as usize {
        return Err(RecordError::Corrupt {
            path: label.to_owned(),
            line: 1,
            message: format!("over {MAX_SESSION_BYTES} bytes"),
        });
    }
    let corrupt = |line: usize, message: String| RecordError::Corrupt {
        path: label.to_owned(),
        line,
        message,
    };
    // A byte-order mark (some editors write one) is not part of the header, as for presets.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut rows = text.split_inclusive('\n').enumerate();
    let Some((_, first)) = rows.next() else {
        return Err(corrupt(
            1,
            "empty file: expected a session header".to_owned(),
        ));
    };
    let probe: serde_json::Value = serde_json::from_str(first)
        .map_err(|e| corrupt(1, format!("not a session header: {e}")))?;
    if probe.get("format").and_then(|f| f.as_str()) != Some(FORMAT) {
        return Err(corrupt(
            1,
            format!("not a rattleback session (format must be \"{FORMAT}\")"),
        ));
    }
    if let Some(v) = probe.get("version").and_then(serde_json::Value::as_u64)
        && !(1..=u64::from(VERSION)).contains(&v)
    {
        return Err(corrupt(
            1,
            format!(
                "format version {v} is not supported; this build reads versions 1 to {VERSION}"
            ),
        ));
    }
    let header: Header =
        serde_json::from_value(probe).map_err(|e| corrupt(1, format!("bad header: {e}")))?;
    let mut sense = super::Sense::of_header(&header).map_err(|e| corrupt(1, e.to_string()))?;
    let mut lines = Vec::new();
    let mut raw = Vec::new();
    let mut warnings = Vec::new();
    for (i, row) in rows {
        let number = i + 1;
        if row.trim().is_empty() {
            continue;
        }
        match serde_json::from_str::<Line>(row) {
            Ok(line) => {
                if let Some(why) = sense.line(&line) {
                    return Err(corrupt(number, why));
                }
                lines.push((number, line));
                raw.push(row.trim_end_matches(['\n', '\r']).to_owned());
            }
            Err(e) if !row.ends_with('\n') => {
                warnings.push(format!(
                    "{label}:{number}: truncated last line ignored ({e})"
                ));
            }
            Err(e) => return Err(corrupt(number, format!("bad event: {e}"))),
        }
    }
    Ok(Recording {
        header,
        header_text: first.trim_end_matches(['\n', '\r']).to_owned(),
        lines,
        raw,
        warnings,
    })
}
