//! The explorer in the browser (issue 82): the program's own [`App`] decides, its worker's
//! interpreter ([`Engine`]) integrates between frames, and its own screens ([`ui::draw`]) are
//! drawn into a cell buffer that the page turns into text in its DOM (`web/index.html`).
//!
//! The module has no imports and a few plain exports taking and giving numbers only (the page
//! passes a preset's name a character at a time and reads the screen cell by cell): nothing to
//! install but the Rust target, no glue generated, and no `unsafe` beyond the attribute that
//! exports a function by name. Everything that is not the screen (files, the clipboard, the
//! server) is the page's or is said not to be there yet.

use std::cell::RefCell;

pub mod trajectory;

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use rattleback::app::{App, Effect, Key, Options, Outcome, ShellError};
use rattleback::record::active::ActiveRecording;

/// The page's frame rate, as a recording's header says it.
const FPS: f64 = 30.0;

/// Where what the page cannot do yet is planned.
const NOT_YET: &str = "issue 82";
use rattleback::sim::{Engine, PlanBook};
use rattleback::ui::{self, Cache, UiOptions};

/// The smallest screen the page asks for (the terminal's own minimum is smaller; the page
/// scrolls sideways below this).
pub const MIN_SIZE: (u16, u16) = (80, 24);

/// One explorer: the app, its interpreter and its screen.
pub struct Explorer {
    app: App,
    engine: Engine,
    cache: Cache,
    options: UiOptions,
    screen: Buffer,
    width: u16,
    height: u16,
    /// Seconds of frames so far: the recording's clock (the module has no other).
    wall: f64,
    /// The recording in progress (`R`), in memory.
    recording: Option<ActiveRecording>,
    /// A finished recording for the page to download: its name and its bytes.
    download: Option<(String, Vec<u8>)>,
    /// The app's first effects, until they run.
    pending: Vec<Effect>,
}

impl Explorer {
    /// The explorer on `preset` (a shipped name), paused at its start, on a screen of `width ×
    /// height` cells.
    ///
    /// # Errors
    /// No shipped preset of that name (the message lists them).
    pub fn new(preset: &str, width: u16, height: u16) -> Result<Self, String> {
        let preset =
            rattleback::scenario::shipped::resolve(preset, &[]).map_err(|e| e.to_string())?;
        Ok(Self::opened(&preset, None, width, height))
    }

    /// The explorer on a shipped lesson (its first step's preset, else the default), as
    /// `rattleback lesson NAME` opens it.
    ///
    /// # Errors
    /// No shipped lesson of that name (the message lists them).
    pub fn lesson(name: &str, width: u16, height: u16) -> Result<Self, String> {
        let lesson = rattleback::scenario::lesson::resolve(name).map_err(|e| e.to_string())?;
        let preset = match lesson.steps[0].preset.clone() {
            Some(p) => p,
            None => rattleback::scenario::shipped::resolve(
                rattleback::scenario::shipped::DEFAULT_PRESET,
                &[],
            )
            .map_err(|e| e.to_string())?,
        };
        Ok(Self::opened(&preset, Some(lesson), width, height))
    }

    /// The explorer forked from a served lecture (`f` on `rattleback serve`'s page): `session`
    /// is the lecture's file so far (its complete lines); the lecture is replayed up to its last
    /// line, as `follow` shows it, then forked there, as `follow`'s `f` does. Gives the
    /// lecture's time it forked at too.
    ///
    /// # Errors
    /// The lines are not a session file, or its header's preset is not valid.
    pub fn forked(session: &str, width: u16, height: u16) -> Result<(Self, f64), String> {
        let rec = rattleback::record::parse(session, "the lecture").map_err(|e| e.to_string())?;
        let preset = rattleback::scenario::Preset::parse(
            &rec.header.preset,
            "the lecture's header",
            "lecture",
            &[],
        )
        .map_err(|e| e.to_string())?;
        let mut explorer = Self::blank(&preset, width, height);
        explorer.engine = Engine::new(rattleback::record::replayer::follower_book(&rec));
        let mut effects = std::mem::take(&mut explorer.pending);
        if let Some(lesson) = rec
            .header
            .lesson
            .as_ref()
            .and_then(rattleback::scenario::lesson::RecordedLesson::lesson)
        {
            explorer.app.replay_lesson(lesson);
        }
        let lines: Vec<_> = rec.lines.iter().map(|(_, l)| l.clone()).collect();
        let now = lines.last().map_or(0.0, |l| l.wall);
        // Played frame by frame, as a follower saw it (each line applied where the display
        // had got to), to the last line.
        let mut replayer = rattleback::record::replayer::Replayer::new(lines);
        effects.extend(replayer.catch_up(&mut explorer.app));
        explorer.exec(effects);
        let mut clock = rattleback::record::replayer::FrameClock::new(FPS);
        while clock.now() <= now {
            let effects = clock.show(&mut replayer, &mut explorer.app);
            explorer.exec(effects);
            clock.next(&replayer, &explorer.app);
        }
        let effects = clock.show(&mut replayer, &mut explorer.app);
        explorer.exec(effects);
        let at = explorer.app.run.shown;
        explorer.app.fork();
        explorer.exec(vec![Effect::Sim(rattleback::sim::Command::Release)]);
        explorer.draw();
        Ok((explorer, at))
    }

    /// The explorer on `preset` with nothing run yet: the app's first effects wait in
    /// `pending`.
    fn blank(preset: &rattleback::scenario::Preset, width: u16, height: u16) -> Self {
        let (app, effects) = App::new(preset, Options::at(FPS));
        Self {
            app,
            engine: Engine::new(PlanBook::default()),
            cache: Cache::default(),
            options: UiOptions::default(),
            screen: Buffer::empty(ratatui::layout::Rect::new(0, 0, width, height)),
            width,
            height,
            wall: 0.0,
            recording: None,
            download: None,
            pending: effects,
        }
    }

    fn opened(
        preset: &rattleback::scenario::Preset,
        lesson: Option<rattleback::scenario::lesson::Lesson>,
        width: u16,
        height: u16,
    ) -> Self {
        let mut explorer = Self::blank(preset, width, height);
        let mut effects = std::mem::take(&mut explorer.pending);
        if let Some(lesson) = lesson {
            effects.extend(explorer.app.start_lesson(lesson));
        }
        explorer.exec(effects);
        explorer.draw();
        explorer
    }

    /// Runs what the app asked: the worker's commands to their end on the interpreter (as
    /// `replay --verify` and the headless tests run them); the picker's catalogue and presets
    /// from what the module carries; for what needs files (recording, exports, saving), the
    /// app is told that it is not in the browser yet, and says so.
    fn exec(&mut self, effects: Vec<Effect>) {
        let mut queue: std::collections::VecDeque<Effect> = effects.into();
        while let Some(effect) = queue.pop_front() {
            let outcome = match effect {
                Effect::Sim(command) => {
                    let app = &mut self.app;
                    rattleback::sim::drive(&mut self.engine, vec![command], &mut |event| {
                        app.on_sim(event);
                    });
                    None
                }
                Effect::ReadCatalogue => {
                    let (entries, _) = rattleback::scenario::shipped::catalogue_in(None);
                    Some(Outcome::Catalogue(entries, Vec::new()))
                }
                Effect::LoadPreset(name) => Some(Outcome::Loaded(Box::new(
                    rattleback::scenario::shipped::resolve(&name, &[]).map_err(ShellError::from),
                ))),
                Effect::StartRecording => Some(self.start_recording()),
                Effect::StopRecording => {
                    if let Some(r) = self.recording.as_mut() {
                        r.stopping = true;
                    }
                    None
                }
                Effect::Export { .. } => {
                    Some(Outcome::Exported(Err(ShellError::NotInThisBuild(format!(
                        "exporting files is not in the browser yet ({NOT_YET}): the terminal's x writes them"
                    )))))
                }
                Effect::SavePreset { .. } => Some(Outcome::Saved(Err(
                    rattleback::scenario::store::SaveError::Io {
                        path: std::path::PathBuf::from("this page"),
                        source: std::io::Error::other(format!(
                            "saving a preset is not in the browser yet ({NOT_YET})"
                        )),
                    },
                ))),
                _ => None,
            };
            if let Some(outcome) = outcome {
                queue.extend(self.app.on_outcome(outcome));
            }
        }
    }

    /// `R`: a recording in memory, named after the scenario; the page downloads it when `R`
    /// ends it ([`Explorer::take_download`]).
    fn start_recording(&mut self) -> Outcome {
        let name = format!("{}.jsonl", rattleback::app::slug(&self.app.scenario.name));
        let size = (self.width, self.height);
        match ActiveRecording::in_memory(&self.app, &name, size, FPS, self.wall) {
            Ok(r) => {
                self.recording = Some(r);
                Outcome::Recording(Ok(name))
            }
            Err(e) => Outcome::Recording(Err(ShellError::Recording(Box::new(e)))),
        }
    }

    /// Checkpoints and writes the recording, as the terminal's explorer does after each
    /// event; a finished one waits for the page.
    fn keep_recording(&mut self) {
        let Some(rec) = self.recording.as_mut() else {
            return;
        };
        if self.app.journal.state == rattleback::app::RecState::On
            && let Some(c) = rec.due(&self.app, self.wall)
        {
            self.exec(vec![c]);
        }
        let Some(rec) = self.recording.as_mut() else {
            return;
        };
        match rec.flush(&mut self.app, self.wall) {
            Ok(None) => {}
            Ok(Some(done)) | Err(done) => {
                if let Some(r) = self.recording.take()
                    && let (Outcome::RecordingSaved(name), Some(bytes)) = (&done, r.bytes())
                {
                    self.download = Some((name.clone(), bytes.to_vec()));
                }
                let effects = self.app.on_outcome(done);
                self.exec(effects);
            }
        }
    }

    /// A finished recording, once: its file name and its bytes.
    pub fn take_download(&mut self) -> Option<(String, Vec<u8>)> {
        self.download.take()
    }

    /// A key, as the terminal's explorer takes it; whether the app asked to quit.
    pub fn key(&mut self, key: Key) -> bool {
        let effects = self.app.on_key(key);
        self.exec(effects);
        self.keep_recording();
        self.app.quit
    }

    /// One frame of `wall` seconds.
    pub fn tick(&mut self, wall: f64) {
        let wall = wall.clamp(0.0, 0.25);
        self.wall += wall;
        let effects = self.app.tick(wall);
        self.exec(effects);
        self.keep_recording();
    }

    /// A new screen size (at least [`MIN_SIZE`]).
    pub fn resize(&mut self, width: u16, height: u16) {
        self.width = width.max(MIN_SIZE.0);
        self.height = height.max(MIN_SIZE.1);
    }

    /// Draws the screen into its buffer.
    pub fn draw(&mut self) {
        let Ok(mut terminal) = Terminal::new(TestBackend::new(self.width, self.height));
        let (app, options, cache) = (&self.app, &self.options, &mut self.cache);
        if terminal.draw(|f| ui::draw(f, app, options, cache)).is_ok() {
            self.screen = terminal.backend().buffer().clone();
        }
    }

    /// The screen as last drawn.
    #[must_use]
    pub fn screen(&self) -> &Buffer {
        &self.screen
    }

    /// The screen as text, a line a row.
    #[must_use]
    pub fn text(&self) -> String {
        let area = self.screen.area;
        let mut out = String::new();
        for y in 0..area.height {
            for x in 0..area.width {
                out.push_str(self.screen[(x, y)].symbol());
            }
            out.push('\n');
        }
        out
    }

    /// The app, for the tests.
    #[must_use]
    pub fn app(&self) -> &App {
        &self.app
    }
}

/// A colour as `0xRRGGBB`, or [`DEFAULT_COLOR`] for the terminal's own (the page's theme).
#[must_use]
pub fn rgb(color: Color) -> u32 {
    const ANSI: [u32; 16] = [
        0x0000_0000,
        0x00cd_3131,
        0x000d_bc79,
        0x00e5_e510,
        0x0024_72c8,
        0x00bc_3fbc,
        0x0011_a8cd,
        0x00e5_e5e5,
        0x0066_6666,
        0x00f1_4c4c,
        0x0023_d18b,
        0x00f5_f543,
        0x003b_8eea,
        0x00d6_70d6,
        0x0029_b8db,
        0x00ff_ffff,
    ];
    match color {
        Color::Reset => DEFAULT_COLOR,
        Color::Black => ANSI[0],
        Color::Red => ANSI[1],
        Color::Green => ANSI[2],
        Color::Yellow => ANSI[3],
        Color::Blue => ANSI[4],
        Color::Magenta => ANSI[5],
        Color::Cyan => ANSI[6],
        Color::Gray => ANSI[7],
        Color::DarkGray => ANSI[8],
        Color::LightRed => ANSI[9],
        Color::LightGreen => ANSI[10],
        Color::LightYellow => ANSI[11],
        Color::LightBlue => ANSI[12],
        Color::LightMagenta => ANSI[13],
        Color::LightCyan => ANSI[14],
        Color::White => ANSI[15],
        Color::Rgb(r, g, b) => (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b),
        Color::Indexed(i) => indexed(i, &ANSI),
    }
}

/// The xterm palette: 16 colours, a 6×6×6 cube, 24 greys.
fn indexed(i: u8, ansi: &[u32; 16]) -> u32 {
    match i {
        0..=15 => ansi[usize::from(i)],
        16..=231 => {
            let n = u32::from(i - 16);
            let level = |v: u32| if v == 0 { 0 } else { 55 + 40 * v };
            (level(n / 36) << 16) | (level((n / 6) % 6) << 8) | level(n % 6)
        }
        _ => {
            let g = 8 + 10 * u32::from(i - 232);
            (g << 16) | (g << 8) | g
        }
    }
}

/// The page's own colour (foreground or background).
pub const DEFAULT_COLOR: u32 = 0x0100_0000;

/// A key from the page: `kind` 0 a character, 1 with Ctrl, 2 with Alt (`code` its code
/// point); 3 a named key (`code`: 1–4 the arrows up, down, left, right, 5–8 the same with
/// Shift, 9 Enter, 10 Esc, 11 Backspace, 12 page up, 13 page down, 14 Home, 15 End, 16 Tab).
#[must_use]
pub fn key_of(kind: u32, code: u32) -> Option<Key> {
    let c = char::from_u32(code);
    match kind {
        0 => c.map(Key::Char),
        1 => c.map(|c| Key::Ctrl(c.to_ascii_lowercase())),
        2 => c.map(Key::Alt),
        3 => Some(match code {
            1 => Key::Up,
            2 => Key::Down,
            3 => Key::Left,
            4 => Key::Right,
            5 => Key::ShiftUp,
            6 => Key::ShiftDown,
            7 => Key::ShiftLeft,
            8 => Key::ShiftRight,
            9 => Key::Enter,
            10 => Key::Esc,
            11 => Key::Backspace,
            12 => Key::PageUp,
            13 => Key::PageDown,
            14 => Key::Home,
            15 => Key::End,
            16 => Key::Tab,
            _ => return None,
        }),
        _ => None,
    }
}

thread_local! {
    static EXPLORER: RefCell<Option<Explorer>> = const { RefCell::new(None) };
    static NAME: RefCell<String> = const { RefCell::new(String::new()) };
    static ERROR: RefCell<Vec<char>> = const { RefCell::new(Vec::new()) };
    static TEXT: RefCell<String> = const { RefCell::new(String::new()) };
    static OUT: RefCell<Vec<char>> = const { RefCell::new(Vec::new()) };
    static FORKED_AT: std::cell::Cell<f64> = const { std::cell::Cell::new(0.0) };
}

/// Longest text pushed to the module (a lecture's file so far): 64 MiB.
pub const MAX_TEXT: usize = 64 << 20;

fn with<T>(f: impl FnOnce(&mut Explorer) -> T) -> Option<T> {
    EXPLORER.with(|e| e.borrow_mut().as_mut().map(f))
}

fn clamp_u16(v: u32) -> u16 {
    u16::try_from(v).unwrap_or(u16::MAX)
}

/// The page's calls. Numbers only, in and out: no pointer crosses, so nothing here is unsafe
/// but the attribute that exports each function under its name.
#[allow(unsafe_code)]
mod exports {
    use super::{
        ERROR, EXPLORER, Explorer, FORKED_AT, NAME, OUT, TEXT, clamp_u16, key_of, rgb, with,
    };

    /// Adds a character to the name of the preset to open.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_name_push(code: u32) {
        if let Some(c) = char::from_u32(code) {
            NAME.with(|n| {
                let mut n = n.borrow_mut();
                if n.len() < 256 {
                    n.push(c);
                }
            });
        }
    }

    /// Opens the explorer on the preset named so far (the default when none was) at `width ×
    /// height`: 1, or 0 with the reason in [`rb_error_char`].
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_start(width: u32, height: u32) -> u32 {
        start(width, height, false)
    }

    /// Opens the explorer on the lesson named so far, as [`rb_start`] does a preset.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_start_lesson(width: u32, height: u32) -> u32 {
        start(width, height, true)
    }

    fn start(width: u32, height: u32, lesson: bool) -> u32 {
        let name = NAME.with(|n| std::mem::take(&mut *n.borrow_mut()));
        let name = if name.is_empty() {
            rattleback::scenario::shipped::DEFAULT_PRESET.to_owned()
        } else {
            name
        };
        let (w, h) = screen_size(width, height);
        install(if lesson {
            Explorer::lesson(&name, w, h)
        } else {
            Explorer::new(&name, w, h)
        })
    }

    /// The screen asked, at least [`super::MIN_SIZE`].
    fn screen_size(width: u32, height: u32) -> (u16, u16) {
        (
            clamp_u16(width).max(super::MIN_SIZE.0),
            clamp_u16(height).max(super::MIN_SIZE.1),
        )
    }

    /// The explorer opened, as the page's (1), or why not ([`rb_error_char`], 0).
    fn install(opened: Result<Explorer, String>) -> u32 {
        match opened {
            Ok(e) => {
                EXPLORER.with(|x| *x.borrow_mut() = Some(e));
                1
            }
            Err(e) => {
                ERROR.with(|x| *x.borrow_mut() = e.chars().collect());
                0
            }
        }
    }

    /// Adds a character to the text the next [`rb_trajectory`] or [`rb_fork`] reads (a preset's
    /// TOML, a lecture's lines); past [`super::MAX_TEXT`] bytes the rest is dropped (and the
    /// text refused as cut).
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_text_push(code: u32) {
        if let Some(c) = char::from_u32(code) {
            TEXT.with(|t| {
                let mut t = t.borrow_mut();
                if t.len() < super::MAX_TEXT {
                    t.push(c);
                }
            });
        }
    }

    /// Runs the preset pushed so far ([`super::trajectory::csv`]) at `samples` samples; the
    /// CSV (or the refusal) is the output, [`rb_out_char`]; gives its length.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_trajectory(samples: u32) -> u32 {
        let toml = TEXT.with(|t| std::mem::take(&mut *t.borrow_mut()));
        out(&super::trajectory::csv(&toml, samples))
    }

    /// Character `i` of the last output.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_out_char(i: u32) -> u32 {
        OUT.with(|o| o.borrow().get(i as usize).map_or(0, |&c| u32::from(c)))
    }

    /// A finished recording (`R` pressed again): its file name becomes the output
    /// ([`rb_out_char`]) and its length is given, then [`rb_download_text`] gives its text;
    /// 0 when there is none. The page asks after every key and frame.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_download_name() -> u32 {
        let name = with(|e| e.download.as_ref().map(|(n, _)| n.clone())).flatten();
        name.map_or(0, |n| out(&n))
    }

    /// The finished recording's text as the output (and no longer held); its length.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_download_text() -> u32 {
        with(Explorer::take_download)
            .flatten()
            .map_or(0, |(_, bytes)| out(&String::from_utf8_lossy(&bytes)))
    }

    fn out(text: &str) -> u32 {
        OUT.with(|o| {
            *o.borrow_mut() = text.chars().collect();
            u32::try_from(o.borrow().len()).unwrap_or(0)
        })
    }

    /// Opens the explorer forked from the lecture whose lines were pushed ([`rb_text_push`]):
    /// 1, or 0 with the reason in [`rb_error_char`]. [`rb_forked_at`] gives the lecture's time.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_fork(width: u32, height: u32) -> u32 {
        let text = TEXT.with(|t| std::mem::take(&mut *t.borrow_mut()));
        let (w, h) = screen_size(width, height);
        if text.len() >= super::MAX_TEXT {
            return install(Err(format!(
                "the lecture's file is over {} bytes",
                super::MAX_TEXT
            )));
        }
        install(Explorer::forked(&text, w, h).map(|(e, at)| {
            FORKED_AT.with(|f| f.set(at));
            e
        }))
    }

    /// The lecture's time the last [`rb_fork`] forked at.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_forked_at() -> f64 {
        FORKED_AT.with(std::cell::Cell::get)
    }

    /// The length of the last error, in characters.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_error_len() -> u32 {
        ERROR.with(|e| u32::try_from(e.borrow().len()).unwrap_or(0))
    }

    /// Character `i` of the last error.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_error_char(i: u32) -> u32 {
        ERROR.with(|e| e.borrow().get(i as usize).map_or(0, |&c| u32::from(c)))
    }

    /// A key ([`key_of`]); 1 when the explorer asked to quit.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_key(kind: u32, code: u32) -> u32 {
        key_of(kind, code)
            .and_then(|k| with(|e| u32::from(e.key(k))))
            .unwrap_or(0)
    }

    /// One frame of `ms` milliseconds, then the screen drawn.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_frame(ms: f64) {
        with(|e| {
            e.tick(ms / 1000.0);
            e.draw();
        });
    }

    /// A new screen size, drawn.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_resize(width: u32, height: u32) {
        with(|e| {
            e.resize(clamp_u16(width), clamp_u16(height));
            e.draw();
        });
    }

    /// The screen's width in cells.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_width() -> u32 {
        with(|e| u32::from(e.screen().area.width)).unwrap_or(0)
    }

    /// The screen's height in cells.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_height() -> u32 {
        with(|e| u32::from(e.screen().area.height)).unwrap_or(0)
    }

    fn cell<T>(i: u32, f: impl FnOnce(&ratatui::buffer::Cell) -> T, none: T) -> T {
        with(|e| e.screen().content.get(i as usize).map(f))
            .flatten()
            .unwrap_or(none)
    }

    /// The character of cell `i` (row by row); 0 for the second half of a wide one.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_char(i: u32) -> u32 {
        cell(i, |c| c.symbol().chars().next().map_or(0, u32::from), 0)
    }

    /// The foreground of cell `i` as `0xRRGGBB` (or the page's own, `0x1000000`).
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_fg(i: u32) -> u32 {
        cell(i, |c| rgb(c.fg), super::DEFAULT_COLOR)
    }

    /// The background of cell `i`.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_bg(i: u32) -> u32 {
        cell(i, |c| rgb(c.bg), super::DEFAULT_COLOR)
    }

    /// The style of cell `i`: 1 bold, 2 dim, 4 italic, 8 underlined, 16 reversed.
    #[unsafe(no_mangle)]
    pub extern "C" fn rb_mods(i: u32) -> u32 {
        cell(i, |c| super::mods(c.modifier), 0)
    }
}

/// The style bits of a cell, as [`exports::rb_mods`] gives them (for the tests).
#[must_use]
pub fn mods(m: Modifier) -> u32 {
    u32::from(m.contains(Modifier::BOLD))
        | u32::from(m.contains(Modifier::DIM)) << 1
        | u32::from(m.contains(Modifier::ITALIC)) << 2
        | u32::from(m.contains(Modifier::UNDERLINED)) << 3
        | u32::from(m.contains(Modifier::REVERSED)) << 4
}
