//! Issue 13's targets under criterion: `auto` at tolerance 1e-8, T = 30, on the averaging
//! note's trapped (α̇0 = 0.5) and rotating (α̇0 = 1.2) starts, every decade of k from 1e2 to
//! 1e12, and our DOP853 at k = 1e8 at the loosest tolerance that meets 1e-8. Errors, estimates
//! and the comparison with the best single configuration and the peer are in
//! `rattleback bench` (its `auto_profile.csv`), against independent references.
//! `auto/…` is every `auto` after the first on a body and start (its averaged-model probes kept
//! for the process, issue 27); `auto-cold/…` forgets them before each run (a first `auto`).
//! As in the binary, `auto`'s verification runs beside its run on a second core
//! (`parallel::install`); `auto-one-core/…` is the same under `fork::sequentially`.
//! Run: `cargo bench --bench stiffness`.

mod common;

use common::problem;
use criterion::{Criterion, criterion_group, criterion_main};
use rattleback::physics::Method;
use rattleback::physics::rattleback::auto::{memo, run_auto};
use rattleback::physics::rattleback::run;
use std::hint::black_box;
use std::time::Duration;

const T_END: f64 = 30.0;
const TOL: f64 = 1e-8;

fn stiffness(c: &mut Criterion) {
    rattleback::parallel::install();
    let mut group = c.benchmark_group("stiffness");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    for (regime, alpha_dot) in [("trapped", 0.5), ("rotating", 1.2)] {
        for e in 2..=12 {
            let k = 10f64.powi(e);
            let p = problem(k, alpha_dot);
            let v = run_auto(&p, TOL, T_END, 0, false).unwrap();
            eprintln!(
                "{regime} k={k:e}: auto -> {} ({} refinements), estimate {:.2e}, met {}",
                v.plan.method, v.refinements, v.error_estimate, v.met
            );
            group.bench_function(format!("{regime}/auto/k={k:e}"), |b| {
                b.iter(|| run_auto(black_box(&p), TOL, T_END, 0, false).unwrap());
            });
            group.bench_function(format!("{regime}/auto-one-core/k={k:e}"), |b| {
                b.iter(|| {
                    rattleback::physics::fork::sequentially(|| {
                        run_auto(black_box(&p), TOL, T_END, 0, false).unwrap()
                    })
                });
            });
            if v.plan.method == Method::Averaged2 {
                group.bench_function(format!("{regime}/auto-cold/k={k:e}"), |b| {
                    b.iter(|| {
                        memo::clear();
                        run_auto(black_box(&p), TOL, T_END, 0, false).unwrap()
                    });
                });
            }
        }
        let p = problem(1e8, alpha_dot);
        let s = common::spec(Method::Dop853, 1e-12, None, T_END);
        group.bench_function(format!("{regime}/dop853-tol1e-12/k=1e8"), |b| {
            b.iter(|| run(black_box(&p), black_box(&s)).unwrap());
        });
    }
    group.finish();
}

criterion_group!(benches, stiffness);
criterion_main!(benches);
