//! The time-series pane (toggle `t`): `alpha_dot(t)` over a recent window with reversal ticks,
//! and the energy error. Not drawn, so not computed, when hidden.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::{Block, Paragraph};

use super::Look;
use crate::app::App;

/// Width of the time window, in simulated time.
const WINDOW: f64 = 20.0;

pub fn draw(frame: &mut Frame<'_>, area: Rect, app: &App, options: &Look) {
    let block = Block::bordered().title(" alpha_dot(t), reversals │ energy error ");
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let [plot, text] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)]).areas(inner);
    let t1 = app.reached.max(WINDOW);
    let t0 = t1 - WINDOW;
    let (cols, _) = (plot.width as usize * 2, plot.height as usize * 4);
    let step = ((app.trail.len() as f64) / (cols.max(1) as f64 * 4.0))
        .ceil()
        .max(1.0) as usize;
    let points: Vec<(f64, f64)> = app
        .trail
        .iter()
        .filter(|p| p.t >= t0)
        .step_by(step)
        .map(|p| (p.t, p.alpha_dot))
        .collect();
    let y = points.iter().fold(1e-3f64, |m, p| m.max(p.1.abs())) * 1.1;
    let theme = options.theme;
    let ticks: Vec<f64> = app.reversals.iter().copied().filter(|t| *t >= t0).collect();
    let canvas = Canvas::default()
        .marker(options.marker)
        .x_bounds([t0, t1])
        .y_bounds([-y, y])
        .paint(move |ctx| {
            ctx.draw(&Line::new(t0, 0.0, t1, 0.0, theme.contour));
            for &t in &ticks {
                ctx.draw(&Line::new(t, -y, t, -0.8 * y, theme.reversal));
            }
            ctx.layer();
            ctx.draw(&Points {
                coords: &points,
                color: theme.trail,
            });
        });
    frame.render_widget(canvas, plot);
    let worst = app
        .trail
        .iter()
        .fold(0.0f64, |m, p| m.max(p.energy_error.abs()));
    let now = app.current().map_or(0.0, |p| p.energy_error);
    frame.render_widget(
        Paragraph::new(format!(
            "t ∈ [{t0:.1}, {t1:.1}]   energy error now {now:.2e}, worst {worst:.2e}"
        ))
        .style(Style::default().fg(options.theme.dim)),
        text,
    );
}
