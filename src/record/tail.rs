//! Following a session file that is still being written (`rattleback follow FILE`): read-only,
//! it reads what was appended since the last look, keeps a partial last line until its newline
//! arrives, and notices a file that was truncated, replaced (another file at the path), removed
//! or finished (its `end` line arrives among the lines). Polled by a thread a few times a second;
//! nothing here blocks or writes.

use std::io::{Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use super::{Line, Recording};
use crate::app::journal::Event;
use crate::scenario::write::{Links, open_regular};

/// What a look at the file found.
#[derive(Debug)]
pub enum TailEvent {
    /// New complete lines.
    Lines(Vec<Line>),
    /// The file was truncated or replaced: here it is, read again from its start.
    Restarted {
        /// Why (for the status line).
        why: String,
        /// The file as it is now.
        recording: Box<Recording>,
    },
    /// The file cannot be read now (removed, or not a session yet); following goes on.
    Missing(String),
}

/// The identity of a file: device and inode (a replaced file has another).
fn identity(meta: &std::fs::Metadata) -> (u64, u64) {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        (meta.dev(), meta.ino())
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        (0, 0)
    }
}

/// A followed file.
pub struct Tail {
    path: PathBuf,
    /// Whether a link at the path is followed (`follow`) or refused (`serve`).
    links: Links,
    /// Bytes consumed (complete lines only).
    offset: u64,
    id: (u64, u64),
    /// Bytes of a line whose newline has not arrived.
    partial: Vec<u8>,
    /// The next line's 1-based number.
    line: usize,
    missing: bool,
    ended: bool,
    /// Dropping an over-long line until its newline.
    skipping: bool,
    /// What the file may say at this point (the scene so far).
    sense: super::Sense,
}

/// Longest line kept (a session's lines are small: the largest holds a preset): a longer one,
/// or bytes with no newline, is skipped, so memory stays bounded whatever the writer does.
pub const MAX_LINE: usize = 1 << 20;
/// Most bytes read in one look (a file that grew by a gigabyte is read over many looks, at
/// bounded memory and CPU).
pub const READ_PER_POLL: u64 = 4 << 20;

impl Tail {
    /// Opens `path` and reads it whole; the tail then continues from its end.
    ///
    /// # Errors
    /// When the file cannot be read as a session.
    pub fn open(path: &Path) -> Result<(Self, Recording), super::RecordError> {
        Self::open_with(path, Links::Follow)
    }

    /// [`Tail::open`], a link at `path` followed or refused as `links` says: every later look
    /// opens the file the same way, only ever a regular file, never blocking (issue 80: a FIFO
    /// put at the path wedged `serve`).
    ///
    /// # Errors
    /// As [`Tail::open`].
    pub fn open_with(path: &Path, links: Links) -> Result<(Self, Recording), super::RecordError> {
        let recording = super::file::read_with(path, links)?;
        let io = |source| super::RecordError::Io {
            path: path.display().to_string(),
            source,
        };
        let mut file = open_regular(path, links).map_err(io)?;
        let meta = file.metadata().map_err(io)?;
        let complete = complete_prefix_of(&mut file, meta.len(), 0, 0);
        let ended = recording
            .lines
            .last()
            .is_some_and(|(_, l)| matches!(l.event, Event::End { .. }));
        // `read` has checked every line with the same validator: this only finds the scene.
        let mut sense = super::Sense::of_header(&recording.header).map_err(|e| {
            super::RecordError::Corrupt {
                path: path.display().to_string(),
                line: 1,
                message: e.to_string(),
            }
        })?;
        for (_, l) in &recording.lines {
            let _ = sense.line(l);
        }
        let tail = Self {
            path: path.to_path_buf(),
            links,
            offset: complete,
            id: identity(&meta),
            partial: Vec::new(),
            line: recording.lines.last().map_or(2, |(n, _)| n + 1),
            missing: false,
            ended,
            skipping: false,
            sense,
        };
        Ok((tail, recording))
    }

    /// Bytes held of a line whose newline has not arrived (at most [`MAX_LINE`] plus one look's
    /// [`READ_PER_POLL`]).
    #[must_use]
    pub fn held(&self) -> usize {
        self.partial.len()
    }

    /// Whether the recording has ended.
    #[must_use]
    pub fn ended(&self) -> bool {
        self.ended
    }

    /// Looks at the file once.
    pub fn poll(&mut self) -> Option<TailEvent> {
        let opened =
            open_regular(&self.path, self.links).and_then(|f| f.metadata().map(|m| (f, m)));
        let (mut file, meta) = match opened {
            Ok(x) => x,
            Err(e) => {
                if self.missing {
                    return None;
                }
                self.missing = true;
                return Some(TailEvent::Missing(format!(
                    "{}: {e}; waiting for it",
                    self.path.display()
                )));
            }
        };
        let replaced = identity(&meta) != self.id;
        let truncated = meta.len() < self.offset;
        if replaced || truncated || self.missing {
            let why = if self.missing {
                "the file is back"
            } else if replaced {
                "the file was replaced"
            } else {
                "the file was truncated"
            };
            return Some(match Self::open_with(&self.path, self.links) {
                Ok((tail, recording)) => {
                    *self = tail;
                    TailEvent::Restarted {
                        why: why.to_owned(),
                        recording: Box::new(recording),
                    }
                }
                Err(e) => {
                    self.missing = true;
                    TailEvent::Missing(e.to_string())
                }
            });
        }
        if meta.len() == self.offset + self.partial.len() as u64 {
            return None;
        }
        file.seek(SeekFrom::Start(self.offset + self.partial.len() as u64))
            .ok()?;
        let mut fresh = Vec::new();
        // At most what the metadata said (a writer racing ahead is read next time), and at most
        // a bounded amount per look.
        let want = (meta.len() - self.offset - self.partial.len() as u64).min(READ_PER_POLL);
        file.take(want).read_to_end(&mut fresh).ok()?;
        self.partial.extend_from_slice(&fresh);
        let mut lines = Vec::new();
        let mut skipped = false;
        while let Some(end) = self.partial.iter().position(|&b| b == b'\n') {
            let row: Vec<u8> = self.partial.drain(..=end).collect();
            self.offset += row.len() as u64;
            self.line += 1;
            if std::mem::take(&mut self.skipping) {
                continue;
            }
            let text = String::from_utf8_lossy(&row);
            if text.trim().is_empty() {
                continue;
            }
            // A corrupt line is skipped (a follower shows what it can); the lecturer's
            // `replay --verify` is what judges the file.
            // So is a line of an impossible time (`t = -5`, `wall = 1e300`): what `replay`
            // refuses, `follow` never shows (issue 56).
            if let Ok(line) = serde_json::from_str::<Line>(&text)
                && self.sense.line(&line).is_none()
            {
                self.ended |= matches!(line.event, Event::End { .. });
                lines.push(line);
            }
        }
        if self.partial.len() > MAX_LINE {
            // No newline in sight: drop what is held and skip to the next newline.
            self.offset += self.partial.len() as u64;
            self.partial.clear();
            skipped = !self.skipping;
            self.skipping = true;
        }
        if skipped && lines.is_empty() {
            return Some(TailEvent::Missing(format!(
                "{}: a line longer than {} MiB was skipped (not a session line)",
                self.path.display(),
                MAX_LINE >> 20
            )));
        }
        (!lines.is_empty()).then_some(TailEvent::Lines(lines))
    }
}

/// The length of the file's part made of complete lines (up to its last newline), read
/// backwards a bounded chunk at a time; only a regular file is read (never a FIFO).
#[must_use]
pub fn complete_prefix(path: &Path, len: u64) -> u64 {
    let Ok(mut file) = open_regular(path, Links::Follow) else {
        return len;
    };
    complete_prefix_of(&mut file, len, 0, 0)
}

/// The end of the last complete line of `file` among its first `len` bytes, knowing that its
/// first `scanned` bytes were looked at already and their last complete line ends at
/// `known_end`: only the bytes after `scanned` are read (issue 80, N6: a huge unfinished last
/// line was scanned again on every request). `known_end` is also what is said when the file
/// cannot be read.
pub fn complete_prefix_of<F: Read + Seek>(
    file: &mut F,
    len: u64,
    scanned: u64,
    known_end: u64,
) -> u64 {
    const CHUNK: u64 = 64 << 10;
    let mut end = len;
    let mut buf = Vec::new();
    while end > scanned {
        let start = end.saturating_sub(CHUNK).max(scanned);
        buf.clear();
        if file.seek(SeekFrom::Start(start)).is_err()
            || (&mut *file)
                .take(end - start)
                .read_to_end(&mut buf)
                .is_err()
        {
            return known_end.min(len);
        }
        if let Some(i) = buf.iter().rposition(|&b| b == b'\n') {
            return start + i as u64 + 1;
        }
        end = start;
    }
    known_end.min(len)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file that counts the bytes read from it.
    struct Counted(std::io::Cursor<Vec<u8>>, u64);

    impl Read for Counted {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let n = self.0.read(buf)?;
            self.1 += n as u64;
            Ok(n)
        }
    }

    impl Seek for Counted {
        fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
            self.0.seek(to)
        }
    }

    #[test]
    fn only_the_bytes_after_the_known_prefix_are_scanned() {
        // A session whose last line never ends (issue 80, N6): 3 MB without a newline.
        let mut bytes = b"{\"header\": 1}\n".to_vec();
        bytes.extend(std::iter::repeat_n(b'x', 3 << 20));
        let len = bytes.len() as u64;
        let mut f = Counted(std::io::Cursor::new(bytes.clone()), 0);
        let end = complete_prefix_of(&mut f, len, 0, 0);
        assert_eq!(end, 14);
        assert!(f.1 >= 3 << 20, "a first look reads it all");
        // Looked at up to `len`, its last line ending at 14: 100 more bytes, 100 read.
        bytes.extend([b'y'; 100]);
        let mut f = Counted(std::io::Cursor::new(bytes.clone()), 0);
        assert_eq!(complete_prefix_of(&mut f, len + 100, len, 14), 14);
        assert!(f.1 <= 100, "{} bytes read", f.1);
        // A newline among them ends a line there.
        bytes.extend(b"z\n");
        let mut f = Counted(std::io::Cursor::new(bytes), 0);
        assert_eq!(
            complete_prefix_of(&mut f, len + 102, len + 100, 14),
            len + 102
        );
    }

    #[test]
    fn the_complete_prefix_stops_at_the_last_newline() {
        let d = std::env::temp_dir().join(format!("rattleback-tail-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join("x.jsonl");
        std::fs::write(&p, b"a\nbb\ncc").unwrap();
        assert_eq!(complete_prefix(&p, 7), 5);
        let _ = std::fs::remove_dir_all(&d);
    }
}
