//! What every scene's `simulate` report is made of (issue 83: a scene's report is its folder's
//! `report.rs`): the format asked, the run resolved, the head every report starts with,
//! `auto`'s account, events, the work counters and the table's shared lines
//! ([`render`]), and [`Ask`], what a report is asked and writes to. Nothing here opens a file,
//! reads a clock or writes to a terminal: the command that asks for a report does that for it
//! through its [`Host`] (`simulate`'s: the preset, the clock, warnings, the text cleaned for a
//! terminal or a JSON file).

pub mod render;

use serde::Serialize;

use super::StepError;
use super::method::{Method, RunSpec};
use super::plan::Shortfall;

/// What the command asking for a report does for it: the preset's words, the clock, the
/// warnings and the cleaning of text from files (`simulate`'s host).
pub trait Host {
    /// The scene's name (`rattleback`, `kapitza`, `celt`).
    fn model(&self) -> &'static str;
    /// The preset's name, as read.
    fn preset(&self) -> &str;
    /// The preset's name on one line, cleaned of control characters (for a table).
    fn preset_line(&self) -> String;
    /// JSON text with every control character escaped.
    fn json_safe(&self, json: &str) -> String;
    /// The CSV's metadata lines for a run by `ran` to `t_end`.
    fn csv_head(&self, ran: Method, t_end: f64) -> String;
    /// Seconds of wall time since the host began (0 where there is no clock).
    fn seconds(&self) -> f64;
    /// Says `text` to the person running the command (a warning).
    fn warn(&self, text: &str);
}

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

/// The resolved settings of one run.
#[derive(Clone, Copy, Debug)]
pub struct Resolved {
    /// Run settings.
    pub spec: RunSpec,
    /// Work budget in predicted seconds ([`BUDGET_SECONDS`](super::budget::BUDGET_SECONDS), or infinite when forced).
    pub budget: f64,
}

impl Resolved {
    /// `auto` asked of a scene planned by `physics::plan` as this run says (verified, within
    /// its budget).
    pub(crate) fn auto_request(&self) -> crate::physics::plan::PlanRequest {
        crate::physics::plan::PlanRequest {
            method: Method::Auto,
            tolerance: self.spec.tolerance,
            t_end: self.spec.t_end,
            policy: crate::physics::plan::AutoRules::Verified,
            budget: self.budget,
        }
    }
}

/// A scene's `simulate`: its report's sections and their price, each scene's in its folder
/// (`NAME/report.rs`, issue 83). No default: a scene that forgets one does not compile.
pub trait Report {
    /// Predicted seconds of everything the report runs for `spec` in `format`.
    fn predicted_seconds(&self, spec: &RunSpec, format: Format) -> f64;
    /// The report, as `ask` says.
    fn simulate_to(&self, ask: Ask<'_>) -> Result<Option<Missed>, Failure>;
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
pub(crate) struct Head<P, S, A> {
    /// [`SCHEMA_VERSION`]: `docs/schemas/simulate-MODEL.schema.json` describes the report.
    pub(crate) schema_version: u32,
    /// Which scene: `rattleback`, `kapitza` or `celt` (second in every JSON output).
    pub(crate) model: &'static str,
    pub(crate) preset: String,
    /// The preset's name on one line, cleaned for a terminal (the table's).
    #[serde(skip)]
    pub(crate) preset_line: String,
    pub(crate) params: P,
    pub(crate) initial: S,
    pub(crate) method: Method,
    /// With `method = auto`: the method it chose (also in `auto.choice`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) auto_choice: Option<Method>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) auto: Option<A>,
    pub(crate) tolerance: f64,
}

impl<P, S, A: Account> Head<P, S, A> {
    /// The head of `preset`'s report, asked as `resolved` says, with `auto`'s account.
    pub(crate) fn new(
        host: &dyn Host,
        (params, initial): (P, S),
        resolved: &Resolved,
        auto: Option<A>,
    ) -> Self {
        Self {
            schema_version: SCHEMA_VERSION,
            model: host.model(),
            preset: host.preset().to_owned(),
            preset_line: host.preset_line(),
            params,
            initial,
            method: resolved.spec.method,
            auto_choice: auto.as_ref().map(|a| a.choice().method),
            auto,
            tolerance: resolved.spec.tolerance,
        }
    }

    /// The table's method line and, for `auto`, the line saying what it chose.
    pub(crate) fn method_lines(&self, o: &mut String, step: Option<f64>, t_end: &str) {
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
pub(crate) struct Ran<S, A, R> {
    pub(crate) spec: S,
    pub(crate) auto: Option<A>,
    pub(crate) missed: Option<Missed>,
    pub(crate) result: R,
    pub(crate) wall_seconds: f64,
}

/// A report asked of a scene: its preset as `resolved` says, in `format`, to `out`, with
/// `progress` called as the runs go (and cancelling them when it returns `false`).
pub struct Ask<'a> {
    /// What the command writing the report does for it.
    pub(crate) host: &'a dyn Host,
    pub(crate) resolved: &'a Resolved,
    pub(crate) format: Format,
    pub(crate) out: &'a mut dyn std::io::Write,
    pub(crate) progress: &'a mut dyn FnMut(f64) -> bool,
}

impl Ask<'_> {
    /// Runs `problem` as `spec` says, `auto` first resolved by `plan` (which makes `spec`
    /// concrete and gives its account), and checks that every number of the result is
    /// finite.
    pub(crate) fn plan_and_run<P, S, A: Account, R: Finite>(
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
        let start = self.host.seconds();
        let result = run(problem, &spec, self.progress).and_then(Finite::finite)?;
        Ok(Ran {
            spec,
            auto,
            missed,
            result,
            wall_seconds: self.host.seconds() - start,
        })
    }

    /// The report's head: the scene's parameters and start, and `auto`'s account.
    pub(crate) fn head<P, S, A: Account>(
        &self,
        params_start: (P, S),
        auto: Option<A>,
    ) -> Head<P, S, A> {
        Head::new(self.host, params_start, self.resolved, auto)
    }

    /// The CSV's metadata lines for a run by `ran` to `t_end`.
    pub(crate) fn csv_head(&self, ran: Method, t_end: f64) -> String {
        self.host.csv_head(ran, t_end)
    }

    /// Writes `report` in the asked format (`table` renders it for people) and flushes.
    pub(crate) fn write<T: Serialize>(
        &mut self,
        report: &T,
        table: impl FnOnce(&T) -> String,
    ) -> Result<(), Failure> {
        let text = match self.format {
            Format::Json => {
                let json = serde_json::to_string_pretty(report).expect("report serializes");
                let mut s = self.host.json_safe(&json);
                s.push('\n');
                s
            }
            Format::Table | Format::Csv => table(report),
        };
        self.out.write_all(text.as_bytes())?;
        self.out.flush()?;
        Ok(())
    }
}

/// A run's result, which holds only finite numbers before it is reported.
pub(crate) trait Finite: Sized {
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
pub(crate) struct PlannedOut<X> {
    pub(crate) choice: Method,
    pub(crate) reason: String,
    /// The tolerance the chosen run was integrated at.
    pub(crate) tolerance: f64,
    #[serde(flatten)]
    pub(crate) extra: X,
    /// The error the chosen run is expected to stay within.
    pub(crate) error_estimate: f64,
    /// Whether `error_estimate` meets the requested tolerance.
    pub(crate) met: bool,
    /// Why not, when not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) shortfall: Option<Shortfall>,
}

impl<X> PlannedOut<X> {
    /// `auto`'s account of the plan `r` that `physics::plan` resolved, `reason` its words;
    /// `run` becomes the plan.
    pub(crate) fn of(
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
pub(crate) trait Account {
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
pub(crate) struct Times {
    pub(crate) count: usize,
    pub(crate) times: Vec<f64>,
}

impl Times {
    pub(crate) fn of(times: &[f64], count: usize) -> Self {
        Self {
            count,
            times: times.to_vec(),
        }
    }
}

/// The one warning of every scene for a run that cannot be accurate: `what` (a conserved
/// quantity, relative) drifted by `drift`, more than the `bound` a run at `tolerance` can be
/// trusted with.
pub(crate) fn warn_drift(host: &dyn Host, what: &str, drift: f64, bound: f64, tolerance: f64) {
    host.warn(&format!(
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

/// `30`, `1000`, `1e9`, `1e100`: plain below a million, scientific above.
pub(crate) fn compact(x: f64) -> String {
    if x.abs() < 1e6 {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

pub(crate) fn opt(v: Option<f64>) -> String {
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
