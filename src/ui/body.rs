//! The body pane (toggle `B`): the rattleback seen from above, so the reversal is seen and not
//! only plotted. An elongated body whose long axis turns with `alpha`; its rocking `gamma`, far
//! too fast to draw at large `k`, shown by the cross bar whose length is the rocking envelope
//! (the largest `|gamma|` over the last stretch of samples, exaggerated to the body's size); the
//! trace of the long axis's tip over the last seconds, `+` while the spin is counter-clockwise
//! (`alpha_dot > 0`) and `-` while clockwise, so a reversal is a change of sign on the ring. It
//! reads the same in Braille, half blocks and under `NO_COLOR` (shapes and signs, not colours).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::Line as TextLine;
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::{Block, Widget};

use super::{Look, title};
use crate::app::RunState;

/// Seconds of trace drawn around the body.
pub const TRACE_SECONDS: f64 = 6.0;
/// Samples the rocking envelope is taken over.
pub const ENVELOPE_SAMPLES: usize = 96;

/// The body pane: what it shows, borrowed.
pub struct BodyPane<'a> {
    /// The run (its displayed samples).
    pub run: &'a RunState,
    /// The body's extent along y over x seen from above: which axis is long (the body is drawn
    /// longer along x when it is at most 1).
    pub aspect: f64,
    /// The fast coordinate's name (`gamma`, `tilt`).
    pub fast: &'a str,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

/// The rocking envelope: the largest `|gamma|` over the last samples shown.
#[must_use]
pub fn envelope(run: &RunState) -> f64 {
    let shown = run.trail_shown();
    shown[shown.len().saturating_sub(ENVELOPE_SAMPLES)..]
        .iter()
        .map(|p| p.gamma.abs())
        .fold(0.0, f64::max)
}

/// The pane's title: the sense of the spin, the reversals, the rocking envelope.
fn heading(run: &RunState, alpha_dot: f64, rock: f64, fast: &str) -> String {
    let turning = match alpha_dot.partial_cmp(&0.0) {
        Some(std::cmp::Ordering::Greater) => "↺ counter-clockwise",
        Some(std::cmp::Ordering::Less) => "↻ clockwise",
        _ => "at rest",
    };
    format!(
        "body from above (B): spin {turning}, reversals {} │ rocking |{fast}| {rock:.1e}",
        run.reversals_shown()
    )
}

/// The long axis's tip over the last [`TRACE_SECONDS`]: `(x, y, counter-clockwise)`, on a ring
/// just outside the body (`along_x`: the long axis is the body's x axis).
fn trace(run: &RunState, along_x: bool) -> Vec<(f64, f64, bool)> {
    let t_now = run.current().map_or(0.0, |p| p.t);
    let (x, y) = if along_x { (1.18, 0.0) } else { (0.0, 1.18) };
    run.trail_shown()
        .iter()
        .rev()
        .take_while(|p| t_now - p.t <= TRACE_SECONDS)
        .step_by(2)
        .map(|p| {
            let (c, s) = (p.alpha.cos(), p.alpha.sin());
            (x * c - y * s, x * s + y * c, p.alpha_dot >= 0.0)
        })
        .collect()
}

impl Widget for BodyPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (run, look) = (self.run, self.look);
        let now = run.current().copied();
        let (alpha, alpha_dot) = now.map_or((0.0, 0.0), |p| (p.alpha, p.alpha_dot));
        let rock = envelope(run);
        let block =
            Block::bordered().title(title(&heading(run, alpha_dot, rock, self.fast), area.width));
        let inner = block.inner(area);
        block.render(area, buf);
        if inner.width < 4 || inner.height < 3 {
            return;
        }
        // Cells are about twice as tall as wide: keep circles round.
        let ratio = f64::from(inner.width) / (2.0 * f64::from(inner.height));
        let (sx, sy) = (1.35 * ratio.max(1.0), 1.35 * (1.0 / ratio).max(1.0));
        // The long axis is the body's x axis when ix > iy (the rattleback's keel).
        let (a, b) = if self.aspect <= 1.0 {
            (1.0, 0.42)
        } else {
            (0.42, 1.0)
        };
        let (c, s) = (alpha.cos(), alpha.sin());
        let rot = |x: f64, y: f64| (x * c - y * s, x * s + y * c);
        let outline: Vec<(f64, f64)> = (0..=96)
            .map(|i| {
                let u = f64::from(i) / 96.0 * std::f64::consts::TAU;
                rot(a * u.cos(), b * u.sin())
            })
            .collect();
        // The cross bar: its half-length is the envelope, scaled so the largest rocking of the
        // run fills the body's width (exaggerated: the real tilt is tiny at large k).
        let biggest = run
            .trail_shown()
            .iter()
            .map(|p| p.gamma.abs())
            .fold(0.0, f64::max);
        let bar = if biggest > 0.0 {
            0.15 + 0.85 * rock / biggest
        } else {
            0.15
        };
        let cross = if a >= b {
            (0.0, b * bar)
        } else {
            (a * bar, 0.0)
        };
        let long = if a >= b { (a, 0.0) } else { (0.0, b) };
        let trace = trace(run, a >= b);
        let theme = look.theme;
        Canvas::default()
            .marker(look.marker)
            .background_color(theme.background)
            .x_bounds([-sx, sx])
            .y_bounds([-sy, sy])
            .paint(|ctx| {
                for w in outline.windows(2) {
                    ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, theme.trail));
                }
                let (x0, y0) = rot(-long.0, -long.1);
                let (x1, y1) = rot(long.0, long.1);
                ctx.draw(&Line::new(x0, y0, x1, y1, theme.separatrix));
                let (u0, v0) = rot(-cross.0, -cross.1);
                let (u1, v1) = rot(cross.0, cross.1);
                ctx.draw(&Line::new(u0, v0, u1, v1, theme.effective));
                ctx.draw(&Points {
                    coords: &[(0.0, 0.0)],
                    color: theme.current,
                });
                ctx.layer();
                for &(x, y, ccw) in &trace {
                    let (glyph, colour) = if ccw {
                        ("+", theme.trail)
                    } else {
                        ("-", theme.reversal)
                    };
                    ctx.print(x, y, TextLine::styled(glyph, Style::default().fg(colour)));
                }
                // The tip of the long axis, bold, where the trace starts.
                ctx.print(
                    x1,
                    y1,
                    TextLine::styled(
                        "●",
                        Style::default()
                            .fg(theme.current)
                            .add_modifier(Modifier::BOLD),
                    ),
                );
            })
            .render(inner, buf);
    }
}
