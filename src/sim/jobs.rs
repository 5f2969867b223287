//! The computations the worker does for panes, behind one [`Job`] interface: the comparison's
//! partner, the weak-* view, the sweep of the small parameter and the regime map. The engine
//! keeps at most one job of each [`JobKind`], each at work on a thread of its own ([`Running`]:
//! a pane never starves the run, issue 56), drops a finished one, and stops the ones that
//! belong to the run when it restarts; a job dropped (its pane closed, its inputs changed) is
//! cancelled at once, through the flag its `go_on` asks. A pane orders its job with
//! [`Command::Job`](super::Command::Job) and a [`JobSpec`], and the job answers with
//! [`SimEvent::Job`] and a [`JobData`]: a new computed pane is a job, a spec and its data here,
//! and neither the engine nor the worker's commands and events change.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, TryRecvError};
use std::time::Duration;

use super::planner::Planner;
use super::{Point, Session, SessionSpec, SimEvent};
use crate::physics::StepError;
use crate::physics::method::Asked;
use crate::physics::method::Method;
use crate::physics::plan::Resolved;
use crate::study::map::Source;
use crate::study::sweep::{ladder, limit_curve, rung};

/// Which job: one of each at a time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum JobKind {
    /// The comparison's partner (what a recording shows waits for it); a restart does not stop
    /// it (it does not depend on the run).
    Partner,
    /// The weak-* view of the run's start.
    Weak,
    /// The sweep of the run's small parameter.
    Sweep,
    /// The regime map.
    Map,
}

impl JobKind {
    /// Whether a restart of the run stops it.
    #[must_use]
    pub fn ends_with_run(self) -> bool {
        self != Self::Partner
    }

    /// Whether what it computes is part of a recorded screen (`replay --verify` computes it
    /// and compares what the pane showed); the others are dropped there.
    #[must_use]
    pub fn shown_in_record(self) -> bool {
        match self {
            Self::Partner => true,
            Self::Weak | Self::Sweep | Self::Map => false,
        }
    }
}

/// What a pane asks its job to compute.
#[derive(Clone, Debug, PartialEq)]
pub enum JobSpec {
    /// The comparison's partner (another preset, on the run's time axis), run to its end.
    Partner(SessionSpec),
    /// The weak-* view of the run's start.
    Weak(WeakSpec),
    /// The sweep of the run's small parameter.
    Sweep(SweepSpec),
    /// The regime map, refined (`study::refine`) from the cells computed so far.
    Map {
        /// What to compute.
        spec: Box<MapSpec>,
        /// The cells computed so far (`None` elsewhere; an inferred cell is inferred again).
        known: Vec<Option<crate::study::chart::Verdict>>,
    },
}

impl JobSpec {
    /// Its job's kind.
    #[must_use]
    pub fn kind(&self) -> JobKind {
        match self {
            Self::Partner(_) => JobKind::Partner,
            Self::Weak(_) => JobKind::Weak,
            Self::Sweep(_) => JobKind::Sweep,
            Self::Map { .. } => JobKind::Map,
        }
    }

    /// Predicted seconds of its work (each pane's cost model): the partner's run as `auto`
    /// plans it, the weak-* view's bounded run, the sweep's limit and rungs, the map's cells
    /// still to compute.
    #[must_use]
    pub fn predicted_seconds(&self) -> f64 {
        match self {
            Self::Partner(spec) => spec.model.predicted_seconds(&Asked::new(
                spec.method,
                spec.tolerance,
                spec.step,
                spec.t_end,
            )),
            Self::Weak(w) => w
                .model
                .posed()
                .weak()
                .map_or(0.0, |weak| weak.seconds(w.t_end)),
            Self::Sweep(w) => crate::study::sweep::predicted_seconds(
                &w.model,
                ladder(w.model.kind()),
                w.t_end,
                w.tolerance,
            )
            .unwrap_or(f64::INFINITY),
            Self::Map { spec, known } => spec.chart.price_left(known.iter().flatten().count()),
        }
    }

    /// What it computes, in words.
    fn what(&self) -> &'static str {
        match self {
            Self::Partner(_) => "the partner",
            Self::Weak(_) => "the weak-* view",
            Self::Sweep(_) => "the sweep",
            Self::Map { .. } => "the map",
        }
    }

    /// The job that computes it, stamped `stamp`.
    #[must_use]
    pub fn job(self, stamp: u64) -> Box<dyn Job> {
        // The door every pane's job passes (issue 56): its cost model is asked before it
        // starts, and a job over the budget sends its reason to the pane instead of working.
        // The partner's runs are priced by the planner, which refuses them with `auto`'s words.
        let predicted = self.predicted_seconds();
        if self.kind() != JobKind::Partner
            && let Err(over) =
                crate::physics::budget::check(predicted, crate::physics::budget::BUDGET_SECONDS)
        {
            return Box::new(Refused {
                stamp,
                kind: self.kind(),
                reason: format!("{} is {over}", self.what()),
            });
        }
        match self {
            Self::Partner(spec) => Box::new(PartnerJob::new(stamp, spec)),
            Self::Weak(spec) => Box::new(WeakJob::new(stamp, spec)),
            Self::Sweep(spec) => Box::new(SweepJob::new(stamp, spec)),
            Self::Map { spec, known } => Box::new(MapJob::new(stamp, *spec, known)),
        }
    }
}

/// What a job sends back, in [`SimEvent::Job`] with its stamp.
#[derive(Clone, Debug, PartialEq)]
pub enum JobData {
    /// The comparison's partner ran to its end (or why it could not).
    Partner(Result<Box<PartnerRun>, String>),
    /// The weak-* view's data (or why it could not be computed).
    Weak {
        /// Sample times, evenly spaced.
        t: Vec<f64>,
        /// `γ̇² g^{3/2}` (the pendulum: `θ̇_ε`) at those times.
        pointwise: Vec<f64>,
        /// The limit's `θ` (the rattleback's constant; 0 for the pendulum).
        theta: f64,
        /// The limit's value at those times, when it is not a constant (the pendulum's `θ̇`).
        reference: Vec<f64>,
        /// Why it failed, if it did.
        failed: Option<String>,
    },
    /// A rung of the sweep.
    SweepPoint {
        /// The rung's parameter (`k`, or `ε`).
        parameter: f64,
        /// `sup |α_k − α_eff|` (`sup |θ_ε − θ|`) over `[0, T]`.
        sup_error: f64,
        /// What `auto` ran.
        method: Method,
    },
    /// The sweep is complete (or could not go on: `failed`).
    SweepDone {
        /// Why it stopped short, if it did.
        failed: Option<String>,
    },
    /// Cells of the map, computed or inferred: each cell's index and verdict.
    MapCells {
        /// The cells.
        cells: Vec<(usize, crate::study::chart::Verdict)>,
    },
    /// The regime map is complete (or could not go on: `failed`).
    MapDone {
        /// Why it stopped short, if it did.
        failed: Option<String>,
    },
}

impl JobData {
    /// The kind of job that sent it.
    #[must_use]
    pub fn kind(&self) -> JobKind {
        match self {
            Self::Partner(_) => JobKind::Partner,
            Self::Weak { .. } => JobKind::Weak,
            Self::SweepPoint { .. } | Self::SweepDone { .. } => JobKind::Sweep,
            Self::MapCells { .. } | Self::MapDone { .. } => JobKind::Map,
        }
    }
}

/// The comparison's partner, run to its end: what the compare pane draws up to the displayed
/// time.
#[derive(Clone, Debug, PartialEq)]
pub struct PartnerRun {
    /// The plan that integrated it (journaled, so a replay runs the same).
    pub plan: Resolved,
    /// `auto`'s error estimate, when it planned.
    pub estimate: Option<f64>,
    /// Samples on its grid.
    pub samples: Vec<Point>,
    /// Its reversals, at the times a display counts them.
    pub reversals: Vec<f64>,
    /// Its second events (the celt's crossings), when the model has them.
    pub marks: Vec<f64>,
}

/// The map pane's computation: the scene's chart (issue 59).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapSpec {
    /// The chart: its grid, scene and source.
    pub chart: crate::study::chart::Chart,
}

impl MapSpec {
    /// The rattleback's map of `grid` from `source` (no preset point marked).
    #[must_use]
    pub fn rattleback(grid: crate::study::map::Grid, source: Source) -> Self {
        Self {
            chart: crate::physics::rattleback::chart::RegimeChart {
                grid,
                source,
                at: (f64::NAN, f64::NAN),
            }
            .into(),
        }
    }
}

/// The weak-* view's computation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeakSpec {
    /// The start (the rattleback's `γ̇² g^{3/2}`, or the pendulum's `θ̇`).
    pub model: crate::physics::Model,
    /// The run's horizon (the view covers a bounded number of fast periods: `Posed::weak_view`).
    pub t_end: f64,
}

/// A sweep of the small parameter (`k`, or the pendulum's `ε`) for the explorer's sweep pane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepSpec {
    /// The start (its `k` or `ε` is replaced by each rung's).
    pub model: crate::physics::Model,
    /// Horizon.
    pub t_end: f64,
    /// `auto`'s tolerance.
    pub tolerance: f64,
}

/// How a slice ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slice {
    /// There is more to do (a cancelled slice is redone from its start).
    More,
    /// The job is finished (its last event sent).
    Done,
    /// Nobody listens any more: the worker stops.
    Closed,
}

impl Slice {
    /// `Closed` when `sent` is false, else `then`.
    fn after(sent: bool, then: Self) -> Self {
        if sent { then } else { Self::Closed }
    }
}

/// What a slice of a job works with.
pub struct Work<'a> {
    /// Plans a run as the engine plans its own (the partner's).
    pub planner: &'a mut Planner,
    /// Most steps in a slice, for a job that steps.
    pub max_steps: usize,
    /// Whether to go on (a command arrived: the slice is cancelled, and redone next time).
    pub go_on: &'a mut dyn FnMut(f64) -> bool,
    /// Where events go; `false` means nobody listens any more.
    pub sink: &'a mut dyn FnMut(SimEvent) -> bool,
}

/// A pane's computation, worked a slice at a time.
pub trait Job: Send {
    /// Which job it is.
    fn kind(&self) -> JobKind;
    /// One slice: at most `max_steps` steps where it steps, else one bounded piece.
    fn slice(&mut self, work: &mut Work) -> Slice;
}

/// The comparison's partner: planned, then integrated in slices to its end.
pub struct PartnerJob {
    id: u64,
    spec: SessionSpec,
    /// The session and what it produced so far, once planned.
    started: Option<(Session, PartnerRun)>,
}

impl PartnerJob {
    /// The partner `spec`, stamped `id`.
    #[must_use]
    pub fn new(id: u64, spec: SessionSpec) -> Self {
        Self {
            id,
            spec,
            started: None,
        }
    }
}

impl Job for PartnerJob {
    fn kind(&self) -> JobKind {
        JobKind::Partner
    }

    fn slice(&mut self, work: &mut Work) -> Slice {
        let (go_on, sink) = (&mut *work.go_on, &mut *work.sink);
        let (id, spec) = (self.id, self.spec);
        let Some((session, run)) = self.started.as_mut() else {
            return match work.planner.start(id, &spec, go_on) {
                Err(StepError::Cancelled { .. }) => Slice::More,
                Err(e) => Slice::after(
                    sink(SimEvent::Job {
                        stamp: id,
                        data: JobData::Partner(Err(super::planner::refusal(&spec, &e))),
                    }),
                    Slice::Done,
                ),
                Ok((session, estimate)) => {
                    let plan = session.plan();
                    self.started = Some((
                        session,
                        PartnerRun {
                            plan,
                            estimate,
                            samples: Vec::new(),
                            reversals: Vec::new(),
                            marks: Vec::new(),
                        },
                    ));
                    Slice::More
                }
            };
        };
        let (events, _) = session.advance(spec.t_end, work.max_steps);
        let mut end = None;
        for e in events {
            match e {
                SimEvent::Samples { full, .. } => run.samples.extend(full),
                SimEvent::Counted {
                    t,
                    effective: false,
                    ..
                } => run.reversals.push(t),
                SimEvent::Mark { t, .. } => run.marks.push(t),
                SimEvent::Failed { message, .. } => end = Some(Err(message)),
                SimEvent::Finished { .. } => end = Some(Ok(())),
                _ => {}
            }
        }
        let outcome = match end {
            None => return Slice::More,
            Some(Err(why)) => Err(why),
            Some(Ok(())) => match self.started.take() {
                Some((_, run)) => Ok(Box::new(run)),
                None => return Slice::More,
            },
        };
        let data = JobData::Partner(outcome);
        Slice::after(sink(SimEvent::Job { stamp: id, data }), Slice::Done)
    }
}

/// A job its cost model put over the budget: it sends why to its pane, and ends.
struct Refused {
    stamp: u64,
    kind: JobKind,
    reason: String,
}

impl Job for Refused {
    fn kind(&self) -> JobKind {
        self.kind
    }

    fn slice(&mut self, work: &mut Work) -> Slice {
        let failed = Some(self.reason.clone());
        let data = match self.kind {
            JobKind::Partner => JobData::Partner(Err(self.reason.clone())),
            JobKind::Weak => JobData::Weak {
                t: Vec::new(),
                pointwise: Vec::new(),
                theta: 0.0,
                reference: Vec::new(),
                failed,
            },
            JobKind::Sweep => JobData::SweepDone { failed },
            JobKind::Map => JobData::MapDone { failed },
        };
        let event = SimEvent::Job {
            stamp: self.stamp,
            data,
        };
        Slice::after((work.sink)(event), Slice::Done)
    }
}

/// The weak-* view of run `generation`: one bounded run (at most `VIEW_PERIODS` fast periods).
pub struct WeakJob {
    generation: u64,
    spec: WeakSpec,
}

impl WeakJob {
    /// The view `spec` of run `generation`.
    #[must_use]
    pub fn new(generation: u64, spec: WeakSpec) -> Self {
        Self { generation, spec }
    }
}

impl Job for WeakJob {
    fn kind(&self) -> JobKind {
        JobKind::Weak
    }

    fn slice(&mut self, work: &mut Work) -> Slice {
        let (go_on, sink) = (&mut *work.go_on, &mut *work.sink);
        let (generation, spec) = (self.generation, self.spec);
        let data = spec.model.weak().map_or_else(
            || {
                Err(StepError::NoStudy {
                    what: "weak-* view",
                    model: spec.model.kind().name(),
                })
            },
            |weak| weak.view(spec.t_end, go_on),
        );
        let event = match data {
            Err(StepError::Cancelled { .. }) => return Slice::More,
            Err(e) => JobData::Weak {
                t: Vec::new(),
                pointwise: Vec::new(),
                theta: 0.0,
                reference: Vec::new(),
                failed: Some(e.to_string()),
            },
            Ok(v) => JobData::Weak {
                t: v.t,
                pointwise: v.pointwise,
                theta: v.level,
                reference: v.reference,
                failed: None,
            },
        };
        let event = SimEvent::Job {
            stamp: generation,
            data: event,
        };
        Slice::after(sink(event), Slice::Done)
    }
}

/// The sweep of run `generation`'s small parameter: the limit's curve once, then one rung per
/// slice.
pub struct SweepJob {
    generation: u64,
    spec: SweepSpec,
    limit: Option<Vec<f64>>,
    next: usize,
}

impl SweepJob {
    /// The sweep `spec` of run `generation`.
    #[must_use]
    pub fn new(generation: u64, spec: SweepSpec) -> Self {
        Self {
            generation,
            spec,
            limit: None,
            next: 0,
        }
    }
}

impl Job for SweepJob {
    fn kind(&self) -> JobKind {
        JobKind::Sweep
    }

    fn slice(&mut self, work: &mut Work) -> Slice {
        let (go_on, sink) = (&mut *work.go_on, &mut *work.sink);
        let (generation, spec) = (self.generation, self.spec);
        let rungs = ladder(spec.model.kind());
        let outcome = match &self.limit {
            None => limit_curve(&spec.model, spec.t_end, go_on).map(|(_, limit)| {
                self.limit = Some(limit);
                None
            }),
            Some(limit) => rung(
                &spec.model,
                rungs[self.next],
                spec.t_end,
                spec.tolerance,
                limit,
                go_on,
            )
            .map(Some),
        };
        let point = match outcome {
            Err(StepError::Cancelled { .. }) => return Slice::More,
            Err(e) => {
                let failed = Some(e.to_string());
                let data = JobData::SweepDone { failed };
                return Slice::after(
                    sink(SimEvent::Job {
                        stamp: generation,
                        data,
                    }),
                    Slice::Done,
                );
            }
            Ok(point) => point,
        };
        if let Some(r) = point {
            self.next += 1;
            let data = JobData::SweepPoint {
                parameter: r.parameter,
                sup_error: r.sup_error,
                method: r.method,
            };
            if !sink(SimEvent::Job {
                stamp: generation,
                data,
            }) {
                return Slice::Closed;
            }
        }
        if self.next < rungs.len() {
            return Slice::More;
        }
        let done = SimEvent::Job {
            stamp: generation,
            data: JobData::SweepDone { failed: None },
        };
        Slice::after(sink(done), Slice::Done)
    }
}

/// The regime map stamped `id`, refined (`study::refine`, as `study map` computes it): each
/// slice computes a row of the cheap charts' pending cells (the rattleback's limit, the
/// pendulum's one-period traces) or, of the ones that run the full motion, as many as the pool
/// has threads times what a thread takes together (`SceneChart::together`: the celt's lanes),
/// and sends them with the cells their blocks now infer.
pub struct MapJob {
    id: u64,
    spec: MapSpec,
    /// The cells computed so far.
    known: Vec<Option<crate::study::chart::Verdict>>,
    /// The cells sent (computed or inferred).
    sent: Vec<bool>,
}

impl MapJob {
    /// The map `spec` stamped `id`, the cells `known` computed already.
    #[must_use]
    pub fn new(
        id: u64,
        spec: MapSpec,
        mut known: Vec<Option<crate::study::chart::Verdict>>,
    ) -> Self {
        known.resize(spec.chart.len(), None);
        let sent = known.iter().map(Option::is_some).collect();
        Self {
            id,
            spec,
            known,
            sent,
        }
    }

    /// The cells of `settled` not sent yet, now marked sent.
    fn unsent(
        &mut self,
        settled: Vec<Option<crate::study::chart::Verdict>>,
    ) -> Vec<(usize, crate::study::chart::Verdict)> {
        let mut cells = Vec::new();
        for (n, v) in settled.into_iter().enumerate() {
            if let Some(v) = v
                && !self.sent[n]
            {
                self.sent[n] = true;
                cells.push((n, v));
            }
        }
        cells
    }
}

impl Job for MapJob {
    fn kind(&self) -> JobKind {
        JobKind::Map
    }

    fn slice(&mut self, work: &mut Work) -> Slice {
        let (go_on, sink) = (&mut *work.go_on, &mut *work.sink);
        let (id, chart) = (self.id, self.spec.chart);
        let refine = chart.refine();
        // One walk: the cells the last batch settled (computed, and those their blocks now
        // infer) go out, and the next batch is read off the same walk.
        let (pending, settled) = refine.step(&self.known, &refine.blocks());
        let cells = self.unsent(settled);
        if !cells.is_empty() {
            let cells = SimEvent::Job {
                stamp: id,
                data: JobData::MapCells { cells },
            };
            if !sink(cells) {
                return Slice::Closed;
            }
        }
        if pending.is_empty() {
            let done = SimEvent::Job {
                stamp: id,
                data: JobData::MapDone { failed: None },
            };
            return Slice::after(sink(done), Slice::Done);
        }
        let chunk = if chart.cheap_cells() {
            chart.axes().0.cells
        } else {
            rayon::current_num_threads().max(1)
                * chart.together().clamp(1, crate::study::chart::CHUNK)
        };
        let batch = &pending[..chunk.min(pending.len())];
        let verdicts = match chart.cells_polled(batch, go_on) {
            Err(StepError::Cancelled { .. }) => return Slice::More,
            Err(e) => {
                let failed = Some(e.to_string());
                let done = SimEvent::Job {
                    stamp: id,
                    data: JobData::MapDone { failed },
                };
                return Slice::after(sink(done), Slice::Done);
            }
            Ok(verdicts) => verdicts,
        };
        for (&n, v) in batch.iter().zip(verdicts) {
            self.known[n] = Some(v);
        }
        Slice::More
    }
}

/// Most steps of a job's slice on its own thread (a cancel is seen between slices, and inside
/// `auto`'s planning and a map's cells through `go_on`).
const JOB_STEPS: usize = 4096;

/// What a job's thread sends back.
enum Message {
    /// One of its events.
    Event(SimEvent),
    /// The predicted seconds its runs were charged (the partner's), when it ends.
    Spent(f64),
}

/// Where a job is after [`Running::take`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Taken {
    /// Still at work.
    Working,
    /// It has ended (its last event taken).
    Ended,
    /// The sink is closed: nobody listens any more.
    Closed,
}

/// A job at work on a thread of its own, so the run never waits for a pane (issue 56: a heavy
/// comparison partner held the run at "verifying" for a minute). Its events come back over a
/// channel, taken by [`Running::take`] (without waiting) or [`Running::finish`] (to its end);
/// dropping it cancels it: the flag its `go_on` asks is set, and its thread ends within a
/// slice, a planning step or a map cell.
pub struct Running {
    kind: JobKind,
    messages: Receiver<Message>,
    cancel: Arc<AtomicBool>,
    #[cfg(not(target_arch = "wasm32"))]
    thread: Option<std::thread::JoinHandle<()>>,
    /// The browser's module: the job, worked a slice at each look ([`Running::take`]).
    #[cfg(target_arch = "wasm32")]
    inline: std::cell::RefCell<Option<Worked>>,
}

/// A job and what it works with: one slice at a time, on its own thread
/// ([`Running::spawn`]'s loop) or, in the browser's module, at each look ([`Running::take`]).
struct Worked {
    job: Box<dyn Job>,
    planner: Planner,
    /// The planner's charge when the job started.
    before: f64,
    go_on: fn() -> bool,
    tx: mpsc::Sender<Message>,
}

impl Worked {
    fn new(
        job: Box<dyn Job>,
        planner: Planner,
        go_on: fn() -> bool,
        tx: mpsc::Sender<Message>,
    ) -> Self {
        let before = planner.spent();
        Self {
            job,
            planner,
            before,
            go_on,
            tx,
        }
    }

    /// One slice (with the planner's elementary functions); whether the job goes on. When it
    /// does not, the charge is sent.
    fn slice(&mut self, cancel: &AtomicBool) -> bool {
        let functions = self.planner.functions();
        let go_on = self.go_on;
        let tx = &self.tx;
        let mut keep_on = |_t: f64| !cancel.load(Ordering::Relaxed) && go_on();
        let mut sink = |e| tx.send(Message::Event(e)).is_ok();
        let mut work = Work {
            planner: &mut self.planner,
            max_steps: JOB_STEPS,
            go_on: &mut keep_on,
            sink: &mut sink,
        };
        let job = &mut self.job;
        let more = crate::physics::numerics::elementary::following(functions, || {
            matches!(job.slice(&mut work), Slice::More)
        });
        if more && !cancel.load(Ordering::Relaxed) && go_on() {
            return true;
        }
        let _ = self
            .tx
            .send(Message::Spent(self.planner.spent() - self.before));
        false
    }
}

impl Running {
    /// Starts `job` on its own thread, planning (the partner) with `planner`; `go_on` is asked
    /// too (a signal that interrupts a headless command). The browser's module starts no
    /// thread: there the job is worked a slice at each look ([`Running::take`]).
    ///
    /// # Panics
    /// When the OS cannot spawn a thread.
    #[must_use]
    pub fn spawn(job: Box<dyn Job>, planner: Planner, go_on: fn() -> bool) -> Self {
        let kind = job.kind();
        let (tx, messages) = mpsc::channel();
        let cancel = Arc::new(AtomicBool::new(false));
        let worked = Worked::new(job, planner, go_on, tx);
        #[cfg(not(target_arch = "wasm32"))]
        let thread = {
            let stop = Arc::clone(&cancel);
            Some(
                std::thread::Builder::new()
                    .name(format!("rattleback-{kind:?}").to_lowercase())
                    .spawn(move || {
                        let mut worked = worked;
                        while worked.slice(&stop) {}
                    })
                    .expect("spawn a pane's job"),
            )
        };
        Self {
            kind,
            messages,
            cancel,
            #[cfg(not(target_arch = "wasm32"))]
            thread,
            #[cfg(target_arch = "wasm32")]
            inline: std::cell::RefCell::new(Some(worked)),
        }
    }

    /// Cancels the job and waits at most `limit` for its thread to end; whether it did.
    #[must_use]
    pub fn cancel_within(mut self, limit: Duration) -> bool {
        self.cancel.store(true, Ordering::Relaxed);
        self.thread_ended_within(limit)
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn thread_ended_within(&mut self, limit: Duration) -> bool {
        let Some(thread) = self.thread.take() else {
            return true;
        };
        let end = std::time::Instant::now() + limit;
        while !thread.is_finished() && std::time::Instant::now() < end {
            std::thread::sleep(Duration::from_millis(1));
        }
        thread.is_finished()
    }

    /// In the browser's module a cancelled job does no more (it works only when looked at).
    #[cfg(target_arch = "wasm32")]
    #[allow(clippy::unused_self)]
    fn thread_ended_within(&mut self, _limit: Duration) -> bool {
        true
    }

    /// Which job it is.
    #[must_use]
    pub fn kind(&self) -> JobKind {
        self.kind
    }

    /// Hands the events that have come to `sink` (waiting at most `wait` for the first), and
    /// the predicted seconds charged to `spent` when it has ended.
    pub fn take(
        &self,
        wait: Option<Duration>,
        sink: &mut dyn FnMut(SimEvent) -> bool,
        spent: &mut dyn FnMut(f64),
    ) -> Taken {
        #[cfg(target_arch = "wasm32")]
        {
            let mut inline = self.inline.borrow_mut();
            if let Some(job) = inline.as_mut()
                && !job.slice(&self.cancel)
            {
                *inline = None;
            }
        }
        // No waiting there: the slice above was the work.
        #[cfg(target_arch = "wasm32")]
        let mut first: Option<Duration> = wait.and(None);
        #[cfg(not(target_arch = "wasm32"))]
        let mut first = wait;
        loop {
            let message = match first.take() {
                Some(d) => match self.messages.recv_timeout(d) {
                    Ok(m) => m,
                    Err(RecvTimeoutError::Timeout) => return Taken::Working,
                    Err(RecvTimeoutError::Disconnected) => return Taken::Ended,
                },
                None => match self.messages.try_recv() {
                    Ok(m) => m,
                    Err(TryRecvError::Empty) => return Taken::Working,
                    Err(TryRecvError::Disconnected) => return Taken::Ended,
                },
            };
            match message {
                Message::Event(e) => {
                    if !sink(e) {
                        return Taken::Closed;
                    }
                }
                Message::Spent(s) => {
                    spent(s);
                    return Taken::Ended;
                }
            }
        }
    }

    /// Hands every event to `sink` until the job has ended (the synchronous drive: replay
    /// verification, the cast, tests); `false` when the sink is closed or `go_on` says stop.
    pub fn finish(
        &self,
        go_on: fn() -> bool,
        sink: &mut dyn FnMut(SimEvent) -> bool,
        spent: &mut dyn FnMut(f64),
    ) -> bool {
        loop {
            if !go_on() {
                self.cancel.store(true, Ordering::Relaxed);
                return false;
            }
            match self.take(Some(Duration::from_millis(5)), sink, spent) {
                Taken::Ended => return true,
                Taken::Working => {}
                Taken::Closed => return false,
            }
        }
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}
