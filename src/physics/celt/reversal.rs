//! A verified count of reversals (issue 59: the celt's reversal chart): the reversals in
//! `[0, T]` and the first one's time, graded only where two tolerances agree. The run is DOP853
//! at a local tolerance against its companion 16× looser (the celt's `auto` policy, through the
//! one loop `physics::verify`); the estimate is the largest difference of their reversal times,
//! infinite when they count differently. A count is *decided* when the estimate met the
//! tolerance (seconds); a chaotic window, whose counts differ between any two tolerances, stops
//! at the loop's stall rule and says it is not.
//!
//! A chart computes its cells in lanes ([`reversals_in_lanes`], issue 84): the same loop,
//! replayed over each cell's runs as they come back from `run::count_in_lanes`, so each cell
//! concludes what [`reversals`] concludes, bit for bit.

use std::collections::{BTreeMap, VecDeque};

use super::Problem;
use super::policy::{FIRST, POLICY};
use super::run::{Counts, Jobs, count, count_in_lanes};
use crate::physics::fork::GoOn;
use crate::physics::method::{Asked, Method, StepError};
use crate::physics::plan::Shortfall;
use crate::physics::verify::{Candidate, Conclusion, Policy, Round, Rounds, verify};

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

/// Runs already counted for one cell, by their tolerance's bits (a batched chart's, issue 84).
type Known = BTreeMap<u64, Result<Counts, StepError>>;

struct Counted<'a> {
    problem: Problem,
    t_end: f64,
    /// A batched cell's runs so far (`None`: a lone cell, which runs its own).
    known: Option<&'a Known>,
    /// The tolerances of the runs a batched cell needs next and has not.
    missing: Vec<f64>,
}

impl Counted<'_> {
    fn run_cost(&self, local: f64) -> f64 {
        super::budget::cost_seconds(
            &self.problem,
            &Asked::new(Method::Dop853, local, None, self.t_end),
        )
    }
}

/// The run and its companion one after the other (a chart's cells already fill the cores),
/// the run kept.
impl Candidate for Counted<'_> {
    type Plan = f64;
    type Run = Counts;
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn round(&mut self, local: &f64, go_on: GoOn<'_>) -> Result<Round<Counts>, StepError> {
        let companion = POLICY.companion(*local);
        let (fine, coarse) = if let Some(known) = self.known {
            let (fine, coarse) = (known.get(&local.to_bits()), known.get(&companion.to_bits()));
            let (Some(fine), Some(coarse)) = (fine, coarse) else {
                self.missing = [*local, companion]
                    .into_iter()
                    .filter(|t| !known.contains_key(&t.to_bits()))
                    .collect();
                return Err(StepError::Cancelled { t: 0.0 });
            };
            // A lone cell's order: the run's error before its companion's.
            (fine.clone()?, coarse.clone()?)
        } else {
            let fine = count(&self.problem, self.t_end, *local, go_on)?;
            (fine, count(&self.problem, self.t_end, companion, go_on)?)
        };
        let measured = if fine.count == coarse.count {
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
        known: None,
        missing: Vec::new(),
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
        known: None,
        missing: Vec::new(),
    };
    let first = first_local(tolerance);
    verify(&mut candidate, Rounds::unbudgeted(first, tolerance), go_on).map(concluded)
}

/// What a cell's verification concluded.
fn concluded(v: Conclusion<f64, Counts>) -> Reversals {
    let best = v.best.1;
    Reversals {
        count: best.count,
        first: best.reversals.first().copied(),
        decided: v.shortfall.is_none(),
    }
}

/// A cell's verification replayed over its runs so far: its conclusion, or the runs it needs
/// next (`Err`).
fn replay(
    problem: &Problem,
    t_end: f64,
    tolerance: f64,
    known: &Known,
    go_on: GoOn<'_>,
) -> Result<Result<Reversals, StepError>, Vec<f64>> {
    let mut candidate = Counted {
        problem: *problem,
        t_end,
        known: Some(known),
        missing: Vec::new(),
    };
    let v = verify(
        &mut candidate,
        Rounds::unbudgeted(first_local(tolerance), tolerance),
        go_on,
    );
    if candidate.missing.is_empty() {
        Ok(v.map(concluded))
    } else {
        Err(candidate.missing)
    }
}

/// One cell of [`reversals_in_lanes`]: its runs so far and how many of those asked are out.
struct Cell {
    problem: Problem,
    known: Known,
    out: usize,
}

/// The cells of [`reversals_in_lanes`] as [`Jobs`]: the runs asked, by id, the queue of those
/// not yet handed out, and each cell replayed when its last run asked comes back.
struct Cells<'a> {
    each_cell: Vec<Cell>,
    t_end: f64,
    tolerance: f64,
    runs: Vec<(usize, f64)>,
    queue: VecDeque<usize>,
    go_on: &'a (dyn Fn(f64) -> bool + Sync),
    each: &'a mut dyn FnMut(usize, Result<Reversals, StepError>),
}

impl Cells<'_> {
    /// Replays cell `i`: hands its conclusion on, or asks its next runs.
    fn replay(&mut self, i: usize) {
        let go_on = self.go_on;
        let cell = &mut self.each_cell[i];
        match replay(
            &cell.problem,
            self.t_end,
            self.tolerance,
            &cell.known,
            &mut |t| go_on(t),
        ) {
            Ok(concluded) => (self.each)(i, concluded),
            Err(missing) => {
                cell.out = missing.len();
                for local in missing {
                    self.queue.push_back(self.runs.len());
                    self.runs.push((i, local));
                }
            }
        }
    }
}

impl Jobs for Cells<'_> {
    fn next(&mut self) -> Option<(usize, Problem, f64, f64)> {
        let id = self.queue.pop_front()?;
        let (i, local) = self.runs[id];
        Some((id, self.each_cell[i].problem, self.t_end, local))
    }
    fn done(&mut self, id: usize, counted: Result<Counts, StepError>) {
        let (i, local) = self.runs[id];
        let cell = &mut self.each_cell[i];
        cell.known.insert(local.to_bits(), counted);
        cell.out -= 1;
        if cell.out == 0 {
            self.replay(i);
        }
    }
}

/// The reversals of each of `problems` as [`reversals`] finds them, bit for bit, their runs
/// taken [`LANES`](crate::physics::numerics::lanes::LANES) at a time (issue 84): each cell's
/// verification is replayed over the runs it has so far whenever the runs it asked come back,
/// and asks its next ones until it concludes. `each(i, …)` hears of cell `i` as it concludes.
pub fn reversals_in_lanes(
    problems: &[Problem],
    t_end: f64,
    tolerance: f64,
    go_on: &(dyn Fn(f64) -> bool + Sync),
    each: &mut dyn FnMut(usize, Result<Reversals, StepError>),
) {
    let mut cells = Cells {
        each_cell: problems
            .iter()
            .map(|&problem| Cell {
                problem,
                known: Known::new(),
                out: 0,
            })
            .collect(),
        t_end,
        tolerance,
        runs: Vec::new(),
        queue: VecDeque::new(),
        go_on,
        each,
    };
    for i in 0..problems.len() {
        cells.replay(i);
    }
    count_in_lanes(&mut cells, &mut |t| go_on(t));
}
