//! `averaged2` and `averaged3`: the second- and third-order averaged models
//! (`physics::rattleback::averaged`, docs/physics.md §4c; `physics::rattleback::averaged3`), their
//! slow flow on `(ᾱ, P̄, ψ̄)` integrated by the DOP853 core.
//!
//! Order 8 in the step, not symplectic; 12 evaluations per step, each a `sin_cos` and a
//! `sqrt`; the cost does not depend on `k`. The error against the full model is the model
//! error, O(k⁻²) (`averaged2`) or O(k⁻³) (`averaged3`) in `α`, `α̇` and the reversal times
//! (`tests/it/averaged.rs`), plus the integration error of the slow flow, which the tolerance
//! controls. The reported state is reconstructed (the fast ripple included); reversals are
//! zeros of the reconstructed `α̇`, located on the dense output.
use crate::physics::numerics::elementary::Elementary;

use nalgebra::SVector;

use crate::physics::flow::{CHECK_EVERY, EventTracker, Flow};
use crate::physics::method::Method;
use crate::physics::method::{StepCap, StepError};
use crate::physics::numerics::dop853::{Dop853, Field};
use crate::physics::numerics::roots::{find_root, find_root_near};
use crate::physics::rattleback::averaged::{Averaged2, SlowState, turned};
use crate::physics::rattleback::averaged3::Averaged3;
use crate::physics::rattleback::model::State;
use crate::physics::rattleback::params::Problem;

/// What the integrator needs of an averaged model.
pub trait SlowModel: Clone + Copy + Send + Sync + 'static {
    /// The method that integrates it.
    const METHOD: Method;
    /// The model of a problem's start and its averaged initial state.
    fn start(problem: &Problem) -> (Self, SlowState);
    /// The slow flow.
    fn rhs(&self, y: &SlowState) -> SlowState;
    /// `K̄(ᾱ, P̄)`.
    fn kbar(&self, alpha_bar: f64, p_bar: f64) -> f64;
    /// The reconstructed `α̇`.
    fn spin_rate(&self, y: &SlowState) -> f64;
    /// The full-model-shaped state.
    fn to_full_state(&self, y: &SlowState) -> State;
    /// The averaged fast action.
    fn ibar(&self) -> f64;
    /// Whether [`SlowModel::rhs_turned`] uses the `(sin 2ᾱ, cos 2ᾱ)` it is given.
    const TURNS: bool = false;
    /// The slow flow given `(sin 2ᾱ, cos 2ᾱ)` (a model whose flow takes them, [`Self::TURNS`]).
    #[inline]
    fn rhs_turned(&self, y: &SlowState, turn: (f64, f64)) -> SlowState {
        let _ = turn;
        self.rhs(y)
    }
}

macro_rules! slow_model {
    ($t:ty, $m:expr, {$($turns:tt)*}) => {
        impl SlowModel for $t {
            const METHOD: Method = $m;
            fn start(problem: &Problem) -> (Self, SlowState) {
                <$t>::new(problem)
            }
            #[inline]
            fn rhs(&self, y: &SlowState) -> SlowState {
                <$t>::rhs(self, y)
            }
            fn kbar(&self, alpha_bar: f64, p_bar: f64) -> f64 {
                <$t>::kbar(self, alpha_bar, p_bar)
            }
            #[inline]
            fn spin_rate(&self, y: &SlowState) -> f64 {
                <$t>::spin_rate(self, y)
            }
            fn to_full_state(&self, y: &SlowState) -> State {
                <$t>::to_full_state(self, y)
            }
            fn ibar(&self) -> f64 {
                <$t>::ibar(self)
            }
            $($turns)*
        }
    };
}
slow_model!(Averaged2, Method::Averaged2, {
    const TURNS: bool = true;
    #[inline]
    fn rhs_turned(&self, y: &SlowState, turn: (f64, f64)) -> SlowState {
        Averaged2::rhs_turned(self, y, turn)
    }
});
slow_model!(Averaged3, Method::Averaged3, {});

/// The slow field of `K̄`.
#[derive(Clone)]
pub struct AveragedField<M> {
    model: M,
    /// Natural size of `P̄`, the momentum scale of the start.
    momentum_unit: f64,
}

impl<M: SlowModel> Field<3> for AveragedField<M> {
    #[inline]
    fn eval(&self, y: &SlowState) -> SlowState {
        self.model.rhs(y)
    }
    fn unit(&self, i: usize) -> f64 {
        if i == 1 { self.momentum_unit } else { 1.0 }
    }
    fn is_angle(&self, i: usize) -> bool {
        i != 1
    }
}

/// DOP853 on the averaged slow flow.
#[derive(Clone)]
pub struct AveragedDop853<M> {
    model: M,
    core: Dop853<3, AveragedField<M>>,
}

/// `averaged2`.
pub type Averaged2Dop853 = AveragedDop853<Averaged2>;
/// `averaged3`.
pub type Averaged3Dop853 = AveragedDop853<Averaged3>;

impl<M: SlowModel> AveragedDop853<M> {
    /// Starts at the problem's initial values (mapped to averaged variables) with local
    /// tolerance `tol`.
    pub fn new(problem: &Problem, tol: f64) -> Self {
        let (model, y0) = M::start(problem);
        let field = AveragedField {
            model,
            momentum_unit: momentum_unit(problem, model.ibar()),
        };
        Self {
            model,
            core: Dop853::new(field, 0.0, y0, tol),
        }
    }
}

/// The natural size of `P̄`: it moves on the scale of `iz·α̇` and of the potential's force,
/// whichever is larger.
fn momentum_unit(problem: &Problem, ibar: f64) -> f64 {
    let p = problem.params();
    let potential_max = crate::physics::rattleback::averaged::potential_max(p, ibar);
    (p.iz * problem.start().alpha_dot.abs())
        .max((p.iz * potential_max).sqrt())
        .max(f64::MIN_POSITIVE)
}

impl<M: SlowModel> AveragedDop853<M> {
    /// The current state `(γ, α, γ̇, α̇)`.
    #[must_use]
    pub fn state(&self) -> State {
        self.model.to_full_state(&self.core.state())
    }
    /// The state at `t` inside the last step.
    pub fn interpolate(&mut self, t: f64) -> State {
        let y = self.core.interpolate(t);
        self.model.to_full_state(&y)
    }
}

impl<M: SlowModel> Flow for AveragedDop853<M> {
    crate::physics::flow::on_core!();
    fn method(&self) -> Method {
        M::METHOD
    }
    fn event_value(&self) -> f64 {
        self.model.spin_rate(&self.core.state())
    }
    fn locate_event(&mut self) -> f64 {
        // The full α̇ is monotone across a reversal (α̈ = g'γ̇²/(2iz) keeps the sign of g' near
        // a turning point), and so is its reconstruction: one bracketed zero per step.
        let (a, b) = (self.core.time_prev(), self.core.time());
        find_root(
            |t| {
                let y = self.core.interpolate(t);
                self.model.spin_rate(&y)
            },
            a,
            b,
        )
    }
    fn energy(&self) -> f64 {
        let y = self.core.state();
        self.model.kbar(y[0], y[1])
    }

    super::drawn_from_state!();
}

/// Where one of [`together`]'s starts ends: `α(T)`, `α̇(T)` (reconstructed) and its reversal
/// times.
#[derive(Clone, Debug, PartialEq)]
pub struct Ending {
    /// `α(T)`.
    pub alpha: f64,
    /// `α̇(T)`.
    pub alpha_dot: f64,
    /// The zeros of the reconstructed `α̇` in `(0, T]`.
    pub reversals: Vec<f64>,
}

impl Ending {
    /// How far apart two endings are in `α(T)` and `α̇(T)`.
    #[must_use]
    pub fn end_distance(&self, other: &Self) -> f64 {
        (self.alpha - other.alpha)
            .abs()
            .max((self.alpha_dot - other.alpha_dot).abs())
    }

    /// How far apart two endings are in `α(T)`, `α̇(T)` and the reversal times; infinite when
    /// they count different reversals (as `auto` compares two runs).
    #[must_use]
    pub fn distance(&self, other: &Self) -> f64 {
        if self.reversals.len() != other.reversals.len() {
            return f64::INFINITY;
        }
        self.reversals
            .iter()
            .zip(&other.reversals)
            .fold(self.end_distance(other), |d, (x, y)| d.max((x - y).abs()))
    }
}

/// The slow flows of three starts side by side, the first one's error alone controlling the
/// steps.
struct Three<M> {
    models: [M; 3],
    momentum_unit: f64,
}

impl<M: SlowModel> Field<9> for Three<M> {
    #[inline]
    fn eval(&self, y: &SVector<f64, 9>) -> SVector<f64, 9> {
        let mut f = SVector::<f64, 9>::zeros();
        // A model that takes them turns the start's sine and cosine through each copy's small
        // angle apart (`averaged::turned`): the start's flow is evaluated as its own run's is.
        let start = slow(y, 0);
        let turn = M::TURNS.then(|| (2.0 * start[0]).e_sin_cos());
        for (c, model) in self.models.iter().enumerate() {
            let here = slow(y, c);
            let d = match turn {
                Some(turn) => model.rhs_turned(&here, turned(turn, start[0], here[0])),
                None => model.rhs(&here),
            };
            f.fixed_rows_mut::<3>(3 * c).copy_from(&d);
        }
        f
    }
    fn unit(&self, i: usize) -> f64 {
        match i {
            1 => self.momentum_unit,
            0 | 2 => 1.0,
            // The copies follow the first start's steps: no error of theirs is controlled.
            _ => f64::INFINITY,
        }
    }
    fn is_angle(&self, i: usize) -> bool {
        i == 0 || i == 2
    }
    fn controlled(&self) -> usize {
        3
    }
}

/// Start `c`'s slow state in the side-by-side state.
fn slow(y: &SVector<f64, 9>, c: usize) -> SlowState {
    SlowState::new(y[3 * c], y[3 * c + 1], y[3 * c + 2])
}

/// Integrates three starts of one body on the slow model `M` together, every one with the
/// steps the first one's error asks for (DOP853 at local tolerance `tol`), and says where each
/// ends. Nudged copies of a start integrated so differ from it by the nudge carried through the
/// flow alone: their truncation errors are the same function of the same steps and cancel in
/// the difference, where separate adaptive runs take slightly different steps and leave their
/// truncation errors' difference in it (internal numerical differentiation, Bock 1981). `auto`
/// measures a start's condition numbers with it at a loose tolerance, in one run of three
/// times the field instead of three runs.
///
/// # Errors
/// A failed step, more steps than `cap`, [`StepError::Cancelled`] when `go_on` says stop
/// (asked every [`CHECK_EVERY`] steps).
///
/// # Panics
/// When `method` is not an averaged model (`averaged2`, `averaged3`).
pub fn together(
    method: Method,
    problems: &[Problem; 3],
    t_end: f64,
    tol: f64,
    cap: StepCap,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<[Ending; 3], StepError> {
    match method {
        Method::Averaged2 => together_on::<Averaged2>(problems, t_end, tol, cap, go_on),
        Method::Averaged3 => together_on::<Averaged3>(problems, t_end, tol, cap, go_on),
        other => panic!("{other} is not an averaged model"),
    }
}

fn together_on<M: SlowModel>(
    problems: &[Problem; 3],
    t_end: f64,
    tol: f64,
    cap: StepCap,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<[Ending; 3], StepError> {
    let mut y0 = SVector::<f64, 9>::zeros();
    let models = std::array::from_fn(|c| {
        let (model, start) = M::start(&problems[c]);
        y0.fixed_rows_mut::<3>(3 * c).copy_from(&start);
        model
    });
    let field = Three {
        momentum_unit: momentum_unit(&problems[0], models[0].ibar()),
        models,
    };
    let mut core = Dop853::new(field, 0.0, y0, tol);
    let spin = |core: &Dop853<9, Three<M>>, y: &SVector<f64, 9>, c: usize| {
        core.field().models[c].spin_rate(&slow(y, c))
    };
    let mut trackers: [EventTracker; 3] =
        std::array::from_fn(|c| EventTracker::new(spin(&core, &y0, c)));
    let mut reversals: [Vec<f64>; 3] = Default::default();
    let mut steps: u64 = 0;
    while core.time() < t_end {
        steps += 1;
        if steps.is_multiple_of(CHECK_EVERY) && !go_on(core.time()) {
            return Err(StepError::Cancelled { t: core.time() });
        }
        cap.check(steps, core.time())?;
        core.step(t_end)?;
        let y = core.state();
        for c in 0..3 {
            if trackers[c].after_value(spin(&core, &y, c), 0.0) {
                let (a, b) = (core.time_prev(), core.time());
                let model = core.field().models[c];
                let f = |t| {
                    let y = core.interpolate(t);
                    model.spin_rate(&slow(&y, c))
                };
                // A copy's reversal lies beside the start's same reversal, when that one fell
                // in this step.
                let t = match reversals[0].get(reversals[c].len()) {
                    Some(&beside) if c > 0 && beside > a => find_root_near(f, a, b, beside),
                    _ => find_root(f, a, b),
                };
                reversals[c].push(t);
            }
        }
    }
    let y = core.state();
    Ok(std::array::from_fn(|c| {
        let full = core.field().models[c].to_full_state(&slow(&y, c));
        Ending {
            alpha: full[1],
            alpha_dot: full[3],
            reversals: std::mem::take(&mut reversals[c]),
        }
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::method::RunSpec;
    use crate::physics::rattleback::params::{Params, Start};
    use crate::physics::rattleback::run::run;

    fn subcritical(k: f64, alpha_dot: f64) -> Problem {
        Problem::new(
            Params {
                ix: 2.0,
                iy: 1.0,
                iz: 1.0,
                k,
            },
            Start {
                gamma: 0.0,
                alpha: 0.0,
                gamma_dot: 1.0,
                alpha_dot,
            },
        )
        .unwrap()
    }

    /// Three equal starts end on the same bits: each copy is stepped with the first one's
    /// steps, by its own model. Their reversal times agree to the root finder's bracket of a
    /// few ulps (a copy's is searched beside the start's, [`find_root_near`]).
    #[test]
    #[allow(clippy::float_cmp)]
    fn equal_starts_end_equal() {
        let p = subcritical(1e4, 0.5);
        let ends = together(
            Method::Averaged2,
            &[p, p, p],
            30.0,
            1e-7,
            StepCap::NONE,
            &mut |_| true,
        )
        .unwrap();
        for copy in &ends[1..] {
            assert_eq!(
                (copy.alpha, copy.alpha_dot),
                (ends[0].alpha, ends[0].alpha_dot)
            );
            assert_eq!(copy.reversals.len(), 7);
            for (a, b) in copy.reversals.iter().zip(&ends[0].reversals) {
                assert!((a - b).abs() <= 4.0 * f64::EPSILON * a, "{a} against {b}");
            }
        }
    }

    /// A nudged copy carried on the start's steps at a loose tolerance moves as separate runs
    /// at a tight one say: the sensitivity of `α(T)`, `α̇(T)` and the reversal times to the spin
    /// rate, trapped and rotating, within 1 %.
    #[test]
    fn a_nudged_copy_moves_as_separate_tight_runs_say() {
        for alpha_dot in [0.5, 1.2] {
            let p = subcritical(1e4, alpha_dot);
            let q = subcritical(1e4, alpha_dot * (1.0 + 1e-8));
            let ends = together(
                Method::Averaged2,
                &[p, q, p],
                30.0,
                1e-7,
                StepCap::NONE,
                &mut |_| true,
            )
            .unwrap();
            let spec = RunSpec {
                method: Method::Averaged2,
                tolerance: 1e-12,
                step: None,
                t_end: 30.0,
                samples: 0,
                monitor_energy: false,
            };
            let ending = |p: &Problem| {
                let r = run(p, &spec).unwrap();
                Ending {
                    alpha: r.final_state[1],
                    alpha_dot: r.final_state[3],
                    reversals: r.reversals,
                }
            };
            let side_by_side = ends[0].distance(&ends[1]);
            let separate = ending(&p).distance(&ending(&q));
            assert!(
                (side_by_side / separate - 1.0).abs() < 0.01,
                "α̇0 = {alpha_dot}: {side_by_side:e} side by side, {separate:e} separately"
            );
        }
    }
}
