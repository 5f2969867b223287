//! The legend: what every mark, line and status field means, in the scene on screen and the
//! characters in use. Each widget says what it draws ([`Section`]s from `portrait::legend`,
//! `series::legend`, …, built from the same constants it draws with), the legend lists the
//! sections of the panes the scene offers, so a scene never inherits another's words, and every
//! mark is the character the terminal is sent (Braille samples, or one character per curve on
//! the console and in ASCII), its text spelled for the character set (`k -> inf` in ASCII).

use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};

use super::Look;
use super::marks::{Facts, Section};
use crate::app::panes::Pane;

/// The sections of the scene's legend: the portrait, then every pane the scene offers, then the
/// status bar.
#[must_use]
pub fn sections(facts: &Facts<'_>, look: &Look<'_>) -> Vec<Section> {
    let mut out = vec![
        super::portrait::legend(facts, look),
        super::params::legend(facts, look),
    ];
    for pane in Pane::KEYED {
        if pane.offered_by(facts.kind)
            && let Some(section) = super::pane_legend(pane, facts, look)
        {
            out.push(section);
        }
    }
    out.push(super::status::legend(facts, look));
    out
}

/// Columns of the legend's text (the help overlay is 66 wide).
const WIDTH: usize = 62;

/// The legend as the help overlay's lines, its text spelled for the character set; a long
/// description wraps under itself, not under the mark.
#[must_use]
pub fn lines(facts: &Facts<'_>, look: &Look<'_>) -> Vec<Line<'static>> {
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let spell = |t: &str| look.charset.spell(t);
    let mut out = Vec::new();
    for (i, s) in sections(facts, look).into_iter().enumerate() {
        if i > 0 {
            out.push(Line::raw(""));
        }
        out.push(Line::styled(format!(" {}", spell(&s.title)), bold));
        for m in s.marks {
            let width = m.glyph.chars().count().max(4) + 1;
            let style = if look.no_color {
                Style::default()
            } else {
                Style::default().fg(m.colour)
            };
            let text = super::wrap_words(&spell(&m.what), WIDTH - width, 4);
            for (j, part) in text.into_iter().enumerate() {
                let head = if j == 0 {
                    Span::styled(
                        format!(
                            " {}{}",
                            m.glyph,
                            " ".repeat(width - m.glyph.chars().count())
                        ),
                        style,
                    )
                } else {
                    Span::raw(" ".repeat(width + 1))
                };
                out.push(Line::from(vec![head, Span::raw(part)]));
            }
        }
        for n in s.notes {
            for part in super::wrap_words(&spell(&n), WIDTH, 4) {
                out.push(Line::raw(format!(" {part}")));
            }
        }
    }
    out
}
