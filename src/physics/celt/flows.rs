//! The celt's integrators behind [`Flow`], and its events.
//!
//! - `dop853`: the 13 components of the state (`mod.rs`) by the adaptive DOP853 core, as the
//!   reference script does. `|γ|`, `|q|` and `γ = R(q)ᵀ Z` hold only to the tolerance.
//! - `dop853-projected`: the same, with the state put back on its constraints after every
//!   accepted step: `q` normalised and `γ` taken as the third row of `R(q)`, so `|γ| = 1`, the
//!   attitude and the up vector agree, and the contact (whose height follows from `γ`) stays on
//!   the plane by construction. The projection does not change the order.
//!
//! **Events** (model.md §8). The spin `σ = ω·γ` is modulated by the pitching, so a step can hold
//! two sign changes with equal signs at its ends. Where a step's ends straddle zero or come near
//! it, the interpolant is sampled at 33 points and every sign change is located by root
//! finding: these are the **crossings** ([`Flow::marks`]). A **reversal** is counted at a step's
//! end where `σ` has the sign opposite to the current sense and `|σ| ≥ band`; its time is the
//! last crossing before. The flow's event function is the current sense (±1), so the generic
//! [`crate::physics::flow::EventTracker`] counts reversals and asks [`Flow::locate_event`] for
//! that crossing.

use super::field::Coefficients;
use super::{DIM, Params, Problem, State, lean, spin, tilt};
use crate::physics::flow::{Flow, Sample};
use crate::physics::method::{Method, Settings, StepError};
use crate::physics::numerics::dop853::{Dop853, Field};
use crate::physics::numerics::dop853_lanes::Packs;
use crate::physics::numerics::lanes::{F64x4, LANES};
use crate::physics::numerics::roots::find_root;

/// The methods this model offers (`auto` first).
pub const METHODS: [Method; 3] = [Method::Auto, Method::Dop853, Method::Dop853Projected];

/// Points per step at which the interpolant is searched for crossings.
const SEARCH: usize = 32;

/// The celt's field for the DOP853 core.
#[derive(Clone)]
pub struct CeltField(Params);

impl Field<DIM> for CeltField {
    #[inline]
    fn eval(&self, y: &State) -> State {
        self.0.field(y)
    }
    fn is_angle(&self, i: usize) -> bool {
        i == DIM - 1
    }
}

impl Packs<DIM> for CeltField {
    type Packed = Coefficients<F64x4>;
    fn pack(fields: [&Self; LANES]) -> Self::Packed {
        Coefficients::lanes(fields.map(|f| &f.0))
    }
    // Inlined into the lanes' caller, compiled for the machine's vector unit (`multiversion`).
    #[allow(clippy::inline_always)]
    #[inline(always)]
    fn eval_packed(packed: &Self::Packed, _t: F64x4, y: &[F64x4; DIM]) -> [F64x4; DIM] {
        packed.field(y)
    }
}

/// Builds a ready-to-step integrator at `t = 0`.
///
/// # Errors
/// [`StepError::Unplanned`] for `auto`; [`StepError::NotOffered`] for another model's method.
pub fn build(problem: &Problem, method: Method, settings: Settings) -> Result<CeltFlow, StepError> {
    match method {
        Method::Dop853 => Ok(CeltFlow::new(problem, settings.tolerance, false)),
        Method::Dop853Projected => Ok(CeltFlow::new(problem, settings.tolerance, true)),
        Method::Auto => Err(StepError::Unplanned),
        other => Err(StepError::NotOffered {
            method: other.name(),
            model: "celt",
        }),
    }
}

/// A running integration of the celt.
#[derive(Clone)]
pub struct CeltFlow {
    params: Params,
    core: Dop853<DIM, CeltField>,
    project: bool,
    band: f64,
    /// The current sense of the spin (±1).
    sense: f64,
    /// The spin at the end of the last step.
    spin_now: f64,
    /// Crossings inside the last step.
    marks: Vec<f64>,
    /// The last crossing found so far.
    last_crossing: Option<f64>,
    /// The time of the last reversal (its crossing).
    reversal: f64,
    /// When the last reversal became certain: the spin reached the band.
    confirmed: f64,
}

/// The spin `ω·γ` of the state's first six components (as [`spin`] computes it).
fn spin_of(w_g: &nalgebra::SVector<f64, 6>) -> f64 {
    w_g[0] * w_g[3] + w_g[1] * w_g[4] + w_g[2] * w_g[5]
}

/// Whether the spin at a step's ends, `s_prev` and `s_new`, calls for a search inside it: they
/// straddle zero or come near it.
fn searched(s_prev: f64, s_new: f64) -> bool {
    let near = s_prev.abs().min(s_new.abs()) < 4.0 * (s_new - s_prev).abs() + 1e-3;
    let straddles = s_prev == 0.0 || s_new == 0.0 || (s_prev > 0.0) != (s_new > 0.0);
    near || straddles
}

/// Puts a state back on its constraints: unit quaternion, `γ` its third row.
pub fn project(y: &mut State) {
    let n = (y[6] * y[6] + y[7] * y[7] + y[8] * y[8] + y[9] * y[9]).sqrt();
    for i in 6..10 {
        y[i] /= n;
    }
    let (w, x, yy, z) = (y[6], y[7], y[8], y[9]);
    y[3] = 2.0 * (x * z - w * yy);
    y[4] = 2.0 * (yy * z + w * x);
    y[5] = 1.0 - 2.0 * (x * x + yy * yy);
}

impl CeltFlow {
    /// Starts at the problem's initial state.
    #[must_use]
    pub fn new(problem: &Problem, tol: f64, project: bool) -> Self {
        let y0 = problem.initial_state();
        let s0 = spin(&y0);
        Self {
            params: *problem.params(),
            core: Dop853::new(CeltField(*problem.params()), 0.0, y0, tol),
            project,
            band: problem.band(),
            sense: if s0 >= 0.0 { 1.0 } else { -1.0 },
            spin_now: s0,
            marks: Vec::new(),
            last_crossing: None,
            reversal: 0.0,
            confirmed: 0.0,
        }
    }

    /// The state now.
    #[must_use]
    pub fn state(&self) -> State {
        self.core.state()
    }

    /// The state at `t` inside the last step (or now).
    pub fn at(&mut self, t: f64) -> State {
        if t >= self.core.time() {
            self.core.state()
        } else {
            self.core.interpolate(t)
        }
    }

    /// The crossings inside the step just taken, from the spin at its ends.
    fn find_crossings(&mut self, s_prev: f64, s_new: f64) {
        self.marks.clear();
        let (t0, t1) = (self.core.time_prev(), self.core.time());
        if !searched(s_prev, s_new) {
            return;
        }
        let mut ts = [0.0; SEARCH + 1];
        let mut ss = [0.0; SEARCH + 1];
        for k in 0..=SEARCH {
            ts[k] = t0 + (t1 - t0) * k as f64 / SEARCH as f64;
            ss[k] = if k == 0 {
                s_prev
            } else if k == SEARCH {
                s_new
            } else {
                spin_of(&self.core.interpolate_first::<6>(ts[k]))
            };
        }
        // Exact comparisons: a sign change, and a start exactly on zero.
        #[allow(clippy::float_cmp)]
        for k in 0..SEARCH {
            let (a, b) = (ss[k], ss[k + 1]);
            // A start exactly on zero is not a crossing.
            if (a > 0.0) != (b > 0.0) && a != b && !(ts[k] == 0.0 && a == 0.0) {
                let t = if a == 0.0 {
                    ts[k]
                } else {
                    let core = &mut self.core;
                    find_root(
                        |t| spin_of(&core.interpolate_first::<6>(t)),
                        ts[k],
                        ts[k + 1],
                    )
                };
                self.marks.push(t);
                self.last_crossing = Some(t);
            }
        }
    }
}

impl Flow for CeltFlow {
    crate::physics::flow::on_core!(own step);
    fn method(&self) -> Method {
        if self.project {
            Method::Dop853Projected
        } else {
            Method::Dop853
        }
    }
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        self.core.step(t_limit)?;
        self.stepped();
        Ok(())
    }
    fn sample(&mut self, t: f64) -> Sample {
        let y = self.at(t);
        Sample {
            q: y[DIM - 1],
            q_dot: spin(&y),
            fast: tilt(&y),
            lean: Some(lean(&y)),
        }
    }
    fn state_at(&mut self, t: f64) -> Vec<f64> {
        self.at(t).iter().copied().collect()
    }
    fn event_value(&self) -> f64 {
        self.sense
    }
    fn locate_event(&mut self) -> f64 {
        self.reversal
    }
    fn event_known_at(&mut self, _located: f64) -> f64 {
        self.confirmed
    }
    fn marks(&self) -> &[f64] {
        &self.marks
    }
    fn energy(&self) -> f64 {
        self.params.energy(&self.core.state())
    }
}

impl CeltFlow {
    /// The integrator, for a batched chart's lane (issue 84), which takes its steps; each
    /// accepted one is then followed by [`CeltFlow::stepped`].
    pub(super) fn core(&mut self) -> &mut Dop853<DIM, CeltField> {
        &mut self.core
    }

    /// The field it integrates.
    pub(super) fn field(&self) -> &CeltField {
        self.core.field()
    }

    /// Whether a step ending at spin `s` ends a reversal (once a crossing has been found).
    fn reverses(&self, s: f64) -> bool {
        s * self.sense < 0.0 && s.abs() >= self.band && self.last_crossing.is_some()
    }

    /// Whether [`CeltFlow::stepped`] will read the accepted step's dense output: a lane hands
    /// the integrator the step's stages first, and only then (issue 84).
    pub(super) fn reads_inside(&self) -> bool {
        let s = spin(&self.core.state());
        self.project || searched(self.spin_now, s) || self.reverses(s)
    }

    /// What follows an accepted step of the integrator: the projection, the crossings inside
    /// the step and a reversal at its end.
    pub(super) fn stepped(&mut self) {
        let s_prev = self.spin_now;
        if self.project {
            self.core.project(project);
        }
        let s = spin(&self.core.state());
        self.find_crossings(s_prev, s);
        self.spin_now = s;
        if self.reverses(s)
            && let Some(t) = self.last_crossing
        {
            {
                let (t0, t1) = (self.core.time_prev(), self.core.time());
                let (band, new) = (self.band, -self.sense);
                let core = &mut self.core;
                let mut beyond = |t: f64| spin_of(&core.interpolate_first::<6>(t)) * new - band;
                self.confirmed = if beyond(t0) >= 0.0 {
                    t0
                } else {
                    find_root(beyond, t0, t1)
                };
                self.sense = new;
                self.reversal = t;
            }
        }
    }
}
