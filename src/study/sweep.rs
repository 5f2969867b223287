//! The stiffness sweep: `α_k(t)` at a ladder of `k` beside the limit `α_eff(t)`, and
//! `sup_{[0,T]} |α_k − α_eff|` against `k` with its fitted log–log slope.
//!
//! Each rung runs `auto` (so the whole ladder costs little more than its stiffest rung's
//! averaged model) with samples on one grid; the limit is the effective model at 1e-14.

use crate::physics::model::ALPHA;
use rayon::prelude::*;
use serde::Serialize;

use crate::physics::auto::run_auto_cancellable;
use crate::physics::run::run_cancellable;
use crate::physics::{Method, Problem, RunSpec, StepError};

/// The default ladder: one stiffness per decade from 1e1 to 1e8.
pub const DEFAULT_LADDER: [f64; 8] = [1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8];

/// Samples of each curve over `[0, T]`.
pub const SAMPLES: usize = 601;

/// One rung of the ladder.
#[derive(Clone, Debug, Serialize)]
pub struct Rung {
    /// Hooke constant.
    pub k: f64,
    /// `sup |α_k − α_eff|` over the samples.
    pub sup_error: f64,
    /// `α_k` at the sample times.
    pub alpha: Vec<f64>,
    /// What `auto` ran and its error estimate.
    pub method: Method,
    /// `auto`'s error estimate of this rung.
    pub estimate: f64,
}

/// A whole sweep.
#[derive(Clone, Debug, Serialize)]
pub struct Sweep {
    /// Sample times.
    pub t: Vec<f64>,
    /// The limit's `α_eff` at the sample times.
    pub limit: Vec<f64>,
    /// The rungs, in the ladder's order.
    pub rungs: Vec<Rung>,
    /// Fitted slope of `log sup_error` against `log k` (O(1/k): −1).
    pub slope: Option<f64>,
}

impl Sweep {
    /// The stiffnesses, in order.
    #[must_use]
    pub fn stiffness(&self) -> Vec<f64> {
        self.rungs.iter().map(|r| r.k).collect()
    }

    /// The sup errors, in order.
    #[must_use]
    pub fn sup_error(&self) -> Vec<f64> {
        self.rungs.iter().map(|r| r.sup_error).collect()
    }
}

/// The limit's `α_eff` at [`SAMPLES`] times over `[0, t_end]`: `(t, α_eff)`.
///
/// # Errors
/// When the integration fails or `go_on` stops it.
pub fn limit_curve(
    problem: &Problem,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(Vec<f64>, Vec<f64>), StepError> {
    let r = run_cancellable(
        problem,
        &RunSpec {
            method: Method::Effective,
            tolerance: 1e-14,
            step: None,
            t_end,
            samples: SAMPLES,
            monitor_energy: false,
        },
        go_on,
    )?;
    Ok(r.samples.iter().map(|s| (s.t, s.state[ALPHA])).unzip())
}

/// One rung: `problem`'s start at stiffness `k` through `auto`, against the limit's curve.
///
/// # Errors
/// When `k` is not a valid Hooke constant, the integration fails, or `go_on` stops it.
pub fn rung(
    problem: &Problem,
    k: f64,
    t_end: f64,
    tolerance: f64,
    limit: &[f64],
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Rung, StepError> {
    let p = problem
        .with_k(k)
        .map_err(|_| StepError::NotFinite { what: "k", t: 0.0 })?;
    let v = run_auto_cancellable(
        &p,
        &RunSpec {
            method: Method::Auto,
            tolerance,
            step: None,
            t_end,
            samples: SAMPLES,
            monitor_energy: false,
        },
        crate::physics::budget::BUDGET_SECONDS,
        go_on,
    )?;
    let alpha: Vec<f64> = v.result.samples.iter().map(|s| s.state[ALPHA]).collect();
    let sup_error = alpha
        .iter()
        .zip(limit)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    Ok(Rung {
        k,
        sup_error,
        alpha,
        method: v.plan.method,
        estimate: v.error_estimate,
    })
}

/// Sweeps `problem`'s start over `ladder` (its own `k` is replaced) to `t_end` at `tolerance`,
/// the rungs in parallel; `go_on` is asked every few hundred steps of every run (from several
/// threads) whether to go on.
///
/// # Errors
/// The first integration that fails, or [`StepError::Cancelled`].
pub fn sweep(
    problem: &Problem,
    ladder: &[f64],
    t_end: f64,
    tolerance: f64,
    go_on: &(dyn Fn(f64) -> bool + Sync),
) -> Result<Sweep, StepError> {
    let (t, limit) = limit_curve(problem, t_end, &mut |t| go_on(t))?;
    let rungs = ladder
        .par_iter()
        .map(|&k| rung(problem, k, t_end, tolerance, &limit, &mut |t| go_on(t)))
        .collect::<Result<Vec<Rung>, StepError>>()?;
    let points: Vec<(f64, f64)> = rungs.iter().map(|r| (r.k, r.sup_error)).collect();
    Ok(Sweep {
        t,
        limit,
        slope: super::log_log_slope(&points),
        rungs,
    })
}
