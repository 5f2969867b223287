//! The problem's conditioning: how much a nudge of the start grows over the run (measured on
//! a cheap model, with its bound kept), and the round-off floor it sets.

use super::memo;
use crate::physics::method::Asked;

use serde::Serialize;

use super::super::budget::{cost_seconds, dop853_evaluations, fastest_rate, slow_rate};
use super::super::effective::Effective;
use super::super::integrators::together;
use super::super::params::Problem;
use super::super::run::{RunResult, run_cancellable};
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::method::StepCap;
use crate::physics::method::StepError;

use super::super::policy::{
    BLANES_MOAN_MAX_NU_H, CONDITIONING_AVERAGED_LIMIT, CONDITIONING_KEPT_MARGIN,
    CONDITIONING_KEPT_SHARE, CONDITIONING_KEPT_X, CONDITIONING_LOOSE_TOLERANCE, CONDITIONING_MODEL,
    CONDITIONING_RECHECK, CONDITIONING_TOLERANCE, NUDGE,
};
use super::measure::{Plan, conditioned_round_off, difference, round_off};
use super::probe::{averaged_is_exact, probe_problem};

/// The settings of [`conditioning`]'s three runs: the plan's method at a coarse setting (its
/// companion's, loosened to a local tolerance of [`CONDITIONING_TOLERANCE`] or a step of
/// `ν h` = [`BLANES_MOAN_MAX_NU_H`]): both runs make nearly the same truncation errors, which
/// mostly cancel in their difference (on the held-out starts of `rattleback_honesty.toml` it
/// gives 0.93–1.6 times the long-double references' κ, at a fraction of a companion's cost).
/// A plan whose start the averaged models describe well ([`CONDITIONING_AVERAGED_LIMIT`]),
/// resolved or averaged, is measured on [`CONDITIONING_MODEL`] instead: the same slow motion,
/// without its fast oscillation, at the cheapest slow model's cost; first
/// ([`Stage::Loose`]) at [`CONDITIONING_LOOSE_TOLERANCE`], then, where that reads above
/// [`CONDITIONING_RECHECK`] ([`Stage::Accurate`]), at [`CONDITIONING_TOLERANCE`] for an averaged
/// plan and on the plan's own method for a resolved one.
pub(super) fn conditioning_spec(
    problem: &Problem,
    t_end: f64,
    plan: &Plan,
    stage: Stage,
) -> RunSpec {
    let slow = |tolerance| RunSpec {
        method: CONDITIONING_MODEL,
        tolerance,
        step: None,
        t_end,
        samples: 0,
        monitor_energy: false,
    };
    if super::super::averaged::expansion_parameter(problem) <= CONDITIONING_AVERAGED_LIMIT {
        // Where the averaged model is accurate, it measures the slow motion's sensitivity at a
        // fraction of a resolved run's cost, and of `averaged3`'s.
        match stage {
            Stage::Loose => return slow(CONDITIONING_LOOSE_TOLERANCE),
            Stage::Accurate if plan.method.is_averaged() => return slow(CONDITIONING_TOLERANCE),
            Stage::Accurate | Stage::Own => {}
        }
    }
    let c = plan.companion();
    RunSpec {
        method: plan.method,
        // The series' cost hardly depends on its tolerance: measured at its companion's own,
        // whatever it is, its base run *is* the companion, which the verification then reuses
        // (one run of five saved). Its truncation errors cancel between the nudged runs at any
        // tolerance (its step is a smooth function of the state, with no rejections).
        tolerance: if plan.method == Method::Taylor {
            c.tolerance
        } else {
            c.tolerance.max(CONDITIONING_TOLERANCE)
        },
        step: c
            .step
            .map(|h| h.max(BLANES_MOAN_MAX_NU_H / fastest_rate(problem))),
        t_end,
        samples: 0,
        monitor_energy: false,
    }
}

/// Which measurement of [`conditioning`] a spec is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Stage {
    /// The first: on the cheapest slow model at a loose tolerance, where it describes the start.
    Loose,
    /// Where the first read above [`CONDITIONING_RECHECK`].
    Accurate,
    /// On the plan's own method (its price).
    Own,
}

/// How much the start's rounding is amplified by `T` ([`conditioning`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Conditioning {
    /// Per relative change of the spin rate `α̇0` (of `γ̇0` for a start at rest in `α̇`): the
    /// energy on which the slow motion's period depends. Near the separatrix 1e3 … 1e7.
    pub rate: f64,
    /// Per radian of the spin angle `α0`: the angle is rounded in absolute terms, `ε |α|`, and
    /// a rotating start takes it to tens of radians.
    pub angle: f64,
    /// 1 where `rate` and `angle` were measured at the run's own `k`;
    /// [`CONDITIONING_KEPT_MARGIN`] where they were read at the start's conditioning stiffness
    /// ([`conditioning_stiffness`]) and bound the start's numbers only once multiplied by it.
    pub margin: f64,
}

impl Conditioning {
    /// The condition number one step's rounding sees in `result`: `rate` for the relative
    /// rounding of the rates, plus `angle · |α|` for the angle's, at the larger of its start
    /// and end values (a rotating `α` grows monotonically; a trapped one stays within its
    /// turning points).
    #[must_use]
    pub fn of_run(&self, problem: &Problem, result: &RunResult) -> f64 {
        self.at_angle(problem.start().alpha.abs().max(result.final_state[1].abs()))
    }

    /// The condition number a step's rounding sees where `|α|` reaches `alpha`.
    pub(super) fn at_angle(&self, alpha: f64) -> f64 {
        self.margin * (self.rate + self.angle * alpha)
    }

    /// Measured at the run's own `k`.
    fn measured(rate: f64, angle: f64) -> Self {
        Self {
            rate,
            angle,
            margin: 1.0,
        }
    }
}

/// The start's condition numbers ([`Conditioning`]): by how much the largest change of
/// `α(T)`, `α̇(T)` and the reversal times exceeds a nudge of the start, which is what a
/// rounding error made early in the run becomes by `T`. Measured with three coarse runs of
/// `plan`'s method (`conditioning_spec`; on the slow model one run of the three side by side,
/// [`slow_condition_numbers`]): as started, with the spin rate scaled by
/// `1 + NUDGE` (the tilt rate, or the tilt, for a start at rest in `α̇`, where a nudge of `α̇0`
/// would add a reversal at `t = 0`), and with the angle moved by `NUDGE` radians. Where two runs count
/// different reversals (an event at a tangency), a nudge a thousand times smaller is tried,
/// then the final state alone is compared.
///
/// # Errors
/// [`StepError::Cancelled`] when `go_on` says stop.
pub fn conditioning(
    problem: &Problem,
    t_end: f64,
    plan: &Plan,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Conditioning, StepError> {
    measure_conditioning(problem, t_end, plan, go_on).map(|(kappa, _)| kappa)
}

/// A run already made, which a later run of the same spec reuses: [`conditioning`]'s base run of
/// a `taylor` plan is its first companion (same method, same tolerance, no samples).
#[derive(Clone, Debug)]
pub(super) struct Made {
    pub(super) spec: RunSpec,
    pub(super) result: RunResult,
}

/// [`conditioning`], with the base run it measured from (none at the equilibrium).
pub(super) fn measure_conditioning(
    problem: &Problem,
    t_end: f64,
    plan: &Plan,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(Conditioning, Option<Made>), StepError> {
    let start = *problem.start();
    if start.alpha_dot == 0.0 && start.gamma_dot == 0.0 && start.gamma == 0.0 {
        // The equilibrium: nothing moves, nothing is amplified.
        return Ok((Conditioning::measured(0.0, 0.0), None));
    }
    let spec = conditioning_spec(problem, t_end, plan, Stage::Loose);
    let cheap = condition_numbers(problem, &spec, go_on)?;
    let accurate = conditioning_spec(problem, t_end, plan, Stage::Accurate);
    if spec != accurate && cheap.0.rate.max(cheap.0.angle) > CONDITIONING_RECHECK {
        // An ill-conditioned start: its round-off floor matters, so it is measured again,
        // accurately: on the slow model at a tight tolerance for an averaged plan, on the plan's
        // own method for a resolved one.
        return condition_numbers(problem, &accurate, go_on);
    }
    Ok(cheap)
}

/// Predicted seconds of [`conditioning`] for `plan`, priced as the measurement on the plan's
/// own method (the averaged model's, when it serves, costs less); two runs for the series, whose
/// base run is its companion.
pub(super) fn conditioning_cost(problem: &Problem, t_end: f64, plan: &Plan) -> f64 {
    let measure = conditioning_spec(problem, t_end, plan, Stage::Own);
    let runs = if plan.method == Method::Taylor {
        2.0
    } else {
        3.0
    };
    runs * cost_seconds(
        problem,
        &Asked::new(measure.method, measure.tolerance, measure.step, t_end),
    )
}

/// Predicted seconds of [`conditioning`] as it is measured first (what decides which of a run
/// and its verification waits for a second core, [`fork::dearer_here`]): on the slow model, the
/// three starts side by side cost about twice one run (0.057 against 0.027 ms, trapped start,
/// k = 1e6 … 1e12); on the plan's own method, its runs.
///
/// [`fork::dearer_here`]: crate::physics::fork::dearer_here
pub(super) fn measuring_cost(problem: &Problem, t_end: f64, plan: &Plan) -> f64 {
    let first = conditioning_spec(problem, t_end, plan, Stage::Loose);
    if first.method.is_averaged() {
        2.0 * cost_seconds(
            problem,
            &Asked::new(first.method, first.tolerance, first.step, t_end),
        )
    } else {
        conditioning_cost(problem, t_end, plan)
    }
}

/// The stiffness at which the start of `problem` is read to bound its condition numbers at every
/// `k` at or above it ([`CONDITIONING_KEPT_X`]): the smallest power of ten from 1e2 on where the
/// start of the same family ([`probe_problem`]) has an expansion parameter of at most
/// `CONDITIONING_KEPT_X`. It depends on the body and the start, not on `k` (for a start with
/// `γ0 = 0`, every shipped preset, the family's start is the start itself), so every `k` above it
/// asks for the same reading. `None` where no stiffness up to 1e22 is that far in.
#[must_use]
pub fn conditioning_stiffness(problem: &Problem) -> Option<f64> {
    (2..=22).map(|n| 10f64.powi(n)).find(|&k| {
        super::super::averaged::expansion_parameter(&probe_problem(problem, k))
            <= CONDITIONING_KEPT_X
    })
}

/// The start of `problem`'s family at its conditioning stiffness, where an averaged `plan` runs
/// above it (its condition numbers may then be bounded by that start's). None where the averaged
/// model is the exact motion (`ix = iy`: no ripple, and the start is measured at its own `k`).
pub(super) fn conditioning_family(problem: &Problem, plan: &Plan) -> Option<Problem> {
    if !plan.method.is_averaged() || averaged_is_exact(problem) {
        return None;
    }
    let k = conditioning_stiffness(problem)?;
    (problem.params().k > k).then(|| probe_problem(problem, k))
}

/// The bound on the condition numbers of every start of `family`'s family at a larger `k`: the
/// first reading of `family` (the slow model side by side at [`CONDITIONING_LOOSE_TOLERANCE`])
/// with [`CONDITIONING_KEPT_MARGIN`], read from [`memo`] where kept (`None` when not, and
/// `compute` false), else measured and kept. What is read is what would be computed.
pub(super) fn family_bound(
    family: &Problem,
    t_end: f64,
    compute: bool,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Option<Conditioning>, StepError> {
    let key = memo::conditioning_key(family, t_end);
    let bound = |[rate, angle]: memo::Gaps| Conditioning {
        rate,
        angle,
        margin: CONDITIONING_KEPT_MARGIN,
    };
    if let Some(kept) = memo::read(&key) {
        return Ok(Some(bound(kept)));
    }
    if !compute {
        return Ok(None);
    }
    let kappa = slow_condition_numbers(
        family,
        CONDITIONING_MODEL,
        CONDITIONING_LOOSE_TOLERANCE,
        t_end,
        go_on,
    )?;
    let reading = [kappa.rate, kappa.angle];
    memo::keep(key, reading);
    Ok(Some(bound(reading)))
}

/// Whether a kept `bound` serves a run of `steps` steps at `tolerance` whose condition number it
/// bounds by `kappa`: its reading is of a well-conditioned start (at most
/// [`CONDITIONING_RECHECK`], where the first reading at `k` is also taken as it is), and the
/// conditioned round-off floor it gives is at most [`CONDITIONING_KEPT_SHARE`] of the tolerance.
pub(super) fn bound_serves(bound: &Conditioning, kappa: f64, steps: f64, tolerance: f64) -> bool {
    bound.rate.max(bound.angle) <= CONDITIONING_RECHECK
        && conditioned_round_off(steps, kappa) <= CONDITIONING_KEPT_SHARE * tolerance
}

/// The largest `|α|` a start may reach over `[0, t_end]`, a priori: its limit's turning points
/// (and half a radian for the corrections), or what its spin covers in `t_end` when it rotates.
/// Only a kept bound's weighing before the run uses it; the run's own `α` decides after it.
pub(super) fn alpha_bound(problem: &Problem, t_end: f64) -> f64 {
    let eff = Effective::new(problem);
    let start = problem.start().alpha.abs();
    match eff.turning_points() {
        Some((low, high)) => start.max(low.abs()).max(high.abs()) + 0.5,
        None => start + eff.spin_scale() * t_end,
    }
}

/// Steps an averaged `plan` is predicted to take, fourfold (where a kept bound is weighed before
/// the run).
pub(super) fn generous_steps(problem: &Problem, plan: &Plan, t_end: f64) -> f64 {
    let periods = slow_rate(problem).max(1e-3) * t_end / std::f64::consts::TAU;
    4.0 * dop853_evaluations(plan.tolerance, periods) / 12.0
}

/// Nudges the energy's first non-zero carrier: the spin rate, else the tilt rate, else the tilt.
pub(super) fn nudge_rate(s: &mut super::super::params::Start, nudge: f64) {
    if s.alpha_dot != 0.0 {
        s.alpha_dot *= 1.0 + nudge;
    } else if s.gamma_dot != 0.0 {
        s.gamma_dot *= 1.0 + nudge;
    } else {
        s.gamma *= 1.0 + nudge;
    }
}

/// Nudges the spin angle.
pub(super) fn nudge_angle(s: &mut super::super::params::Start, nudge: f64) {
    s.alpha += nudge;
}

/// [`conditioning`]'s three runs with `spec`, and the first (the start as it is). On the slow
/// model the three starts are integrated together, the nudged ones on the first one's steps
/// ([`together`]): one run, and no truncation error left in their differences.
pub(super) fn condition_numbers(
    problem: &Problem,
    spec: &RunSpec,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(Conditioning, Option<Made>), StepError> {
    if spec.method.is_averaged() {
        return slow_condition_numbers(problem, spec.method, spec.tolerance, spec.t_end, go_on)
            .map(|kappa| (kappa, None));
    }
    let base = run_cancellable(problem, spec, go_on)?;
    let rate = sensitivity(problem, spec, &base, go_on, nudge_rate)?;
    let angle = sensitivity(problem, spec, &base, go_on, nudge_angle)?;
    Ok((
        Conditioning::measured(rate, angle),
        Some(Made {
            spec: *spec,
            result: base,
        }),
    ))
}

/// `condition_numbers` on the slow model: the start and its two nudged copies integrated
/// together. Where a copy counts other reversals than the start (an event at a tangency), the
/// three are run again with a nudge a thousand times smaller, then the final states alone are
/// compared, as `sensitivity` does. `auto`'s first reading is this on
/// [`CONDITIONING_MODEL`] at [`CONDITIONING_LOOSE_TOLERANCE`].
///
/// # Errors
/// A failed step, and [`StepError::Cancelled`] when `go_on` says stop.
///
/// # Panics
/// When `method` is not an averaged model.
pub fn slow_condition_numbers(
    problem: &Problem,
    method: Method,
    tolerance: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Conditioning, StepError> {
    let cap = StepCap::of(3.0 * cost_seconds(problem, &Asked::new(method, tolerance, None, t_end)));
    // Per copy (rate, angle): its number, once its reversals match the start's; else the
    // final states' difference at the smaller nudge.
    let mut found: [Option<f64>; 2] = [None, None];
    let mut ends_only = [f64::INFINITY; 2];
    for nudge in [NUDGE, NUDGE * 1e-3] {
        let moved = |how: fn(&mut super::super::params::Start, f64)| {
            let mut start = *problem.start();
            how(&mut start, nudge);
            Problem::new(*problem.params(), start).ok()
        };
        let (Some(rate), Some(angle)) = (moved(nudge_rate), moved(nudge_angle)) else {
            return Ok(Conditioning::measured(f64::INFINITY, f64::INFINITY));
        };
        let ends = together(
            method,
            &[*problem, rate, angle],
            t_end,
            tolerance,
            cap,
            go_on,
        )?;
        for (i, slot) in found.iter_mut().enumerate() {
            if slot.is_none() {
                let d = ends[0].distance(&ends[i + 1]);
                *slot = d.is_finite().then_some(d / nudge);
                ends_only[i] = ends[0].end_distance(&ends[i + 1]) / nudge;
            }
        }
        if found.iter().all(Option::is_some) {
            break;
        }
    }
    Ok(Conditioning::measured(
        found[0].unwrap_or(ends_only[0]),
        found[1].unwrap_or(ends_only[1]),
    ))
}

/// How much `base` moves per unit of a nudge that `nudge_start` applies to the start.
pub(super) fn sensitivity(
    problem: &Problem,
    spec: &RunSpec,
    base: &RunResult,
    go_on: &mut dyn FnMut(f64) -> bool,
    nudge_start: impl Fn(&mut super::super::params::Start, f64),
) -> Result<f64, StepError> {
    let mut last = (base.final_state, NUDGE);
    for nudge in [NUDGE, NUDGE * 1e-3] {
        let mut moved = *problem.start();
        nudge_start(&mut moved, nudge);
        let Ok(nudged) = Problem::new(*problem.params(), moved) else {
            return Ok(f64::INFINITY);
        };
        let run = run_cancellable(&nudged, spec, go_on)?;
        let d = difference(base, &run);
        if d.is_finite() {
            return Ok(d / nudge);
        }
        last = (run.final_state, nudge);
    }
    let ((a, b), nudge) = ((base.final_state, last.0), last.1);
    Ok((a[1] - b[1]).abs().max((a[3] - b[3]).abs()) / nudge)
}

/// The phase's round-off floor in an estimate: [`round_off`] for the adaptive methods; nothing
/// for the fixed-step ones, which now add their steps to the time with a compensated sum
/// ([`crate::physics::method::TimeSum`]): what the floor was fitted to (their reversal times
/// drifting at 10⁵ steps and more) was that sum's rounding, and on the held-out starts of
/// `rattleback_honesty.toml` and `averaged.toml` every estimate still bounds its error without
/// it (`tests/it/honesty.rs`, `tests/it/auto_honest.rs`).
pub(super) fn phase_round_off(problem: &Problem, plan: &Plan, steps: f64, t_end: f64) -> f64 {
    if plan.step.is_some() {
        0.0
    } else {
        round_off(problem, steps, t_end)
    }
}
