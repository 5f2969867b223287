//! The compare pane (`C`, `rattleback compare A B`): the run and its partner on one time axis,
//! the run's whole window, each with its spin, its reversal ticks (below the axis), its second
//! events' ticks (above: the celt's crossings) and its own status line. Both are cut at the
//! displayed time. Not drawn, so not computed, when hidden.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line as TextLine, Span};
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::{Paragraph, Widget};

use super::marks::{Facts, Section, curve};
use super::portrait::{resolution, short, y_labels};
use super::series::MARKS;
use super::{Look, framed};
use crate::app::computed::compare::CompareState;
use crate::app::{RunState, Scenario, run::upto};
use crate::physics::scene::Found;
use crate::sim::Point;

/// What the pane draws, for the legend (the time series' marks, in two lanes).
pub fn legend(f: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let _ = f;
    Section::new("compare (C): two lanes on one time axis")
        .mark(
            curve(look, MARKS.trace, "⠉⠒⠤⣀", "▀▄▀▄"),
            t.trail,
            "A, this run's spin (its own scale)",
        )
        .mark(
            curve(look, MARKS.trace, "⠉⠒⠤⣀", "▀▄▀▄"),
            t.effective,
            "B, the partner's spin",
        )
        .mark(curve(look, MARKS.axis, "⠤⠤⠤⠤", "▄▄▄▄"), t.contour, "zero")
        .mark(
            curve(look, MARKS.tick, "⡇", "█"),
            t.reversal,
            "a reversal (tick from the bottom)",
        )
        .mark(
            curve(look, MARKS.second, "⠉", "▀"),
            t.dim,
            "a spin crossing (tick from the top: the celt)",
        )
}

/// The compare pane: what it shows, borrowed.
pub struct ComparePane<'a> {
    /// The run (its samples, events and displayed time).
    pub run: &'a RunState,
    /// The run's scenario (its name and scene).
    pub scenario: &'a Scenario,
    /// The partner and its run.
    pub compare: &'a CompareState,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

/// One lane: a motion's spin over the window, its ticks and its status line.
struct Lane<'a> {
    label: &'static str,
    scene: String,
    /// The scene's short name, for a narrow pane.
    short: &'static str,
    name: String,
    samples: &'a [Point],
    reversals: &'a [f64],
    marks: Option<(&'static str, &'a [f64])>,
    /// Reversals and second events shown (older ones may no longer be kept as ticks).
    counts: (usize, Option<usize>),
    colour: Color,
    /// Instead of a plot: why there is none (computing, failed).
    note: Option<String>,
}

impl Widget for ComparePane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        pane(&self, area, buf);
    }
}

fn pane(pane: &ComparePane<'_>, area: Rect, buf: &mut Buffer) {
    let (run, look) = (pane.run, pane.look);
    let t = run.shown;
    let window = run.t_end.max(1e-9);
    let inner = framed(
        &format!("compare: spin(t) on one time axis, 0 to {}", short(window)),
        area,
        buf,
    );
    let kind = pane.scenario.settings.model.kind();
    let words = kind.words();
    let marks = run.second.as_ref().and_then(|(found, e)| {
        (*found == Found::Flow)
            .then(|| (words.second_events.map_or("", |s| s.name), e.recent_upto(t)))
    });
    let own = Lane {
        label: "A",
        scene: kind.title().to_owned(),
        short: kind.name(),
        name: pane.scenario.name.clone(),
        samples: run.trail_shown(),
        reversals: run.reversal_ticks(),
        marks,
        counts: (run.reversals_shown(), marks.and(run.second_shown())),
        colour: look.theme.trail,
        note: run.failed.clone(),
    };
    let partner = partner_lane(pane.compare, t, look);
    let rows = inner.height;
    // Two status lines and an axis; what is left is shared by the plots.
    let [a_status, a_plot, b_status, b_plot, axis] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Fill(1),
        Constraint::Length(1),
        Constraint::Fill(1),
        Constraint::Length(u16::from(rows >= 5)),
    ])
    .areas(inner);
    draw_lane(&own, t, window, a_status, a_plot, look, buf);
    draw_lane(&partner, t, window, b_status, b_plot, look, buf);
    if axis.height > 0 {
        // Round ticks over the run's whole window, under the plots (8 columns of labels).
        let row = super::axis::row(
            0.0,
            window,
            8,
            (axis.width as usize).saturating_sub(8),
            axis.width as usize,
        );
        Paragraph::new(TextLine::styled(row, look.dim())).render(axis, buf);
    }
}

/// The partner's lane: its run up to `t`, or why it is not drawn.
fn partner_lane<'a>(compare: &'a CompareState, t: f64, look: &Look<'_>) -> Lane<'a> {
    let Some(partner) = compare.partner.as_ref() else {
        return Lane {
            label: "B",
            scene: String::new(),
            short: "",
            name: String::new(),
            samples: &[],
            reversals: &[],
            marks: None,
            counts: (0, None),
            colour: look.theme.effective,
            note: Some("no partner".to_owned()),
        };
    };
    let kind = partner.scenario.settings.model.kind();
    let words = kind.words();
    let mut lane = Lane {
        label: "B",
        scene: kind.title().to_owned(),
        short: kind.name(),
        name: partner.scenario.name.clone(),
        samples: &[],
        reversals: &[],
        marks: None,
        counts: (0, None),
        colour: look.theme.effective,
        note: None,
    };
    match compare.outcome.as_ref() {
        None => lane.note = Some("computing the partner…".to_owned()),
        Some(Err(why)) => lane.note = Some(why.clone()),
        Some(Ok(r)) => {
            let upto_t = |times: &'a [f64]| &times[..times.partition_point(|x| *x <= t)];
            lane.samples = upto(&r.samples, t);
            lane.reversals = upto_t(&r.reversals);
            lane.marks = words
                .second_events
                .filter(|s| s.found == Found::Flow)
                .map(|s| (s.name, upto_t(&r.marks)));
            lane.counts = (lane.reversals.len(), lane.marks.map(|(_, m)| m.len()));
        }
    }
    lane
}

fn draw_lane(
    lane: &Lane<'_>,
    t: f64,
    window: f64,
    status: Rect,
    plot_area: Rect,
    look: &Look<'_>,
    buf: &mut Buffer,
) {
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let mut spans = vec![
        Span::styled(format!("{} ", lane.label), bold.fg(lane.colour)),
        Span::styled(lane.scene.clone(), bold),
    ];
    let counts_width = 40;
    if status.width < (lane.scene.chars().count() + counts_width) as u16 {
        // Narrow: the scene's short name, so the counts stay whole.
        spans[1] = Span::styled(lane.short.to_owned(), bold);
    }
    if lane.note.is_none() {
        spans.push(Span::raw(format!(" │ reversals {}", lane.counts.0)));
        if let (Some((name, _)), Some(n)) = (lane.marks, lane.counts.1) {
            spans.push(Span::raw(format!(" │ {name} {n}")));
        }
        if let Some(p) = lane.samples.last() {
            spans.push(Span::raw(format!(" │ spin {}", short(p.rate))));
        }
    }
    // The preset's name last, only where it fits whole (a cut name reads as another).
    let used: usize = spans.iter().map(|s| s.content.chars().count()).sum();
    let name = format!(" · {}", lane.name);
    if used + name.chars().count() <= status.width as usize {
        spans.push(Span::styled(name, look.dim()));
    }
    Paragraph::new(TextLine::from(spans)).render(status, buf);
    if plot_area.height == 0 {
        return;
    }
    let [y_axis, plot] =
        Layout::horizontal([Constraint::Length(8), Constraint::Min(0)]).areas(plot_area);
    if let Some(note) = &lane.note {
        Paragraph::new(TextLine::styled(
            crate::app::ellipsis(note, plot.width as usize),
            Style::default().fg(look.theme.error),
        ))
        .render(plot, buf);
        return;
    }
    let (rx, _) = resolution(look.marker);
    let cols = (plot.width as usize * rx).max(1);
    let step = (lane.samples.len() / (cols * 4)).max(1);
    let coords: Vec<(f64, f64)> = lane
        .samples
        .iter()
        .step_by(step)
        .chain(lane.samples.last())
        .map(|p| (p.t, p.rate))
        .collect();
    let y = coords.iter().fold(1e-3f64, |m, p| m.max(p.1.abs())) * 1.1;
    let theme = look.theme;
    let (colour, reversals) = (lane.colour, lane.reversals);
    let marks = lane.marks.map_or(&[][..], |(_, m)| m);
    let one_per_cell = look.marker == ratatui::symbols::Marker::Dot;
    Canvas::default()
        .marker(look.marker)
        .background_color(theme.background)
        .x_bounds([0.0, window])
        .y_bounds([-y, y])
        .paint(move |ctx| {
            // One point per cell: each curve its own character, as in the time series.
            let mark = |ctx: &mut ratatui::widgets::canvas::Context<'_>, c: char| {
                if one_per_cell {
                    ctx.marker(ratatui::symbols::Marker::Custom(c));
                }
            };
            mark(ctx, MARKS.axis);
            ctx.draw(&Line::new(0.0, 0.0, t.min(window), 0.0, theme.contour));
            ctx.layer();
            mark(ctx, MARKS.second);
            for &r in marks {
                ctx.draw(&Line::new(r, 0.8 * y, r, y, theme.dim));
            }
            ctx.layer();
            mark(ctx, MARKS.tick);
            for &r in reversals {
                ctx.draw(&Line::new(r, -y, r, -0.7 * y, theme.reversal));
            }
            ctx.layer();
            mark(ctx, MARKS.trace);
            ctx.draw(&Points {
                coords: &coords,
                color: colour,
            });
        })
        .render(plot, buf);
    Paragraph::new(y_labels([-y, y], y_axis.height as usize, look.dim())).render(y_axis, buf);
}
