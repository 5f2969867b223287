//! Taylor-series integration of the full pendulum `θ̈ = (a + (b/ε) cos(t/ε)) sin θ` (issue 27,
//! item 3: the resolved end of `auto`'s cost against ε).
//!
//! Each step expands `θ` and `θ̇` about the step's start to order `N` by the recurrences of the
//! right-hand side's factors (Jorba and Zou's automatic differentiation, 2005):
//! - the forcing's phase, exactly: `cos` and `sin` of `t0/ε + τ/ε` have the coefficients
//!   `u_{n+1} = −v_n / ((n+1) ε)`, `v_{n+1} = u_n / ((n+1) ε)` from one `sin_cos` of `t0/ε`;
//! - `S = sin θ`, `C = cos θ`: `(n+1) S_{n+1} = Σ_{j=1}^{n+1} j θ_j C_{n+1−j}` and
//!   `(n+1) C_{n+1} = −Σ j θ_j S_{n+1−j}`;
//! - `θ_{n+1} = θ̇_n / (n+1)` and `θ̇_{n+1} = (F S)_n / (n+1)`, with `F = a + (b/ε) cos`.
//!
//! `O(N²)` work a step, and no right-hand side is evaluated at all: the forcing's fast
//! oscillation, which makes DOP853 take 19–48 steps a period, enters through its exact
//! coefficients, and a step spans about a radian of the phase. At the tolerances `auto` resolves
//! with (1e-10 … 1e-14) it takes 4–10 steps a forcing period, and DOP853 costs 2.3–3.1× as much at
//! equal error (docs/benchmarks.md).
//!
//! **Step size** (after Jorba and Zou): with the error scale of each component as DOP853's
//! (`tol` for the angle `θ`, `tol (1 + |θ̇|)` for the rate), the step is the smallest of
//! `(1/m_n)^{1/n}` over the last three orders `n = N−2, N−1, N`, `m_n` the largest scaled
//! coefficient of order `n` (three, not their two: the forcing's coefficients alternate between
//! its `cos` and `sin`, and a small one read as a wide radius let an occasional step err far
//! more than the rest). The first neglected term is then about `tol` times the step over the
//! series' radius. The order is fixed ([`ORDER`]). Between step ends the series itself
//! interpolates (dense output to the tolerance). No step is rejected; a step lands exactly on
//! `t_limit` when it would pass it.
use crate::physics::numerics::elementary::Elementary;

use nalgebra::Vector2;

use super::Params;
use crate::physics::method::StepError;
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::stepper::Stepper;
use crate::physics::numerics::taylor::{Clock, horner, natural_step};

/// The order of the series, whatever the tolerance: a run and its companion at a looser
/// tolerance then differ only in their steps, and their errors follow the tolerance (an order
/// that rose with it, Jorba and Zou's `⌈−ln(tol)/2⌉` plus a few, made the error jump by 25× and
/// stall by 1.7× between neighbouring tolerances on the references; docs/benchmarks.md).
pub const ORDER: usize = 20;
/// Safety factor on the step from the last three coefficients.
pub const SAFETY: f64 = 1.0;

/// The Taylor integrator of the full pendulum.
#[derive(Clone)]
pub struct Taylor {
    a: f64,
    b: f64,
    epsilon: f64,
    tol: f64,
    /// The time, the last step's start, the counts.
    clock: Clock,
    y: Vector2<f64>,
    /// Coefficients of `θ` and `θ̇` about the last step's start, orders `0..=ORDER`.
    theta: [f64; ORDER + 1],
    theta_dot: [f64; ORDER + 1],
}

impl Taylor {
    /// Starts at `(t0, y0)` with tolerance `tol` (relative and absolute, as DOP853's).
    #[must_use]
    pub fn new(params: &Params, t0: f64, y0: Vector2<f64>, tol: f64) -> Self {
        let mut theta = [0.0; ORDER + 1];
        let mut theta_dot = [0.0; ORDER + 1];
        theta[0] = y0[0];
        theta_dot[0] = y0[1];
        Self {
            a: params.a,
            b: params.b,
            epsilon: params.epsilon,
            tol,
            clock: Clock::at(t0),
            y: y0,
            theta,
            theta_dot,
        }
    }

    /// Expands `θ` and `θ̇` about the current point into `self.theta`, `self.theta_dot`.
    #[allow(clippy::needless_range_loop)]
    fn expand(&mut self) {
        let n_max = ORDER;
        let eps = self.epsilon;
        let (mut u, mut v) = ([0.0; ORDER + 1], [0.0; ORDER + 1]);
        let (sp, cp) = (self.clock.t / eps).e_sin_cos();
        u[0] = cp;
        v[0] = sp;
        let amplitude = self.b / eps;
        let mut force = [0.0; ORDER + 1];
        force[0] = self.a + amplitude * cp;
        for n in 0..n_max {
            let m = (n + 1) as f64 * eps;
            u[n + 1] = -v[n] / m;
            v[n + 1] = u[n] / m;
            force[n + 1] = amplitude * u[n + 1];
        }
        let (th, om) = (&mut self.theta, &mut self.theta_dot);
        th[0] = self.y[0];
        om[0] = self.y[1];
        let (mut s, mut c) = ([0.0; ORDER + 1], [0.0; ORDER + 1]);
        (s[0], c[0]) = th[0].e_sin_cos();
        // `j θ_j`, kept so each convolution is one pass.
        let mut jth = [0.0; ORDER + 1];
        for n in 0..n_max {
            let mut acc = 0.0;
            for j in 0..=n {
                acc += force[j] * s[n - j];
            }
            let k = (n + 1) as f64;
            th[n + 1] = om[n] / k;
            om[n + 1] = acc / k;
            jth[n + 1] = k * th[n + 1];
            let (mut ds, mut dc) = (0.0, 0.0);
            for j in 1..=n + 1 {
                ds += jth[j] * c[n + 1 - j];
                dc += jth[j] * s[n + 1 - j];
            }
            s[n + 1] = ds / k;
            c[n + 1] = -dc / k;
        }
    }

    /// The step the series allows (see the module's documentation).
    fn natural_step(&self) -> f64 {
        let scale_theta = self.tol;
        let scale_rate = self.tol * (1.0 + self.y[1].abs());
        natural_step(ORDER, |n| {
            (self.theta[n].abs() / scale_theta).max(self.theta_dot[n].abs() / scale_rate)
        })
    }
}

impl Stepper<2> for Taylor {
    /// Current time.
    fn time(&self) -> f64 {
        self.clock.t
    }

    /// Current state.
    fn state(&self) -> Vector2<f64> {
        self.y
    }

    /// Start of the last step.
    fn time_prev(&self) -> f64 {
        self.clock.t_prev
    }

    /// Work counters: each step counts [`ORDER`] evaluations (one pass of the recurrences per
    /// order).
    fn stats(&self) -> Stats {
        self.clock.stats
    }

    /// The series of the last step at `t` in `[time_prev, time]`.
    fn interpolate(&mut self, t: f64) -> Vector2<f64> {
        if t >= self.clock.t {
            return self.y;
        }
        let tau = t - self.clock.t_prev;
        Vector2::new(
            horner(&self.theta[..=ORDER], tau),
            horner(&self.theta_dot[..=ORDER], tau),
        )
    }

    /// Takes one step, never past `t_limit` (which must exceed the current time).
    ///
    /// # Errors
    /// When the series stops being finite or its step underflows.
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        self.expand();
        let natural = SAFETY * self.natural_step();
        let (theta, theta_dot) = (&self.theta[..=ORDER], &self.theta_dot[..=ORDER]);
        self.y = self.clock.advance(ORDER, natural, t_limit, |h| {
            Vector2::new(horner(theta, h), horner(theta_dot, h))
        })?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A forced swing (θ0 = 1 rad about the hanging position, b = 0.3, ε = 0.05) against DOP853
    /// at 1e-15: the end and the dense output at every step's middle within 1e-10, at a few
    /// steps a forcing period.
    #[test]
    fn agrees_with_dop853_on_a_forced_swing() {
        use crate::physics::kapitza::flows::FullField;
        use crate::physics::numerics::dop853::Dop853;
        use crate::physics::numerics::stepper::FullCore;
        let p = Params {
            a: -1.0,
            b: 0.3,
            epsilon: 0.05,
        };
        let y0 = Vector2::new(1.0, 0.2);
        let mut taylor = Taylor::new(&p, 0.0, y0, 1e-13);
        let mut dop = <Dop853<2, FullField> as FullCore<2, _>>::start(&p, y0, 1e-15);
        let t_end = 3.0;
        let (worst, end) = crate::physics::numerics::stepper::gaps(&mut taylor, &mut dop, t_end);
        assert!(end < 1e-10, "end {end}");
        assert!(worst < 1e-10, "dense output {worst}");
        // A few steps a forcing period (2π ε ≈ 0.31), where DOP853 takes about twenty.
        let periods = t_end / (std::f64::consts::TAU * p.epsilon);
        let per_period = taylor.stats().steps as f64 / periods;
        assert!(per_period < 8.0, "{per_period} steps a period");
    }
}
