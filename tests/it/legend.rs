//! Issue 54: every scene explains itself in every terminal. The legend (`?` `?`) is generated
//! from what the scene's panes and status bar draw, so the celt and the pendulum never speak
//! with the rattleback's words; its marks are the characters the terminal is sent (Unicode,
//! the Linux console, ASCII), and every mark a plot draws is in it. ASCII spells `->`, `>=`,
//! `inf`; the time series' axis, trace and ticks are distinct characters.

use std::collections::BTreeSet;

use crate::common::Headless;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

use rattleback::app::Key;
use rattleback::app::panes::Pane;
use rattleback::ui::glyphs::{CONSOLE, Charset};
use rattleback::ui::{self, Cache, UiOptions};

const SETS: [Charset; 3] = [Charset::Unicode, Charset::Console, Charset::Ascii];

fn options(charset: Charset) -> UiOptions {
    UiOptions::default().with_charset(charset)
}

fn legend(h: &Headless, charset: Charset) -> String {
    ui::help::legend_text(&h.app, &options(charset)).join("\n")
}

fn render(h: &Headless, width: u16, height: u16, charset: Charset) -> Buffer {
    let options = options(charset);
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| ui::draw(f, &h.app, &options, &mut Cache::default()))
        .unwrap();
    terminal.backend().buffer().clone()
}

/// The words each scene's legend must have and must not have, per character set.
fn words(scene: &str, charset: Charset) -> (Vec<&'static str>, Vec<&'static str>) {
    match scene {
        "subcritical" => (
            vec![
                match charset {
                    Charset::Ascii => "k -> inf",
                    Charset::Console => "k → inf",
                    Charset::Unicode => "k → ∞",
                },
                "separatrix",
                "reversals N limit M",
                "regime map",
                "weak-*",
                "vs critical",
            ],
            vec!["swings", "falls", "crossings", "ε"],
        ),
        "kapitza-upright" => (
            vec![
                match charset {
                    Charset::Ascii => "eps -> 0",
                    Charset::Console => "eps → 0",
                    Charset::Unicode => "ε → 0",
                },
                "swings N limit M",
                "falls N",
                "b^2-2a",
                "weak-*",
            ],
            vec![
                "k → ∞",
                "k -> inf",
                "crossings",
                "regime map",
                "vs critical",
            ],
        ),
        _ => (
            vec![
                "crossings N",
                "reversals N",
                "largest spin",
                "body (B)",
                "skew",
            ],
            vec![
                "k → ∞",
                "k -> inf",
                "separatrix",
                "E_eff",
                "swings",
                "falls",
                "regime map",
                "weak-*",
                "limit M",
            ],
        ),
    }
}

/// Each scene's legend speaks of its own scene, in every character set; nothing a set cannot
/// show is left in it (ASCII: spelled, never `?`).
#[test]
fn each_scene_has_its_own_legend_in_every_character_set() {
    for scene in ["subcritical", "kapitza-upright", "celt-clockwise"] {
        let h = Headless::new(scene);
        for charset in SETS {
            let text = legend(&h, charset);
            let (must, never) = words(scene, charset);
            for w in must {
                assert!(text.contains(w), "{scene} {charset:?} lacks {w:?}:\n{text}");
            }
            for w in never {
                assert!(!text.contains(w), "{scene} {charset:?} has {w:?}:\n{text}");
            }
            match charset {
                Charset::Ascii => {
                    assert!(text.is_ascii(), "{scene}: not ASCII:\n{text}");
                    assert!(!text.contains('?') || text.contains("? or Esc"), "{text}");
                }
                Charset::Console => {
                    let bad: BTreeSet<char> = text
                        .chars()
                        .filter(|c| !c.is_ascii() && !CONSOLE.contains(*c))
                        .collect();
                    assert!(bad.is_empty(), "{scene}: {bad:?} not in the console fonts");
                }
                Charset::Unicode => {}
            }
        }
    }
}

/// The marks the legend lists for `pane`, as drawn in `charset`.
fn marks(h: &Headless, pane: Pane, charset: Charset) -> BTreeSet<char> {
    let options = options(charset);
    let look = options.look(0);
    let model = &h.app.scenario.settings.model;
    let facts = ui::marks::Facts {
        kind: model.kind(),
        limit: &h.app.scenario.derived.limit,
        drawing: model.drawing(),
        summary: &h.app.scenario.derived.summary,
    };
    ui::pane_legend(pane, &facts, &look)
        .map(|s| {
            s.marks
                .iter()
                .flat_map(|m| m.glyph.chars().map(|c| charset.mark(c)).collect::<Vec<_>>())
                .filter(|c| !c.is_whitespace())
                .collect()
        })
        .unwrap_or_default()
}

/// The characters drawn in a plot's area: inside the border, right of the 8 label columns,
/// above the axis row.
fn drawn(buf: &Buffer, area: Rect) -> BTreeSet<char> {
    let mut out = BTreeSet::new();
    for y in area.y + 1..area.y + area.height.saturating_sub(2) {
        for x in area.x + 9..area.x + area.width.saturating_sub(1) {
            out.extend(buf[(x, y)].symbol().chars());
        }
    }
    out.remove(&' ');
    out
}

/// Every mark a plot draws is explained in the legend, in the characters it is drawn with:
/// each scene, each pane with a plot (the portrait, the series, the sweep, weak-* and the map),
/// played to the end, in ASCII, on the console and in Unicode (Braille dots apart).
#[test]
fn every_mark_a_plot_draws_is_in_the_legend() {
    for scene in ["subcritical", "kapitza-upright", "celt-clockwise"] {
        let mut h = Headless::new(scene);
        h.play_until(f64::INFINITY, 1024.0);
        let kind = h.app.scenario.settings.model.kind();
        for (pane, key) in [
            (Pane::Series, 't'),
            (Pane::Sweep, 'K'),
            (Pane::Weak, 'W'),
            (Pane::Map, 'M'),
        ] {
            if !pane.offered_by(kind) {
                continue;
            }
            h.key(Key::Char(key));
            if pane == Pane::Map {
                h.key(Key::Esc);
            }
            for charset in SETS {
                let buf = render(&h, 120, 48, charset);
                let right = ui::screen(&h.app, Rect::new(0, 0, 120, 48)).right;
                let layout = ui::column_layout(&h.app, right);
                assert!(
                    layout.panes.iter().any(|(p, _)| *p == pane),
                    "{scene}: {pane:?} drawn"
                );
                for (p, area) in &layout.panes {
                    let listed = marks(&h, *p, charset);
                    let unexplained: BTreeSet<char> = drawn(&buf, *area)
                        .into_iter()
                        .filter(|c| !listed.contains(c) && !('\u{2800}'..='\u{28ff}').contains(c))
                        .collect();
                    assert!(
                        unexplained.is_empty(),
                        "{scene} {charset:?} {p:?}: {unexplained:?} drawn but not in its legend {listed:?}"
                    );
                }
            }
            h.key(Key::Char(key));
        }
    }
}

/// In ASCII the time series' zero axis, trace, reversal ticks and energy error are four
/// characters (issue 54: the axis and the trace were both `*`), and the edit cursor is `_`.
#[test]
fn the_time_series_keeps_its_curves_apart_in_ascii() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('t'));
    h.play_until(12.0, 4.0);
    h.key(Key::Char(' '));
    let buf = render(&h, 120, 48, Charset::Ascii);
    let area = ui::column_layout(&h.app, ui::screen(&h.app, Rect::new(0, 0, 120, 48)).right)
        .panes
        .into_iter()
        .find(|(p, _)| *p == Pane::Series)
        .unwrap()
        .1;
    let seen = drawn(&buf, area);
    for c in ['-', '*', '|', 'o', '.'] {
        assert!(seen.contains(&c), "{c:?} not drawn: {seen:?}");
    }
    // The time axis has round ticks.
    let axis: String = (area.x..area.x + area.width)
        .map(|x| buf[(x, area.y + area.height - 2)].symbol().to_owned())
        .collect();
    let ticks: Vec<&str> = axis
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .collect();
    assert!(
        ticks.len() >= 3 && ticks.iter().all(|t| t.parse::<u32>().is_ok()),
        "{axis:?}"
    );
    // The edit cursor.
    h.key(Key::Enter);
    h.key(Key::Char('3'));
    let screen = render(&h, 80, 24, Charset::Ascii);
    let text: String = screen
        .content
        .iter()
        .map(ratatui::buffer::Cell::symbol)
        .collect();
    assert!(text.contains("3_"), "the edit cursor in ASCII");
}

/// The screen's text.
fn text(buf: &Buffer) -> String {
    let mut out = String::new();
    for y in 0..buf.area.height {
        for x in 0..buf.area.width {
            out.push_str(buf[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

/// Each scene's legend at 80×24, in Unicode and in ASCII, page by page as a user scrolls it
/// (the scroll mark in the bottom border), pinned as snapshots.
#[test]
fn each_scenes_legend_at_80x24_in_unicode_and_ascii() {
    let area = Rect::new(0, 0, 80, 24);
    for scene in ["subcritical", "kapitza-upright", "celt-clockwise"] {
        for (charset, name) in [(Charset::Unicode, "unicode"), (Charset::Ascii, "ascii")] {
            let mut h = Headless::new(scene);
            h.key(Key::Char('?'));
            h.key(Key::Char('?'));
            let mut pages = Vec::new();
            loop {
                let page = text(&render(&h, 80, 24, charset));
                h.app
                    .fit_help(ui::help::max_scroll(&h.app, area, &options(charset)));
                let last = pages.last() == Some(&page);
                if last {
                    break;
                }
                pages.push(page);
                h.key(Key::PageDown);
                assert!(pages.len() < 10, "the legend never ends");
            }
            assert!(pages.len() >= 2, "{scene}: the legend scrolls at 80x24");
            if charset == Charset::Ascii {
                assert!(pages.iter().all(|p| p.is_ascii()), "{scene}: ASCII");
            }
            insta::assert_snapshot!(format!("legend_{scene}_{name}_80x24"), pages.join("\n"));
        }
    }
}
