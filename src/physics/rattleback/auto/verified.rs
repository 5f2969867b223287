//! The verified run: the chosen plan run beside its companion, their difference the error
//! estimate, refined until it meets the tolerance or says by how much it misses.

use super::super::policy::POLICY;

use serde::Serialize;

use crate::physics::plan::Shortfall;

use super::super::budget::cost_seconds;
use super::super::params::Problem;
use super::super::run::{RunResult, run_cancellable};
use crate::physics::fork;
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::method::Settings;
use crate::physics::method::StepError;
use crate::physics::verify::{Candidate, Policy, Round, Rounds, verify};

use super::super::policy::AUTO_SECONDS;
use super::choice::{Decision, plan_cancellable};
use super::conditioning::{
    Conditioning, alpha_bound, bound_serves, conditioning_cost, conditioning_family, family_bound,
    generous_steps, measure_conditioning, measuring_cost, phase_round_off,
};
use super::measure::{Plan, conditioned_round_off, difference, over_budget};
use super::probe::{considers_averaged, probes_cost};
use super::resolved::refine;

/// A run chosen by `auto`, with its error estimate.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verified {
    /// The plan finally run (after refinements).
    pub plan: Plan,
    /// Its result.
    pub result: RunResult,
    /// Estimated error of `α(T)`, `α̇(T)` and the reversal times (the largest), model error
    /// and round-off floor included.
    pub error_estimate: f64,
    /// Whether `error_estimate` meets the tolerance.
    pub met: bool,
    /// Why not, when it does not.
    pub shortfall: Option<Shortfall>,
    /// The averaged model's probed error included in the estimate (0 for a resolved run).
    pub model_error: f64,
    /// How many times the first plan had to be refined.
    pub refinements: u32,
    /// The start's measured condition numbers, which scale the round-off floor in the
    /// estimate.
    pub condition: Conditioning,
    /// The round-off floors in `error_estimate` (the phase's and the start's conditioned
    /// one): where they alone pass the tolerance, `auto` says `met = false` after its first
    /// run, with [`Shortfall::Floor`].
    pub round_off_floor: f64,
    /// The settings of the returned run: integrating `plan.method` with these gives `result`
    /// bit for bit, which is how the explorer shows exactly what `simulate` reports.
    pub run_settings: Settings,
}

/// Plans, runs and verifies (see the module documentation).
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
/// predicted seconds (see [`super::super::budget`]), asking `go_on` every few hundred steps whether
/// to continue.
///
/// # Errors
/// When an integration fails, [`StepError::OverBudget`] when the probes or the first plan are
/// predicted over `budget` (later refinements past it are not run: the result says
/// `met = false`), or [`StepError::Cancelled`] when `go_on` says stop.
///
/// # Panics
/// Never: a refinement exists whenever the loop goes on.
pub fn run_auto_cancellable(
    problem: &Problem,
    spec: &RunSpec,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Verified, StepError> {
    let (tolerance, t_end) = (spec.tolerance, spec.t_end);
    let probes = if considers_averaged(problem, tolerance, t_end) {
        probes_cost(problem, t_end)
    } else {
        0.0
    };
    over_budget("auto's probing of the averaged model", probes, budget)?;
    let Decision {
        plan, model_error, ..
    } = plan_cancellable(problem, tolerance, t_end, go_on)?;
    let mut candidate = Auto {
        problem,
        spec,
        model_error,
        measured: None,
    };
    let spent = probes + candidate.cost(&plan);
    over_budget(
        &format!("auto's run and verification with {}", plan.method),
        spent,
        budget,
    )?;
    // The rounds may spend what is left of the allowance after the probes.
    let allowance = budget.min(AUTO_SECONDS).max(spent);
    let v = verify(
        &mut candidate,
        Rounds {
            first: plan,
            tolerance,
            budget: allowance - probes,
        },
        go_on,
    )?;
    let (reading, ran) = v.best;
    Ok(Verified {
        run_settings: reading.plan.settings(),
        plan: reading.plan,
        result: ran.result,
        error_estimate: reading.estimate,
        met: v.shortfall.is_none(),
        shortfall: v.shortfall,
        model_error: ran.model_error,
        refinements: u32::try_from(v.refinements).unwrap_or(u32::MAX),
        condition: ran.condition,
        round_off_floor: reading.floor,
    })
}

/// The rattleback's candidate for [`verify`]: a plan (any method, a tolerance or a step), the
/// averaged model's probed error it carries, and the start's condition numbers once measured
/// (again after a change from the averaged model to the full motion).
pub(super) struct Auto<'a> {
    pub(super) problem: &'a Problem,
    pub(super) spec: &'a RunSpec,
    pub(super) model_error: f64,
    pub(super) measured: Option<Conditioning>,
}

/// What `auto` keeps of a round.
pub(super) struct Ran {
    pub(super) result: RunResult,
    pub(super) condition: Conditioning,
    pub(super) model_error: f64,
}

impl Candidate for Auto<'_> {
    type Plan = Plan;
    type Run = Ran;
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn round(
        &mut self,
        plan: &Plan,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Round<Ran>, StepError> {
        let (result, condition, Checked { estimate, floor }) = run_and_check(
            self.problem,
            self.spec,
            plan,
            self.model_error,
            self.measured,
            go_on,
        )?;
        self.measured = Some(condition);
        Ok(Round {
            run: Ran {
                result,
                condition,
                model_error: self.model_error,
            },
            measured: estimate,
            floor,
        })
    }
    fn cost(&self, plan: &Plan) -> f64 {
        plan.predicted_seconds
            + if self.measured.is_none() {
                conditioning_cost(self.problem, self.spec.t_end, plan)
            } else {
                0.0
            }
    }
    fn refine(&mut self, plan: &Plan, estimate: f64, tolerance: f64) -> Result<Plan, Shortfall> {
        if plan.method.is_averaged()
            && plan.tolerance <= POLICY.tightest
            && self.model_error < 0.5 * tolerance
        {
            return Err(Shortfall::Clamped);
        }
        let t_end = self.spec.t_end;
        let next = refine(
            self.problem,
            plan,
            self.model_error,
            estimate,
            tolerance,
            t_end,
        )
        .ok_or(if plan.method.is_averaged() {
            Shortfall::Model
        } else {
            Shortfall::Clamped
        })?;
        if next.method != plan.method {
            // A new method carries no probed model error; leaving the averaged model, the start's
            // conditioning is measured again on the full motion, as a first resolved plan's is.
            self.model_error = 0.0;
            if plan.method.is_averaged() && !next.method.is_averaged() {
                self.measured = None;
            }
        }
        Ok(next)
    }
    fn continues(&self, plan: &Plan, next: &Plan) -> bool {
        plan.method == next.method
    }
    fn stalls(&self, plan: &Plan) -> usize {
        super::super::policy::of(plan.method).stalls
    }
}

/// Runs `plan` as `spec` asks (samples, energy) and, beside it ([`fork::both`]: on another core
/// where the program has one), its coarser companion, after the start's condition numbers when
/// they are not `measured` yet (a series' companion is then the conditioning's base run); the
/// run, the condition numbers and the run's error estimate (their difference, the model error,
/// the round-off floors, the second conditioned by `kappa`), with the floors' part.
pub(super) fn run_and_check(
    problem: &Problem,
    spec: &RunSpec,
    plan: &Plan,
    model_error: f64,
    measured: Option<Conditioning>,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunResult, Conditioning, Checked), StepError> {
    let run_spec = RunSpec {
        method: plan.method,
        tolerance: plan.tolerance,
        step: plan.step,
        ..*spec
    };
    let companion = plan.companion();
    let check_spec = RunSpec {
        tolerance: companion.tolerance,
        step: companion.step,
        samples: 0,
        monitor_energy: false,
        ..run_spec
    };
    let price = |s: &RunSpec| cost_seconds(problem, &s.asked());
    // Far in (an averaged plan at or above the start's conditioning stiffness), the reading of
    // the start there, kept across k, bounds its condition numbers where the floor it gives is
    // small: the verification is then the companion alone.
    let mut measured = measured;
    let mut family = None;
    if measured.is_none()
        && let Some(start) = conditioning_family(problem, plan)
    {
        match family_bound(&start, spec.t_end, false, go_on)? {
            Some(bound)
                if bound_serves(
                    &bound,
                    bound.at_angle(alpha_bound(problem, spec.t_end)),
                    generous_steps(problem, plan, spec.t_end),
                    spec.tolerance,
                ) =>
            {
                measured = Some(bound);
            }
            // Not read yet, or kept but not known to serve before the run: read beside the run
            // (and kept) and weighed after it, as when it was not kept. Measuring at k here
            // instead made a second resolution of one problem in a process estimate otherwise
            // than its first (issue 80: a recording's two plan lines of one key disagreed, and it
            // failed its own `--verify`).
            _ => family = Some(start),
        }
    }
    let verifying = price(&check_spec)
        + if measured.is_some() {
            0.0
        } else {
            measuring_cost(problem, spec.t_end, plan)
        };
    let (here, there, plan_there) = (*problem, *problem, plan.clone());
    let (result, verification) = fork::dearer_here(
        go_on,
        (
            move |go_on: fork::GoOn<'_>| run_cancellable(&here, &run_spec, go_on),
            price(&run_spec),
        ),
        (
            move |go_on: fork::GoOn<'_>| -> Result<(Conditioning, RunResult), StepError> {
                let (kappa, made) = match (measured, family) {
                    (Some(kappa), _) => (kappa, None),
                    (None, Some(start)) => {
                        let bound = family_bound(&start, check_spec.t_end, true, go_on)?;
                        (bound.expect("computed when not kept"), None)
                    }
                    (None, None) => {
                        measure_conditioning(&there, check_spec.t_end, &plan_there, go_on)?
                    }
                };
                let check = match made {
                    Some(made) if made.spec == check_spec => made.result,
                    _ => run_cancellable(&there, &check_spec, go_on)?,
                };
                Ok((kappa, check))
            },
            verifying,
        ),
    );
    // The run's failure first (a cancellation stops both), then the verification's.
    let result = result?;
    let (mut kappa, check) = verification?;
    let steps = result.stats.steps as f64;
    if kappa.margin > 1.0
        && !bound_serves(
            &kappa,
            kappa.of_run(problem, &result),
            steps,
            spec.tolerance,
        )
    {
        // The bound would weigh on the estimate (more steps than predicted, a rotating start's
        // angle, a tight tolerance), or the start may be ill-conditioned: it is measured at its
        // own k after all.
        kappa = measure_conditioning(problem, spec.t_end, plan, go_on)?.0;
    }
    let floor = phase_round_off(problem, plan, steps, spec.t_end)
        + conditioned_round_off(steps, kappa.of_run(problem, &result));
    let estimate = difference(&result, &check) + model_error + floor;
    Ok((result, kappa, Checked { estimate, floor }))
}

/// A run's estimate, and the part of it that rounding alone sets.
#[derive(Clone, Copy, Debug)]
pub(super) struct Checked {
    pub(super) estimate: f64,
    /// The round-off floors in `estimate` (the phase's and the start's conditioned one): no
    /// refinement lowers them, since a refinement takes more steps.
    pub(super) floor: f64,
}
