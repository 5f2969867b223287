//! SVG files of the studies (plotters), the same plots the explorer's panes show.
use crate::physics::numerics::elementary::Elementary;

use plotters::prelude::*;

use super::chart::ChartOutput;
use super::sweep::Sweep;
use crate::physics::chart::Answer;

type Fallible = Result<String, Box<dyn std::error::Error>>;

pub use super::tick;

/// The sweep: `α_k(t)` of every rung beside the limit, and `sup |α_k − α_eff|` against `k`
/// (log–log) with the fitted slope.
///
/// # Errors
/// When drawing fails.
/// A range a log axis can draw: within `[1e-150, 1e150]`, at most 40 decades and at least one (an
/// infinite or zero end would make the axis loop without end).
fn log_range(lo: f64, hi: f64) -> std::ops::Range<f64> {
    let clamp = |x: f64| {
        if x.is_finite() {
            x.clamp(1e-150, 1e150)
        } else {
            1e150
        }
    };
    let (lo, hi) = (clamp(lo.max(0.0)), clamp(hi));
    let (lo, hi) = if lo < hi { (lo, hi) } else { (hi, lo) };
    // At most 40 decades (the axis's ticks are computed decade by decade).
    let lo = lo.max(hi * 1e-40);
    if hi / lo < 10.0 {
        (hi / 10.0)..hi
    } else {
        lo..hi
    }
}

pub fn sweep_svg(sweep: &Sweep) -> Fallible {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (1200, 500)).into_drawing_area();
        root.fill(&WHITE)?;
        let (left, right) = root.split_horizontally(650);
        let t_end = sweep.t.last().copied().unwrap_or(1.0);
        let all = sweep
            .rungs
            .iter()
            .flat_map(|r| r.alpha.iter())
            .chain(&sweep.limit)
            .copied()
            .filter(|a| a.is_finite());
        let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        let pad = 0.05 * (hi - lo).max(1e-9);
        let words = sweep.model.words();
        let small = sweep.small();
        let (q, parameter) = (words.q_name, small.key);
        let mut chart = ChartBuilder::on(&left)
            .caption(
                format!("{q}(t) closing in on the limit as {parameter} varies"),
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(50)
            .build_cartesian_2d(0.0..t_end, (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .x_desc("t")
            .y_desc(q)
            .x_label_formatter(&|x| tick(*x))
            .y_label_formatter(&|y| tick(*y))
            .draw()?;
        let n = sweep.rungs.len().max(1);
        for (i, r) in sweep.rungs.iter().enumerate() {
            let shade = 0.15 + 0.7 * i as f64 / n as f64;
            let colour = HSLColor(0.6, 0.7, 0.85 - 0.6 * shade);
            chart
                .draw_series(LineSeries::new(
                    sweep.t.iter().copied().zip(r.alpha.iter().copied()),
                    &colour,
                ))?
                .label(format!("{parameter} = {}", tick(r.parameter)))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], colour));
        }
        chart
            .draw_series(LineSeries::new(
                sweep.t.iter().copied().zip(sweep.limit.iter().copied()),
                BLACK.stroke_width(2),
            ))?
            .label("limit")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(2)));
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()?;

        let pts: Vec<(f64, f64)> = sweep
            .rungs
            .iter()
            .map(|r| (r.parameter, r.sup_error))
            .filter(|(k, e)| *k > 0.0 && *e > 0.0 && e.is_finite())
            .collect();
        if !pts.is_empty() {
            let (k0, k1) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.0), b.max(p.0))
            });
            let (e0, e1) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
            let caption = sweep.slope.map_or_else(
                || format!("{} against {parameter}", small.sup),
                |s| format!("{}: slope {s:.2}", small.sup),
            );
            let mut chart = ChartBuilder::on(&right)
                .caption(caption, ("sans-serif", 18))
                .margin(10)
                .x_label_area_size(30)
                .y_label_area_size(60)
                .build_cartesian_2d(
                    log_range(k0 * 0.5, k1 * 2.0).log_scale(),
                    log_range(e0 * 0.3, e1 * 3.0).log_scale(),
                )?;
            chart
                .configure_mesh()
                .x_desc(parameter)
                .x_label_formatter(&|x| tick(*x))
                .y_label_formatter(&|y| tick(*y))
                .draw()?;
            chart.draw_series(LineSeries::new(pts.iter().copied(), &BLUE))?;
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, BLUE.filled())))?;
        }
        root.present()?;
    }
    Ok(out)
}

/// Any scene's chart (issue 59): a rectangle a cell, coloured by its verdict (reversals:
/// white for none, deeper blue for more; stability: green stable, white unstable; grey a cell
/// not decided), the theory's curve in red dots, the preset's cell outlined in black.
///
/// # Errors
/// When drawing fails.
#[allow(clippy::too_many_lines)] // one plot, its four axis kinds spelled out by a macro
pub fn chart_svg(out: &ChartOutput) -> Fallible {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (900, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let (x, y) = (out.columns, out.rows);
        let caption = match &out.position {
            Some(_) => format!(
                "stability of the {} (green stable, grey too close to call); red: {}",
                out.position.as_deref().unwrap_or("upright"),
                out.curve_meaning
            ),
            None => format!(
                "spin reversals in the window (deeper: more; grey: undecided); red: {}",
                out.curve_meaning
            ),
        };
        let columns = out.model.studies().chart.csv;
        let top = out
            .cells
            .iter()
            .filter_map(|c| match c.answer(columns) {
                Some(Answer::Count(n)) => Some(n),
                Some(Answer::Stable(_)) | None => None,
            })
            .max()
            .unwrap_or(0)
            .max(1);
        let edge = |a: &super::chart::Axis, i: usize, side: f64| {
            let f = (i as f64 + side) / a.cells as f64;
            if a.log {
                (a.min.e_ln() + f * (a.max / a.min).e_ln()).e_exp()
            } else {
                a.min + f * (a.max - a.min)
            }
        };
        let cell_colour = |c: &super::chart::CellOutput| -> RGBColor {
            if c.decided == Some(false) {
                return RGBColor(190, 190, 190);
            }
            match c.answer(columns) {
                Some(Answer::Stable(true)) => RGBColor(120, 200, 120),
                Some(Answer::Stable(false) | Answer::Count(0)) | None => WHITE,
                Some(Answer::Count(n)) => {
                    let f = (n as f64 / top as f64).min(1.0);
                    let v = (235.0 - 200.0 * f) as u8;
                    RGBColor(v, v, 255)
                }
            }
        };
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(caption, ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(60);
        let cells = out.cells.iter().map(|c| {
            let (i, j) = (c.index % x.cells, c.index / x.cells);
            (
                [
                    (edge(&x, i, 0.0), edge(&y, j, 0.0)),
                    (edge(&x, i, 1.0), edge(&y, j, 1.0)),
                ],
                cell_colour(c),
            )
        });
        let preset = out.preset_cell.map(|p| {
            [
                (edge(&x, p.column, 0.0), edge(&y, p.row, 0.0)),
                (edge(&x, p.column, 1.0), edge(&y, p.row, 1.0)),
            ]
        });
        let curve = out.curve.iter().map(|p| (p.x, p.y));
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(x.name)
                    .y_desc(y.name)
                    .x_label_formatter(&|v| tick(*v))
                    .y_label_formatter(&|v| tick(*v))
                    .draw()?;
                chart.draw_series(cells.map(|(r, c)| Rectangle::new(r, c.filled())))?;
                chart.draw_series(curve.map(|p| Circle::new(p, 2, RED.filled())))?;
                if let Some(r) = preset {
                    chart.draw_series(std::iter::once(Rectangle::new(r, BLACK.stroke_width(2))))?;
                }
            }};
        }
        match (x.log, y.log) {
            (false, false) => draw!(builder.build_cartesian_2d(x.min..x.max, y.min..y.max)?),
            (false, true) => {
                draw!(builder.build_cartesian_2d(x.min..x.max, (y.min..y.max).log_scale())?);
            }
            (true, false) => {
                draw!(builder.build_cartesian_2d((x.min..x.max).log_scale(), y.min..y.max)?);
            }
            (true, true) => draw!(
                builder
                    .build_cartesian_2d((x.min..x.max).log_scale(), (y.min..y.max).log_scale())?
            ),
        }
        root.present()?;
    }
    Ok(text)
}
