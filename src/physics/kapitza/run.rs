//! One headless run of the pendulum: integrate to `t_end`, find the events, report the
//! limit's energy drift and optional samples. Used by `simulate`, the tests and the benchmarks.
//!
//! Events (both in `(0, t_end]`, at most [`MAX_EVENT_TIMES`] times kept of each):
//! - **swings**: turning points of the slow motion, sign changes of the averaged rate `Θ̇`
//!   (the full `θ̇` changes sign twice per fast period; `Θ̇` only where the pendulum turns);
//! - **falls**: the slow angle leaving the upper half, `cos Θ` going from positive to negative
//!   (the pendulum passes the horizontal on its way down).

use serde::Serialize;

use super::Problem;
use super::flows::build;
use crate::physics::flow::CHECK_EVERY;
use crate::physics::flow::{EventTracker, Flow};
use crate::physics::method::{Method, Settings, StepError};
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::roots::find_root;

/// Most event times kept of each kind; later ones are counted only.
pub const MAX_EVENT_TIMES: usize = 100_000;

/// What to run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RunSpec {
    /// A concrete method (resolve `auto` with [`super::plan::resolve`] first).
    pub method: Method,
    /// Tolerance or the default step's target.
    pub tolerance: f64,
    /// Fixed step, for fixed-step methods.
    pub step: Option<f64>,
    /// Final time.
    pub t_end: f64,
    /// Evenly spaced samples over `[0, t_end]` to record.
    pub samples: usize,
}

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

/// Integrates `problem` as `spec` says, asking `go_on(t)` every [`CHECK_EVERY`] steps.
///
/// # Errors
/// When the integrator cannot continue, for `auto` ([`StepError::Unplanned`]), for a method
/// the model does not offer, and [`StepError::Cancelled`] when `go_on` says stop.
pub fn run(
    problem: &Problem,
    spec: &RunSpec,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<RunResult, StepError> {
    let settings = Settings {
        tolerance: spec.tolerance,
        step: spec.step,
    };
    let mut flow = build(spec.method, problem, settings, spec.t_end)?;
    let mut swings = EventTracker::new(flow.event_value());
    let e0 = flow.energy();
    let mut max_drift: f64 = 0.0;
    let mut events = Events::default();
    // `cos Θ` with `Θ = θ − ripple`, as the explorer counts falls from its samples.
    let slow_up = |flow: &mut dyn Flow, t: f64| {
        let y = flow.sample(t);
        (y.q - y.fast).cos()
    };
    let mut up = slow_up(flow.as_mut(), 0.0);
    let mut samples = Vec::with_capacity(spec.samples.min(1 << 20));
    let mut next_sample = 0usize;
    #[allow(clippy::cast_precision_loss)]
    let sample_time = |i: usize| {
        if spec.samples <= 1 {
            spec.t_end
        } else {
            spec.t_end * i as f64 / (spec.samples - 1) as f64
        }
    };
    let mut steps = 0u64;
    let cap = crate::physics::method::StepCap::of(super::budget::cost_seconds(
        problem,
        spec.method,
        spec.tolerance,
        spec.step,
        spec.t_end,
    ));
    loop {
        while next_sample < spec.samples && sample_time(next_sample) <= flow.time() {
            let t = sample_time(next_sample);
            let y = flow.state_at(t);
            samples.push(Sample {
                t,
                theta: y[0],
                theta_dot: y[1],
            });
            next_sample += 1;
        }
        if flow.time() >= spec.t_end {
            break;
        }
        flow.step(spec.t_end)?;
        steps += 1;
        if steps.is_multiple_of(CHECK_EVERY) && !go_on(flow.time()) {
            return Err(StepError::Cancelled { t: flow.time() });
        }
        cap.check(steps, flow.time())?;
        if let Some(t) = swings.after_step(flow.as_mut()) {
            events.swing_count += 1;
            if events.swings.len() < MAX_EVENT_TIMES {
                events.swings.push(t);
            }
        }
        let t_now = flow.time();
        let now = slow_up(flow.as_mut(), t_now);
        if up > 0.0 && now < 0.0 {
            let (a, b) = (flow.time_prev(), flow.time());
            let t = find_root(|t| slow_up(flow.as_mut(), t), a, b);
            events.fall_count += 1;
            if events.falls.len() < MAX_EVENT_TIMES {
                events.falls.push(t);
            }
        }
        if now != 0.0 {
            up = now;
        }
        max_drift = max_drift.max((flow.energy() - e0).abs());
    }
    let y = flow.state_at(flow.time());
    Ok(RunResult {
        method: flow.method(),
        t: flow.time(),
        theta: y[0],
        theta_dot: y[1],
        events,
        energy_initial: e0,
        energy_final: flow.energy(),
        max_energy_drift: max_drift,
        stats: flow.stats(),
        samples,
    })
}
