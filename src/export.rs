//! The explorer's export (`x`): the phase portrait as it is now, as an SVG (plotters), and the
//! trajectory shown so far as a CSV that starts with `# key = value` lines saying what made it
//! (the same lines as `simulate --format csv`). Above `app` (it reads the app's state) and
//! beside `cast`; written through the one atomic, never-clobbering writer.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use plotters::prelude::*;

use crate::app::{App, ShellError};
use crate::study::svg::tick;

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

/// `points` cut to the rectangle `b`: each run of segments inside is a polyline, a segment that
/// crosses the frame ends (or starts) on it (Liang–Barsky), nothing is drawn along the frame.
#[must_use]
pub fn clip(points: &[(f64, f64)], b: &crate::app::portrait::Bounds) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut open = false;
    for w in points.windows(2) {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        let (dx, dy) = (x1 - x0, y1 - y0);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        let mut inside = true;
        for (p, q) in [
            (-dx, x0 - b.x[0]),
            (dx, b.x[1] - x0),
            (-dy, y0 - b.y[0]),
            (dy, b.y[1] - y0),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    inside = false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        if !inside || t0 > t1 {
            open = false;
            continue;
        }
        let a = (x0 + t0 * dx, y0 + t0 * dy);
        let z = (x0 + t1 * dx, y0 + t1 * dy);
        if !open || t0 > 0.0 {
            out.push(vec![a]);
        }
        if let Some(line) = out.last_mut() {
            line.push(z);
        }
        // The next segment continues this line only if this one ended inside.
        open = t1 >= 1.0;
    }
    out
}

/// A tick label of an axis spanning `span`: a value within 1e-9 of the span from zero is `0`
/// (no `-1.1e-16`).
fn axis_tick(x: f64, span: f64) -> String {
    if x.abs() <= 1e-9 * span.abs() {
        "0".to_owned()
    } else {
        tick(x)
    }
}

/// The portrait's curves as the screen shows them: α folded when wrapped (a curve broken where
/// it folds), clipped to the bounds; the start and the current point.
struct Shown {
    bounds: crate::app::portrait::Bounds,
    trail: Vec<Vec<(f64, f64)>>,
    limit: Vec<Vec<(f64, f64)>>,
    start: (f64, f64),
    now: Option<(f64, f64)>,
}

impl Shown {
    fn of(app: &App) -> Self {
        use crate::app::portrait::{display_alpha, wrap_centre};
        let b = app.bounds();
        let eff = &app.scenario.derived.limit;
        let (wrap, period, centre) = (app.view.view.wrap, eff.period(), wrap_centre(eff));
        let fold = |p: &crate::sim::Point| (display_alpha(p.slow, centre, wrap, period), p.rate);
        let polylines = |points: &[crate::sim::Point]| -> Vec<Vec<(f64, f64)>> {
            let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for p in points.iter().map(fold) {
                let jump = runs
                    .last()
                    .and_then(|r| r.last())
                    .is_some_and(|last| wrap && (p.0 - last.0).abs() > 0.5 * period);
                if jump {
                    runs.push(Vec::new());
                }
                if let Some(run) = runs.last_mut() {
                    run.push(p);
                }
            }
            runs.iter().flat_map(|r| clip(r, &b)).collect()
        };
        let limit = if app.view.overlay {
            polylines(crate::app::run::upto(
                &app.run.effective_trail,
                app.run.shown,
            ))
        } else {
            Vec::new()
        };
        let start = app.scenario.settings.model.slow_start();
        Self {
            bounds: b,
            trail: polylines(app.run.trail_shown()),
            limit,
            start: (display_alpha(start.0, centre, wrap, period), start.1),
            now: app.run.current().map(fold),
        }
    }

    fn inside(&self, (x, y): (f64, f64)) -> bool {
        let b = &self.bounds;
        (b.x[0]..=b.x[1]).contains(&x) && (b.y[0]..=b.y[1]).contains(&y)
    }
}

const GREY: RGBColor = RGBColor(150, 150, 150);
const CYAN: RGBColor = RGBColor(0, 140, 160);
const AMBER: RGBColor = RGBColor(200, 140, 0);
const GREEN: RGBColor = RGBColor(30, 140, 60);
const MAGENTA: RGBColor = RGBColor(170, 40, 170);

type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// The level sets as the screen draws them: dotted, the start's dashed, the separatrix solid.
fn draw_levels(
    chart: &mut Chart<'_, '_>,
    levels: &[crate::app::portrait::Level],
    b: &crate::app::portrait::Bounds,
) -> Result<(), Box<dyn std::error::Error>> {
    use crate::app::portrait::LevelKind;
    for level in levels {
        let (colour, every) = match level.kind {
            LevelKind::Plain => (GREY, 3),
            LevelKind::Start => (CYAN, 2),
            LevelKind::Separatrix => (AMBER, 1),
        };
        for line in &level.lines {
            for (k, w) in line.windows(2).enumerate() {
                if k % every == 0 {
                    for piece in clip(w, b) {
                        chart.draw_series(LineSeries::new(piece, colour.stroke_width(1)))?;
                    }
                }
            }
        }
    }
    Ok(())
}

/// The legend in its own column: a line (or a dot) and a label per entry.
fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    entries: Vec<(String, RGBColor, bool)>,
) -> Result<(), Box<dyn std::error::Error>> {
    for (k, (label, colour, dot)) in entries.into_iter().enumerate() {
        let y = 60 + 26 * i32::try_from(k).unwrap_or(0);
        if dot {
            area.draw(&Circle::new((22, y), 5, colour.filled()))?;
        } else {
            area.draw(&PathElement::new(
                vec![(10, y), (34, y)],
                colour.stroke_width(2),
            ))?;
        }
        area.draw(&Text::new(label, (42, y - 7), ("sans-serif", 14)))?;
    }
    Ok(())
}

/// The portrait as an SVG, as the screen shows it: the same range (zoom, pan, wrap, following),
/// the level sets (dotted), the start's level (dashed) and the separatrix (solid), the trail,
/// the limit (when shown), the start and the current point, every curve clipped to the frame;
/// round tick labels; the legend in its own column right of the plot.
///
/// # Errors
/// When drawing fails.
pub fn portrait_svg(app: &App) -> Result<String, Box<dyn std::error::Error>> {
    let s = &app.scenario.settings;
    let shown = Shown::of(app);
    let b = shown.bounds;
    let eff = &app.scenario.derived.limit;
    let words = s.model.kind().words();
    let level_sets = crate::app::portrait::levels(eff, &b, eff.energy(), app.view.view.levels, 400);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (960, 640)).into_drawing_area();
        root.fill(&WHITE)?;
        let (plot_area, legend_area) = root.split_horizontally(740);
        let caption = format!(
            "{}: {}, t {} of {}",
            crate::scenario::text::clean(&app.scenario.name),
            describe(&s.model),
            tick(app.run.shown),
            tick(s.t_end)
        );
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(caption, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(b.x[0]..b.x[1], b.y[0]..b.y[1])?;
        let (sx, sy) = (b.x[1] - b.x[0], b.y[1] - b.y[0]);
        let x_desc = if app.view.view.wrap {
            format!("{} (wrapped)", words.q_name)
        } else {
            words.q_name.to_owned()
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_desc)
            .y_desc(words.q_dot_name)
            .x_label_formatter(&|x| axis_tick(*x, sx))
            .y_label_formatter(&|y| axis_tick(*y, sy))
            .draw()?;
        draw_levels(&mut chart, &level_sets, &b)?;
        // The limit wide and pale beneath, the full motion on top: both stay visible where
        // they coincide (a stiff spring), as the screen's sparse marks let the trail show.
        for piece in &shown.limit {
            chart.draw_series(LineSeries::new(
                piece.iter().copied(),
                MAGENTA.mix(0.45).stroke_width(5),
            ))?;
        }
        for piece in &shown.trail {
            chart.draw_series(LineSeries::new(
                piece.iter().copied(),
                GREEN.stroke_width(1),
            ))?;
        }
        if shown.inside(shown.start) {
            chart.draw_series(std::iter::once(Circle::new(shown.start, 4, BLACK.filled())))?;
        }
        if let Some(now) = shown.now.filter(|p| shown.inside(*p)) {
            chart.draw_series(std::iter::once(Circle::new(now, 5, RED.filled())))?;
        }
        let mut entries: Vec<(String, RGBColor, bool)> = vec![
            ("energy levels (dotted)".to_owned(), GREY, false),
            ("start's level (dashed)".to_owned(), CYAN, false),
            ("separatrix".to_owned(), AMBER, false),
            ("full motion".to_owned(), GREEN, false),
        ];
        if app.view.overlay {
            let small = s.model.kind().small();
            let label = small.map_or_else(|| "limit".to_owned(), |s| format!("limit {}", s.limit));
            entries.push((format!("{label} (wide, pale)"), MAGENTA, false));
        }
        entries.push(("start".to_owned(), BLACK, true));
        entries.push(("now".to_owned(), RED, true));
        draw_legend(&legend_area, entries)?;
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
    // The monitor's column when the scene has one.
    let monitor = w
        .monitor
        .map_or_else(String::new, |m| format!(",{}", m.column));
    let _ = writeln!(out, "t,{q},{q_dot}{monitor},limit_{q},limit_{q_dot}");
    let limit = if app.view.overlay {
        crate::app::run::upto(&app.run.effective_trail, app.run.shown)
    } else {
        &[]
    };
    // Both on one time grid: walk them together.
    let mut j = 0;
    for p in app.run.trail_shown() {
        let _ = write!(out, "{},{},{}", p.t, p.slow, p.rate);
        if w.monitor.is_some() {
            let _ = write!(out, ",{}", p.energy_error);
        }
        while j < limit.len() && limit[j].t < p.t {
            j += 1;
        }
        match limit.get(j) {
            // The same grid point: the same bits.
            Some(q) if q.t.to_bits() == p.t.to_bits() => {
                let _ = writeln!(out, ",{},{}", q.slow, q.rate);
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
pub fn export(app: &App, dir: &Path, stem: &str) -> Result<Vec<PathBuf>, ShellError> {
    std::fs::create_dir_all(dir).map_err(|source| ShellError::Io {
        path: dir.to_owned(),
        source,
    })?;
    let svg = portrait_svg(app).map_err(|e| ShellError::Drawing(e.to_string()))?;
    let csv = trajectory_csv(app);
    let mut written = Vec::new();
    for (ext, text) in [("svg", svg), ("csv", csv)] {
        let path = crate::scenario::write::fresh_name(dir, stem, ext);
        crate::scenario::write::write_atomic(&path, text.as_bytes(), false).map_err(|source| {
            ShellError::Io {
                path: path.clone(),
                source,
            }
        })?;
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::portrait::Bounds;

    #[test]
    fn clipping_keeps_the_inside_and_ends_on_the_frame() {
        let b = Bounds {
            x: [0.0, 1.0],
            y: [0.0, 1.0],
        };
        // Inside: unchanged.
        assert_eq!(
            clip(&[(0.1, 0.1), (0.5, 0.5)], &b),
            vec![vec![(0.1, 0.1), (0.5, 0.5)]]
        );
        // Out, in, out: one piece from frame to frame.
        let got = clip(&[(-1.0, 0.5), (0.5, 0.5), (2.0, 0.5)], &b);
        assert_eq!(got, vec![vec![(0.0, 0.5), (0.5, 0.5), (1.0, 0.5)]]);
        // Leaving and coming back: two pieces, nothing along the frame.
        let got = clip(&[(0.5, 0.5), (0.5, 2.0), (0.6, 2.0), (0.6, 0.5)], &b);
        assert_eq!(
            got,
            vec![vec![(0.5, 0.5), (0.5, 1.0)], vec![(0.6, 1.0), (0.6, 0.5)]]
        );
        // Wholly outside: nothing.
        assert!(clip(&[(2.0, 2.0), (3.0, 3.0)], &b).is_empty());
    }

    #[test]
    fn tick_labels_near_zero_are_zero() {
        assert_eq!(axis_tick(-1.1e-16, 2.0), "0");
        assert_eq!(axis_tick(0.5, 2.0), "0.5");
    }
}
