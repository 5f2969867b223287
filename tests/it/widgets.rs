//! Issue 83: the status bar, the parameter panel and the legend drawn alone into a buffer and
//! compared with the buffer they must give, cell for cell (text and style), as ratatui's own
//! widget tests do (`Buffer::with_lines`).

use crate::common::Headless;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::widgets::{Paragraph, Widget};

use rattleback::ui::{UiOptions, params::ParamsPanel, status::StatusBar};

fn status(h: &Headless, width: u16) -> Buffer {
    let app = &h.app;
    let mut buf = Buffer::empty(Rect::new(0, 0, width, 1));
    StatusBar {
        run: &app.run,
        settings: &app.scenario.settings,
        replay: app.replay,
        recording: false,
        overlay: app.view.overlay,
    }
    .render(buf.area, &mut buf);
    buf
}

/// The bar in reverse video: every cell of the area, padded.
fn reversed(text: &str, width: u16) -> Buffer {
    let mut want = Buffer::with_lines([format!("{text:<w$}", w = width as usize)]);
    want.set_style(want.area, Style::default().add_modifier(Modifier::REVERSED));
    want
}

#[test]
fn the_status_bar_is_its_fields_in_reverse_video_dropping_whole_fields_when_narrow() {
    let h = Headless::new("subcritical");
    assert_eq!(
        status(&h, 80),
        reversed(
            " t 0.00/30 │ paused │ ×1 │ reversals 0 limit 0 │ ΔE/E 0.0e0 │ est 5e-11 ✓",
            80
        )
    );
    // Narrow: whole fields go by priority (the energy monitor, then the counts), a number is
    // never cut.
    assert_eq!(
        status(&h, 40),
        reversed(" t 0.00/30 │ paused │ ×1 │ est 5e-11 ✓", 40)
    );
    let h = Headless::new("kapitza-upright");
    assert_eq!(
        status(&h, 80),
        reversed(
            " t 0.00/20 │ paused │ ×1 │ swings 0 limit 0 │ falls 0 │ est 2e-10 ✓",
            80
        )
    );
}

#[test]
fn the_panel_shows_each_parameter_right_aligned_under_its_title() {
    let h = Headless::new("kapitza-upright");
    let options = UiOptions::default();
    let look = options.look(h.app.view.theme);
    let mut buf = Buffer::empty(Rect::new(0, 0, 30, 8));
    ParamsPanel {
        scenario: &h.app.scenario,
        editing: None,
        prompt: None,
        hide_predictions: false,
        look: &look,
    }
    .render(buf.area, &mut buf);
    // Its text cell for cell (the styles are the theme's: `presets_themes` checks them).
    let mut plain = buf.clone();
    plain.set_style(plain.area, Style::reset());
    let mut want = Buffer::with_lines([
        "┌ Kapitza: upright … stable ─┐",
        "│› a                        1│",
        "│  b                        2│",
        "│  epsilon           1.000e-3│",
        "│  theta                  0.3│",
        "│  theta_dot                0│",
        "│  t_end                   20│",
        "└────────────────── ↓ 6 more ┘",
    ]);
    want.set_style(want.area, Style::reset());
    assert_eq!(plain, want);
    // The selected row stands out from the others.
    assert_ne!(
        buf[(3, 1)].style(),
        buf[(3, 2)].style(),
        "the selection is marked"
    );
}

#[test]
fn the_legend_is_the_scenes_words() {
    let h = Headless::new("celt-clockwise");
    let options = UiOptions::default();
    let text = rattleback::ui::help::legend_text(&h.app, &options);
    let mut buf = Buffer::empty(Rect::new(0, 0, 62, 6));
    Paragraph::new(
        text.iter()
            .take(6)
            .map(String::as_str)
            .collect::<Vec<_>>()
            .join("\n"),
    )
    .render(buf.area, &mut buf);
    let mut want = Buffer::with_lines([
        " phase portrait: φ across, ω·γ up",
        " ⣀⣤⣀⣤ the motion (dense dots)",
        " ●    the displayed point",
        " ⠒ ⠒  the largest spin the start's energy allows, either sense",
        "      (dashed)",
        " w wraps the angle to one period; z/Z zoom, shift+arrows pan",
    ]);
    // Plain text: the paragraph resets the colours it draws on.
    want.set_style(want.area, Style::reset());
    assert_eq!(buf, want, "{}", text.join("\n"));
}
