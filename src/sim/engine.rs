//! The one interpreter of the worker protocol. The worker thread, `replay --verify`, the cast
//! export, the tests and the benchmarks all drive an [`Engine`]: `handle` takes a command,
//! `work` does a bounded slice of what is pending (planning `auto`, integrating towards the
//! target, checkpoints, the overlay's catch-up).

use std::collections::VecDeque;

use super::jobs::{Job, JobKind, Running, Taken};
use super::planner::{PlanBook, Planner, refusal};
use super::segments::{Ahead, Forward, Next, Progress, Report};
use super::{Command, Session, SessionSpec, SimEvent};
use crate::physics::method::Method;
use crate::physics::method::StepError;
/// The worker's state between commands.
pub struct Engine {
    planner: Planner,
    session: Option<Session>,
    /// A restart whose plan is not resolved yet.
    planning: Option<(u64, SessionSpec)>,
    /// `(generation, target)` asked by the last `AdvanceTo`.
    pending: Option<(u64, f64)>,
    /// Checkpoints wait until the run reaches their time; the run stops there first so the
    /// step containing the time is the last one (the trajectory is the same either way).
    checkpoints: VecDeque<(u64, f64)>,
    /// Stamp of the overlay's current life.
    epoch: u64,
    /// The panes' computations, at most one of each kind, each on a thread of its own.
    jobs: Vec<Running>,
    /// The verification of a run's later segments, while it goes on.
    ahead: Option<Ahead>,
    /// The run has reached its verified horizon short of the target, and waits for the next
    /// segment.
    blocked: bool,
    /// Where the run stops, and why: a later segment could not be verified (it is said when
    /// the run reaches its start, the verified part being shown first).
    stop: Option<(f64, String)>,
    /// Whether to go on: asked by [`drive`] between slices and by the panes' jobs (a headless
    /// command's signal; always yes in the explorer, which has its own).
    keep_going: fn() -> bool,
}

impl Engine {
    /// An idle engine resolving `auto` with `book`.
    #[must_use]
    pub fn new(book: PlanBook) -> Self {
        Self {
            planner: Planner::new(book),
            session: None,
            planning: None,
            pending: None,
            checkpoints: VecDeque::new(),
            epoch: 0,
            jobs: Vec::new(),
            ahead: None,
            blocked: false,
            stop: None,
            keep_going: || true,
        }
    }

    /// This engine, stopping its jobs and [`drive`] as soon as `keep_going` says no (a headless
    /// command's signal: [`crate::interrupt`]).
    #[must_use]
    pub fn stopping_on(mut self, keep_going: fn() -> bool) -> Self {
        self.keep_going = keep_going;
        self
    }

    fn generation(&self) -> Option<u64> {
        self.planning
            .as_ref()
            .map(|(g, _)| *g)
            .or_else(|| self.session.as_ref().map(Session::generation))
    }

    /// Replaces the job of `kind` by `job` on a thread of its own (none: stops it); the job
    /// replaced is cancelled.
    fn set_job(&mut self, kind: JobKind, job: Option<Box<dyn Job>>) {
        self.jobs.retain(|j| j.kind() != kind);
        if let Some(job) = job {
            let at = self.jobs.partition_point(|j| j.kind() < kind);
            self.jobs.insert(
                at,
                Running::spawn(job, self.planner.clone(), self.keep_going),
            );
        }
    }

    /// Whether `work` has anything to do, or the run waits for the verification ahead to reach
    /// a target (a verification ahead that nothing waits for is not work: a replay never waits
    /// for the segments its lecturer did not show). The panes' jobs work on their own threads.
    #[must_use]
    pub fn busy(&self) -> bool {
        self.run_busy() || (self.ahead.is_some() && self.blocked)
    }

    /// Whether only the threads are at work (the verification ahead, the panes' jobs): `work`
    /// would only look at what they report ([`Engine::wait`] waits for the verification's next
    /// report).
    #[must_use]
    pub fn waiting(&self) -> bool {
        (self.ahead.is_some() || !self.jobs.is_empty()) && !self.run_busy()
    }

    /// Whether a pane's job is at work.
    #[must_use]
    pub fn jobs_running(&self) -> bool {
        !self.jobs.is_empty()
    }

    /// Takes what the jobs have sent so far (without waiting) and drops the ones that ended;
    /// `false` means stop.
    fn take_jobs(&mut self, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        let mut spent = 0.0;
        let mut open = true;
        self.jobs
            .retain(|job| match job.take(None, sink, &mut |s| spent += s) {
                Taken::Working => true,
                Taken::Ended => false,
                Taken::Closed => {
                    open = false;
                    true
                }
            });
        self.planner.spent += spent;
        open
    }

    /// Waits for every job to end, handing their events to `sink` (the synchronous drive: what
    /// a pane computes is there before the run's next step, as the recording showed it);
    /// `false` when the sink closed or `go_on` said stop.
    pub fn settle_jobs(
        &mut self,
        go_on: fn() -> bool,
        sink: &mut dyn FnMut(SimEvent) -> bool,
    ) -> bool {
        let mut spent = 0.0;
        let jobs = std::mem::take(&mut self.jobs);
        let mut settled = true;
        for job in &jobs {
            if settled && !job.finish(go_on, sink, &mut |s| spent += s) {
                settled = false;
            }
        }
        self.planner.spent += spent;
        settled
    }

    /// Whether the run itself has work (it goes before the sweep).
    fn run_busy(&self) -> bool {
        self.planning.is_some()
            || (!self.blocked && (self.pending.is_some() || !self.checkpoints.is_empty()))
            || self.session.as_ref().is_some_and(Session::effective_behind)
    }

    /// Takes the jobs' events and the verification ahead's waiting reports; `false` means stop.
    fn poll(&mut self, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        if !self.take_jobs(sink) {
            return false;
        }
        loop {
            let Some(ahead) = self.ahead.as_ref() else {
                return true;
            };
            match ahead.try_next() {
                Next::Report(report) => {
                    if !self.take(report, sink) {
                        return false;
                    }
                }
                Next::Nothing => return true,
                Next::Ended => {
                    self.ahead = None;
                    return true;
                }
            }
        }
    }

    /// Waits for the verification ahead's next report and takes it; `false` means stop. Gives
    /// up waiting when [`Engine::stopping_on`]'s question says stop.
    pub fn wait(&mut self, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        let functions = self.planner.functions();
        crate::physics::numerics::elementary::following(functions, || self.wait_here(sink))
    }

    fn wait_here(&mut self, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        loop {
            let Some(ahead) = self.ahead.as_ref() else {
                return true;
            };
            match ahead.next_within(std::time::Duration::from_millis(5)) {
                Next::Report(report) => return self.take(report, sink),
                Next::Ended => {
                    self.ahead = None;
                    return true;
                }
                Next::Nothing if !(self.keep_going)() => return true,
                Next::Nothing => {}
            }
        }
    }

    /// Takes one report of the verification ahead.
    fn take(&mut self, report: Report, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        let Some(session) = self.session.as_mut() else {
            self.ahead = None;
            return true;
        };
        let generation = session.generation();
        match report {
            Report::Progress {
                until,
                run,
                percent,
            } => sink(SimEvent::Ahead {
                generation,
                until,
                run,
                percent,
            }),
            Report::Verified {
                from,
                until,
                plan,
                estimate,
            } => {
                if let Err(e) = self.planner.charge_segment(session.spec(), plan, until) {
                    let message = refusal(session.spec(), &e);
                    self.ahead = None;
                    return self.stops(from, &message, sink);
                }
                sink(SimEvent::Verified {
                    generation,
                    from,
                    until,
                    plan,
                    error_estimate: estimate,
                })
            }
            Report::Ready(segment) => {
                session.queue(*segment);
                self.blocked = false;
                true
            }
            Report::Failed { from, error } => {
                let message = refusal(session.spec(), &error);
                self.ahead = None;
                self.stops(from, &message, sink)
            }
        }
    }

    /// The run cannot be verified beyond `from`: said at once (the verified part is still
    /// shown), and the run fails when it gets there.
    fn stops(&mut self, from: f64, why: &str, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        let Some(generation) = self.session.as_ref().map(Session::generation) else {
            return true;
        };
        let message = format!("beyond t = {from}: {why}");
        self.stop = Some((from, message.clone()));
        sink(SimEvent::Stops {
            generation,
            at: from,
            message,
        }) && self.stop_if_reached(sink)
    }

    /// Fails the run where it stops, once it has got there.
    fn stop_if_reached(&mut self, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        let Some(s) = self.session.as_ref() else {
            return true;
        };
        if !s.waits() || self.stop.as_ref().is_none_or(|(at, _)| s.horizon() < *at) {
            return true;
        }
        let generation = s.generation();
        let (_, message) = self.stop.take().unwrap_or_default();
        self.pending = None;
        self.checkpoints.clear();
        self.blocked = false;
        sink(SimEvent::Failed {
            generation,
            message,
        })
    }

    /// Takes a command; `false` means stop (quit, or nobody listens any more).
    pub fn handle(&mut self, command: &Command, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        let functions = self.planner.functions();
        crate::physics::numerics::elementary::following(functions, || {
            self.handle_here(command, sink)
        })
    }

    fn handle_here(&mut self, command: &Command, sink: &mut dyn FnMut(SimEvent) -> bool) -> bool {
        match *command {
            Command::Quit => return false,
            Command::Job {
                kind,
                stamp,
                ref spec,
            } => {
                debug_assert!(spec.as_ref().is_none_or(|s| s.kind() == kind));
                self.set_job(kind, spec.clone().map(|spec| spec.job(stamp)));
            }
            Command::Restart { generation, spec } => {
                self.jobs.retain(|j| !j.kind().ends_with_run());
                // Dropping the verification ahead cancels it.
                self.ahead = None;
                self.blocked = false;
                self.stop = None;
                self.session = None;
                self.pending = None;
                self.checkpoints.clear();
                // What is verified before anything is shown: the run, or its first segment.
                let mut first = spec;
                first.t_end = self.planner.book.horizons(&spec)[0];
                let needs_planning =
                    spec.method == Method::Auto && self.planner.book.lookup(&first).is_none();
                self.planning = Some((generation, spec));
                if needs_planning {
                    return sink(SimEvent::Planning { generation });
                }
            }
            Command::AdvanceTo { generation, t } => {
                if self.generation() == Some(generation) {
                    self.pending = Some((generation, t));
                    self.blocked = false;
                }
            }
            Command::Checkpoint { generation, t } => {
                self.checkpoints.push_back((generation, t));
                self.blocked = false;
            }
            Command::Book {
                key,
                plan,
                estimate,
            } => {
                self.planner.book.add(key, plan, estimate);
                if let Some(ahead) = &self.ahead {
                    ahead.forward(Forward::Plan(key, plan, estimate));
                }
            }
            Command::Release => {
                self.planner.book.awaits = false;
                if let Some(ahead) = &self.ahead {
                    ahead.forward(Forward::Release);
                }
            }
            Command::SetEffective { on, epoch } => {
                self.epoch = epoch;
                self.blocked = false;
                if let Some(spec) = self.planning.as_mut().map(|(_, s)| s) {
                    spec.effective = on;
                }
                if let Some(s) = self.session.as_mut() {
                    s.set_effective(on, epoch);
                }
            }
        }
        true
    }

    /// Resolves the pending restart's plan; `go_on` may cancel `auto`'s verification (a new
    /// command arrived), in which case planning resumes from scratch on the next call.
    fn plan(
        &mut self,
        go_on: &mut dyn FnMut(f64) -> bool,
        sink: &mut dyn FnMut(SimEvent) -> bool,
    ) -> bool {
        let Some((generation, spec)) = self.planning else {
            return true;
        };
        let horizons = self.planner.book.horizons(&spec);
        let mut progress = Progress::new(horizons[0]);
        let started = self
            .planner
            .start_until(generation, &spec, horizons[0], &mut |t| {
                if let Some((run, percent)) = progress.at(t) {
                    // A closed sink is seen by the next call's `sink` below.
                    sink(SimEvent::PlanProgress {
                        generation,
                        run,
                        percent,
                    });
                }
                go_on(t)
            });
        let started = match started {
            Err(StepError::Cancelled { .. }) => return true,
            started => started,
        };
        self.planning = None;
        match started {
            Ok((mut session, error_estimate)) => {
                session.set_effective(spec.effective, self.epoch);
                let plan = session.plan();
                let until = session.horizon();
                self.session = Some(session);
                // Priced a priori, every horizon: the first over the budget is where the run
                // stops, known (and said) now; only the horizons before it are verified.
                let book = &self.planner.book;
                let over = (1..horizons.len()).find_map(|j| {
                    let mut asked = spec;
                    asked.t_end = horizons[j];
                    book.check_auto(&asked).err().map(|e| (j, e))
                });
                let mut verified = horizons.clone();
                if let Some((j, _)) = &over {
                    verified.truncate(*j);
                }
                if verified.len() > 1 {
                    self.ahead = Some(Ahead::spawn(book.clone(), spec, &verified));
                }
                let started = sink(SimEvent::Started {
                    generation,
                    plan,
                    error_estimate,
                    until,
                });
                match over {
                    // The horizons before the stop are still verified.
                    Some((j, e)) if started => {
                        self.stops(horizons[j - 1], &refusal(&spec, &e), sink)
                    }
                    _ => started,
                }
            }
            Err(e) => {
                self.pending = None;
                self.checkpoints.clear();
                sink(SimEvent::Failed {
                    generation,
                    message: refusal(&spec, &e),
                })
            }
        }
    }

    /// Works one slice (at most `max_steps` steps, or one planning) towards the next target or
    /// checkpoint; `false` means stop.
    pub fn work(
        &mut self,
        max_steps: usize,
        go_on: &mut dyn FnMut(f64) -> bool,
        sink: &mut dyn FnMut(SimEvent) -> bool,
    ) -> bool {
        let functions = self.planner.functions();
        crate::physics::numerics::elementary::following(functions, || {
            self.work_here(max_steps, go_on, sink)
        })
    }

    fn work_here(
        &mut self,
        max_steps: usize,
        go_on: &mut dyn FnMut(f64) -> bool,
        sink: &mut dyn FnMut(SimEvent) -> bool,
    ) -> bool {
        if !self.poll(sink) {
            return false;
        }
        if self.planning.is_some() {
            return self.plan(go_on, sink);
        }
        if self.waiting() {
            return true;
        }
        let Some(s) = self.session.as_mut() else {
            self.pending = None;
            self.checkpoints.clear();
            return true;
        };
        let generation = s.generation();
        self.checkpoints.retain(|(g, _)| *g == generation);
        if self.pending.is_some_and(|(g, _)| g != generation) {
            self.pending = None;
        }
        let due = self.checkpoints.front().map(|c| c.1);
        let target = match (self.pending.map(|p| p.1), due) {
            (Some(p), Some(c)) => p.min(c),
            (Some(p), None) => p,
            (None, Some(c)) => c,
            // Only the overlay is behind: catch it up (a target at 0 moves nothing else).
            (None, None) => 0.0,
        };
        let (events, reached) = s.advance(target, max_steps);
        self.blocked = !reached && s.waits();
        for e in events {
            if !sink(e) {
                return false;
            }
        }
        if !reached {
            return !self.blocked || self.stop_if_reached(sink);
        }
        if let Some(c) = due.filter(|c| *c <= target) {
            self.checkpoints.pop_front();
            // Exactly at the time asked, even when the run has passed it (it computes ahead
            // of the display): the session integrates again from a snapshot.
            if let Some((state, reversals)) = s.checkpoint(c)
                && !sink(SimEvent::Checkpoint {
                    generation,
                    t: c,
                    state,
                    reversals,
                })
            {
                return false;
            }
        }
        if self.pending.is_some_and(|(_, p)| target >= p) {
            self.pending = None;
        }
        true
    }
}

/// Most steps of one slice of [`drive`]: a signal is seen between slices (a frame of a cast
/// whose run computes for seconds stopped only after it, issue 56).
const DRIVE_STEPS: usize = 4096;

/// Runs commands to completion on `engine`, synchronously, handing the events to `on_event`:
/// the worker's behaviour without a thread (replay verification, cast export, tests). The
/// panes' jobs are waited for before the run goes on. A signal to a headless command stops it
/// within a slice ([`Engine::stopping_on`]: what is left undone is left to the caller, who
/// stops too).
pub fn drive(engine: &mut Engine, commands: Vec<Command>, on_event: &mut dyn FnMut(SimEvent)) {
    let mut sink = |e| {
        on_event(e);
        true
    };
    for c in commands {
        engine.handle(&c, &mut sink);
    }
    let keep_going = engine.keep_going;
    loop {
        if !engine.settle_jobs(keep_going, &mut sink) || !engine.busy() {
            return;
        }
        // Waits for the verification ahead only where the run needs it to reach a target.
        if engine.waiting() {
            engine.wait(&mut sink);
        } else {
            engine.work(DRIVE_STEPS, &mut |_| keep_going(), &mut sink);
        }
        if !keep_going() {
            return;
        }
    }
}
