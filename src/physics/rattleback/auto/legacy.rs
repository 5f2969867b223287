//! The first `auto` planner (issues 3 and 10), frozen: session files of format 1 recorded the
//! trajectory of its *first, unverified plan*, so their replay must plan exactly as it did
//! (`physics::plan::AutoRules::Legacy`). Nothing else uses it; the current planner is
//! [`super`]. Do not change a number here: old recordings would stop verifying
//! (`tests/fixtures/sessions/subcritical.jsonl` checks it).
//!
//! What it did: predict the error and cost of resolved DOP853 (local tolerance 100× tighter),
//! resolved blanes-moan4, phase-locked Strang and, past k = 1e7, the first-order corrected limit
//! (its O(1/k) error probed at k = 1e4 and 1e5), and take the cheapest predicted to meet the
//! tolerance.
use crate::physics::numerics::elementary::Elementary;

use super::Plan;
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::method::StepError;
use crate::physics::rattleback::budget::{
    NS_DOP853_EVAL, NS_EFFECTIVE_PER_TIME, NS_FAST_FLOW, dop853_evaluations, fastest_rate,
};
use crate::physics::rattleback::effective::Effective;
use crate::physics::rattleback::params::Problem;
use crate::physics::rattleback::run::run_cancellable;

/// Error of `blanes-moan4` per unit time at `ν h = 1`.
const C_BLANES_MOAN: f64 = 3e-12;
/// Error of `locked` per unit time at `h = 1` for spin rates up to 0.5 (docs/physics.md: ≈ 0.05 h²
/// over T = 20; measured 1.7e-3 per unit time, doubled for safety).
const C_LOCKED: f64 = 3.4e-3;
/// Growth of the locked error with the largest spin rate: `(α̇_max / 0.5)^4.7`, fitted to
/// rotating starts (4.4e-2 per unit time at `α̇ = 1`).
const LOCKED_SPIN_EXPONENT: f64 = 4.7;
/// Largest `ν h` used for `blanes-moan4` (its largest kick, 0.434 ν h, stays below π/2).
const BLANES_MOAN_MAX_NU_H: f64 = 2.4;
/// Hooke constants at which the corrected effective model's error is probed.
const K_PROBES: [f64; 2] = [1e4, 1e5];
/// Safety factor on the probed O(1/k) error coefficient.
const PROBE_SAFETY: f64 = 2.0;

/// The candidates that need no probe (resolved DOP853, resolved Blanes–Moan, and phase-locked
/// Strang when its steps are long enough), with their predicted errors and costs. Pure and
/// cheap: the work budget uses it before anything runs.
#[must_use]
fn resolved_candidates(problem: &Problem, tolerance: f64, t_end: f64) -> Vec<Plan> {
    let p = problem.params();
    let nu = fastest_rate(problem);
    let periods = nu * t_end / std::f64::consts::TAU;
    let mut candidates = Vec::new();

    // Adaptive candidates run at a local tolerance 100× tighter, and tighter again on long
    // horizons: their global error grows with the number of steps (cost only like tol^{-1/8}).
    let local = (tolerance / 100.0 * (20.0 / t_end).min(1.0)).max(1e-14);
    let evals = dop853_evaluations(local, periods);
    candidates.push(Plan {
        method: Method::Dop853,
        tolerance: local,
        step: None,
        predicted_error: tolerance,
        predicted_seconds: evals * NS_DOP853_EVAL * 1e-9,
        reason: "resolved adaptive integration".to_owned(),
    });

    // Resolved Blanes–Moan at ν h ≤ 2.4.
    let nu_h = (tolerance / (C_BLANES_MOAN * t_end))
        .e_powf(0.25)
        .min(BLANES_MOAN_MAX_NU_H);
    let steps = nu * t_end / nu_h;
    candidates.push(Plan {
        method: Method::BlanesMoan4,
        tolerance,
        step: Some(nu_h / nu),
        predicted_error: C_BLANES_MOAN * nu_h.powi(4) * t_end,
        predicted_seconds: 6.0 * steps * NS_FAST_FLOW * 1e-9,
        reason: format!("resolved exact-flow splitting at ν·h = {nu_h:.2}"),
    });

    // Phase-locked Strang, only once its steps are past the first quarter period.
    let eff = Effective::new(problem);
    let spin_max = (2.0 * (eff.energy() - eff.potential_min()) / p.iz)
        .max(0.0)
        .sqrt();
    let c_locked = C_LOCKED * (spin_max / 0.5).max(1.0).e_powf(LOCKED_SPIN_EXPONENT);
    let h = (tolerance / (c_locked * t_end)).sqrt();
    let omega_min = (p.k / p.ix.max(p.iy)).sqrt();
    if omega_min * h >= std::f64::consts::FRAC_PI_2 {
        candidates.push(Plan {
            method: Method::Locked,
            tolerance,
            step: Some(h),
            predicted_error: c_locked * h * h * t_end,
            predicted_seconds: t_end / h * NS_FAST_FLOW * 1e-9,
            reason: format!("phase-locked steps of {h:.2e}, cost independent of k"),
        });
    }

    candidates
}

/// The first plan, asking `go_on` between probe steps whether to continue.
///
/// # Errors
/// [`StepError::Cancelled`] when `go_on` says stop during a probe.
///
/// # Panics
/// Never: the resolved candidates are always present, so a minimum exists.
pub fn plan_cancellable(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Plan, StepError> {
    let p = problem.params();
    let local = (tolerance / 100.0 * (20.0 / t_end).min(1.0)).max(1e-14);
    let mut candidates = resolved_candidates(problem, tolerance, t_end);

    // The corrected effective model, when its probed O(1/k) error is small enough.
    if p.k > 100.0 * K_PROBES[1] {
        let mut coefficient: f64 = 0.0;
        for k in K_PROBES {
            coefficient = coefficient.max(probe_error(problem, k, t_end, go_on)? * k);
        }
        let predicted = coefficient / p.k * PROBE_SAFETY;
        let probe_cost: f64 = K_PROBES
            .iter()
            .map(|&k| probe_cost(problem, k, t_end))
            .sum();
        if predicted <= tolerance {
            candidates.push(Plan {
                method: Method::EffectiveCorrected,
                tolerance: local,
                step: None,
                predicted_error: predicted,
                predicted_seconds: NS_EFFECTIVE_PER_TIME * t_end * 1e-9 + probe_cost,
                reason: format!(
                    "k large enough: the corrected limit's error, probed at k = 1e4 and 1e5, scales to {predicted:.1e}"
                ),
            });
        }
    }

    let meets: Vec<Plan> = candidates
        .iter()
        .filter(|c| c.predicted_error <= tolerance)
        .cloned()
        .collect();
    let pool = if meets.is_empty() { candidates } else { meets };
    Ok(pool
        .into_iter()
        .min_by(|a, b| a.predicted_seconds.total_cmp(&b.predicted_seconds))
        .expect("at least one candidate"))
}

fn probe_cost(problem: &Problem, k: f64, t_end: f64) -> f64 {
    let nu = fastest_rate(&problem.with_k(k).expect("probe k is valid"));
    6.0 * nu * t_end / 1.2 * NS_FAST_FLOW * 1e-9
}

/// `max(|Δα(T)|, |Δα̇(T)|)` between the full model (blanes-moan4 at `ν h = 1.2`) and the
/// corrected effective model at stiffness `k`; infinite when either run fails, `Err` only
/// when `go_on` stopped it.
fn probe_error(
    problem: &Problem,
    k: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<f64, StepError> {
    let probe = problem.with_k(k).expect("probe k is valid");
    let nu = fastest_rate(&probe);
    let full = run_cancellable(
        &probe,
        &RunSpec {
            method: Method::BlanesMoan4,
            tolerance: 1e-10,
            step: Some(1.2 / nu),
            t_end,
            samples: 0,
            monitor_energy: false,
        },
        go_on,
    );
    let limit = run_cancellable(
        &probe,
        &RunSpec {
            method: Method::EffectiveCorrected,
            tolerance: 1e-12,
            step: None,
            t_end,
            samples: 0,
            monitor_energy: false,
        },
        go_on,
    );
    Ok(match (full, limit) {
        (Err(e @ StepError::Cancelled { .. }), _) | (_, Err(e @ StepError::Cancelled { .. })) => {
            return Err(e);
        }
        (Ok(a), Ok(b)) => (a.final_state[1] - b.final_state[1])
            .abs()
            .max((a.final_state[3] - b.final_state[3]).abs()),
        _ => f64::INFINITY,
    })
}
