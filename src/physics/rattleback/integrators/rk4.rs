//! `rk4`: the classical Runge–Kutta method with a fixed step.
//!
//! Order 4, not symplectic. Cost: 4 right-hand-side evaluations per step (the last stage's
//! field at the new point is reused as the next step's first). Between steps the state is the
//! cubic Hermite interpolant of the end values and fields (order 3 inside the step), which is
//! what reversal location uses.

use crate::physics::flow::Flow;
use crate::physics::method::TimeSum;
use crate::physics::method::{Method, StepError};
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::roots::find_root;
use crate::physics::rattleback::model::{ALPHA_DOT, State, energy, initial_state, rhs};
use crate::physics::rattleback::params::{Params, Problem};

/// Fixed-step RK4 on `(γ, α, γ̇, α̇)`.
#[derive(Clone)]
pub struct Rk4 {
    params: Params,
    h: f64,
    t: f64,
    y: State,
    f: State,
    t_prev: f64,
    y_prev: State,
    f_prev: State,
    stats: Stats,
    time_sum: TimeSum,
    carry: f64,
}

impl Rk4 {
    /// How the steps are added to the time (compensated unless told).
    #[must_use]
    pub fn with_time_sum(mut self, time_sum: TimeSum) -> Self {
        self.time_sum = time_sum;
        self
    }

    /// Starts at the problem's initial values with step `h`.
    pub fn new(problem: &Problem, h: f64) -> Self {
        let params = *problem.params();
        let y = initial_state(problem.start());
        let f = rhs(&params, &y);
        Self {
            params,
            h,
            t: 0.0,
            y,
            f,
            t_prev: 0.0,
            y_prev: y,
            f_prev: f,
            stats: Stats {
                rhs_evaluations: 1,
                ..Stats::default()
            },
            time_sum: TimeSum::default(),
            carry: 0.0,
        }
    }
}

impl Rk4 {
    /// The current state `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn state(&self) -> State {
        self.y
    }
    /// The state at `t` inside the last step.
    pub fn interpolate(&mut self, t: f64) -> State {
        let h = self.t - self.t_prev;
        if h == 0.0 {
            return self.y;
        }
        let s = (t - self.t_prev) / h;
        let s2 = s * s;
        let s3 = s2 * s;
        self.y_prev * (2.0 * s3 - 3.0 * s2 + 1.0)
            + self.f_prev * (h * (s3 - 2.0 * s2 + s))
            + self.y * (3.0 * s2 - 2.0 * s3)
            + self.f * (h * (s3 - s2))
    }
}

impl Flow for Rk4 {
    fn boxed(&self) -> Box<dyn Flow> {
        Box::new(self.clone())
    }
    fn method(&self) -> Method {
        Method::Rk4
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn time_prev(&self) -> f64 {
        self.t_prev
    }
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        let remaining = t_limit - self.t;
        let last = self.h >= remaining;
        let h = if last { remaining } else { self.h };
        let p = &self.params;
        let k1 = self.f;
        let k2 = rhs(p, &(self.y + k1 * (0.5 * h)));
        let k3 = rhs(p, &(self.y + k2 * (0.5 * h)));
        let k4 = rhs(p, &(self.y + k3 * h));
        let y_new = self.y + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
        if !y_new.iter().all(|v| v.is_finite()) {
            return Err(StepError::NonFinite { t: self.t });
        }
        self.t_prev = self.t;
        self.y_prev = self.y;
        self.f_prev = self.f;
        self.t = if last {
            t_limit
        } else {
            self.time_sum.add(self.t, h, &mut self.carry)
        };
        self.y = y_new;
        self.f = rhs(p, &y_new);
        self.stats.steps += 1;
        self.stats.rhs_evaluations += 4;
        Ok(())
    }
    fn locate_event(&mut self) -> f64 {
        let (a, b) = (self.t_prev, self.t);
        find_root(|t| self.interpolate(t)[ALPHA_DOT], a, b)
    }
    fn energy(&self) -> f64 {
        energy(&self.params, &self.state())
    }
    fn stats(&self) -> Stats {
        self.stats
    }

    fn event_value(&self) -> f64 {
        self.state()[super::super::model::ALPHA_DOT]
    }
    super::drawn_from_state!();
}
