//! A verified count of reversals (issue 59: the celt's reversal chart): the reversals in
//! `[0, T]` and the first one's time, graded only where two tolerances agree. The run is DOP853
//! at a local tolerance against its companion 16× looser (the celt's `auto` policy, through the
//! one loop `physics::verify`); the estimate is the largest difference of their reversal times,
//! infinite when they count differently. A count is *decided* when the estimate met the
//! tolerance (seconds); a chaotic window, whose counts differ between any two tolerances, stops
//! at the loop's stall rule and says it is not.

use super::Problem;
use super::policy::{FIRST, POLICY};
use super::run::{RunResult, run};
use crate::physics::fork::GoOn;
use crate::physics::method::{Asked, Method, RunSpec, StepError};
use crate::physics::plan::Shortfall;
use crate::physics::verify::{Candidate, Policy, Round, Rounds, verify};

/// A cell's count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reversals {
    /// Reversals in `[0, T]`.
    pub count: usize,
    /// The first one's time (s).
    pub first: Option<f64>,
    /// Whether two tolerances agree on the count and the times to `tolerance`.
    pub decided: bool,
}

#[derive(Clone, Copy)]
struct Counted {
    problem: Problem,
    t_end: f64,
}

impl Counted {
    fn run(&self, local: f64, go_on: GoOn<'_>) -> Result<RunResult, StepError> {
        let spec = RunSpec::new(Asked::new(Method::Dop853, local, None, self.t_end), 0);
        run(&self.problem, &spec, go_on)
    }
    fn run_cost(&self, local: f64) -> f64 {
        super::budget::cost_seconds(
            &self.problem,
            &Asked::new(Method::Dop853, local, None, self.t_end),
        )
    }
}

/// The run and its companion one after the other (a chart's cells already fill the cores),
/// the run kept.
impl Candidate for Counted {
    type Plan = f64;
    type Run = RunResult;
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn round(&mut self, local: &f64, go_on: GoOn<'_>) -> Result<Round<RunResult>, StepError> {
        let fine = self.run(*local, go_on)?;
        let coarse = self.run(POLICY.companion(*local), go_on)?;
        let measured = if fine.reversal_count == coarse.reversal_count {
            fine.reversals
                .iter()
                .zip(&coarse.reversals)
                .fold(0.0, |d: f64, (a, b)| d.max((a - b).abs()))
        } else {
            f64::INFINITY
        };
        Ok(Round {
            run: fine,
            measured,
            floor: 0.0,
        })
    }
    fn cost(&self, local: &f64) -> f64 {
        self.run_cost(*local) + self.run_cost(POLICY.companion(*local))
    }
    fn refine(&mut self, local: &f64, estimate: f64, tolerance: f64) -> Result<f64, Shortfall> {
        POLICY.tighten(*local, estimate, tolerance)
    }
}

/// The first round's local tolerance for reversal times verified to `tolerance` seconds.
fn first_local(tolerance: f64) -> f64 {
    (tolerance * FIRST).clamp(1e-12, 1e-6)
}

/// Predicted seconds of the first round of [`reversals`] (the run and its companion): what a
/// chart's cell is priced in, asked of the run itself (issue 69: the chart re-derived the first
/// tolerance, so the two could drift apart).
#[must_use]
pub fn first_round_seconds(problem: &Problem, t_end: f64, tolerance: f64) -> f64 {
    let candidate = Counted {
        problem: *problem,
        t_end,
    };
    candidate.cost(&first_local(tolerance))
}

/// The reversals of `problem` in `[0, t_end]`, their times verified to `tolerance` seconds.
///
/// # Errors
/// A failed or cancelled run.
pub fn reversals(
    problem: &Problem,
    t_end: f64,
    tolerance: f64,
    go_on: GoOn<'_>,
) -> Result<Reversals, StepError> {
    let mut candidate = Counted {
        problem: *problem,
        t_end,
    };
    let first = first_local(tolerance);
    let v = verify(&mut candidate, Rounds::unbudgeted(first, tolerance), go_on)?;
    let best = v.best.1;
    Ok(Reversals {
        count: best.reversal_count,
        first: best.reversals.first().copied(),
        decided: v.shortfall.is_none(),
    })
}
