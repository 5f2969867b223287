//! `rattleback simulate`: one headless trajectory, reported as JSON, CSV or a table.
//!
//! The report's field names are a contract (scripts read them): add freely, rename nothing.
//! The rattleback's report is here; each other model's is in its own file (`kapitza`), reached
//! through the preset's [`crate::physics::Model`].

mod render;

/// Each scene's report (`simulate/SCENE.rs`), declared by its registry line.
macro_rules! report_modules {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $name:ident: $folder:ident, $chart:ident;
    )*) => {
        $( $(#[cfg($cfg)])? mod $folder; )*
    };
}
crate::physics::models::with_scenes!(report_modules);

use serde::Serialize;

use crate::physics::StepError;
use crate::physics::budget::{self, BUDGET_SECONDS};
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::rattleback::auto::Shortfall;
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

/// The wall clock of a report's `wall_seconds`: none in the browser's module
/// (`wasm32-unknown-unknown` has no clock; its reports say 0).
pub(crate) struct Stopwatch(#[cfg(not(target_arch = "wasm32"))] std::time::Instant);

impl Stopwatch {
    pub(crate) fn start() -> Self {
        Self(
            #[cfg(not(target_arch = "wasm32"))]
            std::time::Instant::now(),
        )
    }

    pub(crate) fn seconds(&self) -> f64 {
        #[cfg(not(target_arch = "wasm32"))]
        return self.0.elapsed().as_secs_f64();
        #[cfg(target_arch = "wasm32")]
        0.0
    }
}

/// The resolved settings of one run.
#[derive(Clone, Copy, Debug)]
pub struct Resolved {
    /// Run settings.
    pub spec: RunSpec,
    /// Work budget in predicted seconds ([`BUDGET_SECONDS`], or infinite when forced).
    pub budget: f64,
}

impl Resolved {
    /// `auto` asked of a scene planned by `physics::plan` as this run says (verified, within
    /// its budget).
    fn auto_request(&self) -> crate::physics::plan::PlanRequest {
        crate::physics::plan::PlanRequest {
            method: Method::Auto,
            tolerance: self.spec.tolerance,
            t_end: self.spec.t_end,
            policy: crate::physics::plan::AutoRules::Verified,
            budget: self.budget,
        }
    }
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
    report_of(&preset.model).predicted_seconds(&resolved.spec, format)
}

/// A scene's `simulate`: its report's sections and their price, each scene's in its file
/// (`simulate/SCENE.rs`, issue 69). No default: a scene that forgets one does not compile.
trait Report {
    /// Predicted seconds of everything the report runs for `spec` in `format`.
    fn predicted_seconds(&self, spec: &RunSpec, format: Format) -> f64;
    /// The report, as `ask` says.
    fn simulate_to(&self, ask: Ask<'_>) -> Result<Option<Missed>, Failure>;
}

/// The report of a scene's problem: the one dispatch over the scenes in this layer, generated
/// from the registry (`physics::models::with_scenes`).
macro_rules! report_dispatch {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $name:ident: $folder:ident, $chart:ident;
    )*) => {
        /// The report of `model`'s scene.
        fn report_of(model: &crate::physics::Model) -> &dyn Report {
            match model {
                $( $(#[cfg($cfg)])? crate::physics::Model::$name(p) => p, )*
            }
        }
    };
}
crate::physics::models::with_scenes!(report_dispatch);

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
        let clock = Stopwatch::start();
        let result = run(problem, &spec, self.progress).and_then(Finite::finite)?;
        Ok(Ran {
            spec,
            auto,
            missed,
            result,
            wall_seconds: clock.seconds(),
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

impl<X> PlannedOut<X> {
    /// `auto`'s account of the plan `r` that `physics::plan` resolved, `reason` its words;
    /// `run` becomes the plan.
    fn of(
        r: &crate::physics::plan::Resolution,
        run: &mut RunSpec,
        reason: impl FnOnce(bool) -> String,
        extra: X,
    ) -> Self {
        run.method = r.plan.method;
        run.tolerance = r.plan.tolerance;
        let met = r.shortfall.is_none();
        Self {
            choice: r.plan.method,
            reason: reason(met),
            tolerance: r.plan.tolerance,
            extra,
            error_estimate: r.estimate.unwrap_or(f64::INFINITY),
            met,
            shortfall: r.shortfall,
        }
    }
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
    report_of(&preset.model).simulate_to(ask)
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
        // Every scene's CSV names its model, the rattleback's too (issue 68).
        Some(kind.name()),
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

/// The `# key = value` lines every model's CSV starts with: the program, the model, the preset's name cleaned to one line, the method asked and the
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
