//! The legend's parts: a [`Mark`] and what it means, a pane's [`Section`] of them, the
//! [`Facts`] of the scene on screen, and the characters a curve or a point is drawn with. Each
//! widget builds its own section from these (`portrait::legend`, `status::legend`, …); the
//! legend (`legend.rs`) gathers the sections of the scene's panes.

use ratatui::style::Color;
use ratatui::symbols::Marker;

use super::Look;
use crate::physics::{LimitView, ModelKind};

/// One mark and what it means.
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    /// The characters as drawn (already in the character set).
    pub glyph: String,
    /// Its colour.
    pub colour: Color,
    /// What it means (spelled when the legend is laid out).
    pub what: String,
}

/// What one pane (or the status bar) draws.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// The pane's name and key.
    pub title: String,
    /// Its marks.
    pub marks: Vec<Mark>,
    /// Lines of text (the status bar's fields, the axes).
    pub notes: Vec<String>,
}

impl Section {
    /// An empty section titled `title`.
    #[must_use]
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            marks: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Adds a mark.
    #[must_use]
    pub fn mark(
        mut self,
        glyph: impl Into<String>,
        colour: Color,
        what: impl Into<String>,
    ) -> Self {
        self.marks.push(Mark {
            glyph: glyph.into(),
            colour,
            what: what.into(),
        });
        self
    }

    /// Adds a line of text.
    #[must_use]
    pub fn note(mut self, text: impl Into<String>) -> Self {
        self.notes.push(text.into());
        self
    }
}

/// What a scene's legend depends on.
#[derive(Clone, Copy, Debug)]
pub struct Facts<'a> {
    /// The scene.
    pub kind: ModelKind,
    /// What the portrait draws of its limit (the levels and separatrices there are).
    pub limit: &'a LimitView,
    /// What the body pane draws (the celt's body from the side too; the pendulum).
    pub drawing: crate::physics::scene::Drawing,
    /// The panel's derived lines.
    pub summary: &'a [crate::physics::scene::SummaryLine],
}

/// A curve's mark: with one point per cell, its own character in the set in use; else a sample
/// of what the marker draws (Braille dots, half blocks) in the given pattern.
#[must_use]
pub fn curve(look: &Look<'_>, cell: char, braille: &str, halfblock: &str) -> String {
    match look.marker {
        Marker::Braille => braille.to_owned(),
        Marker::HalfBlock => halfblock.to_owned(),
        _ => look.charset.mark(cell).to_string(),
    }
}

/// ` (how)`, the pattern a curve's words name (`dense dots`, `solid`, `dashed`), where the
/// marker draws patterns; nothing where each curve is one character (ASCII, the Linux console:
/// issue 68, the legend said "dense dots" beside a `*`).
#[must_use]
pub fn pattern(look: &Look<'_>, how: &str) -> String {
    match look.marker {
        Marker::Braille | Marker::HalfBlock => format!(" ({how})"),
        _ => String::new(),
    }
}

/// A mark printed as text (not a canvas point), in the set in use.
#[must_use]
pub fn printed(look: &Look<'_>, c: char) -> String {
    look.charset.mark(c).to_string()
}

/// A trace of signed points printed on a canvas: `glyphs.0` where the sign is positive (the
/// trail's colour), `glyphs.1` where it is not (the reversal's), so a change of sign reads as a
/// change of mark (the body's ring, the pendulum's bob).
pub fn print_signed(
    ctx: &mut ratatui::widgets::canvas::Context<'_>,
    trace: &[(f64, f64, bool)],
    glyphs: (char, char),
    theme: &super::Theme,
) {
    use ratatui::style::Style;
    use ratatui::text::Line;
    for &(x, y, positive) in trace {
        let (glyph, colour) = if positive {
            (glyphs.0, theme.trail)
        } else {
            (glyphs.1, theme.reversal)
        };
        ctx.print(
            x,
            y,
            Line::styled(glyph.to_string(), Style::default().fg(colour)),
        );
    }
}
