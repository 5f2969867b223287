//! How well the work budget's prediction matches measured run times on this machine.
//!
//! `cargo run --release --example budget_check` prints, for every shipped preset and method
//! (and a few long runs), the predicted and measured seconds and their ratio. Runs predicted
//! over 20 s are not measured. The budget only needs the right order of magnitude: it decides
//! between "run" and "ask for --force" at 60 s.

use rattleback::physics::method::Asked;
use std::time::Instant;

use rattleback::physics::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::plan::AutoRules;
use rattleback::physics::rattleback::plan::{predicted_seconds, resolve};
use rattleback::physics::rattleback::run;
use rattleback::scenario::preset::Override;
use rattleback::scenario::shipped::{SHIPPED, resolve as preset};

fn main() {
    let mut cases: Vec<(String, Vec<Override>)> = SHIPPED
        .iter()
        .map(|(n, _)| ((*n).to_owned(), Vec::new()))
        .collect();
    for extra in [
        "run.t_end=1000",
        "run.t_end=100000",
        "spring.k=1e8",
        "initial.gamma_dot=1000",
        "body.iz=1e-6",
    ] {
        cases.push((
            format!("subcritical {extra}"),
            vec![extra.parse().expect("override")],
        ));
    }
    println!(
        "{:<34} {:<20} {:>10} {:>10} {:>7}",
        "case", "method", "predicted", "measured", "ratio"
    );
    let mut ratios = Vec::new();
    for (label, overrides) in &cases {
        let name = label.split(' ').next().expect("name");
        let p = preset(name, overrides).expect("preset");
        // The rattleback's presets: the pendulum and the celt price their runs elsewhere.
        let Some(problem) = p.problem() else {
            continue;
        };
        let tol = p.run.tolerance.unwrap_or(1e-9);
        let t_end = p.run.t_end;
        for method in [
            Method::Auto,
            Method::Dop853,
            Method::Taylor,
            Method::Rk4,
            Method::BlanesMoan4,
            Method::Yoshida6,
            Method::Effective,
        ] {
            let predicted = predicted_seconds(problem, &Asked::new(method, tol, None, t_end));
            if predicted > 20.0 {
                println!(
                    "{label:<34} {method:<20} {predicted:>10.3e} {:>10} {:>7}",
                    "-", "-"
                );
                continue;
            }
            let clock = Instant::now();
            let ok = if method == Method::Auto {
                resolve(
                    problem,
                    method,
                    tol,
                    t_end,
                    AutoRules::Verified,
                    f64::INFINITY,
                    &mut |_| true,
                )
                .is_ok()
            } else {
                run(
                    problem,
                    &RunSpec {
                        method,
                        tolerance: tol,
                        step: None,
                        t_end,
                        samples: 0,
                        monitor_energy: true,
                    },
                )
                .is_ok()
            };
            let measured = clock.elapsed().as_secs_f64();
            let ratio = measured / predicted;
            if measured > 0.01 {
                ratios.push(ratio);
            }
            println!(
                "{label:<34} {method:<20} {predicted:>10.3e} {measured:>10.3e} {ratio:>7.2}{}",
                if ok { "" } else { " (failed)" }
            );
        }
    }
    ratios.sort_by(f64::total_cmp);
    if let (Some(lo), Some(hi)) = (ratios.first(), ratios.last()) {
        println!(
            "measured/predicted over runs longer than 10 ms: {lo:.2} … {hi:.2} (median {:.2}, {} runs)",
            ratios[ratios.len() / 2],
            ratios.len()
        );
    }
}
