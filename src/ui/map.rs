//! The regime-map pane (toggle `M`): the reversals in `(0, T]` of the starts `γ0 = α0 = 0`,
//! `α̇0 = √ratio · γ̇0` over a grid of `(α̇0²/γ̇0², iy/ix)`, one glyph per cell whose density
//! grows with the count (blank: none; `░` 1, `▒` 2–3, `▓` 4–7, `█` 8 or more; `·` not computed
//! yet), so it reads without colour; the paper's critical ratio `(ix/iz)(√(ix/iy) − 1)` drawn
//! over it as `┃`; the cursor `+` (reverse video while the map has the arrows). Rows are
//! log-spaced in `iy/ix`, the largest at the top.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::Line as TextLine;
use ratatui::widgets::{Paragraph, Widget};

use super::marks::{Facts, Section, printed};
use super::{Look, framed};
use crate::app::computed::map::{MapSource, MapState};
use crate::study::map::Source;

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

/// The critical curve's mark, and the cursor's.
const CRITICAL: char = '┃';
const CURSOR: char = '+';

/// What the pane draws, for the legend (the same glyphs as [`glyph`]).
pub fn legend(_: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let ramp: String = [1, 2, 4, 8]
        .into_iter()
        .map(|n| look.charset.mark(glyph(Some(n))))
        .collect();
    Section::new("regime map (M)")
        .mark(
            ramp,
            t.trail,
            "reversals in [0, T]: 1, 2-3, 4-7, 8 or more (blank: none)",
        )
        .mark(printed(look, glyph(None)), t.dim, "a cell not computed yet")
        .mark(
            printed(look, CRITICAL),
            t.separatrix,
            "the critical ratio of the paper's theorems",
        )
        .mark(
            printed(look, CURSOR),
            t.current,
            "the cursor (M gives it the arrows, Enter loads the cell)",
        )
        .note("across: alpha_dot0^2/gamma_dot0^2; up: iy/ix (log); f: limit or full model")
}

/// The regime-map pane: what it shows, borrowed.
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
        let source = match map.spec.map(|s| s.source) {
            Some(Source::Full { k, .. }) => format!("full model, k {}", crate::study::svg::tick(k)),
            _ if map.source == MapSource::Full => "full model".to_owned(),
            _ => "limit".to_owned(),
        };
        let total = map.cells.len();
        let progress = match (&map.failed, map.done) {
            (Some(why), _) => format!("stopped: {why}"),
            (None, true) => format!("{total} cells"),
            (None, false) => format!("{}/{total} cells…", map.computed()),
        };
        let keys = if self.focused { "Enter f Esc" } else { "M" };
        format!("map ({source}) {progress} │ {keys}")
    }

    /// What the cursor's cell is, for the x-axis row.
    fn cursor_text(&self) -> Option<String> {
        let map = self.map;
        let (r, i) = map.at_cursor()?;
        let count = map
            .cell(map.cursor.0, map.cursor.1)
            .map_or_else(|| "?".to_owned(), |c| c.to_string());
        Some(format!("+ ratio {r:.3} iy/ix {i:.3}: {count} rev"))
    }
}

impl Widget for MapPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (map, look) = (self.map, self.look);
        let inner = framed(&self.heading(), area, buf);
        let (y_axis, plot, x_axis) = super::plot_areas(inner);
        let Some(spec) = map.spec else { return };
        let g = spec.grid;
        let (w, h) = (plot.width as usize, plot.height as usize);
        if w == 0 || h == 0 {
            return;
        }
        let theme = look.theme;
        let cell_style = Style::default().fg(theme.trail);
        let (lo, hi) = g.inertia;
        // Row `y` of the plot (0 at the top) shows the inertia ratio at its centre.
        let inertia_at = |y: usize| {
            let f = 1.0 - (y as f64 + 0.5) / h as f64;
            (lo.ln() + f * (hi / lo).ln()).exp()
        };
        for y in 0..h {
            let j = g.rows - 1 - ((y * g.rows) / h).min(g.rows - 1);
            for x in 0..w {
                let i = ((x * g.cols) / w).min(g.cols - 1);
                let count = map.cell(i, j);
                let style = if count.is_none() {
                    look.dim()
                } else {
                    cell_style
                };
                buf[(plot.x + x as u16, plot.y + y as u16)]
                    .set_char(glyph(count))
                    .set_style(style);
            }
            if let Some(c) = g.critical(inertia_at(y)) {
                let x = (c / g.ratio_max * w as f64).floor();
                if (0.0..w as f64).contains(&x) {
                    buf[(plot.x + x as u16, plot.y + y as u16)]
                        .set_char(CRITICAL)
                        .set_style(
                            Style::default()
                                .fg(theme.separatrix)
                                .add_modifier(Modifier::BOLD),
                        );
                }
            }
        }
        // The cursor at its cell's centre.
        let cx = (((map.cursor.0 as f64 + 0.5) / g.cols as f64) * w as f64) as usize;
        let cy = (((g.rows - 1 - map.cursor.1) as f64 + 0.5) / g.rows as f64 * h as f64) as usize;
        let mut cursor = Style::default()
            .fg(theme.current)
            .add_modifier(Modifier::BOLD);
        if self.focused {
            cursor = cursor.add_modifier(Modifier::REVERSED);
        }
        buf[(plot.x + cx.min(w - 1) as u16, plot.y + cy.min(h - 1) as u16)]
            .set_char(CURSOR)
            .set_style(cursor);
        let rows = y_axis.height as usize;
        let mut labels = vec![TextLine::raw(""); rows];
        let tick = crate::study::svg::tick;
        if rows >= 2 {
            labels[0] = TextLine::styled(format!("{:>7} ", tick(hi)), look.dim());
            labels[rows - 2] = TextLine::styled(format!("{:>7} ", tick(lo)), look.dim());
        }
        if rows >= 4 {
            labels[rows / 2 - 1] = TextLine::styled(format!("{:>7} ", "iy/ix"), look.dim());
        }
        Paragraph::new(labels).render(y_axis, buf);
        let right = tick(g.ratio_max);
        let axis = "alpha_dot0^2/gamma_dot0^2";
        let cursor = self.cursor_text().unwrap_or_default();
        let width = x_axis.width as usize;
        let room = width.saturating_sub(4 + right.len());
        let middle = [format!("{axis} │ {cursor}"), cursor, axis.to_owned()]
            .into_iter()
            .find(|m| m.chars().count() <= room)
            .unwrap_or_default();
        let pad = room.saturating_sub(middle.chars().count()) / 2;
        let left = format!("0 {}{middle}", " ".repeat(pad + 1));
        let gap = width.saturating_sub(left.chars().count() + right.len());
        let text = format!("{left}{}{right}", " ".repeat(gap));
        Paragraph::new(TextLine::styled(text, look.dim())).render(x_axis, buf);
    }
}
