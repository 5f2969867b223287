//! The one verification loop of every scene's `auto` (issue 57): run a candidate at a local
//! tolerance and a companion some times looser, take their difference (plus the round-off
//! floors) as the estimate, and refine until the estimate meets the tolerance, stalls, reaches
//! the tightest local tolerance, runs out of refinements, or the next round would pass the
//! budget. What differs between scenes is data ([`Policy`]) and what is the model's own
//! ([`Candidate`]: how it runs, what it compares, its floors, its cost).
//!
//! Each round is priced before it runs; the first always runs (the caller has priced it).
//! A refinement tightens the local tolerance by the factor the estimate asks for (half the
//! tolerance over the estimate), at least [`Policy::refine`], [`Policy::blind_refine`] when the
//! estimate is infinite (the two runs disagree on a count). A round stalls when what it
//! measured is more than half the previous round's; [`Policy::stalls`] stalls in a row stop
//! the loop ([`Shortfall::Floor`]).

use super::method::StepError;
use super::plan::Shortfall;

/// How a scene's `auto` verifies: data, the same loop for all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Policy {
    /// How much looser the companion run is than the candidate's.
    pub companion_looser: f64,
    /// The loosest local tolerance a companion is given.
    pub companion_cap: f64,
    /// The companion's global error over the run's where the method converges, as measured
    /// (what an a-priori plan divides a tolerance by; the difference of the two runs bounds the
    /// run's error when it is at least 2).
    pub companion_error: f64,
    /// The least a refinement tightens the local tolerance (a factor below 1).
    pub refine: f64,
    /// The factor of a refinement when the estimate is infinite.
    pub blind_refine: f64,
    /// The tightest local tolerance.
    pub tightest: f64,
    /// The most refinements after the first round.
    pub max_refinements: usize,
    /// How many rounds in a row must fail to halve what was measured for the loop to stop.
    pub stalls: usize,
}

impl Policy {
    /// The companion's local tolerance for a candidate at `local`.
    #[must_use]
    pub fn companion(&self, local: f64) -> f64 {
        (local * self.companion_looser).min(self.companion_cap)
    }
}

/// What a model brings to the loop.
pub trait Candidate {
    /// A finished run.
    type Run;
    /// The candidate at `local` and its companion at `companion` (side by side where the model
    /// finds it pays).
    ///
    /// # Errors
    /// A failed or cancelled run.
    fn pair(
        &mut self,
        local: f64,
        companion: f64,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<(Self::Run, Self::Run), StepError>;
    /// Their difference plus the round-off floors.
    fn measured(&self, fine: &Self::Run, coarse: &Self::Run) -> f64;
    /// The estimate from what was measured at `local`, knowing the previous round's
    /// `(local, measured)` (a model may widen it where rounding sets both runs' errors).
    fn estimate(&self, measured: f64, local: f64, last: Option<(f64, f64)>) -> f64 {
        let _ = (local, last);
        measured
    }
    /// Predicted seconds of one run at `local`.
    fn cost(&self, local: f64) -> f64;
}

/// How the loop ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// The estimate met the tolerance at `local`.
    Met {
        /// The local tolerance.
        local: f64,
        /// Its estimate.
        estimate: f64,
    },
    /// It could not: stalled, clamped or out of refinements, at `local`.
    Declined {
        /// The last local tolerance.
        local: f64,
        /// What it measured.
        measured: f64,
        /// Its estimate.
        estimate: f64,
        /// The round before: `(local, measured)`.
        last: Option<(f64, f64)>,
        /// Why.
        why: Shortfall,
    },
    /// The next round would pass the budget: the last round's `(local, measured)`.
    Time {
        /// The last local tolerance run.
        local: f64,
        /// What it measured.
        measured: f64,
    },
}

/// Verifies `candidate` from the local tolerance `first` until its estimate meets
/// `tolerance`, as [`Policy`] says, spending at most `budget` predicted seconds after the
/// first round.
///
/// # Errors
/// A failed or cancelled run.
pub fn verify(
    policy: &Policy,
    candidate: &mut impl Candidate,
    first: f64,
    tolerance: f64,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Verdict, StepError> {
    let mut local = first;
    let mut spent = 0.0;
    // The last round's `(local, measured)`.
    let mut last: Option<(f64, f64)> = None;
    // Rounds in a row that did not halve what was measured.
    let mut stalls = 0;
    for refinement in 0..=policy.max_refinements {
        let companion = policy.companion(local);
        let predicted = candidate.cost(local) + candidate.cost(companion);
        if let Some((l, m)) = last
            && spent + predicted > budget
        {
            return Ok(Verdict::Time {
                local: l,
                measured: m,
            });
        }
        spent += predicted;
        let (fine, coarse) = candidate.pair(local, companion, go_on)?;
        let measured = candidate.measured(&fine, &coarse);
        let estimate = candidate.estimate(measured, local, last);
        if estimate <= tolerance {
            return Ok(Verdict::Met { local, estimate });
        }
        stalls = if last.is_some_and(|(_, m)| measured > 0.5 * m) {
            stalls + 1
        } else {
            0
        };
        let stalled = stalls >= policy.stalls;
        if stalled || local <= policy.tightest || refinement == policy.max_refinements {
            let why = if stalled {
                Shortfall::Floor
            } else if local <= policy.tightest {
                Shortfall::Clamped
            } else {
                Shortfall::Refinements
            };
            return Ok(Verdict::Declined {
                local,
                measured,
                estimate,
                last,
                why,
            });
        }
        last = Some((local, measured));
        let factor = if estimate.is_finite() {
            (0.5 * tolerance / estimate).min(policy.refine)
        } else {
            policy.blind_refine
        };
        local = (local * factor).max(policy.tightest);
    }
    unreachable!("the loop returns at its last refinement")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model whose runs err by `c · local` (a method of order one in its tolerance) above a
    /// rounding floor.
    struct Linear {
        c: f64,
        floor: f64,
        rounds: usize,
    }

    impl Candidate for Linear {
        type Run = f64;
        fn pair(
            &mut self,
            local: f64,
            companion: f64,
            _: &mut dyn FnMut(f64) -> bool,
        ) -> Result<(f64, f64), StepError> {
            self.rounds += 1;
            Ok((self.c * local, self.c * companion))
        }
        fn measured(&self, fine: &f64, coarse: &f64) -> f64 {
            (coarse - fine).abs() + self.floor
        }
        fn cost(&self, local: f64) -> f64 {
            local.powf(-0.125) * 1e-3
        }
    }

    const POLICY: Policy = Policy {
        companion_looser: 16.0,
        companion_cap: 1e-2,
        companion_error: 14.0,
        refine: 0.25,
        blind_refine: 1.0 / 16.0,
        tightest: 1e-14,
        max_refinements: 4,
        stalls: 2,
    };

    #[test]
    fn refines_until_met_and_stops_at_a_floor_after_its_stalls() {
        let mut m = Linear {
            c: 100.0,
            floor: 0.0,
            rounds: 0,
        };
        let v = verify(&POLICY, &mut m, 1e-9, 1e-8, 60.0, &mut |_| true).unwrap();
        assert!(
            matches!(v, Verdict::Met { estimate, .. } if estimate <= 1e-8),
            "{v:?}"
        );
        assert!(m.rounds >= 2, "it refined");
        let mut m = Linear {
            c: 1.0,
            floor: 1e-6,
            rounds: 0,
        };
        let v = verify(&POLICY, &mut m, 1e-9, 1e-8, 60.0, &mut |_| true).unwrap();
        assert!(
            matches!(
                v,
                Verdict::Declined {
                    why: Shortfall::Floor,
                    ..
                }
            ),
            "{v:?}"
        );
        let one = Policy {
            stalls: 1,
            ..POLICY
        };
        let mut fewer = Linear {
            c: 1.0,
            floor: 1e-6,
            rounds: 0,
        };
        verify(&one, &mut fewer, 1e-9, 1e-8, 60.0, &mut |_| true).unwrap();
        assert_eq!(fewer.rounds + 1, m.rounds, "one stall stops a round sooner");
    }

    #[test]
    fn the_budget_stops_it_after_the_first_round() {
        let mut m = Linear {
            c: 1e6,
            floor: 0.0,
            rounds: 0,
        };
        let v = verify(&POLICY, &mut m, 1e-9, 1e-12, 0.0, &mut |_| true).unwrap();
        assert!(
            matches!(v, Verdict::Time { local, .. } if (local - 1e-9).abs() < 1e-24),
            "{v:?}"
        );
        assert_eq!(m.rounds, 1);
    }
}
