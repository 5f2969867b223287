//! The pendulum's full model by the Taylor series (`taylor`) and by DOP853 (the flows the
//! explorer and `simulate` run, `FullTaylor` and `FullDop853`), against the
//! long-double Taylor-series references: error over the reference's samples, steps and best
//! wall time of seven, at local tolerances 1e-9 … 1e-14 (docs/benchmarks.md, "The resolved end:
//! a Taylor series").
//!
//! `cargo run --release --example taylor_against_dop853 [START]`: START is a reference start
//! (`upright`, `falls`, `hanging`) or the prefix of a case's name; `REF=FILE` reads another
//! reference file (`tests/fixtures/reference/kapitza_honesty.toml`). ε ≥ 1e-3 only.

use std::time::Instant;

use rattleback::physics::flow::Flow;
use rattleback::physics::kapitza::flows::{FullDop853, FullTaylor};
use rattleback::physics::kapitza::{Params, Problem, Start};

struct Case {
    problem: Problem,
    t_end: f64,
    theta: Vec<f64>,
    theta_dot: Vec<f64>,
}

impl Case {
    /// The largest error of `flow` over the reference's samples, and its steps.
    fn error(&self, mut flow: impl Flow) -> (f64, u64) {
        let n = self.theta.len();
        let mut worst: f64 = 0.0;
        for i in 1..n {
            let t = self.t_end * i as f64 / (n - 1) as f64;
            while flow.time() < t {
                flow.step(self.t_end).expect("a step");
            }
            let y = flow.state_at(t);
            worst = worst
                .max((y[0] - self.theta[i]).abs())
                .max((y[1] - self.theta_dot[i]).abs());
        }
        (worst, flow.stats().steps)
    }
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

fn main() {
    let path =
        std::env::var("REF").unwrap_or_else(|_| "tests/fixtures/reference/kapitza.toml".into());
    let text = std::fs::read_to_string(&path).expect("the reference file");
    let table: toml::Table = text.parse().expect("TOML");
    let want = std::env::args().nth(1).unwrap_or_else(|| "upright".into());
    println!("| case | ε | tolerance | taylor error | steps | µs | dop853 error | steps | µs |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for (name, c) in table["case"].as_table().expect("cases") {
        let c = c.as_table().expect("a case");
        let start = c.get("start").and_then(toml::Value::as_str);
        if start != Some(want.as_str()) && !name.starts_with(want.as_str()) {
            continue;
        }
        let num = |k: &str| c[k].as_float().expect(k);
        let list = |k: &str| -> Vec<f64> {
            c[k].as_array()
                .expect(k)
                .iter()
                .map(|v| v.as_float().expect(k))
                .collect()
        };
        let case = Case {
            problem: Problem::new(
                Params {
                    a: num("a"),
                    b: num("b"),
                    epsilon: num("epsilon"),
                },
                Start {
                    theta: num("theta0"),
                    theta_dot: num("theta_dot0"),
                },
            )
            .expect("a valid reference case"),
            t_end: num("t_end"),
            theta: list("theta"),
            theta_dot: list("theta_dot"),
        };
        let epsilon = case.problem.params().epsilon;
        if epsilon < 1e-3 {
            continue;
        }
        for tol in [1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14] {
            let ((te, ts), tt) = best_of_seven(|| case.error(FullTaylor::new(&case.problem, tol)));
            let ((de, ds), dt) = best_of_seven(|| case.error(FullDop853::new(&case.problem, tol)));
            println!(
                "| {name} | {:.0e} | {tol:.0e} | {te:.1e} | {ts} | {:.1} | {de:.1e} | {ds} | {:.1} |",
                epsilon,
                tt * 1e6,
                dt * 1e6
            );
        }
    }
}
