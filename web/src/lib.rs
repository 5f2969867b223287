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

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use rattleback::app::{App, Effect, Key, Options, Outcome};

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

    fn opened(
        preset: &rattleback::scenario::Preset,
        lesson: Option<rattleback::scenario::lesson::Lesson>,
        width: u16,
        height: u16,
    ) -> Self {
        let (mut app, mut effects) = App::new(preset, Options::at(30.0));
        if let Some(lesson) = lesson {
            effects.extend(app.start_lesson(lesson));
        }
        let mut explorer = Self {
            app,
            engine: Engine::new(PlanBook::default()),
            cache: Cache::default(),
            options: UiOptions::default(),
            screen: Buffer::empty(ratatui::layout::Rect::new(0, 0, width, height)),
            width,
            height,
        };
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
                    rattleback::scenario::shipped::resolve(&name, &[]).map_err(|e| e.to_string()),
                ))),
                Effect::StartRecording => Some(Outcome::Recording(Err(format!(
                    "recording is not in the browser yet ({NOT_YET}): record in the terminal, rattleback --record FILE"
                )))),
                Effect::Export { .. } => Some(Outcome::Exported(Err(format!(
                    "exporting files is not in the browser yet ({NOT_YET}): the terminal's x writes them"
                )))),
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

    /// A key, as the terminal's explorer takes it; whether the app asked to quit.
    pub fn key(&mut self, key: Key) -> bool {
        let effects = self.app.on_key(key);
        self.exec(effects);
        self.app.quit
    }

    /// One frame of `wall` seconds.
    pub fn tick(&mut self, wall: f64) {
        let effects = self.app.tick(wall.clamp(0.0, 0.25));
        self.exec(effects);
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
}

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
    use super::{ERROR, EXPLORER, Explorer, NAME, clamp_u16, key_of, rgb, with};

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
            "subcritical".to_owned()
        } else {
            name
        };
        let (w, h) = (
            clamp_u16(width).max(super::MIN_SIZE.0),
            clamp_u16(height).max(super::MIN_SIZE.1),
        );
        let opened = if lesson {
            Explorer::lesson(&name, w, h)
        } else {
            Explorer::new(&name, w, h)
        };
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
