//! One headless run of the celt: integrate to `t_end`, find the crossings and reversals of the
//! spin, follow the energy and the constraints, keep optional samples. Used by `simulate`,
//! `auto`, the tests and the benchmarks; the explorer's worker drives the same [`CeltFlow`].
//! A chart's cells need only the reversals: [`count`] runs watch nothing else, and
//! [`count_in_lanes`] takes such runs four at a time (issue 84).

use crate::physics::method::RunSpec;
use serde::Serialize;

use super::flows::{CeltField, CeltFlow, build};
use super::{DIM, Problem, State, gamma, spin};
use crate::physics::drive::{Course, Drift, Driven, Driver, Watch, drive};
use crate::physics::flow::{Flow, GoOn};
use crate::physics::method::{Asked, Method, StepError};
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::dop853_lanes::{Packs, Scratch, attempt};
use crate::physics::numerics::lanes::LANES;

/// Most event times kept of each kind; later ones are counted only.
pub const MAX_EVENT_TIMES: usize = crate::physics::drive::KEPT;

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

/// Integrates `problem` as `spec` says, asking `go_on(t)` every `CHECK_EVERY` steps.
///
/// # Errors
/// A failed step, `auto` ([`StepError::Unplanned`]), another model's method, the step cap, and
/// [`StepError::Cancelled`] when `go_on` says stop.
pub fn run(problem: &Problem, spec: &RunSpec, go_on: GoOn) -> Result<RunResult, StepError> {
    let ask = spec.asked();
    let mut flow: CeltFlow = build(problem, ask.method, ask.settings())?;
    let y0 = flow.state();
    let e0 = problem.params().energy(&y0);
    let cost = super::budget::cost_seconds(problem, &ask);
    let course = Course::of(&flow, spec.t_end, spec.samples, cost);
    let mut watch = Watched {
        problem,
        drift: Drift::new(e0, false),
        monitor: spec.monitor_energy,
        gamma_norm_error: 0.0,
        quat_norm_error: 0.0,
        contact_height_max: 0.0,
        samples: Vec::with_capacity(spec.samples.min(1 << 20)),
    };
    let driven = drive(&mut flow, &course, go_on, &mut watch)?;
    let state = flow.state();
    Ok(RunResult {
        method: flow.method(),
        t: flow.time(),
        state,
        crossings: driven.marks.times,
        crossing_count: driven.marks.count,
        reversals: driven.events.times,
        reversal_count: driven.events.count,
        energy_initial: e0,
        energy_final: problem.params().energy(&state),
        max_energy_drift: watch.drift.max,
        gamma_norm_error: watch.gamma_norm_error,
        quat_norm_error: watch.quat_norm_error,
        contact_height_max: watch.contact_height_max,
        stats: flow.stats(),
        samples: watch.samples,
    })
}

/// What the celt's run watches: the samples, the energy and the constraints' drift.
struct Watched<'a> {
    problem: &'a Problem,
    drift: Drift,
    /// Whether the energy's drift is followed (`RunSpec::monitor_energy`).
    monitor: bool,
    gamma_norm_error: f64,
    quat_norm_error: f64,
    contact_height_max: f64,
    samples: Vec<Sample>,
}

impl Watch<CeltFlow> for Watched<'_> {
    fn sample(&mut self, flow: &mut CeltFlow, t: f64) -> bool {
        let y = flow.at(t);
        self.samples.push(Sample {
            t,
            turn: y[DIM - 1],
            spin: spin(&y),
            tilt: super::tilt(&y),
        });
        true
    }
    fn stepped(&mut self, flow: &mut CeltFlow) {
        let y = flow.state();
        if self.monitor {
            self.drift.see(self.problem.params().energy(&y));
        }
        self.gamma_norm_error = self.gamma_norm_error.max((gamma(&y).norm() - 1.0).abs());
        let qn = (y[6] * y[6] + y[7] * y[7] + y[8] * y[8] + y[9] * y[9]).sqrt();
        self.quat_norm_error = self.quat_norm_error.max((qn - 1.0).abs());
        self.contact_height_max = self
            .contact_height_max
            .max(contact_height(self.problem, &y).abs());
    }
}

/// What a count of reversals keeps of a run (issue 84: a chart's cells need no more, so their
/// runs watch nothing else).
#[derive(Clone, Debug, PartialEq)]
pub struct Counts {
    /// Reversals with the hysteresis band (the first [`MAX_EVENT_TIMES`]).
    pub reversals: Vec<f64>,
    /// How many.
    pub count: usize,
}

impl Counts {
    fn of(driven: Driven) -> Self {
        Self {
            reversals: driven.events.times,
            count: driven.events.count,
        }
    }
}

/// A watcher that watches nothing.
struct Unwatched;

impl Watch<CeltFlow> for Unwatched {
    fn sample(&mut self, _: &mut CeltFlow, _: f64) -> bool {
        true
    }
    fn stepped(&mut self, _: &mut CeltFlow) {}
}

/// A DOP853 run of `problem` over `[0, t_end]` at tolerance `local`, without samples, ready to
/// drive: the flow and course [`run`] builds for it.
fn counting(problem: &Problem, t_end: f64, local: f64) -> (CeltFlow, Course) {
    let ask = Asked::new(Method::Dop853, local, None, t_end);
    let flow = CeltFlow::new(problem, ask.settings().tolerance, false);
    let cost = super::budget::cost_seconds(problem, &ask);
    let course = Course::of(&flow, t_end, 0, cost);
    (flow, course)
}

/// The reversals of a DOP853 run of `problem` over `[0, t_end]` at tolerance `local`: the
/// reversals [`run`] finds, without what else it watches.
///
/// # Errors
/// A failed step, the step cap, and [`StepError::Cancelled`] when `go_on` says stop.
pub fn count(problem: &Problem, t_end: f64, local: f64, go_on: GoOn) -> Result<Counts, StepError> {
    let (mut flow, course) = counting(problem, t_end, local);
    drive(&mut flow, &course, go_on, &mut Unwatched).map(Counts::of)
}

/// Runs to count, handed out and taken back by [`count_in_lanes`].
pub trait Jobs {
    /// The next run: an id, the problem, its window and its tolerance (`None`: none now).
    fn next(&mut self) -> Option<(usize, Problem, f64, f64)>;
    /// Run `id` ended: what [`count`] gives it, bit for bit.
    fn done(&mut self, id: usize, counted: Result<Counts, StepError>);
}

/// A run in a lane: its flow, its course and where its driver is.
struct Lane {
    id: usize,
    flow: CeltFlow,
    course: Course,
    driver: Driver,
}

/// Counts the reversals of every run `jobs` hands out, [`LANES`] at a time (issue 84): each
/// lane's attempts are taken side by side ([`attempt`]), and each lane is driven by the one
/// [`Driver`] a lone run is driven by, so each run's counts are [`count`]'s; a lane whose run
/// ends or fails is handed the next run at once. Ends when every run handed out has ended
/// and `jobs` has no more. Compiled for AVX2 and AVX too, the best the machine has chosen
/// when first called: the same operations at another width, so the same bits.
#[multiversion::multiversion(targets("x86_64+avx2", "x86_64+avx"))]
pub fn count_in_lanes(jobs: &mut dyn Jobs, go_on: GoOn) {
    let mut lanes: [Option<Lane>; LANES] = [None, None, None, None];
    let mut packed = None;
    let mut scratch = Scratch::default();
    loop {
        for slot in &mut lanes {
            while slot.is_none() {
                let Some((id, problem, t_end, local)) = jobs.next() else {
                    break;
                };
                let (mut flow, course) = counting(&problem, t_end, local);
                let mut driver = Driver::new(&course);
                match driver.before(&mut flow, &course, go_on, &mut Unwatched) {
                    Ok(true) => {
                        *slot = Some(Lane {
                            id,
                            flow,
                            course,
                            driver,
                        });
                        packed = None;
                    }
                    Ok(false) => jobs.done(id, Ok(Counts::of(driver.driven))),
                    Err(e) => jobs.done(id, Err(e)),
                }
            }
        }
        let Some(live) = lanes.iter().position(Option::is_some) else {
            return;
        };
        if packed.is_none() {
            let field = |l: usize| {
                let lane = lanes[l].as_ref().or(lanes[live].as_ref());
                lane.expect("a live lane").flow.field()
            };
            packed = Some(CeltField::pack(std::array::from_fn(field)));
        }
        let t_limits = std::array::from_fn(|l| lanes[l].as_ref().map_or(0.0, |l| l.course.t_end));
        let mut cores = lanes.each_mut().map(|l| l.as_mut().map(|l| l.flow.core()));
        let verdicts = attempt(
            &mut cores,
            packed.as_ref().expect("packed"),
            t_limits,
            &mut scratch,
        );
        for (l, (slot, verdict)) in lanes.iter_mut().zip(verdicts).enumerate() {
            let ended = match verdict {
                None | Some(Ok(false)) => continue,
                Some(Err(e)) => Err(e),
                Some(Ok(true)) => {
                    let lane = slot.as_mut().expect("a live lane");
                    if lane.flow.reads_inside() {
                        scratch.hand_over(lane.flow.core(), l);
                    }
                    lane.flow.stepped();
                    lane.driver
                        .after(&mut lane.flow, &lane.course, &mut Unwatched);
                    match lane
                        .driver
                        .before(&mut lane.flow, &lane.course, go_on, &mut Unwatched)
                    {
                        Ok(true) => continue,
                        Ok(false) => Ok(()),
                        Err(e) => Err(e),
                    }
                }
            };
            let lane = slot.take().expect("a live lane");
            jobs.done(lane.id, ended.map(|()| Counts::of(lane.driver.driven)));
            packed = None;
        }
    }
}
