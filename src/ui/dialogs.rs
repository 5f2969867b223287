//! Pop-ups: the preset picker (scrolling; each broken user file on its own row with its own
//! error), the error dialog, and the address a recording is served at with its QR code.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

use super::Look;
use crate::app::ellipsis;
use crate::app::mode::{Picker, PickerRow};

/// A `width × height` rectangle centred in `area`.
pub fn centred(area: Rect, width: u16, height: u16) -> Rect {
    let (w, h) = (width.min(area.width), height.min(area.height));
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

pub fn picker(frame: &mut Frame<'_>, area: Rect, p: &Picker, look: &Look) {
    let popup = centred(
        area,
        area.width.saturating_sub(8).min(100),
        area.height.saturating_sub(4),
    );
    let visible = p.visible();
    let place = visible
        .iter()
        .position(|&i| i == p.selected)
        .map_or(0, |i| i + 1);
    let block = Block::bordered()
        .title(super::title_middle(
            &format!(
                "presets {place}/{}: type to filter, ↑↓ Home End choose, Enter loads, Esc closes",
                visible.len(),
            ),
            popup.width,
        ))
        .title_bottom(format!(" filter: {}▏ ", p.filter));
    let inner = block.inner(popup);
    frame.render_widget(Clear, popup);
    frame.render_widget(block, popup);
    let [list, detail] = Layout::vertical([Constraint::Min(1), Constraint::Length(6)]).areas(inner);
    let height = list.height as usize;
    let first = p.first_visible(height);
    let width = list.width as usize;
    let mut lines = Vec::new();
    if visible.is_empty() {
        lines.push(Line::styled(
            format!(" nothing matches '{}' (Backspace, Esc clears)", p.filter),
            look.dim(),
        ));
    }
    for i in visible.into_iter().skip(first).take(height) {
        let row = &p.rows[i];
        let style = if i == p.selected {
            Style::default().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        } else {
            Style::default()
        };
        let text = match row {
            PickerRow::Preset(e) => {
                let source = if e.source == crate::scenario::shipped::Source::User {
                    "user"
                } else {
                    ""
                };
                format!(
                    " {:<18} {:<10} {:<4} {}",
                    e.name,
                    e.model.name(),
                    source,
                    e.title
                )
            }
            PickerRow::Broken { name, .. } => format!(" {name:<16} ✗    cannot be loaded"),
        };
        let style = if matches!(row, PickerRow::Broken { .. }) {
            style.fg(look.theme.error)
        } else {
            style
        };
        lines.push(Line::styled(ellipsis(&text, width), style));
    }
    frame.render_widget(Paragraph::new(lines), list);
    let (text, style) = match p.rows.get(p.selected) {
        Some(PickerRow::Preset(e)) => (e.description.clone(), look.dim()),
        Some(PickerRow::Broken { error, .. }) => {
            (error.clone(), Style::default().fg(look.theme.error))
        }
        None => (String::new(), Style::default()),
    };
    frame.render_widget(
        Paragraph::new(text)
            .style(style)
            .wrap(Wrap { trim: false })
            .block(Block::new().borders(ratatui::widgets::Borders::TOP)),
        detail,
    );
}

pub fn error(frame: &mut Frame<'_>, area: Rect, text: &str, look: &Look) {
    let popup = centred(area, 70, 10);
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(text.to_owned())
            .style(Style::default().fg(look.theme.error))
            .wrap(Wrap { trim: true })
            .block(Block::bordered().title(" error (Esc closes; other keys act) ")),
        popup,
    );
}

/// The address a recording is served at (`--serve`) and its QR code, light modules drawn in
/// white on black whatever the theme (a phone reads it from the projector); the address alone
/// where the code does not fit.
pub fn address(frame: &mut Frame<'_>, area: Rect, url: &str, look: &Look) {
    let ascii = look.charset != crate::ui::glyphs::Charset::Unicode;
    let code = super::qr::lines(url, ascii).unwrap_or_default();
    let code_width = code.first().map_or(0, |l| l.chars().count()) as u16;
    let fits =
        !code.is_empty() && code_width + 2 <= area.width && code.len() as u16 + 4 <= area.height;
    let mut lines: Vec<Line<'_>> = Vec::new();
    if fits {
        let qr = Style::default()
            .fg(ratatui::style::Color::White)
            .bg(ratatui::style::Color::Black);
        lines.extend(code.into_iter().map(|l| Line::styled(l, qr).centered()));
    }
    lines.push(Line::from(url.to_owned()).centered());
    let title = " served at (any key closes) ";
    let width = (url.chars().count().max(title.chars().count()) as u16)
        .max(if fits { code_width } else { 0 })
        .saturating_add(2)
        .min(area.width);
    let height = (lines.len() as u16 + 2).min(area.height);
    let popup = centred(area, width, height);
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines)
            .wrap(Wrap { trim: false })
            .block(Block::bordered().title(title)),
        popup,
    );
}
