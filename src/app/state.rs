//! The small types of the app's state: start-up options, the view, messages and captions, the
//! replay's and the recording's state; and the text helpers the app and the UI share.

use super::journal::Event;
use super::keys::{Action, Key};
use super::panes::Panes;
use super::portrait::View;
use super::user_keys;
use crate::scenario::text::clean;

/// Options fixed at start-up.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Frame-rate cap.
    pub fps: f64,
    /// Names of the colour themes `T` cycles through.
    pub theme_names: Vec<String>,
    /// The user's extra keys (`[keys]` in `config.toml`).
    pub keys: user_keys::UserKeys,
    /// The address the recording is served at (`--serve`), which `U` shows again.
    pub served: Option<String>,
}

impl Options {
    /// Options at `fps` with the default theme only.
    #[must_use]
    pub fn at(fps: f64) -> Self {
        Self {
            fps,
            theme_names: vec!["default".to_owned()],
            keys: user_keys::UserKeys::default(),
            served: None,
        }
    }

    /// The action of `key`: the user's binding, else the keymap's.
    #[must_use]
    pub fn action_for(&self, key: Key) -> Option<Action> {
        self.keys.resolve(key)
    }
}

/// Zoom, pan, panes, overlay and theme.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewState {
    /// Zoom, pan, wrap, fixed ranges.
    pub view: View,
    /// The preset's view, which `0` returns to.
    pub home: View,
    /// Visible panes.
    pub panes: Panes,
    /// Effective overlay shown (and so integrated).
    pub overlay: bool,
    /// Index of the colour theme.
    pub theme: usize,
}

/// A line for the user: information or an error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    /// The text (control characters stripped).
    pub text: String,
    /// Whether it reports an error.
    pub error: bool,
}

impl Message {
    // Always `Some`: they fill `App::status`, an `Option`, at every call site.
    #[allow(clippy::unnecessary_wraps)]
    pub(super) fn info(text: impl Into<String>) -> Option<Self> {
        Some(Self {
            text: clean(&text.into()),
            error: false,
        })
    }

    #[allow(clippy::unnecessary_wraps)]
    pub(super) fn error(text: impl Into<String>) -> Option<Self> {
        Some(Self {
            text: clean(&text.into()),
            error: true,
        })
    }
}

/// Every message and caption shown, in full and in order (the message line cuts a long one; `v`
/// shows them all), at most [`MessageLog::KEPT`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MessageLog {
    /// The lines, oldest first.
    pub entries: Vec<Message>,
    /// The last message and caption noted, so each is noted once.
    last: (Option<Message>, Option<(bool, String)>),
    /// What this session wrote, one line each (`recording saved to …`): the explorer prints
    /// them when it ends, so the files are found after the screen has gone.
    pub written: Vec<String>,
}

impl MessageLog {
    /// How many lines are kept.
    pub const KEPT: usize = 200;

    /// Notes `status` and `caption` when they differ from the last ones noted.
    pub fn remember(&mut self, status: Option<&Message>, caption: Option<&Caption>) {
        if let Some(m) = status
            && self.last.0.as_ref() != Some(m)
        {
            self.entries.push(m.clone());
        }
        self.last.0 = status.cloned();
        let cap = caption.map(|c| (c.chapter, c.text.clone()));
        if let Some(c) = caption
            && self.last.1 != cap
        {
            let kind = if c.chapter { "chapter" } else { "note" };
            self.entries.push(Message {
                text: format!("{kind} (t {:.2}): {}", c.t, c.text),
                error: false,
            });
        }
        self.last.1 = cap;
        if self.entries.len() > Self::KEPT {
            self.entries.drain(..self.entries.len() - Self::KEPT);
        }
    }
}

/// A note or chapter title on screen: it stays until the next one.
#[derive(Clone, Debug, PartialEq)]
pub struct Caption {
    /// A chapter (else a note).
    pub chapter: bool,
    /// The text.
    pub text: String,
    /// Simulated time it belongs to.
    pub t: f64,
}

/// The replay's state, as shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReplayInfo {
    /// Replay pace (×).
    pub pace: f64,
    /// Paused.
    pub paused: bool,
    /// Chapters passed.
    pub chapter: usize,
    /// Chapters in the file.
    pub chapters: usize,
    /// The recording's end was reached.
    pub ended: bool,
    /// Wall seconds of the recording replayed.
    pub at: f64,
    /// Wall seconds the recording lasts.
    pub length: f64,
    /// Following a recording as it is written (`rattleback follow`): `Some(ended)`.
    pub live: Option<bool>,
}

/// Whether a recording is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RecState {
    /// No recording.
    #[default]
    Off,
    /// Journaling.
    On,
    /// Waiting for the final checkpoint before closing.
    Stopping,
}

/// The journal of a recording: semantic events `(simulated time, generation, event)`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Journal {
    /// Whether one is on.
    pub state: RecState,
    pub(super) entries: Vec<(f64, u64, Event)>,
    /// A pause, step, chapter, note or lesson event waits for the screen it leads to.
    pub(super) screen_due: bool,
    /// `R` asked to close the recording: it closes once its last frame is settled.
    pub(super) stop_due: bool,
    /// Wall seconds since the last clock line, and the displayed time it stamped, of which run.
    pub(super) since_clock: f64,
    pub(super) clock_t: f64,
    pub(super) clock_generation: u64,
    /// The map's cursor and focus as last journaled (`None`: not yet in this recording).
    pub(super) map_cursor: Option<((usize, usize), bool)>,
}

impl Journal {
    /// Journals `event` at displayed time `t` of run `generation`: nothing without a recording,
    /// and only checkpoints once it is closing after its last frame (what comes after that
    /// frame, a later segment verified meanwhile, is not part of the lecture and would make the
    /// frame not the last: a lecture verified in segments failed `--verify` now and then, issue
    /// 55). A pause, step, chapter, note, lesson step or answer makes a screen due.
    pub(super) fn push(&mut self, t: f64, generation: u64, event: Event) {
        if self.state == RecState::Off
            || self.state == RecState::Stopping && !matches!(event, Event::Checkpoint { .. })
        {
            return;
        }
        self.screen_due |= matches!(
            event,
            Event::Pause
                | Event::Step
                | Event::Chapter { .. }
                | Event::Note { .. }
                | Event::LessonStep { .. }
                | Event::Answer { .. }
        );
        self.entries.push((t, generation, event));
    }

    /// The map's line (format 12) when its cursor or focus `now` differs from the last one
    /// journaled, while recording with the map `shown`.
    pub(super) fn map_cursor_changed(
        &mut self,
        shown: bool,
        now: ((usize, usize), bool),
    ) -> Option<Event> {
        if self.state != RecState::On || !shown || self.map_cursor == Some(now) {
            return None;
        }
        self.map_cursor = Some(now);
        let ((column, row), focused) = now;
        Some(Event::MapCursor {
            column,
            row,
            focused,
        })
    }
}

/// A file-name-safe form of `name`: lower-case letters, digits and single dashes.
#[must_use]
pub fn slug(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars().flat_map(char::to_lowercase) {
        if c.is_ascii_alphanumeric() {
            out.push(c);
        } else if !out.ends_with('-') && !out.is_empty() {
            out.push('-');
        }
    }
    let out = out
        .trim_end_matches('-')
        .chars()
        .take(48)
        .collect::<String>();
    if out.is_empty() {
        "rattleback".to_owned()
    } else {
        out
    }
}

/// `text` cut to `width` characters, ending in `…` when cut.
#[must_use]
pub fn ellipsis(text: &str, width: usize) -> String {
    if text.chars().count() <= width {
        return text.to_owned();
    }
    let mut s: String = text.chars().take(width.saturating_sub(1)).collect();
    s.push('…');
    s
}
