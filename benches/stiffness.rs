//! Issue 3's targets: `auto` at tolerance 1e-8 over k = 1e6 … 1e12 (flat in k), and against
//! DOP853 at k = 1e8 at equal or better accuracy, on a trapped and a rotating start (T = 20).
//! Errors are printed once per configuration against a reference: tight DOP853 for k ≤ 1e6,
//! blanes-moan4 at ωh = 0.8 at k = 1e8 (itself within 1e-11 of DOP853 at 1e-13 at k = 1e6),
//! the corrected effective model at tolerance 1e-13 beyond (its O(1/k) error is < 1e-10 there).
//! Run: `cargo bench --bench stiffness`.

mod common;

use common::problem;
use criterion::{Criterion, criterion_group, criterion_main};
use rattleback::physics::auto::run_auto;
use rattleback::physics::{Method, Problem, run};
use std::hint::black_box;
use std::time::Duration;

const T_END: f64 = 20.0;
const TOL: f64 = 1e-8;

fn reference(p: &Problem) -> (f64, f64) {
    let k = p.params().k;
    let s = if k <= 1e6 {
        common::spec(Method::Dop853, 1e-13, None, T_END)
    } else if k <= 1e8 {
        common::spec(
            Method::BlanesMoan4,
            0.0,
            Some(0.8 / p.params().omega_max()),
            T_END,
        )
    } else {
        common::spec(Method::EffectiveCorrected, 1e-13, None, T_END)
    };
    let y = run(p, &s).unwrap().final_state;
    (y[1], y[3])
}

fn stiffness(c: &mut Criterion) {
    let mut group = c.benchmark_group("stiffness");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(3));
    for (regime, alpha_dot) in [("trapped", 0.5), ("rotating", 1.0)] {
        for k in [1e6, 1e8, 1e10, 1e12] {
            let p = problem(k, alpha_dot);
            let r = reference(&p);
            let v = run_auto(&p, TOL, T_END, 0, false).unwrap();
            let y = v.result.final_state;
            eprintln!(
                "{regime} k={k:e}: auto -> {} ({} refinements), error {:.2e}, estimate {:.2e}",
                v.plan.method,
                v.refinements,
                (y[1] - r.0).abs().max((y[3] - r.1).abs()),
                v.error_estimate
            );
            group.bench_function(format!("{regime}/auto/k={k:e}"), |b| {
                b.iter(|| run_auto(black_box(&p), TOL, T_END, 0, false).unwrap());
            });
        }
        let p = problem(1e8, alpha_dot);
        let r = reference(&p);
        for tol in [1e-11, 1e-12] {
            let s = common::spec(Method::Dop853, tol, None, T_END);
            let y = run(&p, &s).unwrap().final_state;
            eprintln!(
                "{regime} k=1e8: dop853 tol {tol:e}, error {:.2e}",
                (y[1] - r.0).abs().max((y[3] - r.1).abs())
            );
            group.bench_function(format!("{regime}/dop853-tol{tol:e}/k=1e8"), |b| {
                b.iter(|| run(black_box(&p), black_box(&s)).unwrap());
            });
        }
    }
    group.finish();
}

criterion_group!(benches, stiffness);
criterion_main!(benches);
