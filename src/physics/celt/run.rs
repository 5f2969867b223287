//! One headless run of the celt: integrate to `t_end`, find the crossings and reversals of the
//! spin, follow the energy and the constraints, keep optional samples. Used by `simulate`,
//! `auto`, the tests and the benchmarks; the explorer's worker drives the same [`CeltFlow`].

use serde::Serialize;

use super::flows::{CeltFlow, build};
use super::{DIM, Problem, State, gamma, spin};
use crate::physics::flow::{CHECK_EVERY, EventTracker, Flow};
use crate::physics::method::{Method, Settings, StepCap, StepError};
use crate::physics::numerics::dop853::Stats;

/// Most event times kept of each kind; later ones are counted only.
pub const MAX_EVENT_TIMES: usize = 100_000;

/// What to run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RunSpec {
    /// A concrete method.
    pub method: Method,
    /// Tolerance.
    pub tolerance: f64,
    /// Final time (s).
    pub t_end: f64,
    /// Evenly spaced samples over `[0, t_end]` to record.
    pub samples: usize,
}

/// One recorded point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time.
    pub t: f64,
    /// The angle turned about the vertical, `∫ ω·γ dt`.
    pub turn: f64,
    /// The spin `ω·γ`.
    pub spin: f64,
    /// The tilt from upright.
    pub tilt: f64,
}

/// The outcome of a run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunResult {
    /// The method that integrated.
    pub method: Method,
    /// Time reached.
    pub t: f64,
    /// The state at `t`.
    #[serde(skip)]
    pub state: State,
    /// Raw sign changes of the spin (the first [`MAX_EVENT_TIMES`]).
    pub crossings: Vec<f64>,
    /// How many.
    pub crossing_count: usize,
    /// Reversals with the hysteresis band (the first [`MAX_EVENT_TIMES`]).
    pub reversals: Vec<f64>,
    /// How many.
    pub reversal_count: usize,
    /// Energy at `t = 0`.
    pub energy_initial: f64,
    /// Energy at `t`.
    pub energy_final: f64,
    /// Largest `|E − E(0)|` over accepted steps.
    pub max_energy_drift: f64,
    /// Largest `||γ| − 1|` over accepted steps.
    pub gamma_norm_error: f64,
    /// Largest `||q| − 1|` over accepted steps.
    pub quat_norm_error: f64,
    /// Largest `|Z|` of the contact point computed from the attitude `q` over accepted steps
    /// (the body's rolling surface meets the plane: 0 up to the constraint's drift).
    pub contact_height_max: f64,
    /// Work counters.
    pub stats: Stats,
    /// Requested samples.
    pub samples: Vec<Sample>,
}

/// The contact's height when the attitude is taken from `q` alone (`γ_q = R(q)ᵀ Z`) and G's
/// height from the integrated `γ`: 0 exactly on the constraint manifold.
fn contact_height(problem: &Problem, y: &State) -> f64 {
    let mut yq = *y;
    super::flows::project(&mut yq);
    let pose = problem.pose(&yq);
    let g = gamma(y);
    let r = problem.params().contact(&g);
    // G's height from the integrated γ, the contact's offset from the attitude.
    -r.dot(&g) + (pose.rotation * r).z
}

/// Integrates `problem` as `spec` says, asking `go_on(t)` every [`CHECK_EVERY`] steps.
///
/// # Errors
/// A failed step, `auto` ([`StepError::Unplanned`]), another model's method, the step cap, and
/// [`StepError::Cancelled`] when `go_on` says stop.
pub fn run(
    problem: &Problem,
    spec: &RunSpec,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<RunResult, StepError> {
    let settings = Settings {
        tolerance: spec.tolerance,
        step: None,
    };
    let mut flow: CeltFlow = build(problem, spec.method, settings)?;
    let mut reversals_tracker = EventTracker::new(flow.event_value());
    let y0 = flow.state();
    let e0 = problem.params().energy(&y0);
    let mut out = RunResult {
        method: spec.method,
        t: 0.0,
        state: y0,
        crossings: Vec::new(),
        crossing_count: 0,
        reversals: Vec::new(),
        reversal_count: 0,
        energy_initial: e0,
        energy_final: e0,
        max_energy_drift: 0.0,
        gamma_norm_error: 0.0,
        quat_norm_error: 0.0,
        contact_height_max: 0.0,
        stats: Stats::default(),
        samples: Vec::with_capacity(spec.samples.min(1 << 20)),
    };
    #[allow(clippy::cast_precision_loss)]
    let sample_time = |i: usize| {
        if spec.samples <= 1 {
            spec.t_end
        } else {
            spec.t_end * i as f64 / (spec.samples - 1) as f64
        }
    };
    let cap = StepCap::of(super::budget::cost_seconds(
        problem,
        spec.method,
        spec.tolerance,
        spec.t_end,
    ));
    let mut next_sample = 0usize;
    let mut steps = 0u64;
    loop {
        while next_sample < spec.samples && sample_time(next_sample) <= flow.time() {
            let t = sample_time(next_sample);
            let y = flow.at(t);
            out.samples.push(Sample {
                t,
                turn: y[DIM - 1],
                spin: spin(&y),
                tilt: super::tilt(&y),
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
        for &t in flow.marks() {
            out.crossing_count += 1;
            if out.crossings.len() < MAX_EVENT_TIMES {
                out.crossings.push(t);
            }
        }
        if let Some(t) = reversals_tracker.after_step(&mut flow) {
            out.reversal_count += 1;
            if out.reversals.len() < MAX_EVENT_TIMES {
                out.reversals.push(t);
            }
        }
        let y = flow.state();
        out.max_energy_drift = out
            .max_energy_drift
            .max((problem.params().energy(&y) - e0).abs());
        out.gamma_norm_error = out.gamma_norm_error.max((gamma(&y).norm() - 1.0).abs());
        let qn = (y[6] * y[6] + y[7] * y[7] + y[8] * y[8] + y[9] * y[9]).sqrt();
        out.quat_norm_error = out.quat_norm_error.max((qn - 1.0).abs());
        out.contact_height_max = out
            .contact_height_max
            .max(contact_height(problem, &y).abs());
    }
    out.t = flow.time();
    out.state = flow.state();
    out.energy_final = problem.params().energy(&out.state);
    out.stats = flow.stats();
    out.method = flow.method();
    Ok(out)
}
