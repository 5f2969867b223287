//! Issue 58, item 2: does the difference of two consecutive averaged models bound the higher
//! one's model error? On every held-out reference (`averaged.toml`, `rattleback_honesty.toml`,
//! `rattleback_unequal.toml`: the full model in long double, or the note's averaged model at
//! k ≥ 1e10), `averaged2` and `averaged3` at a local tolerance of 1e-13: each one's error
//! against the reference (α(T), α̇(T), reversal times) and their difference, with the start's
//! expansion parameter `x` (`averaged::expansion_parameter`).
//!
//! `cargo run --release --example consecutive_orders` prints one row a case, sorted by `x`, and
//! the largest `x` below which `|a2 − a3|` bounds `averaged3`'s error on every case.

use rattleback::physics::Method;
use rattleback::physics::method::{Asked, RunSpec};
use rattleback::physics::rattleback::averaged::expansion_parameter;
use rattleback::physics::rattleback::{Params, Problem, RunResult, Start, run};

fn num(c: &toml::Table, k: &str) -> f64 {
    c[k].as_float()
        .or_else(|| c[k].as_integer().map(|i| i as f64))
        .unwrap()
}

fn gap(a: (f64, f64, &[f64]), b: (f64, f64, &[f64])) -> f64 {
    if a.2.len() != b.2.len() {
        return f64::INFINITY;
    }
    a.2.iter()
        .zip(b.2)
        .fold((a.0 - b.0).abs().max((a.1 - b.1).abs()), |d, (x, y)| {
            d.max((x - y).abs())
        })
}

fn of(r: &RunResult) -> (f64, f64, &[f64]) {
    (r.final_state[1], r.final_state[3], &r.reversals)
}

fn main() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/reference/");
    let mut rows = Vec::new();
    for file in [
        "averaged.toml",
        "rattleback_honesty.toml",
        "rattleback_unequal.toml",
    ] {
        let table: toml::Table = std::fs::read_to_string(format!("{dir}{file}"))
            .unwrap()
            .parse()
            .unwrap();
        for (name, c) in table["case"].as_table().unwrap() {
            let c = c.as_table().unwrap();
            let params = Params {
                ix: num(c, "ix"),
                iy: num(c, "iy"),
                iz: num(c, "iz"),
                k: num(c, "k"),
            };
            let start = Start {
                gamma: num(c, "gamma0"),
                alpha: num(c, "alpha0"),
                gamma_dot: num(c, "gamma_dot0"),
                alpha_dot: num(c, "alpha_dot0"),
            };
            let problem = Problem::new(params, start).unwrap();
            let t_end = num(c, "t_end");
            let reversals: Vec<f64> = c["reversals"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_float().unwrap())
                .collect();
            let reference = (num(c, "alpha_end"), num(c, "alpha_dot_end"), &reversals[..]);
            let accuracy = c
                .get("uncertainty")
                .map_or(1e-12, |_| num(c, "uncertainty"));
            let go = |m| {
                run(
                    &problem,
                    &RunSpec::new(Asked::new(m, 1e-13, None, t_end), 0),
                )
            };
            let (Ok(a2), Ok(a3)) = (go(Method::Averaged2), go(Method::Averaged3)) else {
                continue;
            };
            let e2 = gap(of(&a2), reference);
            let e3 = gap(of(&a3), reference);
            let d = gap(of(&a2), of(&a3));
            rows.push((
                expansion_parameter(&problem),
                name.clone(),
                params.k,
                e2,
                e3,
                d,
                accuracy,
            ));
        }
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    println!(
        "{:<26} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "case", "k", "x", "err a2", "err a3", "|a2-a3|", "a3/diff"
    );
    let mut boundary = f64::INFINITY;
    for (x, name, k, e2, e3, d, acc) in &rows {
        let ratio = (e3 - acc).max(0.0) / d;
        println!("{name:<26} {k:>9.0e} {x:>9.2e} {e2:>9.1e} {e3:>9.1e} {d:>9.1e} {ratio:>9.2}");
        if ratio > 1.0 && *x < boundary {
            boundary = *x;
        }
    }
    println!("|a2 - a3| bounds averaged3's error on every case with x below {boundary:.2e}");
}
