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

use rattleback::physics::rattleback::auto::{difference, slow_condition_numbers};
use rattleback::physics::rattleback::averaged::expansion_parameter;
use rattleback::physics::rattleback::integrators::Method;
use rattleback::physics::rattleback::run::{RunSpec, run};
use rattleback::physics::rattleback::{Params, Problem, Start};
fn main() {
    let all = std::env::args().nth(1).as_deref() == Some("all");
    for file in ["averaged.toml", "rattleback_honesty.toml"] {
        let text = std::fs::read_to_string(format!("tests/fixtures/reference/{file}")).unwrap();
        let table: toml::Table = text.parse().unwrap();
        for (name, c) in table["case"].as_table().unwrap() {
            let c = c.as_table().unwrap();
            let f = |k: &str| c[k].as_float().unwrap();
            if c["source"].as_str() != Some("rk8-long-double") {
                continue;
            }
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
            let p = Problem::new(params, start).unwrap();
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
}
