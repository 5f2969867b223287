//! `rattleback bench`: a work–precision study of every method over k = 1e2 … 1e12, and a
//! stability report. Wall time is the best of N runs after a warm-up, one thread; errors are
//! against a reference whose source the output names (tight DOP853 for k ≤ 1e6, fine
//! blanes-moan4 at 1e8, the second-order averaged model beyond), itself cross-checked.
use crate::physics::numerics::elementary::Elementary;

pub mod auto_profile;
pub mod celt;
pub mod implicit;
pub mod kapitza;
pub mod plot;
pub mod segments;
mod stability;

use crate::physics::rattleback::model::{ALPHA, ALPHA_DOT};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use serde::Serialize;

use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::rattleback::auto::run_auto;
use crate::physics::rattleback::run::RunResult;
use crate::physics::rattleback::{Params, Problem, Start, run};

/// The best of `repeats` timed calls of `f`, after one untimed call that warms the caches.
pub(crate) fn best_of(repeats: usize, mut f: impl FnMut()) -> f64 {
    f();
    (0..repeats.max(1))
        .map(|_| {
            let clock = Instant::now();
            f();
            clock.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// How much to measure.
#[derive(Clone, Copy, Debug)]
pub struct Config {
    /// The short version (CI smoke check, under a minute).
    pub quick: bool,
}

impl Config {
    fn t_end(self) -> f64 {
        if self.quick { 5.0 } else { 20.0 }
    }
    fn repeats(self) -> usize {
        if self.quick { 1 } else { 3 }
    }
    /// Most fast flows or evaluations one run may cost; larger ones are skipped and said so.
    fn budget(self) -> f64 {
        if self.quick { 3e6 } else { 3e7 }
    }
}

/// Stiffnesses studied.
pub const KS: [f64; 6] = [1e2, 1e4, 1e6, 1e8, 1e10, 1e12];

/// One measured run: a row of `work_precision.csv`.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Method name.
    pub method: String,
    /// Hooke constant.
    pub k: f64,
    /// Tolerance asked (adaptive methods and auto), else empty.
    pub tolerance: Option<f64>,
    /// `ω_max h` (fixed-step methods), else empty.
    pub omega_h: Option<f64>,
    /// Error of `alpha(T)`.
    pub error_alpha: f64,
    /// Error of `alpha_dot(T)`.
    pub error_alpha_dot: f64,
    /// Largest error of the reversal times (infinite when the counts differ).
    pub error_reversals: f64,
    /// Best wall time, seconds.
    pub seconds: f64,
    /// Right-hand-side evaluations or exact fast flows.
    pub rhs_evaluations: u64,
    /// Where the reference came from.
    pub reference: String,
}

/// A start of the public cases' family: `iz = 1`, `gamma = alpha = 0`, `gamma_dot = 1`.
///
/// # Panics
/// For non-positive inertias or `k` (the callers pass positive constants).
#[must_use]
pub fn case(ix: f64, iy: f64, k: f64, alpha_dot: f64) -> Problem {
    Problem::new(
        Params { ix, iy, iz: 1.0, k },
        Start {
            gamma: 0.0,
            alpha: 0.0,
            gamma_dot: 1.0,
            alpha_dot,
        },
    )
    .expect("valid")
}

/// The problem every row integrates: the trapped start of the public cases.
#[must_use]
pub fn problem(k: f64) -> Problem {
    case(2.0, 1.0, k, 0.5)
}

/// A run of the integrator alone: no samples, no energy monitoring.
#[must_use]
pub fn spec(method: Method, tolerance: f64, step: Option<f64>, t_end: f64) -> RunSpec {
    RunSpec {
        method,
        tolerance,
        step,
        t_end,
        samples: 0,
        monitor_energy: false,
    }
}

/// `(method, tolerance, ω h)` of every configuration.
fn configurations(quick: bool) -> Vec<(Method, f64, Option<f64>)> {
    let mut c = Vec::new();
    for tol in if quick {
        vec![1e-6, 1e-9]
    } else {
        vec![1e-6, 1e-8, 1e-10, 1e-12]
    } {
        c.push((Method::Dop853, tol, None));
        c.push((Method::Taylor, tol, None));
    }
    for (m, whs) in [
        (Method::Rk4, vec![0.1, 0.05]),
        (Method::Strang, vec![0.8, 0.2]),
        (Method::Yoshida4, vec![0.8, 0.4]),
        (Method::BlanesMoan4, vec![2.4, 1.2]),
        (Method::Yoshida6, vec![1.6, 0.8]),
        (Method::Suzuki8, vec![1.6, 0.8]),
    ] {
        let whs = if quick { vec![whs[0]] } else { whs };
        for wh in whs {
            c.push((m, 0.0, Some(wh)));
        }
    }
    for h in if quick {
        vec![1e-3]
    } else {
        vec![1e-3, 3e-4, 1e-4]
    } {
        c.push((Method::Locked, 0.0, Some(-h))); // negative: an absolute step, not ω h
    }
    c.push((Method::Effective, 1e-10, None));
    c.push((Method::EffectiveCorrected, 1e-10, None));
    for tol in if quick {
        vec![1e-10]
    } else {
        vec![1e-8, 1e-10, 1e-12, 1e-14]
    } {
        c.push((Method::Averaged2, tol, None));
        c.push((Method::Averaged3, tol, None));
    }
    for tol in if quick { vec![1e-6] } else { vec![1e-6, 1e-8] } {
        c.push((Method::Auto, tol, None));
    }
    c
}

/// Predicted work of a configuration, to skip the unaffordable.
fn predicted_work(method: Method, tol: f64, step: Option<f64>, omega: f64, t_end: f64) -> f64 {
    let periods = omega * t_end / std::f64::consts::TAU;
    match (method, step) {
        (Method::Dop853, _) => 155.0 * (1e-10 / tol).e_powf(0.125) * periods,
        // Twenty orders a step, about six steps a period at 1e-12.
        (Method::Taylor, _) => {
            20.0 * crate::physics::rattleback::budget::taylor_steps(tol, periods)
        }
        (Method::Locked, Some(h)) => t_end / h,
        (m, Some(h)) if m.is_fixed_step() => {
            let stages = match m {
                Method::Rk4 => 4.0,
                Method::Yoshida4 => 3.0,
                Method::BlanesMoan4 => 6.0,
                Method::Yoshida6 => 7.0,
                Method::Suzuki8 => 15.0,
                _ => 1.0,
            };
            stages * t_end / h
        }
        _ => 0.0,
    }
}

/// The reference of one stiffness: its result and a sentence saying what it is.
fn reference(k: f64, t_end: f64) -> (RunResult, String) {
    let p = problem(k);
    let omega = p.params().omega_max();
    let (main, check, what) = if k <= 1e4 {
        (
            spec(Method::Dop853, 1e-13, None, t_end),
            spec(Method::Suzuki8, 0.0, Some(0.1 / omega), t_end),
            "dop853 tol 1e-13; cross-check suzuki8 ωh=0.1",
        )
    } else if k <= 1e6 {
        (
            spec(Method::Dop853, 1e-13, None, t_end),
            spec(Method::BlanesMoan4, 0.0, Some(0.6 / omega), t_end),
            "dop853 tol 1e-13; cross-check blanes-moan4 ωh=0.6",
        )
    } else if k <= 1e8 {
        (
            spec(Method::BlanesMoan4, 0.0, Some(0.8 / omega), t_end),
            spec(Method::Locked, 0.0, Some(1e-4), t_end),
            "blanes-moan4 ωh=0.8; cross-check locked h=1e-4",
        )
    } else {
        (
            spec(Method::Averaged2, 1e-14, None, t_end),
            spec(Method::Locked, 0.0, Some(1e-4), t_end),
            "averaged2 tol 1e-14 (model error below 1e-18 here); cross-check locked h=1e-4",
        )
    };
    let r = run(&p, &main).expect("reference integrates");
    let c = run(&p, &check).expect("cross-check integrates");
    let d = (r.final_state[ALPHA] - c.final_state[ALPHA])
        .abs()
        .max((r.final_state[ALPHA_DOT] - c.final_state[ALPHA_DOT]).abs());
    (r, format!("{what}: differ by {d:.1e}"))
}

fn reversal_error(a: &RunResult, b: &RunResult) -> f64 {
    if a.reversal_count != b.reversal_count {
        return f64::INFINITY;
    }
    a.reversals
        .iter()
        .zip(&b.reversals)
        .fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// Runs the study; prints progress lines through `log`.
#[must_use]
pub fn work_precision(config: Config, log: &mut dyn FnMut(&str)) -> Vec<Row> {
    let t_end = config.t_end();
    let mut rows = Vec::new();
    for k in KS {
        let (reference, source) = reference(k, t_end);
        log(&format!("k = {k:e}: reference {source}"));
        let p = problem(k);
        let omega = p.params().omega_max();
        for (method, tol, wh) in configurations(config.quick) {
            let step = wh.map(|w| if w < 0.0 { -w } else { w / omega });
            let work = predicted_work(method, tol, step, omega, t_end);
            if work > config.budget() {
                log(&format!(
                    "  {:<20} skipped: about {work:.1e} evaluations",
                    label(method, tol, wh)
                ));
                continue;
            }
            let once = || -> Option<RunResult> {
                if method == Method::Auto {
                    run_auto(&p, tol, t_end, 0, false).ok().map(|v| v.result)
                } else {
                    run(&p, &spec(method, tol, step, t_end)).ok()
                }
            };
            let Some(result) = once() else {
                log(&format!("  {:<20} failed", label(method, tol, wh)));
                continue;
            };
            let mut best = f64::INFINITY;
            for _ in 0..config.repeats() {
                let clock = Instant::now();
                let _ = std::hint::black_box(once());
                best = best.min(clock.elapsed().as_secs_f64());
            }
            rows.push(Row {
                method: method.name().to_owned(),
                k,
                tolerance: (tol > 0.0).then_some(tol),
                omega_h: step.filter(|_| method.is_fixed_step()).map(|h| h * omega),
                error_alpha: (result.final_state[ALPHA] - reference.final_state[ALPHA]).abs(),
                error_alpha_dot: (result.final_state[ALPHA_DOT] - reference.final_state[ALPHA_DOT])
                    .abs(),
                error_reversals: reversal_error(&result, &reference),
                seconds: best,
                rhs_evaluations: result.stats.rhs_evaluations,
                reference: source.clone(),
            });
        }
        #[cfg(feature = "peer")]
        peer_rows(config, k, &reference, &source, &mut rows, log);
    }
    rows
}

/// The peer's rows for one stiffness (feature `peer`).
#[cfg(feature = "peer")]
fn peer_rows(
    config: Config,
    k: f64,
    reference: &RunResult,
    source: &str,
    rows: &mut Vec<Row>,
    log: &mut dyn FnMut(&str),
) {
    use peer::Peer;
    let p = problem(k);
    let t_end = config.t_end();
    let omega = p.params().omega_max();
    let tols = if config.quick {
        vec![1e-6, 1e-9]
    } else {
        vec![1e-6, 1e-8, 1e-10, 1e-12]
    };
    for which in [Peer::Dop853, Peer::Vern9] {
        for &tol in &tols {
            let work = predicted_work(Method::Dop853, tol, None, omega, t_end) * 1.3;
            if work > config.budget() {
                log(&format!(
                    "  {:<20} skipped: about {work:.1e} evaluations",
                    format!("{} tol={tol:.0e}", which.name())
                ));
                continue;
            }
            let (y, evals) = match peer::run(&p, which, tol, t_end) {
                Ok(r) => r,
                Err(e) => {
                    log(&format!("  {} tol={tol:.0e} failed: {e}", which.name()));
                    continue;
                }
            };
            let mut best = f64::INFINITY;
            for _ in 0..config.repeats() {
                let clock = Instant::now();
                let _ = std::hint::black_box(peer::run(&p, which, tol, t_end));
                best = best.min(clock.elapsed().as_secs_f64());
            }
            rows.push(Row {
                method: which.name().to_owned(),
                k,
                tolerance: Some(tol),
                omega_h: None,
                error_alpha: (y[ALPHA] - reference.final_state[ALPHA]).abs(),
                error_alpha_dot: (y[ALPHA_DOT] - reference.final_state[ALPHA_DOT]).abs(),
                error_reversals: f64::NAN,
                seconds: best,
                rhs_evaluations: evals,
                reference: source.to_owned(),
            });
        }
    }
}

/// For each stiffness, the fastest of ours and of the peer's whose `alpha(T)` and
/// `alpha_dot(T)` errors are both within `level`, and ours divided by the peer's.
#[must_use]
pub fn peer_summary(rows: &[Row], level: f64) -> String {
    fn fastest(it: Vec<&Row>) -> Option<&Row> {
        it.into_iter()
            .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
    }
    let mut o = format!("fastest within {level:e} (alpha and alpha_dot): ours vs the peer's\n");
    let within = |r: &&Row| r.error_alpha <= level && r.error_alpha_dot <= level;
    for k in KS {
        #[allow(clippy::float_cmp)]
        let at: Vec<&Row> = rows.iter().filter(|r| r.k == k).filter(within).collect();
        let ours = fastest(
            at.iter()
                .copied()
                .filter(|r| !r.method.starts_with("peer-"))
                .collect(),
        );
        let theirs = fastest(
            at.iter()
                .copied()
                .filter(|r| r.method.starts_with("peer-"))
                .collect(),
        );
        let _ = match (ours, theirs) {
            (Some(a), Some(b)) => writeln!(
                o,
                "  k = {k:e}: ours {} {:.3e} s, peer {} {:.3e} s, ours/peer = {:.3}",
                a.method,
                a.seconds,
                b.method,
                b.seconds,
                a.seconds / b.seconds
            ),
            (Some(a), None) => writeln!(
                o,
                "  k = {k:e}: ours {} {:.3e} s, no peer run within {level:e}",
                a.method, a.seconds
            ),
            _ => writeln!(o, "  k = {k:e}: nothing within {level:e}"),
        };
    }
    o
}

fn label(method: Method, tol: f64, wh: Option<f64>) -> String {
    match wh {
        Some(w) if w < 0.0 => format!("{method} h={:.0e}", -w),
        Some(w) => format!("{method} ωh={w}"),
        None => format!("{method} tol={tol:.0e}"),
    }
}

/// The table for people.
#[must_use]
pub fn table(rows: &[Row]) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{:>7}  {:<20} {:>10} {:>10} {:>10} {:>11} {:>12}",
        "k", "method", "err α", "err α̇", "err rev", "seconds", "evaluations"
    );
    for r in rows {
        let setting = r
            .omega_h
            .map(|w| format!("{} ωh={w:.2}", r.method))
            .or_else(|| r.tolerance.map(|t| format!("{} tol={t:.0e}", r.method)))
            .unwrap_or_else(|| r.method.clone());
        let _ = writeln!(
            o,
            "{:>7.0e}  {:<20} {:>10.2e} {:>10.2e} {:>10.2e} {:>11.3e} {:>12}",
            r.k,
            setting,
            r.error_alpha,
            r.error_alpha_dot,
            r.error_reversals,
            r.seconds,
            r.rhs_evaluations
        );
    }
    o
}

/// Writes `header` and one line per row (`line`) to the CSV file `path`, atomically: what every
/// part's `write_csv` shares.
///
/// # Errors
/// When the file cannot be written.
pub(crate) fn write_csv_lines<R>(
    path: &Path,
    header: &str,
    rows: &[R],
    line: impl Fn(&R) -> String,
) -> std::io::Result<()> {
    let mut text = format!("{header}\n");
    for r in rows {
        text.push_str(&line(r));
        text.push('\n');
    }
    crate::scenario::write::write_atomic(path, text.as_bytes(), true)
}

/// Writes `work_precision.csv`.
///
/// # Errors
/// When the file cannot be written.
pub fn write_csv(rows: &[Row], path: &Path) -> std::io::Result<()> {
    let opt = |v: Option<f64>| v.map_or_else(String::new, |x| format!("{x:e}"));
    write_csv_lines(
        path,
        "method,k,tolerance,omega_h,error_alpha,error_alpha_dot,error_reversals,seconds,rhs_evaluations,reference",
        rows,
        |r| {
            format!(
                "{},{:e},{},{},{:e},{:e},{:e},{:e},{},\"{}\"",
                r.method,
                r.k,
                opt(r.tolerance),
                opt(r.omega_h),
                r.error_alpha,
                r.error_alpha_dot,
                r.error_reversals,
                r.seconds,
                r.rhs_evaluations,
                r.reference
            )
        },
    )
}

pub use auto_profile::{ProfileRow, profile, profile_table, write_profile_csv};
pub use plot::{terminal_diagram, write_svg};
pub use stability::{StabilityRow, stability, stability_table, write_stability_csv};
#[cfg(feature = "peer")]
pub mod peer;
