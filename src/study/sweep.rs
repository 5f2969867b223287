//! The sweep of a model's small parameter: the rattleback's stiffness (`α_k(t)` at a ladder of
//! `k` beside the limit `α_eff(t)`, `sup_{[0,T]} |α_k − α_eff|` against `k`), or the pendulum's
//! `ε` (`θ_ε(t)` beside the limit `θ(t)` from the same start, `sup |θ_ε − θ|` against `ε`:
//! positions converge at first order), with the fitted log–log slope.
//!
//! Each rung runs `auto` (so the whole ladder costs little more than its hardest rung) with
//! samples on one grid; the limit is integrated at 1e-14 (1e-13 for the pendulum).

use crate::physics::method::Asked;
use rayon::prelude::*;
use serde::Serialize;

use crate::physics::scene::SmallParameter;
use crate::physics::{Method, Model, ModelKind, StepError};

/// The default ladder of `model`'s small parameter, as its scene gives it (the rattleback's one
/// stiffness per decade from 1e1 to 1e8, the pendulum's `ε` from 1e-1 to 1e-6; empty for a
/// model without a limit).
#[must_use]
pub fn ladder(model: ModelKind) -> &'static [f64] {
    model.small().map_or(&[], |s| s.ladder)
}

/// Samples of each curve over `[0, T]`.
pub const SAMPLES: usize = 601;

/// One rung of the ladder.
#[derive(Clone, Debug, Serialize)]
pub struct Rung {
    /// The small parameter's value: the Hooke constant `k`, or the pendulum's `ε`.
    pub parameter: f64,
    /// `sup |α_k − α_eff|` (`sup |θ_ε − θ|`) over the samples.
    pub sup_error: f64,
    /// The slow coordinate (`α_k`, `θ_ε`) at the sample times.
    pub alpha: Vec<f64>,
    /// What `auto` ran and its error estimate.
    pub method: Method,
    /// `auto`'s error estimate of this rung.
    pub estimate: f64,
}

/// A whole sweep.
#[derive(Clone, Debug, Serialize)]
pub struct Sweep {
    /// Which model's parameter was swept.
    pub model: ModelKind,
    /// The parameter.
    #[serde(skip)]
    pub small: SmallParameter,
    /// Sample times.
    pub t: Vec<f64>,
    /// The limit's slow coordinate at the sample times.
    pub limit: Vec<f64>,
    /// The rungs, in the ladder's order.
    pub rungs: Vec<Rung>,
    /// Fitted slope of `log sup_error` against the log of the parameter (O(1/k): −1;
    /// O(ε): 1).
    pub slope: Option<f64>,
}

impl Sweep {
    /// The small parameter swept.
    #[must_use]
    pub fn small(&self) -> SmallParameter {
        self.small
    }

    /// The stiffnesses, in order.
    #[must_use]
    pub fn stiffness(&self) -> Vec<f64> {
        self.rungs.iter().map(|r| r.parameter).collect()
    }

    /// The sup errors, in order.
    #[must_use]
    pub fn sup_error(&self) -> Vec<f64> {
        self.rungs.iter().map(|r| r.sup_error).collect()
    }
}

/// The limit's slow coordinate at [`SAMPLES`] times over `[0, t_end]`: `(t, q)`, integrated
/// at the model's limit tolerance.
///
/// # Errors
/// When the integration fails or `go_on` stops it.
pub fn limit_curve(
    model: &Model,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(Vec<f64>, Vec<f64>), StepError> {
    let tolerance = model.kind().limit_tolerance();
    let c = model.slow_curve(
        &Asked::new(Method::Effective, tolerance, None, t_end),
        SAMPLES,
        go_on,
    )?;
    Ok((c.t, c.q))
}

/// One rung: the model's start at `parameter`, run by `auto`, against the limit's curve.
///
/// # Errors
/// A rung out of range (as not finite), a failed integration, or `go_on` stopping it.
pub fn rung(
    model: &Model,
    parameter: f64,
    t_end: f64,
    tolerance: f64,
    limit: &[f64],
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Rung, StepError> {
    let at = at_rung(model, parameter).map_err(|e| StepError::NotFinite {
        what: e.field(),
        t: 0.0,
    })?;
    let c = at.slow_curve(
        &Asked::new(Method::Auto, tolerance, None, t_end),
        SAMPLES,
        go_on,
    )?;
    let sup_error =
        c.q.iter()
            .zip(limit)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
    Ok(Rung {
        parameter,
        sup_error,
        alpha: c.q,
        method: c.method,
        estimate: c.estimate,
    })
}

/// Most rungs a sweep takes.
pub const MAX_RUNGS: usize = 64;

/// The model of `model`'s start at one rung (`k`, or the pendulum's `ε`, replaced), validated
/// like a preset.
///
/// # Errors
/// The rung's value, or a quantity derived from it, is out of range.
pub fn at_rung(model: &Model, parameter: f64) -> Result<Model, crate::physics::ParamError> {
    let key = model.kind().small().map_or("", |s| s.key);
    model.with_value(key, parameter)
}

/// `model`'s small parameter, or why it has none to sweep.
///
/// # Errors
/// [`StepError::NoStudy`] for a model without a limit.
pub fn small_of(model: &Model) -> Result<SmallParameter, StepError> {
    model.kind().small().ok_or(StepError::NoStudy {
        what: "small parameter to sweep",
        model: model.kind().name(),
    })
}

/// Predicted seconds of the whole sweep (the limit's curve and every rung, as `auto` plans
/// them), checked before anything runs.
///
/// # Errors
/// Too many rungs, or a rung out of range (named).
pub fn predicted_seconds(
    model: &Model,
    ladder: &[f64],
    t_end: f64,
    tolerance: f64,
) -> Result<f64, String> {
    if ladder.len() > MAX_RUNGS {
        return Err(format!("{} rungs: at most {MAX_RUNGS}", ladder.len()));
    }
    let limit_tol = model.kind().limit_tolerance();
    let mut total = model.predicted_seconds(&Asked::new(Method::Effective, limit_tol, None, t_end));
    for &x in ladder {
        let m = at_rung(model, x).map_err(|e| format!("the rung {x:e}: {e}"))?;
        total += m.predicted_seconds(&Asked::new(Method::Auto, tolerance, None, t_end));
    }
    Ok(total)
}

/// Sweeps `problem`'s start over `ladder` (its own `k` is replaced) to `t_end` at `tolerance`,
/// the rungs in parallel; `go_on` is asked every few hundred steps of every run (from several
/// threads) whether to go on; `done` is told when the limit and each rung are finished (for
/// progress).
///
/// # Errors
/// The first integration that fails, or [`StepError::Cancelled`].
pub fn sweep(
    model: &Model,
    ladder: &[f64],
    t_end: f64,
    tolerance: f64,
    go_on: &(dyn Fn(f64) -> bool + Sync),
    done: &(dyn Fn() + Sync),
) -> Result<Sweep, StepError> {
    let small = small_of(model)?;
    let (t, limit) = limit_curve(model, t_end, &mut |t| go_on(t))?;
    done();
    let rungs = ladder
        .par_iter()
        .map(|&k| {
            let r = rung(model, k, t_end, tolerance, &limit, &mut |t| go_on(t));
            done();
            r
        })
        .collect::<Result<Vec<Rung>, StepError>>()?;
    let points: Vec<(f64, f64)> = rungs.iter().map(|r| (r.parameter, r.sup_error)).collect();
    Ok(Sweep {
        model: model.kind(),
        small,
        t,
        limit,
        slope: super::log_log_slope(&points),
        rungs,
    })
}
