//! The time-series pane (toggle `t`): `alpha_dot(t)` of the full motion and of the limit over a
//! window that widens with the playback speed, reversal ticks, a y scale, the energy error as a
//! plot of `log10 |ΔE/E|`, and a time axis with round ticks. Not drawn, so not computed, when
//! hidden. With one point per cell (the console, ASCII, `--marker dot`) the zero axis, the
//! trace, the ticks and the energy error each have their own character ([`MARKS`]).
use crate::physics::numerics::elementary::Elementary;

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::{Paragraph, Widget};

use super::Look;
use super::marks::{Facts, Section, curve, printed};
use super::portrait::{resolution, y_labels};
use crate::app::RunState;
use crate::sim::Point;

/// The time-series pane: what it shows, borrowed.
pub struct SeriesPane<'a> {
    /// Samples, reversals, the displayed time and the speed.
    pub run: &'a RunState,
    /// The limit is shown.
    pub overlay: bool,
    /// The model (its labels).
    pub model: crate::physics::ModelKind,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

/// The characters of the time plots when each cell holds one point: the zero axis, the trace,
/// an event's tick, the limit's marks and the energy error, apart without colour (folded
/// further in ASCII: `-`, `*`, `|`, `o`, `.`). The comparison's lanes draw with the same.
#[derive(Clone, Copy, Debug)]
pub struct TimeMarks {
    /// The zero line.
    pub axis: char,
    /// The trace of the rate.
    pub trace: char,
    /// An event's tick (a reversal, a swing).
    pub tick: char,
    /// A second kind of event's tick (the celt's crossings), from the top.
    pub second: char,
    /// The limit's marks.
    pub limit: char,
    /// The energy error.
    pub energy: char,
}

/// The time plots' characters.
pub const MARKS: TimeMarks = TimeMarks {
    axis: '─',
    trace: '•',
    tick: '│',
    second: '!',
    limit: '∘',
    energy: '·',
};

/// What the pane draws, for the legend (the same marks as [`pane`]).
pub fn legend(f: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let words = f.kind.words();
    let mut s = Section::new(format!("time series (t): {}(t)", words.q_dot)).mark(
        curve(look, MARKS.trace, "⠉⠒⠤⣀", "▀▄▀▄"),
        t.trail,
        format!("{} of the full motion", words.q_dot),
    );
    if let Some(small) = f.kind.small() {
        s = s.mark(
            printed(look, MARKS.limit),
            t.effective,
            format!("the limit {} (marks)", small.limit),
        );
    }
    s = s
        .mark(curve(look, MARKS.axis, "⠤⠤⠤⠤", "▄▄▄▄"), t.contour, "zero")
        .mark(
            curve(look, MARKS.tick, "⡇", "█"),
            t.reversal,
            format!("a {} (tick from the bottom)", words.event),
        );
    if let Some(m) = words.monitor {
        s = s.mark(
            curve(look, MARKS.energy, "⠉⠉⠉⠉", "▀▀▀▀"),
            t.dim,
            format!(
                "below: log10 |{}|, the energy monitor of the full motion",
                m.label
            ),
        );
    }
    s.note("the time axis at the bottom; the window widens with the speed")
}

/// The pane's title: the rate, the events and the scene's monitor (if any).
fn title(words: &crate::physics::Words, limit: &str) -> String {
    let monitor = words
        .monitor
        .map_or_else(String::new, |m| format!(" │ log10|{}|", m.label));
    format!(
        "{}(t): {limit}, {}{monitor}",
        words.q_dot_name, words.events
    )
}

/// Wall seconds of motion the window shows (at least 10 simulated seconds).
const WINDOW_WALL: f64 = 15.0;

/// The time window `[t0, t1]` ending at the displayed time.
#[must_use]
pub fn window(run: &RunState) -> (f64, f64) {
    let w = (WINDOW_WALL * run.speed).max(10.0).min(run.t_end.max(1e-9));
    let t1 = run.shown.max(w);
    (t1 - w, t1)
}

fn thin(points: &[Point], t0: f64, cols: usize, f: impl Fn(&Point) -> f64) -> Vec<(f64, f64)> {
    let from = points.partition_point(|p| p.t < t0);
    let slice = &points[from..];
    let step = (slice.len() / (cols.max(1) * 4)).max(1);
    slice.iter().step_by(step).map(|p| (p.t, f(p))).collect()
}

impl Widget for SeriesPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        pane(&self, area, buf);
    }
}

fn pane(pane: &SeriesPane<'_>, area: Rect, buf: &mut Buffer) {
    let (run, look) = (pane.run, pane.look);
    let words = pane.model.words();
    let limit = if pane.model.small().is_some() {
        "full · limit ∘"
    } else {
        "full"
    };
    let inner = super::framed_middle(&title(&words, limit), area, buf);
    let [top, energy_area, t_axis] = Layout::vertical([
        Constraint::Min(2),
        Constraint::Length(3),
        Constraint::Length(1),
    ])
    .areas(inner);
    let [y_axis, plot] = Layout::horizontal([Constraint::Length(8), Constraint::Min(0)]).areas(top);
    let (t0, t1) = window(run);
    let (rx, _) = resolution(look.marker);
    let cols = plot.width as usize * rx;
    let full = thin(run.trail_shown(), t0, cols, |p| p.rate);
    let limit = if pane.overlay {
        thin(
            run.effective_shown(),
            t0,
            (plot.width as usize / 3).max(1) / 4,
            |p| p.rate,
        )
    } else {
        Vec::new()
    };
    let y = full
        .iter()
        .chain(&limit)
        .fold(1e-3f64, |m, p| m.max(p.1.abs()))
        * 1.1;
    let theme = look.theme;
    let ticks: Vec<f64> = run
        .reversal_ticks()
        .iter()
        .copied()
        .filter(|t| *t >= t0)
        .collect();
    // One point per cell: each curve its own character.
    let one_per_cell = look.marker == ratatui::symbols::Marker::Dot;
    let mark = move |ctx: &mut ratatui::widgets::canvas::Context<'_>, c: char| {
        if one_per_cell {
            ctx.marker(ratatui::symbols::Marker::Custom(c));
        }
    };
    let canvas = Canvas::default()
        .marker(look.marker)
        .background_color(look.theme.background)
        .x_bounds([t0, t1])
        .y_bounds([-y, y])
        .paint(move |ctx| {
            mark(ctx, MARKS.axis);
            ctx.draw(&Line::new(t0, 0.0, t1, 0.0, theme.contour));
            ctx.layer();
            mark(ctx, MARKS.tick);
            for &t in &ticks {
                ctx.draw(&Line::new(t, -y, t, -0.8 * y, theme.reversal));
            }
            ctx.layer();
            mark(ctx, MARKS.trace);
            ctx.draw(&Points {
                coords: &full,
                color: theme.trail,
            });
            ctx.layer();
            for &(x, v) in &limit {
                ctx.print(
                    x,
                    v,
                    ratatui::text::Line::styled(
                        MARKS.limit.to_string(),
                        ratatui::style::Style::default().fg(theme.effective),
                    ),
                );
            }
        });
    canvas.render(plot, buf);
    Paragraph::new(y_labels([-y, y], y_axis.height as usize, look.dim())).render(y_axis, buf);
    if words.monitor.is_some() {
        energy_strip(run, (t0, t1), cols, energy_area, look, buf);
    }
    // The time axis: round ticks under the plots.
    let row = super::axis::row(
        t0,
        t1,
        (plot.x - t_axis.x) as usize,
        plot.width as usize,
        t_axis.width as usize,
    );
    Paragraph::new(ratatui::text::Line::styled(row, look.dim())).render(t_axis, buf);
}

/// The energy error under the rate: `log10 |ΔE/E|` from 1e-16 up, over the same window.
fn energy_strip(
    run: &RunState,
    (t0, t1): (f64, f64),
    cols: usize,
    area: Rect,
    look: &Look<'_>,
    buf: &mut Buffer,
) {
    let [e_axis, e_plot] =
        Layout::horizontal([Constraint::Length(8), Constraint::Min(0)]).areas(area);
    let errors = thin(run.trail_shown(), t0, cols, |p| {
        p.energy_error.abs().max(1e-16).e_log10()
    });
    let hi = errors.iter().fold(-12.0f64, |m, p| m.max(p.1)).ceil() + 1.0;
    let lo = -16.0;
    let theme = look.theme;
    let one_per_cell = look.marker == ratatui::symbols::Marker::Dot;
    Canvas::default()
        .marker(if one_per_cell {
            ratatui::symbols::Marker::Custom(MARKS.energy)
        } else {
            look.marker
        })
        .background_color(theme.background)
        .x_bounds([t0, t1])
        .y_bounds([lo, hi])
        .paint(move |ctx| {
            ctx.draw(&Points {
                coords: &errors,
                color: theme.dim,
            });
        })
        .render(e_plot, buf);
    let label = |v: f64| format!("{:>7} ", format!("1e{v:.0}"));
    Paragraph::new(vec![
        ratatui::text::Line::styled(label(hi), look.dim()),
        ratatui::text::Line::raw(""),
        ratatui::text::Line::styled(label(lo), look.dim()),
    ])
    .render(e_axis, buf);
}
