//! A scene's own figure in the body pane (issue 83, `physics::scene::Drawing::Figure`): the
//! shapes the scene gives for the point shown, drawn in its square with the theme's colours,
//! and its legend from the scene's words. A body of a new kind needs no edit here.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::Line as TextLine;
use ratatui::widgets::Widget;
use ratatui::widgets::canvas::Line;

use super::marks::{Section, curve};
use super::{Look, Theme, framed};
use crate::app::RunState;
use crate::physics::flow::Sample;
use crate::physics::scene::{Figure, Ink, Shape};

/// The figure's square has half-side 1; the pane shows this much about the origin.
const REACH: f64 = 1.15;

/// The theme's colour for `ink`.
fn colour(theme: &Theme, ink: Ink) -> Color {
    match ink {
        Ink::Body => theme.trail,
        Ink::Fixed => theme.separatrix,
        Ink::Current => theme.current,
        Ink::Event => theme.reversal,
        Ink::Dim => theme.dim,
    }
}

/// The legend of a scene's figure: its title and each ink's words.
#[must_use]
pub fn legend(figure: &Figure, look: &Look<'_>) -> Section {
    let mut s = Section::new(format!("{} (B)", figure.title));
    for &(ink, what) in figure.legend {
        s = s.mark(
            curve(look, '•', "⠒⠒⠒", "▀▀▀"),
            colour(look.theme, ink),
            what,
        );
    }
    s
}

/// The body pane drawing a scene's [`Figure`].
pub struct FigurePane<'a> {
    /// The run (its displayed samples).
    pub run: &'a RunState,
    /// The scene's figure.
    pub figure: Figure,
    /// The scene's counted events, for the heading.
    pub events: &'a str,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

impl Widget for FigurePane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        // The point shown, or the origin at rest before the first.
        let now = self.run.current();
        let t = now.map_or(0.0, |p| p.t);
        let sample = Sample {
            q: now.map_or(0.0, |p| p.slow),
            q_dot: now.map_or(0.0, |p| p.rate),
            fast: now.map_or(0.0, |p| p.fast),
            lean: now.and_then(|p| p.lean),
        };
        let heading = format!(
            "{} (B): {} {}",
            self.figure.title,
            self.events,
            self.run.reversals_shown()
        );
        let inner = framed(&heading, area, buf);
        if inner.width < 4 || inner.height < 3 {
            return;
        }
        let shapes = (self.figure.shapes)(&self.figure.knobs, t, &sample);
        let theme = self.look.theme;
        let (sx, sy) = super::axis::round_bounds(inner, REACH);
        super::glyphs::canvas(self.look, [-sx, sx], [-sy, sy], |ctx| {
            for shape in &shapes {
                if let Shape::Line { from, to, ink } = *shape
                    && [from.0, from.1, to.0, to.1].iter().all(|v| v.is_finite())
                {
                    ctx.draw(&Line::new(from.0, from.1, to.0, to.1, colour(theme, ink)));
                }
            }
            ctx.layer();
            for shape in &shapes {
                if let Shape::Glyph { at, glyph, ink } = *shape
                    && at.0.is_finite()
                    && at.1.is_finite()
                    && !glyph.is_control()
                {
                    let mut style = Style::default().fg(colour(theme, ink));
                    if ink == Ink::Current {
                        style = style.add_modifier(Modifier::BOLD);
                    }
                    // In the set in use (an ASCII terminal gets its likeness).
                    let shown = self.look.charset.mark(glyph);
                    ctx.print(at.0, at.1, TextLine::styled(shown.to_string(), style));
                }
            }
        })
        .render(inner, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::ModelKind;
    use crate::physics::scene::Drawing;
    use crate::sim::Point;
    use ratatui::symbols::Marker;

    fn look(theme: &Theme) -> Look<'_> {
        Look {
            theme,
            marker: Marker::Braille,
            no_color: false,
            charset: crate::ui::glyphs::Charset::Unicode,
        }
    }

    /// `figure` drawn with the sample's slow coordinate at `q`, as text rows.
    fn drawn(figure: Figure, q: f64, width: u16, height: u16) -> Vec<String> {
        drawn_in(
            figure,
            q,
            width,
            height,
            crate::ui::glyphs::Charset::Unicode,
        )
    }

    /// [`drawn`] in the character set `charset`.
    fn drawn_in(
        figure: Figure,
        q: f64,
        width: u16,
        height: u16,
        charset: crate::ui::glyphs::Charset,
    ) -> Vec<String> {
        let mut run = RunState::new(10.0);
        run.trail = vec![Point {
            t: 1.0,
            slow: q,
            rate: 0.0,
            energy_error: 0.0,
            fast: 0.0,
            lean: None,
        }];
        run.shown = 1.0;
        let theme = Theme::default();
        let look = Look {
            charset,
            ..look(&theme)
        };
        let area = Rect::new(0, 0, width, height);
        let mut buf = Buffer::empty(area);
        FigurePane {
            run: &run,
            figure,
            events: "events",
            look: &look,
        }
        .render(area, &mut buf);
        (0..height)
            .map(|y| (0..width).map(|x| buf[(x, y)].symbol()).collect())
            .collect()
    }

    /// Issue 83: a scene's own figure is drawn from its shapes alone, for every registered
    /// scene that has one (the test oscillator draws a mass on a spring): its first glyph is
    /// printed, and lies left or right as its shapes put it for two samples; the heading names
    /// the figure; the legend says the scene's words; too small a pane draws no glyph and does
    /// not panic.
    #[test]
    fn every_scenes_own_figure_is_drawn_where_its_shapes_say() {
        let (width, height) = (40, 12);
        let mut figures = 0;
        for kind in ModelKind::ALL {
            // The defaults, and 1 for a row a preset must give.
            let defaults: Vec<f64> = kind
                .params()
                .iter()
                .map(|p| if p.required { 1.0 } else { p.default })
                .collect();
            let Ok(model) = kind.problem(&defaults) else {
                continue;
            };
            let Drawing::Figure(figure) = model.posed().drawing() else {
                continue;
            };
            figures += 1;
            let glyph_at = |q: f64| {
                let now = Sample {
                    q,
                    q_dot: 0.0,
                    fast: 0.0,
                    lean: None,
                };
                (figure.shapes)(&figure.knobs, 1.0, &now)
                    .into_iter()
                    .find_map(|s| match s {
                        Shape::Glyph { at, glyph, .. } => Some((at, glyph)),
                        Shape::Line { .. } => None,
                    })
                    .expect("a figure with a glyph")
            };
            let column = |q: f64, glyph: char| {
                let rows = drawn(figure, q, width, height);
                rows.iter()
                    .find_map(|r| r.chars().position(|d| d == glyph))
                    .unwrap_or_else(|| panic!("{kind:?}: no {glyph} at {q}:\n{}", rows.join("\n")))
            };
            // Two samples whose glyphs the shapes put apart, drawn in the same order.
            let scale = figure.knobs[0].abs().max(1e-3);
            let (a, b) = (-0.6 * scale, 0.6 * scale);
            let ((pa, ga), (pb, gb)) = (glyph_at(a), glyph_at(b));
            assert!((pa.0 - pb.0).abs() > 0.3, "{kind:?}: {pa:?} {pb:?}");
            let (ca, cb) = (column(a, ga), column(b, gb));
            assert_eq!(
                pa.0 < pb.0,
                ca < cb,
                "{kind:?}: {pa:?} {pb:?} drawn at {ca} {cb}"
            );
            assert!(ca.abs_diff(cb) >= 4, "{kind:?}: {ca} {cb}");
            let rows = drawn(figure, a, width, height);
            assert!(
                rows[0].contains(&format!("{} (B): events 0", figure.title)),
                "{}",
                rows[0]
            );
            assert!(!drawn(figure, a, 5, 3).concat().contains(ga));
            // An ASCII terminal gets the glyph's likeness, never the glyph itself.
            let ascii = drawn_in(figure, a, width, height, crate::ui::glyphs::Charset::Ascii);
            assert!(
                ga.is_ascii() || !ascii.concat().contains(ga),
                "{kind:?}: {ga}"
            );
            let theme = Theme::default();
            let section = legend(&figure, &look(&theme));
            assert_eq!(section.title, format!("{} (B)", figure.title));
            let words: Vec<&str> = section.marks.iter().map(|m| m.what.as_str()).collect();
            let want: Vec<&str> = figure.legend.iter().map(|l| l.1).collect();
            assert_eq!(words, want);
        }
        assert!(figures >= 1, "no registered scene draws its own figure");
    }
}
