//! Issue 3: integration at any stiffness. The phase-locked method has no step-size
//! resonance, the corrected effective model matches the full motion to O(1/k) in `α̇` too, and
//! `auto` meets its tolerance against independent references.

use crate::common;

use rattleback::physics::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::auto::{plan, run_auto};
use rattleback::physics::rattleback::{Problem, run};

fn run_with(
    problem: &Problem,
    method: Method,
    tolerance: f64,
    step: Option<f64>,
    t_end: f64,
) -> (f64, f64) {
    let spec = rattleback::bench::spec(method, tolerance, step, t_end);
    let y = run(problem, &spec).expect("integrates").final_state;
    (y[1], y[3])
}

fn err(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).abs().max((a.1 - b.1).abs())
}

/// At k = 1e8, ω ∈ [7071, 10000]: with h = 4e-4, ωh sweeps through π as α swings, the
/// resonance where plain Strang's error does not shrink with k. Locked steps of the same
/// nominal size avoid it.
#[test]
fn locked_steps_avoid_the_step_size_resonance() {
    let problem = common::problem(2.0, 1.0, 1.0, 1e8, [0.0, 0.0, 1.0, 0.5]);
    let t_end = 5.0;
    let reference = run_with(&problem, Method::BlanesMoan4, 0.0, Some(1.2e-4), t_end);
    let strang = err(
        run_with(&problem, Method::Strang, 0.0, Some(4e-4), t_end),
        reference,
    );
    let locked = err(
        run_with(&problem, Method::Locked, 0.0, Some(4e-4), t_end),
        reference,
    );
    eprintln!("error at h = 4e-4: strang {strang:.2e}, locked {locked:.2e}");
    assert!(locked < 1e-8, "locked error {locked:e}");
    assert!(
        strang > 30.0 * locked,
        "strang {strang:e} is not resonant against locked {locked:e}"
    );
}

/// The locked error does not grow with k (cost and accuracy independent of k).
#[test]
fn locked_error_is_flat_in_k() {
    let mut errors = Vec::new();
    for k in [1e6, 1e9, 1e12] {
        let problem = common::problem(2.0, 1.0, 1.0, k, [0.0, 0.0, 1.0, 0.5]);
        // Beyond k = 1e9 the corrected limit is itself accurate to < 1e-10 here.
        let reference = if k < 1e9 {
            run_with(
                &problem,
                Method::BlanesMoan4,
                0.0,
                Some(1.2 / f64::sqrt(k)),
                5.0,
            )
        } else {
            run_with(&problem, Method::EffectiveCorrected, 1e-13, None, 5.0)
        };
        errors.push(err(
            run_with(&problem, Method::Locked, 0.0, Some(1e-3), 5.0),
            reference,
        ));
    }
    eprintln!("locked errors at k = 1e6, 1e9, 1e12: {errors:?}");
    for e in &errors {
        assert!(*e < 5e-7, "{errors:?}");
    }
    assert!(
        errors[2] < 10.0 * errors[0],
        "error grows with k: {errors:?}"
    );
}

/// The ripple added back by the corrected model is the full motion's: at k = 1e8 the plain
/// limit misses α̇ by ~1e-5 (the O(k^{-1/2}) ripple), the corrected one by < 1e-8.
#[test]
fn corrected_effective_model_restores_the_fast_ripple() {
    let problem = common::problem(2.0, 1.0, 1.0, 1e8, [0.0, 0.0, 1.0, 0.5]);
    let reference = run_with(&problem, Method::BlanesMoan4, 0.0, Some(1.2e-4), 10.0);
    let plain = run_with(&problem, Method::Effective, 1e-12, None, 10.0);
    let corrected = run_with(&problem, Method::EffectiveCorrected, 1e-12, None, 10.0);
    let (e_plain, e_corr) = (
        (plain.1 - reference.1).abs(),
        (corrected.1 - reference.1).abs(),
    );
    eprintln!("alpha_dot error: effective {e_plain:.2e}, corrected {e_corr:.2e}");
    assert!(e_plain > 1e-6, "the plain limit should miss the ripple");
    assert!(e_corr < 1e-8, "corrected error {e_corr:e}");
    // With γ0 ≠ 0 the start's momentum is shifted by the ripple at φ0.
    let tilted = common::problem(2.0, 1.0, 1.0, 1e8, [3e-5, 0.3, 0.6, 0.2]);
    let reference = run_with(&tilted, Method::BlanesMoan4, 0.0, Some(1.2e-4), 5.0);
    let corrected = run_with(&tilted, Method::EffectiveCorrected, 1e-12, None, 5.0);
    assert!(
        err(corrected, reference) < 1e-8,
        "tilted start: {:e}",
        err(corrected, reference)
    );
}

/// `auto` at tolerance 1e-8 against tight DOP853 on the public cases' starts, trapped and
/// rotating, and its choices move from resolved to limit methods as k grows.
#[test]
fn auto_meets_its_tolerance_and_changes_method_with_k() {
    for alpha_dot in [0.5, 1.0] {
        for k in [1e2, 1e4] {
            let problem = common::problem(2.0, 1.0, 1.0, k, [0.0, 0.0, 1.0, alpha_dot]);
            let reference = run_with(&problem, Method::Dop853, 1e-13, None, 20.0);
            let v = run_auto(&problem, 1e-8, 20.0, 0, false).expect("auto runs");
            let got = (v.result.final_state[1], v.result.final_state[3]);
            assert!(
                err(got, reference) < 1e-8,
                "k={k:e}: {} off by {:e}",
                v.plan.method,
                err(got, reference)
            );
            assert!(v.error_estimate <= 1e-8, "estimate {:e}", v.error_estimate);
        }
    }
    let stiff = common::problem(2.0, 1.0, 1.0, 1e12, [0.0, 0.0, 1.0, 0.5]);
    // At k = 1e12 the second-order model's O(k⁻²) error is far below the tolerance, and it is
    // the cheaper averaged model.
    assert_eq!(plan(&stiff, 1e-8, 20.0).method, Method::Averaged2);
    let soft = common::problem(2.0, 1.0, 1.0, 1e2, [0.0, 0.0, 1.0, 0.5]);
    assert!(!plan(&soft, 1e-8, 20.0).method.is_effective());
}

/// Implicit stiff solvers are no way out (physics.md §4b): backward Euler, L-stable like Radau
/// and BDF, damps the fast oscillation at ωh ≫ 1, θ drains away and the reversals vanish,
/// while an exact-flow method at the same step keeps them.
#[test]
fn an_implicit_stiff_method_converges_to_the_wrong_motion() {
    let problem = common::problem(2.0, 1.0, 1.0, 1e8, [0.0, 0.0, 1.0, 0.5]);
    let predicted = rattleback::physics::rattleback::effective::Effective::new(&problem)
        .reversal_times(10.0)
        .len();
    assert!(predicted >= 2);
    let implicit = rattleback::bench::implicit::backward_euler(&problem, 1e-3, 10.0);
    assert!(
        implicit.fast_energy_ratio < 1e-3,
        "fast energy kept: {}",
        implicit.fast_energy_ratio
    );
    assert_eq!(implicit.reversals, 0);
    let spec = RunSpec {
        method: Method::Locked,
        tolerance: 1e-8,
        step: Some(1e-3),
        t_end: 10.0,
        samples: 0,
        monitor_energy: false,
    };
    assert_eq!(run(&problem, &spec).unwrap().reversals.len(), predicted);
}
