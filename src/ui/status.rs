//! The status bar: time and speed, reversals (full and effective), regime, method, energy
//! error and integration rate. Reverse video, so it reads without colour.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::widgets::Paragraph;

use super::Look;
use crate::app::App;

pub fn draw(frame: &mut Frame<'_>, area: Rect, app: &App, _options: &Look) {
    let state = if app.failed.is_some() {
        "failed"
    } else if app.finished {
        "done"
    } else if app.playing {
        "▶"
    } else {
        "paused"
    };
    let energy = app.current().map_or(0.0, |p| p.energy_error);
    let limit = if app.show_effective {
        format!(" (limit {})", app.effective_reversals.len())
    } else {
        String::new()
    };
    let method = match app.method_in_use {
        Some(m) if m != app.settings.method => format!("{}→{m}", app.settings.method),
        _ => app.settings.method.to_string(),
    };
    let text = format!(
        " t {:.3}/{} ×{} {state} │ reversals {}{limit} │ {} │ {} │ ΔE/E {:.1e} │ {} steps/s",
        app.reached,
        app.settings.t_end,
        app.speed,
        app.reversals.len(),
        app.derived.effective.regime().name(),
        method,
        energy,
        human(app.rate),
    );
    frame.render_widget(
        Paragraph::new(text).style(Style::default().add_modifier(Modifier::REVERSED)),
        area,
    );
}

fn human(v: f64) -> String {
    if v >= 1e6 {
        format!("{:.1}M", v / 1e6)
    } else if v >= 1e3 {
        format!("{:.1}k", v / 1e3)
    } else {
        format!("{v:.0}")
    }
}
