//! The one verification loop of every scene's `auto` (issue 57): run a candidate plan and a
//! looser companion, take their difference (plus the round-off floors) as the estimate, and
//! refine until the estimate meets the tolerance or cannot: rounding alone passes it, the
//! refinements stall, the plan cannot be tightened, the refinements run out, or the next round
//! would pass the budget. What differs between scenes is data ([`Policy`]) and what is the
//! model's own ([`Candidate`]: what a plan is, how a round runs and what it measures, how a plan
//! is refined — a tighter tolerance, a smaller step, another method — and what a round costs).
//!
//! Each round is priced before it runs; the first always runs (the caller has priced it). A
//! round stalls when what it measured is not under half what the round before it measured in
//! the same sequence (a change of method starts a new one; an infinite difference after an
//! infinite one stalls); [`Candidate::stalls`] stalls in a row stop the loop
//! ([`Shortfall::Floor`]), as does, where [`Policy::floor_stops`], a round whose round-off floor
//! alone passes the tolerance. The loop keeps the round with the lowest estimate: past
//! the round-off floor a refinement can do worse.

use super::fork::{self, GoOn};
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
    /// How much more than its order asks a fixed step shrinks at a refinement (a model whose
    /// plans have fixed steps: the step for an excess `e` of a method of order `p` is divided by
    /// `step_safety · e^(1/p)`).
    pub step_safety: f64,
    /// The most refinements after the first round.
    pub max_refinements: usize,
    /// How many rounds in a row must fail to halve what was measured for the loop to stop.
    pub stalls: usize,
    /// Whether a round whose round-off floor alone passes the tolerance stops the loop at once
    /// (a refinement only adds steps to it). The pendulum's does not: its next round shows
    /// whether rounding sets both runs' errors, which widens its estimate.
    pub floor_stops: bool,
}

impl Policy {
    /// The companion's local tolerance for a candidate at `local`.
    #[must_use]
    pub fn companion(&self, local: f64) -> f64 {
        (local * self.companion_looser).min(self.companion_cap)
    }

    /// The refinement of a plan that is a local tolerance: tightened by the factor the estimate
    /// asks for (half the tolerance over the estimate), at least [`Policy::refine`],
    /// [`Policy::blind_refine`] when the estimate is infinite (the two runs disagree on a
    /// count), never past [`Policy::tightest`].
    ///
    /// # Errors
    /// [`Shortfall::Clamped`] when `local` is at the tightest already.
    pub fn tighten(&self, local: f64, estimate: f64, tolerance: f64) -> Result<f64, Shortfall> {
        if local <= self.tightest {
            return Err(Shortfall::Clamped);
        }
        let factor = if estimate.is_finite() {
            (0.5 * tolerance / estimate).min(self.refine)
        } else {
            self.blind_refine
        };
        Ok((local * factor).max(self.tightest))
    }
}

/// What one round gave: the run, its difference from the companion plus the round-off floors
/// (`measured`), and those floors alone.
#[derive(Clone, Debug)]
pub struct Round<R> {
    /// What the model keeps of the round.
    pub run: R,
    /// The two runs' difference plus the floors.
    pub measured: f64,
    /// The round-off floors in `measured`: no refinement lowers them.
    pub floor: f64,
}

/// What a model brings to the loop.
pub trait Candidate {
    /// What a round runs: a local tolerance, or a method with its settings.
    type Plan: Clone;
    /// What the model keeps of a round.
    type Run;
    /// The scene's policy: the loop's data (its refinements, stalls and floor rule), read by
    /// [`verify`] from here alone (issue 69: it was an argument too, and the two could differ).
    fn policy(&self) -> &'static Policy;
    /// Runs `plan` and its companion (side by side where the model finds it pays).
    ///
    /// # Errors
    /// A failed or cancelled run.
    fn round(
        &mut self,
        plan: &Self::Plan,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Round<Self::Run>, StepError>;
    /// The estimate from what `plan` measured, knowing the round `before` it in the same
    /// sequence (a model may widen it where rounding sets both runs' errors).
    fn estimate(
        &self,
        measured: f64,
        plan: &Self::Plan,
        before: Option<&(Self::Plan, f64)>,
    ) -> f64 {
        let _ = (plan, before);
        measured
    }
    /// Predicted seconds of a round of `plan` (the run and its companion).
    fn cost(&self, plan: &Self::Plan) -> f64;
    /// The plan after `plan` missed with `estimate`.
    ///
    /// # Errors
    /// Why there is none.
    fn refine(
        &mut self,
        plan: &Self::Plan,
        estimate: f64,
        tolerance: f64,
    ) -> Result<Self::Plan, Shortfall>;
    /// Whether `next` goes on `plan`'s sequence (the stall rule compares like with like).
    fn continues(&self, plan: &Self::Plan, next: &Self::Plan) -> bool {
        let _ = (plan, next);
        true
    }
    /// How many stalls in a row stop the loop at `plan` (the policy's `stalls` unless a method
    /// has its own).
    fn stalls(&self, plan: &Self::Plan) -> usize {
        let _ = plan;
        self.policy().stalls
    }
}

/// A candidate that is one method at a local tolerance (the plan), verified against the
/// companion its policy names, the two run side by side where the program has two cores: what
/// a model writes is a run, the difference of two, the rounding floor and the cost of one.
pub trait AtTolerance: Clone + Send + 'static {
    /// A finished run.
    type Result: Send + 'static;
    /// The policy (its companion and refinement).
    fn policy(&self) -> &'static Policy;
    /// A run at `local`.
    ///
    /// # Errors
    /// A failed or cancelled run.
    fn run(&self, local: f64, go_on: GoOn<'_>) -> Result<Self::Result, StepError>;
    /// The difference of two runs.
    fn difference(&self, fine: &Self::Result, coarse: &Self::Result) -> f64;
    /// The round-off floor of a run.
    fn floor(&self, fine: &Self::Result) -> f64;
    /// Predicted seconds of one run at `local`.
    fn run_cost(&self, local: f64) -> f64;
    /// Rounding measured, not modelled (issue 66): where a method's steps may round more than
    /// its [`AtTolerance::floor`] says, the same run again from a start one rounding away; the
    /// two differ only by their rounding, so their difference (widened) samples what rounding
    /// left in `fine`. `None` (the default): the floor alone. Called after the pair; its cost is
    /// [`AtTolerance::rounding_cost`].
    ///
    /// # Errors
    /// A failed or cancelled run.
    fn rounding(
        &self,
        local: f64,
        fine: &Self::Result,
        go_on: GoOn<'_>,
    ) -> Result<Option<f64>, StepError> {
        let _ = (local, fine, go_on);
        Ok(None)
    }
    /// The floors of `fine` given the rounding `measured` by [`AtTolerance::rounding`] (`None`:
    /// not measured): by default the modelled floor plus what was measured. A model whose
    /// floor's law is a worst case may let a measurement stand in for it.
    fn floors(&self, fine: &Self::Result, measured: Option<f64>) -> f64 {
        self.floor(fine) + measured.unwrap_or(0.0)
    }
    /// Predicted seconds of [`AtTolerance::rounding`] at `local` (0 where it runs nothing).
    fn rounding_cost(&self, local: f64) -> f64 {
        let _ = local;
        0.0
    }
    /// As [`Candidate::estimate`].
    fn estimate(&self, measured: f64, local: f64, before: Option<&(f64, f64)>) -> f64 {
        let _ = (local, before);
        measured
    }
}

impl<T: AtTolerance> Candidate for T {
    type Plan = f64;
    type Run = ();
    fn policy(&self) -> &'static Policy {
        AtTolerance::policy(self)
    }
    fn round(&mut self, local: &f64, go_on: GoOn<'_>) -> Result<Round<()>, StepError> {
        let (local, companion) = (*local, AtTolerance::policy(self).companion(*local));
        let there = self.clone();
        let (fine, coarse) = fork::both(
            go_on,
            |go_on| self.run(local, go_on),
            move |go_on| there.run(companion, go_on),
        );
        let (fine, coarse) = (fine?, coarse?);
        let measured = self.rounding(local, &fine, go_on)?;
        let floor = self.floors(&fine, measured);
        Ok(Round {
            run: (),
            measured: self.difference(&fine, &coarse) + floor,
            floor,
        })
    }
    fn estimate(&self, measured: f64, local: &f64, before: Option<&(f64, f64)>) -> f64 {
        AtTolerance::estimate(self, measured, *local, before)
    }
    fn cost(&self, local: &f64) -> f64 {
        self.run_cost(*local)
            + self.run_cost(AtTolerance::policy(self).companion(*local))
            + self.rounding_cost(*local)
    }
    fn refine(&mut self, local: &f64, estimate: f64, tolerance: f64) -> Result<f64, Shortfall> {
        AtTolerance::policy(self).tighten(*local, estimate, tolerance)
    }
}

/// A round as read: its plan, what it measured, its estimate and its floors.
#[derive(Clone, Debug, PartialEq)]
pub struct Reading<P> {
    /// The plan run.
    pub plan: P,
    /// Its difference from the companion plus the floors.
    pub measured: f64,
    /// Its estimate.
    pub estimate: f64,
    /// The round-off floors in it.
    pub floor: f64,
}

/// How the loop ended.
#[derive(Clone, Debug)]
pub struct Conclusion<P, R> {
    /// Why the estimate misses the tolerance (`None`: it met it).
    pub shortfall: Option<Shortfall>,
    /// The last round.
    pub last: Reading<P>,
    /// The round before the last in its sequence: its plan and what it measured.
    pub before: Option<(P, f64)>,
    /// The round with the lowest estimate (the last when it met) and its run.
    pub best: (Reading<P>, R),
    /// Refinements after the first round.
    pub refinements: usize,
}

/// What the loop is asked: where it starts and what it must meet, within what.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rounds<P> {
    /// The first round's plan.
    pub first: P,
    /// The tolerance the estimate must meet.
    pub tolerance: f64,
    /// Predicted seconds the rounds may spend together (the first always runs: the caller has
    /// priced it).
    pub budget: f64,
}

impl<P> Rounds<P> {
    /// From `first` to `tolerance` with no budget: work whose price was admitted as a whole
    /// (a chart's cell).
    #[must_use]
    pub fn unbudgeted(first: P, tolerance: f64) -> Self {
        Self {
            first,
            tolerance,
            budget: f64::INFINITY,
        }
    }
}

/// Verifies `candidate` from the plan `ask.first` until its estimate meets `ask.tolerance`, as
/// the candidate's policy says, the rounds together predicted at most `ask.budget` seconds (the
/// first always runs).
///
/// # Errors
/// A failed or cancelled run.
pub fn verify<C: Candidate>(
    candidate: &mut C,
    ask: Rounds<C::Plan>,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Conclusion<C::Plan, C::Run>, StepError> {
    let Rounds {
        first,
        tolerance,
        budget,
    } = ask;
    let policy = candidate.policy();
    let mut plan = first;
    let mut spent = candidate.cost(&plan);
    // The round before this one in its sequence, and rounds in a row that did not halve it.
    let mut before: Option<(C::Plan, f64)> = None;
    let mut stalls = 0;
    let mut best: Option<(Reading<C::Plan>, C::Run)> = None;
    for refinement in 0..=policy.max_refinements {
        let Round {
            run,
            measured,
            floor,
        } = candidate.round(&plan, go_on)?;
        let estimate = candidate.estimate(measured, &plan, before.as_ref());
        stalls = if before.as_ref().is_some_and(|(_, m)| measured >= 0.5 * m) {
            stalls + 1
        } else {
            0
        };
        let reading = Reading {
            plan: plan.clone(),
            measured,
            estimate,
            floor,
        };
        let ended = |shortfall, best, before| Conclusion {
            shortfall,
            last: reading.clone(),
            before,
            best,
            refinements: refinement,
        };
        if estimate <= tolerance {
            return Ok(ended(None, (reading.clone(), run), before));
        }
        let best_now = match best.take() {
            Some(b) if b.0.estimate <= estimate => b,
            _ => (reading.clone(), run),
        };
        let next = if (policy.floor_stops && floor > tolerance) || stalls >= candidate.stalls(&plan)
        {
            Err(Shortfall::Floor)
        } else if refinement == policy.max_refinements {
            Err(Shortfall::Refinements)
        } else {
            candidate.refine(&plan, estimate, tolerance)
        };
        let next = next.and_then(|next| {
            let cost = candidate.cost(&next);
            if spent + cost > budget {
                return Err(Shortfall::Time);
            }
            spent += cost;
            Ok(next)
        });
        match next {
            Err(why) => return Ok(ended(Some(why), best_now, before)),
            Ok(next) => {
                before = candidate
                    .continues(&plan, &next)
                    .then_some((plan, measured));
                best = Some(best_now);
                plan = next;
            }
        }
    }
    unreachable!("the loop returns at its last refinement")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model whose runs err by `c · local` (a method of order one in its tolerance) above a
    /// rounding level `noise` it does not know of, and a floor it does.
    struct Linear {
        c: f64,
        noise: f64,
        floor: f64,
        rounds: usize,
        policy: &'static Policy,
    }

    impl Candidate for Linear {
        type Plan = f64;
        type Run = usize;
        fn policy(&self) -> &'static Policy {
            self.policy
        }
        fn round(
            &mut self,
            local: &f64,
            _: &mut dyn FnMut(f64) -> bool,
        ) -> Result<Round<usize>, StepError> {
            self.rounds += 1;
            let d = self.c * (self.policy.companion(*local) - local);
            Ok(Round {
                run: self.rounds,
                measured: d + self.noise + self.floor,
                floor: self.floor,
            })
        }
        fn cost(&self, local: &f64) -> f64 {
            local.powf(-0.125) * 1e-3
        }
        fn refine(&mut self, local: &f64, estimate: f64, tol: f64) -> Result<f64, Shortfall> {
            self.policy.tighten(*local, estimate, tol)
        }
    }

    const POLICY: Policy = Policy {
        companion_looser: 8.0,
        companion_cap: 1e-3,
        companion_error: 7.0,
        refine: 0.25,
        blind_refine: 1.0 / 16.0,
        tightest: 1e-14,
        step_safety: 1.25,
        max_refinements: 4,
        stalls: 2,
        floor_stops: true,
    };

    /// The same policy, stopped by one stall.
    const ONE_STALL: Policy = Policy {
        stalls: 1,
        ..POLICY
    };

    fn linear(c: f64, noise: f64, floor: f64) -> Linear {
        Linear {
            c,
            noise,
            floor,
            rounds: 0,
            policy: &POLICY,
        }
    }

    fn rounds(first: f64, tolerance: f64, budget: f64) -> Rounds<f64> {
        Rounds {
            first,
            tolerance,
            budget,
        }
    }

    #[test]
    fn refines_until_met_and_stops_at_a_hidden_floor_after_its_stalls() {
        let mut m = linear(100.0, 0.0, 0.0);
        let v = verify(&mut m, rounds(1e-9, 1e-8, 60.0), &mut |_| true).unwrap();
        assert_eq!(v.shortfall, None, "{v:?}");
        assert!(
            v.best.0.estimate <= 1e-8 && m.rounds >= 2,
            "it refined: {v:?}"
        );
        assert_eq!(v.best.1, m.rounds, "the met round is the one returned");
        let mut m = linear(1.0, 1e-6, 0.0);
        let v = verify(&mut m, rounds(1e-9, 1e-8, 60.0), &mut |_| true).unwrap();
        assert_eq!(v.shortfall, Some(Shortfall::Floor), "{v:?}");
        assert_eq!(
            v.before.map(|b| b.1 > 0.0),
            Some(true),
            "the round before is kept"
        );
        let mut fewer = Linear {
            policy: &ONE_STALL,
            ..linear(1.0, 1e-6, 0.0)
        };
        verify(&mut fewer, rounds(1e-9, 1e-8, 60.0), &mut |_| true).unwrap();
        assert_eq!(fewer.rounds + 1, m.rounds, "one stall stops a round sooner");
    }

    #[test]
    fn a_floor_above_the_tolerance_stops_it_at_once() {
        let mut m = linear(1.0, 0.0, 1e-6);
        let v = verify(&mut m, rounds(1e-9, 1e-8, 60.0), &mut |_| true).unwrap();
        assert_eq!((v.shortfall, m.rounds), (Some(Shortfall::Floor), 1));
    }

    #[test]
    fn the_budget_stops_it_after_the_first_round() {
        let mut m = linear(1e6, 0.0, 0.0);
        let v = verify(&mut m, rounds(1e-9, 1e-12, 0.0), &mut |_| true).unwrap();
        assert_eq!(v.shortfall, Some(Shortfall::Time));
        assert_eq!((v.last.plan, v.refinements, m.rounds), (1e-9, 0, 1));
    }

    /// Errs by `c · local` until `worse_after` rounds, then by a thousand times more.
    struct Worsening(Linear, usize);

    impl Candidate for Worsening {
        type Plan = f64;
        type Run = usize;
        fn policy(&self) -> &'static Policy {
            self.0.policy
        }
        fn round(
            &mut self,
            local: &f64,
            go_on: &mut dyn FnMut(f64) -> bool,
        ) -> Result<Round<usize>, StepError> {
            let mut o = self.0.round(local, go_on)?;
            if o.run > self.1 {
                o.measured *= 1e6;
            }
            Ok(o)
        }
        fn cost(&self, local: &f64) -> f64 {
            self.0.cost(local)
        }
        fn refine(&mut self, local: &f64, _: f64, _: f64) -> Result<f64, Shortfall> {
            // Its own refinement, and a change of sequence each time: stalls never count.
            Ok(0.5 * local)
        }
        fn continues(&self, _: &f64, _: &f64) -> bool {
            false
        }
    }

    #[test]
    fn it_returns_the_best_round_and_a_new_sequence_forgets_its_stalls() {
        let mut m = Worsening(linear(1.0, 0.0, 0.0), 2);
        let v = verify(&mut m, rounds(1e-6, 1e-16, 60.0), &mut |_| true).unwrap();
        assert_eq!(v.shortfall, Some(Shortfall::Refinements), "{v:?}");
        assert_eq!(
            m.0.rounds,
            POLICY.max_refinements + 1,
            "no stall stopped it"
        );
        assert_eq!(v.best.1, 2, "the second round measured least");
        assert!(v.best.0.estimate < v.last.estimate && v.before.is_none());
    }
}
