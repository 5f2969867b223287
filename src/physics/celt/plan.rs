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
//! **Refinement:** `L` shrinks by the factor the estimate asks for (at least 4×). It stops, and
//! says so with `met = false`, when the estimate stops falling (less than halved by two
//! refinements in a row, [`STALLS`]: round-off, or a chaotic run whose states differ between any
//! two tolerances, model.md §9), at the
//! 1e-14 clamp, after [`MAX_REFINEMENTS`], or before a refinement predicted to take the total
//! past the caller's budget.

use super::Problem;
use super::run::{RunResult, RunSpec, run};
use crate::physics::method::Asked;
use crate::physics::method::{Method, StepError};
use crate::physics::plan::{AutoPolicy, PlanRequest, Resolution, Resolved, Shortfall};

/// How much looser the companion is.
pub const COMPANION_LOOSER: f64 = 16.0;
/// The first local tolerance, over the tolerance asked.
pub const FIRST: f64 = 0.1;
/// How much a refinement tightens at least; also the companion's factor in the cost model's
/// view of `auto` (one run at `tol`, one at `tol · REFINE`).
pub const REFINE: f64 = 0.25;
/// Tightest local tolerance.
pub const TIGHTEST: f64 = 1e-14;
/// Most refinements.
pub const MAX_REFINEMENTS: usize = 4;
/// How many refinements in a row must fail to halve the estimate for `auto` to stop there
/// (`Shortfall::Floor`). One was read as a floor on `celt-pitching` at tolerance 1e-4: its
/// estimate went 1.6e-2, 1.9e-4, 1.1e-4 at local tolerances 1e-5, 3.2e-8, 8.0e-9, far above its
/// round-off, while 5e-5 and every tighter tolerance were met (at 3.8e-9 the estimate is
/// 8.7e-6: DOP853's error falls unevenly before it settles). A chaotic run, whose states differ
/// between any two tolerances, still stops, one refinement later (stop 52).
pub const STALLS: usize = 2;
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
    #[allow(clippy::cast_precision_loss)]
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
        return Ok(Resolution {
            plan: Resolved {
                method: ask.method,
                tolerance: ask.tolerance,
                step: None,
            },
            estimate: None,
            shortfall: None,
            floor: None,
        });
    }
    let spec = |tolerance: f64| RunSpec {
        method: Method::Dop853,
        tolerance,
        t_end: ask.t_end,
        samples: SAMPLES,
    };
    let cost = |l: f64| {
        super::budget::cost_seconds(problem, &Asked::new(Method::Dop853, l, None, ask.t_end))
    };
    let mut local = (ask.tolerance * FIRST).clamp(TIGHTEST, 1e-3);
    if ask.policy == AutoPolicy::Legacy {
        // No session of format 1 holds a celt; plan as the first step does, unverified.
        return Ok(Resolution {
            plan: Resolved {
                method: Method::Dop853,
                tolerance: local,
                step: None,
            },
            estimate: None,
            shortfall: None,
            floor: None,
        });
    }
    let mut spent = 0.0;
    // The last verified local tolerance and its estimate.
    let mut last: Option<(f64, f64)> = None;
    let mut refinements = 0;
    // Refinements in a row that did not halve the estimate.
    let mut stalls = 0;
    loop {
        let companion = (local * COMPANION_LOOSER).min(1e-2);
        let predicted = cost(local) + cost(companion);
        if let Some((l, e)) = last
            && spent + predicted > ask.budget
        {
            return Ok(done(l, Some(e), Some(Shortfall::Time)));
        }
        spent += predicted;
        let fine = run(problem, &spec(local), go_on)?;
        let coarse = run(problem, &spec(companion), go_on)?;
        let estimate = difference(&fine, &coarse) + floor(&fine);
        if estimate <= ask.tolerance {
            return Ok(done(local, Some(estimate), None));
        }
        stalls = if last.is_some_and(|(_, prev)| estimate > 0.5 * prev) {
            stalls + 1
        } else {
            0
        };
        let stalled = stalls >= STALLS;
        let clamp = local <= TIGHTEST;
        let exhausted = refinements >= MAX_REFINEMENTS;
        if stalled || clamp || exhausted {
            let why = if stalled {
                Shortfall::Floor
            } else if clamp {
                Shortfall::Clamped
            } else {
                Shortfall::Refinements
            };
            return Ok(done(local, Some(estimate), Some(why)));
        }
        let factor = if estimate.is_finite() {
            (0.5 * ask.tolerance / estimate).min(REFINE)
        } else {
            REFINE * REFINE
        };
        last = Some((local, estimate));
        local = (local * factor).max(TIGHTEST);
        refinements += 1;
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
