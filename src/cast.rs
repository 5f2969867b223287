//! `replay --export-cast`: render a session into an asciicast v2 file (asciinema-player plays
//! it), with chapters as markers. Rendered headless at the recorded terminal size, 10 frames
//! per second of recorded time; written to a temporary file and renamed, so a failure leaves
//! nothing half-written.

use std::cell::RefCell;
use std::path::Path;
use std::rc::Rc;

use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::{Terminal, TerminalOptions, Viewport};

use crate::app::effects::commands;
use crate::app::journal::Event;
use crate::record::{RecordError, Recording, plan_book, start};
use crate::sim::{Engine, drive};
use crate::ui::{self, Cache, UiOptions};

/// Frames per second of the exported cast.
const CAST_FPS: f64 = 10.0;

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
/// `replace`). Returns the number of frames.
///
/// # Errors
/// A bad header preset, or the output cannot be written.
pub fn export_cast(
    rec: &Recording,
    path: &str,
    out: &Path,
    options: &UiOptions,
    replace: bool,
) -> Result<usize, RecordError> {
    let io = |source| RecordError::Io {
        path: out.display().to_string(),
        source,
    };
    let (mut app, start_effects) = start(rec, path)?;
    let size = rec.header.terminal;
    let area = Rect::new(0, 0, size.width.max(1), size.height.max(1));
    let screen = Shared::default();
    let mut terminal = Terminal::with_options(
        CrosstermBackend::new(screen.clone()),
        TerminalOptions {
            viewport: Viewport::Fixed(area),
        },
    )
    .map_err(io)?;
    let mut engine = Engine::new(plan_book(rec));
    drive(&mut engine, commands(start_effects), &mut |e| {
        app.on_sim(e);
    });
    crate::scenario::write::write_atomic_with(out, replace, &mut |cast| {
        frames_of(
            rec,
            &mut app,
            &mut engine,
            &mut terminal,
            &screen,
            options,
            cast,
        )
    })
    .map_err(io)
}

/// Writes the cast, frame by frame, into `cast` (streamed: nothing is kept but the screen).
/// Idle stretches (paused, no event due) are skipped in one jump, not drawn frame by frame.
fn frames_of(
    rec: &Recording,
    app: &mut crate::app::App,
    engine: &mut Engine,
    terminal: &mut Terminal<CrosstermBackend<Shared>>,
    screen: &Shared,
    options: &UiOptions,
    cast: &mut dyn std::io::Write,
) -> std::io::Result<usize> {
    let mut cache = Cache::default();
    let run = |effects: Vec<crate::app::Effect>, engine: &mut Engine, app: &mut crate::app::App| {
        drive(engine, commands(effects), &mut |e| {
            app.on_sim(e);
        });
    };
    let area = terminal.get_frame().area();
    let header = serde_json::json!({
        "version": 2,
        "width": area.width,
        "height": area.height,
        "title": format!("rattleback: {}", app.scenario.name),
        "env": {"TERM": "xterm-256color"},
    });
    writeln!(cast, "{header}")?;
    let end = rec.lines.last().map_or(0.0, |(_, l)| l.wall) + 1.0;
    let mut next = 0;
    let mut frames = 0;
    let mut clock = 0.0;
    while clock <= end {
        while next < rec.lines.len() && rec.lines[next].1.wall <= clock {
            let line = &rec.lines[next].1;
            if let Event::Chapter { title } = &line.event {
                writeln!(cast, "{}", serde_json::json!([line.wall, "m", title]))?;
            }
            let c = app.seek(line.t);
            run(c, engine, app);
            let c = app.apply_event(&line.event);
            run(c, engine, app);
            next += 1;
        }
        let c = app.tick(1.0 / CAST_FPS);
        run(c, engine, app);
        terminal.draw(|f| ui::draw(f, app, options, &mut cache))?;
        let bytes = std::mem::take(&mut *screen.0.borrow_mut());
        if !bytes.is_empty() {
            let text = String::from_utf8_lossy(&bytes);
            writeln!(cast, "{}", serde_json::json!([clock, "o", text]))?;
            frames += 1;
        }
        clock += 1.0 / CAST_FPS;
        // Nothing moves until the next event: jump there (on the frame grid).
        if !app.run.playing
            && let Some((_, l)) = rec.lines.get(next)
            && l.wall > clock
        {
            clock += ((l.wall - clock) * CAST_FPS).floor() / CAST_FPS;
        }
    }
    Ok(frames)
}
