//! The parameter panel: editable fields, the selection (reverse video, visible without
//! colour), the text being typed, derived values and the last message.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use super::Look;
use crate::app::App;
use crate::app::fields::{Field, format_number};

fn opt(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_owned(), format_number)
}

pub fn draw(frame: &mut Frame<'_>, area: Rect, app: &App, options: &Look) {
    let mut lines = Vec::new();
    for (i, field) in Field::ALL.iter().enumerate() {
        let selected = i == app.selected;
        let value = match (&app.editing, selected) {
            (Some(buffer), true) => format!("{buffer}▏"),
            _ => field.show(&app.settings),
        };
        let text = format!(
            "{} {:<10}{:>16}",
            if selected { "›" } else { " " },
            field.label(),
            value
        );
        let style = if selected {
            Style::default().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        } else {
            Style::default()
        };
        lines.push(Line::styled(text, style));
    }
    let d = &app.derived;
    let dim = Style::default().fg(options.theme.dim);
    lines.push(Line::raw(""));
    lines.push(Line::styled(
        format!("  theta     {:>16}", format_number(d.effective.theta())),
        dim,
    ));
    lines.push(Line::styled(
        format!("  ratio     {:>16}", opt(d.ratio)),
        dim,
    ));
    lines.push(Line::styled(
        format!("  critical  {:>16}", opt(d.critical)),
        dim,
    ));
    lines.push(Line::from(vec![
        Span::styled("  regime    ", dim),
        Span::styled(
            format!("{:>16}", d.effective.regime().name()),
            Style::default().add_modifier(Modifier::BOLD),
        ),
    ]));
    if let Some(prompt) = &app.saving {
        lines.push(Line::raw(""));
        lines.push(Line::styled(
            format!("save as: {}▏", prompt.name),
            Style::default().add_modifier(Modifier::REVERSED),
        ));
    }
    if let Some((text, error)) = &app.message {
        let style = if *error {
            Style::default()
                .fg(options.theme.error)
                .add_modifier(Modifier::BOLD)
        } else {
            Style::default()
        };
        lines.push(Line::raw(""));
        lines.push(Line::styled(text.clone(), style));
    }
    let block = Block::bordered().title(format!(" {} ", app.name));
    frame.render_widget(
        Paragraph::new(lines)
            .block(block)
            .wrap(Wrap { trim: false }),
        area,
    );
}
