//! The exact special solutions of physics.md §1 and the tapping effect, for every method.

use crate::common;

/// Rounding accumulated over a run: each step may add a few ulps of the value.
fn rounding(steps: u64, value: f64) -> f64 {
    4.0 * (steps.max(1) as f64) * f64::EPSILON * (1.0 + value.abs())
}

use rattleback::physics::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::effective::tapping_acceleration;
use rattleback::physics::rattleback::run;

fn spec(method: Method, t_end: f64) -> RunSpec {
    RunSpec {
        method,
        tolerance: 1e-10,
        step: None,
        t_end,
        samples: 0,
        monitor_energy: true,
    }
}

/// `ix = iy`: `α = α0 + α̇0 t` and `γ` harmonic at `sqrt(k/ix)`, for every k.
#[test]
fn symmetric_body_spins_uniformly_and_tilt_is_harmonic() {
    for k in [0.5, 40.0, 1e6] {
        let (g0, a0, gd0, ad0) = (0.01, 0.3, 0.7, -0.4);
        let problem = common::problem(1.5, 1.5, 0.8, k, [g0, a0, gd0, ad0]);
        let t = 3.7;
        let w = (k / 1.5f64).sqrt();
        let gamma = g0 * (w * t).cos() + gd0 / w * (w * t).sin();
        let gamma_dot = -g0 * w * (w * t).sin() + gd0 * (w * t).cos();
        for method in rattleback_methods() {
            // The exact-flow methods are exact at any step; RK4 needs a resolving one.
            let step = (method != Method::Rk4).then_some(0.01);
            let r = run(
                &problem,
                &RunSpec {
                    step,
                    ..spec(method, t)
                },
            )
            .expect("integrates");
            let y = r.final_state;
            // α is exact for every method: its acceleration vanishes identically.
            let bound = rounding(r.stats.steps, y[1]);
            assert!(
                (y[1] - (a0 + ad0 * t)).abs() <= bound,
                "{method} k={k}: alpha {}",
                y[1]
            );
            assert!(
                (y[3] - ad0).abs() < 1e-14,
                "{method} k={k}: alpha_dot {}",
                y[3]
            );
            assert!(
                r.reversals.is_empty(),
                "{method}: a uniform spin never reverses"
            );
            // γ: exact flows (splittings, the effective phase) to rounding, others to tolerance.
            let tol = if matches!(method, Method::Rk4 | Method::Dop853 | Method::Taylor) {
                1e-6
            } else {
                rounding(r.stats.steps, 1.0) * (1.0 + w * t)
            };
            let scale = gd0 / w;
            assert!(
                (y[0] - gamma).abs() < tol * scale.max(1e-3),
                "{method} k={k}: gamma {} vs {gamma}",
                y[0]
            );
            assert!(
                (y[2] - gamma_dot).abs() < tol * gd0.max(1.0) * 10.0,
                "{method} k={k}: gamma_dot"
            );
        }
    }
}

/// `γ0 = γ̇0 = 0`: uniform rotation with `γ ≡ 0`, whatever the body.
#[test]
fn no_tilt_means_uniform_rotation() {
    let problem = common::problem(2.0, 1.0, 1.0, 1e4, [0.0, 0.2, 0.0, 1.3]);
    for method in rattleback_methods() {
        let r = run(&problem, &spec(method, 5.0)).expect("integrates");
        let y = r.final_state;
        let bound = rounding(r.stats.steps, y[1]);
        assert!(
            (y[1] - (0.2 + 1.3 * 5.0)).abs() <= bound,
            "{method}: alpha {}",
            y[1]
        );
        assert!(
            y[0].abs() < 1e-300 && y[2].abs() < 1e-300,
            "{method}: gamma must stay 0"
        );
        assert!((y[3] - 1.3).abs() < 1e-15, "{method}");
    }
}

/// Tapping: from `(0, α0)` with `(γ̇0, 0)`, `α̈(0) = (iy − ix) cos α0 sin α0 γ̇0² / iz`.
/// The full model starts with that acceleration; the effective model with half of it (it sees
/// the average of `γ̇²`, which is half its initial value); the corrected effective model with
/// all of it again, its ripple's slope `c I 2ω / iz` supplying the other half.
#[test]
fn tapping_acceleration_for_every_method() {
    let (ix, iy, iz, alpha0, gd0) = (2.0, 1.0, 1.5, 0.6, 1.2);
    let problem = common::problem(ix, iy, iz, 1e4, [0.0, alpha0, gd0, 0.0]);
    let formula = (iy - ix) * alpha0.cos() * alpha0.sin() * gd0 * gd0 / iz;
    assert!((tapping_acceleration(&problem) - formula).abs() < 1e-15);
    let t = 1e-5;
    for method in rattleback_methods() {
        let r = run(
            &problem,
            &RunSpec {
                step: Some(t / 8.0),
                ..spec(method, t)
            },
        )
        .expect("integrates");
        let measured = r.final_state[3] / t;
        let want = if method == Method::Effective {
            formula / 2.0
        } else {
            formula
        };
        assert!(
            (measured - want).abs() < 1e-5 * want.abs(),
            "{method}: initial spin acceleration {measured}, want {want}"
        );
        assert!(
            r.reversals.is_empty(),
            "{method}: a start from rest is not a reversal"
        );
    }
}

/// The rattleback's concrete methods.
fn rattleback_methods() -> impl Iterator<Item = Method> {
    rattleback::physics::ModelKind::Rattleback
        .methods()
        .iter()
        .copied()
        .filter(|m| *m != Method::Auto)
}
