//! `auto`: the cheapest method that meets a tolerance on the slow observables (`α`, `α̇`,
//! reversal times), chosen from a cost and error model of each candidate.
//!
//! Candidates and their error models (calibrated on this machine, docs/benchmarks.md), for a
//! horizon `T` and `ν` the fastest rate of the problem:
//! - `dop853`, resolved, run at a local tolerance 100× tighter than asked, and tighter still
//!   beyond `T = 20` (its tolerance is local; the margin covers the growth of the global error
//!   over many periods; the same local tolerance serves the corrected effective model);
//! - `blanes-moan4`, resolved with `ν h ≤ 2.4`: error ≈ `C_BM (ν h)^4 T`;
//! - `locked` once `ω_min h ≥ π/2`: error ≈ `C_LOCKED h² T`, whatever `k`;
//! - `effective-corrected` when `k` is large: its O(1/k) error is measured, not assumed, by
//!   probes — the full model against the corrected model at `k = 1e4` and `1e5` — as the larger
//!   coefficient `k · gap`, divided by `k`, with a safety factor of 2. (The coefficient
//!   oscillates with the fast phase at `T`, by about 3× between troughs and crests; two
//!   stiffnesses sample two phases.)
//!
//! Cost is predicted in nanoseconds from per-evaluation costs measured here. Pure: no clock.
//!
//! The models are only a guide to the choice. [`run_auto`] then checks the result a posteriori
//! against a finer companion run (half the step, or a 16× tighter tolerance): with `Δ` their
//! difference in `α(T)`, `α̇(T)` and the reversal times, `Δ · 2^p / (2^p − 1)` estimates the
//! coarser run's error, and the finer run — more accurate still — is the one returned. It
//! refines until that estimate meets the tolerance. (A coarser companion is cheaper but leaves
//! the asymptotic regime at large `ω h`, where it over-estimates wildly.)

use std::fmt::Write as _;

use serde::Serialize;

pub use super::budget::fastest_rate;
use super::budget::{
    NS_DOP853_EVAL, NS_EFFECTIVE_PER_TIME, NS_FAST_FLOW, cost_seconds, dop853_evaluations,
};
use super::effective::Effective;
use super::integrators::StepError;
use super::integrators::{Method, Settings};
use super::params::Problem;
use super::run::{RunResult, RunSpec, run_cancellable};

/// Error of `blanes-moan4` per unit time at `ν h = 1`.
pub const C_BLANES_MOAN: f64 = 3e-12;
/// Error of `locked` per unit time at `h = 1` for spin rates up to 0.5 (physics.md: ≈ 0.05 h²
/// over T = 20; measured 1.7e-3 per unit time, doubled for safety).
pub const C_LOCKED: f64 = 3.4e-3;
/// Growth of the locked error with the largest spin rate: `(α̇_max / 0.5)^4.7`, fitted to
/// rotating starts (4.4e-2 per unit time at `α̇ = 1`).
pub const LOCKED_SPIN_EXPONENT: f64 = 4.7;
/// Largest `ν h` used for `blanes-moan4` (its largest kick, 0.434 ν h, stays below π/2).
pub const BLANES_MOAN_MAX_NU_H: f64 = 2.4;
/// Hooke constants at which the corrected effective model's error is probed.
pub const K_PROBES: [f64; 2] = [1e4, 1e5];
/// Safety factor on the probed O(1/k) error coefficient.
pub const PROBE_SAFETY: f64 = 2.0;

/// What `auto` decided, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Plan {
    /// The method chosen.
    pub method: Method,
    /// Tolerance handed to it (adaptive methods).
    pub tolerance: f64,
    /// Step handed to it (fixed-step methods).
    pub step: Option<f64>,
    /// The error the model predicts for `α(T)`, `α̇(T)`.
    pub predicted_error: f64,
    /// Predicted run time in seconds on the calibration machine.
    pub predicted_seconds: f64,
    /// One sentence on the choice.
    pub reason: String,
}

impl Plan {
    /// The integrator settings of the plan.
    #[must_use]
    pub fn settings(&self) -> Settings {
        Settings {
            tolerance: self.tolerance,
            step: self.step,
        }
    }
}

/// Chooses the method for `problem` over `[0, t_end]` at `tolerance`.
#[must_use]
pub fn plan(problem: &Problem, tolerance: f64, t_end: f64) -> Plan {
    match plan_cancellable(problem, tolerance, t_end, &mut |_| true) {
        Ok(p) => p,
        Err(_) => unreachable_plan(problem, tolerance, t_end),
    }
}

/// Only reached if a never-cancelling probe were cancelled: plain DOP853.
fn unreachable_plan(problem: &Problem, tolerance: f64, t_end: f64) -> Plan {
    let _ = (problem, t_end);
    Plan {
        method: Method::Dop853,
        tolerance: (tolerance / 100.0).max(1e-14),
        step: None,
        predicted_error: tolerance,
        predicted_seconds: 0.0,
        reason: "resolved adaptive integration".to_owned(),
    }
}

/// The candidates that need no probe (resolved DOP853, resolved Blanes–Moan, and phase-locked
/// Strang when its steps are long enough), with their predicted errors and costs. Pure and
/// cheap: the work budget uses it before anything runs.
#[must_use]
pub fn resolved_candidates(problem: &Problem, tolerance: f64, t_end: f64) -> Vec<Plan> {
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
        .powf(0.25)
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
    let c_locked = C_LOCKED * (spin_max / 0.5).max(1.0).powf(LOCKED_SPIN_EXPONENT);
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

/// [`plan`], asking `go_on` between probe steps whether to continue.
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

/// Predicted seconds of `auto`'s probes of the corrected limit (zero when `k` is too small for
/// them to run).
#[must_use]
pub fn probes_cost(problem: &Problem, t_end: f64) -> f64 {
    if problem.params().k > 100.0 * K_PROBES[1] {
        K_PROBES
            .iter()
            .map(|&k| probe_cost(problem, k, t_end))
            .sum()
    } else {
        0.0
    }
}

fn probe_cost(problem: &Problem, k: f64, t_end: f64) -> f64 {
    let nu = fastest_rate(&problem.with_k(k).expect("probe k is valid"));
    6.0 * nu * t_end / 1.2 * NS_FAST_FLOW * 1e-9
}

/// `max(|Δα(T)|, |Δα̇(T)|)` between the full model and the corrected effective model at
/// stiffness `k`; the full model by `blanes-moan4` at `ν h = 1.2` (error ≈ 1e-10 there).
/// Infinite when either run fails.
///
/// # Panics
/// When `k` is not a valid Hooke constant (callers pass the fixed probes).
#[must_use]
pub fn probe_effective_error(problem: &Problem, k: f64, t_end: f64) -> f64 {
    probe_error(problem, k, t_end, &mut |_| true).unwrap_or(f64::INFINITY)
}

/// [`probe_effective_error`], cancellable: `Err` only when `go_on` stopped it.
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

/// A run chosen by `auto`, with its error estimate.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verified {
    /// The plan finally run (after refinements).
    pub plan: Plan,
    /// Its result.
    pub result: RunResult,
    /// Estimated error of `α(T)`, `α̇(T)` and the reversal times (the largest).
    pub error_estimate: f64,
    /// How many times the first plan had to be refined.
    pub refinements: u32,
    /// The settings of the returned (finer) run: integrating `plan.method` with these gives
    /// `result` bit for bit, which is how the explorer shows exactly what `simulate` reports.
    pub run_settings: Settings,
}

/// Most refinements before `auto` reports what it has.
pub const MAX_REFINEMENTS: u32 = 4;

/// Plans, runs and verifies: see the module documentation. The returned result is the finer
/// of the two runs; `error_estimate` bounds the coarser one's error.
///
/// # Errors
/// When an integration fails.
pub fn run_auto(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    samples: usize,
    monitor_energy: bool,
) -> Result<Verified, StepError> {
    run_auto_cancellable(
        problem,
        &RunSpec {
            method: Method::Auto,
            tolerance,
            step: None,
            t_end,
            samples,
            monitor_energy,
        },
        f64::INFINITY,
        &mut |_| true,
    )
}

/// [`run_auto`] for `spec` (its `method` and `step` are ignored), within a work `budget` in
/// predicted seconds (see [`super::budget`]), asking `go_on` every few hundred steps whether
/// to continue.
///
/// # Errors
/// When an integration fails, [`StepError::OverBudget`] before a probe, verification or
/// refinement that would take the predicted total over `budget`, or [`StepError::Cancelled`]
/// when `go_on` says stop.
pub fn run_auto_cancellable(
    problem: &Problem,
    spec: &RunSpec,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Verified, StepError> {
    let (tolerance, t_end, samples, monitor_energy) = (
        spec.tolerance,
        spec.t_end,
        spec.samples,
        spec.monitor_energy,
    );
    let mut spent = probes_cost(problem, t_end);
    over_budget("auto's probing of the corrected limit", spent, budget)?;
    let mut plan = plan_cancellable(problem, tolerance, t_end, go_on)?;
    let mut refinements = 0;
    loop {
        let finer = finer_companion(&plan).0;
        spent += cost_seconds(problem, plan.method, plan.tolerance, plan.step, t_end)
            + cost_seconds(problem, plan.method, finer.tolerance, finer.step, t_end);
        over_budget(
            &if refinements == 0 {
                format!("auto's run and verification with {}", plan.method)
            } else {
                format!("auto's refinement {refinements} ({})", plan.reason)
            },
            spent,
            budget,
        )?;
        let spec = RunSpec {
            method: plan.method,
            tolerance: plan.tolerance,
            step: plan.step,
            t_end,
            samples,
            monitor_energy,
        };
        let (result, estimate) = if plan.method == Method::EffectiveCorrected {
            // Model error (probed) plus integration error (from a finer companion).
            let coarse = run_cancellable(problem, &spec, go_on)?;
            let (finer, divisor) = finer_companion(&plan);
            let fine = run_cancellable(
                problem,
                &RunSpec {
                    tolerance: finer.tolerance,
                    ..spec
                },
                go_on,
            )?;
            let estimate = plan.predicted_error + difference(&coarse, &fine) / divisor;
            (fine, estimate)
        } else {
            let coarse = run_cancellable(
                problem,
                &RunSpec {
                    samples: 0,
                    monitor_energy: false,
                    ..spec
                },
                go_on,
            )?;
            let (finer, divisor) = finer_companion(&plan);
            let fine = run_cancellable(
                problem,
                &RunSpec {
                    tolerance: finer.tolerance,
                    step: finer.step,
                    ..spec
                },
                go_on,
            )?;
            let estimate = difference(&coarse, &fine) / divisor;
            (fine, estimate)
        };
        if estimate <= tolerance || refinements == MAX_REFINEMENTS {
            let run_settings = finer_companion(&plan).0;
            return Ok(Verified {
                plan,
                result,
                error_estimate: estimate,
                refinements,
                run_settings,
            });
        }
        plan = refine(problem, plan, estimate / tolerance, t_end);
        refinements += 1;
    }
}

fn over_budget(what: &str, predicted: f64, budget: f64) -> Result<(), StepError> {
    super::budget::check(predicted, budget).map_err(|over| StepError::OverBudget {
        what: what.to_owned(),
        over,
    })
}

/// The largest difference in `α(T)`, `α̇(T)` and reversal times (infinite when the reversal
/// counts differ).
#[must_use]
pub fn difference(a: &RunResult, b: &RunResult) -> f64 {
    let mut d = (a.final_state[1] - b.final_state[1])
        .abs()
        .max((a.final_state[3] - b.final_state[3]).abs());
    if a.reversal_count != b.reversal_count {
        return f64::INFINITY;
    }
    for (x, y) in a.reversals.iter().zip(&b.reversals) {
        d = d.max((x - y).abs());
    }
    d
}

/// The finer companion of a plan, and the divisor `1 − 2^{−p}` (or `1 − 1/16` for DOP853)
/// that turns the difference into the coarser run's error.
fn finer_companion(plan: &Plan) -> (Settings, f64) {
    match plan.method {
        Method::Dop853 | Method::EffectiveCorrected => (
            Settings {
                tolerance: (plan.tolerance / 16.0).max(1e-14),
                step: None,
            },
            15.0 / 16.0,
        ),
        method => {
            let p = i32::try_from(method.order()).unwrap_or(2);
            (
                Settings {
                    tolerance: plan.tolerance,
                    step: plan.step.map(|h| 0.5 * h),
                },
                1.0 - 2f64.powi(-p),
            )
        }
    }
}

fn refine(problem: &Problem, mut plan: Plan, excess: f64, t_end: f64) -> Plan {
    let excess = if excess.is_finite() { excess } else { 16.0 };
    if plan.method == Method::Locked {
        // Locked steps missed: their error constant varies with the start (near the separatrix
        // it is large) and halving them gets expensive fast. Resolve the fast motion instead,
        // with blanes-moan4, whose error model holds.
        let nu = fastest_rate(problem);
        let nu_h = (plan.predicted_error / excess / (C_BLANES_MOAN * t_end))
            .powf(0.25)
            .min(BLANES_MOAN_MAX_NU_H);
        return Plan {
            method: Method::BlanesMoan4,
            tolerance: plan.tolerance,
            step: Some(nu_h / nu),
            predicted_error: C_BLANES_MOAN * nu_h.powi(4) * t_end,
            predicted_seconds: 6.0 * nu * t_end / nu_h * NS_FAST_FLOW * 1e-9,
            reason: format!(
                "{}; locked missed ×{excess:.1}, resolved instead",
                plan.reason
            ),
        };
    }
    match plan.method {
        Method::Dop853 | Method::EffectiveCorrected => {
            plan.tolerance = (plan.tolerance / (2.0 * excess)).max(1e-14);
        }
        method => {
            let p = f64::from(method.order().max(1));
            plan.step = plan.step.map(|h| h / (1.25 * excess.powf(1.0 / p)));
        }
    }
    let _ = write!(plan.reason, "; refined ×{excess:.1}");
    plan
}
