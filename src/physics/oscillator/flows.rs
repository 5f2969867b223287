//! The oscillator's one method, DOP853, as a [`Flow`], and its run through the one runner
//! ([`crate::physics::drive`]); its `auto` through the one loop ([`crate::physics::verify`]).
use crate::physics::numerics::elementary::Elementary;

use nalgebra::SVector;

use super::Problem;
use crate::physics::drive::{Course, Drift, Watch, drive};
use crate::physics::flow::{Flow, GoOn, Sample};
use crate::physics::method::{Asked, Method, RunSpec, StepError};
use crate::physics::numerics::dop853::{Dop853, Field, Stats};
use crate::physics::numerics::roots::find_root;
use crate::physics::plan::{PlanRequest, Resolution, Resolved};
use crate::physics::verify::{AtTolerance, Policy, Rounds, verify};

/// What it offers.
pub const METHODS: [Method; 2] = [Method::Auto, Method::Dop853];

type State = SVector<f64, 2>;

#[derive(Clone)]
struct Spring(f64);

impl Field<2> for Spring {
    fn eval(&self, y: &State) -> State {
        State::new(y[1], -self.0 * self.0 * y[0])
    }
}

/// DOP853 on the oscillator.
#[derive(Clone)]
pub struct OscillatorFlow {
    problem: Problem,
    core: Dop853<2, Spring>,
}

impl OscillatorFlow {
    /// The flow at `tolerance`.
    #[must_use]
    pub fn new(problem: &Problem, tolerance: f64) -> Self {
        let s = problem.start();
        Self {
            problem: *problem,
            core: Dop853::new(
                Spring(problem.params().omega),
                0.0,
                State::new(s.x, s.v),
                tolerance,
            ),
        }
    }

    fn at(&mut self, t: f64) -> State {
        if t >= self.core.time() {
            self.core.state()
        } else {
            self.core.interpolate(t)
        }
    }
}

impl Flow for OscillatorFlow {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        Method::Dop853
    }
    fn sample(&mut self, t: f64) -> Sample {
        let y = self.at(t);
        Sample {
            q: y[0],
            q_dot: y[1],
            fast: y[0],
            lean: None,
        }
    }
    fn state_at(&mut self, t: f64) -> Vec<f64> {
        let y = self.at(t);
        vec![y[0], y[1]]
    }
    fn event_value(&self) -> f64 {
        self.core.state()[0]
    }
    fn locate_event(&mut self) -> f64 {
        let (a, b) = (self.core.time_prev(), self.core.time());
        let core = &mut self.core;
        find_root(|t| core.interpolate(t)[0], a, b)
    }
    fn energy(&self) -> f64 {
        let y = self.core.state();
        self.problem.energy(y[0], y[1])
    }
}

/// The flow `ask` names.
///
/// # Errors
/// `auto` unplanned, or a method the scene does not offer.
pub fn build(problem: &Problem, ask: &Asked) -> Result<OscillatorFlow, StepError> {
    match ask.method {
        Method::Dop853 => Ok(OscillatorFlow::new(problem, ask.tolerance)),
        Method::Auto => Err(StepError::Unplanned),
        other => Err(StepError::NotOffered {
            method: other.name(),
            model: "oscillator",
        }),
    }
}

/// A run's result.
#[derive(Clone, Debug, PartialEq)]
pub struct RunResult {
    /// Where it stopped.
    pub t: f64,
    /// `(x, v)` there.
    pub state: [f64; 2],
    /// The first crossings' times.
    pub crossings: Vec<f64>,
    /// How many.
    pub crossing_count: usize,
    /// `(t, x, v)` samples.
    pub samples: Vec<[f64; 3]>,
    /// The largest energy drift.
    pub max_energy_drift: f64,
    /// The integrator's counts.
    pub stats: Stats,
}

struct Watched {
    drift: Drift,
    samples: Vec<[f64; 3]>,
}

impl Watch<OscillatorFlow> for Watched {
    fn sample(&mut self, flow: &mut OscillatorFlow, t: f64) -> bool {
        let y = flow.at(t);
        self.samples.push([t, y[0], y[1]]);
        true
    }
    fn stepped(&mut self, flow: &mut OscillatorFlow) {
        self.drift.see(flow.energy());
    }
}

/// Runs `problem` as `spec` says.
///
/// # Errors
/// A failed or cancelled run, `auto` unplanned.
pub fn run(problem: &Problem, spec: &RunSpec, go_on: GoOn) -> Result<RunResult, StepError> {
    let ask = spec.asked();
    let mut flow = build(problem, &ask)?;
    let course = Course::of(&flow, spec.t_end, spec.samples, cost_seconds(problem, &ask));
    let s = problem.start();
    let mut watch = Watched {
        drift: Drift::new(problem.energy(s.x, s.v), false),
        samples: Vec::new(),
    };
    let driven = drive(&mut flow, &course, go_on, &mut watch)?;
    let y = flow.core.state();
    Ok(RunResult {
        t: flow.time(),
        state: [y[0], y[1]],
        crossings: driven.events.times,
        crossing_count: driven.events.count,
        samples: watch.samples,
        max_energy_drift: watch.drift.max,
        stats: flow.stats(),
    })
}

/// Predicted seconds of `ask` (about 3 evaluations a radian at tolerance 1, `tol^{-1/8}`, 50 ns
/// each; `auto` a few runs of its plan).
#[must_use]
pub fn cost_seconds(problem: &Problem, ask: &Asked) -> f64 {
    let one = |tol: f64| {
        3.0 * problem.params().omega
            * ask.t_end.max(0.0)
            * tol.clamp(1e-16, 1.0).e_powf(-0.125)
            * 5e-8
    };
    match ask.method {
        Method::Auto => 6.0 * one(ask.tolerance * 0.1),
        _ => one(ask.tolerance),
    }
}

/// The oscillator's `auto`: DOP853 against a companion 16× looser.
pub const POLICY: Policy = Policy {
    companion_looser: 16.0,
    companion_cap: 1e-2,
    companion_error: 14.0,
    refine: 0.25,
    blind_refine: 1.0 / 16.0,
    tightest: 1e-14,
    step_safety: 1.25,
    max_refinements: 4,
    stalls: 2,
    floor_stops: true,
};

#[derive(Clone)]
struct Auto {
    problem: Problem,
    t_end: f64,
}

impl AtTolerance for Auto {
    type Result = RunResult;
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn run(&self, local: f64, go_on: GoOn<'_>) -> Result<RunResult, StepError> {
        let spec = RunSpec::new(Asked::new(Method::Dop853, local, None, self.t_end), 33);
        run(&self.problem, &spec, go_on)
    }
    fn difference(&self, fine: &RunResult, coarse: &RunResult) -> f64 {
        if fine.crossing_count != coarse.crossing_count {
            return f64::INFINITY;
        }
        fine.samples
            .iter()
            .zip(&coarse.samples)
            .fold(0.0_f64, |d, (a, b)| {
                d.max((a[1] - b[1]).abs()).max((a[2] - b[2]).abs())
            })
    }
    fn floor(&self, fine: &RunResult) -> f64 {
        let steps = fine.stats.steps as f64;
        f64::EPSILON * steps * (1.0 + self.problem.params().omega)
    }
    fn run_cost(&self, local: f64) -> f64 {
        cost_seconds(
            &self.problem,
            &Asked::new(Method::Dop853, local, None, self.t_end),
        )
    }
}

/// Resolves `ask`: a named method as asked; `auto` verified by the loop.
///
/// # Errors
/// A failed or cancelled run, or work over the budget.
pub fn resolve(
    problem: &Problem,
    ask: &PlanRequest,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Resolution, StepError> {
    if ask.method != Method::Auto {
        return Ok(Resolution::named(ask.method, ask.tolerance));
    }
    let mut candidate = Auto {
        problem: *problem,
        t_end: ask.t_end,
    };
    let first = (ask.tolerance * 0.1).clamp(POLICY.tightest, 1e-3);
    let v = verify(
        &mut candidate,
        Rounds {
            first,
            tolerance: ask.tolerance,
            budget: ask.budget,
        },
        go_on,
    )?;
    Ok(Resolution {
        plan: Resolved {
            method: Method::Dop853,
            tolerance: v.last.plan,
            step: None,
        },
        estimate: Some(v.last.estimate),
        shortfall: v.shortfall,
        floor: None,
    })
}
