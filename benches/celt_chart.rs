//! Issue 84: the celt's chart in lanes against the same cells one by one (the scalar path each
//! lane is held to, bit for bit), on one thread: a 16 × 8 corner of `celt-clockwise`'s default
//! chart over its default window. Run: `cargo bench --bench celt_chart`; the ratio of the first
//! and the last is the chart's CPU per cell against the scalar code's; the middle two are the
//! explorer's map pane, a thread's slice one cell against `SceneChart::together`'s four. The
//! second group: the step controller's power for four lanes, in lanes and scalar.

use criterion::{Criterion, criterion_group, criterion_main};
use rattleback::physics::celt::chart::CeltChart;
use rattleback::physics::chart::SceneChart;
use rattleback::scenario::shipped::resolve;
use std::hint::black_box;
use std::time::Duration;

fn celt_chart(c: &mut Criterion) {
    let preset = resolve("celt-clockwise", &[]).unwrap();
    let problem = *preset.model.celt().expect("a celt preset");
    let (columns, rows) = CeltChart::default_axes(&problem, 200, 100);
    let chart = CeltChart {
        problem,
        columns,
        rows,
        t_end: preset.run.t_end,
        tolerance: rattleback::physics::celt::chart::CELT_TOLERANCE,
    };
    // A corner of 16 × 8 cells from the middle of the chart.
    let ns: Vec<usize> = (46..54)
        .flat_map(|j| (92..108).map(move |i| j * 200 + i))
        .collect();
    let mut group = c.benchmark_group("celt chart, 128 cells, one thread");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(8));
    group.bench_function("in lanes", |b| {
        b.iter(|| {
            let mut found = 0;
            chart.cells(black_box(&ns), &|_| true, &mut |_, v| {
                found += usize::from(v.is_ok());
            });
            found
        });
    });
    // The explorer's map pane hands a thread `together()` cells a slice (it was one).
    for at_once in [1, chart.together()] {
        group.bench_function(format!("in lanes, {at_once} cells a call"), |b| {
            b.iter(|| {
                let mut found = 0;
                for slice in black_box(&ns).chunks(at_once) {
                    chart.cells(slice, &|_| true, &mut |_, v| {
                        found += usize::from(v.is_ok());
                    });
                }
                found
            });
        });
    }
    group.bench_function("one by one", |b| {
        b.iter(|| {
            black_box(&ns)
                .iter()
                .filter(|&&n| chart.cell(n, &|_| true).is_ok())
                .count()
        });
    });
    group.finish();
}

/// The step controller's power for four lanes: `eighth_power` against the scalar `pow` four
/// times (the same bits), on errors spread over the controller's range.
fn controller_power(c: &mut Criterion) {
    use rattleback::physics::numerics::eighth_power::eighth_power;
    use rattleback::physics::numerics::elementary::Elementary;
    let errors: Vec<[f64; 4]> = (0..256_u32)
        .map(|i| std::array::from_fn(|l| 1e-3 + f64::from(i * 4) * 7.3e-3 + l as f64 * 7.3e-3))
        .collect();
    let mut group = c.benchmark_group("controller power, 256 × 4 errors");
    group.bench_function("eighth_power (four lanes)", |b| {
        b.iter(|| {
            black_box(&errors)
                .iter()
                .map(|&x| eighth_power(x).iter().sum::<f64>())
                .sum::<f64>()
        });
    });
    group.bench_function("scalar pow, four times", |b| {
        b.iter(|| {
            black_box(&errors)
                .iter()
                .map(|&x| x.map(|v| v.e_powf(-0.125)).iter().sum::<f64>())
                .sum::<f64>()
        });
    });
    group.finish();
}

criterion_group!(benches, celt_chart, controller_power);
criterion_main!(benches);
