//! Issue 27's pendulum target under criterion: `auto` as `simulate` and the explorer run it
//! (planned and verified by `kapitza::plan::verified`, then run) at tolerances 1e-8 (the
//! issue's) and 1e-9 on the references' upright start (a = 1, b = 2, θ0 = 0.3, T = 5), for
//! ε = 1e-1 … 1e-9. Errors against independent references are in `rattleback bench --only
//! kapitza`.
//! Run: `cargo bench --bench pendulum`.

use criterion::{Criterion, criterion_group, criterion_main};
use rattleback::physics::kapitza::run::run;
use rattleback::physics::kapitza::{Params, Problem, Start, plan};
use rattleback::physics::method::RunSpec;
use std::hint::black_box;
use std::time::Duration;

const T_END: f64 = 5.0;

fn auto(problem: &Problem, tol: f64) -> f64 {
    let c = plan::verified(problem, tol, T_END, 60.0, &mut |_| true).unwrap();
    let spec = RunSpec {
        method: c.method,
        tolerance: c.settings.tolerance,
        step: None,
        t_end: T_END,
        samples: 0,
        monitor_energy: true,
    };
    run(problem, &spec, &mut |_| true).unwrap().theta
}

fn pendulum(c: &mut Criterion) {
    let mut group = c.benchmark_group("pendulum");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    for (e, tol) in (1..=9).flat_map(|e| [(e, 1e-8), (e, 1e-9)]) {
        let epsilon = 10f64.powi(-e);
        let p = Problem::new(
            Params {
                a: 1.0,
                b: 2.0,
                epsilon,
            },
            Start {
                theta: 0.3,
                theta_dot: 0.0,
            },
        )
        .unwrap();
        let choice = plan::verified(&p, tol, T_END, 60.0, &mut |_| true).unwrap();
        eprintln!(
            "epsilon={epsilon:e} tol={tol:e}: auto -> {}, estimate {:.2e}, met {}",
            choice.method, choice.estimate, choice.met
        );
        group.bench_function(format!("auto/tol={tol:e}/epsilon={epsilon:e}"), |b| {
            b.iter(|| auto(black_box(&p), tol));
        });
    }
    group.finish();
}

criterion_group!(benches, pendulum);
criterion_main!(benches);
