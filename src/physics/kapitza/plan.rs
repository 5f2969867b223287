//! `auto` for the pendulum: the slow models (the limit with its ripple, `averaged2`,
//! `averaged3`), each checked a posteriori, the cheapest whose estimate meets the tolerance;
//! else the full model resolved by `taylor` and verified; when nothing meets the tolerance, the
//! one with the smaller estimate, `met = false` (`simulate` reports both, the explorer's status
//! bar shows `✗ tol missed`). Every estimate is measured (issue 27, item 3): over the reference
//! starts, ε = 1e-1 … 1e-9, a median 4× the error (`tests/it/kapitza.rs`,
//! `estimates_lie_within_ten_times_the_errors`).
//!
//! - **The slow models** ([`averaged_checked`]). Where `ε s` ≤ [`THIRD_ORDER_MAX_EPS_S`]
//!   (`s = b² + |a| + 1`) each one's model error is its distance from the next order, widened
//!   by [`NEXT_ORDER_MARGIN`] (the next order errs by at most 3.3 % of that distance there): the
//!   limit with its ripple against `averaged2` (only where its a-priori error [`model_error`],
//!   measured 0.03–0.24 of the truth, is within [`LIMIT_WORTH_TRYING`] tolerances), `averaged2`
//!   against `averaged3`, and `averaged3` by its gap to `averaged2` times `(ε s)²` and
//!   [`THIRD_ORDER_MARGIN`]. Beyond, `averaged2` alone, by `2 D (ε s)²` with `D` its distance
//!   from the limit with its ripple ([`SECOND_ORDER_MARGIN`]: the measured error over
//!   `D (ε s)²` is at most 0.72 on the reference and held-out starts). Each estimate adds the
//!   run's distance from a companion `SLOW.companion_looser` times looser (integration) and
//!   the fast phase's rounding. The runs are of the slow motion, 10–20 µs each; distances are
//!   the largest over 33 samples of `(θ, θ̇)` and the end. Where the model error is within half
//!   the tolerance and the integration is not (a long horizon), the best is run once more at
//!   the tightest tolerance.
//! - **The resolved run** is the full model by its Taylor series (`taylor`, [`RESOLVED`]; DOP853
//!   until issue 27): DOP853 costs 2.3–3.1× as much at equal error. Its tolerance is per step
//!   and the global error grows with the number of fast periods `n` (measured on DOP853: 90× the
//!   tolerance after 80 periods of an unstable start, an error that growing motions amplify),
//!   so it is first asked for
//!   `tol / (100 sqrt(1 + n))`. Rounding sets a floor that no tolerance lowers: measured 1.2e-9
//!   after 8 000 periods and 1.2e-8 after 80 000 (`rattleback bench --only kapitza`) on a
//!   stable start, 5.5e-9 after 8 000 on an unstable one. The series rounds less: predicted
//!   `24 ε_mach n^1.5` ([`ROUNDING_GAIN`], stop 51; `1e-12 n` before). Where there is
//!   no separation of scales (`ε s` > 0.1 and `averaged2` predicted [`HOPELESS`] tolerances
//!   off) and a resolved run can meet the tolerance, it runs first and the slow models are
//!   checked only if it misses.
//!
//! - **The fast phase `t/ε`**: the full model's right-hand side rounds it in double; its error,
//!   up to `ε_mach t/ε`, moves the forcing and so `θ̇` by up to `b ε_mach t/ε`, and a resolved
//!   run's floor includes it (at ε = 1e-6, T = 5 it is 2e-9). The lifts of the slow models carry
//!   it exactly ([`super::FastPhase::Exact`], issue 27): what is left is a few ulps of the
//!   harmonics, [`lift_phase_rounding`]. Up to issue 27 the lifts rounded it too, which set a
//!   floor of `b ε_mach t/ε` under every estimate below ε = 1e-6 (2.2e-6 at ε = 1e-9).
//!
//! **A resolved run is verified** ([`verified`], issue 29): the a-priori tolerance is a guess
//! that long runs near the unstable upright beat (6.5× over at 1e-8 on a falling start that
//! keeps returning to the top, T = 50). The run is compared with a companion
//! `POLICY.companion_looser` times looser on 33 samples of `(θ, θ̇)` and the final state; their
//! difference plus the rounding floors is the estimate, widened by [`NOISE_MARGIN`] where the
//! last refinement lowered it much less than the tolerance ([`MIN_CONVERGENCE`]: rounding, not
//! truncation, then sets both runs' errors). Above the tolerance the local tolerance
//! shrinks by the factor the estimate asks for (at least 4×) until it is met, stops falling,
//! reaches 1e-14, or the budget would be passed; then `met = false` with the estimate.
//!
//! The full model's cost grows like `1/ε` and the slow models' does not: as `ε` shrinks `auto`
//! switches to them and its cost stops growing. Whatever misses, the smaller estimate is
//! returned with `met = false`: the slow model's at once where a resolved run's rounding floor
//! is above it or its predicted cost over the budget (`kapitza-just-below` takes `averaged3`,
//! 2e-11 off the long-double reference, where the resolved run ended 2e-7 off with `met =
//! false`).
use crate::physics::numerics::elementary::Elementary;

use super::policy::{POLICY, SLOW};
use super::run::{RunResult, run};
use super::{Problem, Start};
use crate::physics::fork::GoOn;
use crate::physics::method::Asked;
use crate::physics::method::RunSpec;
use crate::physics::method::{Method, Settings, StepError};
use crate::physics::plan::Shortfall;
use crate::physics::verify::{AtTolerance, Candidate, Policy, Round, Rounds, verify};

/// What `auto` chose, and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The concrete method.
    pub method: Method,
    /// Its settings.
    pub settings: Settings,
    /// The model part of `estimate`: a slow model's measured model error ([`averaged_checked`]),
    /// or the limit's predicted one ([`model_error`]) for a resolved run and the a-priori plan.
    pub predicted_model_error: f64,
    /// The error the chosen run is expected to stay within (its target, or its floor).
    pub estimate: f64,
    /// Whether `estimate` meets the tolerance.
    pub met: bool,
    /// Why it does not, when it does not.
    pub shortfall: Option<Shortfall>,
}

/// The method of a resolved run: the Taylor series ([`super::taylor`]); DOP853 costs 2.3–3.1× as
/// much at equal error (issue 27).
pub const RESOLVED: Method = Method::Taylor;

/// Gain of the rounding floor of a resolved run, `ROUNDING_GAIN · ε_mach · n^1.5` over `n` fast
/// periods (a random walk of the energy's rounding, `√n`, moving the phase of a motion whose
/// period depends on its energy, `n`). On the references the Taylor series, where truncation no
/// longer sets its error, ends at most 10.4 `ε_mach n^1.5` off (26 runs, n = 8 … 8 000:
/// `tests/it/kapitza.rs`, `the_rounding_floor_bounds_the_series_at_its_tightest`): 24 keeps a
/// margin of 2.3. (With the platform's sine and cosine, glibc's, the gain was 5.8 and the floor
/// 20: the portable functions, the same in the browser, round up to 1 ulp where glibc's round
/// to nearest, issue 82.) It replaced
/// `1e-12 n` (stop 51), measured on DOP853 at 8 000 periods and 25–300× above the series'
/// rounding at 8 … 800 periods, where it set most of the estimates of tight tolerances. A start
/// that keeps returning near the unstable upright amplifies its rounding beyond any such law
/// (`returns_eps1e-2`: 7e-9 after 800 periods); there the companion's difference carries it,
/// since the two runs round independently, and [`NOISE_MARGIN`] widens it where it shows.
pub const ROUNDING_GAIN: f64 = 24.0;

/// The scale of the expansion's terms: `b² + |a| + 1` (the small parameter is `ε` times it).
fn scale(problem: &Problem) -> f64 {
    let p = problem.params();
    p.b * p.b + p.a.abs() + 1.0
}

/// The expansion's small parameter `ε s`.
fn small_parameter(problem: &Problem) -> f64 {
    problem.params().epsilon * scale(problem)
}

/// Whether the scales separate enough for each slow model's error to be measured by its
/// distance from the next order (`ε s` ≤ [`THIRD_ORDER_MAX_EPS_S`]).
fn separated(problem: &Problem) -> bool {
    small_parameter(problem) <= THIRD_ORDER_MAX_EPS_S
}

/// The limit's predicted model error (see the module's documentation).
#[must_use]
pub fn model_error(problem: &Problem, t_end: f64) -> f64 {
    small_parameter(problem).powi(2) * (1.0 + t_end)
}

/// The second-order averaged model's (`averaged2`) predicted model error: O(ε⁴), with the
/// limit's scale and growth, `0.5 (ε (b² + |a| + 1))⁴ (1 + t_end)`. Against the Taylor-series
/// references (ε = 1e-2 … 1e-6) the measured error is at most 0.35 of it (the falling start at
/// ε = 1e-3, in θ̇), and mostly far less (`tests/it/kapitza.rs`); a start that keeps returning
/// to the unstable upright beats it, so `auto` chooses by the a-posteriori check and uses this
/// only to predict its cost ([`averaged_expected`]).
#[must_use]
pub fn model_error2(problem: &Problem, t_end: f64) -> f64 {
    0.5 * small_parameter(problem).powi(4) * (1.0 + t_end)
}

/// Fast periods over `[0, t_end]`.
fn periods(problem: &Problem, t_end: f64) -> f64 {
    t_end / (2.0 * std::f64::consts::PI * problem.params().epsilon)
}

/// The full model's error from the rounding of the fast phase `t/ε` in its right-hand side
/// (see the module's documentation).
#[must_use]
pub fn phase_rounding(problem: &Problem, t_end: f64) -> f64 {
    let p = problem.params();
    p.b.abs() * f64::EPSILON * t_end / p.epsilon
}

/// What the fast phase leaves in a lift of a slow model: its harmonics, exact to a few ulps
/// ([`super::FastPhase::Exact`]), times the ripple's size `b`, whatever `t/ε`.
#[must_use]
pub fn lift_phase_rounding(problem: &Problem) -> f64 {
    8.0 * problem.params().b.abs() * f64::EPSILON
}

/// What rounding alone leaves in a resolved run: per fast period, and the fast phase's.
#[must_use]
pub fn rounding_floor(problem: &Problem, t_end: f64) -> f64 {
    ROUNDING_GAIN * f64::EPSILON * periods(problem, t_end).e_powf(1.5)
        + phase_rounding(problem, t_end)
}

/// Resolves `auto` for `problem` at `tolerance` over `[0, t_end]`, a priori (no run): the limit
/// with its ripple where its predicted model error and integration allowance (100× its local
/// tolerance) meet the tolerance, else the full model resolved by [`RESOLVED`]. What the cost model
/// assumes; [`verified`] measures instead.
#[must_use]
pub fn resolve(problem: &Problem, tolerance: f64, t_end: f64) -> Choice {
    let model = model_error(problem, t_end);
    let phase = lift_phase_rounding(problem);
    let floor = rounding_floor(problem, t_end);
    // The limit integrated at 1e-4 of the tolerance: its global error stays below 1e-2 of it
    // (at most 100× DOP853's per-step tolerance, which growing motions reach).
    let limit_tolerance = (tolerance * 1e-4).max(1e-14);
    let limit_estimate = model + 100.0 * limit_tolerance + phase;
    let limit = |met| Choice {
        method: Method::EffectiveCorrected,
        settings: Settings {
            tolerance: limit_tolerance,
            step: None,
        },
        predicted_model_error: model,
        estimate: limit_estimate,
        met,
        shortfall: (!met).then_some(Shortfall::Model),
    };
    if limit_estimate <= tolerance {
        return limit(true);
    }
    if floor > tolerance && limit_estimate < floor {
        return limit(false);
    }
    resolved(problem, tolerance, t_end)
}

/// The full model resolved by [`RESOLVED`], a priori: its first local tolerance (see the module's
/// documentation) and, as its estimate, the tolerance or the rounding floor.
fn resolved(problem: &Problem, tolerance: f64, t_end: f64) -> Choice {
    let model = model_error(problem, t_end);
    let n = periods(problem, t_end);
    let floor = rounding_floor(problem, t_end);
    Choice {
        method: RESOLVED,
        settings: Settings {
            tolerance: (tolerance / (100.0 * (1.0 + n).sqrt())).max(1e-14),
            step: None,
        },
        predicted_model_error: model,
        estimate: tolerance.max(floor),
        met: floor <= tolerance,
        shortfall: (floor > tolerance).then_some(Shortfall::Floor),
    }
}

/// Whether `averaged2` is expected, a priori, to pass [`averaged_checked`] where the limit does
/// not: its predicted model error [`model_error2`] and the integration and rounding allowances
/// within the tolerance. Only the cost model uses it (what `auto` will likely run); the choice
/// is the a-posteriori check's.
#[must_use]
pub fn averaged_expected(problem: &Problem, tolerance: f64, t_end: f64) -> bool {
    let local = (tolerance * 1e-4).max(POLICY.tightest);
    model_error2(problem, t_end) + 100.0 * local + lift_phase_rounding(problem) <= tolerance
}

/// How much the model part of `averaged2`'s estimate widens `D (ε s)²` (see the module's
/// documentation: measured at most 0.72 of it).
pub const SECOND_ORDER_MARGIN: f64 = 2.0;

/// How much the model part of `averaged3`'s estimate widens `|averaged3 − averaged2| (ε s)²`:
/// over the Taylor-series references where `ε s ≤` [`THIRD_ORDER_MAX_EPS_S`] and the error
/// stands above the integration floor (ε = 1e-2), the ratio of the measured error to that is
/// 0.12–3.3 (`tests/it/kapitza.rs`, `the_third_order_averaged_model_is_sixth_order`).
pub const THIRD_ORDER_MARGIN: f64 = 8.0;
/// Largest `ε s` (`s = b² + |a| + 1`) where `averaged3` is considered: beyond, the expansion's
/// terms shrink too slowly for its gap to `averaged2` to measure its error (at ε s = 0.6 the
/// ratio above reaches 8.7).
pub const THIRD_ORDER_MAX_EPS_S: f64 = 0.1;

/// How much the distance of a slow model from the next order's widens into its model error,
/// where `ε s` ≤ [`THIRD_ORDER_MAX_EPS_S`]: the next order errs by at most `3.3 (ε s)²` of that
/// distance there (0.033 of it; measured, see [`THIRD_ORDER_MARGIN`]), so the distance is the
/// error within 3.3 %, and this margin covers the rest.
pub const NEXT_ORDER_MARGIN: f64 = 2.0;
/// The limit with its ripple is checked only where its a-priori model error
/// ([`model_error`], measured 0.03–0.24 of the truth) is within this many tolerances: beyond,
/// its check could not pass and would only add runs.
pub const LIMIT_WORTH_TRYING: f64 = 30.0;

/// The slow models checked a posteriori (see the module's documentation), cheapest first; the
/// first whose estimate meets `tolerance` is the choice. Where `ε s` ≤
/// [`THIRD_ORDER_MAX_EPS_S`] each model's error is measured by its distance from the next
/// order ([`NEXT_ORDER_MARGIN`]): the limit with its ripple against `averaged2` (where its
/// a-priori error is within [`LIMIT_WORTH_TRYING`] tolerances), `averaged2` against
/// `averaged3`, and `averaged3` by its gap to `averaged2` times `(ε s)²` (the ratio of their
/// orders, [`THIRD_ORDER_MARGIN`]). Beyond, `averaged2` alone, by its distance from the limit
/// times `(ε s)²` ([`SECOND_ORDER_MARGIN`]). Each estimate adds the run's distance from its
/// companion, `SLOW.companion_looser` times looser (integration), and the lift's rounding. When
/// none meets the tolerance, the one with the smallest estimate, `met = false` (what
/// [`verified`] returns when a resolved run cannot do better).
///
/// # Errors
/// A failed or cancelled run.
pub fn averaged_checked(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Choice, StepError> {
    let local = (tolerance * 1e-4).max(POLICY.tightest);
    let separated = separated(problem);
    let first = if separated && model_error(problem, t_end) <= LIMIT_WORTH_TRYING * tolerance {
        Slow::Limit
    } else {
        Slow::Second
    };
    let mut ladder = Ladder {
        problem,
        t_end,
        local,
        separated,
        es2: small_parameter(problem).powi(2),
        rounding: lift_phase_rounding(problem),
        runs: Vec::new(),
        read: Vec::new(),
    };
    let v = verify(&mut ladder, Rounds::unbudgeted(first, tolerance), go_on)?;
    let best = v.best.0;
    let (method, local, model) = ladder.model_of(best.plan);
    Ok(slow_choice(method, local, model, best.estimate, tolerance))
}

/// A slow model's place on the ladder the check climbs (`SLOW.max_refinements` rounds after
/// the first): the limit with its ripple, `averaged2`, `averaged3`, and the best of them once
/// more at the tightest tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Slow {
    /// The limit with its ripple, its model error from `averaged2`.
    Limit,
    /// `averaged2`, from `averaged3` (separated scales) or the limit.
    Second,
    /// `averaged3`, from its gap to `averaged2`.
    Third,
    /// This model once more at the tightest tolerance, its model error as measured before.
    Tight(Method),
}

/// The slow models' check as a candidate of the one loop ([`verify`]): each round runs a model
/// and its companion `SLOW.companion_looser` times looser (the runs kept: a model's next order
/// is the next round's model); a round's estimate is its model error, the integration's
/// distance and the lift's rounding. The loop keeps the best reading; this candidate says
/// which round comes next.
struct Ladder<'a> {
    problem: &'a Problem,
    t_end: f64,
    /// The local tolerance of every round but the tightening one.
    local: f64,
    separated: bool,
    /// `(ε s)²`.
    es2: f64,
    rounding: f64,
    runs: Vec<((Method, u64), RunResult)>,
    /// Each round read: the plan, its model error and its estimate.
    read: Vec<(Slow, f64, f64)>,
}

impl Ladder<'_> {
    /// `method` at `local`, run once (a later round asks for it again).
    fn run(
        &mut self,
        method: Method,
        local: f64,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<usize, StepError> {
        let key = (method, local.to_bits());
        if let Some(i) = self.runs.iter().position(|(k, _)| *k == key) {
            return Ok(i);
        }
        let spec = RunSpec::new(Asked::new(method, local, None, self.t_end), SAMPLES);
        let r = run(self.problem, &spec, go_on)?;
        self.runs.push((key, r));
        Ok(self.runs.len() - 1)
    }

    /// The distance of `method` at `local` from `other` at `other_local`.
    fn distance(
        &mut self,
        (method, local): (Method, f64),
        (other, other_local): (Method, f64),
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<f64, StepError> {
        let a = self.run(method, local, go_on)?;
        let b = self.run(other, other_local, go_on)?;
        Ok(difference(&self.runs[a].1, &self.runs[b].1))
    }

    /// The method, local tolerance and model error of a plan already read.
    fn model_of(&self, plan: Slow) -> (Method, f64, f64) {
        let model = self
            .read
            .iter()
            .find(|(p, _, _)| *p == plan)
            .map_or(f64::INFINITY, |r| r.1);
        match plan {
            Slow::Limit => (Method::EffectiveCorrected, self.local, model),
            Slow::Second => (Method::Averaged2, self.local, model),
            Slow::Third => (Method::Averaged3, self.local, model),
            Slow::Tight(method) => (method, POLICY.tightest, model),
        }
    }

    /// The best reading so far (the earlier of two equal ones, as the loop keeps it).
    fn best(&self) -> Option<(Slow, f64, f64)> {
        self.read
            .iter()
            .copied()
            .reduce(|a, b| if b.2 < a.2 { b } else { a })
    }
}

impl Candidate for Ladder<'_> {
    type Plan = Slow;
    type Run = ();

    fn policy(&self) -> &'static Policy {
        &SLOW
    }

    fn round(
        &mut self,
        plan: &Slow,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Round<()>, StepError> {
        let local = self.local;
        let companion = SLOW.companion(local);
        let (limit, second, third) = (
            Method::EffectiveCorrected,
            Method::Averaged2,
            Method::Averaged3,
        );
        let (model, integration) = match *plan {
            Slow::Limit => (
                NEXT_ORDER_MARGIN * self.distance((second, local), (limit, local), go_on)?,
                self.distance((limit, local), (limit, companion), go_on)?,
            ),
            Slow::Second if self.separated => (
                NEXT_ORDER_MARGIN * self.distance((third, local), (second, local), go_on)?,
                self.distance((second, local), (second, companion), go_on)?,
            ),
            Slow::Second => (
                SECOND_ORDER_MARGIN
                    * self.distance((second, local), (limit, local), go_on)?
                    * self.es2,
                self.distance((second, local), (second, companion), go_on)?,
            ),
            Slow::Third => (
                THIRD_ORDER_MARGIN
                    * self.distance((third, local), (second, local), go_on)?
                    * self.es2,
                self.distance((third, local), (third, companion), go_on)?,
            ),
            Slow::Tight(method) => {
                // The best's model error, measured in its own round.
                let (tight, model) = (POLICY.tightest, self.best().map_or(f64::INFINITY, |b| b.1));
                (
                    model,
                    self.distance((method, tight), (method, SLOW.companion(tight)), go_on)?,
                )
            }
        };
        let measured = model + integration + self.rounding;
        self.read.push((*plan, model, measured));
        Ok(Round {
            run: (),
            measured,
            floor: self.rounding,
        })
    }

    fn cost(&self, plan: &Slow) -> f64 {
        let (method, local, _) = self.model_of(*plan);
        let price = |tol: f64| {
            super::budget::cost_seconds(self.problem, &Asked::new(method, tol, None, self.t_end))
        };
        price(local) + price(SLOW.companion(local))
    }

    fn refine(&mut self, plan: &Slow, _: f64, tolerance: f64) -> Result<Slow, Shortfall> {
        let next = match *plan {
            Slow::Limit => Some(Slow::Second),
            Slow::Second if self.separated => Some(Slow::Third),
            Slow::Second | Slow::Third => None,
            Slow::Tight(_) => return Err(Shortfall::Refinements),
        };
        if let Some(next) = next {
            return Ok(next);
        }
        // The model is within the tolerance and the integration is not (a long horizon): the
        // best once more at the tightest tolerance.
        let (best, model, _) = self.best().ok_or(Shortfall::Refinements)?;
        if self.local <= POLICY.tightest || model > 0.5 * tolerance {
            return Err(Shortfall::Model);
        }
        Ok(Slow::Tight(self.model_of(best).0))
    }

    /// Each round a model of its own: no stall between them.
    fn continues(&self, _: &Slow, _: &Slow) -> bool {
        false
    }
}

/// The slow model `method` at `local` with its model error and estimate: met, or short by its
/// model error, or by the slow run's integration at the tightest tolerance.
fn slow_choice(method: Method, local: f64, model: f64, estimate: f64, tolerance: f64) -> Choice {
    Choice {
        method,
        settings: Settings {
            tolerance: local,
            step: None,
        },
        predicted_model_error: model,
        estimate,
        met: estimate <= tolerance,
        shortfall: (estimate > tolerance).then_some(
            if model > 0.5 * tolerance || local > POLICY.tightest {
                Shortfall::Model
            } else {
                Shortfall::Clamped
            },
        ),
    }
}

/// `|averaged3 − averaged2|` over `[0, t_end]`, both at the tightest tolerance: what
/// [`averaged_checked`] scales into `averaged3`'s model error (for its calibration).
///
/// # Errors
/// A failed run.
pub fn averaged3_gap(problem: &Problem, t_end: f64) -> Result<f64, StepError> {
    let spec = |method| RunSpec::new(Asked::new(method, POLICY.tightest, None, t_end), SAMPLES);
    let third = run(problem, &spec(Method::Averaged3), &mut |_| true)?;
    let second = run(problem, &spec(Method::Averaged2), &mut |_| true)?;
    Ok(difference(&third, &second))
}

/// How far off, in tolerances, `averaged2`'s a-priori model error ([`model_error2`]) must be,
/// where `ε s` > [`THIRD_ORDER_MAX_EPS_S`], for [`verified`] to try a resolved run before the
/// slow models (their check would only add runs).
pub const HOPELESS: f64 = 1e3;
/// How much a declined run's estimate is widened, and a met one's where rounding shows
/// ([`MIN_CONVERGENCE`]; see [`verified`]).
pub const NOISE_MARGIN: f64 = 3.0;
/// The least slope, in log-log, of a resolved run's estimate against its local tolerance over a
/// refinement for the estimate to be read as truncation: DOP853 and the Taylor series show
/// 0.8–1.1 where truncation sets the error, 0.5–0.65 where rounding does.
pub const MIN_CONVERGENCE: f64 = 0.75;
/// Samples of `(θ, θ̇)` compared.
const SAMPLES: usize = 33;

/// Predicted seconds of a run of `method` over `[0, t_end]`, `auto` as it would likely resolve:
/// the limit with its ripple (its check: it, its companion and `averaged2`; then the run),
/// `averaged2` where that is expected to pass its check (up to five runs of the slow motion,
/// then the run), or the a-priori resolved plan (it, its companion, then the run).
#[must_use]
pub fn predicted_seconds(problem: &Problem, ask: &Asked) -> f64 {
    if ask.method != Method::Auto {
        return super::budget::cost_seconds(problem, ask);
    }
    let (tolerance, t_end) = (ask.tolerance, ask.t_end);
    let c = resolve(problem, tolerance, t_end);
    let (method, tolerance, runs) = if c.method != RESOLVED {
        (c.method, c.settings.tolerance, 4.0)
    } else if averaged_expected(problem, tolerance, t_end) {
        (Method::Averaged2, (tolerance * 1e-4).max(1e-14), 6.0)
    } else {
        // The resolved run, its companion and the run again.
        (c.method, c.settings.tolerance, 3.0)
    };
    runs * super::budget::cost_seconds(problem, &Asked::new(method, tolerance, ask.step, t_end))
}

/// The difference of two runs over their samples and final states.
/// [`difference`] of `a` and `b`, a run started a turn further (`θ0 + 2π`): its angles a turn
/// back.
fn difference_turned(a: &RunResult, b: &RunResult) -> f64 {
    let tau = std::f64::consts::TAU;
    let mut d = (a.theta - (b.theta - tau))
        .abs()
        .max((a.theta_dot - b.theta_dot).abs());
    for (x, y) in a.samples.iter().zip(&b.samples) {
        d = d
            .max((x.theta - (y.theta - tau)).abs())
            .max((x.theta_dot - y.theta_dot).abs());
    }
    d
}

fn difference(a: &RunResult, b: &RunResult) -> f64 {
    let mut d = (a.theta - b.theta)
        .abs()
        .max((a.theta_dot - b.theta_dot).abs());
    for (x, y) in a.samples.iter().zip(&b.samples) {
        d = d
            .max((x.theta - y.theta).abs())
            .max((x.theta_dot - y.theta_dot).abs());
    }
    d
}

/// Resolves `auto` and verifies a resolved run (see the module's documentation): the choice
/// with the local tolerance that met the tolerance, or the last tried with `met = false`. The
/// probes stop before passing `budget` seconds (by the cost model).
///
/// # Errors
/// A failed or cancelled run.
pub fn verified(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Choice, StepError> {
    verified_choice(problem, tolerance, t_end, budget, go_on).map(widen_declined)
}

/// A declined choice's estimate, widened as a declined resolved run's is ([`NOISE_MARGIN`]): a
/// slow model's model part comes from a law whose margin was measured on runs that met it, and
/// a long run near the threshold exceeded it (issue 80: `averaged3` over T = 83 with `b²` just
/// under `2a` erred 9.6× its gap to `averaged2` times `(ε s)²`, the law's margin being 8). No
/// decision changes: only what a decline says of its error.
fn widen_declined(c: Choice) -> Choice {
    if c.met || c.method == RESOLVED {
        return c;
    }
    Choice {
        estimate: NOISE_MARGIN * c.estimate,
        ..c
    }
}

/// [`verified`], a declined slow model's estimate as measured.
fn verified_choice(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Choice, StepError> {
    let first = resolved(problem, tolerance, t_end);
    let floor = rounding_floor(problem, t_end);
    // The slow models first, unless they cannot come near the tolerance (no separation of
    // scales: `ε s` > THIRD_ORDER_MAX_EPS_S and `averaged2` predicted HOPELESS tolerances off)
    // while a resolved run can; then they are checked only if that run misses.
    let hopeless = !separated(problem)
        && model_error2(problem, t_end) > HOPELESS * tolerance
        && floor <= tolerance;
    let mut averaged = None;
    if !hopeless {
        let a = averaged_checked(problem, tolerance, t_end, go_on)?;
        if a.met {
            return Ok(a);
        }
        if floor >= a.estimate {
            // No resolved run can come closer than its rounding floor: the averaged model's
            // shortfall is the better answer, at once.
            return Ok(a);
        }
        averaged = Some(a);
    }
    let mut candidate = Resolved {
        problem: *problem,
        t_end,
        floor,
    };
    let at = |local: f64, estimate: f64, shortfall: Option<Shortfall>| Choice {
        settings: Settings {
            tolerance: local,
            step: None,
        },
        estimate,
        met: shortfall.is_none(),
        shortfall,
        ..first
    };
    let local = first.settings.tolerance;
    // The cost model may have expected `averaged2` (`averaged_expected`): the resolved run it
    // did not count is refused here rather than run past the budget.
    let first_cost = candidate.cost(&local);
    if let Err(over) = crate::physics::budget::check(first_cost, budget) {
        // Refused, unless the averaged model's shortfall is an answer to give instead.
        let a = slow_fallback(&mut averaged, problem, tolerance, t_end, go_on)?;
        if a.estimate.is_finite() {
            return Ok(a);
        }
        return Err(StepError::OverBudget {
            what: "auto's resolved run (the averaged models cannot meet the tolerance)".to_owned(),
            over,
        });
    }
    let v = verify(
        &mut candidate,
        Rounds {
            first: local,
            tolerance,
            budget,
        },
        go_on,
    )?;
    let (local, measured) = (v.last.plan, v.last.measured);
    Ok(match v.shortfall {
        None => at(local, v.last.estimate, None),
        Some(Shortfall::Time) => {
            let a = slow_fallback(&mut averaged, problem, tolerance, t_end, go_on)?;
            closer(at(local, measured, Some(Shortfall::Time)), a)
        }
        // Declined: rounding, stalled, clamped or out of refinements. Near the rounding floor
        // the two runs' difference under-reads either's error (an unstable motion amplifies
        // round-off in both; measured up to 2.2× on the held-out starts), so the estimate given
        // is NOISE_MARGIN times the larger of the last two.
        Some(why) => {
            let worst = v.before.map_or(measured, |(_, e)| e.max(measured));
            let a = slow_fallback(&mut averaged, problem, tolerance, t_end, go_on)?;
            closer(at(local, NOISE_MARGIN * worst, Some(why)), a)
        }
    })
}

/// The pendulum's resolved candidate: the full model by [`RESOLVED`] and its companion, side by
/// side where there are two cores; their difference plus the rounding floor, widened where the
/// last refinement showed rounding rather than truncation.
#[derive(Clone, Copy)]
struct Resolved {
    problem: Problem,
    t_end: f64,
    floor: f64,
}

/// How far above the modelled rounding floor a local tolerance may be and still be twinned:
/// the floor's law ([`ROUNDING_GAIN`]) was off by up to 5× on the held-out random starts
/// (`tests/fixtures/reference/kapitza_random.toml`), and a local tolerance is 100× or more below
/// the error it buys. 1e5 and 1e7 gave the same estimates on every held-out set (0 below the
/// error, 2 of 123 random runs declined needlessly); 1e7 is the wider net, at the price of a
/// third run on most resolved runs.
const TWIN_REACH: f64 = 1e7;

/// The twin's relative nudge of `θ0`: large against rounding (so the twin measures the flow,
/// not a lockstep of roundings), small against the motion (so the flow is linear about it).
const TWIN_NUDGE: f64 = 1e-8;

/// The gain of the measured rounding bound `TWIN_GAIN · A · ε_mach · size · steps` (see
/// `Resolved::rounding`): calibrated on the held-out random starts
/// (`tests/fixtures/reference/kapitza_random.toml`, 41 starts at 1e-10, 1e-9 and 1e-8, in
/// `tests/it/honesty.rs`): with 0.5 no estimate is below its error (the largest error over
/// estimate 0.78) and 2 of 123 runs decline with an error under a tenth of the tolerance; with 1,
/// 7 of 123; a random-walk law (`√steps`) needed a gain of 20 and declined as often.
const TWIN_GAIN: f64 = 0.5;

/// How much the rounding measured by the run a turn further ([`difference_turned`]) is widened:
/// the two runs' roundings are independent draws, and their difference under-reads either's by
/// chance.
const SHIFT_MARGIN: f64 = 4.0;

impl Resolved {
    /// Whether a run at `local` may round more than its floor says.
    fn twinned(&self, local: f64) -> bool {
        local < TWIN_REACH * self.floor
    }
}

impl AtTolerance for Resolved {
    type Result = RunResult;
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn run(&self, tolerance: f64, go_on: GoOn<'_>) -> Result<RunResult, StepError> {
        let spec = RunSpec::new(Asked::new(RESOLVED, tolerance, None, self.t_end), SAMPLES);
        run(&self.problem, &spec, go_on)
    }
    fn difference(&self, fine: &RunResult, coarse: &RunResult) -> f64 {
        difference(fine, coarse)
    }
    fn floor(&self, _: &RunResult) -> f64 {
        self.floor
    }
    // Where the twin measured the run's rounding, that bound stands in for the floor's law
    // (`ROUNDING_GAIN ε_mach n^1.5`, a worst case: an unstable start's), and the fast phase's
    // rounding is added (issue 80: over long horizons the law alone set the estimates of tight
    // tolerances 8–3,000× above the errors, and `auto` declined runs that met them).
    fn floors(&self, _: &RunResult, measured: Option<f64>) -> f64 {
        measured.map_or(self.floor, |m| {
            m + phase_rounding(&self.problem, self.t_end)
        })
    }
    fn run_cost(&self, local: f64) -> f64 {
        super::budget::cost_seconds(
            &self.problem,
            &Asked::new(RESOLVED, local, None, self.t_end),
        )
    }
    // Rounding measured (issue 66): a start that passes near the unstable upright amplifies its
    // roundings beyond the floor's law (at 1e-10 an estimate of 9.9e-11 for an error of
    // 1.58e-10, rounding over 2,500 steps). The twin is the same run from a start moved by
    // TWIN_NUDGE (relative): their difference over the nudge is the flow's amplification A of an
    // error made at the start (a start one ulp away stays in lockstep with the run, so it
    // measures nothing). Each step rounds the state at its size s (ε_mach s), and that grows at
    // most A-fold by the end; over n steps, TWIN_GAIN · A · ε_mach · s · n bounds what they leave
    // (added up, not as a random walk: measured, rounding in these runs does not cancel).
    fn rounding(
        &self,
        local: f64,
        fine: &RunResult,
        go_on: GoOn<'_>,
    ) -> Result<Option<f64>, StepError> {
        if !self.twinned(local) {
            return Ok(None);
        }
        let start = *self.problem.start();
        let scale = start.theta.abs().max(1.0);
        let nudge = TWIN_NUDGE * scale;
        let moved = Start {
            theta: start.theta + nudge,
            ..start
        };
        let Ok(problem) = Problem::new(*self.problem.params(), moved) else {
            return Ok(None);
        };
        let twin = Resolved { problem, ..*self };
        let other = twin.run(local, go_on)?;
        let amplification = difference(fine, &other) / nudge;
        let steps = fine.stats.steps as f64;
        // Each step rounds θ at its own size: a pendulum that winds up to 33 rad rounds 33× more
        // than one that stays near the upright.
        let size = fine
            .samples
            .iter()
            .map(|x| x.theta.abs().max(x.theta_dot.abs()))
            .fold(fine.theta.abs().max(fine.theta_dot.abs()), f64::max)
            .max(scale);
        let bound = TWIN_GAIN * amplification * f64::EPSILON * size * steps;
        // The rounding itself, measured (issue 80): the same run a turn further, from `θ0 + 2π`:
        // the same motion, rounded at another size at every step, so the two differ by their
        // rounding alone; widened by SHIFT_MARGIN, it stands in for the floor's law.
        let turned = Start {
            theta: start.theta + std::f64::consts::TAU,
            ..start
        };
        let Ok(problem) = Problem::new(*self.problem.params(), turned) else {
            return Ok(None);
        };
        let shifted = Resolved { problem, ..*self }.run(local, go_on)?;
        let rounded = SHIFT_MARGIN * difference_turned(fine, &shifted);
        // The law where it is the smaller (a short run: it is tight there), the measurement
        // where the law's worst case is far above it (a long run of a start that does not
        // return near the upright).
        let law = self.floor - phase_rounding(&self.problem, self.t_end);
        Ok(Some(bound + rounded.min(law)))
    }
    fn rounding_cost(&self, local: f64) -> f64 {
        if self.twinned(local) {
            2.0 * self.run_cost(local)
        } else {
            0.0
        }
    }
    // A refinement that lowered the difference much less than the tolerance (a slope below
    // MIN_CONVERGENCE in log-log) shows rounding, not truncation, setting both runs' errors:
    // their difference then under-reads either's (the held-out `returns_eps1e-2`, with a
    // companion 16× looser, read 8.5e-9 for 1.1e-8 after slopes of 0.57 and 0.64), so it is
    // widened.
    fn estimate(&self, measured: f64, local: f64, before: Option<&(f64, f64)>) -> f64 {
        let noisy = before
            .is_some_and(|(l, e)| (e / measured).e_ln() < MIN_CONVERGENCE * (l / local).e_ln());
        if noisy {
            NOISE_MARGIN * measured
        } else {
            measured
        }
    }
}

/// What a slow model's error is measured against in [`averaged_checked`], in words (for
/// `simulate`'s reason).
#[must_use]
pub fn checked_against(problem: &Problem, method: Method) -> &'static str {
    let near = separated(problem);
    match method {
        Method::EffectiveCorrected => "the second-order averaged model",
        Method::Averaged2 if near => "the third-order averaged model",
        Method::Averaged2 => "the limit with its ripple (times (eps s)^2)",
        _ => "the second-order averaged model (times (eps s)^2)",
    }
}

/// The slow models' answer for [`verified`]'s fallbacks: checked now if it was skipped.
fn slow_fallback(
    averaged: &mut Option<Choice>,
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Choice, StepError> {
    if let Some(a) = averaged {
        return Ok(*a);
    }
    let a = averaged_checked(problem, tolerance, t_end, go_on)?;
    *averaged = Some(a);
    Ok(a)
}

/// Whichever came closer: a resolved run's shortfall or the slow models'.
fn closer(resolved: Choice, averaged: Choice) -> Choice {
    if resolved.estimate < averaged.estimate {
        resolved
    } else {
        averaged
    }
}
