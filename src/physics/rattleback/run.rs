//! One headless trajectory: integrate to `t_end`, collect reversals, the energy error and
//! optional samples. Used by `simulate`, the tests and the benchmarks.

use crate::physics::method::RunSpec;
use serde::Serialize;

use super::integrators;

use crate::physics::numerics::dop853::Stats;

use super::model::State;
use super::params::Problem;
use crate::physics::drive::{Course, Drift, Watch, drive};
use crate::physics::flow::Flow;
use crate::physics::method::StepError;

/// One recorded point of the trajectory.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time.
    pub t: f64,
    /// `(γ, α, γ̇, α̇)`.
    pub state: State,
}

/// The outcome of a run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunResult {
    /// Time reached (`t_end`).
    pub t: f64,
    /// State at `t`.
    pub final_state: State,
    /// Times of the spin reversals in `(0, t]`: the first [`MAX_REVERSAL_TIMES`] of them
    /// (memory stays bounded for any run length; `reversal_count` counts them all).
    pub reversals: Vec<f64>,
    /// How many spin reversals there were in `(0, t]`.
    pub reversal_count: usize,
    /// Conserved quantity at `t = 0` (energy, or `E_eff` for the effective model).
    pub energy_initial: f64,
    /// The same at `t`.
    pub energy_final: f64,
    /// Largest `|E − E0| / |E0|` seen at step ends (absolute when `E0 = 0`); 0 when not
    /// monitored.
    pub max_relative_energy_error: f64,
    /// Work counters.
    pub stats: Stats,
    /// Requested samples.
    pub samples: Vec<Sample>,
}

/// Most reversal times a run keeps (8 MB); later ones are counted only.
pub use super::effective::MAX_REVERSAL_TIMES;

/// Integrates `problem` as `spec` says.
///
/// # Errors
/// When the integrator cannot continue (step underflow, non-finite state), or for `auto`
/// ([`StepError::Unplanned`]: resolve it with `physics::plan` first).
pub fn run(problem: &Problem, spec: &RunSpec) -> Result<RunResult, StepError> {
    run_cancellable(problem, spec, &mut |_| true)
}

/// [`run`], asking `go_on(t)` every `CHECK_EVERY` steps whether to continue (`t` is the time
/// reached, for progress); the physics stays clock-free, the caller decides.
///
/// # Errors
/// As [`run`], and [`StepError::Cancelled`] when `go_on` says stop.
pub fn run_cancellable(
    problem: &Problem,
    spec: &RunSpec,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<RunResult, StepError> {
    let mut samples = Vec::with_capacity(spec.samples.min(1 << 20));
    let mut result = run_streaming(problem, spec, go_on, &mut |s| {
        samples.push(s);
        true
    })?;
    result.samples = samples;
    Ok(result)
}

/// [`run_cancellable`], handing each sample to `on_sample` as it is computed instead of
/// collecting them (the result's `samples` stays empty), so memory does not grow with
/// `spec.samples`. `on_sample` returning `false` cancels the run like `go_on` does (a closed
/// output, say).
///
/// # Errors
/// As [`run_cancellable`].
pub fn run_streaming(
    problem: &Problem,
    spec: &RunSpec,
    go_on: &mut dyn FnMut(f64) -> bool,
    on_sample: &mut dyn FnMut(Sample) -> bool,
) -> Result<RunResult, StepError> {
    let ask = spec.asked();
    let mut flow = integrators::build(problem, &ask, crate::physics::method::TimeSum::default())?;
    let cost = super::budget::cost_seconds(problem, &ask);
    let course = Course {
        event0: problem.start().alpha_dot,
        keep: MAX_REVERSAL_TIMES,
        ..Course::of(flow.as_ref(), spec.t_end, spec.samples, cost)
    };
    let mut watch = Watched {
        drift: Drift::new(flow.energy(), true),
        monitor: spec.monitor_energy,
        on_sample,
    };
    let driven = drive(flow.as_mut(), &course, go_on, &mut watch)?;
    let t = flow.time();
    let final_state = state(flow.as_mut(), t);
    let energy_final = flow.energy();
    watch.drift.see(energy_final);
    Ok(RunResult {
        t,
        final_state,
        reversals: driven.events.times,
        reversal_count: driven.events.count,
        energy_initial: watch.drift.initial,
        energy_final,
        max_relative_energy_error: watch.drift.max,
        stats: flow.stats(),
        samples: Vec::new(),
    })
}

/// The state `(γ, α, γ̇, α̇)` of a rattleback flow at `t`.
fn state(flow: &mut dyn Flow, t: f64) -> State {
    State::from_column_slice(&flow.state_at(t))
}

/// What the rattleback's run watches: the samples, handed on, and the energy's drift.
struct Watched<'a> {
    drift: Drift,
    monitor: bool,
    on_sample: &'a mut dyn FnMut(Sample) -> bool,
}

impl Watch<dyn Flow> for Watched<'_> {
    fn sample(&mut self, flow: &mut (dyn Flow + 'static), t: f64) -> bool {
        (self.on_sample)(Sample {
            t,
            state: state(flow, t),
        })
    }
    fn stepped(&mut self, flow: &mut (dyn Flow + 'static)) {
        if self.monitor {
            self.drift.see(flow.energy());
        }
    }
}
