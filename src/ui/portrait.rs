//! The phase portrait of `(alpha, alpha_dot)`: effective-energy level sets (separatrix and the
//! start's level distinct), the full trail, the effective overlay, the current point, and axes
//! with tick labels.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::{Line as TextLine, Span};
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::{Block, Paragraph};

use super::Look;
use crate::app::App;
use crate::app::fields::format_number;
use crate::app::portrait::{Bounds, LevelKind, decimate, display_alpha, wrap_centre};

/// Width of the `alpha_dot` tick labels.
const Y_LABELS: u16 = 8;

/// Canvas cells per terminal cell for a marker.
fn resolution(marker: Marker) -> (usize, usize) {
    match marker {
        Marker::Braille => (2, 4),
        Marker::HalfBlock => (1, 2),
        _ => (1, 1),
    }
}

pub fn draw(frame: &mut Frame<'_>, area: Rect, app: &mut App, options: &Look) {
    let wrap = if app.view.wrap {
        "wrapped"
    } else {
        "unwrapped"
    };
    let block = Block::bordered().title(format!(" phase portrait: alpha ({wrap}) vs alpha_dot "));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let [body, x_axis] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)]).areas(inner);
    let [y_axis, plot] =
        Layout::horizontal([Constraint::Length(Y_LABELS), Constraint::Min(0)]).areas(body);
    let bounds = app.bounds();
    let (rx, ry) = resolution(options.marker);
    let (cols, rows) = (plot.width as usize * rx, plot.height as usize * ry);
    let theme = options.theme;
    app.refresh_contours(cols.max(16));
    let app: &App = app;
    let levels = app.levels();
    let centre = wrap_centre(&app.derived.effective);
    let wrap = app.view.wrap;
    let to_xy = |p: &crate::sim::Point| (display_alpha(p.alpha, centre, wrap), p.alpha_dot);
    let trail = decimate(app.trail.iter().map(to_xy), &bounds, cols, rows);
    let overlay = if app.show_effective {
        decimate(app.effective_trail.iter().map(to_xy), &bounds, cols, rows)
    } else {
        Vec::new()
    };
    let current = app.current().map(to_xy);
    let canvas = Canvas::default()
        .marker(options.marker)
        .x_bounds(bounds.x)
        .y_bounds(bounds.y)
        .paint(move |ctx| {
            for kind in [LevelKind::Plain, LevelKind::Separatrix, LevelKind::Start] {
                let color = match kind {
                    LevelKind::Plain => theme.contour,
                    LevelKind::Separatrix => theme.separatrix,
                    LevelKind::Start => theme.start_level,
                };
                for level in levels.iter().filter(|l| l.kind == kind) {
                    for line in &level.lines {
                        for w in line.windows(2) {
                            ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, color));
                        }
                    }
                }
                ctx.layer();
            }
            ctx.draw(&Points {
                coords: &overlay,
                color: theme.effective,
            });
            ctx.layer();
            ctx.draw(&Points {
                coords: &trail,
                color: theme.trail,
            });
            ctx.layer();
            if let Some((x, y)) = current {
                ctx.print(
                    x,
                    y,
                    TextLine::styled("●", Style::default().fg(theme.current)),
                );
            }
        });
    frame.render_widget(canvas, plot);
    draw_axes(frame, y_axis, x_axis, plot, &bounds, options);
}

fn draw_axes(
    frame: &mut Frame<'_>,
    y_axis: Rect,
    x_axis: Rect,
    plot: Rect,
    b: &Bounds,
    options: &Look,
) {
    let dim = Style::default().fg(options.theme.dim);
    // alpha_dot: top, middle, bottom.
    let mut ylines = vec![TextLine::raw(""); y_axis.height as usize];
    let h = ylines.len();
    if h >= 3 {
        let fmt = |v: f64| format!("{:>7} ", short(v));
        ylines[0] = TextLine::styled(fmt(b.y[1]), dim);
        ylines[h / 2] = TextLine::styled(fmt(0.5 * (b.y[0] + b.y[1])), dim);
        ylines[h - 1] = TextLine::styled(fmt(b.y[0]), dim);
    }
    frame.render_widget(Paragraph::new(ylines), y_axis);
    // alpha: five ticks across the plot.
    let width = plot.width as usize;
    let mut row = vec![' '; x_axis.width as usize];
    let ticks = 5;
    for i in 0..ticks {
        let f = f64::from(i) / f64::from(ticks - 1);
        let label = short(b.x[0] + f * (b.x[1] - b.x[0]));
        let col = (plot.x - x_axis.x) as usize + (f * (width.saturating_sub(1)) as f64) as usize;
        let start = col
            .saturating_sub(label.len() / 2)
            .min(row.len().saturating_sub(label.len()));
        for (j, ch) in label.chars().enumerate() {
            if let Some(slot) = row.get_mut(start + j) {
                *slot = ch;
            }
        }
    }
    frame.render_widget(
        Paragraph::new(TextLine::from(Span::styled(
            row.into_iter().collect::<String>(),
            dim,
        ))),
        x_axis,
    );
}

fn short(v: f64) -> String {
    if v.abs() < 5e-13 {
        "0".to_owned()
    } else {
        format_number((v * 1e3).round() / 1e3)
    }
}
