//! Every chart priced from its window (issue 80, shared/docs/reviews/reliability.md N2): the
//! pendulum's cell is priced from its own coefficients, and over generated windows the work its
//! cells take (DOP853 steps, counted, so nothing here depends on the machine's speed) is within
//! 2× of the price; the reviews' hostile windows are refused at once, and a chart the cost
//! model misjudges is stopped by its watchdog (`study map`) rather than run for minutes.

use crate::common::{Seeded, bin};
use rattleback::physics::kapitza::floquet::{Mathieu, floquet};

#[test]
fn the_pendulums_cells_take_the_work_their_price_says_on_generated_windows() {
    let mut g = Seeded::new("pendulum prices");
    for window in 0..24 {
        let eps = g.log_uniform(1e-3, 0.5);
        let hanging = g.next_u64().is_multiple_of(2);
        let scale = 1.0 / (eps * eps);
        let (a0, a1) = {
            let c = g.uniform(-3.0, 3.0) * scale * g.log_uniform(1e-4, 1e2);
            let w = g.log_uniform(1e-2, 10.0) * scale.min(1e6);
            (c - w, c + w)
        };
        let (b0, b1) = {
            let lo = g.log_uniform(1e-3, 1e4);
            (lo, lo * g.log_uniform(2.0, 1e3))
        };
        let tolerance = *g.pick(&[1e-10, 1e-8, 1e-12, 1e-6]);
        let (mut taken, mut priced, mut cells) = (0.0, 0.0, 0);
        for i in 0..8 {
            for j in 0..5 {
                let a = a0 + (a1 - a0) * (f64::from(i) + 0.5) / 8.0;
                let b = (b0.ln() + (b1 / b0).ln() * (f64::from(j) + 0.5) / 5.0).exp();
                let e2a = eps * eps * a;
                let m = Mathieu {
                    delta: if hanging { e2a } else { -e2a },
                    q: eps * b,
                };
                // Cells too fast for a chart (a run of minutes) are not what this prices.
                if (m.delta.abs() + m.q.abs()).sqrt() > 2e4 {
                    continue;
                }
                // A failed cell (a step size that underflowed) stops early: priced in full.
                if let Ok(f) = floquet(m, tolerance) {
                    {
                        taken += f.steps as f64;
                    }
                    priced += m.price_steps(tolerance);
                    cells += 1;
                }
            }
        }
        if cells < 10 {
            continue;
        }
        let ratio = taken / priced;
        assert!(
            (0.4..=2.0).contains(&ratio),
            "window {window} (eps {eps}, a {a0}..{a1}, b {b0}..{b1}, tolerance {tolerance}, \
             hanging {hanging}): {taken} steps against {priced} priced ({ratio:.2}x) {}",
            g.tag()
        );
    }
}

#[test]
fn the_reviews_hostile_windows_are_refused_at_once() {
    for args in [
        &[
            "--preset",
            "kapitza-upright",
            "--grid",
            "100x60",
            "--columns",
            "1e11,1e12",
            "--rows",
            "1e11,1e12",
            "--exhaustive",
        ][..],
        &[
            "--preset",
            "subcritical",
            "--k",
            "1e4",
            "--grid",
            "40x24",
            "--inertia-min",
            "0.001",
            "--inertia-max",
            "1000",
        ],
    ] {
        let mut a = vec!["study", "map", "--format", "json"];
        a.extend_from_slice(args);
        let (code, out, err) = bin(&a);
        assert_eq!(code, 2, "{args:?}: {out} {err}");
        assert!(
            err.contains("budget 60 s") && err.contains("--force"),
            "{args:?}: {err}"
        );
    }
}
