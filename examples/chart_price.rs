//! How a chart's cells are priced against what they take (issue 80), the calibration behind the
//! cost models' constants:
//!
//! - `cargo run --release --example chart_price pendulum [N] [SEED]`: N random pendulum cells
//!   (ε 1e-3 … 0.5, both positions, `a` and `b` over twelve decades, tolerances 1e-6 … 1e-12),
//!   each's verified Floquet trace: the steps it took against `Mathieu::price_steps`, and the
//!   seconds a step took (`PENDULUM_STEP_SECONDS`); prints the ratio's spread and the mean of the
//!   steps over `2π ω l^(-1/8) + 40` by decade of `ω` and of the tolerance (`PRICE_FACTORS`).
//! - `cargo run --release --example chart_price full [N]`: N random full-model cells (`k` 1e2 …
//!   1e6, tolerances 1e-6 … 1e-10, T 10 … 100, inertia ratios 1e-3 … 1e3): the seconds each took
//!   against its price (`map::cell_seconds`), the median setting `FULL_CELL_OVER_RUN`, and how
//!   many of the probed cells the probes send to a resolved plan (`plan::REFUSED_SHARE`).
//! - `cargo run --release --example chart_price chart [STEP] [K]`: every STEP-th cell of the
//!   full model's 100×50 chart at K (`study map --grid 100x50 --k K`): where a computed cell's
//!   time goes (the probes, then the run and its verification) by the method `auto` ends with,
//!   against its price (issue 84).
//!
//! Timed on this machine: a calibration aid, not a test.

use rattleback::physics::kapitza::floquet::{Mathieu, floquet};
use rattleback::physics::rattleback::map::{Grid, Source, cell_reversals, cell_seconds};

/// A seeded generator of numbers in `[0, 1)`.
fn generator(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn pendulum(n: usize, seed: u64) {
    let mut rnd = generator(seed);
    let mut ratios = Vec::new();
    let mut per_step = Vec::new();
    let mut table = std::collections::BTreeMap::<(i32, i32), Vec<f64>>::new();
    let mut k = 0;
    while k < n {
        let eps = 10f64.powf(-3.0 + 2.7 * rnd());
        let a = if rnd() < 0.5 { -1.0 } else { 1.0 } * 10f64.powf(-2.0 + 10.0 * rnd());
        let b = 10f64.powf(-3.0 + 10.0 * rnd());
        let e2a = eps * eps * a;
        let m = Mathieu {
            delta: if rnd() < 0.5 { e2a } else { -e2a },
            q: eps * b,
        };
        let w = (m.delta.abs() + m.q.abs()).sqrt();
        if w > 3e4 {
            continue;
        }
        k += 1;
        let tol = if rnd() < 0.4 {
            1e-10
        } else {
            10f64.powf(-6.0 - 6.0 * rnd())
        };
        let start = std::time::Instant::now();
        let Ok(f) = floquet(m, tol) else { continue };
        let secs = start.elapsed().as_secs_f64();
        let steps = f.steps as f64;
        ratios.push(steps / m.price_steps(tol));
        if steps > 2000.0 {
            per_step.push(secs / steps);
        }
        let first = (tol * 0.1).clamp(1e-14, 1e-3);
        let x = 2.0 * std::f64::consts::PI * w * first.powf(-0.125) + 40.0;
        let key = (
            w.max(1e-3).log10().round().clamp(-1.0, 4.0) as i32,
            (2.0 * (tol.log10() / 2.0).round()).clamp(-12.0, -6.0) as i32,
        );
        table.entry(key).or_default().push(steps / x);
    }
    ratios.sort_by(f64::total_cmp);
    per_step.sort_by(f64::total_cmp);
    let at = |v: &[f64], q: f64| v[((v.len() - 1) as f64 * q) as usize];
    println!(
        "pendulum: {} cells, steps over price: min {:.2}, median {:.2}, 95% {:.2}, max {:.2}",
        ratios.len(),
        ratios[0],
        at(&ratios, 0.5),
        at(&ratios, 0.95),
        at(&ratios, 1.0)
    );
    println!(
        "seconds a step: median {:.2e} (PENDULUM_STEP_SECONDS)",
        at(&per_step, 0.5)
    );
    println!("steps over 2π ω l^(-1/8) + 40 by (log10 ω, log10 tolerance): mean (cells)");
    for ((lw, lt), v) in &table {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        println!("  ({lw:2}, {lt:3}): {mean:.2} ({})", v.len());
    }
}

fn full(n: usize) {
    use rattleback::physics::rattleback::auto;
    let (mut probed, mut refused) = (0, 0);
    let mut rnd = generator(3);
    let mut ratios = Vec::new();
    for _ in 0..n {
        let k = 10f64.powf(2.0 + 4.0 * rnd());
        let tolerance = 10f64.powf(-6.0 - 4.0 * rnd());
        let t_end = [10.0, 30.0, 100.0][((rnd() * 3.0) as usize).min(2)];
        let lo = 10f64.powf(-3.0 + 2.9 * rnd());
        let grid = Grid {
            cols: 7,
            rows: 7,
            ratio_max: 10f64.powf(-1.0 + 2.0 * rnd()),
            inertia: (lo, lo * 10f64.powf(0.1 + 3.0 * rnd())),
            ix: 2.0,
            iz: 1.0,
            gamma_dot: 1.0,
            t_end,
        };
        let (i, j) = (
            ((rnd() * 7.0) as usize).min(6),
            ((rnd() * 7.0) as usize).min(6),
        );
        let source = Source::Full { k, tolerance };
        let price = cell_seconds(&grid, source, i, j);
        if let Ok(p) = grid.problem(grid.ratio(i), grid.inertia_ratio(j), k)
            && auto::considers_averaged(&p, tolerance, t_end)
            && !auto::averaged_is_exact(&p)
        {
            probed += 1;
            if let Ok(d) = auto::plan_cancellable(&p, tolerance, t_end, &mut |_| true) {
                refused += usize::from(!d.plan.method.is_averaged());
            }
        }
        let start = std::time::Instant::now();
        if cell_reversals(&grid, source, i, j, &|_| true).is_ok() && price.is_finite() {
            ratios.push(start.elapsed().as_secs_f64() / price);
        }
    }
    println!("probed {probed}, the averaged model refused on {refused}");
    ratios.sort_by(f64::total_cmp);
    let at = |q: f64| ratios[((ratios.len() - 1) as f64 * q) as usize];
    println!(
        "full model: {} cells, seconds over price: min {:.2}, 10% {:.2}, median {:.2}, 90% {:.2}, max {:.1}",
        ratios.len(),
        at(0.0),
        at(0.1),
        at(0.5),
        at(0.9),
        at(1.0)
    );
}

/// Where a full-model chart's computed cell goes: every `step`-th cell of the `subcritical`
/// preset's 100×50 chart at `k` (tolerance 1e-9, T = 30, the chart `study map --grid 100x50 --k
/// K` draws), each planned (the probes, timed), then run and verified (the probes remembered by
/// then: [`auto::memo`]), by the method `auto` ends with.
fn chart(k: f64, step: usize) {
    use rattleback::physics::rattleback::auto;
    let grid = Grid {
        cols: 100,
        rows: 50,
        ratio_max: 2.0,
        inertia: (0.1, 10.0),
        ix: 2.0,
        iz: 1.0,
        gamma_dot: 1.0,
        t_end: 30.0,
    };
    let tolerance = 1e-9;
    // (cells, probed, probe seconds, run seconds, price seconds) by the method run.
    let mut by = std::collections::BTreeMap::<String, (usize, usize, f64, f64, f64)>::new();
    // Probed cells, and those resolved after all, by quarter decade of the expansion parameter.
    let mut rhos = std::collections::BTreeMap::<i32, (usize, usize)>::new();
    for n in (0..grid.cols * grid.rows).step_by(step) {
        let (i, j) = (n % grid.cols, n / grid.cols);
        let Ok(p) = grid.problem(grid.ratio(i), grid.inertia_ratio(j), k) else {
            continue;
        };
        let price = cell_seconds(&grid, Source::Full { k, tolerance }, i, j);
        let start = std::time::Instant::now();
        let Ok(decision) = auto::plan_cancellable(&p, tolerance, grid.t_end, &mut |_| true) else {
            continue;
        };
        let probing = start.elapsed().as_secs_f64();
        let start = std::time::Instant::now();
        let Ok(v) = auto::run_auto(&p, tolerance, grid.t_end, 0, false) else {
            continue;
        };
        let running = start.elapsed().as_secs_f64();
        if decision.probe.is_some() {
            let x = rattleback::physics::rattleback::averaged::expansion_parameter(&p);
            let bin = (4.0 * x.log10()).floor() as i32;
            let b = rhos.entry(bin).or_insert((0, 0));
            b.0 += 1;
            b.1 += usize::from(!v.plan.method.is_averaged());
        }
        let e = by.entry(format!("{}", v.plan.method)).or_default();
        e.0 += 1;
        e.1 += usize::from(decision.probe.is_some());
        e.2 += probing;
        e.3 += running;
        e.4 += price;
    }
    for (bin, (n, refused)) in &rhos {
        println!(
            "  expansion parameter in [1e{:.2}, 1e{:.2}): {n} probed, {refused} resolved",
            f64::from(*bin) / 4.0,
            f64::from(bin + 1) / 4.0
        );
    }
    let cells: usize = by.values().map(|e| e.0).sum();
    let total: f64 = by.values().map(|e| e.2 + e.3).sum();
    println!(
        "k {k:e}: {cells} cells, {:.2} ms a cell",
        1e3 * total / cells as f64
    );
    for (m, (n, probed, probing, running, price)) in &by {
        let c = *n as f64;
        println!(
            "  {m:>13}: {n:4} cells ({probed} probed), probes {:.2} ms, run and verification {:.2} ms, price {:.2} ms a cell; {:.0} % of the time",
            1e3 * probing / c,
            1e3 * running / c,
            1e3 * price / c,
            100.0 * (probing + running) / total
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n = args.get(2).and_then(|s| s.parse().ok());
    match args.get(1).map(String::as_str) {
        Some("full") => full(n.unwrap_or(150)),
        Some("chart") => chart(
            args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1e4),
            n.unwrap_or(7),
        ),
        _ => pendulum(
            n.unwrap_or(3000),
            args.get(3).and_then(|s| s.parse().ok()).unwrap_or(5),
        ),
    }
}
