//! Pop-ups: the preset picker (names and what to look for) and the error dialog.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

use super::Look;
use crate::app::App;

fn centred(area: Rect, width: u16, height: u16) -> Rect {
    let (w, h) = (width.min(area.width), height.min(area.height));
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

pub fn picker(frame: &mut Frame<'_>, area: Rect, app: &App, look: &Look) {
    let Some(p) = &app.picker else { return };
    let popup = centred(
        area,
        area.width.saturating_sub(8).min(100),
        area.height.saturating_sub(4),
    );
    let mut lines = Vec::new();
    for (i, e) in p.entries.iter().enumerate() {
        let style = if i == p.selected {
            Style::default().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        } else {
            Style::default()
        };
        let source = if e.source == crate::scenario::shipped::Source::User {
            "user"
        } else {
            ""
        };
        lines.push(Line::styled(
            format!(" {:<16} {:<4} {}", e.name, source, e.title),
            style,
        ));
    }
    if let Some(e) = p.entries.get(p.selected) {
        lines.push(Line::raw(""));
        lines.push(Line::from(Span::styled(
            e.description.clone(),
            Style::default().fg(look.theme.dim),
        )));
    }
    for problem in &p.problems {
        lines.push(Line::styled(
            problem.clone(),
            Style::default().fg(look.theme.error),
        ));
    }
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines)
            .wrap(Wrap { trim: false })
            .block(Block::bordered().title(" presets: ↑/↓ choose, Enter load, Esc close ")),
        popup,
    );
}

pub fn error(frame: &mut Frame<'_>, area: Rect, text: &str, look: &Look) {
    let popup = centred(area, 70, 10);
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(text.to_owned())
            .style(Style::default().fg(look.theme.error))
            .wrap(Wrap { trim: true })
            .block(Block::bordered().title(" error (any key closes) ")),
        popup,
    );
}
