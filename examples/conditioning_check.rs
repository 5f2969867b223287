//! How well `auto`'s first conditioning measurement (the slow model `averaged2` at local
//! tolerance 1e-7) reads the start's condition number where the expansion parameter is between
//! 0.1 and 0.3, against the full model by the Taylor series at 1e-11 and the references' own
//! (`rattleback_honesty.toml`); `auto` re-measures on the plan's own method wherever the first
//! reading passes 100 (`auto::CONDITIONING_RECHECK`):
//! `cargo run --release --example conditioning_check`. Since stop 48 `auto` reads it with the
//! nudged starts side by side on the start's steps (`auto::slow_condition_numbers`), printed
//! beside the three separate runs at 1e-7 and 1e-9; `… conditioning_check all` takes every
//! start with expansion parameter up to 0.25 (the slow model's range), not only 0.1 … 0.3.
//! Each line ends with what the reading costs (best of 7): side by side, and as the three
//! separate runs at 1e-7 it replaced (the start, its spin rate and its angle nudged).
//!
//! `… conditioning_check spread` (issue 27, stop 51) asks whether a start's condition numbers could
//! be read once and kept for every larger `k`, as the probes are: for each family of reference
//! starts (the start at every `k`, `auto::probe_problem`), from the smallest power of ten where
//! its expansion parameter is at most 0.01 up to 1e12 in steps of √10, the largest reading over
//! the reading at that smallest `k`. They are not: the reversal times cross where the fast ripple
//! of `α̇` is steep or shallow by turns, and `α̇(T)` takes the ripple's phase, so κ moves by up to
//! 16× (rate) and 21× (angle) from one `k` to another: `auto` measures it at the `k` it runs.
//! `… conditioning_check limit` reads each family once on the effective limit (three separate
//! runs) against `averaged2`'s readings at every `k`: up to 466× apart, and dearer.

use rattleback::physics::method::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::auto::{difference, slow_condition_numbers};
use rattleback::physics::rattleback::averaged::expansion_parameter;
use rattleback::physics::rattleback::run::run;
use rattleback::physics::rattleback::{Params, Problem, Start};
fn main() {
    if std::env::args().nth(1).as_deref() == Some("limit") {
        limit();
        return;
    }
    if std::env::args().nth(1).as_deref() == Some("spread") {
        spread();
        return;
    }
    let all = std::env::args().nth(1).as_deref() == Some("all");
    for (name, c) in cases() {
        let f = |k: &str| c[k].as_float().unwrap();
        if c["source"].as_str() != Some("rk8-long-double") {
            continue;
        }
        let p = problem_of(&c);
        let (params, start) = (*p.params(), *p.start());
        let x = expansion_parameter(&p);
        if (all && x > 0.25) || (!all && (x > 0.3 || x <= 0.1)) {
            continue;
        }
        let kref = c.get("condition").and_then(toml::Value::as_float);
        let t_end = f("t_end");
        let spec = |m, tol| RunSpec {
            method: m,
            tolerance: tol,
            step: None,
            t_end,
            samples: 0,
            monitor_energy: false,
        };
        let kappa = |m, tol| {
            let base = run(&p, &spec(m, tol)).unwrap();
            let mut s2 = start;
            s2.alpha_dot *= 1.0 + 1e-10;
            let n = run(&Problem::new(params, s2).unwrap(), &spec(m, tol)).unwrap();
            difference(&base, &n) / 1e-10
        };
        let side_by_side =
            slow_condition_numbers(&p, Method::Averaged2, 1e-7, t_end, &mut |_| true)
                .unwrap()
                .rate;
        let best_of_seven = |f: &dyn Fn()| {
            (0..7)
                .map(|_| {
                    let clock = std::time::Instant::now();
                    f();
                    clock.elapsed().as_secs_f64() * 1e3
                })
                .fold(f64::INFINITY, f64::min)
        };
        let together_ms = best_of_seven(&|| {
            let _ = slow_condition_numbers(&p, Method::Averaged2, 1e-7, t_end, &mut |_| true);
        });
        let separate_ms = best_of_seven(&|| {
            let (mut rate, mut angle) = (start, start);
            rate.alpha_dot *= 1.0 + 1e-10;
            angle.alpha += 1e-10;
            for s in [start, rate, angle] {
                let _ = run(
                    &Problem::new(params, s).unwrap(),
                    &spec(Method::Averaged2, 1e-7),
                );
            }
        });
        println!(
            "{name:24} x {x:.3} T {t_end}: averaged2 side by side 1e-7 {side_by_side:.3e}, separate 1e-7 {:.3e}, 1e-9 {:.3e}; taylor 1e-11 {:.3e}, reference {kref:?}; ms side by side {together_ms:.3}, three runs {separate_ms:.3}",
            kappa(Method::Averaged2, 1e-7),
            kappa(Method::Averaged2, 1e-9),
            kappa(Method::Taylor, 1e-11)
        );
    }
}

/// A reference case's problem.
fn problem_of(c: &toml::Table) -> Problem {
    let f = |k: &str| c[k].as_float().unwrap();
    let params = Params {
        ix: f("ix"),
        iy: f("iy"),
        iz: f("iz"),
        k: f("k"),
    };
    let start = Start {
        gamma: f("gamma0"),
        alpha: f("alpha0"),
        gamma_dot: f("gamma_dot0"),
        alpha_dot: f("alpha_dot0"),
    };
    Problem::new(params, start).unwrap()
}

/// `auto`'s first reading (`averaged2` side by side at its loose tolerance) of the start of
/// `p`'s family at every `k` from the smallest power of ten where its expansion parameter is at
/// most `x` to 1e12, in steps of √10: that smallest `k` and the readings `[rate, angle]`.
fn over_k(p: &Problem, t_end: f64, x: f64) -> Option<(f64, Vec<[f64; 2]>)> {
    use rattleback::physics::rattleback::auto::{CONDITIONING_LOOSE_TOLERANCE, probe_problem};
    let lowest = (2..=12)
        .map(|n| 10f64.powi(n))
        .find(|&k| expansion_parameter(&probe_problem(p, k)) <= x)?;
    let mut readings = Vec::new();
    let mut k = lowest;
    while k <= 1e12 {
        let c = slow_condition_numbers(
            &probe_problem(p, k),
            Method::Averaged2,
            CONDITIONING_LOOSE_TOLERANCE,
            t_end,
            &mut |_| true,
        )
        .unwrap();
        readings.push([c.rate, c.angle]);
        k *= 10f64.sqrt();
    }
    Some((lowest, readings))
}

/// The largest of `readings` over `by`, rate and angle apart.
fn most_over(readings: &[[f64; 2]], by: [f64; 2]) -> [f64; 2] {
    readings.iter().fold([0.0f64; 2], |m, r| {
        [m[0].max(r[0] / by[0]), m[1].max(r[1] / by[1])]
    })
}

/// Every reference start (both files) with its horizon, one per family (the start at every `k`).
fn families() -> Vec<(String, Problem, f64)> {
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for (name, c) in cases() {
        let t_end = c["t_end"].as_float().unwrap();
        let family = format!("{} T {t_end}", name.split("_k").next().unwrap());
        if seen.insert(family.clone()) {
            out.push((family, problem_of(&c), t_end));
        }
    }
    out
}

/// Every reference case of both files, by name.
fn cases() -> Vec<(String, toml::Table)> {
    let mut out = Vec::new();
    for file in ["averaged.toml", "rattleback_honesty.toml"] {
        let text = std::fs::read_to_string(format!("tests/fixtures/reference/{file}")).unwrap();
        let table: toml::Table = text.parse().unwrap();
        for (name, c) in table["case"].as_table().unwrap() {
            out.push((name.clone(), c.as_table().unwrap().clone()));
        }
    }
    out
}

/// How much a start's condition numbers move with `k` above the stiffness where its expansion
/// parameter is 0.01 (see the module's documentation).
fn spread() {
    let mut worst = [0.0f64; 2];
    for (family, p, t_end) in families() {
        let Some((lowest, readings)) = over_k(&p, t_end, 0.01) else {
            continue;
        };
        let first = readings[0];
        let [rate, angle] = most_over(&readings, first);
        worst = [worst[0].max(rate), worst[1].max(angle)];
        println!(
            "{family:20} from k {lowest:.0e} (κ rate {:.3e}, angle {:.3e}) to 1e12: at most {rate:.2}× (rate), {angle:.2}× (angle)",
            first[0], first[1]
        );
    }
    println!("largest: {:.2}× (rate), {:.2}× (angle)", worst[0], worst[1]);
}

/// The start's condition numbers on the effective limit (three separate runs), `[rate, angle]`,
/// and what they cost, ms (best of 7).
fn on_the_limit(p: &Problem, t_end: f64, tolerance: f64) -> ([f64; 2], f64) {
    let spec = RunSpec {
        method: Method::Effective,
        tolerance,
        step: None,
        t_end,
        samples: 0,
        monitor_energy: false,
    };
    let read = || {
        let base = run(p, &spec).unwrap();
        let mut out = [0.0; 2];
        for (i, slot) in out.iter_mut().enumerate() {
            let mut s = *p.start();
            if i == 0 {
                s.alpha_dot *= 1.0 + 1e-10;
            } else {
                s.alpha += 1e-10;
            }
            let other = run(&Problem::new(*p.params(), s).unwrap(), &spec).unwrap();
            *slot = difference(&base, &other) / 1e-10;
        }
        out
    };
    let kappa = read();
    let ms = (0..7)
        .map(|_| {
            let clock = std::time::Instant::now();
            let _ = read();
            clock.elapsed().as_secs_f64() * 1e3
        })
        .fold(f64::INFINITY, f64::min);
    (kappa, ms)
}

/// `… conditioning_check limit`: the reading on the effective limit against `auto`'s on
/// `averaged2` at every `k` of each family.
fn limit() {
    let mut worst = [0.0f64; 2];
    for (family, p, t_end) in families() {
        let Some((lowest, readings)) = over_k(&p, t_end, 0.25) else {
            continue;
        };
        let (lim, ms) = on_the_limit(&p, t_end, 1e-9);
        let [rate, angle] = most_over(&readings, lim.map(|x| x.max(1.0)));
        worst = [worst[0].max(rate), worst[1].max(angle)];
        println!(
            "{family:20} from k {lowest:.0e}: limit κ rate {:.3e} angle {:.3e} ({ms:.3} ms); averaged2 at most {rate:.2}× (rate), {angle:.2}× (angle) of max(limit, 1)",
            lim[0], lim[1]
        );
    }
    println!("largest: {:.2}× (rate), {:.2}× (angle)", worst[0], worst[1]);
}
