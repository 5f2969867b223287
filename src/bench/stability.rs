//! The stability report: long runs (energy error and drift of the fast action `I = E⊥/ω`),
//! a start near the separatrix, extreme inertia ratios. Every number is measured here.

use std::fmt::Write as _;
use std::time::Instant;

use serde::Serialize;

use super::{Config, case};
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::rattleback::auto::run_auto;
use crate::physics::rattleback::effective::Effective;
use crate::physics::rattleback::model::{initial_state, transverse_energy};
use crate::physics::rattleback::run::RunResult;
use crate::physics::rattleback::{Params, Problem, State, run};

/// One line of the report.
#[derive(Clone, Debug, Serialize)]
pub struct StabilityRow {
    /// What is tested.
    pub case: String,
    /// The method (what auto chose, for auto).
    pub method: String,
    /// Horizon.
    pub t_end: f64,
    /// Largest relative energy error over the run.
    pub max_energy_error: f64,
    /// `|I(T)/I(0) − 1|` of the fast action (0 by construction for the effective models).
    pub action_drift: f64,
    /// Reversals of the run, and what the effective model predicts.
    pub reversals: (usize, usize),
    /// Wall time.
    pub seconds: f64,
}

fn action(p: &Params, y: &State) -> f64 {
    transverse_energy(p, y) / p.omega(y[1])
}

fn row(
    case: &str,
    problem: &Problem,
    method: &str,
    t_end: f64,
    r: &RunResult,
    seconds: f64,
) -> StabilityRow {
    let p = problem.params();
    let i0 = action(p, &initial_state(problem.start()));
    let drift = if i0 > 0.0 {
        (action(p, &r.final_state) / i0 - 1.0).abs()
    } else {
        0.0
    };
    StabilityRow {
        case: case.to_owned(),
        method: method.to_owned(),
        t_end,
        max_energy_error: r.max_relative_energy_error,
        action_drift: drift,
        reversals: (
            r.reversal_count,
            Effective::new(problem).reversal_count(t_end),
        ),
        seconds,
    }
}

/// Runs the report.
#[must_use]
pub fn stability(config: Config) -> Vec<StabilityRow> {
    let mut rows = Vec::new();
    let long = if config.quick { 1e3 } else { 1e4 };
    let p = case(2.0, 1.0, 1e4, 0.5);
    let omega = p.params().omega_max();
    for (method, tol, step) in [
        (Method::Dop853, 1e-10, None),
        (Method::Strang, 0.0, Some(0.8 / omega)),
        (Method::BlanesMoan4, 0.0, Some(2.4 / omega)),
        (Method::Locked, 0.0, Some(1e-3)),
        (Method::EffectiveCorrected, 1e-12, None),
    ] {
        let spec = RunSpec {
            method,
            tolerance: tol,
            step,
            t_end: long,
            samples: 0,
            monitor_energy: true,
        };
        let clock = Instant::now();
        if let Ok(r) = run(&p, &spec) {
            rows.push(row(
                "long run, k = 1e4, trapped",
                &p,
                method.name(),
                long,
                &r,
                clock.elapsed().as_secs_f64(),
            ));
        }
    }
    // Near the separatrix and at extreme inertia ratios: what auto does.
    let probe = case(2.0, 1.0, 1e8, 0.0);
    let critical = Effective::new(&probe).critical_ratio(&probe).unwrap_or(1.0);
    let near = case(2.0, 1.0, 1e8, (critical * (1.0 - 1e-6)).sqrt());
    let mut cases = vec![("within 1e-6 below the critical ratio, k = 1e8", near, 60.0)];
    for iy in [1e-6, 1e6] {
        cases.push((
            "inertia ratio iy/ix = 1e-6 / 1e6, k = 1e4",
            case(1.0, iy, 1e4, 0.2),
            2.0,
        ));
    }
    // An implicit stiff method at large k: damps the fast energy, loses the reversals.
    let stiff = case(2.0, 1.0, 1e8, 0.5);
    let t_end = if config.quick { 10.0 } else { 20.0 };
    let clock = Instant::now();
    let outcome = super::implicit::backward_euler(&stiff, 1e-3, t_end);
    rows.push(StabilityRow {
        case: "implicit stiff method, k = 1e8, h = 1e-3 (ωh ≈ 10)".to_owned(),
        method: format!(
            "backward Euler (fast energy ×{:.1e})",
            outcome.fast_energy_ratio
        ),
        t_end,
        max_energy_error: (1.0 - outcome.fast_energy_ratio).abs(),
        action_drift: f64::NAN,
        reversals: (
            outcome.reversals,
            Effective::new(&stiff).reversal_count(t_end),
        ),
        seconds: clock.elapsed().as_secs_f64(),
    });
    for (case, p, t_end) in cases {
        let clock = Instant::now();
        if let Ok(v) = run_auto(&p, 1e-6, t_end, 0, true) {
            let name = format!("auto→{}", v.plan.method);
            rows.push(row(
                case,
                &p,
                &name,
                t_end,
                &v.result,
                clock.elapsed().as_secs_f64(),
            ));
        }
    }
    rows
}

/// Writes `stability.csv`.
///
/// # Errors
/// When the file cannot be written.
pub fn write_stability_csv(rows: &[StabilityRow], path: &std::path::Path) -> std::io::Result<()> {
    super::write_csv_lines(
        path,
        "case,method,t_end,max_energy_error,action_drift,reversals,expected_reversals,seconds",
        rows,
        |r| {
            let StabilityRow {
                case,
                method,
                t_end,
                max_energy_error: de,
                action_drift: di,
                reversals: (got, expected),
                seconds,
            } = r;
            format!("\"{case}\",{method},{t_end},{de:e},{di:e},{got},{expected},{seconds:e}")
        },
    )
}

/// The report for people.
#[must_use]
pub fn stability_table(rows: &[StabilityRow]) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{:<48} {:<26} {:>7} {:>11} {:>11} {:>11} {:>9}",
        "case", "method", "T", "max ΔE/E", "|ΔI/I|", "reversals", "seconds"
    );
    for r in rows {
        let (got, expected) = r.reversals;
        let _ = writeln!(
            o,
            "{:<48} {:<26} {:>7} {:>11.2e} {:>11.2e} {got:>5}/{expected:<5} {:>9.3}",
            r.case, r.method, r.t_end, r.max_energy_error, r.action_drift, r.seconds
        );
    }
    o
}
