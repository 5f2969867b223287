//! The parameter panel: editable fields (the selection in reverse video, visible without
//! colour), the text being typed or the open prompt (labelled by what it is for), the limit's
//! derived values and the last message. Any value fits: the label gives way to a long value.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget, Wrap};

use super::Look;
use super::marks::{Facts, Section};
use crate::app::Scenario;
use crate::app::fields::{Field, format_number};
use crate::app::mode::Prompt;
use crate::physics::scene::Shown;

/// The parameter panel: what it shows, borrowed.
pub struct ParamsPanel<'a> {
    /// Name, settings, derived values, selection.
    pub scenario: &'a Scenario,
    /// The value being typed, if any.
    pub editing: Option<&'a str>,
    /// The open prompt, if any.
    pub prompt: Option<&'a Prompt>,
    /// A lesson's question is open: the predictions are shown without their values.
    pub hide_predictions: bool,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

/// What a prediction shows while a lesson's question is open.
pub const HIDDEN: &str = "?";

fn opt(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_owned(), format_number)
}

/// `label` and `value` on one row of `width` columns, the value right-aligned; the label is
/// shortened with `…` only if the value needs the room.
fn row(marker: &str, label: &str, value: &str, width: usize) -> String {
    let value_w = value.chars().count();
    let room = width.saturating_sub(marker.chars().count() + value_w + 1);
    let label = crate::app::ellipsis(label, room);
    let pad = width.saturating_sub(marker.chars().count() + label.chars().count() + value_w);
    format!("{marker}{label}{}{value}", " ".repeat(pad))
}

impl Widget for ParamsPanel<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        panel(&self, area, buf);
    }
}

/// The read-only lines under the parameters: what the model derives from them.
fn derived_lines(p: &ParamsPanel<'_>, width: usize) -> Vec<Line<'static>> {
    let look = p.look;
    let mut lines = Vec::new();
    let d = &p.scenario.derived;
    let dim = look.dim();
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let verdict = |label: &str, value: &str| {
        Line::from(vec![
            Span::styled(format!("  {label}"), dim),
            Span::styled(
                format!(
                    "{:>w$}",
                    value,
                    w = width.saturating_sub(label.chars().count() + 2)
                ),
                bold,
            ),
        ])
    };
    for line in &d.summary {
        if line.predicts && p.hide_predictions {
            lines.push(Line::styled(row("  ", line.label, HIDDEN, width), dim));
            continue;
        }
        lines.push(match line.value {
            Shown::Number(v) => Line::styled(row("  ", line.label, &opt(v), width), dim),
            Shown::Percent(v) => {
                let side = v.map_or_else(|| "-".to_owned(), |x| format!("{:+.3}%", 100.0 * x));
                Line::styled(row("  ", line.label, &side, width), dim)
            }
            Shown::Verdict(v) => verdict(line.label, v),
        });
    }
    lines
}

/// What the panel shows, for the legend: the scene's derived lines, each with its meaning.
#[must_use]
pub fn legend(f: &Facts<'_>, _look: &Look<'_>) -> Section {
    let mut s = Section::new("panel (left): the parameters, then what they give")
        .note("up and down select, left and right change (H L coarse), Enter types a value");
    for line in f.summary {
        s = s.note(format!("{}: {}", line.label, line.meaning));
    }
    s.note("an arrow and a count on its border: rows out of sight above or below; selecting the last parameter (↑ from the first) brings the rows below it into sight")
}

/// The edit cursor after a typed value.
pub const CURSOR: char = '▏';

fn panel(p: &ParamsPanel<'_>, area: Rect, buf: &mut Buffer) {
    let width = area.width.saturating_sub(2) as usize;
    let mut lines = Vec::new();
    for (i, field) in Field::rows(p.scenario.settings.model.kind())
        .iter()
        .enumerate()
    {
        let selected = i == p.scenario.selected;
        let value = match (p.editing, selected) {
            (Some(buffer), true) => format!("{buffer}{CURSOR}"),
            _ => field.show(&p.scenario.settings),
        };
        let text = row(
            if selected { "› " } else { "  " },
            field.label(),
            &value,
            width,
        );
        let style = if selected {
            Style::default().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        } else {
            Style::default()
        };
        lines.push(Line::styled(text, style));
    }
    lines.extend(derived_lines(p, width));
    if let Some(prompt) = p.prompt {
        lines.push(Line::styled(
            format!("{}: {}{CURSOR}", prompt.purpose.label(), prompt.text),
            Style::default().add_modifier(Modifier::REVERSED),
        ));
    }
    // Taller than the panel: the selection (or the open prompt) stays in sight, and the border
    // says how many rows are out of sight above and below.
    let rows = area.height.saturating_sub(2) as usize;
    let total = lines.len();
    let first = if total <= rows {
        0
    } else if p.prompt.is_some() {
        total - rows
    } else if p.scenario.selected + 1 == Field::rows(p.scenario.settings.model.kind()).len() {
        // The last parameter selected: the rows below it come into sight (at 80×24 the celt's
        // derived rows, issue 68), so ↑ from the first row shows them.
        total - rows
    } else {
        (p.scenario.selected + 2)
            .saturating_sub(rows)
            .min(total - rows)
    };
    let mut block = Block::bordered().title(super::title_middle(&p.scenario.name, area.width));
    let below = total.saturating_sub(first + rows);
    if first > 0 {
        block = block.title(Line::from(format!(" ↑{first} ")).right_aligned());
    }
    if below > 0 {
        block = block.title_bottom(Line::from(format!(" ↓ {below} more ")).right_aligned());
    }
    let shown: Vec<Line> = lines.into_iter().skip(first).take(rows.max(1)).collect();
    Paragraph::new(shown)
        .block(block)
        .wrap(Wrap { trim: false })
        .render(area, buf);
}

#[cfg(test)]
mod tests {
    use super::row;

    #[test]
    fn long_values_push_the_label_aside_never_out() {
        assert_eq!(
            row("› ", "method", "auto", 28),
            "› method                auto"
        );
        let r = row("› ", "method", "effective-corrected", 28);
        assert_eq!(r, "› method effective-corrected");
        let r = row("  ", "tolerance", "a-very-long-value-here", 28);
        assert!(
            r.ends_with("a-very-long-value-here") && r.contains('…'),
            "{r}"
        );
        assert_eq!(r.chars().count(), 28);
    }
}
