//! The run as the screen shows it: the displayed time, the samples and events received from the
//! worker, and the pacing that asks the worker for more.
//!
//! Two clocks: `reached` is how far the worker's samples go; `shown` is the displayed time,
//! which never passes `reached` nor the `goal` the user's clock set. Everything drawn and
//! counted is cut at `shown`: a reversal the worker found ahead of the display is counted when
//! the display gets there. The worker is asked for at most a short lead beyond the goal, so a
//! pause or a change takes effect at once, however slow the integration.
use crate::physics::numerics::elementary::Elementary;

use crate::physics::plan::Resolved;
use crate::physics::scene::Found;
use crate::sim::{Command, Point, SessionSpec, SimEvent};

/// Most trail points kept per trail (the oldest half is dropped beyond).
pub const TRAIL_CAP: usize = 40_000;
/// Most event times kept per motion; older ones already on screen are only counted.
pub const EVENTS_CAP: usize = 4_096;

/// Times of events (reversals) in order: the recent ones kept, the older ones counted, so
/// memory stays bounded however long a run reverses.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Events {
    dropped: usize,
    times: Vec<f64>,
}

impl Events {
    /// Records an event at `t`; when too many are kept, forgets the oldest that are at or before
    /// `shown` (they stay counted).
    pub fn push(&mut self, t: f64, shown: f64) {
        self.times.push(t);
        if self.times.len() > EVENTS_CAP {
            let old =
                self.times[..self.times.len() - EVENTS_CAP / 2].partition_point(|x| *x <= shown);
            self.times.drain(..old);
            self.dropped += old;
        }
    }

    /// How many happened at or before `t` (`t` at least the last forgotten one's time).
    #[must_use]
    pub fn count_upto(&self, t: f64) -> usize {
        self.dropped + self.times.partition_point(|x| *x <= t)
    }

    /// The kept times at or before `t`.
    #[must_use]
    pub fn recent_upto(&self, t: f64) -> &[f64] {
        &self.times[..self.times.partition_point(|x| *x <= t)]
    }

    /// Every kept time (possibly ahead of the display).
    #[must_use]
    pub fn kept(&self) -> &[f64] {
        &self.times
    }

    /// No events.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.dropped == 0 && self.times.is_empty()
    }

    fn clear(&mut self) {
        *self = Self::default();
    }
}
/// Wall seconds of lead the worker is asked to compute beyond the displayed clock.
const LEAD: f64 = 0.25;

/// Where `auto`'s plan stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlanState {
    /// Not known yet (the worker has not answered).
    Pending,
    /// `auto` is verifying its choice over the whole run; nothing is shown until it is done.
    /// Its `run`-th integration (0 before the first report) has reached `percent` of the
    /// horizon.
    Verifying {
        /// Which of `auto`'s integrations.
        run: u32,
        /// How far it has reached, in whole percent.
        percent: u8,
    },
    /// Integrating this plan; `estimate` is `auto`'s verified error when it planned.
    Running {
        /// The plan.
        plan: Resolved,
        /// `auto`'s error estimate.
        estimate: Option<f64>,
    },
}

/// Progress of the current run.
#[derive(Clone, Debug)]
pub struct RunState {
    /// Stamp of the run; events of older runs are ignored.
    pub generation: u64,
    /// Stamp of the overlay's life; its samples from an older life are ignored.
    pub epoch: u64,
    /// Playing or paused.
    pub playing: bool,
    /// Simulated seconds per wall second.
    pub speed: f64,
    /// Where the user's clock has got to.
    pub goal: f64,
    /// The displayed time.
    pub shown: f64,
    /// Time of the last sample received.
    pub reached: f64,
    /// End of the run.
    pub t_end: f64,
    /// Spacing of the run's sample grid: the worker is always asked for one sample past the
    /// goal, so a paused display sits exactly on its time (as it does after playing).
    pub sample_dt: f64,
    /// Samples of the full motion (possibly ahead of `shown`).
    pub trail: Vec<Point>,
    /// Samples of the effective motion.
    pub effective_trail: Vec<Point>,
    /// Reversal times of the full motion (possibly ahead of `shown`).
    pub reversals: Events,
    /// The model's second kind of event (the pendulum's falls, found here between consecutive
    /// samples; the celt's crossings, sent by the worker), with where they are found; `None` for
    /// models without them.
    pub second: Option<(Found, Events)>,
    /// Reversal times of the effective motion.
    pub effective_reversals: Events,
    /// The worker reached `t_end`.
    pub finished: bool,
    /// The run failed.
    pub failed: Option<String>,
    /// Steps taken by the worker in this run.
    pub steps: u64,
    /// The plan integrating.
    pub plan: PlanState,
    /// Steps per wall second, smoothed.
    pub rate: f64,
    /// The latest time the display may show (a replay: the next recorded displayed time, so it
    /// never shows a time the lecturer did not).
    pub ceiling: Option<f64>,
    steps_at_tick: u64,
    /// The verified segments of the run, in order (one, covering the whole run, unless `auto`
    /// verifies it in segments): `plan` is the one the displayed time lies in.
    pub segments: Vec<VerifiedSegment>,
    /// How far the verification ahead has come, while it goes on.
    pub ahead: Option<AheadProgress>,
    /// Where the run stops: a later segment could not be verified (it fails there).
    pub stops: Option<f64>,
    /// The failure at that stop, once the worker got there: it takes effect when the display
    /// has shown everything before it.
    failing: Option<String>,
}

/// A segment of the run and the plan `auto` verified for it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VerifiedSegment {
    /// Shown after this time (0 for the first).
    pub from: f64,
    /// Up to this one, inclusive: the horizon its plan was verified for.
    pub until: f64,
    /// The plan.
    pub plan: Resolved,
    /// `auto`'s error estimate over `[0, until]`.
    pub estimate: Option<f64>,
}

/// The verification ahead of the display: the horizon being verified and how far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AheadProgress {
    /// The horizon being verified.
    pub until: f64,
    /// Which of `auto`'s integrations.
    pub run: u32,
    /// In whole percent of the horizon.
    pub percent: u8,
}

impl RunState {
    /// A paused run at `t = 0`, not started.
    #[must_use]
    pub fn new(t_end: f64) -> Self {
        Self {
            generation: 0,
            epoch: 0,
            playing: false,
            speed: 1.0,
            goal: 0.0,
            shown: 0.0,
            reached: 0.0,
            t_end,
            sample_dt: 0.0,
            trail: Vec::new(),
            effective_trail: Vec::new(),
            reversals: Events::default(),
            second: None,
            effective_reversals: Events::default(),
            finished: false,
            failed: None,
            steps: 0,
            plan: PlanState::Pending,
            rate: 0.0,
            ceiling: None,
            steps_at_tick: 0,
            segments: Vec::new(),
            ahead: None,
            stops: None,
            failing: None,
        }
    }

    /// How far the run is verified: the horizon of its last verified segment (0 before its
    /// plan).
    #[must_use]
    pub fn verified(&self) -> f64 {
        self.segments.last().map_or(0.0, |s| s.until)
    }

    /// The first segment verified ahead whose estimate misses `tolerance` and which the display
    /// has not reached: where the run will stop meeting it, known before it is shown.
    #[must_use]
    pub fn missed_ahead(&self, tolerance: f64) -> Option<f64> {
        self.segments
            .iter()
            .find(|s| s.from >= self.shown && s.estimate.is_some_and(|e| e > tolerance))
            .map(|s| s.from)
    }

    /// The plan of the segment the displayed time lies in.
    fn follow_segments(&mut self) {
        let shown = self.shown;
        if let Some(s) = self
            .segments
            .iter()
            .rev()
            .find(|s| s.from < shown)
            .or(self.segments.first())
        {
            self.plan = PlanState::Running {
                plan: s.plan,
                estimate: s.estimate,
            };
        }
    }

    /// Starts `spec` from `t = 0` as a new generation; the commands that start it.
    pub fn restart(&mut self, spec: SessionSpec) -> Vec<Command> {
        let (generation, epoch, playing, speed, rate) = (
            self.generation + 1,
            self.epoch,
            self.playing,
            self.speed,
            self.rate,
        );
        *self = Self {
            generation,
            epoch,
            playing,
            speed,
            rate,
            sample_dt: spec.sample_dt,
            ..Self::new(spec.t_end)
        };
        if let Some(second) = spec.model.kind().words().second_events {
            self.second = Some((second.found, Events::default()));
        }
        vec![
            Command::Restart { generation, spec },
            self.advance_command(),
        ]
    }

    /// What the worker is asked to reach: the goal, plus a short lead while playing.
    #[must_use]
    pub fn target(&self) -> f64 {
        let lead = if self.playing { LEAD * self.speed } else { 0.0 };
        (self.goal + lead.max(self.sample_dt)).min(self.t_end)
    }

    /// The worker command for the current target.
    #[must_use]
    pub fn advance_command(&self) -> Command {
        Command::AdvanceTo {
            generation: self.generation,
            t: self.target(),
        }
    }

    /// The display reached the end of the run (or it failed).
    #[must_use]
    pub fn done(&self) -> bool {
        self.failed.is_some() || (self.finished && self.shown >= self.reached)
    }

    /// Pauses at the displayed time: the worker stops where it is.
    pub fn pause(&mut self) -> Command {
        self.playing = false;
        self.goal = self.shown;
        self.advance_command()
    }

    /// Pauses at the goal (a replayed pause, at the recorded time the replay sought).
    pub fn pause_at_goal(&mut self) -> Command {
        self.playing = false;
        self.show();
        self.advance_command()
    }

    /// Moves the displayed clock one frame (`dt` simulated seconds) forward, paused.
    pub fn step(&mut self, dt: f64) -> Command {
        self.playing = false;
        self.goal = (self.shown + dt).min(self.t_end);
        // The worker may already be past the new goal (it computed ahead while playing): no
        // sample will arrive to move the display, so move it now.
        self.show();
        self.advance_command()
    }

    /// Sets the displayed clock to `t` (replay keeps the recorded times).
    pub fn seek(&mut self, t: f64) -> Command {
        self.goal = t.min(self.t_end);
        self.show();
        self.advance_command()
    }

    /// Sets the latest time the display may show, and shows what it now allows. A replay
    /// raises it after applying the lines it read; a pause read in that same pass was shown
    /// under the old ceiling (the last clock line), and a worker already past the pause sends
    /// nothing that would show it again: the follower showed the clock line's time, not the
    /// lecturer's pause, until the next line came.
    pub fn set_ceiling(&mut self, ceiling: Option<f64>) {
        self.ceiling = ceiling;
        self.show();
    }

    fn show(&mut self) {
        self.shown = self
            .goal
            .min(self.reached)
            .min(self.ceiling.unwrap_or(f64::INFINITY));
        if self.playing && self.finished && self.shown >= self.reached {
            self.playing = false;
        }
        if self.segments.len() > 1 {
            self.follow_segments();
        }
        if self.failing.is_some() && self.shown >= self.reached {
            self.failed = self.failing.take();
            self.playing = false;
        }
    }

    /// Advances the clock by `wall_seconds × speed` while playing; the command asking for more.
    pub fn tick(&mut self, wall_seconds: f64) -> Vec<Command> {
        let done = self.steps.saturating_sub(self.steps_at_tick) as f64;
        self.steps_at_tick = self.steps;
        if wall_seconds > 0.0 {
            let now = done / wall_seconds;
            self.rate = if self.rate == 0.0 {
                now
            } else {
                0.8 * self.rate + 0.2 * now
            };
        }
        if !self.playing || self.failed.is_some() {
            return Vec::new();
        }
        // The clock never runs ahead of what is computed by more than one tick: when the
        // integration cannot keep up, the display follows it instead of piling up a backlog.
        let dt = wall_seconds * self.speed;
        self.goal = (self.goal + dt).min(self.reached + dt).min(self.t_end);
        self.show();
        vec![self.advance_command()]
    }

    /// Takes a worker event about the run's plan (its verification, its segments); whether
    /// anything visible changed.
    fn on_plan(&mut self, event: &SimEvent) -> bool {
        match *event {
            SimEvent::Planning { generation } if generation == self.generation => {
                self.plan = PlanState::Verifying { run: 0, percent: 0 };
                true
            }
            SimEvent::PlanProgress {
                generation,
                run,
                percent,
            } if generation == self.generation
                && matches!(self.plan, PlanState::Verifying { .. }) =>
            {
                self.plan = PlanState::Verifying { run, percent };
                true
            }
            SimEvent::Started {
                generation,
                plan,
                error_estimate,
                until,
            } if generation == self.generation => {
                self.plan = PlanState::Running {
                    plan,
                    estimate: error_estimate,
                };
                self.segments = vec![VerifiedSegment {
                    from: 0.0,
                    until,
                    plan,
                    estimate: error_estimate,
                }];
                true
            }
            SimEvent::Verified {
                generation,
                from,
                until,
                plan,
                error_estimate,
            } if generation == self.generation => {
                self.segments.push(VerifiedSegment {
                    from,
                    until,
                    plan,
                    estimate: error_estimate,
                });
                self.ahead = None;
                self.follow_segments();
                true
            }
            SimEvent::Ahead {
                generation,
                until,
                run,
                percent,
            } if generation == self.generation => {
                self.ahead = Some(AheadProgress {
                    until,
                    run,
                    percent,
                });
                true
            }
            SimEvent::Stops { generation, at, .. } if generation == self.generation => {
                self.stops = Some(at);
                self.ahead = None;
                true
            }
            _ => false,
        }
    }

    /// Takes a worker event of this run; whether anything visible changed.
    pub fn on_sim(&mut self, event: SimEvent, overlay: bool) -> bool {
        match event {
            e @ (SimEvent::Planning { .. }
            | SimEvent::PlanProgress { .. }
            | SimEvent::Started { .. }
            | SimEvent::Verified { .. }
            | SimEvent::Ahead { .. }
            | SimEvent::Stops { .. }) => self.on_plan(&e),
            SimEvent::Samples {
                generation,
                epoch,
                full,
                effective,
                t,
                steps,
            } if generation == self.generation => {
                if let Some(t) = t {
                    self.reached = self.reached.max(t);
                }
                if let Some((Found::SlowAngleFalls, falls)) = self.second.as_mut() {
                    // `Θ = θ − ripple`; a fall is `cos Θ` going from positive to negative.
                    let up = |p: &Point| (p.slow - p.fast).e_cos();
                    let mut prev = self.trail.last().copied();
                    for p in &full {
                        if let Some(q) = prev {
                            let (a, b) = (up(&q), up(p));
                            if a > 0.0 && b <= 0.0 {
                                falls.push(q.t + (p.t - q.t) * a / (a - b), self.shown);
                            }
                        }
                        prev = Some(*p);
                    }
                }
                push_capped(&mut self.trail, full);
                if overlay && epoch == self.epoch {
                    push_capped(&mut self.effective_trail, effective);
                }
                self.steps = steps;
                let before = self.shown;
                self.show();
                self.shown > before || self.trail.len() <= 1
            }
            SimEvent::Counted {
                generation,
                epoch,
                t,
                effective,
            } if generation == self.generation => {
                if !effective {
                    self.reversals.push(t, self.shown);
                } else if overlay && epoch == self.epoch {
                    self.effective_reversals.push(t, self.shown);
                }
                t <= self.shown
            }
            SimEvent::Mark { generation, t } if generation == self.generation => {
                if let Some((Found::Flow, marks)) = self.second.as_mut() {
                    marks.push(t, self.shown);
                }
                t <= self.shown
            }
            SimEvent::Finished { generation } if generation == self.generation => {
                self.finished = true;
                self.show();
                true
            }
            SimEvent::Failed {
                generation,
                message,
            } if generation == self.generation => {
                if self.stops.is_some() && self.shown < self.reached {
                    // The worker reached the stop ahead of the display: what it computed
                    // before it is still shown.
                    self.failing = Some(message);
                } else {
                    self.failed = Some(message);
                    self.playing = false;
                }
                true
            }
            _ => false,
        }
    }

    /// A new life of the overlay (on or off); its old samples are dropped.
    pub fn set_overlay(&mut self, on: bool) -> Command {
        self.epoch += 1;
        self.effective_trail.clear();
        self.effective_reversals.clear();
        Command::SetEffective {
            on,
            epoch: self.epoch,
        }
    }

    /// The full trail up to the displayed time.
    #[must_use]
    pub fn trail_shown(&self) -> &[Point] {
        upto(&self.trail, self.shown)
    }

    /// The effective trail up to the displayed time.
    #[must_use]
    pub fn effective_shown(&self) -> &[Point] {
        upto(&self.effective_trail, self.shown)
    }

    /// Number of reversals of the full motion up to the displayed time.
    #[must_use]
    pub fn reversals_shown(&self) -> usize {
        self.reversals.count_upto(self.shown)
    }

    /// The model's second events up to the displayed time (`None` for models without them).
    #[must_use]
    pub fn second_shown(&self) -> Option<usize> {
        self.second.as_ref().map(|(_, e)| e.count_upto(self.shown))
    }

    /// The pendulum's falls up to the displayed time (`None` for models without them).
    #[must_use]
    pub fn falls_shown(&self) -> Option<usize> {
        match &self.second {
            Some((Found::SlowAngleFalls, e)) => Some(e.count_upto(self.shown)),
            _ => None,
        }
    }

    /// The celt's crossings up to the displayed time (`None` for models without them).
    #[must_use]
    pub fn crossings_shown(&self) -> Option<usize> {
        match &self.second {
            Some((Found::Flow, e)) => Some(e.count_upto(self.shown)),
            _ => None,
        }
    }

    /// Number of reversals of the limit up to the displayed time.
    #[must_use]
    pub fn effective_reversals_shown(&self) -> usize {
        self.effective_reversals.count_upto(self.shown)
    }

    /// The recent reversal times of the full motion up to the displayed time (for ticks).
    #[must_use]
    pub fn reversal_ticks(&self) -> &[f64] {
        self.reversals.recent_upto(self.shown)
    }

    /// The displayed point of the full motion.
    #[must_use]
    pub fn current(&self) -> Option<&Point> {
        self.trail_shown().last()
    }

    /// Forgets the drawn trails (not the counts).
    pub fn clear_trails(&mut self) {
        let keep = |trail: &mut Vec<Point>, shown: f64| {
            let n = upto(trail, shown).len();
            trail.drain(..n.saturating_sub(1));
        };
        keep(&mut self.trail, self.shown);
        keep(&mut self.effective_trail, self.shown);
    }
}

/// The samples of `trail` up to time `t` (what is displayed).
#[must_use]
pub fn upto(trail: &[Point], t: f64) -> &[Point] {
    &trail[..trail.partition_point(|p| p.t <= t)]
}

fn push_capped(trail: &mut Vec<Point>, new: Vec<Point>) {
    trail.extend(new);
    if trail.len() > TRAIL_CAP {
        trail.drain(..trail.len() - TRAIL_CAP / 2);
    }
}
