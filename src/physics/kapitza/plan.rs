//! `auto` for the pendulum: the limit with its ripple (`effective-corrected`) when its model
//! error is predicted below the tolerance, else the full model resolved by `dop853`; when
//! neither can meet the tolerance, the one predicted closer, with `met = false` and its
//! estimate (`simulate` reports both, the explorer's status bar shows `✗ tol missed`).
//!
//! - **The limit's model error** after the ripple is added back is O(ε²) and grows with the
//!   horizon like a phase error: predicted `ε² (b² + |a| + 1)² (1 + t_end)`, which bounds what
//!   `tests/it/kapitza.rs` measures against the Taylor-series references (measured/predicted 0.03 to
//!   0.24 there). It is integrated at 1e-4 of the tolerance (DOP853's tolerance is per step;
//!   the global error of the slow limit reaches 100 times it on a growing motion), and that
//!   integration error is added to the estimate.
//! - **The resolved run**: DOP853's tolerance is per step and the global error grows with the
//!   number of fast periods `n` (measured: 90× the tolerance after 80 periods of an unstable
//!   start, an error that growing motions amplify), so it is asked for `tol / (100 sqrt(1 + n))`. Rounding sets a floor that no
//!   tolerance lowers: measured 1.2e-9 after 8 000 periods and 1.2e-8 after 80 000 (`rattleback
//!   bench --only kapitza`) on a stable start, 5.5e-9 after 8 000 on an unstable one; predicted
//!   `1e-12 n`.
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
//! keeps returning to the top, T = 50). The run is compared with a companion 16× looser on 33
//! samples of `(θ, θ̇)` and the final state; their difference plus the rounding floors is the
//! estimate. Above the tolerance the local tolerance shrinks by the factor the estimate asks
//! for (at least 4×) until it is met, stops falling, reaches 1e-14, or the budget would be
//! passed; then `met = false` with the estimate. The limit's estimate stays a priori (its model
//! error is a bound measured 4–30× above the truth).
//!
//! The full model's cost grows like `1/ε` and the limit's does not: as `ε` shrinks `auto`
//! switches to the limit and its cost stops growing.
//!
//! **The second-order averaged model** (`averaged2`, [`super::averaged`]: O(ε⁴) at the limit's
//! cost) is tried, checked a posteriori ([`averaged_checked`]), before a resolved run whenever
//! the limit cannot meet the tolerance a priori. Three runs of the slow motion (about 10 µs
//! each): `averaged2`, its companion 16× looser, and the limit with its ripple. The estimate is
//! `2 D (ε s)²` for the model (`D` the largest distance of `averaged2` from the limit with its
//! ripple over 33 samples and the end, `s = b² + |a| + 1`: the O(ε²) correction's own effect
//! along this trajectory, growth included, times the next order's relative size; measured
//! error over `D (ε s)²` at most 0.72 on the reference and held-out starts wherever the model
//! error is above the rounding), plus the run's distance from its companion (integration), plus
//! the fast phase's rounding. Met: `averaged2` runs; else `averaged3` where `ε s` ≤ 0.1
//! ([`averaged_checked`]); else, where the model error is within half the tolerance and the
//! integration is not (a long horizon), the better of the two once more at the tightest
//! tolerance; else the resolved run. Whatever misses, the smaller estimate is returned with
//! `met = false`: the averaged model's at once where a resolved run's rounding floor is above
//! it or its predicted cost over the budget (issue 27; `kapitza-just-below` takes `averaged3`,
//! 2e-11 off the long-double reference, where the resolved run ended 2e-7 off with `met =
//! false`).

use super::Problem;
use super::run::{RunResult, RunSpec, run};
use crate::physics::method::Asked;
use crate::physics::method::{Method, Settings, StepError};
use crate::physics::plan::Shortfall;

/// What `auto` chose, and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The concrete method.
    pub method: Method,
    /// Its settings.
    pub settings: Settings,
    /// The limit's predicted model error over the run.
    pub predicted_model_error: f64,
    /// The error the chosen run is expected to stay within (its target, or its floor).
    pub estimate: f64,
    /// Whether `estimate` meets the tolerance.
    pub met: bool,
    /// Why it does not, when it does not.
    pub shortfall: Option<Shortfall>,
}

/// Rounding floor of a resolved run, per fast period.
pub const ROUNDING_PER_PERIOD: f64 = 1e-12;

/// The scale of the expansion's terms: `b² + |a| + 1` (the small parameter is `ε` times it).
fn scale(problem: &Problem) -> f64 {
    let p = problem.params();
    p.b * p.b + p.a.abs() + 1.0
}

/// The limit's predicted model error (see the module's documentation).
#[must_use]
pub fn model_error(problem: &Problem, t_end: f64) -> f64 {
    (problem.params().epsilon * scale(problem)).powi(2) * (1.0 + t_end)
}

/// The second-order averaged model's (`averaged2`) predicted model error: O(ε⁴), with the
/// limit's scale and growth, `0.5 (ε (b² + |a| + 1))⁴ (1 + t_end)`. Against the Taylor-series
/// references (ε = 1e-2 … 1e-6) the measured error is at most 0.35 of it (the falling start at
/// ε = 1e-3, in θ̇), and mostly far less (`tests/it/kapitza.rs`); a start that keeps returning
/// to the unstable upright beats it, so `auto` chooses by the a-posteriori check and uses this
/// only to predict its cost ([`averaged_expected`]).
#[must_use]
pub fn model_error2(problem: &Problem, t_end: f64) -> f64 {
    0.5 * (problem.params().epsilon * scale(problem)).powi(4) * (1.0 + t_end)
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
    ROUNDING_PER_PERIOD * periods(problem, t_end) + phase_rounding(problem, t_end)
}

/// Resolves `auto` for `problem` at `tolerance` over `[0, t_end]`, a priori (no run): what
/// [`verified`] starts from, and what the cost model assumes.
#[must_use]
pub fn resolve(problem: &Problem, tolerance: f64, t_end: f64) -> Choice {
    let model = model_error(problem, t_end);
    let n = periods(problem, t_end);
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
    Choice {
        method: Method::Dop853,
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
    let local = (tolerance * 1e-4).max(TIGHTEST);
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

/// The averaged models checked a posteriori (see the module's documentation): `averaged2`'s
/// choice when its estimate meets `tolerance`; else `averaged3`'s when its does, its model
/// error measured by its gap to `averaged2` times `(ε s)²` (the ratio of their orders); else
/// the one with the smaller estimate, `met = false` (what [`verified`] returns when a resolved
/// run cannot do better). `averaged3` is not run where `ε s` > [`THIRD_ORDER_MAX_EPS_S`].
///
/// # Errors
/// A failed or cancelled run.
pub fn averaged_checked(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Choice, StepError> {
    let p = problem.params();
    let local = (tolerance * 1e-4).max(TIGHTEST);
    let spec = |method, tolerance| RunSpec {
        method,
        tolerance,
        step: None,
        t_end,
        samples: SAMPLES,
    };
    let es2 = (p.epsilon * scale(problem)).powi(2);
    let rounding = lift_phase_rounding(problem);
    let choice = |method, local, model, estimate: f64| Choice {
        method,
        settings: Settings {
            tolerance: local,
            step: None,
        },
        predicted_model_error: model,
        estimate,
        met: estimate <= tolerance,
        // Short of the tolerance by its model error, or by the slow run's integration at the
        // tightest tolerance (the one retry below).
        shortfall: (estimate > tolerance).then_some(
            if model > 0.5 * tolerance || local > TIGHTEST {
                Shortfall::Model
            } else {
                Shortfall::Clamped
            },
        ),
    };
    // A model's run at `local` and its companion, 16× looser.
    let pair = |method, local: f64, go_on: &mut dyn FnMut(f64) -> bool| -> Result<_, StepError> {
        Ok((
            run(problem, &spec(method, local), go_on)?,
            run(
                problem,
                &spec(method, (local * COMPANION_LOOSER).min(1e-3)),
                go_on,
            )?,
        ))
    };
    let (second, companion) = pair(Method::Averaged2, local, go_on)?;
    let first = run(problem, &spec(Method::EffectiveCorrected, local), go_on)?;
    let model2 = SECOND_ORDER_MARGIN * difference(&second, &first) * es2;
    let estimate = model2 + difference(&second, &companion) + rounding;
    let mut best = choice(Method::Averaged2, local, model2, estimate);
    if !best.met && es2 <= THIRD_ORDER_MAX_EPS_S.powi(2) {
        let (third, companion) = pair(Method::Averaged3, local, go_on)?;
        let model = THIRD_ORDER_MARGIN * difference(&third, &second) * es2;
        let estimate = model + difference(&third, &companion) + rounding;
        let third_choice = choice(Method::Averaged3, local, model, estimate);
        if third_choice.met || third_choice.estimate < best.estimate {
            best = third_choice;
        }
    }
    if best.met || local <= TIGHTEST || best.predicted_model_error > 0.5 * tolerance {
        return Ok(best);
    }
    // The model is within the tolerance and the integration is not (a long horizon): once more
    // at the tightest tolerance.
    let (tight, companion) = pair(best.method, TIGHTEST, go_on)?;
    let estimate = best.predicted_model_error + difference(&tight, &companion) + rounding;
    let tightened = choice(best.method, TIGHTEST, best.predicted_model_error, estimate);
    Ok(if tightened.estimate < best.estimate {
        tightened
    } else {
        best
    })
}

/// `|averaged3 − averaged2|` over `[0, t_end]`, both at the tightest tolerance: what
/// [`averaged_checked`] scales into `averaged3`'s model error (for its calibration).
///
/// # Errors
/// A failed run.
pub fn averaged3_gap(problem: &Problem, t_end: f64) -> Result<f64, StepError> {
    let spec = |method| RunSpec {
        method,
        tolerance: TIGHTEST,
        step: None,
        t_end,
        samples: SAMPLES,
    };
    let third = run(problem, &spec(Method::Averaged3), &mut |_| true)?;
    let second = run(problem, &spec(Method::Averaged2), &mut |_| true)?;
    Ok(difference(&third, &second))
}

/// How much looser the companion of a resolved run is.
pub const COMPANION_LOOSER: f64 = 16.0;
/// Most refinements of a resolved run.
pub const MAX_REFINEMENTS: usize = 4;
/// Tightest local tolerance.
pub const TIGHTEST: f64 = 1e-14;
/// How much a declined run's estimate is widened (see [`verified`]).
pub const NOISE_MARGIN: f64 = 3.0;
/// Samples of `(θ, θ̇)` compared.
const SAMPLES: usize = 33;

/// The difference of two runs over their samples and final states.
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
    let first = resolve(problem, tolerance, t_end);
    if first.met && first.method != Method::Dop853 {
        return Ok(first);
    }
    // The limit cannot meet the tolerance: the averaged models may.
    let averaged = averaged_checked(problem, tolerance, t_end, go_on)?;
    if averaged.met {
        return Ok(averaged);
    }
    // Whatever else ends short of the tolerance is returned only when it came closer than the
    // averaged model.
    let closer = |c: Choice| {
        if c.estimate < averaged.estimate {
            c
        } else {
            averaged
        }
    };
    if first.method != Method::Dop853 {
        return Ok(closer(first));
    }
    let floor = rounding_floor(problem, t_end);
    if floor >= averaged.estimate {
        // No resolved run can come closer than its rounding floor: the averaged model's
        // shortfall is the better answer, at once.
        return Ok(averaged);
    }
    let spec = |tolerance: f64| RunSpec {
        method: Method::Dop853,
        tolerance,
        step: None,
        t_end,
        samples: SAMPLES,
    };
    let cost =
        |l: f64| super::budget::cost_seconds(problem, &Asked::new(Method::Dop853, l, None, t_end));
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
    let mut local = first.settings.tolerance;
    // The cost model may have expected `averaged2` (`averaged_expected`): the resolved run it
    // did not count is refused here rather than run past the budget.
    let first_cost = cost(local) + cost((local * COMPANION_LOOSER).min(1e-3));
    if let Err(over) = crate::physics::budget::check(first_cost, budget) {
        // Refused, unless the averaged model's shortfall is an answer to give instead.
        if averaged.estimate.is_finite() {
            return Ok(averaged);
        }
        return Err(StepError::OverBudget {
            what: "auto's resolved run (the averaged models cannot meet the tolerance)".to_owned(),
            over,
        });
    }
    let mut spent = 0.0;
    let mut last: Option<(f64, f64)> = None;
    for refinement in 0..=MAX_REFINEMENTS {
        let companion = (local * COMPANION_LOOSER).min(1e-3);
        let predicted = cost(local) + cost(companion);
        if let Some((l, e)) = last
            && spent + predicted > budget
        {
            return Ok(closer(at(l, e, Some(Shortfall::Time))));
        }
        spent += predicted;
        let fine = run(problem, &spec(local), go_on)?;
        let coarse = run(problem, &spec(companion), go_on)?;
        let estimate = difference(&fine, &coarse) + floor;
        if estimate <= tolerance {
            return Ok(at(local, estimate, None));
        }
        // Declined: stalled, clamped or out of refinements. Near the rounding floor the two
        // runs' difference under-reads either's error (an unstable motion amplifies round-off
        // in both; measured up to 2.2× on the held-out starts), so the estimate given is
        // NOISE_MARGIN times the larger of the last two.
        let stalled = last.is_some_and(|(_, e)| estimate > 0.5 * e);
        if stalled || local <= TIGHTEST || refinement == MAX_REFINEMENTS {
            let why = if stalled {
                Shortfall::Floor
            } else if local <= TIGHTEST {
                Shortfall::Clamped
            } else {
                Shortfall::Refinements
            };
            let worst = last.map_or(estimate, |(_, e)| e.max(estimate));
            return Ok(closer(at(local, NOISE_MARGIN * worst, Some(why))));
        }
        last = Some((local, estimate));
        let factor = if estimate.is_finite() {
            (0.5 * tolerance / estimate).min(0.25)
        } else {
            1.0 / 16.0
        };
        local = (local * factor).max(TIGHTEST);
    }
    unreachable!("the loop returns at its last refinement")
}
