//! How runs are planned: the plans a session recorded (`PlanKey`, `PlanBook`) and the
//! [`Planner`] that resolves and prices every run (the engine's own, and a job's: the
//! comparison's partner), refusing one over the budget with words for the panel.

use super::{Session, SessionSpec};
use crate::physics::method::Method;
use crate::physics::method::StepError;
use crate::physics::method::{Arithmetic, Asked};
use crate::physics::plan::{AutoRules, Resolved};

pub use crate::physics::models::PlanKey;

impl PlanKey {
    /// The key of a session spec.
    #[must_use]
    pub fn of(spec: &SessionSpec) -> Self {
        Self::for_model(&spec.model, spec.tolerance, spec.t_end)
    }
}

/// How `auto` is resolved: a policy, and the plans a recording already resolved (replay uses
/// them, so a later change of `auto` never changes an old session's trajectory).
#[derive(Clone, Debug, PartialEq)]
pub struct PlanBook {
    /// Policy for keys not recorded.
    pub policy: AutoRules,
    /// Recorded plans of `auto` (a method asked by name is its own plan).
    pub recorded: Vec<(PlanKey, Resolved)>,
    /// The error estimates recorded with them (format 4 on), shown again by a replay.
    pub estimates: Vec<(PlanKey, f64)>,
    /// Work budget of `auto`'s verification, in predicted seconds: over it, planning fails
    /// with a message instead of computing for hours before the first frame.
    pub budget: f64,
    /// Budget of all the runs together, in predicted seconds (a replayed session: its own
    /// length and a margin; unbounded in the explorer, whose user restarts at will).
    pub total: f64,
    /// The arithmetic the runs follow: the current rules, as `simulate` does, except in a
    /// replay of an old file, which follows the rules it was recorded with
    /// ([`Arithmetic::of_format`]).
    pub arithmetic: Arithmetic,
    /// `auto` verifies a long run in segments, drawing once the first is verified
    /// ([`super::segments`]); a replay of a file older than format 9 shows its runs in one
    /// piece, as they were shown.
    pub segmented: bool,
    /// A follower's book: the verification ahead waits for the lecturer's plans of the later
    /// segments ([`Command::Book`](super::Command::Book)) instead of verifying them at the
    /// same moment as the lecturer, for at most [`super::segments::AWAIT_SECONDS`] a segment,
    /// until [`Command::Release`](super::Command::Release).
    pub awaits: bool,
}

impl Default for PlanBook {
    fn default() -> Self {
        Self {
            policy: AutoRules::default(),
            recorded: Vec::new(),
            estimates: Vec::new(),
            budget: crate::physics::budget::BUDGET_SECONDS,
            total: f64::INFINITY,
            arithmetic: Arithmetic::default(),
            segmented: true,
            awaits: false,
        }
    }
}

impl PlanBook {
    /// What the model is asked to plan for `spec`, under this book's policy and budget.
    #[must_use]
    pub fn request(&self, spec: &SessionSpec) -> crate::physics::plan::PlanRequest {
        crate::physics::plan::PlanRequest {
            method: spec.method,
            tolerance: spec.tolerance,
            t_end: spec.t_end,
            policy: self.policy,
            budget: self.budget,
        }
    }

    /// What was recorded for `spec`'s key, in `list`: `auto`'s plans only. A method asked by
    /// name is its own plan and never read from the book: a key does not say which method was
    /// asked, so a lecture that changed the method without changing the key (the panel's method
    /// field) replayed the first plan of its key, `auto`'s, where the lecturer had picked
    /// another method (a replay's book keeps `auto`'s lines only: `record::plan_book`).
    fn find<T: Copy>(list: &[(PlanKey, T)], spec: &SessionSpec) -> Option<T> {
        if spec.method != Method::Auto {
            return None;
        }
        let key = PlanKey::of(spec);
        list.iter().find(|(k, _)| *k == key).map(|(_, v)| *v)
    }

    /// Adds a plan resolved elsewhere (a follower's forwarded line), unless its key is known.
    pub fn add(&mut self, key: PlanKey, plan: Resolved, estimate: Option<f64>) {
        if self.recorded.iter().any(|(k, _)| *k == key) {
            return;
        }
        self.recorded.push((key, plan));
        if let Some(e) = estimate {
            self.estimates.push((key, e));
        }
    }

    pub(super) fn estimate(&self, spec: &SessionSpec) -> Option<f64> {
        Self::find(&self.estimates, spec)
    }

    pub(super) fn lookup(&self, spec: &SessionSpec) -> Option<Resolved> {
        Self::find(&self.recorded, spec)
    }

    /// Prices `auto`'s verification of `spec` against the budget (a recorded plan costs
    /// nothing): over it, `auto` is refused before it computes for minutes.
    ///
    /// # Errors
    /// [`StepError::OverBudget`].
    pub fn check_auto(&self, spec: &SessionSpec) -> Result<(), StepError> {
        if self.lookup(spec).is_some() {
            return Ok(());
        }
        let cost = spec.model.predicted_seconds(&Asked::new(
            Method::Auto,
            spec.tolerance,
            None,
            spec.t_end,
        )) + limit_cost(spec);
        crate::physics::budget::check(cost, self.budget).map_err(|over| StepError::OverBudget {
            what: "auto".to_owned(),
            over,
        })
    }

    /// The horizons `spec` is verified over: in segments for `auto` in a segmented book
    /// ([`super::segments::horizons`]), else its own end.
    #[must_use]
    pub fn horizons(&self, spec: &SessionSpec) -> Vec<f64> {
        if self.segmented && spec.method == Method::Auto {
            super::segments::horizons(spec.t_end)
        } else {
            vec![spec.t_end]
        }
    }
}

/// How runs are planned: the book of recorded plans and policy, and the predicted seconds of
/// the runs started so far (against [`PlanBook::total`]). The run and the comparison's partner
/// are planned by the same rules (a job plans with a copy, and its charge is added when it ends).
#[derive(Clone)]
pub struct Planner {
    pub(super) book: PlanBook,
    pub(super) spent: f64,
}

impl Planner {
    /// Whose elementary functions the runs take (the book's arithmetic).
    #[must_use]
    pub fn functions(&self) -> crate::physics::method::Functions {
        self.book.arithmetic.functions
    }

    /// A planner with `book`, nothing charged yet.
    #[must_use]
    pub fn new(book: PlanBook) -> Self {
        Self { book, spent: 0.0 }
    }

    /// The predicted seconds of the runs charged so far.
    #[must_use]
    pub fn spent(&self) -> f64 {
        self.spent
    }

    /// The plan `spec` integrates, with `auto`'s estimate: a recorded plan, else `auto` priced
    /// before any probe runs (as `simulate` does: a plan that would verify for minutes is
    /// refused at once) and verified, else the method asked. The scene's cost model is asked
    /// before the run starts (a plan read from a file included) and the prediction is charged
    /// to the engine's total; the limit's overlay is counted too (it may be turned on at any
    /// time), as `simulate` counts its comparison run.
    fn resolve(
        &mut self,
        spec: &SessionSpec,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<(Resolved, Option<f64>), StepError> {
        let model = &spec.model;
        let limit_cost = || limit_cost(spec);
        let (mut plan, estimate) = match self.book.lookup(spec) {
            Some(plan) => (plan, self.book.estimate(spec)),
            None if spec.method == Method::Auto => {
                self.book.check_auto(spec)?;
                let r = model.resolve(&self.book.request(spec), go_on)?;
                (r.plan, r.estimate)
            }
            None => {
                let r = model.resolve(&self.book.request(spec), go_on)?;
                (r.plan, r.estimate)
            }
        };
        // A method asked by name integrates with the preset's step, as `simulate` does.
        if spec.method != Method::Auto && spec.step.is_some() {
            plan.step = spec.step;
        }
        let predicted = model.predicted_seconds(&Asked::new(
            plan.method,
            plan.tolerance,
            plan.step,
            spec.t_end,
        )) + limit_cost();
        self.charge(plan, predicted)?;
        Ok((plan, estimate))
    }

    /// A session of `spec` stamped `generation`, on the plan `Planner::resolve` gives, with
    /// `auto`'s estimate.
    ///
    /// # Errors
    /// As `Planner::resolve`, and a plan the model cannot build.
    pub fn start(
        &mut self,
        generation: u64,
        spec: &SessionSpec,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<(Session, Option<f64>), StepError> {
        self.start_until(generation, spec, spec.t_end, go_on)
    }

    /// [`Planner::start`] on the plan verified for the horizon `until` (the first of a run
    /// verified in segments, priced alone: the engine prices the later horizons before it
    /// verifies them, and the run stops before the first over the budget).
    ///
    /// # Errors
    /// As [`Planner::start`].
    pub fn start_until(
        &mut self,
        generation: u64,
        spec: &SessionSpec,
        until: f64,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<(Session, Option<f64>), StepError> {
        let mut first = *spec;
        first.t_end = until;
        let (plan, estimate) = self.resolve(&first, go_on)?;
        Session::until(generation, *spec, plan, until, self.book.arithmetic).map(|s| (s, estimate))
    }

    /// Charges the run of a later segment's `plan` (horizon `until`) to the total, as
    /// [`Planner::resolve`] charges a run.
    pub(super) fn charge_segment(
        &mut self,
        spec: &SessionSpec,
        plan: Resolved,
        until: f64,
    ) -> Result<(), StepError> {
        let predicted = spec.model.predicted_seconds(&Asked::new(
            plan.method,
            plan.tolerance,
            plan.step,
            until,
        ));
        self.charge(plan, predicted)
    }

    /// Charges `predicted` seconds of `plan`'s run to the total: refused over the budget, or
    /// over what is left of the total.
    fn charge(&mut self, plan: Resolved, predicted: f64) -> Result<(), StepError> {
        let left = self.book.total - self.spent;
        crate::physics::budget::check(predicted, self.book.budget.min(left)).map_err(|over| {
            StepError::OverBudget {
                what: plan.method.name().to_owned(),
                over,
            }
        })?;
        self.spent += predicted;
        Ok(())
    }
}

/// Predicted seconds of the limit's overlay over `spec`'s run (it may be turned on at any time).
fn limit_cost(spec: &SessionSpec) -> f64 {
    spec.model.predicted_seconds(&Asked::new(
        Method::Effective,
        spec.model.kind().limit_tolerance(),
        None,
        spec.t_end,
    ))
}

/// Why a run was refused or failed before it started, short enough for the parameter panel at
/// 80×24.
pub(super) fn refusal(spec: &SessionSpec, e: &StepError) -> String {
    match e {
        StepError::OverBudget { over, .. } if spec.method == Method::Auto => format!(
            "auto needs about {} to verify (budget {}): pick a method in the panel or a shorter t_end",
            crate::physics::budget::duration(over.predicted),
            crate::physics::budget::duration(over.budget)
        ),
        StepError::OverBudget { what, over } => format!(
            "{what} would take about {} (budget {}): shorten t_end, loosen the tolerance or pick another method",
            crate::physics::budget::duration(over.predicted),
            crate::physics::budget::duration(over.budget)
        ),
        e => format!("planning {} failed: {e}", spec.method),
    }
}
