//! The work–precision diagram: error of `alpha(T)` against time, log–log, as an SVG (plotters)
//! and as text for the terminal. Rows are grouped by `k`, compared exactly: they are the
//! constants of [`super::KS`].
#![allow(clippy::float_cmp)]

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
                chart
                    .draw_series(LineSeries::new(series.clone(), colour.stroke_width(2)))?
                    .label(m.clone())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 15, y)], colour.stroke_width(2))
                    });
                chart.draw_series(series.iter().map(|p| Circle::new(*p, 3, colour.filled())))?;
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .label_font(("sans-serif", 10))
                .draw()?;
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
        .filter_map(|r| usable(r).map(|(t, e)| (r.method.as_str(), t.log10(), e.log10())))
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
