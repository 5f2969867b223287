//! Kapitza's pendulum (issues 11 and 27): cost against accuracy as ε shrinks. For ε = 1e-1 …
//! 1e-9 on the reference start `upright` (a = 1, b = 2, θ0 = 0.3, T = 5), each configuration's
//! error against the references and its best wall time: to ε = 1e-6 the Taylor-series
//! references (`tests/fixtures/reference/kapitza.toml`, long double, independent of this
//! crate), below it the third-order averaged equation in 30 digits
//! (`tests/fixtures/reference/kapitza_small_eps.toml`). The headline is `auto` at each
//! tolerance: planned and verified as `simulate` runs it (its time includes that), it resolves
//! the full motion while no averaged model can meet the tolerance, then takes `averaged3`, then
//! `averaged2`, then the limit with its ripple, so its cost stops growing like `1/ε`.

use serde::Serialize;

use super::best_of;

use crate::physics::Method;
use crate::physics::kapitza::run::run;
use crate::physics::kapitza::{Params, Problem, Start, plan};
use crate::physics::method::RunSpec;

/// The Taylor-series references (ε = 1e-1 … 1e-6), then the averaged references in 30 digits
/// where the full model cannot be resolved (ε = 1e-7 … 1e-9).
const REFERENCES: [&str; 2] = [
    include_str!("../../tests/fixtures/reference/kapitza.toml"),
    include_str!("../../tests/fixtures/reference/kapitza_small_eps.toml"),
];

/// `auto`'s verification budget here, in predicted seconds (as `simulate`'s default).
const VERIFY_BUDGET: f64 = crate::physics::budget::BUDGET_SECONDS;

/// The ε studied.
pub const EPSILONS: [f64; 9] = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9];

/// One measured run.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The fast time scale.
    pub epsilon: f64,
    /// Method asked (`auto` included).
    pub method: String,
    /// What ran.
    pub ran: String,
    /// Tolerance asked.
    pub tolerance: f64,
    /// `auto`'s estimate (empty for the other methods).
    pub estimate: Option<f64>,
    /// Largest error of `θ` and `θ̇` over the reference's 21 samples.
    pub error: f64,
    /// Best wall time, seconds.
    pub seconds: f64,
    /// Right-hand-side evaluations (kicks for the compositions).
    pub rhs_evaluations: u64,
}

struct Reference {
    problem: Problem,
    t_end: f64,
    theta: Vec<f64>,
    theta_dot: Vec<f64>,
}

fn reference(epsilon: f64) -> Option<Reference> {
    REFERENCES
        .iter()
        .find_map(|text| reference_in(text, epsilon))
}

fn reference_in(text: &str, epsilon: f64) -> Option<Reference> {
    let table: toml::Table = text.parse().ok()?;
    let cases = table.get("case")?.as_table()?;
    let c = cases.values().filter_map(toml::Value::as_table).find(|c| {
        c.get("start").and_then(toml::Value::as_str) == Some("upright")
            && c.get("epsilon")
                .and_then(toml::Value::as_float)
                .is_some_and(|e| (e - epsilon).abs() < 1e-3 * epsilon)
    })?;
    let num = |k: &str| c.get(k).and_then(toml::Value::as_float);
    let list = |k: &str| -> Option<Vec<f64>> {
        c.get(k)?
            .as_array()?
            .iter()
            .map(toml::Value::as_float)
            .collect()
    };
    let problem = Problem::new(
        Params {
            a: num("a")?,
            b: num("b")?,
            epsilon: num("epsilon")?,
        },
        Start {
            theta: num("theta0")?,
            theta_dot: num("theta_dot0")?,
        },
    )
    .ok()?;
    Some(Reference {
        problem,
        t_end: num("t_end")?,
        theta: list("theta")?,
        theta_dot: list("theta_dot")?,
    })
}

/// Most right-hand-side evaluations one configuration may cost (larger ones are skipped).
fn budget(quick: bool) -> f64 {
    if quick { 2e6 } else { 4e8 }
}

/// The study: every ε, `auto` at 1e-6, 1e-8 and 1e-9, the resolved `dop853` and `suzuki8` (where
/// they fit the budget), the limit with its ripple and the averaged models.
pub fn study(quick: bool, log: &mut dyn FnMut(&str)) -> Vec<Row> {
    let repeats = if quick { 1 } else { 5 };
    let mut rows = Vec::new();
    for epsilon in EPSILONS {
        let Some(r) = reference(epsilon) else {
            log(&format!("kapitza: no reference at epsilon = {epsilon:e}"));
            continue;
        };
        for (method, tolerance) in [
            (Method::Auto, 1e-6),
            (Method::Auto, 1e-8),
            (Method::Auto, 1e-9),
            (Method::Dop853, 1e-9),
            (Method::Taylor, 1e-9),
            (Method::Suzuki8, 1e-9),
            (Method::EffectiveCorrected, 1e-10),
            (Method::Averaged2, 1e-10),
            (Method::Averaged3, 1e-10),
        ] {
            // `auto` as `simulate` and the explorer run it: planned and verified, then run.
            let verified =
                |p: &Problem| plan::verified(p, tolerance, r.t_end, VERIFY_BUDGET, &mut |_| true);
            let (ran, tol, estimate) = if method == Method::Auto {
                let Ok(c) = verified(&r.problem) else {
                    log(&format!(
                        "kapitza: auto at epsilon = {epsilon:e} failed to plan"
                    ));
                    continue;
                };
                (c.method, c.settings.tolerance, Some(c.estimate))
            } else {
                (method, tolerance, None)
            };
            // The resolved methods follow the fast period: about 100 evaluations a period.
            let resolved = matches!(ran, Method::Dop853 | Method::Taylor | Method::Suzuki8);
            let predicted = if resolved {
                100.0 * r.t_end / (2.0 * std::f64::consts::PI * epsilon)
            } else {
                1e4
            };
            if predicted > budget(quick) {
                log(&format!(
                    "kapitza: {method} at epsilon = {epsilon:e} skipped (about {predicted:.0e} evaluations)"
                ));
                continue;
            }
            let spec = RunSpec {
                method: ran,
                tolerance: tol,
                step: None,
                t_end: r.t_end,
                samples: r.theta.len(),
                monitor_energy: true,
            };
            let Ok(result) = run(&r.problem, &spec, &mut |_| true) else {
                log(&format!(
                    "kapitza: {method} at epsilon = {epsilon:e} failed"
                ));
                continue;
            };
            let error = result
                .samples
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    (s.theta - r.theta[i])
                        .abs()
                        .max((s.theta_dot - r.theta_dot[i]).abs())
                })
                .fold(0.0, f64::max);
            let timed = RunSpec { samples: 0, ..spec };
            // `auto`'s time includes its planning and verification.
            let seconds = best_of(repeats, || {
                if method == Method::Auto {
                    let _ = std::hint::black_box(verified(&r.problem));
                }
                let _ = std::hint::black_box(run(&r.problem, &timed, &mut |_| true));
            });
            rows.push(Row {
                epsilon,
                method: method.name().to_owned(),
                ran: ran.name().to_owned(),
                tolerance,
                estimate,
                error,
                seconds,
                rhs_evaluations: result.stats.rhs_evaluations,
            });
        }
    }
    rows
}

/// The rows as a table, and the headline: the span of `auto`'s cost over ε at each tolerance.
#[must_use]
pub fn table(rows: &[Row]) -> String {
    use std::fmt::Write as _;
    let mut o = String::from(
        "epsilon   method               ran                  tol      estimate  error      seconds     rhs evals\n",
    );
    for r in rows {
        let estimate = r
            .estimate
            .map_or_else(|| "-".to_owned(), |e| format!("{e:.1e}"));
        let _ = writeln!(
            o,
            "{:<9.0e} {:<20} {:<20} {:<8.0e} {:<9} {:<10.2e} {:<11.3e} {}",
            r.epsilon,
            r.method,
            r.ran,
            r.tolerance,
            estimate,
            r.error,
            r.seconds,
            r.rhs_evaluations
        );
    }
    for tol in [1e-6, 1e-8, 1e-9] {
        let _ = writeln!(o, "{}", span_line(rows, tol));
    }
    o
}

/// `auto`'s cost over every ε at `tol`: its span (largest over smallest time, and where), the
/// span from ε = 1e-2 on, and where it did not meet the tolerance or erred above it.
#[must_use]
pub fn span_line(rows: &[Row], tol: f64) -> String {
    let auto: Vec<&Row> = rows
        .iter()
        .filter(|r| r.method == "auto" && r.tolerance.to_bits() == tol.to_bits())
        .collect();
    let extreme = |from: f64| {
        let kept = auto.iter().filter(|r| r.epsilon <= from * (1.0 + 1e-9));
        let lo = kept.clone().min_by(|a, b| a.seconds.total_cmp(&b.seconds));
        let hi = kept.max_by(|a, b| a.seconds.total_cmp(&b.seconds));
        lo.zip(hi)
    };
    let (Some((lo, hi)), Some((lo2, hi2))) = (extreme(1.0), extreme(1e-2)) else {
        return format!("auto at tolerance {tol:.0e}: no rows");
    };
    let unmet: Vec<String> = auto
        .iter()
        .filter(|r| r.estimate.is_some_and(|e| e > tol) || r.error > tol)
        .map(|r| format!("{:.0e}", r.epsilon))
        .collect();
    format!(
        "auto at tolerance {tol:.0e}: cost spans {:.1}x over epsilon {:.0e} … {:.0e} ({:.3e} s at {:.0e}, {:.3e} s at {:.0e}); {:.1}x from 1e-2 on; {}",
        hi.seconds / lo.seconds,
        auto.iter().map(|r| r.epsilon).fold(0.0, f64::max),
        auto.iter().map(|r| r.epsilon).fold(f64::INFINITY, f64::min),
        hi.seconds,
        hi.epsilon,
        lo.seconds,
        lo.epsilon,
        hi2.seconds / lo2.seconds,
        if unmet.is_empty() {
            "met and within the tolerance at every epsilon".to_owned()
        } else {
            format!(
                "not met (estimate or error above it) at {}",
                unmet.join(", ")
            )
        }
    )
}

/// Writes the rows as CSV.
///
/// # Errors
/// When the file cannot be written.
pub fn write_csv(rows: &[Row], path: &std::path::Path) -> std::io::Result<()> {
    super::write_csv_lines(
        path,
        "epsilon,method,ran,tolerance,estimate,error,seconds,rhs_evaluations",
        rows,
        |r| {
            let estimate = r.estimate.map(|e| format!("{e:e}")).unwrap_or_default();
            format!(
                "{:e},{},{},{:e},{estimate},{:e},{:e},{}",
                r.epsilon, r.method, r.ran, r.tolerance, r.error, r.seconds, r.rhs_evaluations
            )
        },
    )
}

/// The study's curves: time against `ε` for each method and tolerance, as an SVG.
///
/// # Errors
/// When drawing or writing fails.
pub fn write_svg(rows: &[Row], path: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for r in rows {
        let label = format!("{} at {:e}", r.method, r.tolerance);
        let point = (r.epsilon, r.seconds * 1e3);
        match series.iter_mut().find(|(l, _)| *l == label) {
            Some((_, s)) => s.push(point),
            None => series.push((label, vec![point])),
        }
    }
    let panel = super::plot::Panel {
        title: "Kapitza's pendulum, T = 5".to_owned(),
        series,
    };
    super::plot::write_curves_svg(
        &[panel],
        ("epsilon", "milliseconds"),
        &plotters::prelude::SeriesLabelPosition::UpperRight,
        path,
    )
}
