//! DOP853 in lanes (issue 84): [`LANES`] integrations advanced side by side, one attempt each
//! per call of [`attempt`], each with its own step size, verdict and events. Only the stages'
//! arithmetic is shared: each lane's step size comes from [`Dop853::begin`], its stages are
//! computed in a lane of [`F64x4`] with the operations, in the order, of the scalar
//! `Dop853::stages` (the same nonzero terms of the same tableau), and its verdict is the scalar
//! `Dop853::judge` on them, given the attempt's error and the controller's power of it
//! computed in lanes (the scalar core's `error_of`; [`eighth_power`], the scalar power's
//! bits). So a lane's every step is the step a lone run takes, bit for bit, and a lane that
//! fails fails alone.
//!
//! The one difference in work: the field at an attempt's end is evaluated in every lane, also
//! where the attempt is then rejected (a lone run evaluates it only when it accepts).
// Inlined into the caller compiled for the machine's vector unit (`multiversion`): a call
// that is not inlined runs at the baseline's width.
#![allow(clippy::inline_always)]

use nalgebra::SVector;

use super::dop853::{Attempt, C, Dop853, Field, error_of};
use super::dop853_tableau::{A_TERMS, B_TERMS, E3_TERMS, E5_TERMS, STAGES, Terms};
use super::eighth_power::eighth_power;
use super::lanes::{F64x4, LANES, Real};
use crate::physics::method::StepError;

/// A field that can be evaluated in lanes, each lane with its own constants.
pub trait Packs<const N: usize>: Field<N> {
    /// The constants of [`LANES`] fields, lane by lane.
    type Packed;
    /// `fields[l]`'s constants in lane `l`.
    fn pack(fields: [&Self; LANES]) -> Self::Packed;
    /// The field in every lane at time `t` and state `y`: lane by lane what
    /// [`Field::eval_at`] gives, bit for bit.
    fn eval_packed(packed: &Self::Packed, t: F64x4, y: &[F64x4; N]) -> [F64x4; N];
}

/// What one lane's attempt came to: `Ok(true)` its step is taken, `Ok(false)` rejected (the
/// next call attempts it again, smaller), or its run's error.
pub type Verdict = Result<bool, StepError>;

/// The stages of a batched attempt, kept between attempts so that none starts by filling
/// 5 KB.
pub struct Scratch<const N: usize> {
    k: [[F64x4; N]; STAGES + 1],
}

impl<const N: usize> Default for Scratch<N> {
    fn default() -> Self {
        Self {
            k: [[F64x4::default(); N]; STAGES + 1],
        }
    }
}

impl<const N: usize> Scratch<N> {
    /// Hands lane `l`'s stages of the last attempt to `core`, whose step it took: what its
    /// dense output reads. Only a step that will be interpolated needs them (issue 84: most
    /// steps are not).
    pub fn hand_over<F: Field<N>>(&self, core: &mut Dop853<N, F>, l: usize) {
        core.stages_from(|s| SVector::<f64, N>::from_fn(|i, _| self.k[s][i].0[l]));
    }
}

/// One attempt of each lane's current step (`None`: an empty lane), `cores[l]` towards
/// `t_limits[l]`, the fields' constants being `packed` (of the same lanes).
///
/// # Panics
/// Never: a lane read is one found live.
#[inline(always)]
pub fn attempt<const N: usize, F: Packs<N>>(
    cores: &mut [Option<&mut Dop853<N, F>>; LANES],
    packed: &F::Packed,
    t_limits: [f64; LANES],
    scratch: &mut Scratch<N>,
) -> [Option<Verdict>; LANES] {
    let mut out: [Option<Verdict>; LANES] = [None, None, None, None];
    let mut steps = [(0.0, false); LANES];
    let mut first = None;
    for l in 0..LANES {
        if let Some(core) = cores[l].as_deref() {
            match core.begin(t_limits[l]) {
                Ok(step) => {
                    steps[l] = step;
                    first.get_or_insert(l);
                }
                Err(e) => out[l] = Some(Err(e)),
            }
        }
    }
    let Some(first) = first else {
        return out;
    };
    // An empty or failed lane computes the first live lane's attempt, and is not read.
    let live: [bool; LANES] = std::array::from_fn(|l| cores[l].is_some() && out[l].is_none());
    let from: [usize; LANES] = std::array::from_fn(|l| if live[l] { l } else { first });
    let k = &mut scratch.k;
    let mut t = [0.0; LANES];
    let mut y = [F64x4::default(); N];
    let (mut tol, mut unit) = ([0.0; LANES], [[0.0; LANES]; N]);
    let mut angle = [false; N];
    for l in 0..LANES {
        let core = cores[from[l]].as_deref().expect("a live lane");
        let (tl, yl, fl) = core.point();
        t[l] = tl;
        for i in 0..N {
            y[i].0[l] = yl[i];
            k[0][i].0[l] = fl[i];
            (tol[l], unit[i][l], angle[i]) = core.scaled(i);
        }
    }
    let h = F64x4(std::array::from_fn(|l| steps[from[l]].0));
    let tv = F64x4(t);
    for s in 1..STAGES {
        let ys = advanced(&y, &sum(&A_TERMS[s], k), h);
        k[s] = F::eval_packed(packed, tv + F64x4::splat(C[s]) * h, &ys);
    }
    let y_new = advanced(&y, &sum(&B_TERMS, k), h);
    // The scalar core's `norms`, lane by lane.
    let (err5, err3) = (sum(&E5_TERMS, k), sum(&E3_TERMS, k));
    let tol = F64x4(tol);
    let (mut e5, mut e3) = (F64x4::splat(0.0), F64x4::splat(0.0));
    for i in 0..N {
        let u = F64x4(unit[i]);
        let sk = if angle[i] {
            tol * u
        } else {
            tol * (u + y[i].abs().max(y_new[i].abs()))
        };
        let (q5, q3) = (err5[i] / sk, err3[i] / sk);
        e5 = e5 + q5 * q5;
        e3 = e3 + q3 * q3;
    }
    let t_new = F64x4(std::array::from_fn(|l| {
        let (hl, last) = steps[from[l]];
        if last { t_limits[from[l]] } else { t[l] + hl }
    }));
    k[STAGES] = F::eval_packed(packed, t_new, &y_new);
    // Each lane's error (the scalar core's `error_of`) and the controller's power of it.
    let n = cores[first].as_deref().expect("a live lane").controlled();
    let quotient = error_of(h, e5, e3, F64x4::splat(n));
    let errors: [f64; LANES] = std::array::from_fn(|l| {
        if e5.0[l] == 0.0 && e3.0[l] == 0.0 {
            0.0
        } else {
            quotient.0[l]
        }
    });
    let powers = eighth_power(errors);
    for l in (0..LANES).filter(|&l| live[l]) {
        let lane = |v: &[F64x4; N]| SVector::<f64, N>::from_fn(|i, _| v[i].0[l]);
        let core = cores[l].as_deref_mut().expect("a live lane");
        let attempt = Attempt {
            y_new: lane(&y_new),
            norms: (e5.0[l], e3.0[l]),
            controller: Some((errors[l], powers[l])),
        };
        let (hl, last) = steps[l];
        out[l] = Some(core.judge(hl, last, t_limits[l], attempt, Some(lane(&k[STAGES]))));
    }
    out
}

/// `y + acc h`, component by component. A loop, not `std::array::from_fn`, which the
/// compiler may leave out of line, compiled for the baseline's width (issue 84: the new state's
/// was, and its call and copy cost a thirtieth of a chart's time).
#[inline(always)]
fn advanced<const N: usize>(y: &[F64x4; N], acc: &[F64x4; N], h: F64x4) -> [F64x4; N] {
    let mut out = [F64x4::default(); N];
    for i in 0..N {
        out[i] = y[i] + acc[i] * h;
    }
    out
}

/// `Σ w_j k_j` over `terms`, from `+0`, in the scalar core's order.
#[inline(always)]
fn sum<const N: usize>(terms: &Terms, k: &[[F64x4; N]; STAGES + 1]) -> [F64x4; N] {
    let mut acc = [F64x4::splat(0.0); N];
    for i in 0..terms.len {
        let w = F64x4::splat(terms.w[i]);
        let kj = &k[terms.j[i]];
        for c in 0..N {
            acc[c] = acc[c] + kj[c] * w;
        }
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y' = c (y_1, −y_0) + d y`: a rotation at rate `c` with growth `d`, each lane its own.
    #[derive(Clone, Copy, Debug)]
    struct Spiral {
        c: f64,
        d: f64,
    }

    impl Field<2> for Spiral {
        fn eval(&self, y: &SVector<f64, 2>) -> SVector<f64, 2> {
            SVector::<f64, 2>::new(
                self.c * y[1] + self.d * y[0],
                -self.c * y[0] + self.d * y[1],
            )
        }
    }

    impl Packs<2> for Spiral {
        type Packed = (F64x4, F64x4);
        fn pack(fields: [&Self; LANES]) -> Self::Packed {
            (F64x4(fields.map(|f| f.c)), F64x4(fields.map(|f| f.d)))
        }
        fn eval_packed(p: &Self::Packed, _t: F64x4, y: &[F64x4; 2]) -> [F64x4; 2] {
            let (c, d) = *p;
            [c * y[1] + d * y[0], -c * y[0] + d * y[1]]
        }
    }

    /// Every accepted step's `(t, y)` of a run to `t_end`, and how it ended.
    type Trace = (Vec<(u64, u64, u64)>, Result<(), StepError>);

    fn lone(f: Spiral, tol: f64, t_end: f64) -> Trace {
        let mut core = Dop853::new(f, 0.0, SVector::<f64, 2>::new(1.0, 0.0), tol);
        let mut steps = Vec::new();
        while core.time() < t_end {
            if let Err(e) = core.step(t_end) {
                return (steps, Err(e));
            }
            let y = core.state();
            steps.push((core.time().to_bits(), y[0].to_bits(), y[1].to_bits()));
        }
        (steps, Ok(()))
    }

    /// Issue 84: four runs in lanes, each with its own field, tolerance and window, one whose
    /// field is not finite from the start and one that overflows on the way: each lane's steps
    /// are its lone run's, bit for bit, and a lane that fails fails alone, with its lone run's
    /// error, while the others go on to their ends.
    #[test]
    fn each_lane_is_its_lone_run_and_fails_alone() {
        let runs = [
            (Spiral { c: 3.0, d: -0.1 }, 1e-9, 10.0),
            (
                Spiral {
                    c: f64::NAN,
                    d: 0.0,
                },
                1e-6,
                10.0,
            ),
            (Spiral { c: 40.0, d: 0.0 }, 1e-6, 3.0),
            (Spiral { c: 1.0, d: 300.0 }, 1e-8, 10.0),
        ];
        let mut cores: [Dop853<2, Spiral>; LANES] = std::array::from_fn(|l| {
            let (f, tol, _) = runs[l];
            Dop853::new(f, 0.0, SVector::<f64, 2>::new(1.0, 0.0), tol)
        });
        let packed = Spiral::pack(std::array::from_fn(|l| &runs[l].0));
        let mut traces: [Trace; LANES] = std::array::from_fn(|_| (Vec::new(), Ok(())));
        let mut ended = [false; LANES];
        let mut scratch = Scratch::default();
        while ended.iter().any(|e| !e) {
            let mut lanes: [Option<&mut Dop853<2, Spiral>>; LANES] = [None, None, None, None];
            for (l, (slot, core)) in lanes.iter_mut().zip(cores.iter_mut()).enumerate() {
                if !ended[l] {
                    *slot = Some(core);
                }
            }
            let verdicts = attempt(&mut lanes, &packed, runs.map(|r| r.2), &mut scratch);
            for l in 0..LANES {
                match verdicts[l] {
                    None | Some(Ok(false)) => {}
                    Some(Err(ref e)) => {
                        traces[l].1 = Err(e.clone());
                        ended[l] = true;
                    }
                    Some(Ok(true)) => {
                        scratch.hand_over(&mut cores[l], l);
                        let y = cores[l].state();
                        traces[l].0.push((
                            cores[l].time().to_bits(),
                            y[0].to_bits(),
                            y[1].to_bits(),
                        ));
                        ended[l] = cores[l].time() >= runs[l].2;
                    }
                }
            }
        }
        for l in 0..LANES {
            let (f, tol, t_end) = runs[l];
            assert_eq!(traces[l], lone(f, tol, t_end), "lane {l}");
        }
        assert!(
            traces[1].1.is_err() && traces[3].1.is_err(),
            "{:?}",
            traces.map(|t| t.1)
        );
        assert!(traces[0].0.len() > 10 && traces[2].0.len() > 10);
        // Dense output after a step taken in lanes: the lone run's.
        let mut alone = Dop853::new(runs[0].0, 0.0, SVector::<f64, 2>::new(1.0, 0.0), 1e-9);
        for _ in 0..traces[0].0.len() {
            alone.step(runs[0].2).unwrap();
        }
        let mid = 0.5 * (cores[0].time_prev() + cores[0].time());
        assert_eq!(cores[0].interpolate(mid), alone.interpolate(mid));
    }
}
