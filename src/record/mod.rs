//! Session recording, replay and export.
//!
//! A session file is JSON Lines: a [`Header`] (format, version, program version, the preset
//! inline, method and tolerance, terminal size, theme, frame rate), then one [`Line`] per
//! semantic event, stamped with the wall-clock offset (pacing) and the simulated time at which
//! it applies. Lines are flushed one by one, so a crash or a dropped connection loses at most
//! the last. Checkpoints hold the exact state at their time and a hash of its bits; because
//! trajectories do not depend on pacing, `replay --verify` re-runs the events headless and
//! compares them bit for bit.
//!
//! Format 2 adds `plan` lines: the concrete plan each run integrated (what `auto` resolved
//! to); replay integrates the recorded plan. Format 1 files, which have none, replay `auto`
//! as it was then (its first plan, unverified), so they keep verifying.
//!
//! Nothing here draws: the cast export, which renders, lives above both (`crate::cast`).

pub mod active;
mod file;
pub mod replayer;
pub mod sign;
pub mod tail;
mod verify;

pub use file::{Recorder, Recording, parse, read, read_with};
pub use verify::{Divergence, Report, VerifyError, plan_book, start, verify, verify_watched};

use serde::{Deserialize, Serialize};

use crate::app::journal::Event;

/// The `format` field of every session file.
pub const FORMAT: &str = "rattleback-session";
/// The format version this build writes (it reads 1 to this). 3: the header names its theme.
/// 4: a SHA-256 chain over every byte of every line, an end line with the count (and an optional
/// signature), checkpoints and events at the displayed time, `clock` and `screen` lines.
/// 5: `layout` lines (the panes as a list) and `partner` lines (the comparison), and a screen's
/// `crossings` (the celt's) and `compare` (the partner shown). 6: nothing new in the lines;
/// fixed-step runs add their steps to the time with a compensated sum
/// ([`crate::physics::method::TimeSum`]), so a file of 5 or older replays with the plain sum it
/// was recorded with. 7: `window` lines (the weak-* pane's averaging window). 8: nothing new
/// in the lines; the pendulum's lifts carry the fast phase
/// `t/ε` exactly ([`crate::physics::kapitza::FastPhase`]), so a file of 7 or older replays with
/// the rounded phase it was recorded with ([`crate::physics::method::Arithmetic::of_format`]).
/// 9: nothing new in the lines; a run longer than [`crate::sim::segments::FIRST_SEGMENT`] is
/// verified and shown in segments, each with its own `plan` line (its key's `t_end` is the
/// segment's horizon), so a file of 8 or older replays its runs in one piece, as shown.
/// 10: the lesson in the header, `given` and `lesson_done` lines, the last frame. 11: a `plan`
/// line names its key's model (`docs/session-format.md`), so no model's key reads as another's.
/// 14: `terminal` lines (a resize while recording) and numbers that are not finite written as
/// the strings `"inf"`, `"-inf"`, `"nan"` (`physics::json`), where 13 wrote `null` and failed
/// its own `--verify`. 15: nothing new in the lines; the runs take the portable elementary
/// functions (`physics::numerics::elementary`: the same bits natively and in the browser's
/// module), so a file of 14 or older replays with the platform's, as it was recorded.
pub const VERSION: u32 = 15;

/// The largest terminal side a session may say it had (columns or rows).
pub const MAX_TERMINAL: u16 = 1000;

/// First line of a session file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Header {
    /// Always `rattleback-session`.
    pub format: String,
    /// Format version.
    pub version: u32,
    /// Version of the program that wrote it.
    pub program: String,
    /// The scenario at the start of the recording, as preset TOML.
    pub preset: String,
    /// Method at the start.
    pub method: String,
    /// Tolerance at the start.
    pub tolerance: f64,
    /// Terminal size when recording.
    pub terminal: Size,
    /// The theme shown when recording: its name (format 3 on) or, in older files, its index
    /// in that machine's theme list.
    pub theme: ThemeRef,
    /// Frame-rate cap.
    pub fps: f64,
    /// The lesson being taught, when the recording is of one (format 10 on): a replay shows its
    /// pane as the lecturer saw it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lesson: Option<crate::scenario::lesson::RecordedLesson>,
}

/// How a header refers to its theme.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum ThemeRef {
    /// The theme's name (what `--theme` takes, or its title).
    Name(String),
    /// Formats 1 and 2: an index into the recording machine's list (not portable).
    Index(usize),
}

impl ThemeRef {
    /// The name, when the header has one.
    #[must_use]
    pub fn name(&self) -> Option<&str> {
        match self {
            Self::Name(n) => Some(n),
            Self::Index(_) => None,
        }
    }
}

/// Terminal size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Size {
    /// Columns.
    pub width: u16,
    /// Rows.
    pub height: u16,
}

/// One event line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Line {
    /// Seconds since the recording started.
    pub wall: f64,
    /// Simulated time at which it applies.
    pub t: f64,
    /// Run stamp in the recording explorer (informational).
    pub generation: u64,
    /// Format 2 on: FNV-1a of the previous line's chain (the header's text for the first) and
    /// of this line without its chain, in hex. `--verify` recomputes it, so an edit, a deleted
    /// or an inserted line anywhere is found and named, not only a changed checkpoint.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chain: Option<String>,
    /// What happened.
    #[serde(flatten)]
    pub event: Event,
}

/// Any line of a session file: the header (line 1) or an event line (the others). The JSON
/// Schema of this type is `docs/session.schema.json` (`cargo run --example session_schema`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
#[schemars(title = "rattleback session line")]
pub enum SessionLine {
    /// Line 1.
    Header(Header),
    /// Every other line.
    Event(Line),
}

/// The JSON Schema of a session file's lines, as pretty JSON.
#[must_use]
pub fn session_schema() -> String {
    let schema = schemars::schema_for!(SessionLine);
    let mut s = serde_json::to_string_pretty(&schema).unwrap_or_default();
    s.push('\n');
    s
}

/// One chapter of a recording (a chapter marker or a lesson step).
#[derive(Clone, Debug, PartialEq, serde::Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Chapter {
    /// 1-based, in the file's order.
    pub number: usize,
    /// Seconds of the recording's wall clock.
    pub wall: f64,
    /// Simulated time shown then.
    pub t: f64,
    /// The title, cleaned of control characters and on one line.
    pub title: String,
}

/// The chapters of a recording; lesson steps count as chapters too.
#[must_use]
pub fn chapter_list(rec: &Recording) -> Vec<Chapter> {
    let mut out = Vec::new();
    for (i, (_, line)) in rec.lines.iter().enumerate() {
        let title = match &line.event {
            Event::Chapter { title } => title.clone(),
            Event::LessonStep {
                lesson,
                step,
                steps,
                title,
                ..
            } => format!("{lesson}, step {}/{steps}: {title}", step + 1),
            _ => continue,
        };
        out.push(Chapter {
            number: out.len() + 1,
            wall: line.wall,
            t: step_start(rec, i),
            title: crate::scenario::text::clean(&title).replace(['\n', '\t'], " "),
        });
    }
    out
}

/// What an exported page and a cast call a recording: its lesson's title (issue 67: they named
/// the lesson's first preset), else `preset`'s name.
#[must_use]
pub fn title(rec: &Recording, preset: &str) -> String {
    let name = rec
        .header
        .lesson
        .as_ref()
        .map_or(preset, |l| l.title.as_str());
    format!("rattleback: {}", crate::scenario::text::one_line(name))
}

/// The simulated time a chapter starts at: its line's, but a lesson step's is its own run's
/// first (the step line is written at the previous step's last time; its preset and changes
/// then start a new run: issue 67, `--chapters` listed each step at the one before's end).
fn step_start(rec: &Recording, index: usize) -> f64 {
    let (_, line) = &rec.lines[index];
    if !matches!(line.event, Event::LessonStep { .. }) {
        return line.t;
    }
    rec.lines[index + 1..]
        .iter()
        .map(|(_, l)| l)
        .find(|l| {
            !matches!(
                l.event,
                Event::Preset { .. } | Event::Set { .. } | Event::Select { .. }
            )
        })
        .filter(|l| l.generation != line.generation)
        .map_or(line.t, |l| l.t)
}

/// Why a line's times cannot be (a wall clock outside `[0, MAX_WALL]`, a simulated time that
/// is not a finite number at or after 0), or `None`: one rule for `replay`, `--verify` and
/// `follow`.
#[must_use]
pub fn impossible(line: &Line) -> Option<String> {
    use crate::physics::Number;
    if !(line.wall.is_finite() && (0.0..=MAX_WALL).contains(&line.wall)) {
        return Some(format!(
            "wall = {}: allowed 0 to {MAX_WALL} s",
            Number(line.wall)
        ));
    }
    if !(line.t.is_finite() && line.t >= 0.0) {
        return Some(format!(
            "t = {}: not a time of the run (a finite number, at least 0)",
            Number(line.t)
        ));
    }
    if let crate::app::journal::Event::Plan {
        model: Some(model),
        key,
        ..
    } = &line.event
        && model != key.model().name()
    {
        return Some(format!(
            "a plan line for the model \"{}\" whose key is the {}'s",
            crate::scenario::text::one_line(model),
            key.model().name()
        ));
    }
    None
}

/// The chapter list of a recording, one line each: its number, the wall clock of the recording
/// (`m:ss.s`), the simulated time and the title (cleaned of control characters); lesson steps
/// count as chapters too.
#[must_use]
pub fn chapters(rec: &Recording) -> String {
    use std::fmt::Write as _;
    let list = chapter_list(rec);
    if list.is_empty() {
        return "no chapters".to_owned();
    }
    let mut out = String::new();
    for c in list {
        let minutes = (c.wall / 60.0).floor();
        let seconds = c.wall - 60.0 * minutes;
        let _ = writeln!(
            out,
            "{:>3}  {minutes:.0}:{seconds:04.1}  t {:>9.2}  {}",
            c.number, c.t, c.title
        );
    }
    out.trim_end().to_owned()
}

/// The chain value after `text` (see [`Line::chain`]).
#[must_use]
pub fn chain_after(previous: &str, text: &str) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in previous.bytes().chain([b'\n']).chain(text.bytes()) {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// The format-4 chain value after the line whose exact bytes are `text` (before its chain
/// field): SHA-256 of the previous value, a newline and the text, in hex.
#[must_use]
pub fn chain_sha256(previous: &str, text: &str) -> String {
    use sha2::Digest as _;
    let mut h = sha2::Sha256::new();
    h.update(previous.as_bytes());
    h.update(b"\n");
    h.update(text.as_bytes());
    hex::encode(h.finalize())
}

/// What is wrong with a session file's header (issue 83: typed; each says itself to a person).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HeaderError {
    /// A terminal size out of bounds.
    #[error("terminal {width}x{height}: allowed sizes are 1 to 1000 columns and rows")]
    Terminal {
        /// Columns.
        width: u16,
        /// Rows.
        height: u16,
    },
    /// A frame rate out of bounds.
    #[error("fps {0}: allowed 1 to 240")]
    Fps(f64),
    /// A tolerance that is not a finite number > 0.
    #[error("tolerance {0}: must be a finite number > 0")]
    Tolerance(f64),
    /// A lesson in a header older than format 10.
    #[error("a lesson in the header (format 10)")]
    LessonBeforeFormat10,
    /// A lesson's description in a header older than format 13.
    #[error("a lesson description in the header (format 13)")]
    DescriptionBeforeFormat13,
    /// A lesson that is no lesson.
    #[error("lesson: no step, or a choice's answer out of its choices")]
    Lesson,
    /// A preset that does not read.
    #[error("its preset: {0}")]
    Preset(String),
    /// A method the scene does not offer.
    #[error("method \"{method}\": not one of the {scene}'s ({offered})")]
    Method {
        /// The method, as written (cleaned, 60 characters at most).
        method: String,
        /// The scene, as titled.
        scene: &'static str,
        /// The methods it offers.
        offered: String,
    },
    /// A theme given as an index from format 3 on.
    #[error("a theme given as an index: from format 3 on a header names its theme")]
    ThemeIndex,
}

/// Sane bounds on a header, checked before anything is built from it.
///
/// # Errors
/// Which field is out of range and what is allowed.
pub fn check_header(h: &Header) -> Result<(), HeaderError> {
    if !(1..=MAX_TERMINAL).contains(&h.terminal.width)
        || !(1..=MAX_TERMINAL).contains(&h.terminal.height)
    {
        return Err(HeaderError::Terminal {
            width: h.terminal.width,
            height: h.terminal.height,
        });
    }
    if !(h.fps.is_finite() && (1.0..=240.0).contains(&h.fps)) {
        return Err(HeaderError::Fps(h.fps));
    }
    if !(h.tolerance.is_finite() && h.tolerance > 0.0) {
        return Err(HeaderError::Tolerance(h.tolerance));
    }
    if let Some(lesson) = &h.lesson {
        if h.version < 10 {
            return Err(HeaderError::LessonBeforeFormat10);
        }
        if h.version < 13 && !lesson.description.is_empty() {
            return Err(HeaderError::DescriptionBeforeFormat13);
        }
        if lesson.lesson().is_none() {
            return Err(HeaderError::Lesson);
        }
    }
    Ok(())
}

/// What a session file may say, read line by line in order: the one validator of replay,
/// follow and `--verify` (issue 66). It knows the scene (the header's preset, then each preset
/// line's), so it refuses what the program never writes: a header whose method is not one of
/// its scene's or whose theme is an index in a file of format 3 or later, a `set` of a field the
/// scene has not, a `map_cursor` outside every chart the scene's pane draws, and every line
/// [`impossible`] refuses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sense {
    scene: crate::physics::ModelKind,
}

impl Sense {
    /// The header checked ([`check_header`], then its preset, method and theme).
    ///
    /// # Errors
    /// What is wrong with it, in words.
    pub fn of_header(h: &Header) -> Result<Self, HeaderError> {
        check_header(h)?;
        let scene = preset_scene(&h.preset)
            .map_err(|e| HeaderError::Preset(crate::scenario::text::one_line(&e.to_string())))?;
        let shown =
            |t: &str| crate::scenario::text::one_line(&t.chars().take(60).collect::<String>());
        match crate::physics::Method::from_name(&h.method) {
            Some(m) if scene.methods().contains(&m) => {}
            _ => {
                return Err(HeaderError::Method {
                    method: shown(&h.method),
                    scene: scene.title(),
                    offered: scene.method_names(),
                });
            }
        }
        if h.version >= 3 && matches!(h.theme, ThemeRef::Index(_)) {
            return Err(HeaderError::ThemeIndex);
        }
        Ok(Self { scene })
    }

    /// The scene at this point of the file.
    #[must_use]
    pub fn scene(&self) -> crate::physics::ModelKind {
        self.scene
    }

    /// Why `line` cannot be in a file at this point (`None`: it can); a preset line moves the
    /// scene on.
    pub fn line(&mut self, line: &Line) -> Option<String> {
        use crate::app::journal::Event;
        if let Some(why) = impossible(line) {
            return Some(why);
        }
        match &line.event {
            Event::Preset { toml } => match preset_scene(toml) {
                Ok(scene) => self.scene = scene,
                Err(e) => {
                    return Some(format!(
                        "a preset line that is no preset: {}",
                        crate::scenario::text::one_line(&e.to_string())
                    ));
                }
            },
            Event::Set { field, .. } | Event::Select { field }
                if !crate::app::fields::Field::named(self.scene, field)
                    .is_some_and(|f| f.belongs_to(self.scene)) =>
            {
                return Some(format!(
                    "a `{}` of the field \"{}\", which the {} has not",
                    if matches!(line.event, Event::Set { .. }) {
                        "set"
                    } else {
                        "select"
                    },
                    crate::scenario::text::one_line(&field.chars().take(60).collect::<String>()),
                    self.scene.title()
                ));
            }
            Event::Terminal { width, height }
                if !(1..=MAX_TERMINAL).contains(width) || !(1..=MAX_TERMINAL).contains(height) =>
            {
                return Some(format!(
                    "a terminal of {width}x{height}: allowed sizes are 1 to {MAX_TERMINAL}"
                ));
            }
            Event::MapCursor { column, row, .. } => {
                let (cols, rows) = crate::study::chart::pane::largest(self.scene);
                if *column >= cols || *row >= rows {
                    return Some(format!(
                        "a map cursor at column {column}, row {row}: the {}'s chart has {cols} columns and {rows} rows",
                        self.scene.title()
                    ));
                }
            }
            _ => {}
        }
        None
    }
}

/// The scene of a preset's TOML, read by the preset validator.
fn preset_scene(toml: &str) -> Result<crate::physics::ModelKind, crate::scenario::PresetError> {
    crate::scenario::Preset::parse(toml, "inline preset", "recorded", &[]).map(|p| p.model.kind())
}

/// Longest recording replayed or exported, in wall seconds (a week).
pub const MAX_WALL: f64 = 7.0 * 24.0 * 3600.0;

/// Problems with a session file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RecordError {
    /// Cannot read or write the file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// The file exists and would be overwritten.
    #[error("{0}: exists; choose another file name (nothing was overwritten)")]
    Exists(String),
    /// A line that is not what it must be.
    #[error("{path}:{line}: {message}")]
    Corrupt {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_names_its_theme_and_older_indices_still_read() {
        let named: ThemeRef = serde_json::from_str(r#""Dark (truecolour)""#).unwrap();
        assert_eq!(named.name(), Some("Dark (truecolour)"));
        assert_eq!(
            serde_json::to_string(&named).unwrap(),
            r#""Dark (truecolour)""#
        );
        let old: ThemeRef = serde_json::from_str("0").unwrap();
        assert_eq!(old, ThemeRef::Index(0));
        assert_eq!(old.name(), None);
    }
}
