//! `dop853`: Dormand–Prince 8(5,3), adaptive, with its 7th-order dense output.
//!
//! Order 8, not symplectic. Cost: 12 right-hand-side evaluations per accepted step (11 per
//! rejected attempt plus one reused first-same-as-last stage), and 3 more for the dense output,
//! which is only computed when asked (an event inside the step, or a sample). Step-size control
//! follows Hairer's code: the error norm mixes the 5th- and 3rd-order estimates, the factor is
//! `0.9 err^{−1/8}` clamped to `[1/3, 6]`. The scale of component `i` is
//! `tol (u_i + max(|y_i|, |y_new_i|))` (relative and absolute tolerance both `tol`, in the
//! component's natural unit `u_i`), except for angles ([`Field::is_angle`]), whose scale is
//! `tol u_i`. A field may give a component a natural unit (a fast coordinate measured
//! in units of its frequency, say) so that both halves of an oscillation are held to the same
//! energy-relative accuracy.
//!
//! The core is generic over the dimension, so every model's full and limit systems (2 to 4
//! components) share it, and over time (a forced field gets each stage's own time).
use crate::physics::numerics::elementary::Elementary;

use nalgebra::SVector;

use super::lanes::Real;

use super::dop853_tableau::{
    A, A_TERMS, B_TERMS, D_TERMS, E3_TERMS, E5_TERMS, STAGES, STAGES_DENSE, Terms,
};
use crate::physics::method::StepError;

/// The stage times `c_s` (row sums of `A`), for non-autonomous fields.
pub(super) const C: [f64; STAGES_DENSE] = {
    let mut c = [0.0; STAGES_DENSE];
    let mut s = 0;
    while s < STAGES_DENSE {
        let mut j = 0;
        while j < STAGES_DENSE {
            c[s] += A[s][j];
            j += 1;
        }
        s += 1;
    }
    c
};

/// Counters of the work done by an integrator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts.
    pub rejected: u64,
    /// Right-hand-side evaluations (for the splittings: exact fast sub-flows).
    pub rhs_evaluations: u64,
}

/// The right-hand side of a system `y' = f(t, y)` (autonomous unless [`Field::eval_at`] is
/// given: the default ignores `t`).
pub trait Field<const N: usize> {
    /// Evaluates `f(y)`.
    fn eval(&self, y: &SVector<f64, N>) -> SVector<f64, N>;

    /// Evaluates `f(t, y)`; the core calls this one, at each stage's own time `t + c_s h`, so
    /// a forced system needs no time component in its state (whose rounding would drift from
    /// the step's time over many steps).
    #[inline]
    fn eval_at(&self, t: f64, y: &SVector<f64, N>) -> SVector<f64, N> {
        let _ = t;
        self.eval(y)
    }

    /// The error scale of component `i` is `tol · (unit(i) + max(|y_i|, |y_new_i|))`; the unit
    /// is the component's natural size (1 by default).
    fn unit(&self, i: usize) -> f64 {
        let _ = i;
        1.0
    }

    /// Whether component `i` is an unbounded angle, whose error is controlled in absolute
    /// terms (`tol · unit(i)`): its unwrapped size carries no meaning, so it must not loosen
    /// the tolerance.
    fn is_angle(&self, i: usize) -> bool {
        let _ = i;
        false
    }

    /// How many components the error norm averages over: all `N`, unless some are carried
    /// along uncontrolled (an infinite [`Field::unit`]), as the nudged copies of a start that
    /// must take the base start's steps.
    fn controlled(&self) -> usize {
        N
    }
}

impl<const N: usize, F: Fn(&SVector<f64, N>) -> SVector<f64, N>> Field<N> for F {
    fn eval(&self, y: &SVector<f64, N>) -> SVector<f64, N> {
        self(y)
    }
}

/// Adaptive DOP853 on an autonomous system `y' = f(y)` of dimension `N`.
#[derive(Clone)]
pub struct Dop853<const N: usize, F> {
    f: F,
    tol: f64,
    t: f64,
    y: SVector<f64, N>,
    /// `f(y)` at the current point (first stage of the next step).
    f_now: SVector<f64, N>,
    /// Proposed size of the next step.
    h_next: f64,
    t_prev: f64,
    y_prev: SVector<f64, N>,
    h_last: f64,
    k: [SVector<f64, N>; STAGES_DENSE],
    /// The last step's dense-output coefficients, when `dense_ready`.
    dense: [SVector<f64, N>; 7],
    dense_ready: bool,
    stats: Stats,
    /// Whether the step being taken had an attempt rejected (its growth is then held to 1).
    rejected_once: bool,
    /// Whether the last step's stages are still elsewhere (taken in lanes and not handed over:
    /// its dense output cannot be computed until they are).
    stages_away: bool,
}

/// What an attempt's stages give: the new state and the sums of squares of the 5th- and
/// 3rd-order error estimates over their scales; and, where the caller computed them beside the
/// stages (in lanes), the attempt's [`Dop853::error`] and the controller's power of it,
/// `error^(−1/8)` (`super::eighth_power`): the bits [`Dop853::judge`] would compute.
#[derive(Clone, Copy, Debug)]
pub(super) struct Attempt<const N: usize> {
    pub(super) y_new: SVector<f64, N>,
    pub(super) norms: (f64, f64),
    pub(super) controller: Option<(f64, f64)>,
}

/// Hairer's DOP853 error of an attempt of size `h` over `n` components, from its sums of
/// squares `e5`, `e3` (nonzero), in one number or in lanes: the same operations.
#[inline(always)]
#[allow(clippy::inline_always)] // inlined into the lanes' caller, compiled for AVX2
pub(super) fn error_of<R: Real>(h: R, e5: R, e3: R, n: R) -> R {
    h.abs() * e5 / ((e5 + R::splat(0.01) * e3) * n).sqrt()
}

impl<const N: usize, F: Field<N>> Dop853<N, F> {
    /// Starts at `(t0, y0)` with relative and absolute tolerance `tol`.
    pub fn new(f: F, t0: f64, y0: SVector<f64, N>, tol: f64) -> Self {
        let f_now = f.eval_at(t0, &y0);
        let mut me = Self {
            f,
            tol,
            t: t0,
            y: y0,
            f_now,
            h_next: 0.0,
            t_prev: t0,
            y_prev: y0,
            h_last: 0.0,
            k: [SVector::zeros(); STAGES_DENSE],
            dense: [SVector::zeros(); 7],
            dense_ready: false,
            stats: Stats {
                rhs_evaluations: 1,
                ..Stats::default()
            },
            rejected_once: false,
            stages_away: false,
        };
        me.h_next = me.initial_step();
        me
    }

    fn scale(&self, a: &SVector<f64, N>, b: &SVector<f64, N>, i: usize) -> f64 {
        if self.f.is_angle(i) {
            self.tol * self.f.unit(i)
        } else {
            self.tol * (self.f.unit(i) + a[i].abs().max(b[i].abs()))
        }
    }

    fn rms(&self, v: &SVector<f64, N>) -> f64 {
        let mut sum = 0.0;
        for i in 0..N {
            sum += (v[i] / self.scale(&self.y, &self.y, i)).powi(2);
        }
        let n = self.f.controlled() as f64;
        (sum / n).sqrt()
    }

    /// Hairer's starting step: balance the first and second derivatives' sizes.
    fn initial_step(&mut self) -> f64 {
        let d0 = self.rms(&self.y);
        let d1 = self.rms(&self.f_now);
        let h0 = if d0 < 1e-10 || d1 < 1e-10 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        let y1 = self.y + self.f_now * h0;
        let f1 = self.f.eval_at(self.t + h0, &y1);
        self.stats.rhs_evaluations += 1;
        let d2 = self.rms(&(f1 - self.f_now)) / h0;
        let h1 = if d1.max(d2) <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).e_powf(1.0 / 8.0)
        };
        (100.0 * h0).min(h1)
    }

    /// Current time.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The field it integrates.
    pub fn field(&self) -> &F {
        &self.f
    }

    /// Current state.
    pub fn state(&self) -> SVector<f64, N> {
        self.y
    }

    /// Start of the last accepted step.
    pub fn time_prev(&self) -> f64 {
        self.t_prev
    }

    /// State at the start of the last accepted step.
    pub fn state_prev(&self) -> SVector<f64, N> {
        self.y_prev
    }

    /// Work counters.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Replaces the current state by its projection `p` onto the system's constraints (after an
    /// accepted step) and evaluates the field there, so the next step starts from the projected
    /// point. The last step's interpolant then ends at the projected state.
    pub fn project(&mut self, p: impl FnOnce(&mut SVector<f64, N>)) {
        p(&mut self.y);
        self.f_now = self.f.eval_at(self.t, &self.y);
        self.stats.rhs_evaluations += 1;
    }

    /// Takes one accepted step, never past `t_limit` (which must exceed the current time).
    ///
    /// # Errors
    /// When the step size underflows or the solution stops being finite.
    pub fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        loop {
            let (h, last) = self.begin(t_limit)?;
            let attempt = self.stages(h);
            if self.judge(h, last, t_limit, attempt, None)? {
                return Ok(());
            }
        }
    }

    /// The size of the next attempt towards `t_limit`, and whether it lands on it (issue 84:
    /// one attempt of [`Dop853::step`] is this, the stages, and `Dop853::judge`, so that
    /// `super::dop853_lanes` takes the same attempt in lanes).
    ///
    /// # Errors
    /// When the step size is not a positive number or has underflowed.
    pub fn begin(&self, t_limit: f64) -> Result<(f64, bool), StepError> {
        let remaining = t_limit - self.t;
        let last = self.h_next >= remaining;
        let h = if last { remaining } else { self.h_next };
        // A step size that is not a positive number (a start whose derivative is not
        // finite makes the first one NaN) would loop here for ever.
        if h.is_nan() || h <= 0.0 || h.is_infinite() {
            return Err(StepError::NonFinite { t: self.t });
        }
        if h <= 16.0 * f64::EPSILON * self.t.abs() && !last {
            return Err(StepError::StepTooSmall { t: self.t, h });
        }
        Ok((h, last))
    }

    /// The stages of an attempt of size `h` from the current point, into `k`, and what they
    /// give: the new state and the two error estimates.
    fn stages(&mut self, h: f64) -> Attempt<N> {
        self.k[0] = self.f_now;
        for s in 1..STAGES {
            let row = &A_TERMS[s];
            let mut acc = SVector::<f64, N>::zeros();
            for i in 0..row.len {
                acc += self.k[row.j[i]] * row.w[i];
            }
            self.k[s] = self.f.eval_at(self.t + C[s] * h, &(self.y + acc * h));
        }
        let sum = |terms: &Terms, k: &[SVector<f64, N>; STAGES_DENSE]| {
            let mut acc = SVector::<f64, N>::zeros();
            for i in 0..terms.len {
                acc += k[terms.j[i]] * terms.w[i];
            }
            acc
        };
        let y_new = self.y + sum(&B_TERMS, &self.k) * h;
        let norms = self.norms(&y_new, &sum(&E5_TERMS, &self.k), &sum(&E3_TERMS, &self.k));
        Attempt {
            y_new,
            norms,
            controller: None,
        }
    }

    /// The sums of squares of the 5th- and 3rd-order error estimates `err5`, `err3` of an
    /// attempt ending at `y_new`, each component over its scale.
    fn norms(
        &self,
        y_new: &SVector<f64, N>,
        err5: &SVector<f64, N>,
        err3: &SVector<f64, N>,
    ) -> (f64, f64) {
        let (mut e5, mut e3) = (0.0, 0.0);
        for i in 0..N {
            let sk = self.scale(&self.y, y_new, i);
            let (q5, q3) = (err5[i] / sk, err3[i] / sk);
            e5 += q5 * q5;
            e3 += q3 * q3;
        }
        (e5, e3)
    }

    /// The tolerance, the scales' unit of component `i` and whether it is an angle: what a
    /// batched attempt reads to compute [`Dop853::norms`] in lanes.
    pub(super) fn scaled(&self, i: usize) -> (f64, f64, bool) {
        (self.tol, self.f.unit(i), self.f.is_angle(i))
    }

    /// The current point and the field there: what a batched attempt starts from.
    pub(super) fn point(&self) -> (f64, &SVector<f64, N>, &SVector<f64, N>) {
        (self.t, &self.y, &self.f_now)
    }

    /// The stages of an attempt taken elsewhere (in lanes), which the dense output reads.
    pub(super) fn stages_from(&mut self, k: impl Fn(usize) -> SVector<f64, N>) {
        for s in 0..STAGES {
            self.k[s] = k(s);
        }
        self.stages_away = false;
    }

    /// The error of an attempt of size `h` whose sums of squares are `norms`, which the
    /// step-size controller reads.
    fn error(&self, h: f64, (e5, e3): (f64, f64)) -> f64 {
        if e5 == 0.0 && e3 == 0.0 {
            0.0
        } else {
            error_of(h, e5, e3, self.controlled())
        }
    }

    /// How many components the error norm counts, as the norm reads it.
    pub(super) fn controlled(&self) -> f64 {
        self.f.controlled() as f64
    }

    /// Accepts or rejects the attempt of size `h` whose stages are in `k` (where accepted) and
    /// gave `attempt`;
    /// `f_new` is the field at its end when already evaluated (the lanes evaluate it whatever
    /// the verdict), else it is evaluated here when accepted. `Ok(true)`: the step is taken.
    ///
    /// # Errors
    /// When the solution stops being finite and the step cannot shrink any further.
    pub(super) fn judge(
        &mut self,
        h: f64,
        last: bool,
        t_limit: f64,
        attempt: Attempt<N>,
        f_new: Option<SVector<f64, N>>,
    ) -> Result<bool, StepError> {
        let Attempt {
            y_new,
            norms,
            controller,
        } = attempt;
        self.stats.rhs_evaluations += (STAGES - 1) as u64;
        let err = controller.map_or_else(|| self.error(h, norms), |(err, _)| err);
        let power = || controller.map_or_else(|| err.e_powf(-0.125), |(_, power)| power);
        if !err.is_finite() || !y_new.iter().all(|v| v.is_finite()) {
            self.stats.rejected += 1;
            self.h_next = h * 0.1;
            // Not greater (NaN included): the step cannot shrink any further.
            if self
                .h_next
                .partial_cmp(&(f64::EPSILON * self.t.abs().max(1.0)))
                != Some(std::cmp::Ordering::Greater)
            {
                return Err(StepError::NonFinite { t: self.t });
            }
            self.rejected_once = true;
            return Ok(false);
        }
        if err > 1.0 {
            self.stats.rejected += 1;
            self.rejected_once = true;
            self.h_next = h * (0.9 * power()).max(0.2);
            return Ok(false);
        }
        let t_new = if last { t_limit } else { self.t + h };
        self.stages_away = f_new.is_some();
        let f_new = f_new.unwrap_or_else(|| self.f.eval_at(t_new, &y_new));
        self.stats.rhs_evaluations += 1;
        self.k[STAGES] = f_new;
        self.t_prev = self.t;
        self.y_prev = self.y;
        self.t = t_new;
        self.y = y_new;
        self.f_now = f_new;
        self.h_last = h;
        self.dense_ready = false;
        self.stats.steps += 1;
        let mut factor = if err == 0.0 {
            6.0
        } else if self.rejected_once && err < 0.43 {
            // Held to 1 below: `0.9 err^(−1/8)` exceeds 1.0001 here (0.9⁸ = 0.4305), far beyond
            // the power's rounding, so the power is not computed (issue 84: it was an eighth
            // of a chart's time).
            1.0
        } else {
            (0.9 * power()).clamp(1.0 / 3.0, 6.0)
        };
        if self.rejected_once {
            factor = factor.min(1.0);
        }
        self.rejected_once = false;
        // A step shortened to land on `t_limit` says little about the natural size.
        self.h_next = if last {
            self.h_next.max(h * factor)
        } else {
            h * factor
        };
        Ok(true)
    }

    /// Computes the last step's dense-output coefficients into `dense`, at its first
    /// interpolation; later ones read them in place (issue 84: a copy of them for each of the
    /// crossing search's 31 points was a twentieth of a chart's time).
    #[allow(clippy::needless_range_loop)]
    fn compute_dense(&mut self) {
        if self.dense_ready {
            return;
        }
        assert!(
            !self.stages_away,
            "a step taken in lanes was interpolated before its stages were handed back"
        );
        let h = self.h_last;
        for s in STAGES + 1..STAGES_DENSE {
            let row = &A_TERMS[s];
            let mut acc = SVector::<f64, N>::zeros();
            for i in 0..row.len {
                acc += self.k[row.j[i]] * row.w[i];
            }
            self.k[s] = self
                .f
                .eval_at(self.t_prev + C[s] * h, &(self.y_prev + acc * h));
        }
        self.stats.rhs_evaluations += 3;
        let dy = self.y - self.y_prev;
        let mut d = [SVector::<f64, N>::zeros(); 7];
        d[0] = dy;
        d[1] = self.k[0] * h - dy;
        d[2] = dy * 2.0 - (self.k[STAGES] + self.k[0]) * h;
        for (row, terms) in D_TERMS.iter().enumerate() {
            let mut acc = SVector::<f64, N>::zeros();
            for i in 0..terms.len {
                acc += self.k[terms.j[i]] * terms.w[i];
            }
            d[3 + row] = acc * h;
        }
        self.dense = d;
        self.dense_ready = true;
    }

    /// The dense-output interpolant of the last step at `t` in `[time_prev, time]`.
    pub fn interpolate(&mut self, t: f64) -> SVector<f64, N> {
        self.interpolate_first::<N>(t)
    }

    /// The first `M` components of [`Dop853::interpolate`]`(t)`, without the others' work
    /// (issue 84: the celt's crossing search reads the spin, 6 of its 13).
    pub fn interpolate_first<const M: usize>(&mut self, t: f64) -> SVector<f64, M> {
        const { assert!(M <= N) };
        if self.h_last == 0.0 {
            return SVector::<f64, M>::from_fn(|i, _| self.y[i]);
        }
        self.compute_dense();
        let d = &self.dense;
        let x = (t - self.t_prev) / self.h_last;
        let x1 = 1.0 - x;
        SVector::<f64, M>::from_fn(|i, _| {
            let v = d[0][i]
                + (d[1][i]
                    + (d[2][i] + (d[3][i] + (d[4][i] + (d[5][i] + d[6][i] * x) * x1) * x) * x1)
                        * x)
                    * x1;
            self.y_prev[i] + v * x
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn harmonic_oscillator_to_tolerance_with_accurate_dense_output() {
        let f = |y: &Vector2<f64>| Vector2::new(y[1], -y[0]);
        let mut ode = Dop853::new(f, 0.0, Vector2::new(0.0, 1.0), 1e-12);
        let mut worst: f64 = 0.0;
        while ode.time() < 10.0 {
            ode.step(10.0).unwrap();
            let tm = 0.5 * (ode.time_prev() + ode.time());
            worst = worst.max((ode.interpolate(tm)[0] - tm.e_sin()).abs());
        }
        assert!((ode.state()[0] - 10f64.e_sin()).abs() < 1e-10);
        assert!(worst < 1e-10, "dense output error {worst}");
    }
}
