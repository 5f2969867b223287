//! The rattleback's full model by its Taylor series (`taylor`) against DOP853, on the
//! long-double references of `tests/fixtures/reference/averaged.toml` and
//! `rattleback_honesty.toml` (docs/benchmarks.md, "The middle by a Taylor series"):
//!
//! - `cargo run --release --example rattleback_taylor cost [START] [K]`: error (α(T), α̇(T) and
//!   the reversal times), steps and best wall time of seven of both methods at local tolerances
//!   1e-9 … 1e-14, on the averaging note's trapped (`A`, default) or rotating (`B`) start at
//!   T = 30 and k = 1e2 … 1e5 (or only `K`);
//! - `… companion`: how well a looser companion reads a run's error, what `auto`'s verification
//!   rests on. For every reference up to k = 1e6, each method at 1e-9 … 1e-14 and a companion
//!   4 … 64 times looser: the smallest, 5th-percentile and median ratio of `auto`'s estimate
//!   (their difference plus the round-off floors, the reference's condition number standing for
//!   the measured one) to the run's true error, where that error stands above the reference's
//!   own. `METHOD=dop853` for DOP853;
//! - `… probe`: both at the probes' full-model tolerance (1e-12) on every reference up to
//!   k = 1e6;
//! - `… tighter`: the series' run 16 … 1024 times tighter than its companion (what `auto` now
//!   verifies it with), how often their difference reads below the run's true error;
//! - `… growth`: the global error over the local tolerance per fast period (`METHOD=dop853`
//!   for DOP853);
//! - `… auto`: `auto` at 1e-5 … 1e-10 on every reference up to k = 1e6, wherever it resolves
//!   with the series: its estimate against the true error;
//! - `… stall`: the series and its companion on an ill-conditioned reference at local
//!   tolerances a factor 2 apart, and `auto` there at 1e-5 … 1e-8 (`policy::TAYLOR.stalls`);
//! - `… monotone`: `auto` at every decade from 1e-4 to 1e-10 on every reference of T ≤ 100
//!   (any method): estimates below the error, and tolerances met where a looser one is missed.

use std::time::Instant;

use rattleback::physics::method::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::auto::{conditioned_round_off, difference, round_off};
use rattleback::physics::rattleback::run::{RunResult, run};
use rattleback::physics::rattleback::{Params, Problem, Start};

struct Case {
    name: String,
    start: String,
    problem: Problem,
    t_end: f64,
    /// The reference's own error (its `uncertainty`, else the files' 2e-12).
    floor: f64,
    /// Its condition number (held-out starts), else 1.
    kappa: f64,
    alpha: f64,
    alpha_dot: f64,
    reversals: Vec<f64>,
}

impl Case {
    fn error(&self, r: &RunResult) -> f64 {
        if r.reversal_count != self.reversals.len() {
            return f64::INFINITY;
        }
        let mut e = (r.final_state[1] - self.alpha)
            .abs()
            .max((r.final_state[3] - self.alpha_dot).abs());
        for (a, b) in r.reversals.iter().zip(&self.reversals) {
            e = e.max((a - b).abs());
        }
        e
    }

    fn run(&self, method: Method, tolerance: f64) -> RunResult {
        let spec = RunSpec {
            method,
            tolerance,
            step: None,
            t_end: self.t_end,
            samples: 0,
            monitor_energy: false,
        };
        run(&self.problem, &spec).expect("a run")
    }
}

/// The long-double full-model references up to k = 1e6.
fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    for file in ["averaged.toml", "rattleback_honesty.toml"] {
        let text = std::fs::read_to_string(format!("tests/fixtures/reference/{file}"))
            .expect("the references (run from the repository)");
        let table: toml::Table = text.parse().expect("TOML");
        for (name, c) in table["case"].as_table().expect("cases") {
            let c = c.as_table().expect("a case");
            let f = |k: &str| c[k].as_float().expect("a number");
            let optional = |k: &str| c.get(k).and_then(toml::Value::as_float);
            if c["source"].as_str() != Some("rk8-long-double") || f("k") > 1e6 {
                continue;
            }
            out.push(Case {
                name: name.clone(),
                start: c["start"].as_str().unwrap_or_default().to_owned(),
                problem: Problem::new(
                    Params {
                        ix: f("ix"),
                        iy: f("iy"),
                        iz: f("iz"),
                        k: f("k"),
                    },
                    Start {
                        gamma: f("gamma0"),
                        alpha: f("alpha0"),
                        gamma_dot: f("gamma_dot0"),
                        alpha_dot: f("alpha_dot0"),
                    },
                )
                .expect("a valid reference"),
                t_end: f("t_end"),
                floor: optional("uncertainty").unwrap_or(2e-12).max(2e-12),
                kappa: optional("condition").unwrap_or(1.0),
                alpha: f("alpha_end"),
                alpha_dot: f("alpha_dot_end"),
                reversals: c["reversals"]
                    .as_array()
                    .expect("reversals")
                    .iter()
                    .map(|v| v.as_float().expect("a time"))
                    .collect(),
            });
        }
    }
    out
}

/// Local tolerances 1e-9 … 1e-14 in half decades.
fn tolerances() -> impl Iterator<Item = f64> {
    (0..11).map(|i| 1e-9 * 10f64.powf(-0.5 * f64::from(i)))
}

fn best_of_seven<T>(mut f: impl FnMut() -> T) -> (T, f64) {
    let mut best = f64::INFINITY;
    let mut out = f();
    for _ in 0..7 {
        let start = Instant::now();
        out = f();
        best = best.min(start.elapsed().as_secs_f64());
    }
    (out, best)
}

fn cost(start: &str, only_k: Option<f64>) {
    for case in cases() {
        let k = case.problem.params().k;
        if case.start != start
            || (case.t_end - 30.0).abs() > 0.0
            || k > 1e5
            || only_k.is_some_and(|only| (only - k).abs() > 0.0)
        {
            continue;
        }
        println!("start {start}, k = {k:e}");
        println!("  tol      | taylor: error  steps   µs     | dop853: error  steps   µs");
        for tol in tolerances() {
            let go = |method| {
                let (r, s) = best_of_seven(|| case.run(method, tol));
                (case.error(&r), r.stats.steps, s * 1e6)
            };
            let (te, ts, tt) = go(Method::Taylor);
            let (de, ds, dt) = go(Method::Dop853);
            println!("  {tol:.1e}  | {te:.1e} {ts:>7} {tt:>8.1} | {de:.1e} {ds:>7} {dt:>8.1}");
        }
    }
}

fn companion(method: Method) {
    let factors = [4.0, 8.0, 16.0, 32.0, 64.0];
    let mut ratios: Vec<Vec<(f64, String)>> = vec![Vec::new(); factors.len()];
    for case in cases() {
        for tol in tolerances() {
            let r = case.run(method, tol);
            let e = case.error(&r);
            if e.is_nan() || e < 10.0 * case.floor {
                continue;
            }
            let steps = r.stats.steps as f64;
            let floors = round_off(&case.problem, steps, case.t_end)
                + conditioned_round_off(steps, case.kappa);
            for (j, &f) in factors.iter().enumerate() {
                let c = case.run(method, tol * f);
                let estimate = difference(&r, &c) + floors;
                ratios[j].push((estimate / e, format!("{} at {tol:.1e}", case.name)));
            }
        }
    }
    println!("{method}: auto's estimate over the true error");
    for (r, f) in ratios.iter_mut().zip(factors) {
        r.sort_by(|a, b| a.0.total_cmp(&b.0));
        let below = |x: f64| r.iter().filter(|v| v.0 < x).count();
        println!(
            "  companion {f:>2}x looser: {} runs; smallest {:.2} ({}), 5th percentile {:.2}, median {:.1}; below 1: {}, below 2: {}",
            r.len(),
            r[0].0,
            r[0].1,
            r[r.len() / 20].0,
            r[r.len() / 2].0,
            below(1.0),
            below(2.0)
        );
    }
}

/// A run `ratio` times *tighter* than its companion, the companion at 1e-8 … 1e-12: how often
/// their difference (plus the floors) reads below the tight run's true error.
fn tighter() {
    let ratios_asked = [16.0, 64.0, 256.0, 1024.0];
    for &ratio in &ratios_asked {
        let mut found: Vec<(f64, String)> = Vec::new();
        let (mut hidden, mut hidden_ok) = (0, 0);
        for case in cases() {
            for i in 0..9 {
                let loose = 1e-8 * 10f64.powf(-0.5 * f64::from(i));
                let tight = (loose / ratio).max(1e-14);
                let r = case.run(Method::Taylor, tight);
                let c = case.run(Method::Taylor, loose);
                let e = case.error(&r);
                let steps = r.stats.steps as f64;
                let floors = round_off(&case.problem, steps, case.t_end)
                    + conditioned_round_off(steps, case.kappa);
                let estimate = difference(&r, &c) + floors;
                if e.is_nan() || e < 10.0 * case.floor {
                    hidden += 1;
                    if estimate >= 10.0 * case.floor {
                        hidden_ok += 1;
                    }
                    continue;
                }
                found.push((estimate / e, format!("{} at {loose:.1e}", case.name)));
            }
        }
        found.sort_by(|a, b| a.0.total_cmp(&b.0));
        let below = |x: f64| found.iter().filter(|v| v.0 < x).count();
        println!(
            "  run {ratio:>4}x tighter: {} measured; smallest {:.2} ({}), 5th percentile {:.2}, median {:.1}; below 1: {}, below 2: {}; under the references' floor: {hidden} ({hidden_ok} estimated above 10x that floor)",
            found.len(),
            found[0].0,
            found[0].1,
            found[found.len() / 20].0,
            found[found.len() / 2].0,
            below(1.0),
            below(2.0)
        );
    }
}

/// Global error of a run over its local tolerance and the fast periods of its horizon
/// (at least 20), at 1e-8 … 1e-12, where the error stands above the reference's own.
fn growth(method: Method) {
    let mut worst: Vec<(f64, String)> = Vec::new();
    for case in cases() {
        let nu = rattleback::physics::rattleback::budget::fastest_rate(&case.problem);
        let periods = (nu * case.t_end / std::f64::consts::TAU).max(20.0);
        for i in 0..9 {
            let tol = 1e-8 * 10f64.powf(-0.5 * f64::from(i));
            let e = case.error(&case.run(method, tol));
            if e.is_nan() || e < 10.0 * case.floor {
                continue;
            }
            worst.push((
                e / (tol * periods),
                format!("{} at {tol:.1e}, {periods:.0} periods", case.name),
            ));
        }
    }
    worst.sort_by(|a, b| b.0.total_cmp(&a.0));
    println!("{method}: error / (local tolerance x periods), largest first");
    for (g, name) in worst.iter().filter(|w| !w.1.starts_with("sep_")).take(12) {
        println!("  {g:.3}  {name}");
    }
    println!(
        "  median {:.3} of {}",
        worst[worst.len() / 2].0,
        worst.len()
    );
}

/// `auto` itself at 1e-5 … 1e-10 on every reference up to k = 1e6: where it resolves with the
/// series, its estimate against the true error.
fn auto_taylor() {
    use rattleback::physics::rattleback::auto::run_auto;
    let (mut plans, mut unmeasurable, mut below) = (0, 0, 0);
    let mut worst = (f64::INFINITY, String::new());
    for case in cases() {
        for tol in [
            1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10,
        ] {
            let Ok(v) = run_auto(&case.problem, tol, case.t_end, 0, false) else {
                continue;
            };
            if v.plan.method != Method::Taylor {
                continue;
            }
            plans += 1;
            let e = case.error(&v.result);
            if v.error_estimate < e {
                below += 1;
                println!(
                    "  below: {} at {tol:e}: estimate {:e}, error {e:e}",
                    case.name, v.error_estimate
                );
            }
            if e < 10.0 * case.floor {
                unmeasurable += 1;
                continue;
            }
            let ratio = v.error_estimate / e;
            if ratio < worst.0 {
                worst = (
                    ratio,
                    format!(
                        "{} at {tol:e}: estimate {:.2e}, error {e:.2e}",
                        case.name, v.error_estimate
                    ),
                );
            }
        }
    }
    println!(
        "auto resolved with taylor {plans} times ({unmeasurable} with an error under ten times the reference's own); \
         estimates below the error: {below}; smallest estimate / error where measurable: {:.1} ({})",
        worst.0, worst.1
    );
}

fn probe() {
    let (mut worst_taylor, mut worst_dop) = (0.0f64, 0.0f64);
    let mut worst_ratio = (0.0f64, String::new());
    for case in cases() {
        let t = case.error(&case.run(Method::Taylor, 1e-12));
        let d = case.error(&case.run(Method::Dop853, 1e-12));
        println!(
            "{:<22} k {:>4.0e} T {:>4}: taylor {t:.1e}, dop853 {d:.1e} (reference {:.0e})",
            case.name,
            case.problem.params().k,
            case.t_end,
            case.floor
        );
        worst_taylor = worst_taylor.max(t);
        worst_dop = worst_dop.max(d);
        let ratio = t / d.max(case.floor);
        if ratio > worst_ratio.0 {
            worst_ratio = (ratio, case.name.clone());
        }
    }
    println!(
        "largest error: taylor {worst_taylor:.1e}, dop853 {worst_dop:.1e}; \
         largest taylor / max(dop853, reference's own) {:.2} ({})",
        worst_ratio.0, worst_ratio.1
    );
}

/// The series' run and its companion (1024× looser) at local tolerances 1e-9 … 1e-14 in steps
/// of 2, on the reference `M_k1e03_T100` (κ ≈ 2 300): each one's error against the reference,
/// and their difference, `auto`'s estimate before its floors. The companion's error does not
/// fall steadily (`policy::TAYLOR.stalls`), then `auto` at 1e-5 … 1e-8.
fn stall() {
    let case = cases()
        .into_iter()
        .find(|c| c.name == "M_k1e03_T100")
        .expect("the reference M_k1e03_T100");
    let mut l = 1e-9;
    while l > 1e-14 {
        let (run, companion) = (
            case.run(Method::Taylor, l),
            case.run(Method::Taylor, 1024.0 * l),
        );
        println!(
            "local {l:.1e}: run's error {:.1e}, companion's {:.1e}, difference {:.1e}",
            case.error(&run),
            case.error(&companion),
            difference(&run, &companion)
        );
        l /= 2.0;
    }
    for tolerance in [1e-5, 1e-6, 1e-7, 1e-8] {
        let v = rattleback::physics::rattleback::auto::run_auto(
            &case.problem,
            tolerance,
            case.t_end,
            0,
            false,
        )
        .expect("auto");
        println!(
            "auto at {tolerance:.0e}: {} at {:.1e}, {} refinements, estimate {:.1e} (floor {:.1e}), \
             error {:.1e}, met {}",
            v.plan.method,
            v.plan.tolerance,
            v.refinements,
            v.error_estimate,
            v.round_off_floor,
            case.error(&v.result),
            v.met
        );
    }
}

/// `auto` at every decade from 1e-4 to 1e-10 on every reference of T ≤ 100: whether its estimate
/// bounds its error, and whether it meets every tolerance looser than one it meets (stop 52:
/// `auto_honest::a_looser_tolerance_is_never_missed_where_a_tighter_one_is_met` keeps the cases
/// that failed).
fn monotone() {
    use rattleback::physics::rattleback::auto::run_auto;
    let tolerances = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
    let (mut starts, mut runs, mut low, mut inverted) = (0, 0, 0, 0);
    for case in cases().iter().filter(|c| c.t_end <= 100.0) {
        // The marks, and whether a looser tolerance was missed so far.
        let (mut marks, mut missed) = (String::new(), false);
        for &tol in &tolerances {
            let v = run_auto(&case.problem, tol, case.t_end, 0, false).expect("auto");
            let e = case.error(&v.result);
            if v.error_estimate < e - case.floor {
                low += 1;
                println!(
                    "  below: {} at {tol:e}: estimate {:.1e}, error {e:.1e}",
                    case.name, v.error_estimate
                );
            }
            if v.met && missed {
                inverted += 1;
                println!(
                    "  {}: met at {tol:e}, missed at a looser tolerance",
                    case.name
                );
            }
            missed |= !v.met;
            marks.push(if v.met { '+' } else { '-' });
            runs += 1;
        }
        println!("{:>22} {marks}", case.name);
        starts += 1;
    }
    println!(
        "{starts} references, {runs} runs: {low} estimates below the error, \
         {inverted} tolerances met where a looser one was missed"
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("companion") => {
            let method = if std::env::var("METHOD").is_ok_and(|m| m == "dop853") {
                Method::Dop853
            } else {
                Method::Taylor
            };
            companion(method);
        }
        Some("probe") => probe(),
        Some("tighter") => tighter(),
        Some("auto") => auto_taylor(),
        Some("stall") => stall(),
        Some("monotone") => monotone(),
        Some("growth") => growth(if std::env::var("METHOD").is_ok_and(|m| m == "dop853") {
            Method::Dop853
        } else {
            Method::Taylor
        }),
        Some("cost") | None => cost(
            args.get(1).map_or("A", String::as_str),
            args.get(2).map(|k| k.parse().expect("a stiffness")),
        ),
        Some(other) => {
            panic!(
                "unknown mode {other}: cost, companion, probe, tighter, growth, auto, stall or monotone"
            )
        }
    }
}
