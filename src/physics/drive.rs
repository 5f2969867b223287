//! The one headless runner: drives any model's [`Flow`] to `t_end`, asking whether to go on,
//! holding the run to its step cap, counting the flow's events and marks, and handing the
//! evenly spaced samples and every accepted step to the model's [`Watch`]. Each model's
//! `run.rs` says only what it watches and how its report is shaped.

use serde::Serialize;

use super::flow::{CHECK_EVERY, EventTracker, Flow};
use super::method::{StepCap, StepError};

/// Times of one kind of event: the first few kept, all of them counted (memory stays bounded
/// for any run length).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Counted {
    /// The first times, in order.
    pub times: Vec<f64>,
    /// How many there were.
    pub count: usize,
}

impl Counted {
    /// Counts one at `t`, keeping its time while fewer than `keep` are kept.
    pub fn push(&mut self, t: f64, keep: usize) {
        self.count += 1;
        if self.times.len() < keep {
            self.times.push(t);
        }
    }
}

/// Most event times a run keeps of each kind by default; later ones are counted only.
pub const KEPT: usize = 100_000;

/// The course of a run.
#[derive(Clone, Copy, Debug)]
pub struct Course {
    /// Final time.
    pub t_end: f64,
    /// Evenly spaced samples over `[0, t_end]` (one: the start; none: none computed).
    pub samples: usize,
    /// The run's step cap (from its cost model).
    pub cap: StepCap,
    /// The event function's value at the start, whose sign the first event changes.
    pub event0: f64,
    /// Most event times kept of each kind.
    pub keep: usize,
}

impl Course {
    /// The course of `flow` to `t_end` with `samples` samples, for a run predicted to take
    /// `predicted_seconds` (its step cap); its events change the sign the flow's event function
    /// has now; [`KEPT`] times of each kind are kept.
    #[must_use]
    pub fn of<F: Flow + ?Sized>(
        flow: &F,
        t_end: f64,
        samples: usize,
        predicted_seconds: f64,
    ) -> Self {
        Self {
            t_end,
            samples,
            cap: StepCap::of(predicted_seconds),
            event0: flow.event_value(),
            keep: KEPT,
        }
    }

    /// The time of sample `i`.
    #[must_use]
    pub fn sample_time(&self, i: usize) -> f64 {
        if self.samples <= 1 {
            0.0
        } else {
            let f = i as f64 / (self.samples - 1) as f64;
            self.t_end * f
        }
    }
}

/// What a model watches of its run of a flow `F` (its own type, or `dyn Flow`).
pub trait Watch<F: ?Sized> {
    /// Sample time `t` was reached (`t <= flow.time()`: interpolate with `flow.state_at(t)`);
    /// `false` cancels the run (a closed output, say).
    fn sample(&mut self, flow: &mut F, t: f64) -> bool;
    /// A step was accepted (after its events were counted).
    fn stepped(&mut self, flow: &mut F);
}

/// The events a run counted.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Driven {
    /// Sign changes of the flow's event function (with its hysteresis).
    pub events: Counted,
    /// The flow's marks (its second kind of event found inside steps).
    pub marks: Counted,
}

/// Drives `flow` from its current time to `course.t_end`, asking `go_on(t)` every
/// [`CHECK_EVERY`] steps.
///
/// # Errors
/// A failed step, the step cap, and [`StepError::Cancelled`] when `go_on` or the watcher says
/// stop.
pub fn drive<F: Flow + ?Sized>(
    flow: &mut F,
    course: &Course,
    go_on: &mut dyn FnMut(f64) -> bool,
    watch: &mut impl Watch<F>,
) -> Result<Driven, StepError> {
    let mut driver = Driver::new(course);
    while driver.before(flow, course, go_on, watch)? {
        flow.step(course.t_end)?;
        driver.after(flow, course, watch);
    }
    Ok(driver.driven)
}

/// The runner's state between two steps: [`drive`]'s loop, opened up so that a flow whose steps
/// are taken elsewhere (a lane of a batched chart, issue 84) is driven by the same rules.
#[derive(Clone, Debug)]
pub struct Driver {
    tracker: EventTracker,
    /// What was counted so far.
    pub driven: Driven,
    next_sample: usize,
    steps: u64,
}

impl Driver {
    /// At the start of `course`.
    #[must_use]
    pub fn new(course: &Course) -> Self {
        Self {
            tracker: EventTracker::new(course.event0),
            driven: Driven::default(),
            next_sample: 0,
            steps: 0,
        }
    }

    /// Before a step: the samples reached, the end, `go_on` and the step cap. `Ok(true)`: take
    /// a step; `Ok(false)`: the course is run.
    ///
    /// # Errors
    /// The step cap, and [`StepError::Cancelled`] when `go_on` or the watcher says stop.
    pub fn before<F: Flow + ?Sized>(
        &mut self,
        flow: &mut F,
        course: &Course,
        go_on: &mut dyn FnMut(f64) -> bool,
        watch: &mut impl Watch<F>,
    ) -> Result<bool, StepError> {
        while self.next_sample < course.samples
            && course.sample_time(self.next_sample) <= flow.time()
        {
            let t = course.sample_time(self.next_sample);
            if !watch.sample(flow, t) {
                return Err(StepError::Cancelled { t });
            }
            self.next_sample += 1;
        }
        if flow.time() >= course.t_end {
            return Ok(false);
        }
        self.steps += 1;
        if self.steps.is_multiple_of(CHECK_EVERY) && !go_on(flow.time()) {
            return Err(StepError::Cancelled { t: flow.time() });
        }
        course.cap.check(self.steps, flow.time())?;
        Ok(true)
    }

    /// After an accepted step: its marks and events counted, the watcher told.
    pub fn after<F: Flow + ?Sized>(
        &mut self,
        flow: &mut F,
        course: &Course,
        watch: &mut impl Watch<F>,
    ) {
        for &t in flow.marks() {
            self.driven.marks.push(t, course.keep);
        }
        if let Some(t) = self.tracker.after_step(flow) {
            self.driven.events.push(t, course.keep);
        }
        watch.stepped(flow);
    }
}

/// The largest of `|E − E0|` (or `|E − E0| / |E0|`) over the steps a [`Watch`] sees.
#[derive(Clone, Copy, Debug)]
pub struct Drift {
    /// `E0`.
    pub initial: f64,
    /// What the difference is divided by (1 for an absolute drift).
    pub scale: f64,
    /// The largest so far.
    pub max: f64,
}

impl Drift {
    /// Starts from `e0`; `relative` divides by `|E0|` (by 1 when `E0 = 0`).
    #[must_use]
    pub fn new(e0: f64, relative: bool) -> Self {
        let scale = if relative && e0 != 0.0 { e0.abs() } else { 1.0 };
        Self {
            initial: e0,
            scale,
            max: 0.0,
        }
    }

    /// Takes `e`.
    pub fn see(&mut self, e: f64) {
        self.max = self.max.max((e - self.initial).abs() / self.scale);
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values: 0, 1, 4 and halves
mod tests {
    use super::*;

    #[test]
    fn counted_keeps_the_first_times_and_counts_them_all() {
        let mut c = Counted::default();
        for t in [1.0, 2.0, 3.0] {
            c.push(t, 2);
        }
        assert_eq!(c.times, vec![1.0, 2.0]);
        assert_eq!(c.count, 3);
    }

    #[test]
    fn one_sample_is_the_start_and_many_span_the_run() {
        let course = |samples| Course {
            t_end: 4.0,
            samples,
            cap: StepCap::of(1.0),
            event0: 1.0,
            keep: 1,
        };
        assert_eq!(course(1).sample_time(0), 0.0);
        assert_eq!(course(5).sample_time(4), 4.0);
        assert_eq!(course(5).sample_time(1), 1.0);
    }

    #[test]
    fn a_relative_drift_of_a_zero_energy_is_absolute() {
        let mut d = Drift::new(0.0, true);
        d.see(-0.5);
        assert_eq!(d.max, 0.5);
        let mut d = Drift::new(-2.0, true);
        d.see(-1.0);
        assert_eq!(d.max, 0.5);
    }
}
