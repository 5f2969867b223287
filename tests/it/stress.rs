//! Stress tests, bounded in time: extreme stiffness, long horizons, starts at the critical
//! ratio, extreme inertia ratios, degenerate and tilted starts. No NaN, no panic, bounded
//! energy error, and reversal counts that agree with the effective model where theory says
//! they must.

use crate::common;

use rattleback::physics::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::auto::run_auto;
use rattleback::physics::rattleback::effective::{Effective, Regime};
use rattleback::physics::rattleback::{Problem, RunResult, run};

#[track_caller]
fn sane(label: &str, r: &RunResult, energy_bound: f64) {
    assert!(
        r.final_state.iter().all(|v| v.is_finite()),
        "{label}: non-finite state"
    );
    assert!(
        r.reversals.iter().all(|t| t.is_finite()),
        "{label}: non-finite reversal"
    );
    assert!(
        r.max_relative_energy_error < energy_bound,
        "{label}: energy error {:e}",
        r.max_relative_energy_error
    );
}

fn auto(problem: &Problem, tolerance: f64, t_end: f64) -> RunResult {
    run_auto(problem, tolerance, t_end, 0, true)
        .expect("auto runs")
        .result
}

#[test]
fn every_stiffness_from_1e_minus_2_to_1e12() {
    for exp in -2..=12 {
        let k = 10f64.powi(exp);
        for alpha_dot in [0.0, 0.5, 1.0] {
            let problem = common::problem(2.0, 1.0, 1.0, k, [0.0, 0.0, 1.0, alpha_dot]);
            let r = auto(&problem, 1e-6, 10.0);
            sane(&format!("k=1e{exp} alpha_dot={alpha_dot}"), &r, 1e-3);
        }
    }
}

#[test]
fn long_horizon_trapped_reversal_counts_match_the_limit() {
    // T = 2000 is about 450 reversals; counts must agree with the quadrature exactly.
    for k in [1e4, 1e6, 1e10] {
        let problem = common::problem(2.0, 1.0, 1.0, k, [0.0, 0.0, 1.0, 0.5]);
        let t_end = 2000.0;
        let predicted = Effective::new(&problem).reversal_times(t_end).len();
        let r = auto(&problem, 1e-6, t_end);
        sane(&format!("k={k:e}"), &r, 1e-3);
        assert_eq!(r.reversals.len(), predicted, "k={k:e}");
    }
}

#[test]
fn horizon_of_ten_thousand() {
    let problem = common::problem(2.0, 1.0, 1.0, 1e4, [0.0, 0.0, 1.0, 0.5]);
    let spec = RunSpec {
        method: Method::BlanesMoan4,
        tolerance: 1e-6,
        step: Some(0.02),
        t_end: 1e4,
        samples: 0,
        monitor_energy: true,
    };
    let r = run(&problem, &spec).unwrap();
    sane("T=1e4 blanes-moan4", &r, 1e-4);
    let stiff = common::problem(2.0, 1.0, 1.0, 1e10, [0.0, 0.0, 1.0, 0.5]);
    let r = auto(&stiff, 1e-6, 1e4);
    sane("T=1e4 k=1e10 auto", &r, 1e-6);
    assert_eq!(
        r.reversals.len(),
        Effective::new(&stiff).reversal_times(1e4).len()
    );
}

#[test]
fn starts_within_1e_minus_6_of_the_critical_ratio() {
    let probe = common::problem(2.0, 1.0, 1.0, 1e8, [0.0, 0.0, 1.0, 0.0]);
    let critical = Effective::new(&probe).critical_ratio(&probe).unwrap();
    for (factor, regime) in [
        (1.0 - 1e-6, Regime::Trapped),
        (1.0 + 1e-6, Regime::Rotating),
    ] {
        let problem = common::problem(
            2.0,
            1.0,
            1.0,
            1e8,
            [0.0, 0.0, 1.0, (critical * factor).sqrt()],
        );
        let eff = Effective::new(&problem);
        assert_eq!(eff.regime(), regime, "factor {factor}");
        // Near the separatrix the half period grows like a logarithm: finite, long.
        if regime == Regime::Trapped {
            let half = eff.half_period().unwrap();
            assert!(half.is_finite() && half > 10.0, "half period {half}");
        }
        let r = auto(&problem, 1e-6, 20.0);
        sane(&format!("critical x {factor}"), &r, 1e-6);
    }
}

#[test]
fn inertia_ratios_from_1e_minus_6_to_1e6() {
    for exp in [-6, -3, 0, 3, 6] {
        let iy = 10f64.powi(exp);
        let problem = common::problem(1.0, iy, 1.0, 1e4, [0.0, 0.3, 1.0, 0.2]);
        let r = auto(&problem, 1e-6, 2.0);
        sane(&format!("iy/ix = 1e{exp}"), &r, 1e-3);
    }
}

#[test]
fn degenerate_and_tilted_starts() {
    for start in [
        [0.0, 0.4, 1.0, 0.0],   // alpha_dot = 0: the tapping start
        [0.0, 0.4, 0.0, 0.7],   // gamma_dot = 0, gamma = 0: uniform spin
        [0.0, 0.4, 0.0, 0.0],   // at rest
        [0.002, 0.4, 0.0, 0.3], // gamma != 0, gamma_dot = 0
        [0.002, 1.1, -0.5, -0.3],
    ] {
        for k in [1e2, 1e6, 1e11] {
            let problem = common::problem(2.0, 1.0, 1.5, k, start);
            let r = auto(&problem, 1e-6, 10.0);
            sane(&format!("start {start:?} k={k:e}"), &r, 1e-3);
        }
    }
}

#[test]
fn bad_steps_do_not_panic_at_any_method() {
    let problem = common::problem(2.0, 1.0, 1.0, 1e12, [0.0, 0.0, 1.0, 0.5]);
    for method in rattleback_methods() {
        let spec = RunSpec {
            method,
            tolerance: 1e-3,
            step: Some(0.5),
            t_end: 1.0,
            samples: 3,
            monitor_energy: true,
        };
        // Any outcome but a panic: a result or a typed error.
        if let Ok(r) = run(&problem, &spec) {
            assert_eq!(r.samples.len(), 3);
        }
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
