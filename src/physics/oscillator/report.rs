//! `simulate` for the scene contract's oscillator (the library's own tests only): JSON with the
//! head, `final` {`t`, `x`, `v`}, `exact` {`x`, `v`} and the error against it, `events`
//! {`crossings`}, `energy`, `stats`; CSV `t,x,v`; a table.

use std::fmt::Write as _;

use serde::Serialize;

use crate::physics::method::{Asked, RunSpec};
use crate::physics::oscillator::flows::{self, RunResult};
use crate::physics::oscillator::{Params, Problem, Start};
use crate::physics::report::{
    Ask, Failure, Finite, Format, Head, Missed, PlannedOut, Resolved, Times, render,
};

#[derive(Serialize)]
struct Report {
    #[serde(flatten)]
    head: Head<Params, Start, AutoOut>,
    t_end: f64,
    #[serde(rename = "final")]
    final_: [f64; 2],
    exact: [f64; 2],
    error: f64,
    events: Times,
    max_energy_drift: f64,
    stats: render::StatsOut,
}

type AutoOut = PlannedOut<NoExtra>;

#[derive(Serialize)]
struct NoExtra {}

impl Finite for RunResult {
    fn named_numbers(&self) -> (f64, Vec<(&'static str, f64)>) {
        (
            self.t,
            vec![("the state", self.state[0]), ("the state", self.state[1])],
        )
    }
}

fn plan_auto(
    problem: &Problem,
    resolved: &Resolved,
    run: &mut RunSpec,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<AutoOut, crate::physics::StepError> {
    let r = flows::resolve(problem, &resolved.auto_request(), progress)?;
    let reason = |_| format!("dop853 at local tolerance {:.1e}", r.plan.tolerance);
    Ok(AutoOut::of(&r, run, reason, NoExtra {}))
}

fn simulate_to(problem: &Problem, mut ask: Ask<'_>) -> Result<Option<Missed>, Failure> {
    let ran = ask.plan_and_run((problem, ask.resolved.spec), plan_auto, flows::run)?;
    let (spec, result) = (ran.spec, ran.result);
    if ask.format == Format::Csv {
        let head = ask.csv_head(spec.method, spec.t_end);
        ask.out.write_all(head.as_bytes())?;
        ask.out.write_all(b"t,x,v\n")?;
        for s in &result.samples {
            writeln!(ask.out, "{},{},{}", s[0], s[1], s[2])?;
        }
        ask.out.flush()?;
        return Ok(ran.missed);
    }
    let (x, v) = problem.exact(result.t);
    let report = Report {
        head: ask.head((*problem.params(), *problem.start()), ran.auto),
        t_end: spec.t_end,
        final_: result.state,
        exact: [x, v],
        error: (result.state[0] - x).abs().max((result.state[1] - v).abs()),
        events: Times::of(&result.crossings, result.crossing_count),
        max_energy_drift: result.max_energy_drift,
        stats: render::StatsOut::of(&result.stats, ran.wall_seconds),
    };
    ask.write(&report, table)?;
    Ok(ran.missed)
}

fn table(r: &Report) -> String {
    let mut o = format!("oscillator to t = {}\n", r.t_end);
    let _ = writeln!(o, "final      x {} v {}", r.final_[0], r.final_[1]);
    let _ = writeln!(o, "exact      x {} v {}", r.exact[0], r.exact[1]);
    let _ = writeln!(o, "error      {:.1e}", r.error);
    o
}

impl crate::physics::report::Report for Problem {
    fn predicted_seconds(&self, spec: &RunSpec, _format: Format) -> f64 {
        flows::cost_seconds(
            self,
            &Asked::new(spec.method, spec.tolerance, None, spec.t_end),
        )
    }

    fn simulate_to(&self, ask: Ask<'_>) -> Result<Option<Missed>, Failure> {
        simulate_to(self, ask)
    }
}
