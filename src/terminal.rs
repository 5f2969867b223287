//! The only place that touches the tty: raw mode, the alternate screen, synchronized output
//! around each frame, a panic hook that restores the terminal before the message prints, and
//! translation of crossterm's key and mouse events into the app's [`Input`]. Mouse capture is
//! enabled only when asked (`--mouse` or `mouse = true`), and always disabled on restore.
//! Restoring is idempotent and also happens on drop.

use std::io::{self, Write};
use std::sync::Once;

use ratatui::Frame;
use ratatui::Terminal;
use ratatui::backend::CrosstermBackend;
use ratatui::crossterm::event::{
    DisableMouseCapture, Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton,
    MouseEventKind,
};
use ratatui::crossterm::terminal::{
    BeginSynchronizedUpdate, EndSynchronizedUpdate, EnterAlternateScreen, LeaveAlternateScreen,
    disable_raw_mode, enable_raw_mode,
};
use ratatui::crossterm::{cursor, execute, queue};

use crate::app::Key;

pub mod depth;

pub use depth::Depth;

/// Mouse reporting for what the explorer uses, clicks and the wheel: normal tracking (`?1000`)
/// in SGR coordinates (`?1006`). Crossterm's `EnableMouseCapture` also asks for any-motion
/// tracking (`?1003`), which sends every move of the mouse over the pane, and over SSH every
/// one of them crosses the network for nothing. `DisableMouseCapture` turns all of them off.
pub struct EnableClickCapture;

impl ratatui::crossterm::Command for EnableClickCapture {
    fn write_ansi(&self, f: &mut impl std::fmt::Write) -> std::fmt::Result {
        f.write_str("\x1b[?1000h\x1b[?1006h")
    }

    #[cfg(windows)]
    fn execute_winapi(&self) -> io::Result<()> {
        // The Windows console reports what it reports; no escape codes cross anything there.
        ratatui::crossterm::Command::execute_winapi(&ratatui::crossterm::event::EnableMouseCapture)
    }
}

/// The terminal in explorer mode; restores it when dropped.
pub struct Tty {
    terminal: Terminal<CrosstermBackend<FrameWriter>>,
    mouse: bool,
    /// Set when the terminal is handed back: its writer then writes nothing.
    released: std::rc::Rc<std::cell::Cell<bool>>,
}

static HOOK: Once = Once::new();

/// Puts the terminal back: cooked mode, main screen, visible cursor. Safe to call twice.
pub fn restore() {
    crate::fault::disarm();
    let _ = disable_raw_mode();
    let _ = execute!(
        io::stdout(),
        EndSynchronizedUpdate,
        DisableMouseCapture,
        LeaveAlternateScreen,
        cursor::Show
    );
}

impl Tty {
    /// Enters raw mode and the alternate screen (with mouse capture when `mouse`), and
    /// installs the panic hook.
    ///
    /// # Errors
    /// When stdout is not a terminal or cannot be configured.
    pub fn enter(mouse: bool, depth: Depth) -> io::Result<Self> {
        HOOK.call_once(|| {
            let previous = std::panic::take_hook();
            std::panic::set_hook(Box::new(move |info| {
                restore();
                previous(info);
            }));
        });
        // A fault puts the terminal back as it is now.
        crate::fault::arm();
        enable_raw_mode()?;
        if let Err(e) = execute!(io::stdout(), EnterAlternateScreen, cursor::Hide) {
            restore();
            return Err(e);
        }
        if mouse && let Err(e) = execute!(io::stdout(), EnableClickCapture) {
            restore();
            return Err(e);
        }
        let writer = FrameWriter::new(depth);
        let released = std::rc::Rc::clone(&writer.released);
        let terminal = Terminal::new(CrosstermBackend::new(writer)).inspect_err(|_| restore())?;
        Ok(Self {
            terminal,
            mouse,
            released,
        })
    }

    /// Puts `text` on the terminal's clipboard with OSC 52 (`ESC ] 52 ; c ; BASE64 BEL`), which
    /// terminals honour over SSH, and tmux passes on (`set-clipboard` on or external, its
    /// default).
    ///
    /// # Errors
    /// When writing to the terminal fails.
    pub fn copy(&mut self, text: &str) -> io::Result<()> {
        let sequence = osc52(text);
        let out = self.terminal.backend_mut();
        out.write_all(sequence.as_bytes())?;
        Write::flush(out)
    }

    /// Draws one frame wrapped in synchronized-output escapes, so the terminal shows it whole.
    ///
    /// # Errors
    /// When writing to the terminal fails.
    pub fn draw(&mut self, render: impl FnOnce(&mut Frame<'_>)) -> io::Result<()> {
        queue!(self.terminal.backend_mut(), BeginSynchronizedUpdate)?;
        self.terminal.draw(render)?;
        queue!(self.terminal.backend_mut(), EndSynchronizedUpdate)?;
        Write::flush(self.terminal.backend_mut())
    }

    /// Clears the screen and forces a full redraw on the next frame (Ctrl-L: a line noise or
    /// another program scribbled on the terminal).
    ///
    /// # Errors
    /// When writing to the terminal fails.
    pub fn clear(&mut self) -> io::Result<()> {
        self.invalidate()
    }

    /// Clears the screen and makes the next frame rewrite every cell. Ratatui's own `clear`
    /// asks the terminal for the cursor position, which blocks (and fails) on terminals that
    /// do not answer; this only writes. The next frame is drawn over a frame of hidden cells,
    /// which differs from it everywhere, inside one synchronized update.
    fn invalidate(&mut self) -> io::Result<()> {
        use ratatui::backend::{Backend, ClearType};
        use ratatui::style::{Modifier, Style};
        queue!(self.terminal.backend_mut(), BeginSynchronizedUpdate)?;
        self.terminal.backend_mut().clear_region(ClearType::All)?;
        self.terminal.draw(|f| {
            let area = f.area();
            f.buffer_mut()
                .set_style(area, Style::new().add_modifier(Modifier::HIDDEN));
        })?;
        queue!(self.terminal.backend_mut(), EndSynchronizedUpdate)?;
        Write::flush(self.terminal.backend_mut())
    }

    /// Suspends the process like a shell's Ctrl-Z: restores the terminal, stops until `fg`
    /// (SIGCONT), then re-enters raw mode and the alternate screen and redraws everything.
    ///
    /// # Errors
    /// When the terminal cannot be set up again.
    pub fn suspend(&mut self) -> io::Result<()> {
        restore();
        // SIGTSTP's default action stops the process (the explorer also catches SIGTSTP to get
        // here, so the default is emulated); it returns here on SIGCONT.
        signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGTSTP)?;
        crate::fault::arm();
        enable_raw_mode()?;
        execute!(io::stdout(), EnterAlternateScreen, cursor::Hide)?;
        if self.mouse {
            execute!(io::stdout(), EnableClickCapture)?;
        }
        self.invalidate()
    }

    /// Forces a full redraw on the next frame (after a resize).
    ///
    /// # Errors
    /// When the size cannot be read.
    pub fn autoresize(&mut self) -> io::Result<()> {
        self.terminal.autoresize()
    }
}

impl Drop for Tty {
    fn drop(&mut self) {
        restore();
        // The terminal is restored (cursor shown): ratatui's own drop writes nothing more. On a
        // terminal that is gone (a hang-up: SSH dropped, tmux killed) its attempt to show the
        // cursor failed and it said so with `eprintln!`, which panics when standard error is
        // that dead terminal: the recording was never finished (issue 55).
        self.released.set(true);
    }
}

/// What ratatui's crossterm backend writes after every frame to reset the underline colour
/// (its `underline-color` feature, which ratatui 0.30 always enables there). The explorer never
/// sets an underline colour, so the reset carries nothing.
const UNDERLINE_RESET: &[u8] = b"\x1b[59m";

/// The terminal's writer: holds a frame's bytes until the flush that ends it, drops the
/// useless underline-colour resets (5 bytes a frame, ≈ 1.5 % of the bytes over SSH), fits the
/// colour codes to the terminal's depth ([`depth::fit`]), then writes the frame in one go.
pub struct FrameWriter {
    buf: Vec<u8>,
    depth: Depth,
    /// The terminal has been restored (or is gone): nothing more is written to it. Shared with
    /// the [`Tty`], which sets it when it hands the terminal back.
    released: std::rc::Rc<std::cell::Cell<bool>>,
}

impl FrameWriter {
    /// A writer for a terminal of `depth` colours.
    #[must_use]
    pub fn new(depth: Depth) -> Self {
        Self {
            buf: Vec::new(),
            depth,
            released: std::rc::Rc::default(),
        }
    }

    /// `bytes` without the underline-colour resets.
    #[must_use]
    pub fn strip(bytes: &[u8]) -> Vec<u8> {
        let mut out = Vec::with_capacity(bytes.len());
        let mut i = 0;
        while i < bytes.len() {
            if bytes[i..].starts_with(UNDERLINE_RESET) {
                i += UNDERLINE_RESET.len();
            } else {
                out.push(bytes[i]);
                i += 1;
            }
        }
        out
    }
}

impl Write for FrameWriter {
    fn write(&mut self, data: &[u8]) -> io::Result<usize> {
        self.buf.extend_from_slice(data);
        Ok(data.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if self.released.get() {
            self.buf.clear();
            return Ok(());
        }
        let bytes = depth::fit(&Self::strip(&std::mem::take(&mut self.buf)), self.depth);
        let mut out = io::stdout().lock();
        out.write_all(&bytes)?;
        out.flush()
    }
}

/// The OSC 52 sequence that puts `text` on the clipboard.
#[must_use]
pub fn osc52(text: &str) -> String {
    use base64::Engine as _;
    format!(
        "\u{1b}]52;c;{}\u{7}",
        base64::engine::general_purpose::STANDARD.encode(text)
    )
}

/// What a terminal event means to the explorer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// A key.
    Key(Key),
    /// The terminal changed size.
    Resize,
    /// A left click at `(column, row)`.
    Click(u16, u16),
    /// The wheel turned (`true`: up).
    Wheel(bool),
}

/// Translates a crossterm event; `None` for events the explorer ignores.
#[must_use]
pub fn translate(event: &Event) -> Option<Input> {
    match event {
        Event::Resize(..) => Some(Input::Resize),
        Event::Key(k) => translate_key(k).map(Input::Key),
        Event::Mouse(m) => match m.kind {
            MouseEventKind::Down(MouseButton::Left) => Some(Input::Click(m.column, m.row)),
            MouseEventKind::ScrollUp => Some(Input::Wheel(true)),
            MouseEventKind::ScrollDown => Some(Input::Wheel(false)),
            _ => None,
        },
        _ => None,
    }
}

fn translate_key(k: &KeyEvent) -> Option<Key> {
    if k.kind == KeyEventKind::Release {
        return None;
    }
    let shift = k.modifiers.contains(KeyModifiers::SHIFT);
    let ctrl = k.modifiers.contains(KeyModifiers::CONTROL);
    let alt = k.modifiers.contains(KeyModifiers::ALT);
    Some(match k.code {
        // Modifiers are kept: Ctrl-P is not p, Alt-q is not q.
        KeyCode::Char(c) if ctrl => Key::Ctrl(c.to_ascii_lowercase()),
        KeyCode::Char(c) if alt => Key::Alt(c),
        KeyCode::Char(c) => Key::Char(c),
        _ if ctrl || alt => return None,
        KeyCode::Up if shift => Key::ShiftUp,
        KeyCode::Down if shift => Key::ShiftDown,
        KeyCode::Left if shift => Key::ShiftLeft,
        KeyCode::Right if shift => Key::ShiftRight,
        KeyCode::Up => Key::Up,
        KeyCode::Down => Key::Down,
        KeyCode::Left => Key::Left,
        KeyCode::Right => Key::Right,
        KeyCode::Enter => Key::Enter,
        KeyCode::Esc => Key::Esc,
        KeyCode::Backspace => Key::Backspace,
        KeyCode::PageUp => Key::PageUp,
        KeyCode::PageDown => Key::PageDown,
        KeyCode::Home => Key::Home,
        KeyCode::End => Key::End,
        KeyCode::Tab => Key::Tab,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(code: KeyCode, modifiers: KeyModifiers) -> Option<Key> {
        translate_key(&KeyEvent::new(code, modifiers))
    }

    #[test]
    fn the_underline_reset_is_dropped_and_nothing_else() {
        // What the crossterm backend writes, in the fragments it writes them.
        let mut frame = b"\x1b[1;1H\x1b[38;5;2mab".to_vec();
        frame.extend_from_slice(b"\x1b[39m\x1b[49m\x1b[59m\x1b[0m");
        assert_eq!(
            FrameWriter::strip(&frame),
            b"\x1b[1;1H\x1b[38;5;2mab\x1b[39m\x1b[49m\x1b[0m".to_vec()
        );
        assert_eq!(
            FrameWriter::strip(b"\x1b[59"),
            b"\x1b[59".to_vec(),
            "a partial one stays"
        );
        let mut w = FrameWriter::new(Depth::Indexed);
        for piece in [&b"\x1b["[..], b"59", b"m"] {
            w.write_all(piece).unwrap();
        }
        assert_eq!(
            FrameWriter::strip(&w.buf),
            Vec::<u8>::new(),
            "fragments are joined first"
        );
    }

    #[test]
    fn osc52_carries_the_text_in_base64() {
        assert_eq!(
            osc52("rattleback simulate"),
            "\u{1b}]52;c;cmF0dGxlYmFjayBzaW11bGF0ZQ==\u{7}"
        );
    }

    #[test]
    fn clicks_and_the_wheel_translate() {
        use ratatui::crossterm::event::MouseEvent;
        let m = |kind| {
            Event::Mouse(MouseEvent {
                kind,
                column: 12,
                row: 5,
                modifiers: KeyModifiers::NONE,
            })
        };
        assert_eq!(
            translate(&m(MouseEventKind::Down(MouseButton::Left))),
            Some(Input::Click(12, 5))
        );
        assert_eq!(
            translate(&m(MouseEventKind::ScrollUp)),
            Some(Input::Wheel(true))
        );
        assert_eq!(
            translate(&m(MouseEventKind::ScrollDown)),
            Some(Input::Wheel(false))
        );
        assert_eq!(translate(&m(MouseEventKind::Moved)), None);
    }

    #[test]
    fn modifiers_are_respected() {
        assert_eq!(
            key(KeyCode::Char('l'), KeyModifiers::CONTROL),
            Some(Key::Ctrl('l'))
        );
        assert_eq!(
            key(KeyCode::Char('p'), KeyModifiers::CONTROL),
            Some(Key::Ctrl('p'))
        );
        assert_eq!(
            key(KeyCode::Char('q'), KeyModifiers::ALT),
            Some(Key::Alt('q'))
        );
        assert_eq!(
            key(KeyCode::Char('L'), KeyModifiers::SHIFT),
            Some(Key::Char('L'))
        );
        assert_eq!(key(KeyCode::Left, KeyModifiers::CONTROL), None);
        assert_eq!(
            key(KeyCode::Left, KeyModifiers::SHIFT),
            Some(Key::ShiftLeft)
        );
    }
}

#[cfg(test)]
mod mouse_tests {
    use super::EnableClickCapture;
    use ratatui::crossterm::Command;

    #[test]
    fn the_mouse_reports_clicks_and_the_wheel_not_every_motion() {
        let mut ansi = String::new();
        EnableClickCapture.write_ansi(&mut ansi).unwrap();
        assert!(
            ansi.contains("?1000h") && ansi.contains("?1006h"),
            "{ansi:?}"
        );
        // Any-motion (1003) and button-motion (1002) tracking would send every move over SSH.
        assert!(
            !ansi.contains("?1003h") && !ansi.contains("?1002h"),
            "{ansi:?}"
        );
    }
}
