//! The map pane (toggle `M`): the scene's chart (issues 12 and 59), one glyph per cell, so it
//! reads without colour; `·` a cell not computed yet, `×` one not decided at the chart's
//! tolerance; the theory's curve drawn over it; the cursor `+` (reverse video while the map has
//! the arrows).
//!
//! - the rattleback and the celt: reversals, a density that grows with the count (blank: none;
//!   `░` 1, `▒` 2–3, `▓` 4–7, `█` 8 or more); the rattleback's critical ratio
//!   `(ix/iz)(√(ix/iy) − 1)` as `┃`, the celt's linear-theory curve as `┃`;
//! - the pendulum: `█` where the upright is stable, blank where it is not; Kapitza's
//!   `b² = 2a` as `┃`.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::Line as TextLine;
use ratatui::widgets::{Paragraph, Widget};

use super::marks::{Facts, Section, printed};
use super::{Look, framed};
use crate::app::computed::map::{MapSource, MapState};
use crate::study::chart::{Answer, Mark, Verdict};

/// The glyph of a count of reversals (`None`: not computed).
#[must_use]
pub fn glyph(count: Option<usize>) -> char {
    match count {
        None => '·',
        Some(0) => ' ',
        Some(1) => '░',
        Some(2..=3) => '▒',
        Some(4..=7) => '▓',
        Some(_) => '█',
    }
}

/// The glyph of a cell's verdict (`None`: not computed).
#[must_use]
pub fn verdict_glyph(v: Option<&Verdict>) -> char {
    // A computed cell and an inferred one are drawn alike: by their answer.
    match v.map(Verdict::answer) {
        None => glyph(None),
        Some(None) => UNDECIDED,
        Some(Some(Answer::Count(count))) => glyph(Some(count)),
        Some(Some(Answer::Stable(true))) => STABLE,
        Some(Some(Answer::Stable(false))) => ' ',
    }
}

/// The curve's mark, the cursor's, a stable cell's and an undecided one's.
const CRITICAL: char = '┃';
const CURSOR: char = '+';
const STABLE: char = '█';
const UNDECIDED: char = '×';

/// What the pane draws, for the legend: the scene's own glyphs and curve.
pub fn legend(facts: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let words = crate::study::chart::words(facts.kind);
    let answer = crate::physics::chart::answer_field(words.csv);
    // A yes/no chart draws its stable cells, a count's its ramp of counts.
    let answers: String = if answer.is_some_and(|f| f.kind == crate::physics::chart::Kind::Flag) {
        printed(look, STABLE)
    } else {
        [1, 2, 4, 8]
            .into_iter()
            .map(|n| look.charset.mark(glyph(Some(n))))
            .collect()
    };
    Section::new(words.title)
        .mark(answers, t.trail, words.pane_legend[0])
        .mark(printed(look, UNDECIDED), t.dim, words.pane_legend[1])
        .mark(printed(look, glyph(None)), t.dim, "a cell not computed yet")
        .mark(printed(look, CRITICAL), t.separatrix, words.curve)
        .mark(
            printed(look, CURSOR),
            t.current,
            "the cursor (M gives it the arrows, Enter loads the cell)",
        )
        .note(words.note)
}

/// The map pane: what it shows, borrowed.
pub struct MapPane<'a> {
    /// Cells, cursor and source.
    pub map: &'a MapState,
    /// Whether the map has the arrows.
    pub focused: bool,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

impl MapPane<'_> {
    fn heading(&self) -> String {
        let map = self.map;
        let chart = map.spec.map(|s| s.chart);
        let source = match chart {
            Some(c) => c.title(),
            None if map.source == MapSource::Full => "map (full model)".to_owned(),
            None => "map (limit)".to_owned(),
        };
        let total = map.cells.len();
        let progress = match (&map.failed, map.done) {
            (Some(why), _) => format!("stopped: {why}"),
            (None, true) => format!("{total} cells"),
            (None, false) => {
                let left = map.seconds_left().map_or_else(String::new, |s| {
                    let s = s.ceil().clamp(1.0, 99_999.0) as u64;
                    format!(" ~{s} s")
                });
                format!("{}/{total} cells{left}…", map.computed())
            }
        };
        let sources = chart.is_some_and(|c| c.words().sources);
        let keys = match (self.focused, sources) {
            (true, true) => "Enter f Esc",
            (true, false) => "Enter Esc",
            (false, _) => "M",
        };
        format!("{source} {progress} │ {keys}")
    }

    /// What the cursor's cell is, for the x-axis row, and whether it was inferred.
    fn cursor_text(&self) -> Option<(String, bool)> {
        let map = self.map;
        let chart = map.spec?.chart;
        let (vx, vy) = map.at_cursor()?;
        let (nx, ny) = chart.words().axes;
        let cell = map.cell(map.cursor.0, map.cursor.1);
        let verdict = match cell {
            None => "?".to_owned(),
            Some(Verdict::Failed { .. }) => "failed (its run stopped)".to_owned(),
            Some(v) => match v.answer() {
                None => "undecided".to_owned(),
                Some(Answer::Count(count)) => format!("{count} rev"),
                Some(Answer::Stable(true)) => "stable".to_owned(),
                Some(Answer::Stable(false)) => "unstable".to_owned(),
            },
        };
        let inferred = cell.is_some_and(|v| v.mark() == Mark::Inferred);
        let nx = if chart.words().sources { "ratio" } else { nx };
        let tick = crate::study::tick;
        let text = format!("+ {nx} {} {ny} {}: {verdict}", tick(vx), tick(vy));
        Some((text, inferred))
    }
}

impl Widget for MapPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (map, look) = (self.map, self.look);
        let inner = framed(&self.heading(), area, buf);
        let (y_axis, plot, x_axis) = super::plot_areas(inner);
        let Some(spec) = map.spec else { return };
        let chart = spec.chart;
        let (ax, ay) = chart.axes();
        let (cols, rows) = (ax.cells, ay.cells);
        let (w, h) = (plot.width as usize, plot.height as usize);
        if w == 0 || h == 0 {
            return;
        }
        let theme = look.theme;
        let cell_style = Style::default().fg(theme.trail);
        for y in 0..h {
            let j = rows - 1 - ((y * rows) / h).min(rows - 1);
            for x in 0..w {
                let i = ((x * cols) / w).min(cols - 1);
                let verdict = map.cell(i, j);
                let style = if verdict.is_none_or(|v| !v.decided()) {
                    look.dim()
                } else {
                    cell_style
                };
                buf[(plot.x + x as u16, plot.y + y as u16)]
                    .set_char(look.charset.mark(verdict_glyph(verdict)))
                    .set_style(style);
            }
        }
        // The theory's curve: a point is drawn on the screen rows that show its grid row (so a
        // row of the grid drawn on fewer screen rows shows its own points, not its
        // neighbours'), in the screen column it falls in.
        let curve_style = Style::default()
            .fg(theme.separatrix)
            .add_modifier(Modifier::BOLD);
        for &(px, py) in &map.curve {
            let (Some(i), Some(j)) = (ax.cell_of(px), ay.cell_of(py)) else {
                continue;
            };
            // The screen column whose cell holds the curve (the first showing column `i` or
            // the next one), so that the cells drawn left of it are left of the curve.
            let x = (0..w).find(|x| (x * cols) / w >= i).unwrap_or(w - 1);
            for y in (0..h).filter(|y| rows - 1 - ((y * rows) / h).min(rows - 1) == j) {
                buf[(plot.x + x as u16, plot.y + y as u16)]
                    .set_char(look.charset.mark(CRITICAL))
                    .set_style(curve_style);
            }
        }
        // The cursor at its cell's centre.
        let cx = (((map.cursor.0 as f64 + 0.5) / cols as f64) * w as f64) as usize;
        let cy = (((rows - 1 - map.cursor.1) as f64 + 0.5) / rows as f64 * h as f64) as usize;
        let mut cursor = Style::default()
            .fg(theme.current)
            .add_modifier(Modifier::BOLD);
        if self.focused {
            cursor = cursor.add_modifier(Modifier::REVERSED);
        }
        buf[(plot.x + cx.min(w - 1) as u16, plot.y + cy.min(h - 1) as u16)]
            .set_char(CURSOR)
            .set_style(cursor);
        let (x_name, y_name) = chart.words().axes;
        let n_rows = y_axis.height as usize;
        let mut labels = vec![TextLine::raw(""); n_rows];
        let tick = crate::study::tick;
        if n_rows >= 2 {
            labels[0] = TextLine::styled(format!("{:>7} ", tick(ay.max)), look.dim());
            labels[n_rows - 2] = TextLine::styled(format!("{:>7} ", tick(ay.min)), look.dim());
        }
        if n_rows >= 4 {
            labels[n_rows / 2 - 1] = TextLine::styled(format!("{y_name:>7} "), look.dim());
        }
        Paragraph::new(labels).render(y_axis, buf);
        let (left_end, right) = (tick(ax.min), tick(ax.max));
        let (plain, inferred) = self.cursor_text().unwrap_or_default();
        let cursor = if inferred {
            format!("{plain} (inferred)")
        } else {
            plain.clone()
        };
        let width = x_axis.width as usize;
        let room = width.saturating_sub(3 + left_end.len() + right.len());
        // Where the cursor's words do not fit, without saying the cell was inferred first.
        let middle = [
            format!("{x_name} │ {cursor}"),
            cursor,
            plain,
            x_name.to_owned(),
        ]
        .into_iter()
        .find(|m| m.chars().count() <= room)
        .unwrap_or_default();
        let pad = room.saturating_sub(middle.chars().count()) / 2;
        let left = format!("{left_end} {}{middle}", " ".repeat(pad + 1));
        let gap = width.saturating_sub(left.chars().count() + right.len());
        let text = format!("{left}{}{right}", " ".repeat(gap));
        Paragraph::new(TextLine::styled(text, look.dim())).render(x_axis, buf);
    }
}
