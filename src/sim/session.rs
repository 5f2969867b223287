//! One run of the explorer: the full integrator, optionally the effective one, reversal
//! trackers, and interpolated samples at the times the UI asks for.

use serde::{Deserialize, Serialize};

use super::SimEvent;
use crate::physics::Problem;
use crate::physics::integrators::reversals::ReversalTracker;
use crate::physics::integrators::{self, Integrator, Method, Settings};

/// What a session runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SessionSpec {
    /// Body, spring and start.
    pub problem: Problem,
    /// Method (`auto` is planned once, at the start).
    pub method: Method,
    /// Tolerance.
    pub tolerance: f64,
    /// End of the run.
    pub t_end: f64,
    /// Whether the effective overlay is integrated.
    pub effective: bool,
}

/// A sample of the motion for drawing.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// Time.
    pub t: f64,
    /// Spin angle.
    pub alpha: f64,
    /// Spin rate.
    pub alpha_dot: f64,
    /// Relative error of the conserved quantity at the last step end.
    pub energy_error: f64,
}

struct Track {
    integrator: Box<dyn Integrator>,
    tracker: ReversalTracker,
    e0: f64,
    scale: f64,
}

impl Track {
    fn new(spec: &SessionSpec, method: Method) -> Self {
        let settings = Settings {
            tolerance: spec.tolerance,
            step: None,
        };
        let integrator = integrators::build(method, &spec.problem, settings, spec.t_end);
        let e0 = integrator.energy();
        Self {
            integrator,
            tracker: ReversalTracker::new(spec.problem.start().alpha_dot),
            e0,
            scale: if e0 == 0.0 { 1.0 } else { e0.abs() },
        }
    }

    fn point(&mut self, t: f64) -> Point {
        let y = if t >= self.integrator.time() {
            self.integrator.state()
        } else {
            self.integrator.interpolate(t)
        };
        Point {
            t,
            alpha: y[1],
            alpha_dot: y[3],
            energy_error: (self.integrator.energy() - self.e0) / self.scale,
        }
    }
}

/// A synchronous run: `advance` integrates to a target and returns what happened.
pub struct Session {
    spec: SessionSpec,
    generation: u64,
    full: Track,
    effective: Option<Track>,
    next_sample: f64,
    finished: bool,
    reversals: Vec<f64>,
}

impl Session {
    /// Starts a run at `t = 0`.
    #[must_use]
    pub fn new(generation: u64, spec: SessionSpec) -> Self {
        let effective = spec.effective.then(|| Track::new(&spec, Method::Effective));
        Self {
            full: Track::new(&spec, spec.method),
            spec,
            generation,
            effective,
            next_sample: 0.0,
            finished: false,
            reversals: Vec::new(),
        }
    }

    /// Time the full integrator has reached.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.full.integrator.time()
    }

    /// The exact state at `t` and the reversals up to it, once the run has reached `t` with
    /// `t` inside its last step (as `advance(t, ..)` leaves it); `None` otherwise.
    pub fn checkpoint(&mut self, t: f64) -> Option<([f64; 4], usize)> {
        let i = &mut self.full.integrator;
        // Exactly the end of the last step: its state, not an interpolation.
        #[allow(clippy::float_cmp)]
        let at_end = t == i.time();
        let y = if at_end {
            i.state()
        } else if t >= i.time_prev() && t < i.time() {
            i.interpolate(t)
        } else {
            return None;
        };
        let reversals = self.reversals.iter().filter(|r| **r <= t).count();
        Some(([y[0], y[1], y[2], y[3]], reversals))
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

    /// Turns the effective overlay on (from the current time's state of the limit) or off.
    pub fn set_effective(&mut self, on: bool) {
        if on && self.effective.is_none() {
            let mut track = Track::new(&self.spec, Method::Effective);
            let t = self.full.integrator.time();
            // Catch up from 0 (cheap: its cost does not depend on k).
            while track.integrator.time() < t {
                if track.integrator.step(self.spec.t_end).is_err() {
                    return;
                }
                track.tracker.after_step(track.integrator.as_mut());
            }
            self.effective = Some(track);
        } else if !on {
            self.effective = None;
        }
    }

    /// Integrates until `t` (clamped to `t_end`), at most `max_steps` steps; samples every
    /// `sample_dt` from the last sample on. Returns the events, and whether `t` was reached.
    pub fn advance(&mut self, t: f64, sample_dt: f64, max_steps: usize) -> (Vec<SimEvent>, bool) {
        let mut events = Vec::new();
        if self.finished {
            return (events, true);
        }
        let target = t.min(self.spec.t_end);
        let generation = self.generation;
        let mut full = Vec::new();
        let mut effective = Vec::new();
        let mut steps = 0;
        let mut reached = false;
        loop {
            // Emit the samples the full motion has already passed.
            while self.next_sample <= target && self.next_sample <= self.full.integrator.time() {
                let ts = self.next_sample;
                full.push(self.full.point(ts));
                if let Some(track) = self.effective.as_mut() {
                    while track.integrator.time() < ts {
                        if let Err(e) = track.integrator.step(self.spec.t_end) {
                            events.push(SimEvent::Failed {
                                generation,
                                message: format!("effective model: {e}"),
                            });
                            self.effective = None;
                            break;
                        }
                        if let Some(tr) = track.tracker.after_step(track.integrator.as_mut()) {
                            events.push(SimEvent::Reversal {
                                generation,
                                t: tr,
                                effective: true,
                            });
                        }
                    }
                    if let Some(track) = self.effective.as_mut() {
                        effective.push(track.point(ts));
                    }
                }
                self.next_sample += sample_dt.max(1e-12);
            }
            if self.full.integrator.time() >= target {
                reached = true;
                break;
            }
            if steps >= max_steps {
                break;
            }
            if let Err(e) = self.full.integrator.step(self.spec.t_end) {
                events.push(SimEvent::Failed {
                    generation,
                    message: e.to_string(),
                });
                self.finished = true;
                break;
            }
            steps += 1;
            if let Some(tr) = self.full.tracker.after_step(self.full.integrator.as_mut()) {
                self.reversals.push(tr);
                events.push(SimEvent::Reversal {
                    generation,
                    t: tr,
                    effective: false,
                });
            }
        }
        let t_reached = full.last().map_or(self.next_sample.min(target), |p| p.t);
        events.push(SimEvent::Samples {
            generation,
            full,
            effective,
            t: t_reached,
            steps: self.full.integrator.stats().steps,
        });
        if reached && target >= self.spec.t_end && !self.finished {
            // Make sure the very end is sampled, then stop.
            self.finished = true;
            events.push(SimEvent::Finished { generation });
        }
        (events, reached)
    }
}
