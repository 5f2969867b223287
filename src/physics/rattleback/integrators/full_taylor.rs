//! `taylor` on the full model: the Taylor series of `(γ, α, γ̇, α̇)` about each step's start
//! (issue 27, items 1–2: the middle stiffnesses, where `auto` still resolves the fast motion).
//!
//! At equal error DOP853 costs 1.7–6.6× as much on the averaging note's starts, k = 1e2 … 1e5,
//! T = 30 (four to six steps a fast period, where DOP853 takes twenty to forty; `cargo run
//! --release --example rattleback_taylor cost`). `auto` runs its probes' full model with it (its
//! `PROBE_FULL_METHOD`), but not its resolved runs: its
//! error does not fall smoothly with the tolerance, so a looser companion does not bound it.
//! `α̇` carries a ripple at twice the fast frequency, which a step of a fifth of a fast period
//! samples two or three times a ripple period; each step's truncation error in `α̇` takes the
//! sign of the ripple's phase there, and the run's error is their sum, a random walk, which
//! neighbouring tolerances cancel differently (B at k = 1e3: 1.0e-10 at 1e-10, 5.9e-10 at
//! 3.2e-11). A companion 16× looser read less than the error in 14 of 375 runs on the references
//! (`… rattleback_taylor companion`; DOP853, whose steps sample the ripple densely and whose
//! error is systematic, never: docs/benchmarks.md).
//!
//! The right-hand side `γ̈ = −(g' α̇ γ̇ + k γ)/g`, `α̈ = g' γ̇² / (2 iz)` is written in the
//! double angle `β = 2α`: `g = G0 + G1 cos β` with `G0 = (ix + iy)/2`, `G1 = (ix − iy)/2`, and
//! `g' = (iy − ix) sin β`. With `S = sin β`, `C = cos β`, `w = γ̇`, `v = α̇`, each order `n`
//! takes six convolutions (Jorba and Zou's automatic differentiation, 2005):
//! - `P = S w`, then `A = P v` and `B = P w` (`g' α̇ γ̇ = (iy − ix) A`, `g' γ̇² = (iy − ix) B`);
//! - the quotient `q = (k γ + (iy − ix) A) / g`, `q_n = (N_n − G1 Σ_{j≥1} C_j q_{n−j}) / g_0`;
//! - `S`, `C` by their recurrences in `β`: `(n+1) S_{n+1} = Σ j β_j C_{n+1−j}`,
//!   `(n+1) C_{n+1} = −Σ j β_j S_{n+1−j}`;
//!
//! and then `γ_{n+1} = w_n/(n+1)`, `α_{n+1} = v_n/(n+1)`, `w_{n+1} = −q_n/(n+1)`,
//! `v_{n+1} = (iy − ix) B_n / (2 iz (n+1))`. One `sin_cos` a step; no right-hand side is
//! evaluated.
//!
//! **Step size and error scale** as the pendulum's series (`numerics::taylor`): the smallest
//! `(1/m_n)^{1/n}` over the last three orders, `m_n` the largest coefficient of order `n` over
//! its component's error scale, which is DOP853's here (`tol (u + |γ|)` for `γ` with `u = 1/ω_max`,
//! `tol` for the angle `α`, `tol (1 + |y_i|)` for the rates). The order is fixed ([`ORDER`]);
//! the series itself is the dense output; no step is rejected.
use crate::physics::numerics::elementary::Elementary;

use crate::physics::method::StepError;
use crate::physics::numerics::dop853::Stats;
use crate::physics::numerics::stepper::Stepper;
use crate::physics::numerics::taylor::{Clock, horner, natural_step};
use crate::physics::rattleback::model::State;
use crate::physics::rattleback::params::Params;

/// The order of the series, whatever the tolerance (as the pendulum's, for the same reason: a
/// run and its looser companion then differ only in their steps).
pub const ORDER: usize = 20;

const N1: usize = ORDER + 1;

/// `1/m` for `m = 0..=ORDER` (`INVERSE[0]` unused): the recurrences multiply by it, a division
/// being several times a multiplication's latency on their critical path.
const INVERSE: [f64; N1] = {
    let mut r = [0.0; N1];
    let mut m = 1;
    while m < N1 {
        {
            r[m] = 1.0 / m as f64;
        }
        m += 1;
    }
    r
};

/// The Taylor integrator of the full model.
#[derive(Clone)]
pub struct TaylorCore {
    g0: f64,
    g1: f64,
    /// `iy − ix`.
    d: f64,
    k: f64,
    /// `(iy − ix) / (2 iz)`.
    d_over_two_iz: f64,
    /// `1/ω_max`, the natural unit of `γ`.
    unit_gamma: f64,
    tol: f64,
    /// The time, the last step's start, the counts.
    clock: Clock,
    y: State,
    /// Coefficients of `γ`, `α`, `γ̇`, `α̇` about the last step's start, orders `0..=ORDER`.
    c: [[f64; N1]; 4],
}

impl TaylorCore {
    /// Starts at `(t0, y0)` with tolerance `tol`.
    #[must_use]
    pub fn new(params: &Params, t0: f64, y0: State, tol: f64) -> Self {
        let mut c = [[0.0; N1]; 4];
        for (i, series) in c.iter_mut().enumerate() {
            series[0] = y0[i];
        }
        Self {
            g0: 0.5 * (params.ix + params.iy),
            g1: 0.5 * (params.ix - params.iy),
            d: params.iy - params.ix,
            k: params.k,
            d_over_two_iz: (params.iy - params.ix) / (2.0 * params.iz),
            unit_gamma: 1.0 / params.omega_max(),
            tol,
            clock: Clock::at(t0),
            y: y0,
            c,
        }
    }

    /// Expands the state about the current point into `self.c`.
    fn expand(&mut self) {
        const O: usize = ORDER;
        let [gm, al, w, v] = &mut self.c;
        gm[0] = self.y[0];
        al[0] = self.y[1];
        w[0] = self.y[2];
        v[0] = self.y[3];
        let (mut s, mut c) = ([0.0; N1], [0.0; N1]);
        (s[0], c[0]) = (2.0 * al[0]).e_sin_cos();
        let (mut p, mut q) = ([0.0; N1], [0.0; N1]);
        // `j β_j = 2 j α_j`, kept so the sine and cosine are one pass.
        let mut jb = [0.0; N1];
        // The second factors of the convolutions, stored backwards (`r[ORDER − i]` is order `i`)
        // so every convolution is a dot product of two contiguous slices.
        let (mut wr, mut vr, mut qr, mut sr, mut cr) =
            ([0.0; N1], [0.0; N1], [0.0; N1], [0.0; N1], [0.0; N1]);
        wr[O] = w[0];
        vr[O] = v[0];
        sr[O] = s[0];
        cr[O] = c[0];
        let g_at0 = self.g0 + self.g1 * c[0];
        let inv_g0 = 1.0 / g_at0;
        for n in 0..ORDER {
            // `P_n = Σ S_j w_{n−j}`; `A_n`, `B_n` = `Σ P_j (v, w)_{n−j}` but for their `j = n`
            // term, which needs `P_n`; the quotient's `Σ_{j≥1} C_j q_{n−j}`; and the next
            // order's `Σ j β_j (C, S)_{n+1−j}` but for its `j = n + 1` term, which needs
            // `α_{n+1}`.
            let pn = s[0] * w[n] + dot(&s[1..=n], &wr[O + 1 - n..]);
            let mut a = dot(&p[..n], &vr[O - n..O]);
            let mut b = dot(&p[..n], &wr[O - n..O]);
            let qc = dot(&c[1..=n], &qr[O + 1 - n..]);
            let mut ds = dot(&jb[1..=n], &cr[O - n..O]);
            let mut dc = dot(&jb[1..=n], &sr[O - n..O]);
            p[n] = pn;
            a += pn * v[0];
            b += pn * w[0];
            q[n] = (self.k * gm[n] + self.d * a - self.g1 * qc) * inv_g0;
            qr[O - n] = q[n];
            let inv_m = INVERSE[n + 1];
            gm[n + 1] = w[n] * inv_m;
            al[n + 1] = v[n] * inv_m;
            w[n + 1] = -q[n] * inv_m;
            v[n + 1] = self.d_over_two_iz * b * inv_m;
            jb[n + 1] = 2.0 * v[n];
            ds += jb[n + 1] * c[0];
            dc += jb[n + 1] * s[0];
            s[n + 1] = ds * inv_m;
            c[n + 1] = -dc * inv_m;
            wr[O - n - 1] = w[n + 1];
            vr[O - n - 1] = v[n + 1];
            sr[O - n - 1] = s[n + 1];
            cr[O - n - 1] = c[n + 1];
        }
    }

    /// The step the series allows (see the module's documentation).
    fn natural_step(&self) -> f64 {
        let tol = self.tol;
        let scale = [
            tol * (self.unit_gamma + self.y[0].abs()),
            tol,
            tol * (1.0 + self.y[2].abs()),
            tol * (1.0 + self.y[3].abs()),
        ];
        natural_step(ORDER, |n| {
            (0..4)
                .map(|i| self.c[i][n].abs() / scale[i])
                .fold(0.0, f64::max)
        })
    }
}

impl Stepper<4> for TaylorCore {
    /// Current time.
    fn time(&self) -> f64 {
        self.clock.t
    }

    /// Current state.
    fn state(&self) -> State {
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
    fn interpolate(&mut self, t: f64) -> State {
        if t >= self.clock.t {
            return self.y;
        }
        let tau = t - self.clock.t_prev;
        State::from_fn(|i, _| horner(&self.c[i], tau))
    }

    /// Takes one step, never past `t_limit` (which must exceed the current time).
    ///
    /// # Errors
    /// When the series stops being finite or its step underflows.
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        self.expand();
        let natural = self.natural_step();
        let c = &self.c;
        self.y = self.clock.advance(ORDER, natural, t_limit, |h| {
            State::from_fn(|i, _| horner(&c[i], h))
        })?;
        Ok(())
    }
}

/// `Σ a_i b_i` over two slices of one length, in four interleaved partial sums (which the
/// compiler keeps in vector registers).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    debug_assert_eq!(a.len(), b.len());
    let mut acc = [0.0; 4];
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ar, br) = (ac.remainder(), bc.remainder());
    for (x, y) in ac.zip(bc) {
        for i in 0..4 {
            acc[i] += x[i] * y[i];
        }
    }
    let mut tail = 0.0;
    for (x, y) in ar.iter().zip(br) {
        tail += x * y;
    }
    (acc[0] + acc[2]) + (acc[1] + acc[3]) + tail
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::numerics::dop853::Dop853;
    use crate::physics::numerics::stepper::FullCore;
    use crate::physics::rattleback::integrators::full::FullField;

    /// The series against DOP853 at 1e-15 on a rotating body at k = 300 (about 100 fast
    /// periods): the end and the series at every step's middle within 1e-9, at a few steps a
    /// fast period where DOP853 takes about twenty.
    #[test]
    fn agrees_with_dop853_through_the_fast_motion() {
        let p = Params {
            ix: 1.3,
            iy: 0.8,
            iz: 1.1,
            k: 300.0,
        };
        let y0 = State::new(0.02, 0.4, -0.5, 1.2);
        let mut taylor = TaylorCore::new(&p, 0.0, y0, 1e-13);
        let mut dop = <Dop853<4, FullField> as FullCore<4, _>>::start(&p, y0, 1e-15);
        let t_end = 30.0;
        let (worst, end) = crate::physics::numerics::stepper::gaps(&mut taylor, &mut dop, t_end);
        assert!(end < 1e-9, "end {end}");
        assert!(worst < 1e-9, "dense output {worst}");
        let periods = t_end * p.omega_max() / std::f64::consts::TAU;
        let per_period = taylor.stats().steps as f64 / periods;
        assert!(per_period < 8.0, "{per_period} steps a period");
    }
}
