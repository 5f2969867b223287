//! The explorer's export (`x`): the phase portrait as it is now, as an SVG (plotters), and the
//! trajectory shown so far as a CSV that starts with `# key = value` lines saying what made it
//! (the same lines as `simulate --format csv`). Above `app` (it reads the app's state) and
//! beside `cast`; written through the one atomic, never-clobbering writer.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use plotters::prelude::*;

use crate::app::App;
use crate::study::svg::tick;

/// The separatrices of the limit, `E_eff(q, q̇) = V` at each unstable equilibrium, as two
/// branches each over `[x0, x1]`.
fn separatrix(app: &App, x0: f64, x1: f64) -> Vec<Vec<(f64, f64)>> {
    let eff = &app.scenario.derived.limit;
    let mut out = Vec::new();
    for top in eff.separatrices() {
        let mut upper = Vec::new();
        let n = 400;
        for i in 0..=n {
            let a = x0 + (x1 - x0) * f64::from(i) / f64::from(n);
            let base = eff.energy_of(a, 0.0);
            let c = eff.energy_of(a, 1.0) - base;
            if c > 0.0 && top >= base {
                upper.push((a, ((top - base) / c).sqrt()));
            }
        }
        let lower = upper.iter().map(|&(a, v)| (a, -v)).collect();
        out.push(upper);
        out.push(lower);
    }
    out
}

/// The model's physical parameters for a caption (the start left out; the small parameter by
/// its symbol).
fn describe(model: &crate::physics::Model) -> String {
    let kind = model.kind();
    let small = kind.small();
    kind.params()
        .iter()
        .zip(model.values())
        .filter(|(p, _)| p.section != "initial")
        .map(|(p, v)| {
            let name = small.filter(|s| s.key == p.key).map_or(p.key, |s| s.symbol);
            format!("{name} {}", tick(v))
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The portrait as an SVG: the full trajectory shown so far, the limit's (when shown), the
/// separatrix, the start and the current point; α unwrapped.
///
/// # Errors
/// When drawing fails.
pub fn portrait_svg(app: &App) -> Result<String, Box<dyn std::error::Error>> {
    let trail: Vec<(f64, f64)> = app
        .run
        .trail_shown()
        .iter()
        .map(|p| (p.alpha, p.alpha_dot))
        .collect();
    let limit: Vec<(f64, f64)> = if app.view.overlay {
        crate::app::run::upto(&app.run.effective_trail, app.run.shown)
            .iter()
            .map(|p| (p.alpha, p.alpha_dot))
            .collect()
    } else {
        Vec::new()
    };
    let s = &app.scenario.settings;
    let start = s.model.slow_start();
    let words = s.model.kind().words();
    let params = describe(&s.model);
    let small = s.model.kind().small();
    let (mut x0, mut x1, mut y0, mut y1) = (start.0, start.0, start.1, start.1);
    for &(x, y) in trail.iter().chain(&limit) {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let (px, py) = (0.08 * (x1 - x0).max(0.1), 0.08 * (y1 - y0).max(0.1));
    let (x0, x1, y0, y1) = (x0 - px, x1 + px, y0 - py, y1 + py);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (900, 640)).into_drawing_area();
        root.fill(&WHITE)?;
        let caption = format!(
            "{}: {params}, t {} of {}",
            crate::scenario::text::clean(&app.scenario.name),
            tick(app.run.shown),
            tick(s.t_end)
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(words.q_name)
            .y_desc(words.q_dot_name)
            .x_label_formatter(&|x| tick(*x))
            .y_label_formatter(&|y| tick(*y))
            .draw()?;
        let sep_colour = RGBColor(200, 150, 0);
        for (i, branch) in separatrix(app, x0, x1).into_iter().enumerate() {
            let series = chart.draw_series(LineSeries::new(branch, sep_colour.stroke_width(1)))?;
            if i == 0 {
                series
                    .label("separatrix of the limit")
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], sep_colour));
            }
        }
        let green = RGBColor(30, 140, 60);
        chart
            .draw_series(LineSeries::new(
                trail.iter().copied(),
                green.stroke_width(1),
            ))?
            .label("full motion")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], green));
        if !limit.is_empty() {
            let magenta = RGBColor(170, 40, 170);
            chart
                .draw_series(LineSeries::new(
                    limit.iter().copied(),
                    magenta.stroke_width(2),
                ))?
                .label(small.map_or_else(|| "limit".to_owned(), |s| format!("limit {}", s.limit)))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], magenta));
        }
        chart
            .draw_series(std::iter::once(Circle::new(start, 4, BLACK.filled())))?
            .label("start")
            .legend(|(x, y)| Circle::new((x + 8, y), 4, BLACK.filled()));
        if let Some(&last) = trail.last() {
            chart
                .draw_series(std::iter::once(Circle::new(last, 5, RED.filled())))?
                .label("now")
                .legend(|(x, y)| Circle::new((x + 8, y), 5, RED.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()?;
        root.present()?;
    }
    Ok(out)
}

/// The trajectory shown so far as CSV: the metadata lines, then
/// `t,alpha,alpha_dot,energy_error,limit_alpha,limit_alpha_dot` (the limit's columns empty when
/// it is hidden; both motions are sampled on the same grid).
#[must_use]
pub fn trajectory_csv(app: &App) -> String {
    let s = &app.scenario.settings;
    let ran = match app.run.plan {
        crate::app::PlanState::Running { plan, .. } => Some(plan.method),
        _ => None,
    };
    let mut out = crate::simulate::csv_metadata_of(
        &app.scenario.name,
        &s.model,
        s.method,
        ran,
        s.tolerance,
        s.t_end,
    );
    let w = s.model.kind().words();
    let (q, q_dot) = (w.q_name, w.q_dot_name);
    let _ = writeln!(
        out,
        "t,{q},{q_dot},{},limit_{q},limit_{q_dot}",
        w.monitor_column
    );
    let limit = if app.view.overlay {
        crate::app::run::upto(&app.run.effective_trail, app.run.shown)
    } else {
        &[]
    };
    // Both on one time grid: walk them together.
    let mut j = 0;
    for p in app.run.trail_shown() {
        let _ = write!(
            out,
            "{},{},{},{}",
            p.t, p.alpha, p.alpha_dot, p.energy_error
        );
        while j < limit.len() && limit[j].t < p.t {
            j += 1;
        }
        match limit.get(j) {
            // The same grid point: the same bits.
            Some(q) if q.t.to_bits() == p.t.to_bits() => {
                let _ = writeln!(out, ",{},{}", q.alpha, q.alpha_dot);
            }
            _ => out.push_str(",,\n"),
        }
    }
    out
}

/// Writes both files into `dir` (created if missing) with fresh readable names after `stem`;
/// returns their paths.
///
/// # Errors
/// What went wrong, for the status line.
pub fn export(app: &App, dir: &Path, stem: &str) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let svg = portrait_svg(app).map_err(|e| format!("drawing the portrait: {e}"))?;
    let csv = trajectory_csv(app);
    let mut written = Vec::new();
    for (ext, text) in [("svg", svg), ("csv", csv)] {
        let path = crate::scenario::write::fresh_name(dir, stem, ext);
        crate::scenario::write::write_atomic(&path, text.as_bytes(), false)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}
