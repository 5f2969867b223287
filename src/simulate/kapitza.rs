//! `simulate` for Kapitza's pendulum: JSON with `params` {`a`, `b`, `epsilon`}, `final`
//! {`t`, `theta`, `theta_dot`}, `effective` {`stable_upright`, `threshold`, `energy`, `theta`,
//! `theta_dot`, …}, `events` {`swings`, `falls`}, `energy` (the full model is driven: the
//! limit's energy `E_eff` of the averaged state, and its drift), `stats`; CSV and a table too.

use crate::physics::method::Asked;
use std::fmt::Write as _;
use std::time::Instant;

use serde::Serialize;

use super::render::StatsOut;
use super::{Failure, Format, Missed, Resolved, compact, times};
use crate::physics::Method;
use crate::physics::StepError;
use crate::physics::kapitza::limit::Limit;
use crate::physics::kapitza::run::{self, RunResult, RunSpec};
use crate::physics::kapitza::{self, Problem, plan};
use crate::physics::plan::Shortfall;
use crate::scenario::Preset;

/// Predicted seconds of the run `spec` asks for (the pendulum's cost model,
/// [`kapitza::budget`]).
#[must_use]
pub fn predicted_seconds(problem: &Problem, spec: &crate::physics::rattleback::RunSpec) -> f64 {
    // The requested run, and the limit's own run the report compares it with (cheap, except
    // when `b` makes the slow motion fast too).
    kapitza::budget::cost_seconds(
        problem,
        &Asked::new(spec.method, spec.tolerance, spec.step, spec.t_end),
    ) + kapitza::budget::cost_seconds(
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
    head: super::Head<kapitza::Params, kapitza::Start, AutoOut>,
    step: Option<f64>,
    t_end: f64,
    #[serde(rename = "final")]
    final_: FinalOut,
    events: EventsOut,
    energy: EnergyOut,
    effective: EffectiveOut,
    stats: StatsOut,
}

#[derive(Serialize)]
struct AutoOut {
    choice: Method,
    reason: String,
    /// The tolerance the chosen method was run at.
    tolerance: f64,
    /// The limit's predicted model error over the run.
    predicted_model_error: f64,
    /// The error the chosen run is expected to stay within.
    error_estimate: f64,
    /// Whether `error_estimate` meets the requested tolerance.
    met: bool,
    /// Why not, when not (as the celt's).
    #[serde(skip_serializing_if = "Option::is_none")]
    shortfall: Option<Shortfall>,
}

impl super::Account for AutoOut {
    fn account(&self) -> (bool, f64, Option<Shortfall>) {
        (self.met, self.error_estimate, self.shortfall)
    }
}

#[derive(Serialize)]
struct FinalOut {
    t: f64,
    theta: f64,
    theta_dot: f64,
}

#[derive(Serialize)]
struct Times {
    count: usize,
    times: Vec<f64>,
}

#[derive(Serialize)]
struct EventsOut {
    /// Turning points of the slow motion (sign changes of the averaged rate `Θ̇`).
    swings: Times,
    /// The slow angle passing the horizontal going down (`cos Θ` turning negative).
    falls: Times,
}

#[derive(Serialize)]
struct EnergyOut {
    /// `E_eff` of the averaged start.
    initial: f64,
    #[serde(rename = "final")]
    final_: f64,
    /// Largest `|E_eff − E_eff(0)|` over the run: the limit's energy drift along the full
    /// motion (O(ε²) for a resolved run; the tolerance for the limit itself).
    max_drift: f64,
}

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

fn times_of(list: &[f64], count: usize) -> Times {
    Times {
        count,
        times: list.to_vec(),
    }
}

impl super::Finite for RunResult {
    fn named_numbers(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("theta", self.theta),
            ("theta_dot", self.theta_dot),
            ("the energy", self.energy_final),
            ("the energy", self.max_energy_drift),
        ]
    }

    fn reached(&self) -> f64 {
        self.t
    }
}

/// The concrete method and tolerance of `resolved`, with `auto`'s account.
fn plan_of(
    problem: &Problem,
    resolved: &Resolved,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunSpec, Option<AutoOut>), StepError> {
    let spec = resolved.spec;
    let mut run = RunSpec {
        method: spec.method,
        tolerance: spec.tolerance,
        step: spec.step,
        t_end: spec.t_end,
        samples: spec.samples,
    };
    if spec.method != Method::Auto {
        return Ok((run, None));
    }
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
    let reason = match (c.method, c.met) {
        (Method::EffectiveCorrected, true) => format!(
            "the limit with its ripple: its predicted model error {:.1e} is within the tolerance; cost independent of epsilon",
            c.predicted_model_error
        ),
        (Method::EffectiveCorrected, false) => format!(
            "the limit with its ripple: its predicted model error {:.1e} is above the tolerance, but a resolved run's rounding ({:.1e}) would be worse",
            c.predicted_model_error, c.estimate
        ),
        (Method::Averaged2, _) => format!(
            "the second-order averaged model: its error, checked against the limit with its ripple and a run 16x looser, is {:.1e}; cost independent of epsilon",
            c.estimate
        ),
        (_, true) => format!(
            "the full model resolved at local tolerance {:.1e}, verified against a run 16x looser: the limit's predicted model error {:.1e} exceeds the tolerance",
            c.settings.tolerance, c.predicted_model_error
        ),
        (_, false) => format!(
            "the full model resolved at local tolerance {:.1e}, but its error ({:.1e}, against a run 16x looser, with the rounding) stays above the tolerance; the limit's model error {:.1e} is larger still",
            c.settings.tolerance, c.estimate, c.predicted_model_error
        ),
    };
    Ok((
        run,
        Some(AutoOut {
            choice: c.method,
            reason,
            tolerance: c.settings.tolerance,
            predicted_model_error: c.predicted_model_error,
            error_estimate: c.estimate,
            met: c.met,
            shortfall: c.shortfall,
        }),
    ))
}

/// Runs the pendulum's preset and writes the report.
///
/// # Errors
/// As [`super::simulate_to`].
pub fn simulate_to(
    preset: &Preset,
    problem: &Problem,
    resolved: &Resolved,
    format: Format,
    out: &mut dyn std::io::Write,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Option<Missed>, Failure> {
    let (spec, auto) = plan_of(problem, resolved, progress)?;
    let missed = auto
        .as_ref()
        .and_then(|a| super::Account::missed(a, resolved.spec.tolerance));
    let clock = Instant::now();
    let result = run::run(problem, &spec, progress).and_then(super::Finite::finite)?;
    let wall_seconds = clock.elapsed().as_secs_f64();
    if format == Format::Csv {
        let head = super::csv_head(preset, resolved, spec.method, spec.t_end);
        return write_csv(problem, &head, &result, out).map(|()| missed);
    }
    let limit_spec = RunSpec {
        method: Method::Effective,
        tolerance: crate::physics::ModelKind::Kapitza.limit_tolerance(),
        step: None,
        t_end: spec.t_end,
        samples: 0,
    };
    let limit_run = run::run(problem, &limit_spec, progress).and_then(super::Finite::finite);
    let p = problem.params();
    let s = problem.start();
    let report = Report {
        head: super::Head::new(preset, (*p, *s), resolved, auto, |a| a.choice),
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
            swings: times_of(&result.events.swings, result.events.swing_count),
            falls: times_of(&result.events.falls, result.events.fall_count),
        },
        energy: EnergyOut {
            initial: result.energy_initial,
            final_: result.energy_final,
            max_drift: result.max_energy_drift,
        },
        effective: effective_out(problem, &limit_run),
        stats: StatsOut::of(&result.stats, wall_seconds),
    };
    let text = super::render::text(format, &report, || table(&report));
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(missed)
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
            |r| times_of(&r.events.swings, r.events.swing_count),
        ),
        falls: limit_run.as_ref().map_or_else(
            |_| empty(()),
            |r| times_of(&r.events.falls, r.events.fall_count),
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
        let (th, thd) =
            crate::physics::kapitza::limit::to_slow(problem.params(), s.t, (s.theta, s.theta_dot));
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
    let _ = writeln!(o, "preset        {} (Kapitza's pendulum)", r.head.preset);
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
    super::render::method_lines(
        &mut o,
        (r.head.method, r.head.tolerance, r.step),
        &compact(r.t_end),
        r.head.auto.as_ref().map(|a| super::render::Choice {
            method: a.choice,
            reason: &a.reason,
            error_estimate: a.error_estimate,
            met: a.met,
        }),
    );
    super::render::compare_rows(
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
    let _ = writeln!(o, "  full at      {}", times(&r.events.swings.times));
    let _ = writeln!(
        o,
        "falls         {:>16}    {:>16}",
        r.events.falls.count, e.falls.count
    );
    let _ = writeln!(o, "  full at      {}", times(&r.events.falls.times));
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
    super::render::work_line(&mut o, &r.stats);
    o
}
