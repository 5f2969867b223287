//! The pendulum's integrators behind [`Flow`]:
//!
//! - `dop853`: the full model on `(θ, θ̇)` by the adaptive DOP853 core (forced at each stage's
//!   time); resolves the fast
//!   period, so its cost grows like `1/ε`.
//! - `taylor`: the full model by its Taylor series ([`super::taylor`]), the forcing expanded
//!   exactly: 4–10 steps a forcing period, where DOP853 costs 2.3–3.1× as much at equal error; what
//!   `auto` resolves with. Its cost grows like `1/ε` too.
//! - `rk4` and the compositions (`strang`, `yoshida4`, `blanes-moan4`, `yoshida6`, `suzuki8`):
//!   fixed steps of a fraction of the fast period. The compositions split
//!   `H = p²/2 + (a + (b/ε) cos(t/ε)) cos θ` into the drift `θ += τ p` and the kick with `θ`
//!   frozen, integrated exactly over any `τ`: `p += (aτ + b[sin((t+τ)/ε) − sin(t/ε)]) sin θ`,
//!   `t += τ`. Symplectic; the coefficients are `numerics::compositions`'.
//! - `effective`: the limit `θ̈ = a sin θ − (b²/4) sin 2θ` from `(θ0, θ̇0)` by DOP853;
//!   `effective-corrected`: the limit from the averaged start, with the first-order ripple
//!   added back (`limit`). Their cost does not depend on `ε`; their error is the model's,
//!   O(ε) and O(ε²).
//!
//! Between step ends the fixed-step methods interpolate `θ` by the quintic Hermite polynomial
//! of `(θ, θ̇, θ̈)` at both ends. Events are sign changes of the averaged rate `Θ̇`
//! ([`limit::to_slow`]); the full flows keep an O(ε) ripple in it, which the event hysteresis
//! covers.
use crate::physics::numerics::elementary::Elementary;

use nalgebra::Vector2;

use super::averaged;
use super::limit::{self, Limit};
use super::taylor::Taylor;
use super::{FastPhase, Params, Problem};
use crate::physics::flow::{Flow, Sample};
use crate::physics::method::{Asked, DEFAULT_STEP_BUDGET, Method, StepError};
use crate::physics::numerics::compositions::{Composition, Split};
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::dop853::{Dop853, Field};
use crate::physics::numerics::roots::find_root;
use crate::physics::numerics::stepper::FullCore;

/// The methods this model offers (`auto` resolves to one of them).
pub const METHODS: [Method; 13] = Method::all_but(&[Method::Dop853Projected, Method::Locked]);

/// Whether this model offers `method`.
#[must_use]
pub fn offers(method: Method) -> bool {
    METHODS.contains(&method)
}

/// The fastest rate of the problem: the shaking's frequency `1/ε`, or the slow motion's.
fn rate(problem: &Problem) -> f64 {
    let p = problem.params();
    let s = problem.start();
    let slow = s.theta_dot.abs() + (p.a.abs() + p.b * p.b).sqrt();
    (1.0 / p.epsilon).max(slow).max(1e-3)
}

/// Default fixed step for `method` at `tolerance` over `[0, t_end]`: `c · tol^{1/p} / ν` with
/// `ν` the fastest rate, never more than [`DEFAULT_STEP_BUDGET`] steps.
#[must_use]
pub fn default_step(method: Method, problem: &Problem, tolerance: f64, t_end: f64) -> f64 {
    let (c, order) = match method {
        Method::Rk4 => (0.5, 4.0),
        Method::Strang => (0.3, 2.0),
        Method::Yoshida4 => (0.6, 4.0),
        Method::BlanesMoan4 => (1.2, 4.0),
        Method::Yoshida6 => (1.0, 6.0),
        _ => (1.5, 8.0),
    };
    (c * tolerance.e_powf(1.0 / order) / rate(problem)).max(t_end / DEFAULT_STEP_BUDGET)
}

/// Builds a ready-to-step integrator at `t = 0`, its lifts taking the fast phase as `phase`
/// says.
///
/// # Errors
/// [`StepError::Unplanned`] for `auto` (resolved by [`super::plan`]), and
/// [`StepError::NotOffered`] for a method of another model.
pub fn build(problem: &Problem, ask: &Asked, phase: FastPhase) -> Result<Box<dyn Flow>, StepError> {
    let (method, settings, t_end) = (ask.method, ask.settings(), ask.t_end);
    let step = settings
        .step
        .unwrap_or_else(|| default_step(method, problem, settings.tolerance, t_end));
    Ok(match method {
        Method::Auto => return Err(StepError::Unplanned),
        Method::Dop853 => Box::new(FullDop853::new(problem, settings.tolerance).with_phase(phase)),
        Method::Taylor => Box::new(FullTaylor::new(problem, settings.tolerance).with_phase(phase)),
        Method::Rk4 => Box::new(Fixed::new(problem, Scheme::Rk4, step, phase)),
        Method::Strang
        | Method::Yoshida4
        | Method::BlanesMoan4
        | Method::Yoshida6
        | Method::Suzuki8 => Box::new(Fixed::new(
            problem,
            Scheme::Split(Composition::of(method)),
            step,
            phase,
        )),
        Method::Effective | Method::EffectiveCorrected | Method::Averaged2 | Method::Averaged3 => {
            let order = match method {
                Method::Effective => Order::Limit,
                Method::EffectiveCorrected => Order::Corrected,
                Method::Averaged2 => Order::Second,
                _ => Order::Third,
            };
            Box::new(LimitDop853::new(problem, settings.tolerance, order, phase))
        }
        other => {
            return Err(StepError::NotOffered {
                method: other.name(),
                model: "kapitza",
            });
        }
    })
}

/// The size the averaged rate's leftover ripple can reach in a full flow: `Θ̇` is exact to
/// O(ε²) (the ripple is removed to that order, `limit`), capped so that a coarse `ε`, where the
/// split into slow and fast motion means little, does not swallow real turning points.
fn hysteresis(p: &Params) -> f64 {
    let scale = p.b * p.b + p.b + p.a.abs();
    (4.0 * (p.epsilon * scale).powi(2)).min(0.02)
}

fn slow_sample(p: &Params, phase: FastPhase, t: f64, theta: f64, theta_dot: f64) -> Sample {
    let (slow, _) = limit::to_slow(p, phase, t, (theta, theta_dot));
    Sample {
        q: theta,
        q_dot: theta_dot,
        fast: theta - slow,
        lean: None,
    }
}

/// The full field on `(θ, θ̇)`, forced at the stage's time.
#[derive(Clone)]
pub struct FullField(Params);

impl Field<2> for FullField {
    fn eval(&self, y: &Vector2<f64>) -> Vector2<f64> {
        self.eval_at(0.0, y)
    }
    #[inline]
    fn eval_at(&self, t: f64, y: &Vector2<f64>) -> Vector2<f64> {
        Vector2::new(y[1], self.0.forcing(t) * y[0].e_sin())
    }
    fn is_angle(&self, i: usize) -> bool {
        i == 0
    }
}

impl FullCore<2, Params> for Dop853<2, FullField> {
    const METHOD: Method = Method::Dop853;
    fn start(params: &Params, y0: Vector2<f64>, tol: f64) -> Self {
        Dop853::new(FullField(*params), 0.0, y0, tol)
    }
}

impl FullCore<2, Params> for Taylor {
    const METHOD: Method = Method::Taylor;
    fn start(params: &Params, y0: Vector2<f64>, tol: f64) -> Self {
        Taylor::new(params, 0.0, y0, tol)
    }
}

/// The full model by `dop853`.
pub type FullDop853 = Full<Dop853<2, FullField>>;
/// The full model by `taylor`.
pub type FullTaylor = Full<Taylor>;

/// The full model on `core`: samples, the averaged rate's events and the energy.
#[derive(Clone)]
pub struct Full<C> {
    params: Params,
    phase: FastPhase,
    limit: Limit,
    core: C,
}

impl<C: FullCore<2, Params>> Full<C> {
    /// Starts at the problem's initial values with tolerance `tol`.
    #[must_use]
    pub fn new(problem: &Problem, tol: f64) -> Self {
        let (p, s) = (*problem.params(), problem.start());
        Self {
            params: p,
            phase: FastPhase::default(),
            limit: Limit::new(&p),
            core: C::start(&p, Vector2::new(s.theta, s.theta_dot), tol),
        }
    }

    /// The same, its averaged rate (events, energy) taken with the fast phase as `phase` says.
    #[must_use]
    pub fn with_phase(self, phase: FastPhase) -> Self {
        Self { phase, ..self }
    }

    fn at(&mut self, t: f64) -> Vector2<f64> {
        if t >= self.core.time() {
            self.core.state()
        } else {
            self.core.interpolate(t)
        }
    }
}

impl<C: FullCore<2, Params>> Flow for Full<C> {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        C::METHOD
    }
    fn sample(&mut self, t: f64) -> Sample {
        let y = self.at(t);
        slow_sample(&self.params, self.phase, t, y[0], y[1])
    }
    fn state_at(&mut self, t: f64) -> Vec<f64> {
        let y = self.at(t);
        vec![y[0], y[1]]
    }
    fn event_value(&self) -> f64 {
        let y = self.core.state();
        limit::to_slow(&self.params, self.phase, self.core.time(), (y[0], y[1])).1
    }
    fn locate_event(&mut self) -> f64 {
        let (a, b) = (self.core.time_prev(), self.core.time());
        let (p, phase) = (self.params, self.phase);
        find_root(
            |t| {
                let y = self.core.interpolate(t);
                limit::to_slow(&p, phase, t, (y[0], y[1])).1
            },
            a,
            b,
        )
    }
    fn event_hysteresis(&self) -> f64 {
        hysteresis(&self.params)
    }
    fn energy(&self) -> f64 {
        let y = self.core.state();
        let (th, thd) = limit::to_slow(&self.params, self.phase, self.core.time(), (y[0], y[1]));
        self.limit.energy_of(th, thd)
    }
}

/// The pendulum as a [`Split`]: the drift `θ += τ p`, and the kick with `θ` frozen,
/// `p += (aτ + b[sin((t+τ)/ε) − sin(t/ε)]) sin θ`, `t += τ`.
struct PendulumSplit<'a> {
    params: &'a Params,
    t: f64,
    theta: f64,
    p: f64,
}

impl Split for PendulumSplit<'_> {
    #[inline]
    fn drift(&mut self, c: f64, h: f64) {
        self.theta += c * h * self.p;
    }
    #[inline]
    fn kick(&mut self, c: f64, h: f64) {
        self.p += self.params.forcing_integral(self.t, c * h) * self.theta.e_sin();
        self.t += c * h;
    }
}

/// A fixed-step scheme on the full model.
#[derive(Clone)]
enum Scheme {
    Rk4,
    Split(Composition),
}

/// A fixed-step method: `rk4` or a composition with exact kicks.
#[derive(Clone)]
pub struct Fixed {
    params: Params,
    phase: FastPhase,
    limit: Limit,
    scheme: Scheme,
    h: f64,
    /// Steps taken (the time is `n h`, computed from the count so no rounding accumulates).
    n: u64,
    /// `(θ, θ̇)` now and at the start of the last step.
    y: (f64, f64),
    y_prev: (f64, f64),
    t_prev: f64,
    t: f64,
    stats: Stats,
}

impl Fixed {
    fn new(problem: &Problem, scheme: Scheme, h: f64, phase: FastPhase) -> Self {
        let p = *problem.params();
        let s = problem.start();
        Self {
            params: p,
            phase,
            limit: Limit::new(&p),
            scheme,
            h,
            n: 0,
            y: (s.theta, s.theta_dot),
            y_prev: (s.theta, s.theta_dot),
            t_prev: 0.0,
            t: 0.0,
            stats: Stats::default(),
        }
    }

    fn accel(&self, t: f64, theta: f64) -> f64 {
        self.params.forcing(t) * theta.e_sin()
    }

    /// `(θ, θ̇)` at `t` inside the last step: quintic Hermite of `(θ, θ̇, θ̈)` at its ends.
    fn at(&self, t: f64) -> (f64, f64) {
        if t >= self.t || self.t <= self.t_prev {
            return self.y;
        }
        let (t0, t1) = (self.t_prev, self.t);
        let (h, (y0, v0), (y1, v1)) = (t1 - t0, self.y_prev, self.y);
        let (a0, a1) = (self.accel(t0, y0), self.accel(t1, y1));
        hermite5(
            h,
            (y0, v0 * h, a0 * h * h),
            (y1, v1 * h, a1 * h * h),
            (t - t0) / h,
        )
    }
}

/// The quintic through value, first and second derivative (in the unit `s ∈ [0, 1]`) at both
/// ends, at `s`: returns the value and the derivative per unit of `t` (divided by `h`).
fn hermite5(h: f64, start: (f64, f64, f64), end: (f64, f64, f64), s: f64) -> (f64, f64) {
    let (p0, m0, c0) = start;
    let (p1, m1, c1) = end;
    let (s2, s3) = (s * s, s * s * s);
    let (s4, s5) = (s3 * s, s3 * s2);
    let h00 = 1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5;
    let h10 = s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5;
    let h20 = 0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5;
    let h21 = 0.5 * s3 - s4 + 0.5 * s5;
    let h11 = -4.0 * s3 + 7.0 * s4 - 3.0 * s5;
    let h01 = 10.0 * s3 - 15.0 * s4 + 6.0 * s5;
    let d00 = -30.0 * s2 + 60.0 * s3 - 30.0 * s4;
    let d10 = 1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4;
    let d20 = s - 4.5 * s2 + 6.0 * s3 - 2.5 * s4;
    let d21 = 1.5 * s2 - 4.0 * s3 + 2.5 * s4;
    let d11 = -12.0 * s2 + 28.0 * s3 - 15.0 * s4;
    let d01 = 30.0 * s2 - 60.0 * s3 + 30.0 * s4;
    let value = h00 * p0 + h10 * m0 + h20 * c0 + h21 * c1 + h11 * m1 + h01 * p1;
    let slope = d00 * p0 + d10 * m0 + d20 * c0 + d21 * c1 + d11 * m1 + d01 * p1;
    (value, slope / h)
}

impl Flow for Fixed {
    fn boxed(&self) -> Box<dyn Flow> {
        Box::new(self.clone())
    }
    fn method(&self) -> Method {
        match &self.scheme {
            Scheme::Rk4 => Method::Rk4,
            Scheme::Split(c) => c.method(),
        }
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn time_prev(&self) -> f64 {
        self.t_prev
    }
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        let t0 = self.t;
        let full = (self.n + 1) as f64 * self.h;
        let (t1, h) = if full >= t_limit {
            (t_limit, t_limit - t0)
        } else {
            (full, full - t0)
        };
        let (mut th, mut p) = self.y;
        match &self.scheme {
            Scheme::Rk4 => {
                let f = |t: f64, th: f64, p: f64| (p, self.params.forcing(t) * th.e_sin());
                let k1 = f(t0, th, p);
                let k2 = f(t0 + 0.5 * h, th + 0.5 * h * k1.0, p + 0.5 * h * k1.1);
                let k3 = f(t0 + 0.5 * h, th + 0.5 * h * k2.0, p + 0.5 * h * k2.1);
                let k4 = f(t0 + h, th + h * k3.0, p + h * k3.1);
                th += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
                p += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
                self.stats.rhs_evaluations += 4;
            }
            Scheme::Split(c) => {
                let mut s = PendulumSplit {
                    params: &self.params,
                    t: t0,
                    theta: th,
                    p,
                };
                c.apply(&mut s, h);
                (th, p) = (s.theta, s.p);
                self.stats.rhs_evaluations += c.stages() as u64;
            }
        }
        if !(th.is_finite() && p.is_finite()) {
            return Err(StepError::NonFinite { t: t1 });
        }
        self.y_prev = self.y;
        self.y = (th, p);
        self.t_prev = t0;
        self.t = t1;
        if t1 >= full {
            self.n += 1;
        }
        self.stats.steps += 1;
        Ok(())
    }
    fn sample(&mut self, t: f64) -> Sample {
        let (th, thd) = self.at(t);
        slow_sample(&self.params, self.phase, t, th, thd)
    }
    fn state_at(&mut self, t: f64) -> Vec<f64> {
        let (th, thd) = self.at(t);
        vec![th, thd]
    }
    fn event_value(&self) -> f64 {
        limit::to_slow(&self.params, self.phase, self.t, self.y).1
    }
    fn locate_event(&mut self) -> f64 {
        let (p, phase) = (self.params, self.phase);
        find_root(
            |t| limit::to_slow(&p, phase, t, self.at(t)).1,
            self.t_prev,
            self.t,
        )
    }
    fn event_hysteresis(&self) -> f64 {
        hysteresis(&self.params)
    }
    fn energy(&self) -> f64 {
        let (th, thd) = limit::to_slow(&self.params, self.phase, self.t, self.y);
        self.limit.energy_of(th, thd)
    }
    fn stats(&self) -> Stats {
        self.stats
    }
}

/// The limit's field on `(Θ, Θ̇)`, with the averaged models' `ε² F2` (and `ε⁴ F4`) terms.
#[derive(Clone)]
struct LimitField {
    limit: Limit,
    params: Params,
    order: Order,
}

impl Field<2> for LimitField {
    #[inline]
    fn eval(&self, y: &Vector2<f64>) -> Vector2<f64> {
        let mut acceleration = self.limit.acceleration(y[0]);
        let (p, e2) = (&self.params, self.params.epsilon * self.params.epsilon);
        match self.order {
            Order::Limit | Order::Corrected => {}
            Order::Second => acceleration += e2 * averaged::f2(p, y[0], y[1]),
            Order::Third => {
                let (f2, f4) = averaged::f2_f4(p, y[0], y[1]);
                acceleration += e2 * (f2 + e2 * f4);
            }
        }
        Vector2::new(y[1], acceleration)
    }
    fn is_angle(&self, i: usize) -> bool {
        i == 0
    }
}

/// How much of the averaging a [`LimitDop853`] keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Order {
    /// `effective`: the limit from `(θ0, θ̇0)` as it is.
    Limit,
    /// `effective-corrected`: the limit from the averaged start, with the first ripple.
    Corrected,
    /// `averaged2`: the averaged equation to O(ε²) from the averaged start, with the ripple
    /// to O(ε⁴) (`averaged`).
    Second,
    /// `averaged3`: the averaged equation to O(ε⁴), with the ripple to O(ε⁶).
    Third,
}

/// `effective`, `effective-corrected`, `averaged2` and `averaged3`: DOP853 on the slow motion.
#[derive(Clone)]
pub struct LimitDop853 {
    params: Params,
    phase: FastPhase,
    limit: Limit,
    order: Order,
    core: Dop853<2, LimitField>,
}

/// The averaged start of `problem`: the inverse ripple at `t = 0`.
#[must_use]
pub fn averaged_start(problem: &Problem) -> (f64, f64) {
    let s = problem.start();
    // At t = 0 the phase is 0 either way.
    limit::to_slow(
        problem.params(),
        FastPhase::default(),
        0.0,
        (s.theta, s.theta_dot),
    )
}

impl LimitDop853 {
    /// Starts the slow motion of `order` (see [`Order`]); the ripple it keeps is added back to
    /// what it reports, at the fast phase taken as `phase` says.
    #[must_use]
    pub fn new(problem: &Problem, tol: f64, order: Order, phase: FastPhase) -> Self {
        let p = *problem.params();
        let s = problem.start();
        let (th, thd) = match order {
            Order::Limit => (s.theta, s.theta_dot),
            Order::Corrected => averaged_start(problem),
            Order::Second => averaged::to_slow(&p, phase, 0.0, (s.theta, s.theta_dot)),
            Order::Third => averaged::to_slow3(&p, phase, 0.0, (s.theta, s.theta_dot)),
        };
        let limit = Limit::new(&p);
        let field = LimitField {
            limit,
            params: p,
            order,
        };
        Self {
            params: p,
            phase,
            limit,
            order,
            core: Dop853::new(field, 0.0, Vector2::new(th, thd), tol),
        }
    }

    fn at(&mut self, t: f64) -> Vector2<f64> {
        if t >= self.core.time() {
            self.core.state()
        } else {
            self.core.interpolate(t)
        }
    }

    fn lift(&self, t: f64, y: &Vector2<f64>) -> (f64, f64) {
        match self.order {
            Order::Limit => (y[0], y[1]),
            Order::Corrected => limit::to_full(&self.params, self.phase, t, (y[0], y[1])),
            Order::Second => averaged::to_full(&self.params, self.phase, t, (y[0], y[1])),
            Order::Third => averaged::to_full3(&self.params, self.phase, t, (y[0], y[1])),
        }
    }
}

impl Flow for LimitDop853 {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        match self.order {
            Order::Limit => Method::Effective,
            Order::Corrected => Method::EffectiveCorrected,
            Order::Second => Method::Averaged2,
            Order::Third => Method::Averaged3,
        }
    }
    fn sample(&mut self, t: f64) -> Sample {
        let y = self.at(t);
        let (th, thd) = self.lift(t, &y);
        Sample {
            q: th,
            q_dot: thd,
            fast: th - y[0],
            lean: None,
        }
    }
    fn state_at(&mut self, t: f64) -> Vec<f64> {
        let y = self.at(t);
        let (th, thd) = self.lift(t, &y);
        vec![th, thd]
    }
    fn event_value(&self) -> f64 {
        self.core.state()[1]
    }
    fn locate_event(&mut self) -> f64 {
        let (a, b) = (self.core.time_prev(), self.core.time());
        find_root(|t| self.core.interpolate(t)[1], a, b)
    }
    fn energy(&self) -> f64 {
        let y = self.core.state();
        self.limit.energy_of(y[0], y[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite5_reproduces_a_quintic() {
        let f =
            |x: f64| 1.0 + 2.0 * x - x * x + 0.5 * x.powi(3) - 0.3 * x.powi(4) + 0.1 * x.powi(5);
        let df = |x: f64| 2.0 - 2.0 * x + 1.5 * x * x - 1.2 * x.powi(3) + 0.5 * x.powi(4);
        let ddf = |x: f64| -2.0 + 3.0 * x - 3.6 * x * x + 2.0 * x.powi(3);
        let (t0, h) = (0.4, 0.7);
        let end = |x: f64| (f(x), df(x) * h, ddf(x) * h * h);
        for i in 0..=10 {
            let s = f64::from(i) / 10.0;
            let (v, d) = hermite5(h, end(t0), end(t0 + h), s);
            assert!((v - f(t0 + s * h)).abs() < 1e-12);
            assert!((d - df(t0 + s * h)).abs() < 1e-11);
        }
    }
}
