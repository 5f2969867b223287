//! The celt (issue 26): run time against error on every shipped celt preset that has a
//! reference. Each configuration's error is that of the final `ω` (rad/s) against the
//! independent references of `tests/fixtures/celt/references.json` (scipy's DOP853 at rtol
//! 1e-13 on an implementation that shares no code with the crate, two derivations), with its
//! crossing and reversal counts checked against the reference's; the headline is `auto`
//! (verification included) against the cheapest single configuration that meets the same
//! tolerance, which a user could only have chosen knowing the reference.

use serde::Serialize;

use super::best_of;

use crate::physics::celt::plan::resolve;
use crate::physics::celt::run::run;
use crate::physics::celt::{Problem, omega};
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::models::Model;
use crate::physics::plan::{AutoRules, PlanRequest};

const REFERENCES: &str = include_str!("../../tests/fixtures/celt/references.json");

/// The tolerances studied.
pub const TOLERANCES: [f64; 4] = [1e-6, 1e-8, 1e-10, 1e-12];

/// One measured configuration.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The preset.
    pub preset: String,
    /// Method asked (`auto` included).
    pub method: String,
    /// Tolerance asked.
    pub tolerance: f64,
    /// What `auto` ran at (its local tolerance), else the tolerance.
    pub ran_at: f64,
    /// `auto`'s estimate (none for the other methods).
    pub estimate: Option<f64>,
    /// Whether `auto` says it met the tolerance.
    pub met: Option<bool>,
    /// Largest error of the final `ω` against the reference (rad/s).
    pub error: f64,
    /// The reference's own uncertainty there (the spread of its two derivations).
    pub reference_uncertainty: f64,
    /// Crossing and reversal counts equal to the reference's.
    pub counts_exact: bool,
    /// Best wall time, seconds (`auto`: its verification included).
    pub seconds: f64,
    /// Right-hand-side evaluations of the returned run.
    pub rhs_evaluations: u64,
}

struct Reference {
    preset: String,
    problem: Problem,
    t_end: f64,
    omega: [f64; 3],
    uncertainty: f64,
    crossings: usize,
    reversals: usize,
}

fn references(log: &mut dyn FnMut(&str)) -> Vec<Reference> {
    let Ok(json) = serde_json::from_str::<serde_json::Value>(REFERENCES) else {
        log("celt: the references do not parse");
        return Vec::new();
    };
    let cases = json["cases"].as_array().cloned().unwrap_or_default();
    cases
        .iter()
        .filter_map(|c| {
            let name = c["preset"].as_str()?;
            let preset = crate::scenario::shipped::resolve(name, &[]).ok()?;
            let Model::Celt(problem) = preset.model else {
                return None;
            };
            let w = c["reference"]["omega"].as_array()?;
            let count = |k: &str| c["reference"][k].as_u64().map(|n| n as usize);
            Some(Reference {
                preset: name.to_owned(),
                problem,
                t_end: c["t_end"].as_f64()?,
                omega: [w[0].as_f64()?, w[1].as_f64()?, w[2].as_f64()?],
                uncertainty: c["omega_uncertainty"].as_f64().unwrap_or(0.0),
                crossings: count("crossings")?,
                reversals: count("reversals")?,
            })
        })
        .collect()
}

/// The study: every preset with a reference, `dop853`, `dop853-projected` and `auto` at every
/// tolerance of [`TOLERANCES`] (`quick`: the first two presets, 1e-6 and 1e-10, one repeat).
pub fn study(quick: bool, log: &mut dyn FnMut(&str)) -> Vec<Row> {
    let repeats = if quick { 1 } else { 5 };
    let mut rows = Vec::new();
    let refs = references(log);
    let take = if quick { 2 } else { refs.len() };
    for r in refs.iter().take(take) {
        let tolerances: &[f64] = if quick { &[1e-6, 1e-10] } else { &TOLERANCES };
        for &tolerance in tolerances {
            for method in [Method::Dop853, Method::Dop853Projected, Method::Auto] {
                match measure(r, method, tolerance, repeats) {
                    Ok(row) => rows.push(row),
                    Err(e) => log(&format!(
                        "celt: {} {method} at {tolerance:e} failed: {e}",
                        r.preset
                    )),
                }
            }
        }
    }
    rows
}

fn measure(
    r: &Reference,
    method: Method,
    tolerance: f64,
    repeats: usize,
) -> Result<Row, crate::physics::method::StepError> {
    let ask = PlanRequest {
        method,
        tolerance,
        t_end: r.t_end,
        policy: AutoRules::Verified,
        budget: f64::INFINITY,
    };
    let plan = |go: &mut dyn FnMut(f64) -> bool| resolve(&r.problem, &ask, go);
    let resolution = plan(&mut |_| true)?;
    let spec = RunSpec {
        method: resolution.plan.method,
        tolerance: resolution.plan.tolerance,
        t_end: r.t_end,
        samples: 0,
        step: None,
        monitor_energy: true,
    };
    let result = run(&r.problem, &spec, &mut |_| true)?;
    let w = omega(&result.state);
    let error = (0..3)
        .map(|i| (w[i] - r.omega[i]).abs())
        .fold(0.0, f64::max);
    // `auto` is timed as a user pays for it: the planning (its probes and verification) and
    // the run it returns.
    let seconds = best_of(repeats, || {
        if method == Method::Auto {
            let _ = std::hint::black_box(plan(&mut |_| true));
        }
        let _ = std::hint::black_box(run(&r.problem, &spec, &mut |_| true));
    });
    let auto = method == Method::Auto;
    Ok(Row {
        preset: r.preset.clone(),
        method: method.name().to_owned(),
        tolerance,
        ran_at: spec.tolerance,
        estimate: resolution.estimate.filter(|_| auto),
        met: auto.then_some(resolution.shortfall.is_none()),
        error,
        reference_uncertainty: r.uncertainty,
        counts_exact: result.crossing_count == r.crossings && result.reversal_count == r.reversals,
        seconds,
        rhs_evaluations: result.stats.rhs_evaluations,
    })
}

/// For every `auto` row: the cheapest single configuration (a method at one of the studied
/// tolerances, on the same preset) whose error is within the tolerance `auto` was asked for,
/// and the ratio of their times; `None` when no single configuration met it.
#[must_use]
pub fn against_best(rows: &[Row]) -> Vec<(&Row, Option<(&Row, f64)>)> {
    rows.iter()
        .filter(|a| a.method == "auto")
        .map(|a| {
            let best = rows
                .iter()
                .filter(|s| s.method != "auto" && s.preset == a.preset && s.error <= a.tolerance)
                .min_by(|x, y| x.seconds.total_cmp(&y.seconds));
            (a, best.map(|b| (b, a.seconds / b.seconds)))
        })
        .collect()
}

/// The rows as a table, then `auto` against the best single configuration at equal error.
#[must_use]
pub fn table(rows: &[Row]) -> String {
    use std::fmt::Write as _;
    let mut o = String::from(
        "preset              method            tol     ran at   estimate  met    error     ref ±     counts  seconds    rhs evals\n",
    );
    for r in rows {
        let estimate = r
            .estimate
            .map_or_else(|| "-".to_owned(), |e| format!("{e:.1e}"));
        let met = r.met.map_or("-", |m| if m { "yes" } else { "no" });
        let _ = writeln!(
            o,
            "{:<19} {:<17} {:<7.0e} {:<8.1e} {:<9} {:<6} {:<9.1e} {:<9.1e} {:<7} {:<10.3e} {}",
            r.preset,
            r.method,
            r.tolerance,
            r.ran_at,
            estimate,
            met,
            r.error,
            r.reference_uncertainty,
            if r.counts_exact { "exact" } else { "OFF" },
            r.seconds,
            r.rhs_evaluations
        );
    }
    o.push_str(
        "(errors below `ref ±`, the reference's own spread, are not resolved by it)\n\nauto against the cheapest single configuration that meets the same tolerance:\n",
    );
    for (a, best) in against_best(rows) {
        let _ = match best {
            Some((b, ratio)) => writeln!(
                o,
                "{:<19} tol {:.0e}: auto {:.3e} s (error {:.1e}) vs {} at {:.0e} {:.3e} s (error {:.1e}): {ratio:.2}x",
                a.preset,
                a.tolerance,
                a.seconds,
                a.error,
                b.method,
                b.tolerance,
                b.seconds,
                b.error
            ),
            None => writeln!(
                o,
                "{:<19} tol {:.0e}: auto {:.3e} s (error {:.1e}): no single configuration met it",
                a.preset, a.tolerance, a.seconds, a.error
            ),
        };
    }
    o
}

/// Writes the rows as CSV.
///
/// # Errors
/// When the file cannot be written.
pub fn write_csv(rows: &[Row], path: &std::path::Path) -> std::io::Result<()> {
    super::write_csv_lines(
        path,
        "preset,method,tolerance,ran_at,estimate,met,error,reference_uncertainty,counts_exact,seconds,rhs_evaluations",
        rows,
        |r| {
            let estimate = r.estimate.map(|e| format!("{e:e}")).unwrap_or_default();
            let met = r.met.map(|m| m.to_string()).unwrap_or_default();
            format!(
                "{},{},{:e},{:e},{estimate},{met},{:e},{:e},{},{:e},{}",
                r.preset,
                r.method,
                r.tolerance,
                r.ran_at,
                r.error,
                r.reference_uncertainty,
                r.counts_exact,
                r.seconds,
                r.rhs_evaluations
            )
        },
    )
}
