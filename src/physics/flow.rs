//! The model-generic face of an integration: what the explorer's worker, the runners and the
//! benchmarks need from any model's integrator, in terms of a slow coordinate, an event
//! function and a state vector (never of a particular model's variables).
//!
//! Each model (`rattleback`, `kapitza`) implements [`Flow`] in its own folder; the worker holds
//! a `Box<dyn Flow>` built through [`super::Model`]. Events are sign changes of the event
//! function at `t > 0` ([`EventTracker`]), located inside a step by the method's own
//! interpolant.

pub use super::method::{Method, StepError};
pub use super::numerics::dop853::Stats;

/// What is drawn of a state: the slow coordinate, its rate, and the fast coordinate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The slow coordinate (the rattleback's spin angle `α`, the pendulum's `θ`).
    pub q: f64,
    /// Its rate as integrated (with the fast ripple where the model has one).
    pub q_dot: f64,
    /// The fast coordinate (the rattleback's tilt `γ`; the pendulum's ripple of `θ`, `θ − Θ`).
    pub fast: f64,
    /// The body's lean, for a model whose body pane draws it from the side (the celt): the
    /// angles (rad) by which the ends of its long and its cross axis rise above the horizontal.
    pub lean: Option<[f64; 2]>,
}

/// A running integration of one model's problem.
pub trait Flow: Send {
    /// Which method this is.
    fn method(&self) -> Method;
    /// Current time.
    fn time(&self) -> f64;
    /// Start of the last step (equal to [`Flow::time`] before the first).
    fn time_prev(&self) -> f64;
    /// Takes one step, never past `t_limit`, which must exceed the current time.
    ///
    /// # Errors
    /// When the step cannot be completed with a finite result.
    fn step(&mut self, t_limit: f64) -> Result<(), StepError>;
    /// The drawn sample at `t`: the current state when `t >= time()`, else from the method's
    /// own interpolant inside the last step.
    fn sample(&mut self, t: f64) -> Sample;
    /// The state vector at `t` (same rule), in the model's own order.
    fn state_at(&mut self, t: f64) -> Vec<f64>;
    /// The event function at the current time (the slow rate: the rattleback's `α̇`, the
    /// pendulum's averaged `Θ̇`).
    fn event_value(&self) -> f64;
    /// Where the event function vanishes inside the last step, given that it changed sign.
    fn locate_event(&mut self) -> f64;
    /// When the event just located at `located` became certain, for a display that counts
    /// events as its time passes them: `located` itself for an event found inside the step
    /// that holds it; later for one confirmed only afterwards (the celt's reversal, dated at
    /// its last crossing but certain only once the spin reaches the band).
    fn event_known_at(&mut self, located: f64) -> f64 {
        located
    }
    /// Smallest size the event function must reach between two events for the second to
    /// count: the size of whatever ripple the event function keeps (0 when it has none).
    fn event_hysteresis(&self) -> f64 {
        0.0
    }
    /// Times of the model's second kind of event found inside the last step, in order (the
    /// celt's raw spin crossings); empty for a model whose second events are found elsewhere or
    /// that has none.
    fn marks(&self) -> &[f64] {
        &[]
    }
    /// The quantity the method conserves (or whose drift it reports) at the current state.
    fn energy(&self) -> f64;
    /// Work counters.
    fn stats(&self) -> Stats;
    /// A copy of this integration in its current state: stepping the copy gives the same bits
    /// as stepping the original (the explorer rewinds to a displayed time with it).
    fn boxed(&self) -> Box<dyn Flow>;
}

/// The [`Flow`] methods of a `Clone` flow whose integration is its field `core` (a
/// [`crate::physics::numerics::dop853::Dop853`]): the copy, the clock, the step and the
/// counters (`on_core!(own step)`: all but the step, for a flow that does more in a step). The
/// flow says the rest (its method, samples, events and energy).
macro_rules! on_core {
    () => {
        $crate::physics::flow::on_core!(own step);
        fn step(&mut self, t_limit: f64) -> Result<(), $crate::physics::method::StepError> {
            self.core.step(t_limit)
        }
    };
    (own step) => {
        fn boxed(&self) -> Box<dyn $crate::physics::flow::Flow> {
            Box::new(self.clone())
        }
        fn time(&self) -> f64 {
            self.core.time()
        }
        fn time_prev(&self) -> f64 {
            self.core.time_prev()
        }
        fn stats(&self) -> $crate::physics::numerics::dop853::Stats {
            self.core.stats()
        }
    };
}
pub(crate) use on_core;

/// Follows the sign of a flow's event function from step to step.
///
/// It remembers the last nonzero sign, so a start on zero is not an event and a step ending
/// exactly on zero is neither missed nor counted twice. With a hysteresis `h > 0`, a sign
/// change counts only if the function reached `|f| > h` since the last one (a ripple of size
/// below `h` cannot make events chatter).
#[derive(Clone, Copy, Debug, Default)]
pub struct EventTracker {
    last_sign: f64,
    armed: bool,
}

impl EventTracker {
    /// Starts from the initial value of the event function.
    #[must_use]
    pub fn new(value0: f64) -> Self {
        Self {
            last_sign: sign(value0),
            armed: true,
        }
    }

    /// Checks the step just taken; returns the event time inside it, if any.
    pub fn after_step<F: Flow + ?Sized>(&mut self, flow: &mut F) -> Option<f64> {
        let counted = self.after_value(flow.event_value(), flow.event_hysteresis());
        counted.then(|| flow.locate_event())
    }

    /// Whether the event function, `v` at the end of the step just taken, changed sign in it
    /// (with hysteresis `h`): [`EventTracker::after_step`] for a function that is not a
    /// flow's.
    pub fn after_value(&mut self, v: f64, h: f64) -> bool {
        let now = sign(v);
        if now == 0.0 {
            return false;
        }
        // Signs are exactly -1, 0 or 1.
        #[allow(clippy::float_cmp)]
        let changed = self.last_sign != 0.0 && now != self.last_sign;
        self.last_sign = now;
        let counted = changed && self.armed;
        if counted && h > 0.0 {
            self.armed = false;
        }
        if v.abs() > h {
            self.armed = true;
        }
        counted
    }
}

/// `-1`, `0` or `1`: the sign the event trackers follow.
#[must_use]
pub(crate) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Asked now and then during long work whether to go on (given the time reached, for progress);
/// `false` stops it with [`StepError::Cancelled`]. The physics stays clock-free: the caller
/// decides.
pub type GoOn<'a> = &'a mut dyn FnMut(f64) -> bool;

/// Steps between two calls of a run's cancellation check.
pub const CHECK_EVERY: u64 = 256;
