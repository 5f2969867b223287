//! The sweep of a model's small parameter: the rattleback's stiffness (`α_k(t)` at a ladder of
//! `k` beside the limit `α_eff(t)`, `sup_{[0,T]} |α_k − α_eff|` against `k`), or the pendulum's
//! `ε` (`θ_ε(t)` beside the limit `θ(t)` from the same start, `sup |θ_ε − θ|` against `ε`:
//! positions converge at first order), with the fitted log–log slope.
//!
//! Each rung runs `auto` (so the whole ladder costs little more than its hardest rung) with
//! samples on one grid; the limit is integrated at 1e-14 (1e-13 for the pendulum).

use crate::physics::rattleback::model::ALPHA;
use rayon::prelude::*;
use serde::Serialize;

use crate::physics::rattleback::RunSpec;
use crate::physics::rattleback::auto::run_auto_cancellable;
use crate::physics::rattleback::run::run_cancellable;
use crate::physics::{Method, Model, ModelKind, StepError};

/// The default ladder: one stiffness per decade from 1e1 to 1e8.
pub const DEFAULT_LADDER: [f64; 8] = [1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8];

/// The pendulum's default ladder of `ε`, one per decade.
pub const EPSILON_LADDER: [f64; 6] = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6];

/// The default ladder of `model`'s small parameter.
#[must_use]
pub fn ladder(model: ModelKind) -> &'static [f64] {
    match model {
        ModelKind::Rattleback => &DEFAULT_LADDER,
        ModelKind::Kapitza => &EPSILON_LADDER,
    }
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

/// The limit's `α_eff` at [`SAMPLES`] times over `[0, t_end]`: `(t, α_eff)`.
///
/// # Errors
/// When the integration fails or `go_on` stops it.
pub fn limit_curve(
    model: &Model,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(Vec<f64>, Vec<f64>), StepError> {
    let problem = match model {
        Model::Rattleback(p) => p,
        Model::Kapitza(p) => {
            use crate::physics::kapitza::run::{RunSpec, run};
            let spec = RunSpec {
                method: Method::Effective,
                tolerance: 1e-13,
                step: None,
                t_end,
                samples: SAMPLES,
            };
            let r = run(p, &spec, go_on)?;
            return Ok(r.samples.iter().map(|s| (s.t, s.theta)).unzip());
        }
    };
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

pub fn rung(
    model: &Model,
    parameter: f64,
    t_end: f64,
    tolerance: f64,
    limit: &[f64],
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Rung, StepError> {
    let sup = |q: &[f64]| {
        q.iter()
            .zip(limit)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    let problem = match model {
        Model::Rattleback(p) => p,
        Model::Kapitza(p) => {
            use crate::physics::kapitza::run::{RunSpec, run};
            use crate::physics::kapitza::{Params, Problem, plan};
            let pendulum = Problem::new(
                Params {
                    epsilon: parameter,
                    ..*p.params()
                },
                *p.start(),
            )
            .map_err(|_| StepError::NotFinite {
                what: "epsilon",
                t: 0.0,
            })?;
            let c = plan::resolve(&pendulum, tolerance, t_end);
            let spec = RunSpec {
                method: c.method,
                tolerance: c.settings.tolerance,
                step: None,
                t_end,
                samples: SAMPLES,
            };
            let r = run(&pendulum, &spec, go_on)?;
            let theta: Vec<f64> = r.samples.iter().map(|s| s.theta).collect();
            return Ok(Rung {
                parameter,
                sup_error: sup(&theta),
                alpha: theta,
                method: c.method,
                estimate: c.estimate,
            });
        }
    };
    let k = parameter;
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
    let sup_error = sup(&alpha);
    Ok(Rung {
        parameter: k,
        sup_error,
        alpha,
        method: v.plan.method,
        estimate: v.error_estimate,
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
    Ok(match model {
        Model::Rattleback(p) => Model::Rattleback(p.with_k(parameter)?),
        Model::Kapitza(p) => Model::Kapitza(crate::physics::kapitza::Problem::new(
            crate::physics::kapitza::Params {
                epsilon: parameter,
                ..*p.params()
            },
            *p.start(),
        )?),
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
    let mut total = model.predicted_seconds(Method::Effective, limit_tol, None, t_end);
    for &x in ladder {
        let m = at_rung(model, x).map_err(|e| format!("the rung {x:e}: {e}"))?;
        total += m.predicted_seconds(Method::Auto, tolerance, None, t_end);
    }
    Ok(total)
}

/// Sweeps `problem`'s start over `ladder` (its own `k` is replaced) to `t_end` at `tolerance`,
/// the rungs in parallel; `go_on` is asked every few hundred steps of every run (from several
/// threads) whether to go on.
///
/// # Errors
/// The first integration that fails, or [`StepError::Cancelled`].
pub fn sweep(
    model: &Model,
    ladder: &[f64],
    t_end: f64,
    tolerance: f64,
    go_on: &(dyn Fn(f64) -> bool + Sync),
) -> Result<Sweep, StepError> {
    let (t, limit) = limit_curve(model, t_end, &mut |t| go_on(t))?;
    let rungs = ladder
        .par_iter()
        .map(|&k| rung(model, k, t_end, tolerance, &limit, &mut |t| go_on(t)))
        .collect::<Result<Vec<Rung>, StepError>>()?;
    let points: Vec<(f64, f64)> = rungs.iter().map(|r| (r.parameter, r.sup_error)).collect();
    Ok(Sweep {
        model: model.kind(),
        t,
        limit,
        slope: super::log_log_slope(&points),
        rungs,
    })
}
