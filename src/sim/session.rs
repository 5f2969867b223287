//! One run of the explorer: the full integrator of a resolved plan, optionally the effective
//! one, reversal trackers, and samples on a fixed time grid.
//!
//! The grid (`i · sample_dt`, and `t_end` exactly) depends on the dynamics only, never on the
//! playback speed or the frame rate, so the trail at ×1024 is the same curve as at ×1.

use crate::physics::method::{Arithmetic, Asked};
use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use super::SimEvent;
use crate::physics::Model;
use crate::physics::flow::{EventTracker, Flow};
use crate::physics::method::Method;
use crate::physics::method::Settings;
use crate::physics::method::StepError;
use crate::physics::plan::Resolved;
/// What a session runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SessionSpec {
    /// The model and its problem.
    pub model: Model,
    /// Method as asked (`auto` is resolved by the engine before the session starts).
    pub method: Method,
    /// Tolerance as asked.
    pub tolerance: f64,
    /// End of the run.
    pub t_end: f64,
    /// Whether the effective overlay is integrated from the start (the engine turns it on).
    pub effective: bool,
    /// Spacing of the sample grid (simulated time), set by the dynamics.
    pub sample_dt: f64,
    /// The preset's fixed step (`run.step`) for a fixed-step method, as `simulate` takes it.
    pub step: Option<f64>,
}

/// A sample of the motion for drawing, in the scene's own coordinates: its slow coordinate (the
/// rattleback's `α`, the pendulum's `θ`, the celt's heading), its rate (`α̇`, `θ̇`, the celt's
/// spin) and its fast coordinate (issue 57: the names are no one scene's).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// Time.
    pub t: f64,
    /// The slow coordinate.
    pub slow: f64,
    /// Its rate.
    pub rate: f64,
    /// Relative error of the conserved quantity at the last step end (for the driven
    /// pendulum: the drift of the limit's energy, relative to its scale).
    pub energy_error: f64,
    /// The fast coordinate (the rattleback's tilt `γ`, whose envelope the body pane draws;
    /// the pendulum's ripple `θ − Θ`).
    pub fast: f64,
    /// The body's lean (the celt's): see [`crate::physics::flow::Sample::lean`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lean: Option<[f64; 2]>,
}

/// Steps between two snapshots of the full motion, at first (the spacing doubles whenever
/// [`MAX_SNAPSHOTS`] are kept).
const SNAPSHOT_EVERY: u64 = 32;
/// Most snapshots kept: memory stays bounded however far the worker runs ahead.
const MAX_SNAPSHOTS: usize = 256;

/// The full motion at a step boundary: enough to integrate again from there, bit for bit.
struct Snapshot {
    integrator: Box<dyn Flow>,
    tracker: EventTracker,
    reversals: usize,
    last_reversal: Option<f64>,
}

impl Snapshot {
    fn of(track: &Track) -> Self {
        Self {
            integrator: track.integrator.boxed(),
            tracker: track.tracker,
            reversals: track.reversals,
            last_reversal: track.last_reversal,
        }
    }

    fn time(&self) -> f64 {
        self.integrator.time()
    }
}

/// Snapshots of the full motion behind the worker's look-ahead, so the exact state at a time the
/// screen shows (a pause, a checkpoint) can be had after the worker has integrated past it.
struct Rewind {
    snapshots: VecDeque<Snapshot>,
    every: u64,
    since: u64,
}

impl Rewind {
    fn new(track: &Track) -> Self {
        Self {
            snapshots: VecDeque::from([Snapshot::of(track)]),
            every: SNAPSHOT_EVERY,
            since: 0,
        }
    }

    /// Called before each step of the full motion.
    fn before_step(&mut self, track: &Track) {
        self.since += 1;
        if self.since < self.every {
            return;
        }
        self.since = 0;
        self.snapshots.push_back(Snapshot::of(track));
        if self.snapshots.len() > MAX_SNAPSHOTS {
            // Keep every other one (the first and the newest stay): the spacing doubles.
            let kept: VecDeque<Snapshot> = std::mem::take(&mut self.snapshots)
                .into_iter()
                .enumerate()
                .filter(|(i, _)| i % 2 == 0)
                .map(|(_, s)| s)
                .collect();
            self.snapshots = kept;
            self.every *= 2;
        }
    }

    /// Forgets the snapshots no time at or after `t` needs.
    fn forget_before(&mut self, t: f64) {
        while self.snapshots.len() > 1 && self.snapshots[1].time() <= t {
            self.snapshots.pop_front();
        }
    }

    /// The exact state at `t` and the reversals up to it, integrating again from the newest
    /// snapshot at or before `t` (the same steps, so the same bits as the run itself).
    fn state_at(&self, t: f64, t_end: f64) -> Option<(Vec<f64>, usize)> {
        let from = self.snapshots.iter().rev().find(|s| s.time() <= t)?;
        let mut track = Track {
            integrator: from.integrator.boxed(),
            cap: crate::physics::method::StepCap::NONE,
            tracker: from.tracker,
            e0: 0.0,
            scale: 1.0,
            next: 0,
            reversals: from.reversals,
            last_reversal: from.last_reversal,
        };
        while track.integrator.time() < t {
            track.step(t_end, 0, 0, false).ok()?;
        }
        Some(track.state_in_last_step(t))
    }
}

struct Track {
    integrator: Box<dyn Flow>,
    tracker: EventTracker,
    e0: f64,
    scale: f64,
    /// Index of the next grid sample this track emits.
    next: u64,
    /// Steps this track may take (ten times its predicted work): a run that exceeds it is
    /// stopped, the same step on every machine.
    cap: crate::physics::method::StepCap,
    /// Reversals found so far, and the time of the last (a step holds at most one, so this is
    /// all a checkpoint inside the last step needs; memory stays bounded).
    reversals: usize,
    last_reversal: Option<f64>,
}

impl Track {
    fn new(
        model: &Model,
        method: Method,
        settings: Settings,
        t_end: f64,
        arithmetic: Arithmetic,
    ) -> Result<Self, StepError> {
        let ask = Asked::new(method, settings.tolerance, settings.step, t_end);
        let integrator = model.build(&ask, arithmetic)?;
        let e0 = integrator.energy();
        let cap = crate::physics::method::StepCap::of(model.predicted_seconds(&ask));
        Ok(Self {
            cap,
            tracker: EventTracker::new(integrator.event_value()),
            integrator,
            e0,
            scale: if e0 == 0.0 { 1.0 } else { e0.abs() },
            next: 0,
            reversals: 0,
            last_reversal: None,
        })
    }

    /// The state at `t` inside the last step (or at its end) and the reversals up to `t`.
    fn state_in_last_step(&mut self, t: f64) -> (Vec<f64>, usize) {
        let y = self.integrator.state_at(t);
        // `t` lies in the last step, which holds at most the last reversal.
        let reversals = self.reversals - usize::from(self.last_reversal.is_some_and(|r| r > t));
        (y, reversals)
    }

    fn point(&mut self, t: f64) -> Point {
        let y = self.integrator.sample(t);
        Point {
            t,
            slow: y.q,
            rate: y.q_dot,
            energy_error: (self.integrator.energy() - self.e0) / self.scale,
            fast: y.fast,
            lean: y.lean,
        }
    }

    /// One step; the second events (the flow's marks) and the reversal inside it, as the events
    /// that report them.
    fn step(
        &mut self,
        t_end: f64,
        generation: u64,
        epoch: u64,
        effective: bool,
    ) -> Result<Vec<SimEvent>, StepError> {
        self.cap
            .check(self.integrator.stats().steps, self.integrator.time())?;
        self.integrator.step(t_end)?;
        // The display counts an event once its time passes when it became certain.
        let r = self
            .tracker
            .after_step(self.integrator.as_mut())
            .map(|t| self.integrator.event_known_at(t));
        if let Some(t) = r {
            self.reversals += 1;
            self.last_reversal = Some(t);
        }
        let mut out: Vec<SimEvent> = if effective {
            Vec::new()
        } else {
            self.integrator
                .marks()
                .iter()
                .map(|&t| SimEvent::Mark { generation, t })
                .collect()
        };
        out.extend(r.map(|t| SimEvent::Counted {
            generation,
            epoch,
            t,
            effective,
        }));
        Ok(out)
    }
}

/// A synchronous run: `advance` integrates to a target and returns what happened.
pub struct Session {
    spec: SessionSpec,
    plan: Resolved,
    generation: u64,
    full: Track,
    rewind: Rewind,
    effective: Option<Track>,
    /// Stamp of the overlay's current life: samples of an older one are ignored by the app.
    epoch: u64,
    finished: bool,
    failed: bool,
    /// The horizon the integrating plan was verified for, where its steps end: the run's end,
    /// except in a run verified in segments ([`super::segments`]), whose plans take over one
    /// another at their horizons.
    horizon: f64,
    /// Added to the integrating track's own count of reversals: the count shown at the last
    /// switch, less the new track's own count there (they agree but for an event within the
    /// tolerance of the switch).
    offset: i64,
    /// Segments verified ahead, waiting for the run to reach their start.
    queued: VecDeque<Segment>,
    /// Earlier segments, kept for checkpoints at times behind the last switch.
    past: VecDeque<Past>,
}

/// A segment that was integrated, kept for the exact states behind the switch that ended it.
struct Past {
    until: f64,
    track: Track,
    rewind: Rewind,
    offset: i64,
}

/// The plan of a longer horizon, integrated from `t = 0` (without being shown) to the start of
/// its segment (the horizon the run has reached when it takes over), ready to take over from
/// the run there. Prepared on the verifying thread, so the display never waits for its catch-up.
pub struct Segment {
    until: f64,
    plan: Resolved,
    track: Track,
    rewind: Rewind,
    /// Its own count of reversals at `from`.
    at_from: usize,
    /// Events of its last catch-up step that lie after `from` (shown after the switch).
    late_reversal: Option<f64>,
    late_marks: Vec<f64>,
}

impl Segment {
    /// `plan` (verified for the horizon `until`) integrated from `t = 0` to the first step end
    /// at or after `from`; `go_on` is asked every few hundred steps.
    ///
    /// # Errors
    /// When the plan cannot be built, a step fails, or `go_on` says stop
    /// ([`StepError::Cancelled`]).
    pub fn prepare(
        spec: &SessionSpec,
        plan: Resolved,
        from: f64,
        until: f64,
        arithmetic: Arithmetic,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Self, StepError> {
        let mut track = Track::new(&spec.model, plan.method, plan.settings(), until, arithmetic)?;
        let mut rewind = Rewind::new(&track);
        let mut last = Vec::new();
        let mut steps = 0_u64;
        while track.integrator.time() < from {
            rewind.before_step(&track);
            last = track.step(until, 0, 0, false)?;
            steps += 1;
            if steps.is_multiple_of(256) && !go_on(track.integrator.time()) {
                return Err(StepError::Cancelled {
                    t: track.integrator.time(),
                });
            }
        }
        let mut late_reversal = None;
        let mut late_marks = Vec::new();
        for e in last {
            match e {
                SimEvent::Counted { t, .. } if t > from => late_reversal = Some(t),
                SimEvent::Mark { t, .. } if t > from => late_marks.push(t),
                _ => {}
            }
        }
        let at_from = track.reversals - usize::from(late_reversal.is_some());
        rewind.forget_before(from);
        Ok(Self {
            until,
            plan,
            track,
            rewind,
            at_from,
            late_reversal,
            late_marks,
        })
    }
}

impl Session {
    /// Starts a run of the resolved `plan` at `t = 0`, its fixed steps added to the time by
    /// `arithmetic` (a replay of an old file: as it was recorded).
    ///
    /// # Errors
    /// [`StepError::Unplanned`] when `plan` is still `auto`.
    pub fn new(
        generation: u64,
        spec: SessionSpec,
        plan: Resolved,
        arithmetic: Arithmetic,
    ) -> Result<Self, StepError> {
        Self::until(generation, spec, plan, spec.t_end, arithmetic)
    }

    /// [`Session::new`] for a run verified in segments: `plan` was verified for the horizon
    /// `until` only, and integrates as `auto` verified it (its steps end there); the run goes
    /// past `until` once the next segment is [queued](Session::queue).
    ///
    /// # Errors
    /// As [`Session::new`].
    pub fn until(
        generation: u64,
        mut spec: SessionSpec,
        plan: Resolved,
        until: f64,
        arithmetic: Arithmetic,
    ) -> Result<Self, StepError> {
        spec.sample_dt = grid_spacing(spec.sample_dt, spec.t_end);
        let horizon = until.min(spec.t_end);
        let full = Track::new(
            &spec.model,
            plan.method,
            plan.settings(),
            horizon,
            arithmetic,
        )?;
        Ok(Self {
            spec,
            plan,
            generation,
            rewind: Rewind::new(&full),
            full,
            effective: None,
            epoch: 0,
            finished: false,
            failed: false,
            horizon,
            offset: 0,
            queued: VecDeque::new(),
            past: VecDeque::new(),
        })
    }

    /// What it runs.
    #[must_use]
    pub fn spec(&self) -> &SessionSpec {
        &self.spec
    }

    /// The horizon the integrating plan was verified for (the run's end, unless verified in
    /// segments).
    #[must_use]
    pub fn horizon(&self) -> f64 {
        self.horizon
    }

    /// Queues the next segment of a run verified in segments: it takes over when the run
    /// reaches its start.
    pub fn queue(&mut self, segment: Segment) {
        self.queued.push_back(segment);
    }

    /// Whether the run has reached its verified horizon, short of its end, with no segment
    /// queued to go on: it waits for the verification ahead.
    #[must_use]
    pub fn waits(&self) -> bool {
        self.horizon < self.spec.t_end
            && self.full.integrator.time() >= self.horizon
            && self.queued.is_empty()
    }

    /// The queued segment takes over at the horizon the run has reached: its samples and events
    /// after its start are the run's from now on.
    fn switch(&mut self, segment: Segment, events: &mut Vec<SimEvent>) {
        let shown = counted(self.full.reversals, self.offset);
        let next = self.full.next;
        let track = std::mem::replace(&mut self.full, segment.track);
        let rewind = std::mem::replace(&mut self.rewind, segment.rewind);
        self.past.push_back(Past {
            until: self.horizon,
            track,
            rewind,
            offset: self.offset,
        });
        self.full.next = next;
        self.offset = wide(shown) - wide(segment.at_from);
        self.horizon = segment.until.min(self.spec.t_end);
        self.plan = segment.plan;
        let generation = self.generation;
        events.extend(
            segment
                .late_marks
                .iter()
                .map(|&t| SimEvent::Mark { generation, t }),
        );
        events.extend(segment.late_reversal.map(|t| SimEvent::Counted {
            generation,
            epoch: self.epoch,
            t,
            effective: false,
        }));
    }

    /// Time the full integrator has reached.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.full.integrator.time()
    }

    /// The resolved plan this run integrates.
    #[must_use]
    pub fn plan(&self) -> Resolved {
        self.plan
    }

    /// The exact state at `t` and the reversals up to it, for any `t` the run has reached:
    /// inside the last step from the method's interpolant, behind it by integrating again from
    /// a snapshot (the worker computes ahead of the display; what is recorded is the state at
    /// the displayed time, the same bits a run stopped there gives). `None` beyond the run.
    /// Times before `t` are forgotten: checkpoints come in order.
    pub fn checkpoint(&mut self, t: f64) -> Option<(Vec<f64>, usize)> {
        // Behind the last switch: the segment that showed `t` (a segment shows up to its
        // horizon, inclusive).
        while self.past.front().is_some_and(|p| p.until < t) {
            self.past.pop_front();
        }
        if let Some(p) = self.past.front_mut() {
            return state_of(&mut p.track, &mut p.rewind, t, p.until)
                .map(|(y, n)| (y, counted(n, p.offset)));
        }
        state_of(&mut self.full, &mut self.rewind, t, self.horizon)
            .map(|(y, n)| (y, counted(n, self.offset)))
    }

    /// The run's stamp.
    #[must_use]
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The method actually integrating (what `auto` chose).
    #[must_use]
    pub fn method(&self) -> Method {
        self.full.integrator.method()
    }

    /// Turns the effective overlay on or off; `epoch` stamps what it sends from now on. When
    /// turned on, the limit starts again from `t = 0` and catches up, sample by sample and
    /// reversal by reversal, with the full motion.
    pub fn set_effective(&mut self, on: bool, epoch: u64) {
        self.epoch = epoch;
        self.effective = if on {
            Track::new(
                &self.spec.model,
                Method::Effective,
                // The limit `simulate` reports: the same run, drawn, counted and exported.
                Settings {
                    tolerance: self.spec.model.kind().limit_tolerance(),
                    step: None,
                },
                self.spec.t_end,
                // Adaptive, and without a ripple to add back: no rule applies.
                Arithmetic::default(),
            )
            .ok()
        } else {
            None
        };
    }

    /// Time of grid sample `i` (the last one is `t_end` exactly).
    fn grid(&self, i: u64) -> f64 {
        grid_time(i, self.spec.sample_dt, self.spec.t_end)
    }

    /// Whether grid sample `i` exists (the grid stops at `t_end`).
    fn on_grid(&self, i: u64) -> bool {
        i == 0 || self.grid(i - 1) < self.spec.t_end
    }

    /// Integrates until `t` (clamped to `t_end`), at most `max_steps` steps of the full model;
    /// emits the grid samples passed, and the reversals. Returns the events, and whether `t`
    /// was reached.
    pub fn advance(&mut self, t: f64, max_steps: usize) -> (Vec<SimEvent>, bool) {
        let mut events = Vec::new();
        if self.failed || (self.finished && !self.effective_behind()) {
            return (events, true);
        }
        let target = t.min(self.spec.t_end);
        let generation = self.generation;
        let mut full = Vec::new();
        let mut steps = 0;
        let reached = loop {
            while self.on_grid(self.full.next)
                && self.grid(self.full.next) <= target
                && self.grid(self.full.next) <= self.full.integrator.time()
            {
                let ts = self.grid(self.full.next);
                full.push(self.full.point(ts));
                self.full.next += 1;
            }
            if self.full.integrator.time() >= target {
                break true;
            }
            if self.full.integrator.time() >= self.horizon {
                // The end of a verified segment: the next one takes over, or the run waits.
                match self.queued.pop_front() {
                    Some(segment) => {
                        self.switch(segment, &mut events);
                        continue;
                    }
                    None => break false,
                }
            }
            if steps >= max_steps {
                break false;
            }
            self.rewind.before_step(&self.full);
            match self.full.step(self.horizon, generation, self.epoch, false) {
                Ok(reversal) => events.extend(reversal),
                Err(e) => {
                    events.push(SimEvent::Failed {
                        generation,
                        message: format!("integration failed: {e}"),
                    });
                    self.failed = true;
                    break false;
                }
            }
            steps += 1;
        };
        let effective = self.catch_up_effective(&mut events, max_steps);
        let t_reached = full.last().map(|p| p.t);
        events.push(SimEvent::Samples {
            generation,
            epoch: self.epoch,
            full,
            effective,
            t: t_reached,
            steps: self.full.integrator.stats().steps,
        });
        if reached && target >= self.spec.t_end && !self.finished {
            self.finished = true;
            events.push(SimEvent::Finished { generation });
        }
        (events, reached)
    }

    /// Brings the overlay to the full motion's last emitted sample (at most `max_steps` of its
    /// own steps), returning its samples.
    fn catch_up_effective(&mut self, events: &mut Vec<SimEvent>, max_steps: usize) -> Vec<Point> {
        let mut out = Vec::new();
        let upto = self.full.next;
        let (generation, epoch, t_end, dt) = (
            self.generation,
            self.epoch,
            self.spec.t_end,
            self.spec.sample_dt,
        );
        let Some(track) = self.effective.as_mut() else {
            return out;
        };
        let mut steps = 0;
        while track.next < upto {
            let ts = grid_time(track.next, dt, t_end);
            if track.integrator.time() < ts {
                if steps >= max_steps {
                    break;
                }
                steps += 1;
                match track.step(t_end, generation, epoch, true) {
                    Ok(reversal) => events.extend(reversal),
                    Err(e) => {
                        events.push(SimEvent::Failed {
                            generation,
                            message: format!("integration failed: effective model: {e}"),
                        });
                        self.effective = None;
                        return out;
                    }
                }
                continue;
            }
            out.push(track.point(ts));
            track.next += 1;
        }
        out
    }

    /// Whether the overlay is behind the full motion's samples.
    #[must_use]
    pub fn effective_behind(&self) -> bool {
        self.effective
            .as_ref()
            .is_some_and(|e| e.next < self.full.next)
    }
}

/// The exact state of `track` at `t` and its own count of reversals up to `t`: inside its last
/// step from the method's interpolant, behind it by integrating again from a snapshot of
/// `rewind` (steps end at `horizon`). Snapshots before `t` are forgotten.
fn state_of(
    track: &mut Track,
    rewind: &mut Rewind,
    t: f64,
    horizon: f64,
) -> Option<(Vec<f64>, usize)> {
    let i = &track.integrator;
    // Exactly the end of the last step: its state, not an interpolation.
    #[allow(clippy::float_cmp)]
    let at_end = t == i.time();
    let out = if at_end || (t >= i.time_prev() && t < i.time()) {
        Some(track.state_in_last_step(t))
    } else if t < i.time_prev() {
        rewind.state_at(t, horizon)
    } else {
        None
    };
    rewind.forget_before(t);
    out
}

/// A track's own count shifted by the offset of its switch (never below zero).
fn counted(own: usize, offset: i64) -> usize {
    usize::try_from(wide(own).saturating_add(offset)).unwrap_or(0)
}

/// A count as a signed number (counts never come near `i64::MAX`).
fn wide(n: usize) -> i64 {
    i64::try_from(n).unwrap_or(i64::MAX)
}

/// Most samples of a run's grid: memory and the work of drawing stay bounded whatever the
/// dynamics ask (a spacing of 0, or not a number, from a degenerate body).
pub const MAX_GRID_SAMPLES: f64 = 1e6;

/// The grid's spacing: the one asked, but at least `t_end / MAX_GRID_SAMPLES` (a spacing that is
/// not a positive number becomes that).
#[must_use]
pub fn grid_spacing(asked: f64, t_end: f64) -> f64 {
    let least = t_end / MAX_GRID_SAMPLES;
    if asked.is_finite() && asked > least {
        asked
    } else {
        least
    }
}

/// Time of grid sample `i`: `i · dt`, never past `t_end` (computed from the index, so no
/// rounding accumulates).
fn grid_time(i: u64, dt: f64, t_end: f64) -> f64 {
    (i as f64 * dt).min(t_end)
}
