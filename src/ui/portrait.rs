//! The phase portrait of `(alpha, alpha_dot)`: effective-energy level sets (separatrix and the
//! start's level distinct), the full trail up to the displayed time, the limit's overlay, the
//! current point, and axes with tick labels.
//!
//! The curves differ by shape as well as colour, so they read under `NO_COLOR`: background
//! levels are dotted, the start's level dashed, the separatrix solid; the trail is a dense
//! line of dots and the limit's overlay a row of `∘` marks. With one point per cell (`--marker
//! dot`, the console, ASCII) each curve has its own character instead: `.` levels, `:` the
//! start's level, `+` the separatrix, `•` the trail, `∘` the limit, `●` now.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line as TextLine, Span};
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::{Paragraph, StatefulWidget, Widget};

use super::marks::{Facts, Section, curve, pattern, printed};
use super::{Look, framed};
use crate::app::fields::{Settings, format_number};
use crate::app::portrait::{
    Bounds, Level, LevelKind, decimate, display_alpha, following, levels as level_sets, wrap_centre,
};
use crate::app::{RunState, Scenario, ViewState};

/// Width of the `alpha_dot` tick labels.
const Y_LABELS: u16 = 8;
/// Marks of the limit's overlay across the plot (about one per this many columns).
const OVERLAY_MARK_EVERY: usize = 3;

/// The characters of the portrait's curves when each cell holds one point (`--marker dot`, the
/// Linux console, ASCII): one per curve, so they stay apart without colour. Folded further
/// under ASCII (`•` → `*`), still distinct.
#[derive(Clone, Copy, Debug)]
struct CellMarks {
    plain: char,
    start: char,
    separatrix: char,
    trail: char,
}

const CELL_MARKS: CellMarks = CellMarks {
    plain: '.',
    start: ':',
    separatrix: '+',
    trail: '•',
};

impl CellMarks {
    fn level(self, kind: LevelKind) -> char {
        match kind {
            LevelKind::Plain => self.plain,
            LevelKind::Start => self.start,
            LevelKind::Separatrix => self.separatrix,
        }
    }
}

/// What the portrait draws, for the legend: the same marks as [`pane`], for the scene's limit
/// (a limit's marks only where there is one; levels only where its potential varies).
pub fn legend(f: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let words = f.kind.words();
    let small = f.kind.small();
    let motion = small.map_or_else(
        || "the motion".to_owned(),
        |s| format!("the full motion at this {}", s.symbol),
    );
    let mut s = Section::new(format!(
        "phase portrait: {} across, {} up",
        words.q, words.q_dot
    ))
    .mark(
        curve(look, CELL_MARKS.trail, "⣀⣤⣀⣤", "▄▄▄▄"),
        t.trail,
        format!("{motion}{}", pattern(look, "dense dots")),
    );
    if let Some(small) = small {
        s = s.mark(
            printed(look, OVERLAY_MARK),
            t.effective,
            format!("the limit {} (marks); e hides it", small.limit),
        );
    }
    s = s.mark(
        printed(look, CURRENT_MARK),
        t.current,
        "the displayed point",
    );
    let levels = f.limit.potential_max() > f.limit.potential_min();
    if !f.limit.separatrices().is_empty() {
        s = s.mark(
            curve(look, CELL_MARKS.separatrix, "⠒⠒⠒⠒", "▀▀▀▀"),
            t.separatrix,
            format!("separatrix of the limit{}", pattern(look, "solid")),
        );
    }
    let start = if levels {
        format!(
            "the start's level of the limit's energy E_eff{}",
            pattern(look, "dashed")
        )
    } else {
        format!(
            "the largest spin the start's energy allows, either sense{}",
            pattern(look, "dashed")
        )
    };
    s = s.mark(
        curve(look, CELL_MARKS.start, "⠒ ⠒ ", "▀ ▀ "),
        t.start_level,
        start,
    );
    if levels {
        s = s.mark(
            curve(look, CELL_MARKS.plain, "⠂  ⠂", "▀  ▀"),
            t.contour,
            "other levels of E_eff (dotted)",
        );
    }
    s.note("w wraps the angle to one period; z/Z zoom, shift+arrows pan")
}

/// The limit's mark in the portrait.
const OVERLAY_MARK: char = '∘';
/// The displayed point.
const CURRENT_MARK: char = '●';

/// Canvas cells per terminal cell for a marker.
pub fn resolution(marker: Marker) -> (usize, usize) {
    match marker {
        Marker::Braille => (2, 4),
        Marker::HalfBlock => (1, 2),
        _ => (1, 1),
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Key {
    settings: Settings,
    bounds: Bounds,
    levels: usize,
    samples: usize,
}

/// The level sets of the last frame, recomputed only when what they depend on changes.
#[derive(Debug, Default)]
pub struct Cache {
    contours: Option<(Key, Vec<Level>)>,
    /// Where the last frame drew the portrait's plot, and the bounds it drew (the mouse maps
    /// a click through them).
    pub plot: Option<(Rect, Bounds)>,
}

impl Cache {
    fn levels(
        &mut self,
        scenario: &Scenario,
        levels: usize,
        bounds: Bounds,
        samples: usize,
    ) -> &[Level] {
        let key = Key {
            settings: scenario.settings,
            bounds,
            levels,
            samples,
        };
        if self.contours.as_ref().is_none_or(|(k, _)| *k != key) {
            let eff = &scenario.derived.limit;
            let l = level_sets(eff, &bounds, eff.energy(), key.levels, samples);
            self.contours = Some((key, l));
        }
        self.contours.as_ref().map_or(&[], |(_, l)| l.as_slice())
    }
}

/// The phase portrait: what it shows, borrowed; its state is the level-set cache.
pub struct PortraitPane<'a> {
    /// The limit's potential and the settings.
    pub scenario: &'a Scenario,
    /// Samples up to the displayed time.
    pub run: &'a RunState,
    /// Zoom, wrap, overlay.
    pub view: &'a ViewState,
    /// The axes' bounds.
    pub bounds: Bounds,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

impl StatefulWidget for PortraitPane<'_> {
    type State = Cache;

    fn render(self, area: Rect, buf: &mut Buffer, cache: &mut Cache) {
        pane(&self, area, buf, cache);
    }
}

fn pane(p: &PortraitPane<'_>, area: Rect, buf: &mut Buffer, cache: &mut Cache) {
    let look = p.look;
    let trail_shown = p.run.trail_shown();
    let wrap = p.view.view.wrap;
    let limit = &p.scenario.derived.limit;
    let period = limit.period();
    let mode = if wrap {
        "wrapped"
    } else if following(trail_shown, wrap, period) {
        "following"
    } else {
        "unwrapped"
    };
    let words = p.scenario.settings.model.kind().words();
    let inner = framed(
        &format!(
            "phase portrait: {} ({mode}) vs {}",
            words.q_name, words.q_dot_name
        ),
        area,
        buf,
    );
    let [body, x_axis] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)]).areas(inner);
    let [y_axis, plot] =
        Layout::horizontal([Constraint::Length(Y_LABELS), Constraint::Min(0)]).areas(body);
    cache.plot = Some((plot, p.bounds));
    let bounds = p.bounds;
    let (rx, ry) = resolution(look.marker);
    let (cols, rows) = (plot.width as usize * rx, plot.height as usize * ry);
    let theme = look.theme;
    let levels = cache.levels(p.scenario, p.view.view.levels, bounds, cols.max(16));
    let centre = wrap_centre(limit);
    let to_xy = |p: &crate::sim::Point| (display_alpha(p.slow, centre, wrap, period), p.rate);
    let trail = decimate(trail_shown.iter().map(to_xy), &bounds, cols, rows);
    let overlay = if p.view.overlay {
        decimate(
            p.run.effective_shown().iter().map(to_xy),
            &bounds,
            (plot.width as usize / OVERLAY_MARK_EVERY).max(1),
            (plot.height as usize / 2).max(1),
        )
    } else {
        Vec::new()
    };
    let current = p.run.current().map(to_xy);
    let one_per_cell = (look.marker == Marker::Dot).then_some(CELL_MARKS);
    let canvas = Canvas::default()
        .marker(look.marker)
        .background_color(look.theme.background)
        .x_bounds(bounds.x)
        .y_bounds(bounds.y)
        .paint(move |ctx| {
            draw_levels(ctx, levels, theme, one_per_cell);
            if let Some(m) = one_per_cell {
                ctx.marker(Marker::Custom(m.trail));
            }
            ctx.draw(&Points {
                coords: &trail,
                color: theme.trail,
            });
            ctx.layer();
            for &(x, y) in &overlay {
                ctx.print(
                    x,
                    y,
                    TextLine::styled(
                        OVERLAY_MARK.to_string(),
                        Style::default().fg(theme.effective),
                    ),
                );
            }
            if let Some((x, y)) = current {
                ctx.print(
                    x,
                    y,
                    TextLine::styled(
                        CURRENT_MARK.to_string(),
                        Style::default()
                            .fg(theme.current)
                            .add_modifier(Modifier::BOLD),
                    ),
                );
            }
        });
    canvas.render(plot, buf);
    draw_axes(buf, y_axis, x_axis, plot, &bounds, look);
}

/// The level sets, each kind a layer: dotted, dashed or solid, so they read without colour;
/// with one point per cell, each kind its own character too.
fn draw_levels(
    ctx: &mut ratatui::widgets::canvas::Context<'_>,
    levels: &[Level],
    theme: &super::Theme,
    one_per_cell: Option<CellMarks>,
) {
    for kind in [LevelKind::Plain, LevelKind::Start, LevelKind::Separatrix] {
        let (color, every) = match kind {
            LevelKind::Plain => (theme.contour, 3),
            LevelKind::Start => (theme.start_level, 2),
            LevelKind::Separatrix => (theme.separatrix, 1),
        };
        if let Some(m) = one_per_cell {
            ctx.marker(Marker::Custom(m.level(kind)));
        }
        for level in levels.iter().filter(|l| l.kind == kind) {
            for line in &level.lines {
                for (i, w) in line.windows(2).enumerate() {
                    if i % every == 0 {
                        ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, color));
                    }
                }
            }
        }
        ctx.layer();
    }
}

fn draw_axes(buf: &mut Buffer, y_axis: Rect, x_axis: Rect, plot: Rect, b: &Bounds, look: &Look) {
    let dim = look.dim();
    Paragraph::new(y_labels(b.y, y_axis.height as usize, dim)).render(y_axis, buf);
    // The angle: round ticks across the plot.
    let row = super::axis::row(
        b.x[0],
        b.x[1],
        (plot.x - x_axis.x) as usize,
        plot.width as usize,
        x_axis.width as usize,
    );
    Paragraph::new(TextLine::from(Span::styled(row, dim))).render(x_axis, buf);
}

/// Labels of a vertical axis `[lo, hi]` over `h` rows: top, middle, bottom.
pub fn y_labels(y: [f64; 2], h: usize, style: Style) -> Vec<TextLine<'static>> {
    let mut lines = vec![TextLine::raw(""); h];
    if h >= 3 {
        let fmt = |v: f64| format!("{:>7} ", short(v));
        lines[0] = TextLine::styled(fmt(y[1]), style);
        lines[h / 2] = TextLine::styled(fmt(0.5 * (y[0] + y[1])), style);
        lines[h - 1] = TextLine::styled(fmt(y[0]), style);
    }
    lines
}

/// A tick label: at most 7 characters.
pub fn short(v: f64) -> String {
    if v.abs() < 5e-13 {
        return "0".to_owned();
    }
    let s = format_number((v * 1e3).round() / 1e3);
    if s.chars().count() <= 7 {
        s
    } else {
        format!("{v:.1e}")
    }
}
