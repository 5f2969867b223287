//! Issue 12's targets: a 200 × 100 regime map from the limit (≤ 1 s on 2 cores), and a sweep of
//! 8 stiffnesses up to 1e8 at T = 30, tolerance 1e-8 (≤ 1 s). Run: `cargo bench --bench studies`.

use criterion::{Criterion, criterion_group, criterion_main};
use rattleback::scenario::shipped::resolve;
use rattleback::study::map::{Grid, Source, regime_map};
use rattleback::study::sweep::{ladder, sweep};
use std::hint::black_box;
use std::time::Duration;

fn studies(c: &mut Criterion) {
    let mut group = c.benchmark_group("studies");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(3));
    let grid = Grid::new(200, 100, 2.0, 1.0, 1.0, 30.0);
    group.bench_function("map 200x100 from the limit", |b| {
        b.iter(|| regime_map(black_box(&grid), Source::Limit, &|_| true).unwrap());
    });
    let preset = resolve("subcritical", &[]).unwrap();
    group.bench_function("sweep 1e1..1e8, T = 30, tol 1e-8", |b| {
        b.iter(|| {
            sweep(
                black_box(&preset.model),
                ladder(rattleback::physics::ModelKind::Rattleback),
                30.0,
                1e-8,
                &|_| true,
                &|| {},
            )
            .unwrap()
        });
    });
    group.finish();
}

criterion_group!(benches, studies);
criterion_main!(benches);
