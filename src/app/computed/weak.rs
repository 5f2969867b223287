//! The weak-* pane's state (issue 12): `γ̇² g^{3/2}` of the full motion, pointwise (computed
//! by the worker once per run while the pane is shown) and its moving average over a window the
//! user changes (`<`, `>`): pointwise it keeps swinging between 0 and `2θ`; averaged over a
//! window much longer than the fast period it settles on `θ` as `k` grows.

use super::{ComputedPane, Cx};
use crate::sim::jobs::WeakSpec;
use crate::sim::{Command, JobData, JobKind, JobSpec};
use crate::study::weak::moving_average;

/// Smallest and largest window.
pub const WINDOW_RANGE: (f64, f64) = (1e-3, 100.0);

/// What the pane shows.
#[derive(Clone, Debug, PartialEq)]
pub struct WeakState {
    /// The run the data belong to.
    pub generation: u64,
    /// Sample times.
    pub t: Vec<f64>,
    /// `γ̇² g^{3/2}`.
    pub pointwise: Vec<f64>,
    /// Its moving average over `window` (NaN where the window leaves the samples).
    pub average: Vec<f64>,
    /// The limit's `θ`.
    pub theta: f64,
    /// The limit's value at the sample times when it is not a constant (the pendulum's `θ̇`);
    /// empty for the rattleback.
    pub reference: Vec<f64>,
    /// The reference averaged over the same window.
    pub reference_average: Vec<f64>,
    /// The averaging window.
    pub window: f64,
    /// The data are in.
    pub done: bool,
    /// Why they could not be computed.
    pub failed: Option<String>,
}

impl Default for WeakState {
    fn default() -> Self {
        Self {
            generation: 0,
            t: Vec::new(),
            pointwise: Vec::new(),
            average: Vec::new(),
            theta: 0.0,
            reference: Vec::new(),
            reference_average: Vec::new(),
            window: 1.0,
            done: false,
            failed: None,
        }
    }
}

impl WeakState {
    fn average_again(&mut self) {
        self.average = moving_average(&self.t, &self.pointwise, self.window);
        self.reference_average = if self.reference.is_empty() {
            Vec::new()
        } else {
            moving_average(&self.t, &self.reference, self.window)
        };
    }

    /// Multiplies the window by `factor` (within [`WINDOW_RANGE`]) and averages again.
    pub fn scale_window(&mut self, factor: f64) {
        self.set_window(self.window * factor);
    }

    /// Sets the window (within [`WINDOW_RANGE`]; a value that is not a number keeps it) and
    /// averages again.
    pub fn set_window(&mut self, window: f64) {
        if window.is_nan() {
            return;
        }
        self.window = window.clamp(WINDOW_RANGE.0, WINDOW_RANGE.1);
        self.average_again();
    }

    /// The largest `|average/θ − 1|` where the window fits (NaN before the data); for the
    /// pendulum, the largest distance between the two averages over the largest limit velocity.
    #[must_use]
    pub fn worst_deviation(&self) -> f64 {
        if !self.reference.is_empty() {
            // The pendulum: the averages of θ̇_ε and of the limit's θ̇, relative to the largest
            // limit velocity.
            let scale = self
                .reference
                .iter()
                .fold(0.0f64, |m, r| m.max(r.abs()))
                .max(1e-12);
            return self
                .average
                .iter()
                .zip(&self.reference_average)
                .filter(|(a, r)| a.is_finite() && r.is_finite())
                .map(|(a, r)| (a - r).abs() / scale)
                .fold(0.0, f64::max);
        }
        if self.theta == 0.0 || self.average.is_empty() {
            return f64::NAN;
        }
        self.average
            .iter()
            .filter(|a| a.is_finite())
            .map(|a| (a / self.theta - 1.0).abs())
            .fold(0.0, f64::max)
    }
}

impl ComputedPane for WeakState {
    fn kind(&self) -> JobKind {
        JobKind::Weak
    }

    /// Forgets the data (keeps the window) and asks for the view of the current start.
    fn start(&mut self, cx: &mut Cx) -> Option<Command> {
        *self = Self {
            generation: cx.generation,
            window: self.window,
            ..Self::default()
        };
        let spec = WeakSpec {
            model: cx.settings.model,
            t_end: cx.settings.t_end,
        };
        Some(Command::start_job(cx.generation, JobSpec::Weak(spec)))
    }

    fn stop(&mut self) -> Command {
        Command::stop_job(JobKind::Weak, self.generation)
    }

    /// The view's data (or why it could not be computed), averaged over the window.
    fn take(&mut self, stamp: u64, data: JobData, _: &mut Cx) -> bool {
        let JobData::Weak {
            t,
            pointwise,
            theta,
            reference,
            failed,
        } = data
        else {
            return false;
        };
        if stamp != self.generation {
            return false;
        }
        self.t = t;
        self.pointwise = pointwise;
        self.theta = theta;
        self.reference = reference;
        self.failed = failed;
        self.done = true;
        self.average_again();
        true
    }
}
