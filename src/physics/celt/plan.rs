//! The celt's `auto`: DOP853 at a local tolerance `L`, verified against a coarser companion at
//! `16 L` (the rattleback's rule, `rattleback::auto`), refined until the estimate meets the
//! tolerance or it cannot.
//!
//! **What is estimated:** the error of the spin `ω·γ` on 33 evenly spaced times of `[0, T]` and
//! of the final `ω` (rad/s), the largest of them; infinite when the two runs count different
//! crossings or reversals. The difference bounds the returned run's error whenever the
//! companion's error is at least twice the run's, which holds where DOP853 converges (about 14×
//! for a 16× looser tolerance). A round-off floor `ε · steps · max|ω|` is added.
//!
//! **Refinement** is the one loop, `physics::verify`, as [`POLICY`] says: `L` shrinks by the
//! factor the estimate asks for (at least 4×). It stops, and says so with `met = false`, when
//! the estimate stops falling (less than halved by two refinements in a row: round-off, or a
//! chaotic run whose states differ between any two tolerances, model.md §9), at the 1e-14 clamp,
//! after four refinements, or before a refinement predicted to take the total past the caller's
//! budget.

use super::Problem;
use super::policy::{FIRST, POLICY};
use super::run::{RunResult, run};
use crate::physics::fork::GoOn;
use crate::physics::method::Asked;
use crate::physics::method::RunSpec;
use crate::physics::method::{Method, StepError};
use crate::physics::plan::{AutoRules, PlanRequest, Resolution, Resolved, Shortfall};
use crate::physics::verify::{AtTolerance, Policy, Rounds, verify};

/// Times of the spin compared.
const SAMPLES: usize = 33;

/// The difference of two runs (see the module's documentation).
#[must_use]
pub fn difference(a: &RunResult, b: &RunResult) -> f64 {
    if a.crossing_count != b.crossing_count || a.reversal_count != b.reversal_count {
        return f64::INFINITY;
    }
    let mut d: f64 = 0.0;
    for (x, y) in a.samples.iter().zip(&b.samples) {
        d = d.max((x.spin - y.spin).abs());
    }
    for i in 0..3 {
        d = d.max((a.state[i] - b.state[i]).abs());
    }
    d
}

fn floor(r: &RunResult) -> f64 {
    let w = super::omega(&r.state).amax().max(1.0);
    let steps = r.stats.steps as f64;
    f64::EPSILON * steps * w
}

/// Resolves `ask` for the celt.
///
/// # Errors
/// A failed or cancelled probe.
pub fn resolve(
    problem: &Problem,
    ask: &PlanRequest,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Resolution, StepError> {
    if ask.method != Method::Auto {
        return Ok(Resolution::named(ask.method, ask.tolerance));
    }
    let local = (ask.tolerance * FIRST).clamp(POLICY.tightest, 1e-3);
    if ask.policy == AutoRules::Legacy {
        // No session of format 1 holds a celt; plan as the first step does, unverified.
        return Ok(Resolution::named(Method::Dop853, local));
    }
    let mut candidate = Dop853 {
        problem: *problem,
        t_end: ask.t_end,
    };
    let v = verify(
        &mut candidate,
        Rounds {
            first: local,
            tolerance: ask.tolerance,
            budget: ask.budget,
        },
        go_on,
    )?;
    Ok(done(v.last.plan, Some(v.last.estimate), v.shortfall))
}

/// The celt's candidate: DOP853 at a local tolerance over `[0, t_end]`.
#[derive(Clone)]
struct Dop853 {
    problem: Problem,
    t_end: f64,
}

impl AtTolerance for Dop853 {
    type Result = RunResult;
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn run(&self, tolerance: f64, go_on: GoOn<'_>) -> Result<RunResult, StepError> {
        let spec = RunSpec::new(
            Asked::new(Method::Dop853, tolerance, None, self.t_end),
            SAMPLES,
        );
        run(&self.problem, &spec, go_on)
    }
    fn difference(&self, fine: &RunResult, coarse: &RunResult) -> f64 {
        difference(fine, coarse)
    }
    fn floor(&self, fine: &RunResult) -> f64 {
        floor(fine)
    }
    fn run_cost(&self, local: f64) -> f64 {
        super::budget::cost_seconds(
            &self.problem,
            &Asked::new(Method::Dop853, local, None, self.t_end),
        )
    }
}

fn done(local: f64, estimate: Option<f64>, shortfall: Option<Shortfall>) -> Resolution {
    Resolution {
        plan: Resolved {
            method: Method::Dop853,
            tolerance: local,
            step: None,
        },
        estimate: Some(estimate.unwrap_or(f64::INFINITY)),
        shortfall,
        floor: None,
    }
}
