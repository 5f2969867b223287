//! `replay --export-cast`: render a session into an asciicast v2 file (asciinema-player plays
//! it), with chapters and notes as markers. Rendered headless at the recorded terminal size (or
//! `--cols`/`--rows`), 10 frames per second of recorded time (or `--fps`), timestamps rounded to
//! the microsecond, `idle_time_limit` set; written to a temporary file and persisted, so a
//! failure leaves nothing half-written.

use std::cell::RefCell;
use std::path::Path;
use std::rc::Rc;

use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::{Terminal, TerminalOptions, Viewport};

use crate::app::effects::commands;
use crate::app::journal::Event;
use crate::record::replayer::{FrameClock, Replayer};
use crate::record::{RecordError, Recording, plan_book, start};
use crate::sim::{Engine, drive};
use crate::ui::{self, Cache, UiOptions};

/// Longest pause the player shows (seconds): longer idle stretches are cut to it.
pub const IDLE_TIME_LIMIT: f64 = 2.0;

/// The cast's size and frame rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CastSize {
    /// Columns (`None`: the recorded terminal's).
    pub cols: Option<u16>,
    /// Rows (`None`: the recorded terminal's).
    pub rows: Option<u16>,
    /// Frames per second of recorded time.
    pub fps: f64,
}

impl Default for CastSize {
    fn default() -> Self {
        Self {
            cols: None,
            rows: None,
            fps: 10.0,
        }
    }
}

/// The cast's events on the player's clock: each event's time (seconds), each gap between events
/// cut to the header's `idle_time_limit` as asciinema-player cuts it, and its kind (`"o"` output,
/// `"m"` marker).
#[must_use]
pub fn player_clock(cast: &str) -> Vec<(f64, String)> {
    let mut lines = cast.lines();
    let limit = lines
        .next()
        .and_then(|h| serde_json::from_str::<serde_json::Value>(h).ok())
        .and_then(|h| h.get("idle_time_limit").and_then(serde_json::Value::as_f64))
        .unwrap_or(f64::INFINITY);
    let (mut previous, mut cut) = (0.0, 0.0);
    let mut events = Vec::new();
    for line in lines {
        let Ok(serde_json::Value::Array(event)) = serde_json::from_str(line) else {
            continue;
        };
        let (Some(t), Some(kind)) = (
            event.first().and_then(serde_json::Value::as_f64),
            event.get(1).and_then(serde_json::Value::as_str),
        ) else {
            continue;
        };
        let idle = t - previous - limit;
        previous = t;
        if idle > 0.0 {
            cut += idle;
        }
        events.push((t - cut, kind.to_owned()));
    }
    events
}

/// When the player shows the cast's last frame (seconds on the player's clock): the page's
/// poster, so the page opens on the session's end.
#[must_use]
pub fn last_frame_time(cast: &str) -> f64 {
    player_clock(cast)
        .iter()
        .rev()
        .find(|(_, kind)| kind == "o")
        .map_or(0.0, |(t, _)| *t)
}

/// Whether a frame's bytes print anything: some byte outside escape sequences (CSI, OSC and
/// two-byte escapes) that is not a control character.
#[must_use]
pub fn changes_something(bytes: &[u8]) -> bool {
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            0x1b => {
                i += 1;
                match bytes.get(i) {
                    // CSI: parameters and intermediates, then a final byte 0x40..=0x7e.
                    Some(b'[') => {
                        i += 1;
                        while i < bytes.len() && !(0x40..=0x7e).contains(&bytes[i]) {
                            i += 1;
                        }
                        i += 1;
                    }
                    // OSC: up to BEL or ESC \.
                    Some(b']') => {
                        while i < bytes.len() && bytes[i] != 0x07 && bytes[i] != 0x1b {
                            i += 1;
                        }
                        i += if bytes.get(i) == Some(&0x1b) { 2 } else { 1 };
                    }
                    _ => i += 1,
                }
            }
            b if b < 0x20 || b == 0x7f => i += 1,
            _ => return true,
        }
    }
    false
}

/// The label of the player's marker an event makes: a chapter's title, a lesson step's
/// `step N/M: TITLE`, `note: TEXT` for a note (cleaned of control characters); `None` for every
/// other event.
#[must_use]
pub fn marker_label(event: &Event) -> Option<String> {
    match event {
        Event::Chapter { title } => Some(crate::scenario::text::one_line(title)),
        Event::LessonStep {
            step, steps, title, ..
        } => Some(format!(
            "step {}/{steps}: {}",
            step + 1,
            crate::scenario::text::one_line(title)
        )),
        Event::Note { text } => Some(format!("note: {}", crate::scenario::text::one_line(text))),
        _ => None,
    }
}

/// A time rounded to the microsecond (what asciinema writes).
fn micro(t: f64) -> f64 {
    (t * 1e6).round() / 1e6
}

/// A writer whose bytes can be taken out between frames.
#[derive(Clone, Default)]
struct Shared(Rc<RefCell<Vec<u8>>>);

impl std::io::Write for Shared {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Writes `rec` as an asciicast v2 file at `out` (replacing an existing file only when
/// `replace`), telling `seen` how many of the file's lines have been drawn (for progress).
/// Returns the number of frames.
///
/// # Errors
/// A bad header preset, or the output cannot be written.
pub fn export_cast(
    rec: &Recording,
    path: &str,
    out: &Path,
    options: &UiOptions,
    size: CastSize,
    replace: bool,
    seen: &mut dyn FnMut(usize),
) -> Result<usize, RecordError> {
    let io = |source| RecordError::Io {
        path: out.display().to_string(),
        source,
    };
    let (mut app, mut engine, mut screen) = prepare(rec, path, size)?;
    crate::scenario::write::write_atomic_with(out, replace, &mut |cast| {
        frames_of(
            rec,
            &mut app,
            &mut engine,
            &mut screen,
            (options, size),
            cast,
            seen,
        )
    })
    .map_err(io)
}

/// The cast of `rec` as text (for a page that inlines it), and its number of frames.
///
/// # Errors
/// As [`export_cast`].
pub fn cast_text(
    rec: &Recording,
    path: &str,
    options: &UiOptions,
    size: CastSize,
    seen: &mut dyn FnMut(usize),
) -> Result<(String, usize), RecordError> {
    let (mut app, mut engine, mut screen) = prepare(rec, path, size)?;
    let mut cast = Vec::new();
    let frames = frames_of(
        rec,
        &mut app,
        &mut engine,
        &mut screen,
        (options, size),
        &mut cast,
        seen,
    )
    .map_err(|source| RecordError::Io {
        path: path.to_owned(),
        source,
    })?;
    Ok((String::from_utf8_lossy(&cast).into_owned(), frames))
}

/// A terminal that draws into memory: each frame's bytes (what a terminal would receive), and
/// the whole screen again on demand (for a reader who joins late). The cast, the exported page
/// and `rattleback serve` draw through it, so all show the same frames.
pub(crate) struct MemoryScreen {
    terminal: Terminal<CrosstermBackend<Shared>>,
    screen: Shared,
    cache: Cache,
    /// The last frame drawn, whole.
    last: ratatui::buffer::Buffer,
}

impl MemoryScreen {
    /// A screen of `area`.
    pub(crate) fn new(area: Rect) -> std::io::Result<Self> {
        let screen = Shared::default();
        let terminal = Terminal::with_options(
            CrosstermBackend::new(screen.clone()),
            TerminalOptions {
                viewport: Viewport::Fixed(area),
            },
        )?;
        Ok(Self {
            terminal,
            screen,
            cache: Cache::default(),
            last: ratatui::buffer::Buffer::empty(area),
        })
    }

    /// The screen's size.
    pub(crate) fn area(&mut self) -> Rect {
        self.terminal.get_frame().area()
    }

    /// Draws from now on into `width × height` at the top left, the rest of the screen
    /// cleared (the lecturer resized the terminal; format 14): nothing when it is the size
    /// already. The size is held within `within`.
    pub(crate) fn resize_to(
        &mut self,
        (width, height): (u16, u16),
        within: Rect,
    ) -> std::io::Result<()> {
        let area = Rect::new(
            0,
            0,
            width.clamp(1, within.width.max(1)),
            height.clamp(1, within.height.max(1)),
        );
        if area == self.area() {
            return Ok(());
        }
        // A clear screen, then the whole frame at the new size (a new terminal of that size,
        // whose last frame is empty: `Terminal::resize` would ask the real terminal its size).
        self.screen
            .0
            .borrow_mut()
            .extend_from_slice(b"\x1b[0m\x1b[2J\x1b[H");
        self.terminal = Terminal::with_options(
            CrosstermBackend::new(self.screen.clone()),
            TerminalOptions {
                viewport: Viewport::Fixed(area),
            },
        )?;
        self.last = ratatui::buffer::Buffer::empty(area);
        Ok(())
    }

    /// Draws `app` as the lecturer saw it (no replay status); the bytes a terminal receives,
    /// or `None` when they change nothing on screen (escape codes alone).
    pub(crate) fn frame(
        &mut self,
        app: &mut crate::app::App,
        options: &UiOptions,
    ) -> std::io::Result<Option<Vec<u8>>> {
        app.replay = None;
        let cache = &mut self.cache;
        let done = self.terminal.draw(|f| ui::draw(f, app, options, cache))?;
        self.last.clone_from(done.buffer);
        let bytes =
            crate::terminal::FrameWriter::strip(&std::mem::take(&mut *self.screen.0.borrow_mut()));
        Ok(changes_something(&bytes).then_some(bytes))
    }

    /// The last frame drawn.
    pub(crate) fn last(&self) -> &ratatui::buffer::Buffer {
        &self.last
    }
}

/// The bytes that draw `buffer` on a cleared terminal.
#[must_use]
pub fn whole(buffer: &ratatui::buffer::Buffer) -> Vec<u8> {
    use ratatui::backend::Backend as _;
    let blank = ratatui::buffer::Buffer::empty(buffer.area);
    let mut out = b"\x1b[0m\x1b[2J\x1b[H".to_vec();
    let mut backend = CrosstermBackend::new(&mut out);
    let _ = backend
        .draw(blank.diff(buffer).into_iter())
        .and_then(|()| backend.hide_cursor())
        .and_then(|()| ratatui::backend::Backend::flush(&mut backend));
    crate::terminal::FrameWriter::strip(&out)
}

type Prepared = (crate::app::App, Engine, MemoryScreen);

/// The cast's whole screen: `--cols`/`--rows` when given (every frame at that size), else the
/// largest the lecturer's terminal was (the header's and every `terminal` line's, format 14),
/// so each moment is drawn at the size the lecturer saw, at the top left.
#[must_use]
pub fn canvas(rec: &Recording, size: CastSize) -> Rect {
    let mut w = rec.header.terminal.width;
    let mut h = rec.header.terminal.height;
    for (_, line) in &rec.lines {
        if let Event::Terminal { width, height } = line.event {
            w = w.max(width);
            h = h.max(height);
        }
    }
    let max = crate::record::MAX_TERMINAL;
    Rect::new(
        0,
        0,
        size.cols.unwrap_or(w).clamp(1, max),
        size.rows.unwrap_or(h).clamp(1, max),
    )
}

/// The replay's app at its start, its engine, and a terminal drawing into memory.
fn prepare(rec: &Recording, path: &str, size: CastSize) -> Result<Prepared, RecordError> {
    let io = |source| RecordError::Io {
        path: path.to_owned(),
        source,
    };
    let (mut app, start_effects) = start(rec, path)?;
    let recorded = rec.header.terminal;
    let area = Rect::new(
        0,
        0,
        size.cols.unwrap_or(recorded.width).max(1),
        size.rows.unwrap_or(recorded.height).max(1),
    );
    let mut screen = MemoryScreen::new(canvas(rec, size)).map_err(io)?;
    screen
        .resize_to((area.width, area.height), canvas(rec, size))
        .map_err(io)?;
    let mut engine = Engine::new(plan_book(rec)).stopping_on(crate::interrupt::not_requested);
    drive(&mut engine, commands(start_effects), &mut |e| {
        app.on_sim(e);
    });
    Ok((app, engine, screen))
}

/// Writes the cast, frame by frame, into `cast` (streamed: nothing is kept but the screen).
/// Idle stretches (paused, no event due) are skipped in one jump, not drawn frame by frame.
fn frames_of(
    rec: &Recording,
    app: &mut crate::app::App,
    engine: &mut Engine,
    screen: &mut MemoryScreen,
    (options, size): (&UiOptions, CastSize),
    cast: &mut dyn std::io::Write,
    seen: &mut dyn FnMut(usize),
) -> std::io::Result<usize> {
    let fps = size.fps;
    let run = |effects: Vec<crate::app::Effect>, engine: &mut Engine, app: &mut crate::app::App| {
        drive(engine, commands(effects), &mut |e| {
            app.on_sim(e);
        });
    };
    let area = canvas(rec, size);
    let header = serde_json::json!({
        "version": 2,
        "width": area.width,
        "height": area.height,
        "title": crate::record::title(rec, &app.scenario.name),
        "idle_time_limit": IDLE_TIME_LIMIT,
        "env": {"TERM": "xterm-256color"},
    });
    writeln!(cast, "{header}")?;
    let end = rec.lines.last().map_or(0.0, |(_, l)| l.wall) + 1.0;
    // The replay's own clock and line application (so the cast shows what the lecturer showed,
    // never a time past the next recorded one), drawn without the replay's status.
    let mut replay = Replayer::new(rec.lines.iter().map(|(_, l)| l.clone()).collect());
    let c = replay.catch_up(app);
    run(c, engine, app);
    let mut frames = 0;
    let mut clock = FrameClock::new(fps);
    while clock.now() <= end {
        if crate::interrupt::requested().is_some() {
            // The temporary file is removed when the error drops it.
            return Err(crate::interrupt::error());
        }
        let now = clock.now();
        let before = replay.position();
        let c = clock.show(&mut replay, app);
        seen(replay.position());
        run(c, engine, app);
        // The lecturer's size at this moment, unless the cast was given one.
        if let (None, None, Some(now)) = (size.cols, size.rows, app.lecturer_terminal) {
            screen.resize_to(now, area)?;
        }
        for (_, line) in &rec.lines[before..replay.position()] {
            if let Some(label) = marker_label(&line.event) {
                writeln!(
                    cast,
                    "{}",
                    serde_json::json!([micro(line.wall), "m", label])
                )?;
            }
        }
        // A frame of escape codes alone (cursor moves, resets) changes nothing on screen.
        if let Some(bytes) = screen.frame(app, options)? {
            let text = String::from_utf8_lossy(&bytes);
            writeln!(cast, "{}", serde_json::json!([micro(now), "o", text]))?;
            frames += 1;
        }
        clock.next(&replay, app);
    }
    Ok(frames)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_player_clock_cuts_idle_gaps_as_the_player_does() {
        let cast = "{\"version\":2,\"width\":80,\"height\":24,\"idle_time_limit\":2.0}\n\
                    [0.5,\"o\",\"a\"]\n[1.0,\"m\",\"one\"]\n[10.0,\"o\",\"b\"]\n\
                    [10.5,\"m\",\"two\"]\n[20.0,\"m\",\"end\"]\n";
        let clock = player_clock(cast);
        let times: Vec<f64> = clock.iter().map(|(t, _)| *t).collect();
        assert_eq!(times, [0.5, 1.0, 3.0, 3.5, 5.5]);
        // The last frame is the last output, not the marker after it.
        assert!((last_frame_time(cast) - 3.0).abs() < 1e-12);
        // Without a limit nothing is cut.
        let uncut = cast.replace(",\"idle_time_limit\":2.0", "");
        assert!((last_frame_time(&uncut) - 10.0).abs() < 1e-12);
        assert!(last_frame_time("{}").abs() < 1e-12, "an empty cast");
    }
}
