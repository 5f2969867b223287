//! `simulate` for Kapitza's pendulum: JSON with `params` {`a`, `b`, `epsilon`}, `final`
//! {`t`, `theta`, `theta_dot`}, `effective` {`stable_upright`, `threshold`, `energy`, `theta`,
//! `theta_dot`, …}, `events` {`swings`, `falls`}, `energy` (the full model is driven: the
//! limit's energy `E_eff` of the averaged state, and its drift), `stats`; CSV and a table too.

use crate::physics::method::Asked;
use std::fmt::Write as _;

use serde::Serialize;

use crate::physics::Method;
use crate::physics::StepError;
use crate::physics::kapitza::limit::Limit;
use crate::physics::kapitza::run::{self, RunResult};
use crate::physics::kapitza::{self, FastPhase, Problem, plan};
use crate::physics::method::RunSpec;
use crate::physics::report::{
    Ask, Failure, Finite, Format, Head, Host, Missed, PlannedOut, Resolved, Times, compact,
    energy_bound, render, times, warn_drift,
};

/// Predicted seconds of the run `spec` asks for (the pendulum's cost model,
/// [`kapitza::budget`]).
#[must_use]
pub fn predicted_seconds(problem: &Problem, spec: &crate::physics::method::RunSpec) -> f64 {
    // The requested run, and the limit's own run the report compares it with (cheap, except
    // when `b` makes the slow motion fast too).
    kapitza::plan::predicted_seconds(problem, &spec.asked())
        + kapitza::budget::cost_seconds(
            problem,
            &Asked::new(
                Method::Effective,
                crate::physics::ModelKind::Kapitza.limit_tolerance(),
                None,
                spec.t_end,
            ),
        )
}

#[derive(Serialize)]
struct Report {
    #[serde(flatten)]
    head: Head<kapitza::Params, kapitza::Start, AutoOut>,
    step: Option<f64>,
    t_end: f64,
    #[serde(rename = "final")]
    final_: FinalOut,
    events: EventsOut,
    energy: EnergyOut,
    effective: EffectiveOut,
    stats: render::StatsOut,
}

/// `auto`'s account, with the limit's predicted model error over the run.
type AutoOut = PlannedOut<ModelErrorOut>;

#[derive(Serialize)]
struct ModelErrorOut {
    /// The limit's predicted model error over the run.
    predicted_model_error: f64,
}

#[derive(Serialize)]
struct FinalOut {
    t: f64,
    theta: f64,
    theta_dot: f64,
}

#[derive(Serialize)]
struct EventsOut {
    /// Turning points of the slow motion (sign changes of the averaged rate `Θ̇`).
    swings: Times,
    /// The slow angle passing the horizontal going down (`cos Θ` turning negative).
    falls: Times,
}

/// `E_eff` of the averaged start and at the end; `max_drift` the largest `|E_eff − E_eff(0)|`
/// over the run: the limit's energy drift along the full motion (O(ε²) for a resolved run; the
/// tolerance for the limit itself). No relative drift.
type EnergyOut = render::DriftOut;

#[derive(Serialize)]
struct EffectiveOut {
    /// `b² > 2a`.
    stable_upright: bool,
    /// `b² − 2a`.
    threshold: f64,
    /// `E_eff` of the start `(θ0, θ̇0)`.
    energy: f64,
    /// The limit's own `θ(T)` from `(θ0, θ̇0)`; null only when its run failed.
    theta: Option<f64>,
    /// The limit's own `θ̇(T)`.
    theta_dot: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    comparison_error: Option<String>,
    /// Angular frequency of small oscillations about the upright, when stable.
    upright_frequency: Option<f64>,
    /// Equilibria in `[0, π]` with their stability.
    equilibria: Vec<EquilibriumOut>,
    /// `E_eff` levels of the separatrices.
    separatrices: Vec<f64>,
    swings: Times,
    falls: Times,
}

#[derive(Serialize)]
struct EquilibriumOut {
    theta: f64,
    stable: bool,
}

impl Finite for RunResult {
    fn named_numbers(&self) -> (f64, Vec<(&'static str, f64)>) {
        let numbers = vec![
            ("theta", self.theta),
            ("theta_dot", self.theta_dot),
            ("the energy", self.energy_final),
            ("the energy", self.max_energy_drift),
        ];
        (self.t, numbers)
    }
}

/// Resolves `auto` into the concrete method and tolerance of `run`, and gives its account.
fn plan_auto(
    problem: &Problem,
    resolved: &Resolved,
    run: &mut RunSpec,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<AutoOut, StepError> {
    let spec = resolved.spec;
    let c = plan::verified(
        problem,
        spec.tolerance,
        spec.t_end,
        resolved.budget,
        progress,
    )?;
    run.method = c.method;
    run.tolerance = c.settings.tolerance;
    run.step = None;
    let slow = kapitza::policy::SLOW.companion_looser;
    let resolved_looser = kapitza::policy::POLICY.companion_looser;
    let against = plan::checked_against(problem, c.method);
    let short = if c.met {
        ""
    } else {
        ", above the tolerance, and nothing came closer"
    };
    let reason = match c.method {
        Method::EffectiveCorrected | Method::Averaged2 | Method::Averaged3 => format!(
            "{}: its error, checked against {against} and a run {slow}x looser, is {:.1e}{short}; cost independent of epsilon",
            match c.method {
                Method::EffectiveCorrected => "the limit with its ripple",
                Method::Averaged2 => "the second-order averaged model",
                _ => "the third-order averaged model",
            },
            c.estimate
        ),
        _ if c.met => format!(
            "the full model resolved at local tolerance {:.1e}, verified against a run {resolved_looser}x looser: the slow models cannot meet the tolerance (the limit's predicted model error is {:.1e})",
            c.settings.tolerance, c.predicted_model_error
        ),
        _ => format!(
            "the full model resolved at local tolerance {:.1e}, but its error ({:.1e}, against a run {resolved_looser}x looser, with the rounding) stays above the tolerance; the slow models came no closer",
            c.settings.tolerance, c.estimate
        ),
    };
    Ok(AutoOut {
        choice: c.method,
        reason,
        tolerance: c.settings.tolerance,
        extra: ModelErrorOut {
            predicted_model_error: c.predicted_model_error,
        },
        error_estimate: c.estimate,
        met: c.met,
        shortfall: c.shortfall,
    })
}

/// Runs the pendulum's preset and writes the report.
///
/// # Errors
/// The pendulum's report (`simulate`).
pub(super) fn simulate_to(problem: &Problem, mut ask: Ask<'_>) -> Result<Option<Missed>, Failure> {
    let ran = ask.plan_and_run((problem, ask.resolved.spec), plan_auto, run::run)?;
    let (spec, result) = (ran.spec, ran.result);
    warn_inaccurate(ask.host, problem, &result, spec.tolerance);
    if ask.format == Format::Csv {
        let head = ask.csv_head(spec.method, spec.t_end);
        return write_csv(problem, &head, &result, ask.out).map(|()| ran.missed);
    }
    let limit_spec = RunSpec {
        method: Method::Effective,
        tolerance: crate::physics::ModelKind::Kapitza.limit_tolerance(),
        step: None,
        t_end: spec.t_end,
        samples: 0,
        monitor_energy: true,
    };
    let limit_run = run::run(problem, &limit_spec, ask.progress).and_then(Finite::finite);
    let p = problem.params();
    let s = problem.start();
    let report = Report {
        head: ask.head((*p, *s), ran.auto),
        step: spec.method.is_fixed_step().then(|| {
            spec.step.unwrap_or_else(|| {
                kapitza::flows::default_step(spec.method, problem, spec.tolerance, spec.t_end)
            })
        }),
        t_end: spec.t_end,
        final_: FinalOut {
            t: result.t,
            theta: result.theta,
            theta_dot: result.theta_dot,
        },
        events: EventsOut {
            swings: Times::of(&result.events.swings, result.events.swing_count),
            falls: Times::of(&result.events.falls, result.events.fall_count),
        },
        energy: EnergyOut {
            initial: result.energy_initial,
            final_: result.energy_final,
            max_drift: result.max_energy_drift,
            rel_drift: None,
        },
        effective: effective_out(problem, &limit_run),
        stats: render::StatsOut::of(&result.stats, ran.wall_seconds),
    };
    ask.write(&report, table)?;
    Ok(ran.missed)
}

/// Says on stderr when a run cannot be accurate (a fixed step too long for the fast forcing,
/// issue 56), as the rattleback does: the limit's energy `E_eff` of the averaged state drifts by
/// about ε² of itself in an accurate run (the averaging's own error: at most 6ε² on the shipped
/// presets); a drift more than a hundred times that, and past what the tolerance promises, is
/// the integration's.
fn warn_inaccurate(host: &dyn Host, problem: &Problem, result: &RunResult, tolerance: f64) {
    let eps = problem.params().epsilon;
    let scale = result.energy_initial.abs().max(1.0);
    let drift = result.max_energy_drift / scale;
    let bound = energy_bound(tolerance).max(100.0 * eps * eps);
    if drift.is_nan() || drift > bound {
        warn_drift(host, "the limit's energy E_eff", drift, bound, tolerance);
    }
}

/// The limit's account of the start, and its own run (`limit_run`) to `t_end`.
fn effective_out(problem: &Problem, limit_run: &Result<RunResult, StepError>) -> EffectiveOut {
    let p = problem.params();
    let s = problem.start();
    let limit = Limit::new(p);
    let empty = |()| Times {
        count: 0,
        times: Vec::new(),
    };
    EffectiveOut {
        stable_upright: p.stable_upright(),
        threshold: p.threshold(),
        energy: limit.energy_of(s.theta, s.theta_dot),
        theta: limit_run.as_ref().ok().map(|r| r.theta),
        theta_dot: limit_run.as_ref().ok().map(|r| r.theta_dot),
        comparison_error: limit_run.as_ref().err().map(ToString::to_string),
        upright_frequency: limit.upright_frequency(),
        equilibria: limit
            .equilibria()
            .iter()
            .map(|e| EquilibriumOut {
                theta: e.theta,
                stable: e.stable,
            })
            .collect(),
        separatrices: limit.separatrices(),
        swings: limit_run.as_ref().map_or_else(
            |_| empty(()),
            |r| Times::of(&r.events.swings, r.events.swing_count),
        ),
        falls: limit_run.as_ref().map_or_else(
            |_| empty(()),
            |r| Times::of(&r.events.falls, r.events.fall_count),
        ),
    }
}

/// The samples as CSV after `head`: `t,theta,theta_dot,energy` (the limit's `E_eff` of the
/// averaged state).
fn write_csv(
    problem: &Problem,
    head: &str,
    result: &RunResult,
    out: &mut dyn std::io::Write,
) -> Result<(), Failure> {
    out.write_all(head.as_bytes())?;
    out.write_all(b"t,theta,theta_dot,energy\n")?;
    let limit = Limit::new(problem.params());
    for s in &result.samples {
        let (th, thd) = crate::physics::kapitza::limit::to_slow(
            problem.params(),
            FastPhase::default(),
            s.t,
            (s.theta, s.theta_dot),
        );
        writeln!(
            out,
            "{},{},{},{}",
            s.t,
            s.theta,
            s.theta_dot,
            limit.energy_of(th, thd)
        )?;
    }
    out.flush()?;
    Ok(())
}

fn table(r: &Report) -> String {
    let mut o = String::new();
    let e = &r.effective;
    let _ = writeln!(
        o,
        "preset        {} (Kapitza's pendulum)",
        r.head.preset_line
    );
    let _ = writeln!(
        o,
        "pendulum      a = {}, b = {}, epsilon = {:e}",
        r.head.params.a, r.head.params.b, r.head.params.epsilon
    );
    let _ = writeln!(
        o,
        "start         theta = {}, theta_dot = {}",
        r.head.initial.theta, r.head.initial.theta_dot
    );
    r.head.method_lines(&mut o, r.step, &compact(r.t_end));
    render::compare_rows(
        &mut o,
        "limit (ε → 0)",
        crate::physics::ModelKind::Kapitza.words(),
        (r.final_.theta, r.final_.theta_dot),
        (e.theta, e.theta_dot),
        e.comparison_error.as_deref(),
    );
    let _ = writeln!(
        o,
        "swings        {:>16}    {:>16}",
        r.events.swings.count, e.swings.count
    );
    event_times(&mut o, &r.events.swings.times, &e.swings.times);
    let _ = writeln!(
        o,
        "falls         {:>16}    {:>16}",
        r.events.falls.count, e.falls.count
    );
    event_times(&mut o, &r.events.falls.times, &e.falls.times);
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "upright       {} (b^2 - 2a = {:.6})",
        if e.stable_upright {
            "stable"
        } else {
            "unstable"
        },
        e.threshold
    );
    let _ = writeln!(
        o,
        "E_eff         {:.12} (drift along the run {:.2e})",
        r.energy.initial, r.energy.max_drift
    );
    render::work_line(&mut o, &r.stats);
    o
}

/// The `full at` and `limit at` lines of a count, each only when it has a time (issue 68: an
/// empty `full at` line said nothing).
fn event_times(o: &mut String, full: &[f64], limit: &[f64]) {
    if !full.is_empty() {
        let _ = writeln!(o, "  full at      {}", times(full));
    }
    if !limit.is_empty() {
        let _ = writeln!(o, "  limit at     {}", times(limit));
    }
}

impl crate::physics::report::Report for Problem {
    fn predicted_seconds(&self, spec: &RunSpec, _format: Format) -> f64 {
        predicted_seconds(self, spec)
    }

    fn simulate_to(&self, ask: Ask<'_>) -> Result<Option<Missed>, Failure> {
        simulate_to(self, ask)
    }
}
