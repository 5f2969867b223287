//! Whole screens rendered through ratatui's `TestBackend`, snapshotted with insta at 80×24 and
//! 160×48, with the colours and styles of key cells asserted separately.

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};

use rattleback::app::{App, Key, Options};
use rattleback::physics::Method;
use rattleback::scenario::shipped::resolve;
use rattleback::sim::{Session, SimEvent};
use rattleback::ui::{self, UiOptions};

/// The default preset, run synchronously to `t` (deterministic, no threads).
fn app_at(t: f64) -> App {
    preset_at("subcritical", t)
}

fn preset_at(name: &str, t: f64) -> App {
    let preset = resolve(name, &[]).expect("shipped preset");
    let (mut app, commands) = App::new(&preset, Options { fps: 30.0 });
    let spec = commands
        .iter()
        .find_map(|c| match c {
            rattleback::sim::Command::Restart { spec, .. } => Some(*spec),
            _ => None,
        })
        .expect("a restart");
    let mut session = Session::new(app.generation, spec);
    app.on_sim(SimEvent::Started {
        generation: app.generation,
        method: session.method(),
    });
    let (events, _) = session.advance(t, 0.02, usize::MAX);
    for e in events {
        app.on_sim(e);
    }
    app.reached = t;
    app
}

fn render(app: &mut App, width: u16, height: u16) -> Buffer {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| ui::draw(f, app, &UiOptions::default()))
        .unwrap();
    terminal.backend().buffer().clone()
}

fn text(buffer: &Buffer) -> String {
    let area = buffer.area;
    let mut out = String::new();
    for y in 0..area.height {
        for x in 0..area.width {
            out.push_str(buffer[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

fn find(buffer: &Buffer, needle: &str) -> Option<(u16, u16)> {
    let area = buffer.area;
    for y in 0..area.height {
        let row: String = (0..area.width)
            .map(|x| buffer[(x, y)].symbol().to_owned())
            .collect();
        if let Some(i) = row.find(needle) {
            let col = row[..i].chars().count() as u16;
            return Some((col, y));
        }
    }
    None
}

#[test]
fn screen_80x24_after_ten_seconds() {
    let mut app = app_at(10.0);
    let buffer = render(&mut app, 80, 24);
    insta::assert_snapshot!("screen_80x24", text(&buffer));
}

#[test]
fn screen_160x48_with_series_pane() {
    let mut app = app_at(10.0);
    app.on_key(Key::Char('t'));
    let buffer = render(&mut app, 160, 48);
    insta::assert_snapshot!("screen_160x48_series", text(&buffer));
}

#[test]
fn help_overlay_lists_the_bindings() {
    let mut app = app_at(0.0);
    app.on_key(Key::Char('?'));
    let buffer = render(&mut app, 80, 24);
    insta::assert_snapshot!("help_80x24", text(&buffer));
}

#[test]
fn key_cells_have_their_styles_and_colours() {
    let mut app = app_at(10.0);
    let buffer = render(&mut app, 80, 24);
    // The selected row is reverse video: visible without colour.
    let (x, y) = find(&buffer, "› ix").expect("selected row");
    assert!(buffer[(x + 2, y)].modifier.contains(Modifier::REVERSED));
    // The status bar is reverse video too.
    let (x, y) = find(&buffer, "reversals").expect("status bar");
    assert!(buffer[(x, y)].modifier.contains(Modifier::REVERSED));
    // The current point is red; the separatrix and the start's level have their colours.
    let (x, y) = find(&buffer, "●").expect("current point");
    assert_eq!(buffer[(x, y)].fg, Color::Red);
    let colours: Vec<Color> = buffer.content().iter().map(|c| c.fg).collect();
    for (colour, what) in [(Color::Yellow, "separatrix"), (Color::Green, "trail")] {
        assert!(colours.contains(&colour), "no {what} cell ({colour:?})");
    }
    // At k = 1e4 the limit's trail lies under the full one; with a soft spring they part.
    let soft = render(&mut preset_at("soft-spring", 20.0), 80, 24);
    assert!(
        soft.content().iter().any(|c| c.fg == Color::Magenta),
        "no effective-overlay cell"
    );
    // The trail runs along the start's own level and covers it; before it, the level shows.
    let fresh = render(&mut app_at(0.0), 80, 24);
    assert!(
        fresh.content().iter().any(|c| c.fg == Color::Cyan),
        "no start-level cell"
    );
}

#[test]
fn status_counts_reversals_and_names_the_chosen_method() {
    let mut app = app_at(10.0);
    let buffer = render(&mut app, 160, 48);
    let screen = text(&buffer);
    // Reversals of the limit before t = 10: 2.217 and 6.651.
    assert!(screen.contains("reversals 2 (limit 2)"), "{screen}");
    let chosen = app.method_in_use.expect("worker said");
    assert_ne!(chosen, Method::Auto);
    assert!(screen.contains(&format!("auto→{chosen}")), "{screen}");
}

#[test]
fn tiny_terminals_get_a_message_not_a_panic() {
    for (w, h) in [(20, 5), (79, 24), (80, 23), (1, 1)] {
        let mut app = app_at(0.0);
        let buffer = render(&mut app, w, h);
        if w >= 20 {
            assert!(text(&buffer).contains("too small"), "{w}x{h}");
        }
    }
}

#[test]
fn marker_option_changes_the_canvas() {
    let mut app = app_at(5.0);
    let mut terminal = Terminal::new(TestBackend::new(80, 24)).unwrap();
    let options = UiOptions {
        marker: ratatui::symbols::Marker::Dot,
        ..UiOptions::default()
    };
    terminal.draw(|f| ui::draw(f, &mut app, &options)).unwrap();
    let screen = text(terminal.backend().buffer());
    assert!(
        !screen
            .chars()
            .any(|c| ('\u{2801}'..='\u{28FF}').contains(&c)),
        "Braille with --marker dot"
    );
    assert!(screen.contains('•'), "dots expected");
}
