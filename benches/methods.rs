//! Work–precision of every method at k = 1e2, 1e4, 1e6 over T = 20 (subcritical start).
//!
//! For each configuration the error of `alpha(T)` and `alpha_dot(T)` against a reference
//! (DOP853 at tolerance 1e-13, cross-checked against suzuki8 at ωh = 0.05) is printed once to
//! stderr; criterion then times the integration alone (no energy monitoring, no samples).
//! Run: `cargo bench --bench methods`.

mod common;

use common::problem;
use criterion::{Criterion, criterion_group, criterion_main};
use rattleback::physics::Method;
use rattleback::physics::rattleback::run;
use std::hint::black_box;
use std::time::Duration;

const T_END: f64 = 20.0;

/// `(method, tolerance, ω_max·h)` of each timed configuration.
const CONFIGS: &[(Method, f64, Option<f64>)] = &[
    (Method::Dop853, 1e-8, None),
    (Method::Dop853, 1e-10, None),
    (Method::Dop853, 3e-11, None),
    (Method::Dop853, 1e-12, None),
    (Method::Taylor, 1e-10, None),
    (Method::Taylor, 1e-12, None),
    (Method::Rk4, 0.0, Some(0.1)),
    (Method::Rk4, 0.0, Some(0.05)),
    (Method::Strang, 0.0, Some(0.8)),
    (Method::Strang, 0.0, Some(0.2)),
    (Method::Yoshida4, 0.0, Some(0.8)),
    (Method::Yoshida4, 0.0, Some(0.4)),
    (Method::BlanesMoan4, 0.0, Some(3.2)),
    (Method::BlanesMoan4, 0.0, Some(2.4)),
    (Method::BlanesMoan4, 0.0, Some(1.2)),
    (Method::Yoshida6, 0.0, Some(1.6)),
    (Method::Yoshida6, 0.0, Some(0.8)),
    (Method::Suzuki8, 0.0, Some(1.6)),
    (Method::Suzuki8, 0.0, Some(0.8)),
    (Method::Effective, 1e-10, None),
];

fn work_precision(c: &mut Criterion) {
    for k in [1e2, 1e4, 1e6] {
        let problem = problem(k, 0.5);
        let omega = problem.params().omega_max();
        let reference = run(&problem, &common::spec(Method::Dop853, 1e-13, None, T_END))
            .unwrap()
            .final_state;
        let check = run(
            &problem,
            &common::spec(Method::Suzuki8, 0.0, Some(0.05 / omega), T_END),
        )
        .unwrap()
        .final_state;
        eprintln!(
            "k = {k:e}: reference alpha(T) = {:.15}, cross-check differs by {:.1e}",
            reference[1],
            (check[1] - reference[1]).abs()
        );
        let mut group = c.benchmark_group(format!("k={k:e}"));
        group.sample_size(10);
        group.warm_up_time(Duration::from_millis(300));
        group.measurement_time(Duration::from_secs(2));
        for &(method, tolerance, omega_h) in CONFIGS {
            let s = common::spec(method, tolerance, omega_h.map(|wh| wh / omega), T_END);
            let r = run(&problem, &s).unwrap();
            let setting =
                omega_h.map_or_else(|| format!("tol={tolerance:e}"), |wh| format!("wh={wh}"));
            eprintln!(
                "  {:<10} {:<10} err_alpha {:.2e}  err_alpha_dot {:.2e}  rhs {}",
                method.name(),
                setting,
                (r.final_state[1] - reference[1]).abs(),
                (r.final_state[3] - reference[3]).abs(),
                r.stats.rhs_evaluations
            );
            group.bench_function(format!("{}/{setting}", method.name()), |b| {
                b.iter(|| run(black_box(&problem), black_box(&s)).unwrap());
            });
        }
        group.finish();
    }
}

criterion_group!(benches, work_precision);
criterion_main!(benches);
