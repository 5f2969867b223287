//! `rattleback simulate`: one headless trajectory, reported as JSON, CSV or a table.
//!
//! The report's field names are a contract (scripts read them): add freely, rename nothing.
//! The rattleback's report is here; each other model's is in its own file (`kapitza`), reached
//! through the preset's [`crate::physics::Model`].

mod celt;
mod kapitza;
mod render;

use crate::physics::method::Asked;
use render::StatsOut;

use crate::physics::rattleback::model::{ALPHA, ALPHA_DOT, GAMMA, GAMMA_DOT};
use std::fmt::Write as _;
use std::time::Instant;

use serde::Serialize;

use crate::physics::StepError;
use crate::physics::budget::{self, BUDGET_SECONDS};
use crate::physics::method::Method;
use crate::physics::rattleback::RunSpec;
use crate::physics::rattleback::auto::{Shortfall, run_auto_cancellable};
use crate::physics::rattleback::averaged::Averaged2;
use crate::physics::rattleback::budget::cost_seconds;
use crate::physics::rattleback::effective::{Effective, tapping_acceleration};
use crate::physics::rattleback::model::energy;
use crate::physics::rattleback::plan;
use crate::physics::rattleback::run::{RunResult, run_cancellable, run_streaming};
use crate::scenario::Preset;

/// Tolerance when neither the command line nor the preset gives one.
pub const DEFAULT_TOLERANCE: f64 = crate::physics::DEFAULT_TOLERANCE;
/// Method when neither the command line nor the preset names one.
pub const DEFAULT_METHOD: Method = Method::Auto;

/// Output format of `simulate`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// One JSON object.
    Json,
    /// The sampled trajectory as CSV.
    Csv,
    /// A summary for people.
    Table,
}

/// What the command line asks of one run (each absent value falls back to the preset).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Request {
    /// Method.
    pub method: Option<Method>,
    /// Tolerance.
    pub tolerance: Option<f64>,
    /// Fixed step.
    pub step: Option<f64>,
    /// Final time.
    pub t_end: Option<f64>,
    /// Output format.
    pub format: Format,
    /// Samples of the CSV output.
    pub samples: u32,
    /// Run even when the work is predicted over [`BUDGET_SECONDS`].
    pub force: bool,
}

/// The resolved settings of one run.
#[derive(Clone, Copy, Debug)]
pub struct Resolved {
    /// Run settings.
    pub spec: RunSpec,
    /// Work budget in predicted seconds ([`BUDGET_SECONDS`], or infinite when forced).
    pub budget: f64,
}

/// Combines the preset's `[run]` section with command-line flags (flags win).
#[must_use]
pub fn resolve(preset: &Preset, args: &Request) -> Resolved {
    let method = args.method.or(preset.run.method).unwrap_or(DEFAULT_METHOD);
    let tolerance = args
        .tolerance
        .or(preset.run.tolerance)
        .unwrap_or(DEFAULT_TOLERANCE);
    let t_end = args.t_end.unwrap_or(preset.run.t_end);
    let step = if method.is_fixed_step() {
        Some(
            args.step
                .or(preset.run.step)
                .unwrap_or_else(|| preset.model.default_step(method, tolerance, t_end)),
        )
    } else {
        None
    };
    let samples = if args.format == Format::Csv {
        args.samples as usize
    } else {
        0
    };
    Resolved {
        spec: RunSpec {
            method,
            tolerance,
            step,
            t_end,
            samples,
            monitor_energy: true,
        },
        budget: if args.force {
            f64::INFINITY
        } else {
            BUDGET_SECONDS
        },
    }
}

/// Predicted seconds of everything `simulate` would run for `resolved` in `format`: the run
/// (for `auto`, planned and verified), then the limit's comparison run (JSON, table) or the
/// streamed rerun of `auto`'s plan (CSV).
#[must_use]
pub fn predicted_seconds(preset: &Preset, resolved: &Resolved, format: Format) -> f64 {
    let spec = resolved.spec;
    let problem = match &preset.model {
        crate::physics::Model::Rattleback(p) => p,
        crate::physics::Model::Kapitza(p) => return kapitza::predicted_seconds(p, &spec),
        crate::physics::Model::Celt(p) => return celt::predicted_seconds(p, &spec),
    };
    let main = plan::predicted_seconds(
        problem,
        &Asked::new(spec.method, spec.tolerance, spec.step, spec.t_end),
    );
    let extra = match format {
        Format::Csv if spec.method == Method::Auto => main / (1.0 + plan::VERIFY_FRACTION),
        Format::Csv => 0.0,
        Format::Json | Format::Table => cost_seconds(
            problem,
            &Asked::new(Method::Effective, spec.tolerance, None, spec.t_end),
        ),
    };
    main + extra
}

/// Why `simulate` produced no (complete) output.
#[derive(Debug, thiserror::Error)]
pub enum Failure {
    /// The integration failed, was refused by the work budget, or produced a non-finite number.
    #[error("{0}")]
    Run(#[from] StepError),
    /// The output could not be written (a closed pipe, a full disk).
    #[error("writing the output: {0}")]
    Output(#[from] std::io::Error),
}

/// The version of `simulate --format json`'s reports (both scenes), whose JSON Schemas live in
/// `docs/schemas/` and are checked against real reports by `tests/it/schemas.rs`. Raised when a
/// field is renamed, removed or changes meaning; adding a field does not raise it.
pub const SCHEMA_VERSION: u32 = 1;

/// What every scene's report starts with, flattened into it (the JSON keeps its keys and order).
#[derive(Serialize)]
struct Head<P, S, A> {
    /// [`SCHEMA_VERSION`]: `docs/schemas/simulate-MODEL.schema.json` describes the report.
    schema_version: u32,
    /// Which scene: `rattleback`, `kapitza` or `celt` (second in every JSON output).
    model: &'static str,
    preset: String,
    params: P,
    initial: S,
    method: Method,
    /// With `method = auto`: the method it chose (also in `auto.choice`).
    #[serde(skip_serializing_if = "Option::is_none")]
    auto_choice: Option<Method>,
    #[serde(skip_serializing_if = "Option::is_none")]
    auto: Option<A>,
    tolerance: f64,
}

impl<P, S, A: Account> Head<P, S, A> {
    /// The head of `preset`'s report, asked as `resolved` says, with `auto`'s account.
    fn new(
        preset: &Preset,
        (params, initial): (P, S),
        resolved: &Resolved,
        auto: Option<A>,
    ) -> Self {
        Self {
            schema_version: SCHEMA_VERSION,
            model: preset.model.kind().name(),
            preset: preset.name.clone(),
            params,
            initial,
            method: resolved.spec.method,
            auto_choice: auto.as_ref().map(|a| a.choice().method),
            auto,
            tolerance: resolved.spec.tolerance,
        }
    }

    /// The table's method line and, for `auto`, the line saying what it chose.
    fn method_lines(&self, o: &mut String, step: Option<f64>, t_end: &str) {
        render::method_lines(
            o,
            (self.method, self.tolerance, step),
            t_end,
            self.auto.as_ref().map(Account::choice),
        );
    }
}

/// What a scene's planned run gives its report: the run that was made and `auto`'s account
/// (none for another method), the shortfall, the result and its wall time.
struct Ran<S, A, R> {
    spec: S,
    auto: Option<A>,
    missed: Option<Missed>,
    result: R,
    wall_seconds: f64,
}

/// A report asked of a scene: its preset as `resolved` says, in `format`, to `out`, with
/// `progress` called as the runs go (and cancelling them when it returns `false`).
struct Ask<'a> {
    preset: &'a Preset,
    resolved: &'a Resolved,
    format: Format,
    out: &'a mut dyn std::io::Write,
    progress: &'a mut dyn FnMut(f64) -> bool,
}

impl Ask<'_> {
    /// Runs `problem` as `spec` says, `auto` first resolved by `plan` (which makes `spec`
    /// concrete and gives its account), and checks that every number of the result is
    /// finite.
    fn plan_and_run<P, S, A: Account, R: Finite>(
        &mut self,
        (problem, mut spec): (&P, S),
        plan: impl FnOnce(&P, &Resolved, &mut S, &mut dyn FnMut(f64) -> bool) -> Result<A, StepError>,
        run: impl FnOnce(&P, &S, &mut dyn FnMut(f64) -> bool) -> Result<R, StepError>,
    ) -> Result<Ran<S, A, R>, Failure> {
        let auto = if self.resolved.spec.method == Method::Auto {
            Some(plan(problem, self.resolved, &mut spec, self.progress)?)
        } else {
            None
        };
        let missed = auto
            .as_ref()
            .and_then(|a| a.missed(self.resolved.spec.tolerance));
        let clock = Instant::now();
        let result = run(problem, &spec, self.progress).and_then(Finite::finite)?;
        Ok(Ran {
            spec,
            auto,
            missed,
            result,
            wall_seconds: clock.elapsed().as_secs_f64(),
        })
    }

    /// The report's head: the scene's parameters and start, and `auto`'s account.
    fn head<P, S, A: Account>(&self, params_start: (P, S), auto: Option<A>) -> Head<P, S, A> {
        Head::new(self.preset, params_start, self.resolved, auto)
    }

    /// The CSV's metadata lines for a run by `ran` to `t_end`.
    fn csv_head(&self, ran: Method, t_end: f64) -> String {
        csv_head(self.preset, self.resolved, ran, t_end)
    }

    /// Writes `report` in the asked format (`table` renders it for people) and flushes.
    fn write<T: Serialize>(
        &mut self,
        report: &T,
        table: impl FnOnce(&T) -> String,
    ) -> Result<(), Failure> {
        let text = render::text(self.format, report, || table(report));
        self.out.write_all(text.as_bytes())?;
        self.out.flush()?;
        Ok(())
    }
}

/// A run's result, which holds only finite numbers before it is reported.
trait Finite: Sized {
    /// The time the run reached, and its numbers, each with the name an error gives it, in
    /// the order they are checked.
    fn named_numbers(&self) -> (f64, Vec<(&'static str, f64)>);
    /// `self`, or the error naming its first number that is not finite.
    fn finite(self) -> Result<Self, StepError> {
        let (t, numbers) = self.named_numbers();
        match numbers.into_iter().find(|(_, x)| !x.is_finite()) {
            Some((what, _)) => Err(StepError::NotFinite { what, t }),
            None => Ok(self),
        }
    }
}

#[derive(Serialize)]
struct Report {
    #[serde(flatten)]
    head: Head<ParamsOut, crate::physics::rattleback::Start, AutoOut>,
    step: Option<f64>,
    t_end: f64,
    #[serde(rename = "final")]
    final_: FinalOut,
    reversals: Times,
    energy: EnergyOut,
    effective: EffectiveOut,
    #[serde(skip_serializing_if = "Option::is_none")]
    averaged: Option<AveragedOut>,
    stats: StatsOut,
}

#[derive(Serialize)]
struct AutoOut {
    choice: Method,
    reason: String,
    tolerance: f64,
    step: Option<f64>,
    predicted_error: f64,
    /// Bounds the error of `α(T)`, `α̇(T)` and the reversal times (model error included),
    /// unless `met` is false.
    error_estimate: f64,
    /// Whether `error_estimate` meets the requested tolerance.
    met: bool,
    /// Why not (`floor`, `clamped`, `refinements`, `time`), or null.
    shortfall: Option<Shortfall>,
    /// The averaged model's probed error included in the estimate (0 for a resolved run).
    model_error: f64,
    refinements: u32,
    /// The start's condition numbers (`rate`: per relative change of the spin rate; `angle`:
    /// per radian of the spin angle) that scale the round-off floor in `error_estimate`, times
    /// `margin` (1 where measured at this `k`; 50 where bounded by the start's reading at its
    /// conditioning stiffness, kept across `k`).
    condition: crate::physics::rattleback::auto::Conditioning,
    /// The part of `error_estimate` that rounding alone sets (no refinement lowers it; above
    /// the tolerance, `auto` stops after its first run with `shortfall = floor`).
    round_off_floor: f64,
}

/// The averaged model's own account of the start (method `averaged2` or `averaged3`, or `auto`
/// choosing one): the second-order account, good to O(k⁻²), for either.
#[derive(Serialize)]
struct AveragedOut {
    /// The averaged fast action `Ī`, an exact constant of the averaged motion.
    ibar: f64,
    /// `θ̄ = Ī √k`.
    theta_bar: f64,
    /// The averaged Hamiltonian `K̄` of the start.
    kbar: f64,
    regime: &'static str,
    /// Averaged time between turning points (trapped starts).
    half_period: Option<f64>,
}

impl AveragedOut {
    fn of(problem: &crate::physics::rattleback::Problem) -> Self {
        let (m, y0) = Averaged2::new(problem);
        Self {
            ibar: m.ibar(),
            theta_bar: m.theta_bar(),
            kbar: m.kbar(y0[0], y0[1]),
            regime: m.regime(&y0).name(),
            half_period: m.half_period(&y0),
        }
    }
}

impl Account for AutoOut {
    /// Met exactly when there is no shortfall.
    fn account(&self) -> (bool, f64, Option<Shortfall>) {
        (
            self.shortfall.is_none(),
            self.error_estimate,
            self.shortfall,
        )
    }

    fn choice(&self) -> render::Choice<'_> {
        render::Choice::new(self.choice, &self.reason, self.error_estimate, self.met)
    }

    fn floor(&self) -> Option<f64> {
        Some(self.round_off_floor)
    }
}

/// `auto`'s account in the report of a scene planned by [`crate::physics::plan`] (the pendulum
/// and the celt; the rattleback's has fields and an order of its own): `extra` holds the
/// scene's own fields, between the tolerance and the estimate.
#[derive(Serialize)]
struct PlannedOut<X> {
    choice: Method,
    reason: String,
    /// The tolerance the chosen run was integrated at.
    tolerance: f64,
    #[serde(flatten)]
    extra: X,
    /// The error the chosen run is expected to stay within.
    error_estimate: f64,
    /// Whether `error_estimate` meets the requested tolerance.
    met: bool,
    /// Why not, when not.
    #[serde(skip_serializing_if = "Option::is_none")]
    shortfall: Option<Shortfall>,
}

impl<X> Account for PlannedOut<X> {
    fn account(&self) -> (bool, f64, Option<Shortfall>) {
        (self.met, self.error_estimate, self.shortfall)
    }

    fn choice(&self) -> render::Choice<'_> {
        render::Choice::new(self.choice, &self.reason, self.error_estimate, self.met)
    }
}

/// `auto` fell short of the tolerance: what `simulate` warns about (and `--strict` fails on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Missed {
    /// The estimate reached.
    pub estimate: f64,
    /// The tolerance asked for.
    pub tolerance: f64,
    /// Why.
    pub why: Shortfall,
    /// The part of the estimate that rounding alone sets, where the scene measures it.
    pub floor: Option<f64>,
}

/// A scene's account of `auto` in its report, as far as a shortfall is concerned.
trait Account {
    /// Whether it met the tolerance, its estimate, and why not.
    fn account(&self) -> (bool, f64, Option<Shortfall>);

    /// What it chose and why, for the table (and the report's `auto_choice`).
    fn choice(&self) -> render::Choice<'_>;

    /// The part of the estimate that rounding alone sets, where the scene measures it.
    fn floor(&self) -> Option<f64> {
        None
    }

    /// The shortfall unless it met `tolerance` (`why` defaults to the round-off floor).
    fn missed(&self, tolerance: f64) -> Option<Missed> {
        let (met, estimate, why) = self.account();
        (!met).then(|| Missed {
            estimate,
            tolerance,
            why: why.unwrap_or(Shortfall::Floor),
            floor: self.floor(),
        })
    }
}

impl std::fmt::Display for Missed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let estimate = if self.estimate.is_finite() {
            format!("its error estimate is {:.1e}", self.estimate)
        } else {
            "it has no error estimate".to_owned()
        };
        write!(
            f,
            "auto could not meet the tolerance {:e}: {estimate} ({}",
            self.tolerance,
            self.why.describe()
        )?;
        match self.floor {
            Some(floor) if self.why == Shortfall::Floor => {
                write!(f, "; rounding alone accounts for {floor:.1e} of it)")
            }
            _ => write!(f, ")"),
        }
    }
}

#[derive(Serialize)]
struct ParamsOut {
    ix: f64,
    iy: f64,
    iz: f64,
    k: f64,
}

#[derive(Serialize)]
struct FinalOut {
    t: f64,
    gamma: f64,
    alpha: f64,
    gamma_dot: f64,
    alpha_dot: f64,
}

/// Events in a report: `times` holds the first ones (as many as the run kept), `count` all.
#[derive(Serialize)]
struct Times {
    count: usize,
    times: Vec<f64>,
}

impl Times {
    fn of(times: &[f64], count: usize) -> Self {
        Self {
            count,
            times: times.to_vec(),
        }
    }
}

#[derive(Serialize)]
struct EnergyOut {
    initial: f64,
    #[serde(rename = "final")]
    final_: f64,
    max_relative_error: f64,
    /// Whether the energy drifted past what the method's tolerance promises (see
    /// [`energy_bound`]): the run is not to be trusted, and stderr says so.
    exceeds_bound: bool,
}

impl EnergyOut {
    fn of(result: &crate::physics::rattleback::RunResult, tolerance: f64) -> Self {
        Self {
            initial: result.energy_initial,
            final_: result.energy_final,
            max_relative_error: result.max_relative_energy_error,
            exceeds_bound: result.max_relative_energy_error > energy_bound(tolerance),
        }
    }
}

/// Says on stderr that a run's energy drifted past [`energy_bound`].
fn warn_energy(energy: &EnergyOut, tolerance: f64) {
    if energy.exceeds_bound {
        warn_drift(
            "the energy",
            energy.max_relative_error,
            energy_bound(tolerance),
            tolerance,
        );
    }
}

/// The one warning of every scene for a run that cannot be accurate: `what` (a conserved
/// quantity, relative) drifted by `drift`, more than the `bound` a run at `tolerance` can be
/// trusted with.
pub(super) fn warn_drift(what: &str, drift: f64, bound: f64, tolerance: f64) {
    crate::scenario::text::warn(&format!(
        "rattleback: warning: {what} drifted by {drift:.1e} (relative), more than the {bound:.0e} a run at tolerance {tolerance:e} can be trusted with: the result is not accurate (a smaller --step, a tighter --tolerance, or --method auto)"
    ));
}

/// The largest relative energy error a run at `tolerance` may show and still be trusted: ten
/// thousand times the tolerance (the energy's error stays within a few hundred times it on
/// every shipped preset and on long runs of every method at its default step), between 1e-8 and
/// 1e-3 (beyond that the trajectory means nothing, whatever was asked).
#[must_use]
pub fn energy_bound(tolerance: f64) -> f64 {
    (1e4 * tolerance).clamp(1e-8, 1e-3)
}

#[derive(Serialize)]
struct EffectiveOut {
    theta: f64,
    regime: &'static str,
    critical_ratio: Option<f64>,
    start_ratio: Option<f64>,
    energy: f64,
    /// The limit's own `α(T)`; `null` only when its comparison run failed (`comparison_error`).
    alpha: Option<f64>,
    /// The limit's own `α̇(T)`, likewise.
    alpha_dot: Option<f64>,
    /// Why the comparison with the limit could not be made (the requested run succeeded).
    #[serde(skip_serializing_if = "Option::is_none")]
    comparison_error: Option<String>,
    half_period: Option<f64>,
    turning_points: Option<(f64, f64)>,
    tapping_acceleration: f64,
    reversals: Times,
}

/// Runs `preset` as `resolved` says and renders the report in `format` (CSV included: this
/// holds it all in memory; the command streams it with [`simulate_to`]).
///
/// # Errors
/// As [`simulate_to`].
pub fn simulate(preset: &Preset, resolved: &Resolved, format: Format) -> Result<String, Failure> {
    let mut out = Vec::new();
    simulate_to(preset, resolved, format, &mut out, &mut |_| true)?;
    Ok(String::from_utf8_lossy(&out).into_owned())
}

/// Runs `preset` as `resolved` says and writes the report in `format` to `out`; the CSV is
/// written sample by sample as the integration goes, so memory does not grow with
/// `--samples`. `progress(t)` is called every few hundred steps with the time reached (it
/// restarts from 0 for each of `auto`'s runs) and may cancel by returning `false`.
///
/// Nothing starts when the work is predicted over `resolved.budget`
/// ([`StepError::OverBudget`]); `auto` also checks each of its verification runs.
///
/// Returns `auto`'s shortfall when it could not meet the tolerance (the output is complete and
/// says so too: `auto.met = false`); `None` when it met it or another method ran.
///
/// # Errors
/// The integration failed or was refused, a result is not a finite number (an error naming
/// it, never a NaN in the output), or `out` failed.
///
/// # Panics
/// Never in practice: the report holds only finite numbers and strings, which serialize.
pub fn simulate_to(
    preset: &Preset,
    resolved: &Resolved,
    format: Format,
    out: &mut dyn std::io::Write,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Option<Missed>, Failure> {
    within_budget(preset, resolved, format)?;
    let ask = Ask {
        preset,
        resolved,
        format,
        out,
        progress,
    };
    match &preset.model {
        crate::physics::Model::Rattleback(p) => rattleback_to(p, ask),
        crate::physics::Model::Kapitza(p) => kapitza::simulate_to(p, ask),
        crate::physics::Model::Celt(p) => celt::simulate_to(p, ask),
    }
}

/// The rattleback's report (see [`simulate_to`]).
fn rattleback_to(
    problem: &crate::physics::rattleback::Problem,
    mut ask: Ask<'_>,
) -> Result<Option<Missed>, Failure> {
    let (preset, resolved) = (ask.preset, ask.resolved);
    let spec = resolved.spec;
    let clock = Instant::now();
    if ask.format == Format::Csv {
        let (result, shortfall) = csv(preset, problem, resolved, ask.out, ask.progress)?;
        result.finite()?;
        ask.out.flush()?;
        return Ok(shortfall);
    }
    let (result, auto) = requested_run(problem, resolved, ask.progress)?;
    let result = result.finite()?;
    let wall_seconds = clock.elapsed().as_secs_f64();
    // The limit's own trajectory at t_end, for comparison (cheap: cost independent of k).
    let eff_spec = RunSpec {
        method: Method::Effective,
        tolerance: crate::physics::ModelKind::Rattleback.limit_tolerance(),
        samples: 0,
        monitor_energy: true,
        step: None,
        ..spec
    };
    // A failure of this extra comparison does not discard the requested run: it is reported.
    let eff_run = run_cancellable(problem, &eff_spec, ask.progress).and_then(Finite::finite);
    let eff = Effective::new(problem);
    let p = problem.params();
    let y = result.final_state;
    let ran = auto.as_ref().map_or(spec.method, |a| a.choice);
    let averaged = ran.is_averaged().then(|| AveragedOut::of(problem));
    let shortfall = auto.as_ref().and_then(|a| a.missed(spec.tolerance));
    let step = auto.as_ref().map_or(spec.step, |a| a.step);
    let params = ParamsOut {
        ix: p.ix,
        iy: p.iy,
        iz: p.iz,
        k: p.k,
    };
    let report = Report {
        head: ask.head((params, *problem.start()), auto),
        step,
        t_end: spec.t_end,
        final_: FinalOut {
            t: result.t,
            gamma: y[GAMMA],
            alpha: y[ALPHA],
            gamma_dot: y[GAMMA_DOT],
            alpha_dot: y[ALPHA_DOT],
        },
        reversals: Times::of(&result.reversals, result.reversal_count),
        energy: EnergyOut::of(&result, spec.tolerance),
        effective: EffectiveOut {
            theta: eff.theta(),
            regime: eff.regime().name(),
            critical_ratio: eff.critical_ratio(problem),
            start_ratio: eff.start_ratio(problem),
            energy: eff.energy(),
            alpha: eff_run.as_ref().ok().map(|r| r.final_state[ALPHA]),
            alpha_dot: eff_run.as_ref().ok().map(|r| r.final_state[ALPHA_DOT]),
            comparison_error: eff_run.as_ref().err().map(ToString::to_string),
            half_period: eff.half_period(),
            turning_points: eff.turning_points(),
            tapping_acceleration: tapping_acceleration(problem),
            reversals: Times::of(
                &eff.reversal_times(spec.t_end),
                eff.reversal_count(spec.t_end),
            ),
        },
        averaged,
        stats: StatsOut::of(&result.stats, wall_seconds),
    };
    warn_energy(&report.energy, spec.tolerance);
    ask.write(&report, table)?;
    Ok(shortfall)
}

/// Refuses, before anything runs, work predicted over the budget.
pub(crate) fn within_budget(
    preset: &Preset,
    resolved: &Resolved,
    format: Format,
) -> Result<(), StepError> {
    let spec = resolved.spec;
    budget::check(predicted_seconds(preset, resolved, format), resolved.budget).map_err(|over| {
        StepError::OverBudget {
            what: format!(
                "this run ({}, t_end = {})",
                spec.method,
                compact(spec.t_end)
            ),
            over,
        }
    })
}

/// The requested run, and `auto`'s account of it.
fn requested_run(
    problem: &crate::physics::rattleback::Problem,
    resolved: &Resolved,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunResult, Option<AutoOut>), StepError> {
    let spec = resolved.spec;
    if spec.method != Method::Auto {
        return Ok((run_cancellable(problem, &spec, progress)?, None));
    }
    let v = run_auto_cancellable(problem, &spec, resolved.budget, progress)?;
    let auto = AutoOut {
        choice: v.plan.method,
        reason: v.plan.reason.clone(),
        tolerance: v.plan.tolerance,
        step: v.plan.step,
        predicted_error: v.plan.predicted_error,
        error_estimate: v.error_estimate,
        met: v.met,
        shortfall: v.shortfall,
        model_error: v.model_error,
        refinements: v.refinements,
        condition: v.condition,
        round_off_floor: v.round_off_floor,
    };
    Ok((v.result, Some(auto)))
}

/// What a CSV of a run starts with: `# key = value` lines (the program, the model unless it is
/// the default, the preset's name, the method asked and the one that ran, the tolerance, the
/// horizon, then every parameter of the model's table, every number as text that parses back
/// to the same bits), so the file says what made it. `simulate --format csv` and the
/// explorer's export (`x`) write the same lines.
#[must_use]
pub fn csv_metadata_of(
    preset: &str,
    model: &crate::physics::Model,
    method: Method,
    ran: Option<Method>,
    tolerance: f64,
    t_end: f64,
) -> String {
    let kind = model.kind();
    let mut numbers = vec![("tolerance", tolerance), ("t_end", t_end)];
    numbers.extend(kind.params().iter().map(|p| p.key).zip(model.values()));
    metadata_lines(
        preset,
        kind.scene().model_required.then(|| kind.name()),
        method,
        ran,
        &numbers,
    )
}

/// [`csv_metadata_of`] for `preset` run as `resolved` asks, by `ran` to `t_end`.
fn csv_head(preset: &Preset, resolved: &Resolved, ran: Method, t_end: f64) -> String {
    csv_metadata_of(
        &preset.name,
        &preset.model,
        resolved.spec.method,
        Some(ran),
        resolved.spec.tolerance,
        t_end,
    )
}

/// The `# key = value` lines every model's CSV starts with: the program, the model (absent for
/// the rattleback, the first), the preset's name cleaned to one line, the method asked and the
/// one that ran, then `numbers` as text that parses back to the same bits.
pub(crate) fn metadata_lines(
    preset: &str,
    model: Option<&str>,
    method: Method,
    ran: Option<Method>,
    numbers: &[(&str, f64)],
) -> String {
    use std::fmt::Write as _;
    let name = crate::scenario::text::one_line(&crate::scenario::text::shown(preset));
    let mut out = format!("# program = rattleback {}\n", env!("CARGO_PKG_VERSION"));
    if let Some(m) = model {
        let _ = writeln!(out, "# model = {m}");
    }
    let _ = writeln!(out, "# preset = {name}\n# method = {}", method.name());
    if let Some(m) = ran {
        let _ = writeln!(out, "# integrated = {}", m.name());
    }
    for (key, value) in numbers {
        let _ = writeln!(out, "# {key} = {value:?}");
    }
    out
}

/// Streams the CSV: `auto` is planned and verified first (no samples), then its plan is run
/// again with the samples, which gives the verified run bit for bit.
fn csv(
    preset: &Preset,
    problem: &crate::physics::rattleback::Problem,
    resolved: &Resolved,
    out: &mut dyn std::io::Write,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunResult, Option<Missed>), Failure> {
    let mut spec = resolved.spec;
    let mut shortfall = None;
    if spec.method == Method::Auto {
        let resolution = plan::resolve(
            problem,
            spec.method,
            spec.tolerance,
            spec.t_end,
            crate::physics::plan::AutoPolicy::Verified,
            resolved.budget,
            progress,
        )?;
        shortfall = resolution.shortfall.map(|why| Missed {
            estimate: resolution.estimate.unwrap_or(f64::NAN),
            tolerance: spec.tolerance,
            why,
            floor: resolution.floor,
        });
        let plan = resolution.plan;
        spec.method = plan.method;
        spec.tolerance = plan.tolerance;
        spec.step = plan.step;
    }
    let p = problem.params();
    out.write_all(csv_head(preset, resolved, spec.method, spec.t_end).as_bytes())?;
    out.write_all(b"t,gamma,alpha,gamma_dot,alpha_dot,energy\n")?;
    let mut failure: Option<Failure> = None;
    let result = run_streaming(problem, &spec, progress, &mut |s| {
        let y = s.state;
        let e = energy(p, &y);
        if let Some(i) = y.iter().position(|x| !x.is_finite()) {
            failure = Some(
                StepError::NotFinite {
                    what: STATE_NAMES[i],
                    t: s.t,
                }
                .into(),
            );
            return false;
        }
        match writeln!(
            out,
            "{},{},{},{},{},{}",
            s.t, y[GAMMA], y[ALPHA], y[GAMMA_DOT], y[ALPHA_DOT], e
        ) {
            Ok(()) => true,
            Err(err) => {
                failure = Some(err.into());
                false
            }
        }
    });
    match (result, failure) {
        (_, Some(f)) => Err(f),
        (r, None) => Ok((r?, shortfall)),
    }
}

/// `30`, `1000`, `1e9`, `1e100`: plain below a million, scientific above.
pub(crate) fn compact(x: f64) -> String {
    if x.abs() < 1e6 {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

fn opt(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_owned(), |x| format!("{x:.9}"))
}

pub(crate) fn times(t: &[f64]) -> String {
    const SHOWN: usize = 8;
    let mut s: Vec<String> = t.iter().take(SHOWN).map(|x| format!("{x:.6}")).collect();
    if t.len() > SHOWN {
        s.push(format!("… ({} more)", t.len() - SHOWN));
    }
    s.join(", ")
}

fn table(r: &Report) -> String {
    let mut o = String::new();
    let e = &r.effective;
    let _ = writeln!(
        o,
        "preset        {}",
        crate::scenario::text::one_line(&r.head.preset)
    );
    let _ = writeln!(
        o,
        "body          ix = {}, iy = {}, iz = {}, k = {:e}",
        r.head.params.ix, r.head.params.iy, r.head.params.iz, r.head.params.k
    );
    let _ = writeln!(
        o,
        "start         gamma = {}, alpha = {}, gamma_dot = {}, alpha_dot = {}",
        r.head.initial.gamma,
        r.head.initial.alpha,
        r.head.initial.gamma_dot,
        r.head.initial.alpha_dot
    );
    r.head.method_lines(&mut o, r.step, &r.t_end.to_string());
    render::compare_rows(
        &mut o,
        "effective (k → ∞)",
        crate::physics::ModelKind::Rattleback.words(),
        (r.final_.alpha, r.final_.alpha_dot),
        (e.alpha, e.alpha_dot),
        e.comparison_error.as_deref(),
    );
    let _ = writeln!(
        o,
        "reversals     {:>16}    {:>16}",
        r.reversals.count, e.reversals.count
    );
    let _ = writeln!(o, "  full at      {}", times(&r.reversals.times));
    let _ = writeln!(o, "  limit at     {}", times(&e.reversals.times));
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "regime        {} (ratio {} vs critical {})",
        e.regime,
        opt(e.start_ratio),
        opt(e.critical_ratio)
    );
    let _ = writeln!(o, "theta         {:.12}", e.theta);
    let _ = writeln!(o, "half period   {}", opt(e.half_period));
    // `+ 0.0` prints a negative zero as 0.
    let _ = writeln!(o, "tapping acc.  {:.9}", e.tapping_acceleration + 0.0);
    let _ = writeln!(
        o,
        "energy        {:.12} (max relative error {:.2e})",
        r.energy.initial, r.energy.max_relative_error
    );
    render::work_line(&mut o, &r.stats);
    o
}

const STATE_NAMES: [&str; 4] = ["gamma", "alpha", "gamma_dot", "alpha_dot"];

impl Finite for RunResult {
    fn named_numbers(&self) -> (f64, Vec<(&'static str, f64)>) {
        let state = STATE_NAMES
            .into_iter()
            .zip(self.final_state.iter().copied());
        let energy = [self.energy_final, self.max_relative_energy_error].map(|e| ("the energy", e));
        let reversals = self.reversals.iter().map(|&t| ("a reversal time", t));
        (self.t, state.chain(energy).chain(reversals).collect())
    }
}
