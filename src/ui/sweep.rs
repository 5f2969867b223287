//! The sweep pane (toggle `K`): `sup_{[0,T]} |α_k − α_eff|` against `k` (the pendulum:
//! `sup |θ_ε − θ|` against `ε`), log–log, one `●` per rung as the worker delivers it, joined by
//! a line, with the fitted slope in the title (the paper's uniform convergence: O(1/k), slope
//! −1, on trapped starts; the pendulum's positions: O(ε), slope 1). Not computed while hidden.
use crate::physics::numerics::elementary::Elementary;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line as TextLine;
use ratatui::widgets::canvas::{Canvas, Line};
use ratatui::widgets::{Paragraph, Widget};

use super::marks::{Facts, Section, curve, printed};
use super::{Look, framed};
use crate::app::computed::sweep::SweepState;
use crate::physics::ModelKind;
use crate::study::sweep::ladder;

/// The sweep pane: what it shows, borrowed.
/// A rung's mark.
const RUNG: char = '●';

/// What the pane draws, for the legend.
pub fn legend(f: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let Some(small) = f.kind.small() else {
        return Section::new("sweep (K)");
    };
    Section::new(format!("{}-sweep (K)", small.symbol))
        .mark(
            printed(look, RUNG),
            t.current,
            format!(
                "one run per rung of {}: {} over [0, T]",
                small.symbol, small.sup
            ),
        )
        .mark(
            curve(look, '•', "⠑⠢⠤", "▀▄▄"),
            t.trail,
            "the rungs joined; the title's slope is their log-log fit",
        )
}

pub struct SweepPane<'a> {
    /// The rungs so far.
    pub sweep: &'a SweepState,
    /// Whose parameter is swept.
    pub model: ModelKind,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

impl Widget for SweepPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (sweep, look) = (self.sweep, self.look);
        let ladder = ladder(self.model);
        let Some(small) = self.model.small() else {
            return;
        };
        let symbol = small.symbol;
        let status = match (&sweep.failed, sweep.done, sweep.slope()) {
            (Some(why), _, _) => format!("stopped: {why}"),
            (None, true, Some(s)) => format!("slope {s:.2}"),
            (None, false, _) => {
                format!("computing {}/{}…", sweep.points.len(), ladder.len())
            }
            (None, true, None) => "no rung".to_owned(),
        };
        let inner = framed(
            &format!("{symbol}-sweep: {status} │ {} against {symbol}", small.sup),
            area,
            buf,
        );
        let (y_axis, plot, x_axis) = super::plot_areas(inner);
        let (lo_x, hi_x) = ladder
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x.e_log10()), b.max(x.e_log10()))
            });
        let (x0, x1) = (lo_x - 0.3, hi_x + 0.3);
        let pts: Vec<(f64, f64)> = sweep
            .points
            .iter()
            .filter(|p| p.sup_error > 0.0 && p.sup_error.is_finite())
            .map(|p| (p.parameter.e_log10(), p.sup_error.e_log10()))
            .collect();
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
        // `+ 0.0` turns a ceiling of −0 into 0 for the label.
        let (lo, hi) = if lo.is_finite() {
            ((lo - 0.5).floor() + 0.0, (hi + 0.5).ceil() + 0.0)
        } else {
            (-10.0, 0.0)
        };
        let theme = look.theme;
        Canvas::default()
            .marker(look.marker)
            .background_color(theme.background)
            .x_bounds([x0, x1])
            .y_bounds([lo, hi])
            .paint(|ctx| {
                for w in pts.windows(2) {
                    ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, theme.trail));
                }
                ctx.layer();
                for &(x, y) in &pts {
                    ctx.print(
                        x,
                        y,
                        TextLine::styled(
                            RUNG.to_string(),
                            ratatui::style::Style::default().fg(theme.current),
                        ),
                    );
                }
            })
            .render(plot, buf);
        let rows = y_axis.height as usize;
        let mut labels = vec![TextLine::raw(""); rows];
        if rows >= 2 {
            labels[0] = TextLine::styled(format!("{:>7} ", format!("1e{hi:.0}")), look.dim());
            labels[rows - 2] =
                TextLine::styled(format!("{:>7} ", format!("1e{lo:.0}")), look.dim());
        }
        Paragraph::new(labels).render(y_axis, buf);
        let first = format!("{symbol} 1e{lo_x:.0}");
        let last = format!("1e{hi_x:.0}");
        let width = x_axis.width as usize;
        let gap = width.saturating_sub(first.len() + last.len());
        Paragraph::new(TextLine::styled(
            format!("{first}{}{last}", " ".repeat(gap)),
            look.dim(),
        ))
        .render(x_axis, buf);
    }
}
