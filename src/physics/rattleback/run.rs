//! One headless trajectory: integrate to `t_end`, collect reversals, the energy error and
//! optional samples. Used by `simulate`, the tests and the benchmarks.

use serde::Serialize;

use super::integrators::reversals::ReversalTracker;
use super::integrators::{self, Method, Settings, Stats, StepError};
use super::model::State;
use super::params::Problem;
use crate::physics::flow::CHECK_EVERY;

/// What to run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RunSpec {
    /// The integrator.
    pub method: Method,
    /// Tolerance (adaptive methods) or the default step's target (fixed-step methods).
    pub tolerance: f64,
    /// Fixed step, for fixed-step methods; `None` derives it from `tolerance`.
    pub step: Option<f64>,
    /// Final time.
    pub t_end: f64,
    /// Evenly spaced samples over `[0, t_end]` to record (0: none, so none are computed).
    pub samples: usize,
    /// Whether to evaluate the energy after every step for `max_relative_energy_error`
    /// (benchmarks turn it off to time the integrator alone).
    pub monitor_energy: bool,
}

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

/// Checks that a fixed step advances time all the way to `t_end` (a step below `t_end · 2⁻⁵²`
/// leaves `t + h == t` and would never finish).
///
/// # Errors
/// What is wrong and the smallest step allowed.
pub fn check_step(step: f64, t_end: f64) -> Result<(), String> {
    let smallest = t_end * f64::EPSILON * 4.0;
    if step.is_finite() && step > 0.0 && step >= smallest {
        Ok(())
    } else {
        Err(format!(
            "a step of {step:e} cannot advance time to t_end = {t_end} (t + h == t); allowed: \
             at least {smallest:.1e}"
        ))
    }
}

/// Most reversal times a run keeps (8 MB); later ones are counted only.
pub const MAX_REVERSAL_TIMES: usize = 1_000_000;

/// Integrates `problem` as `spec` says.
///
/// # Errors
/// When the integrator cannot continue (step underflow, non-finite state), or for `auto`
/// ([`StepError::Unplanned`]: resolve it with `physics::plan` first).
pub fn run(problem: &Problem, spec: &RunSpec) -> Result<RunResult, StepError> {
    run_cancellable(problem, spec, &mut |_| true)
}

/// [`run`], asking `go_on(t)` every [`CHECK_EVERY`] steps whether to continue (`t` is the time
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
    let settings = Settings {
        tolerance: spec.tolerance,
        step: spec.step,
    };
    let mut integrator = integrators::build(
        spec.method,
        problem,
        settings,
        spec.t_end,
        crate::physics::method::TimeSum::default(),
    )?;
    let e0 = integrator.energy();
    let scale = if e0 == 0.0 { 1.0 } else { e0.abs() };
    let mut tracker = ReversalTracker::new(problem.start().alpha_dot);
    let mut reversals = Vec::new();
    let mut reversal_count = 0;
    let mut max_err: f64 = 0.0;
    let sample_time = |i: usize| {
        if spec.samples <= 1 {
            0.0
        } else {
            #[allow(clippy::cast_precision_loss)]
            let f = i as f64 / (spec.samples - 1) as f64;
            spec.t_end * f
        }
    };
    let mut next_sample = 0;
    if spec.samples > 0 {
        if !on_sample(Sample {
            t: 0.0,
            state: integrator.state(),
        }) {
            return Err(StepError::Cancelled { t: 0.0 });
        }
        next_sample = 1;
    }
    let mut steps: u64 = 0;
    let cap = crate::physics::method::StepCap::of(super::budget::cost_seconds(
        problem,
        spec.method,
        spec.tolerance,
        spec.step,
        spec.t_end,
    ));
    while integrator.time() < spec.t_end {
        steps += 1;
        if steps.is_multiple_of(CHECK_EVERY) && !go_on(integrator.time()) {
            return Err(StepError::Cancelled {
                t: integrator.time(),
            });
        }
        cap.check(steps, integrator.time())?;
        integrator.step(spec.t_end)?;
        if let Some(t) = tracker.after_step(integrator.as_mut()) {
            reversal_count += 1;
            if reversals.len() < MAX_REVERSAL_TIMES {
                reversals.push(t);
            }
        }
        if spec.monitor_energy {
            max_err = max_err.max((integrator.energy() - e0).abs() / scale);
        }
        while next_sample < spec.samples && sample_time(next_sample) <= integrator.time() {
            let t = sample_time(next_sample);
            let state = if t >= integrator.time() {
                integrator.state()
            } else {
                integrator.interpolate(t)
            };
            if !on_sample(Sample { t, state }) {
                return Err(StepError::Cancelled { t });
            }
            next_sample += 1;
        }
    }
    let final_state = integrator.state();
    let energy_final = integrator.energy();
    max_err = max_err.max((energy_final - e0).abs() / scale);
    Ok(RunResult {
        t: integrator.time(),
        final_state,
        reversals,
        reversal_count,
        energy_initial: e0,
        energy_final,
        max_relative_energy_error: max_err,
        stats: integrator.stats(),
        samples: Vec::new(),
    })
}
