//! One headless run of the pendulum: integrate to `t_end`, find the events, report the
//! limit's energy drift and optional samples. Used by `simulate`, the tests and the benchmarks.
//!
//! Events (both in `(0, t_end]`, at most [`MAX_EVENT_TIMES`] times kept of each):
//! - **swings**: turning points of the slow motion, sign changes of the averaged rate `Θ̇`
//!   (the full `θ̇` changes sign twice per fast period; `Θ̇` only where the pendulum turns);
//! - **falls**: the slow angle leaving the upper half, `cos Θ` going from positive to negative
//!   (the pendulum passes the horizontal on its way down).
use crate::physics::numerics::elementary::Elementary;

use crate::physics::method::RunSpec;
use serde::Serialize;

use super::flows::build;
use super::{FastPhase, Problem};
use crate::physics::drive::{Counted, Course, Drift, Watch, drive};
use crate::physics::flow::{Flow, GoOn};
use crate::physics::method::{Method, StepError};
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::roots::find_root;

/// Most event times kept of each kind; later ones are counted only.
pub const MAX_EVENT_TIMES: usize = crate::physics::drive::KEPT;

/// One recorded point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time.
    pub t: f64,
    /// `θ`.
    pub theta: f64,
    /// `θ̇`.
    pub theta_dot: f64,
}

/// The events of a run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Events {
    /// Times of the slow motion's turning points (the first [`MAX_EVENT_TIMES`]).
    pub swings: Vec<f64>,
    /// How many.
    pub swing_count: usize,
    /// Times the slow angle passed the horizontal going down (the first [`MAX_EVENT_TIMES`]).
    pub falls: Vec<f64>,
    /// How many.
    pub fall_count: usize,
}

/// The outcome of a run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunResult {
    /// The method that integrated.
    pub method: Method,
    /// Time reached.
    pub t: f64,
    /// `θ` at `t`.
    pub theta: f64,
    /// `θ̇` at `t`.
    pub theta_dot: f64,
    /// Swings and falls.
    pub events: Events,
    /// The limit's energy `E_eff` of the averaged start.
    pub energy_initial: f64,
    /// The same at `t` (of the averaged state the method reports).
    pub energy_final: f64,
    /// Largest `|E_eff − E_eff(0)|` over step ends (absolute: `E_eff` can vanish).
    pub max_energy_drift: f64,
    /// Work counters.
    pub stats: Stats,
    /// Requested samples.
    pub samples: Vec<Sample>,
}

/// Integrates `problem` as `spec` says, asking `go_on(t)` every `CHECK_EVERY` steps.
///
/// # Errors
/// When the integrator cannot continue, for `auto` ([`StepError::Unplanned`]), for a method
/// the model does not offer, and [`StepError::Cancelled`] when `go_on` says stop.
pub fn run(problem: &Problem, spec: &RunSpec, go_on: GoOn) -> Result<RunResult, StepError> {
    let ask = spec.asked();
    let mut flow = build(problem, &ask, FastPhase::default())?;
    let cost = super::budget::cost_seconds(problem, &ask);
    let course = Course::of(flow.as_ref(), spec.t_end, spec.samples, cost);
    let mut watch = Watched {
        drift: Drift::new(flow.energy(), false),
        monitor: spec.monitor_energy,
        up: slow_up(flow.as_mut(), 0.0),
        falls: Counted::default(),
        samples: Vec::with_capacity(spec.samples.min(1 << 20)),
    };
    let driven = drive(flow.as_mut(), &course, go_on, &mut watch)?;
    let t = flow.time();
    let y = flow.state_at(t);
    Ok(RunResult {
        method: flow.method(),
        t,
        theta: y[0],
        theta_dot: y[1],
        events: Events {
            swings: driven.events.times,
            swing_count: driven.events.count,
            falls: watch.falls.times,
            fall_count: watch.falls.count,
        },
        energy_initial: watch.drift.initial,
        energy_final: flow.energy(),
        max_energy_drift: watch.drift.max,
        stats: flow.stats(),
        samples: watch.samples,
    })
}

/// `cos Θ` with `Θ = θ − ripple`, as the explorer counts falls from its samples.
fn slow_up(flow: &mut dyn Flow, t: f64) -> f64 {
    let y = flow.sample(t);
    (y.q - y.fast).e_cos()
}

/// What the pendulum's run watches: the samples, the falls and the limit's energy drift.
struct Watched {
    drift: Drift,
    /// Whether the drift is followed (`RunSpec::monitor_energy`).
    monitor: bool,
    /// `cos Θ` at the last step's end that was not 0.
    up: f64,
    falls: Counted,
    samples: Vec<Sample>,
}

impl Watch<dyn Flow> for Watched {
    fn sample(&mut self, flow: &mut (dyn Flow + 'static), t: f64) -> bool {
        let y = flow.state_at(t);
        self.samples.push(Sample {
            t,
            theta: y[0],
            theta_dot: y[1],
        });
        true
    }
    fn stepped(&mut self, flow: &mut (dyn Flow + 'static)) {
        let t_now = flow.time();
        let now = slow_up(flow, t_now);
        if self.up > 0.0 && now < 0.0 {
            let (a, b) = (flow.time_prev(), flow.time());
            self.falls
                .push(find_root(|t| slow_up(flow, t), a, b), MAX_EVENT_TIMES);
        }
        if now != 0.0 {
            self.up = now;
        }
        if self.monitor {
            self.drift.see(flow.energy());
        }
    }
}
