//! The weak-* pane (toggle `W`, window `<` `>`): `γ̇² g^{3/2}` of the full motion as dots, its
//! moving average over the window as a line, `θ` dashed. Pointwise the quantity swings between
//! 0 and `2θ` at every `k`; its average settles on `θ` once the window spans many fast periods
//! (the paper's weak-* convergence). The view covers at most 400 fast periods from `t = 0`.
//! For the pendulum: `θ̇_ε` as dots (its O(1) ripple), its average as a line, the limit's `θ̇`
//! dashed; the title gives the distance between the two averages (over 4000 fast periods).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line as TextLine;
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::{Paragraph, Widget};

use super::marks::{Facts, Section, curve};
use super::portrait::resolution;
use super::{Look, framed};
use crate::app::computed::weak::WeakState;

/// The weak-* pane's characters with one point per cell: the samples, the dashed reference,
/// the average.
const SAMPLE: char = '.';
const REFERENCE: char = '-';
const AVERAGE: char = '•';

/// What the pane draws, for the legend.
pub fn legend(f: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let Some(words) = f.kind.studies().weak else {
        return Section::new("weak-* (W)");
    };
    Section::new("weak-* (W)")
        .mark(
            curve(look, SAMPLE, "⠁⠈⠐⠂", "▀ ▄ "),
            t.contour,
            words.observable,
        )
        .mark(
            curve(look, AVERAGE, "⠒⠒⠒⠒", "▀▀▀▀"),
            t.trail,
            "its moving average over the window w (< > halve or double w)",
        )
        .mark(
            curve(look, REFERENCE, "⠒ ⠒ ", "▀ ▀ "),
            t.effective,
            words.reference,
        )
}

/// The weak-* pane: what it shows, borrowed.
pub struct WeakPane<'a> {
    /// The data and the window.
    pub weak: &'a WeakState,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

impl Widget for WeakPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (weak, look) = (self.weak, self.look);
        let pendulum = !weak.reference.is_empty();
        let inner = framed(&heading(weak, pendulum), area, buf);
        let (y_axis, plot, x_axis) = super::plot_areas(inner);
        if weak.t.len() < 2 || (!pendulum && weak.theta <= 0.0) {
            return;
        }
        let t1 = weak.t[weak.t.len() - 1];
        let (bottom, top) = y_bounds(weak, pendulum);
        let (rx, _) = resolution(look.marker);
        let cols = (plot.width as usize * rx).max(1);
        // Pointwise: every sample would be a solid band; a few per column show the swing.
        let step = (weak.t.len() / (cols * 6)).max(1);
        let dots: Vec<(f64, f64)> = weak
            .t
            .iter()
            .zip(&weak.pointwise)
            .step_by(step)
            .map(|(&t, &q)| (t, q))
            .collect();
        let avg_step = (weak.t.len() / cols).max(1);
        let average: Vec<(f64, f64)> = weak
            .t
            .iter()
            .zip(&weak.average)
            .step_by(avg_step)
            .filter(|(_, a)| a.is_finite())
            .map(|(&t, &a)| (t, a))
            .collect();
        let theta = weak.theta;
        // The pendulum's reference curve, every other segment (dashed).
        let reference: Vec<(f64, f64)> = weak
            .t
            .iter()
            .zip(&weak.reference)
            .step_by(avg_step)
            .map(|(&t, &r)| (t, r))
            .collect();
        let theme = look.theme;
        // One point per cell (`--marker dot`, the console, ASCII): each curve its own
        // character, so they stay apart without colour: `.` samples, `-` the reference, `•` the
        // average (`*` in ASCII).
        let one_per_cell = look.marker == ratatui::symbols::Marker::Dot;
        let mark = |ctx: &mut ratatui::widgets::canvas::Context<'_>, c: char| {
            if one_per_cell {
                ctx.marker(ratatui::symbols::Marker::Custom(c));
            }
        };
        Canvas::default()
            .marker(look.marker)
            .background_color(theme.background)
            .x_bounds([0.0, t1])
            .y_bounds([bottom, top])
            .paint(|ctx| {
                mark(ctx, SAMPLE);
                ctx.draw(&Points {
                    coords: &dots,
                    color: theme.contour,
                });
                ctx.layer();
                mark(ctx, REFERENCE);
                if pendulum {
                    for w in reference.windows(2).step_by(2) {
                        ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, theme.effective));
                    }
                } else {
                    // θ, dashed.
                    let dash = t1 / 40.0;
                    for i in (0..40).step_by(2) {
                        let a = f64::from(i) * dash;
                        ctx.draw(&Line::new(a, theta, a + dash, theta, theme.effective));
                    }
                }
                ctx.layer();
                mark(ctx, AVERAGE);
                for w in average.windows(2) {
                    ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, theme.trail));
                }
            })
            .render(plot, buf);
        let low = if pendulum {
            format!("{bottom:.3}")
        } else {
            "0".to_owned()
        };
        Paragraph::new(y_labels(y_axis.height as usize, top, &low, look)).render(y_axis, buf);
        let row = super::axis::row(
            0.0,
            t1,
            (plot.x - x_axis.x) as usize,
            plot.width as usize,
            x_axis.width as usize,
        );
        Paragraph::new(TextLine::styled(row, look.dim())).render(x_axis, buf);
    }
}

/// The plot's vertical range: `[0, 2.2 θ]` for the rattleback, the data's range for the pendulum.
fn y_bounds(weak: &WeakState, pendulum: bool) -> (f64, f64) {
    if !pendulum {
        return (0.0, 2.2 * weak.theta);
    }
    let (lo, hi) = weak
        .pointwise
        .iter()
        .chain(&weak.reference)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &q| {
            (a.min(q), b.max(q))
        });
    let pad = 0.05 * (hi - lo).max(1e-9);
    (lo - pad, hi + pad)
}

/// The top and bottom labels of the y axis.
fn y_labels(rows: usize, top: f64, low: &str, look: &Look<'_>) -> Vec<TextLine<'static>> {
    let mut labels = vec![TextLine::raw(""); rows];
    if rows >= 2 {
        labels[0] = TextLine::styled(format!("{:>7} ", format!("{top:.3}")), look.dim());
        labels[rows - 1] = TextLine::styled(format!("{low:>7} "), look.dim());
    }
    labels
}

/// The pane's title: how far the averages are, and what is drawn.
fn heading(weak: &WeakState, pendulum: bool) -> String {
    let status = match (&weak.failed, weak.done) {
        (Some(why), _) => format!("failed: {why}"),
        (None, false) => "computing…".to_owned(),
        (None, true) => format!(
            "average over w = {} within {:.2} % of {}",
            crate::study::tick(weak.window),
            100.0 * weak.worst_deviation(),
            if pendulum { "the limit's" } else { "theta" }
        ),
    };
    let what = if pendulum {
        "theta_dot (dots), average (line), limit's theta_dot (dashed)"
    } else {
        "gamma_dot^2*g^1.5 (dots), average (line), theta (dashed)"
    };
    format!("weak-*: {status} │ {what} │ < >")
}
