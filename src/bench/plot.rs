//! The work–precision diagram: error of `alpha(T)` against time, log–log, as an SVG (plotters)
//! and as text for the terminal. Rows are grouped by `k`, compared exactly: they are the
//! constants of [`super::KS`].
#![allow(clippy::float_cmp)]
use crate::physics::numerics::elementary::Elementary;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use super::Row;

const PALETTE: [RGBColor; 11] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(0, 0, 0),
];

/// A log–log chart on an SVG string.
type LogChart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// One labelled series: a line through its points, and the points.
fn draw_line(
    chart: &mut LogChart<'_, '_>,
    label: &str,
    colour: RGBColor,
    series: &[(f64, f64)],
) -> Result<(), Box<dyn std::error::Error>> {
    chart
        .draw_series(LineSeries::new(series.to_vec(), colour.stroke_width(2)))?
        .label(label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], colour.stroke_width(2)));
    chart.draw_series(series.iter().map(|p| Circle::new(*p, 3, colour.filled())))?;
    Ok(())
}

/// The series' legend, boxed, at `position` (plotters' default where `None`).
fn draw_legend<'a>(
    chart: &mut LogChart<'a, 'a>,
    position: Option<&SeriesLabelPosition>,
    font_size: u32,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut labels = chart.configure_series_labels();
    if let Some(p) = position {
        labels.position(p.clone());
    }
    labels
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", font_size))
        .draw()?;
    Ok(())
}

fn usable(r: &Row) -> Option<(f64, f64)> {
    (r.error_alpha.is_finite() && r.seconds > 0.0).then(|| (r.seconds, r.error_alpha.max(1e-16)))
}

/// Draws one panel per stiffness into an SVG file.
///
/// # Errors
/// When drawing or writing fails.
pub fn write_svg(rows: &[Row], path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let ks: Vec<f64> = rows.iter().map(|r| r.k).fold(Vec::new(), |mut v, k| {
        if !v.contains(&k) {
            v.push(k);
        }
        v
    });
    let methods: Vec<String> =
        rows.iter()
            .map(|r| r.method.clone())
            .fold(Vec::new(), |mut v, m| {
                if !v.contains(&m) {
                    v.push(m);
                }
                v
            });
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1200, 800)).into_drawing_area();
        root.fill(&WHITE)?;
        let panels = root.split_evenly((2, 3));
        for (panel, k) in panels.iter().zip(&ks) {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.k == *k)
                .filter_map(usable)
                .collect();
            let (t0, t1) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.0), b.max(p.0))
            });
            let (e0, e1) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
            if pts.is_empty() {
                continue;
            }
            let mut chart = ChartBuilder::on(panel)
                .caption(format!("k = {k:e}"), ("sans-serif", 18))
                .margin(8)
                .x_label_area_size(30)
                .y_label_area_size(50)
                .build_cartesian_2d(
                    (t0 * 0.5..t1 * 2.0).log_scale(),
                    (e0 * 0.3..e1 * 3.0).log_scale(),
                )?;
            chart
                .configure_mesh()
                .x_desc("seconds")
                .y_desc("error of alpha(T)")
                .draw()?;
            for (i, m) in methods.iter().enumerate() {
                let colour = PALETTE[i % PALETTE.len()];
                let mut series: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.k == *k && &r.method == m)
                    .filter_map(usable)
                    .collect();
                series.sort_by(|a, b| a.0.total_cmp(&b.0));
                if series.is_empty() {
                    continue;
                }
                draw_line(&mut chart, m, colour, &series)?;
            }
            draw_legend(&mut chart, None, 10)?;
        }
        root.present()?;
    }
    crate::scenario::write::write_atomic(path, svg.as_bytes(), true)?;
    Ok(())
}

/// A text scatter of error against time for one stiffness: one letter per method.
#[must_use]
pub fn terminal_diagram(rows: &[Row], k: f64, width: usize, height: usize) -> String {
    let pts: Vec<(&str, f64, f64)> = rows
        .iter()
        .filter(|r| r.k == k)
        .filter_map(|r| usable(r).map(|(t, e)| (r.method.as_str(), t.e_log10(), e.e_log10())))
        .collect();
    if pts.is_empty() {
        return String::new();
    }
    let (x0, x1) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    let (y0, y1) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.2), b.max(p.2))
        });
    let mut grid = vec![vec![' '; width]; height];
    let mut legend: BTreeMap<&str, char> = BTreeMap::new();
    let letters = "abcdefghijklmnopqrstuvwxyz";
    for (m, x, y) in &pts {
        let n = legend.len();
        let c = *legend
            .entry(m)
            .or_insert_with(|| letters.chars().nth(n).unwrap_or('?'));
        let col = (((x - x0) / (x1 - x0).max(1e-9)) * (width - 1) as f64).round() as usize;
        let row = (((y1 - y) / (y1 - y0).max(1e-9)) * (height - 1) as f64).round() as usize;
        grid[row.min(height - 1)][col.min(width - 1)] = c;
    }
    let mut o = format!(
        "k = {k:e}: error of alpha(T) (10^{y1:.1} top, 10^{y0:.1} bottom) against seconds (10^{x0:.1} left, 10^{x1:.1} right)\n"
    );
    for line in grid {
        o.push('|');
        o.extend(line);
        o.push('\n');
    }
    let _ = writeln!(o, "+{}", "-".repeat(width));
    for (m, c) in legend {
        let _ = write!(o, "  {c} {m}");
    }
    o.push('\n');
    o
}

/// A tick label with at most three significant digits (log axes put ticks at values such as
/// 0.6000000000000001).
fn significant(y: f64) -> String {
    if (1e-3..1e4).contains(&y) {
        let decimals = (2 - y.e_log10().floor() as i32).clamp(0, 6) as usize;
        let t = format!("{y:.decimals$}");
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            t
        }
    } else {
        format!("{y:.1e}")
    }
}

/// One panel of [`write_curves_svg`]: a title and its named series of `(x, y)` points.
pub struct Panel {
    /// Caption.
    pub title: String,
    /// `(label, points)`; points with a non-positive or non-finite coordinate are left out.
    pub series: Vec<(String, Vec<(f64, f64)>)>,
}

/// Cost curves, log–log, one panel per entry side by side, as an SVG file (the `auto`
/// profile's time against `k`, the pendulum's against `ε`).
///
/// # Errors
/// When drawing or writing fails.
pub fn write_curves_svg(
    panels: &[Panel],
    (x_desc, y_desc): (&str, &str),
    legend: &SeriesLabelPosition,
    path: &Path,
) -> Result<(), Box<dyn std::error::Error>> {
    let ok = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite() && p.0 > 0.0 && p.1 > 0.0;
    let mut svg = String::new();
    {
        let width = 560 * u32::try_from(panels.len().max(1)).unwrap_or(1);
        let root = SVGBackend::with_string(&mut svg, (width, 420)).into_drawing_area();
        root.fill(&WHITE)?;
        let areas = root.split_evenly((1, panels.len().max(1)));
        for (area, panel) in areas.iter().zip(panels) {
            let pts: Vec<(f64, f64)> = panel
                .series
                .iter()
                .flat_map(|(_, s)| s.iter().filter(ok).copied())
                .collect();
            if pts.is_empty() {
                continue;
            }
            let bounds = |f: fn(&(f64, f64)) -> f64| {
                pts.iter()
                    .map(f)
                    .fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(v), b.max(v)))
            };
            let ((x0, x1), (y0, y1)) = (bounds(|p| p.0), bounds(|p| p.1));
            let mut chart = ChartBuilder::on(area)
                .caption(&panel.title, ("sans-serif", 18))
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(55)
                .build_cartesian_2d(
                    (x0 * 0.5..x1 * 2.0).log_scale(),
                    (y0 * 0.5..y1 * 2.0).log_scale(),
                )?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(y_desc)
                .x_label_formatter(&|x| format!("{x:.0e}"))
                .y_label_formatter(&|y| significant(*y))
                .light_line_style(RGBColor(240, 240, 240))
                .draw()?;
            for (i, (label, series)) in panel.series.iter().enumerate() {
                let colour = PALETTE[i % PALETTE.len()];
                let series: Vec<(f64, f64)> = series.iter().filter(ok).copied().collect();
                if series.is_empty() {
                    continue;
                }
                draw_line(&mut chart, label, colour, &series)?;
            }
            draw_legend(&mut chart, Some(legend), 11)?;
        }
        root.present()?;
    }
    crate::scenario::write::write_atomic(path, svg.as_bytes(), true)?;
    Ok(())
}
