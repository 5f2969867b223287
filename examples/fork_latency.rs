//! What `auto`'s second core costs and saves (issue 27, `physics::fork`, `parallel`):
//! - how long rayon's pool takes to start an offered job (after it went to sleep, and back to
//!   back), a fresh `std::thread`, and what spawning one costs the caller;
//! - the parts of `auto` on the averaging note's starts A (trapped) and B (rotating): the run it
//!   returns, its companion, the start's conditioning, and `auto` on two cores and on one (best
//!   of 50: best of 7 left 30 % between runs on a busy machine; probes kept).
//!
//! Timing belongs here, not in the tests. Run:
//! `cargo run --release --example fork_latency`

use std::time::{Duration, Instant};

use rattleback::physics::fork;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::auto::{conditioning, plan, run_auto};
use rattleback::physics::rattleback::run::run;

fn best_ms(mut f: impl FnMut()) -> f64 {
    f();
    (0..50)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
        * 1e3
}

/// Median and 90th percentile of 200 starts, in µs.
fn latency(mut start: impl FnMut() -> Duration) -> (f64, f64) {
    let mut us: Vec<f64> = (0..200).map(|_| start().as_secs_f64() * 1e6).collect();
    us.sort_by(f64::total_cmp);
    (us[100], us[180])
}

fn main() {
    rattleback::parallel::install();
    let offered = || {
        let t0 = Instant::now();
        let (tx, rx) = std::sync::mpsc::channel();
        rayon::spawn(move || {
            let _ = tx.send(t0.elapsed());
        });
        rx.recv().expect("the pool answers")
    };
    let (m, p) = latency(|| {
        std::thread::sleep(Duration::from_micros(300));
        offered()
    });
    println!("a pool thread starts an offered job after 300 us idle: median {m:.1} us, p90 {p:.1}");
    let (m, p) = latency(offered);
    println!("back to back: median {m:.1} us, p90 {p:.1}");
    let (m, p) = latency(|| {
        let t0 = Instant::now();
        std::thread::spawn(move || t0.elapsed())
            .join()
            .expect("a thread")
    });
    println!("a fresh std::thread starts: median {m:.1} us, p90 {p:.1}");
    let (m, p) = latency(|| {
        let t0 = Instant::now();
        let handle = std::thread::spawn(|| ());
        let spent = t0.elapsed();
        handle.join().expect("a thread");
        spent
    });
    println!("spawning it costs the caller: median {m:.1} us, p90 {p:.1}");
    let per = best_ms(|| {
        for _ in 0..1000 {
            let _ = std::hint::black_box(fork::both(&mut |_| true, |_| 1, |_| 2));
        }
    });
    println!("fork::both of two empty jobs: {per:.2} us of the caller's time");

    for (name, alpha_dot) in [("A (trapped)", 0.5), ("B (rotating)", 1.2)] {
        for k in [1e2, 1e3, 1e4, 1e6, 1e8] {
            // The averaging note's body and start (`ix = 2, iy = 1, iz = 1`, `γ̇0 = 1`).
            let p = rattleback::bench::case(2.0, 1.0, k, alpha_dot);
            let pl = plan(&p, 1e-8, 30.0);
            let spec = |s: rattleback::physics::method::Settings| RunSpec {
                method: pl.method,
                tolerance: s.tolerance,
                step: s.step,
                t_end: 30.0,
                samples: 0,
                monitor_energy: false,
            };
            let (r, c) = (spec(pl.settings()), spec(pl.companion()));
            let run_ms = best_ms(|| {
                let _ = std::hint::black_box(run(&p, &r));
            });
            let companion_ms = best_ms(|| {
                let _ = std::hint::black_box(run(&p, &c));
            });
            let conditioning_ms = best_ms(|| {
                let _ = std::hint::black_box(conditioning(&p, 30.0, &pl, &mut |_| true));
            });
            let two = best_ms(|| {
                let _ = std::hint::black_box(run_auto(&p, 1e-8, 30.0, 0, false));
            });
            let one = best_ms(|| {
                fork::sequentially(|| {
                    let _ = std::hint::black_box(run_auto(&p, 1e-8, 30.0, 0, false));
                });
            });
            println!(
                "{name} k = {k:.0e}: {} run {run_ms:.3} ms, companion {companion_ms:.3}, \
                 conditioning {conditioning_ms:.3}; auto {two:.3} ms on two cores, {one:.3} on one",
                pl.method
            );
        }
    }
}
