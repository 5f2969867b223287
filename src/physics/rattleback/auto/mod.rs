//! `auto`: the cheapest method that meets a tolerance on the slow observables (`α(T)`,
//! `α̇(T)` and the reversal times), with an error estimate that never claims more than it
//! knows.
//!
//! **Candidates** (costs predicted by [`super::budget`], calibrated on this machine):
//! - `taylor`, resolving the fast motion by its Taylor series, at a local tolerance `L / 1024`
//!   where its companion at `L` should still meet the tolerance: the companion's global error
//!   is about `G L` with `G = 0.25 · max(20, fast periods)` ([`TAYLOR_GROWTH`]). The series'
//!   error is a random walk that a slightly looser companion can under-read; one
//!   `TAYLOR.companion_looser` = 1024 times looser did not on any reference, and the series'
//!   cost grows so slowly with its tolerance (`tol^-0.05`) that the tight run costs 1.4× the
//!   companion. The cheapest resolving candidate at tolerances down to about 1e-9;
//! - `dop853`, resolving the fast motion, at a local tolerance `L` such that its companion at
//!   `16 L` should still meet the tolerance: the global error is about `G L` with
//!   `G = 2.5 · max(20, fast periods)` (measured, [`DOP853_GROWTH`]); a plan whose `L` would
//!   fall below the 1e-14 clamp cannot be verified and counts as missing the tolerance;
//! - `blanes-moan4`, resolving, at a step `h` such that its companion at `2h` should meet the
//!   tolerance: error ≈ `(C_BM spin^2.5 c_max⁴ ν²/g_min + C_FAST ν⁴) h⁴ T` ([`C_BM`]);
//!   `ν h ≤ 0.75`, so that the companion at `2h` stays where the error follows `h⁴`;
//! - `averaged3`, the O(k⁻³) averaged model ([`AVERAGED`]), once `k` is far enough above the
//!   stiffnesses at which its model error can be *measured* cheaply. Two probes at `k_lo` and
//!   `k_hi = 4 k_lo` (the smallest `k` where the averaging expansion is valid for this start:
//!   `|α̇|/ω ≤ 0.2`) compare it with the resolved full model (`taylor` at 1e-12) over `[0, T]`
//!   (33 samples of `α`, `α̇`, and the reversal times); the model error at `k` is predicted as
//!   `2 · gap(k_hi) · (k_hi/k)^p`, with `p` the measured slope between the probes clamped to
//!   `[0.5, 3]` (3 is the theory's; a pre-asymptotic start decays slower and is extrapolated
//!   with its own, smaller slope). Where the model is exact (`ix = iy`, or no fast action) no
//!   probe runs. The slow flow then runs at a local tolerance such that its companion at `16 L`
//!   meets the rest of the tolerance;
//! - `averaged2`, the O(k⁻²) model, measured by the same probes against the same full runs and
//!   extrapolated the same way (slope clamped to `[0.5, 2]`), where its predicted model error is
//!   at most [`SECOND_ORDER_MODEL_SHARE`] of the tolerance and it is predicted cheaper (a run
//!   costs half of `averaged3`'s): the large stiffnesses.
//!
//! **Verification.** Every plan runs twice: the run that is returned, and a *coarser*
//! companion (step `2h`, or tolerance `16 L`; `1024 L` for the series) that costs 0.5–0.7× as
//! much and is never identical to it. The estimate is their difference in `α(T)`, `α̇(T)` and
//! the reversal times (infinite when the reversal counts differ), plus the probed model error for
//! the averaged model, plus the round-off floors (the phase's, and the start's rounding scaled by
//! its measured condition numbers, [`conditioning`], first read on the slow model at a loose
//! tolerance and measured again accurately where they pass [`CONDITIONING_RECHECK`]). The
//! difference bounds
//! the returned run's error whenever the companion's error is at least twice the run's, which
//! holds with a wide margin where the method converges (the companion's is 16× for a 4th-order
//! step, ~14× for a 16× looser tolerance) and fails only at the round-off floor, which the
//! refinement rule detects.
//!
//! **Refinement**, by the one loop (`physics::verify`, as `POLICY` and `TAYLOR` say; the
//! candidate here is `Auto`), until the estimate meets the tolerance: the step or tolerance
//! shrinks by the factor the estimate asks for; an averaged model whose error is too large gives way to the
//! best resolving method. It stops, and says so with `met = false`, when the estimate stops
//! falling (less than halved by a refinement: the round-off floor or an ill-conditioned start;
//! the estimate reached is reported as the floor), at once when the round-off floors alone pass
//! the tolerance (a refinement only adds steps to them), when an adaptive tolerance reaches its
//! 1e-14 clamp, after `POLICY.max_refinements`, or before a refinement predicted to take the total
//! past [`AUTO_SECONDS`] (or the caller's smaller budget).
//!
//! **Far in** (an averaged plan at `k` above the start's conditioning stiffness, where its
//! expansion parameter is [`CONDITIONING_KEPT_X`], stop 51), the start's condition numbers are
//! bounded instead of measured: by its reading at that one stiffness, kept across `k` ([`memo`]),
//! times [`CONDITIONING_KEPT_MARGIN`] (they move with `k`, by up to 21× on the references),
//! wherever that reading is at most [`CONDITIONING_RECHECK`] and the floor the bound gives at
//! most [`CONDITIONING_KEPT_SHARE`] of the tolerance; elsewhere they are measured at `k`. With
//! the reading kept, the verification is the companion alone.
//!
//! **Two cores.** The run, its companion and the condition numbers do not depend on one another,
//! nor do the two probes: [`fork::both`] runs them side by side where the program installed a
//! second core (the binary does: `crate::parallel`), the dearer half on the calling thread. The
//! answer is the same either way, bit for bit; only the wall time differs (issue 27: with the
//! probes and the conditioning's reading kept, 0.8–1.5× the cheapest single run at `auto`'s
//! error, against 1.4–2.5× on one core).
//!
//! The first planner is kept, frozen, in [`legacy`] for the replay of old session files.
//! Pure: no clock; a caller's `go_on` decides about cancellation.

pub mod legacy;
pub mod memo;

use super::policy::{POLICY, TAYLOR};
use crate::physics::method::Asked;
use std::fmt::Write as _;

use serde::Serialize;

pub use crate::physics::plan::Shortfall;

use super::budget::{cost_seconds, dop853_evaluations, fastest_rate, slow_rate};
use super::effective::Effective;
use super::integrators::together;
use super::params::Problem;
use super::run::{RunResult, run_cancellable};
use crate::physics::fork;
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::method::Settings;
use crate::physics::method::StepCap;
use crate::physics::method::StepError;
use crate::physics::verify::{Candidate, Outcome, Policy, verify};

/// Error of `blanes-moan4` per unit time: `C_BM · spin^2.5 · c_max⁴ · h⁴ ν² / g_min`, with
/// `spin` the largest spin rate of the limit, `c_max = |iy − ix| / (4 min(ix, iy))`, fitted on
/// the averaging note's starts A, B, D for k = 1e2 … 1e5 and `ν h` ≤ 1.5 (measured 6.9e-3 …
/// 7.3e-3, doubled: docs/benchmarks.md).
pub const C_BM: f64 = 1.5e-2;
/// Error of `blanes-moan4` per unit time at `ν h = 1` that remains where `c_max` or the spin
/// vanish (issue 3's calibration at k = 1e6).
pub const C_FAST: f64 = 3e-12;
/// Largest `ν h` of a `blanes-moan4` run: its companion at `2h` stays where the error still
/// follows `h⁴` (measured up to `ν h = 1.5`; at 2 it jumps by 10²–10³ on trapped starts).
pub const BLANES_MOAN_MAX_NU_H: f64 = 0.75;
/// The series' global error over its local tolerance per fast period of the horizon (at least
/// 20): median 0.27 on the long-double references up to k = 1e6, a tenth of DOP853's
/// (`cargo run --release --example rattleback_taylor growth`, and with `METHOD=dop853`), which
/// is what [`DOP853_GROWTH`] is to DOP853.
pub const TAYLOR_GROWTH: f64 = 0.25;
/// DOP853's global error over its local tolerance per fast period of the horizon (measured
/// 0.6–2.7 on trapped starts, 0.06–0.25 on rotating ones, k = 1e2 … 1e5, T = 30).
pub const DOP853_GROWTH: f64 = 2.5;
/// The averaged model `auto` plans with (probes, plans and refines): `averaged3`, whose
/// O(k⁻³) error reaches into the middle stiffnesses `averaged2` could not serve.
pub const AVERAGED: Method = Method::Averaged3;
/// `averaged2` runs instead of [`AVERAGED`] where its probed model error is at most this share
/// of the tolerance (issue 27): at large `k` its O(k⁻²) error is far below any tolerance, and a
/// run costs half of `averaged3`'s (12 against 34 ns per evaluation), so `auto`'s run and
/// companion do too. Within a tenth, the integration still gets most of the tolerance, as with
/// `averaged3`.
pub const SECOND_ORDER_MODEL_SHARE: f64 = 0.1;

/// The order in `1/k` of [`AVERAGED`]'s model error (the theory's; a probe's slope is clamped
/// to it).
pub const MODEL_ORDER: f64 = 3.0;
/// Safety factor on the probed model error of the averaged model.
pub const PROBE_SAFETY: f64 = 2.0;
/// Samples of `α`, `α̇` compared by a probe.
pub const PROBE_SAMPLES: usize = 33;
/// The method of a probe's full model: the Taylor series (`taylor`). At
/// [`PROBE_FULL_TOLERANCE`] its error in `α(T)`, `α̇(T)` and the reversal times is at most
/// DOP853's on every long-double reference of `averaged.toml` and `rattleback_honesty.toml` up
/// to k = 1e6, and 3–70× below it from k = 1e2 to 1e4, where the probes run (over the samples
/// too, within 3e-11 there: `averaged::the_probes_full_model_is_as_accurate_as_dop853`), at
/// 0.3–0.5 of its time (`cargo run --release --example rattleback_taylor probe`;
/// docs/benchmarks.md, "The middle by a Taylor series").
pub const PROBE_FULL_METHOD: Method = Method::Taylor;
/// Local tolerance of the full model in a probe: its global error at the probe stiffnesses (≤ 100
/// fast periods over T = 30) is at most 1.5e-11 on the references (DOP853's at this tolerance
/// was about 2.5e-10), against the averaged model's gaps of 1e-8 and more there
/// (docs/averaging/third-order.md).
pub const PROBE_FULL_TOLERANCE: f64 = 1e-12;
/// Local tolerance of the averaged model in a probe (its global error ≈ 1e-10, against gaps
/// of 1e-8 and more at the probe stiffnesses).
pub const PROBE_TOLERANCE: f64 = 1e-12;
/// Largest `|α̇| (1 + c_max) / ω_min` at the lower probe stiffness: where the averaging
/// expansion already holds (from k = 1e2, where this is 0.1–0.3 for the note's starts,
/// `averaged3`'s errors already fall like k^-2.7 … k^-3: docs/averaging/third-order.md).
pub const PROBE_VALIDITY: f64 = 0.2;
/// Most rungs of probes ([`probe_averaged`]).
pub const PROBE_RUNGS: u32 = 3;
/// The averaged model is considered from `k ≥ AVERAGED_MIN_RATIO · k_hi` on (where probing
/// is predicted cheaper than resolving): its error is extrapolated from `k_hi` with the
/// measured slope, which a pre-asymptotic start keeps below the theory's 3, so the prediction
/// errs high.
pub const AVERAGED_MIN_RATIO: f64 = 4.0;
/// Predicted seconds (calibration machine) after which `auto` stops refining and reports
/// `met = false` instead of computing on: it answers within about this time, whatever the
/// start and tolerance.
pub const AUTO_SECONDS: f64 = 10.0;
/// Gain of the round-off floor ([`round_off`]): blanes-moan4's reversal times at very small
/// steps, against the long-double references, fit a gain of 1.2–1.5 (T = 30, k = 1e4, and
/// T = 1000, k = 1e2, 10⁵–6·10⁵ steps); 5 keeps a margin for the scatter. What it was fitted
/// to was mostly the time itself, summed `t + h` in double each step; the fixed-step methods now
/// sum it compensated (4.3e-11 → 1.2e-12 on `lib_b1_a015_k1e06`'s reversal times:
/// docs/benchmarks.md, "Issue 29"), so only the adaptive methods keep it, in their predicted
/// errors and their estimates (`phase_round_off`); the splitting's prediction counts one
/// rounding per step ([`conditioned_round_off`] at κ = 1).
pub const ROUND_OFF_GAIN: f64 = 5.0;
/// Relative nudge of the rates, and absolute nudge of the angle (radians), by which
/// [`conditioning`] measures how much the start's rounding is amplified by `T` (small enough
/// to stay linear at condition numbers of 1e7, large enough to stand far above the rounding of
/// the runs it compares).
pub const NUDGE: f64 = 1e-10;
/// Largest expansion parameter ([`super::averaged::expansion_parameter`]) at which a plan's
/// condition numbers are measured on [`CONDITIONING_MODEL`] instead of the plan's own method:
/// a sensitivity measured with nudges of 1e-10 is the derivative of the slow motion in its start,
/// which the averaged models' errors (`averaged2`'s O(x⁴) relative) move by far less than the
/// factor of two the round-off floor's gain leaves. Raised from 0.1 in issue 27 to take in the
/// rotating start at k = 1e2 (x = 0.21): on the long-double references with 0.1 < x ≤ 0.3 the
/// slow model's κ is within 0.3 % of the full model's away from the separatrix (B, C, D, E at
/// k = 1e2); near it (κ of 1e3 … 1e6) it is off by up to 300× either way but always reads above
/// [`CONDITIONING_RECHECK`], so it is measured again on the plan's own method
/// (`cargo run --release --example conditioning_check`).
pub const CONDITIONING_AVERAGED_LIMIT: f64 = 0.25;
/// The model [`conditioning`] measures on below [`CONDITIONING_AVERAGED_LIMIT`]: `averaged2`,
/// the cheapest slow model with the fast action's back-reaction (12 ns per evaluation against
/// `averaged3`'s 34: its three runs took 0.14 ms instead of 0.31 ms at k = 1e8 on the trapped
/// start). It replaced `averaged3` here in issue 27: on the held-out starts of
/// `rattleback_honesty.toml` (k = 1e2 … 1e12) the condition numbers `auto` measures stay within
/// 0.9–1.7 of the long-double references' (`honesty::auto_measures_the_conditioning_the_references_report`).
pub const CONDITIONING_MODEL: Method = Method::Averaged2;
/// Condition number above which a measurement on the averaged model
/// ([`CONDITIONING_AVERAGED_LIMIT`]) is repeated on the plan's own method: below it the
/// conditioned round-off floor (`10 ε √steps κ`) is far under any tolerance `auto` is asked
/// for, so the cheap measurement's accuracy does not matter; above it, it does (the shipped
/// `just-below` start measures κ = 1.4e4 on `averaged3` and 9.1e3 on the full model).
pub const CONDITIONING_RECHECK: f64 = 100.0;
/// Expansion parameter ([`super::averaged::expansion_parameter`]) below which (at a `k` above the
/// start's [`conditioning_stiffness`]) an averaged plan's condition numbers may be bounded by the
/// start's reading at that one stiffness instead of measured at its own `k` (issue 27, stop 51):
/// that reading is kept ([`memo`]) and serves every larger `k` (the explorer's `k` slider, a sweep's
/// rungs), so `auto`'s verification is its companion alone.
pub const CONDITIONING_KEPT_X: f64 = 0.01;
/// How much a reading at the conditioning stiffness is widened into a bound on the start's
/// condition numbers at a larger `k`: they move with `k` (the fast ripple's phase in `α̇(T)`, and
/// the reversals crossing where the ripple makes `α̇` steep or shallow by turns), on the reference
/// families up to 16× (rate) and 21× (angle) above that reading, `k` up to 1e12
/// (`cargo run --release --example conditioning_check spread`;
/// `honesty::a_kept_conditioning_bounds_the_start_at_every_larger_k`).
pub const CONDITIONING_KEPT_MARGIN: f64 = 50.0;
/// The bound ([`CONDITIONING_KEPT_MARGIN`]) serves only where the conditioned round-off floor it
/// gives is at most this share of the tolerance: there it can neither cost `met` nor, misread
/// by less than tenfold, hide an error of the tolerance's size. Elsewhere (tight tolerances,
/// ill-conditioned starts) the start is measured at its own `k`, as below
/// [`CONDITIONING_KEPT_X`].
pub const CONDITIONING_KEPT_SHARE: f64 = 0.1;
/// Local tolerance of [`conditioning`]'s runs (at least; the companion's when looser).
pub const CONDITIONING_TOLERANCE: f64 = 1e-9;
/// Local tolerance of [`conditioning`]'s first measurement on [`CONDITIONING_MODEL`]: the nudged
/// starts are integrated side by side with the start, on its steps
/// ([`slow_condition_numbers`]), so their truncation errors cancel and a loose run measures the
/// sensitivity as well as a tight one where it is small; where it reads above
/// [`CONDITIONING_RECHECK`] (the floor may matter) the measurement is repeated at
/// [`CONDITIONING_TOLERANCE`], as before. Issue 27: three separate runs at 1e-9 were half of
/// `auto`'s time at k ≥ 1e5 with the probes kept; at 1e-7 side by side the reading costs
/// 0.06 ms (trapped start) and 0.10 ms (rotating), against 0.09 and 0.18 ms for three separate
/// runs at 1e-7 (`cargo run --release --example conditioning_check all`).
pub const CONDITIONING_LOOSE_TOLERANCE: f64 = 1e-7;
/// Gain of the conditioned round-off floor `CONDITIONED_GAIN · ε · √steps · κ`: a step rounds
/// several numbers, so the random walk's step is a few ε. Measured on the held-out starts near
/// the separatrix of `rattleback_honesty.toml` (κ = 1e3 … 2e7): restarting from one to five ulps
/// away spreads `α(T)` by up to 3.3 `ε √steps κ` (`sep_b2_in5_k1e03`, a 1-ulp change moved it
/// by 1e-8); 10 bounds every one of 225 such runs with a margin of two.
pub const CONDITIONED_GAIN: f64 = 10.0;
/// Global-to-local error growth of the averaged slow flow over `T = 30` (measured 6–140 on the
/// note's starts at local tolerance 1e-10; it grows linearly with `T` on rotating starts).
pub const AVERAGED_GROWTH: f64 = 150.0;

/// What `auto` decided, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Plan {
    /// The method chosen.
    pub method: Method,
    /// Tolerance handed to it (adaptive methods).
    pub tolerance: f64,
    /// Step handed to it (fixed-step methods).
    pub step: Option<f64>,
    /// The error the models predict for the returned run (model error included).
    pub predicted_error: f64,
    /// Predicted seconds of the run and its companion on the calibration machine.
    pub predicted_seconds: f64,
    /// One sentence on the choice.
    pub reason: String,
}

impl Plan {
    /// The integrator settings of the plan (the run that is returned).
    #[must_use]
    pub fn settings(&self) -> Settings {
        Settings {
            tolerance: self.tolerance,
            step: self.step,
        }
    }

    /// The coarser companion that verifies it: twice the step, or a looser tolerance
    /// (`POLICY.companion_looser`, `TAYLOR.companion_looser` for the series).
    #[must_use]
    pub fn companion(&self) -> Settings {
        companion_of(self.method, self.tolerance, self.step)
    }
}

/// The coarser companion of a run of `method` with these settings.
fn companion_of(method: Method, tolerance: f64, step: Option<f64>) -> Settings {
    match step {
        Some(h) => Settings {
            tolerance,
            step: Some(2.0 * h),
        },
        None => Settings {
            tolerance: super::policy::of(method).companion(tolerance),
            step: None,
        },
    }
}

/// The averaged models' errors as measured by the probes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ModelProbe {
    /// The two probe stiffnesses.
    pub k: [f64; 2],
    /// The largest difference, full model against [`AVERAGED`] (`averaged3`), at each.
    pub gap: [f64; 2],
    /// The same against `averaged2`, from the same full runs: at large `k` its O(k⁻²) error is
    /// far below the tolerance ([`SECOND_ORDER_MODEL_SHARE`]), and a run costs half of
    /// `averaged3`'s.
    pub gap2: [f64; 2],
}

impl ModelProbe {
    /// The measured slope, clamped to `[0.5, MODEL_ORDER]` (`MODEL_ORDER` where the gaps are at
    /// the floor).
    #[must_use]
    pub fn slope(&self) -> f64 {
        let [lo, hi] = self.gap;
        if hi < 1e-12 {
            return MODEL_ORDER;
        }
        let s = (lo / hi).ln() / (self.k[1] / self.k[0]).ln();
        if s.is_finite() {
            s.clamp(0.5, MODEL_ORDER)
        } else {
            0.5
        }
    }

    /// The measured slope, unclamped (NaN or infinite when a gap is not finite).
    #[must_use]
    pub fn raw_slope(&self) -> f64 {
        (self.gap[0] / self.gap[1]).ln() / (self.k[1] / self.k[0]).ln()
    }

    /// The model error predicted at `k ≥ k_hi`, with the safety factor.
    #[must_use]
    pub fn predict(&self, k: f64) -> f64 {
        if !self.gap[1].is_finite() {
            return f64::INFINITY;
        }
        PROBE_SAFETY * self.gap[1] * (self.k[1] / k).min(1.0).powf(self.slope())
    }

    /// `averaged2`'s measured slope, clamped to `[0.5, 2]` (its order; 2 where the gaps are at
    /// the floor).
    #[must_use]
    pub fn slope2(&self) -> f64 {
        let [lo, hi] = self.gap2;
        if hi < 1e-12 {
            return 2.0;
        }
        let s = (lo / hi).ln() / (self.k[1] / self.k[0]).ln();
        if s.is_finite() {
            s.clamp(0.5, 2.0)
        } else {
            0.5
        }
    }

    /// `averaged2`'s model error predicted at `k ≥ k_hi` as [`ModelProbe::predict`] predicts
    /// `averaged3`'s, with [`ModelProbe::slope2`].
    #[must_use]
    pub fn predict2(&self, k: f64) -> f64 {
        if !self.gap2[1].is_finite() {
            return f64::INFINITY;
        }
        PROBE_SAFETY * self.gap2[1] * (self.k[1] / k).min(1.0).powf(self.slope2())
    }
}

/// The stiffnesses `[k_lo, k_hi]` at which the averaged model's error is probed: the smallest
/// where the expansion is valid for this start (`|α̇| (1 + |c|)/ω ≤ 0.2` at the slowest fast
/// frequency, `θ √g / (iz k) ≤ 0.02`), at least 100, and four times that.
#[must_use]
pub fn probe_stiffnesses(problem: &Problem) -> [f64; 2] {
    let p = problem.params();
    let eff = Effective::new(problem);
    let spin = eff.spin_scale();
    let g_max = p.ix.max(p.iy);
    let c_max = (p.iy - p.ix).abs() / (4.0 * p.ix.min(p.iy));
    let from_spin = g_max * (spin * (1.0 + c_max) / PROBE_VALIDITY).powi(2);
    let from_theta = 50.0 * eff.theta() * g_max.sqrt() / p.iz;
    let k_lo = from_spin.max(from_theta).max(100.0);
    [k_lo, 4.0 * k_lo]
}

/// Predicted seconds of the two probes (full and averaged model at each stiffness); none
/// where the averaged model is exact ([`averaged_is_exact`]).
///
/// # Panics
/// Never: the probe stiffnesses are positive and finite.
#[must_use]
pub fn probes_cost(problem: &Problem, t_end: f64) -> f64 {
    if averaged_is_exact(problem) {
        return 0.0;
    }
    probe_stiffnesses(problem)
        .iter()
        .map(|&k| {
            let probe = probe_problem(problem, k);
            cost_seconds(
                &probe,
                &Asked::new(PROBE_FULL_METHOD, PROBE_FULL_TOLERANCE, None, t_end),
            ) + cost_seconds(&probe, &Asked::new(AVERAGED, PROBE_TOLERANCE, None, t_end))
                + cost_seconds(
                    &probe,
                    &Asked::new(Method::Averaged2, PROBE_TOLERANCE, None, t_end),
                )
        })
        .sum()
}

/// Whether the averaged model is the exact motion: a body with `ix = iy` or no fast action,
/// where every correction vanishes ([`super::averaged::expansion_parameter`] is 0). No probe is
/// needed there, and its model error is 0.
#[must_use]
pub fn averaged_is_exact(problem: &Problem) -> bool {
    super::averaged::expansion_parameter(problem) == 0.0
}

/// Whether `auto` considers the averaged model for this problem at all: exact, or `k` well
/// above the probes and resolving predicted dearer than probing.
#[must_use]
pub fn considers_averaged(problem: &Problem, tolerance: f64, t_end: f64) -> bool {
    if averaged_is_exact(problem) {
        return true;
    }
    let k_hi = probe_stiffnesses(problem)[1];
    problem.params().k >= AVERAGED_MIN_RATIO * k_hi
        && best_resolved(problem, tolerance, t_end).predicted_seconds > probes_cost(problem, t_end)
}

/// Measures the averaged model's error at the probe stiffnesses (each probe once per process:
/// [`memo`]), climbing a rung (both ×4) while
/// the measurement says the probes are not yet in the averaging's range (the full motion and the
/// averaged one count different reversals, or the error decays slower than `1/k`) and `k` is far
/// enough above the next rung (at most [`PROBE_RUNGS`] rungs).
///
/// # Errors
/// [`StepError::Cancelled`] when `go_on` says stop.
pub fn probe_averaged(
    problem: &Problem,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<ModelProbe, StepError> {
    let mut k = probe_stiffnesses(problem);
    let mut rung = 0;
    loop {
        // The two stiffnesses' probes are independent: side by side where there are two cores.
        let there = *problem;
        let (high, low) = fork::both(
            go_on,
            |go_on| probe_gap(problem, k[1], t_end, go_on),
            move |go_on| probe_gap(&there, k[0], t_end, go_on),
        );
        let ([gap_lo, gap2_lo], [gap_hi, gap2_hi]) = (low?, high?);
        let (gap, gap2) = ([gap_lo, gap_hi], [gap2_lo, gap2_hi]);
        let probe = ModelProbe { k, gap, gap2 };
        let settled = gap[1].is_finite() && (gap[1] < 1e-12 || probe.raw_slope() >= 1.0);
        rung += 1;
        if settled || rung == PROBE_RUNGS || problem.params().k < AVERAGED_MIN_RATIO * 16.0 * k[1] {
            return Ok(probe);
        }
        k = [4.0 * k[0], 4.0 * k[1]];
    }
}

/// The start at stiffness `k` that the averaging sees as the same: `γ0` scaled by
/// `sqrt(k_problem / k)`, which keeps the fast action, its phase and `θ` (the family the note's
/// error constants are measured on, its cases C and D). A tilt kept fixed instead would carry
/// a fast energy `½ k γ0²` that changes with `k`: another motion.
///
/// # Panics
/// When `k` is not finite and positive (callers pass the probe stiffnesses).
#[must_use]
pub fn probe_problem(problem: &Problem, k: f64) -> Problem {
    let mut start = *problem.start();
    start.gamma *= (problem.params().k / k).sqrt();
    Problem::new(
        super::params::Params {
            k,
            ..*problem.params()
        },
        start,
    )
    .expect("probe k is valid")
}

/// The gaps of `averaged3` and `averaged2` to the full model at the probe stiffness `k`.
fn probe_gap(
    problem: &Problem,
    k: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<memo::Gaps, StepError> {
    let probe = probe_problem(problem, k);
    let key = memo::key(&probe, t_end);
    if let Some(gaps) = memo::read(&key) {
        return Ok(gaps);
    }
    let spec = |method, tolerance| RunSpec {
        method,
        tolerance,
        step: None,
        t_end,
        samples: PROBE_SAMPLES,
        monitor_energy: false,
    };
    let full = match run_cancellable(
        &probe,
        &spec(PROBE_FULL_METHOD, PROBE_FULL_TOLERANCE),
        go_on,
    ) {
        Err(e @ StepError::Cancelled { .. }) => return Err(e),
        full => full.ok(),
    };
    let mut gap_of = |method| -> Result<f64, StepError> {
        let averaged = match run_cancellable(&probe, &spec(method, PROBE_TOLERANCE), go_on) {
            Err(e @ StepError::Cancelled { .. }) => return Err(e),
            averaged => averaged.ok(),
        };
        Ok(match (&full, averaged) {
            (Some(a), Some(b)) => {
                let mut d = difference(a, &b);
                for (x, y) in a.samples.iter().zip(&b.samples) {
                    d = d
                        .max((x.state[1] - y.state[1]).abs())
                        .max((x.state[3] - y.state[3]).abs());
                }
                d
            }
            _ => f64::INFINITY,
        })
    };
    let gaps = [gap_of(AVERAGED)?, gap_of(Method::Averaged2)?];
    memo::keep(key, gaps);
    Ok(gaps)
}

/// The cheapest plan that resolves the fast motion (taylor, dop853 or blanes-moan4) among those
/// whose coarser companion should still meet `tolerance` (or, when none can, the most accurate).
///
/// # Panics
/// Never: there are always three candidates.
#[must_use]
pub fn best_resolved(problem: &Problem, tolerance: f64, t_end: f64) -> Plan {
    let plans = resolved_plans(problem, tolerance, t_end);
    let meeting = plans.iter().filter(|p| p.predicted_error <= tolerance);
    meeting
        .min_by(|a, b| a.predicted_seconds.total_cmp(&b.predicted_seconds))
        .or_else(|| {
            plans
                .iter()
                .min_by(|a, b| a.predicted_error.total_cmp(&b.predicted_error))
        })
        .expect("three candidates")
        .clone()
}

fn resolved_plans(problem: &Problem, tolerance: f64, t_end: f64) -> [Plan; 3] {
    let nu = fastest_rate(problem);
    let periods = nu * t_end / std::f64::consts::TAU;
    let (taylor_local, taylor_error) = taylor_local(tolerance, periods);
    let taylor_steps = super::budget::taylor_steps(taylor_local, periods);
    let taylor = Plan {
        method: Method::Taylor,
        tolerance: taylor_local,
        step: None,
        predicted_error: taylor_error + round_off(problem, taylor_steps, t_end),
        predicted_seconds: with_companion(
            problem,
            &Asked::new(Method::Taylor, taylor_local, None, t_end),
        ),
        reason: "resolved Taylor series, verified by a companion 1024x looser".to_owned(),
    };
    let (local, dop_error) = dop853_local(tolerance, periods);
    // Accepted steps: 12 evaluations each.
    let dop_steps = dop853_evaluations(local, periods) / 12.0;
    let dop_error = dop_error + round_off(problem, dop_steps, t_end);
    let dop = Plan {
        method: Method::Dop853,
        tolerance: local,
        step: None,
        predicted_error: dop_error,
        predicted_seconds: with_companion(problem, &Asked::new(Method::Dop853, local, None, t_end)),
        reason: "resolved adaptive integration".to_owned(),
    };
    // The companion at 2h should meet the tolerance: error(2h) ≤ tolerance / 2.
    let per_time = tolerance / (2.0 * t_end.max(1e-300));
    let h_companion = (per_time / blanes_moan_rate(problem)).powf(0.25);
    let h = (0.5 * h_companion).min(BLANES_MOAN_MAX_NU_H / nu);
    let bm = Plan {
        method: Method::BlanesMoan4,
        tolerance,
        step: Some(h),
        predicted_error: blanes_moan_error(problem, 2.0 * h, t_end)
            + conditioned_round_off(t_end / h, 1.0)
            + splitting_drift(t_end / h),
        predicted_seconds: with_companion(
            problem,
            &Asked::new(Method::BlanesMoan4, tolerance, Some(h), t_end),
        ),
        reason: format!("resolved exact-flow splitting at ν·h = {:.2}", nu * h),
    };
    [dop, bm, taylor]
}

/// The drift a fixed-step splitting's rounding builds over `steps` steps, before the start's
/// conditioning is known: the exact fast rotation by a nearly constant small angle rounds its
/// cosine the same way at every step, so the rounding adds up linearly, `ε · steps` (measured on
/// a body with `iy/ix = 1000` at `k = 1e4`, started at `α = 1.5`: `ν h = 5e-5`, 6.3e7 steps, the
/// run and its companion at `2h` differed by 4e-7 where the series at 1e-14 agrees with DOP853
/// to 1e-11; 3.2e7 steps erred by 1.6e-8). Not in the measured floor: an estimate reads it.
fn splitting_drift(steps: f64) -> f64 {
    f64::EPSILON * steps
}

fn blanes_moan_error(problem: &Problem, h: f64, t_end: f64) -> f64 {
    blanes_moan_rate(problem) * h.powi(4) * t_end
}

/// `blanes-moan4`'s error per unit time and per `h⁴`.
fn blanes_moan_rate(problem: &Problem) -> f64 {
    let p = problem.params();
    let nu = fastest_rate(problem);
    let g_min = p.ix.min(p.iy);
    let c_max = (p.iy - p.ix).abs() / (4.0 * g_min);
    C_BM * Effective::new(problem).spin_scale().powf(2.5) * c_max.powi(4) * nu * nu / g_min
        + C_FAST * nu.powi(4)
}

/// DOP853's local tolerance for `tolerance` over `periods` fast periods, so that its companion
/// still meets it, and the error the companion is then predicted to have (above `tolerance`
/// when the local tolerance would have to go below the clamp).
fn dop853_local(tolerance: f64, periods: f64) -> (f64, f64) {
    let growth = DOP853_GROWTH * periods.max(20.0);
    let wanted = tolerance / (2.0 * POLICY.companion_error * growth);
    let local = wanted.max(POLICY.tightest);
    (local, 0.5 * tolerance * local / wanted)
}

/// The series' local tolerance for `tolerance` over `periods` fast periods: its companion,
/// `TAYLOR.companion_looser` times looser, should still meet it. With the error the companion
/// is then predicted to have (what the estimate will read: above `tolerance` when the run's
/// tolerance would have to go below the clamp).
fn taylor_local(tolerance: f64, periods: f64) -> (f64, f64) {
    let growth = TAYLOR_GROWTH * periods.max(20.0);
    let companion = tolerance / (2.0 * growth);
    let local = (companion / TAYLOR.companion_looser).max(POLICY.tightest);
    (
        local,
        0.5 * tolerance * local * TAYLOR.companion_looser / companion,
    )
}

/// The averaged model's local tolerance for the integration share `share` of the tolerance.
fn averaged_local(share: f64, t_end: f64) -> f64 {
    let growth = AVERAGED_GROWTH * (t_end / 30.0).max(1.0);
    (share / (2.0 * POLICY.companion_error * growth)).max(POLICY.tightest)
}

fn with_companion(problem: &Problem, ask: &Asked) -> f64 {
    let (method, tolerance, step, t_end) = (ask.method, ask.tolerance, ask.step, ask.t_end);
    let c = companion_of(method, tolerance, step);
    cost_seconds(problem, &Asked::new(method, tolerance, step, t_end))
        + cost_seconds(problem, &Asked::new(method, c.tolerance, c.step, t_end))
}

/// What [`plan_cancellable`] decided: the plan, the probed model error it carries (0 for a
/// resolved plan) and the probes, when they ran.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Decision {
    /// The plan.
    pub plan: Plan,
    /// The averaged model's predicted error at this `k` (0 unless the plan is the averaged model).
    pub model_error: f64,
    /// The probes, when `k` called for them.
    pub probe: Option<ModelProbe>,
}

/// Chooses the method for `problem` over `[0, t_end]` at `tolerance` (no verification).
///
/// # Errors
/// [`StepError::Cancelled`] when `go_on` says stop during a probe.
pub fn plan_cancellable(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Decision, StepError> {
    let resolved = best_resolved(problem, tolerance, t_end);
    if !considers_averaged(problem, tolerance, t_end) {
        return Ok(Decision {
            plan: resolved,
            model_error: 0.0,
            probe: None,
        });
    }
    let probe = if averaged_is_exact(problem) {
        None
    } else {
        Some(probe_averaged(problem, t_end, go_on)?)
    };
    let model_error = probe.map_or(0.0, |p| p.predict(problem.params().k));
    let averaged = averaged_plan(
        problem,
        AVERAGED,
        model_error,
        tolerance,
        t_end,
        probe.map_or_else(
            || "the averaged model is exact here (ix = iy, or no fast action)".to_owned(),
            |probe| {
                format!(
                    "k large enough: the averaged model's error, probed at k = {:.0} and {:.0} \
                     (slope {:.2}), scales to {model_error:.1e}",
                    probe.k[0],
                    probe.k[1],
                    probe.slope()
                )
            },
        ),
    );
    // `averaged2` where its model error is a small share of the tolerance, when it is cheaper.
    let second = probe.and_then(|probe| {
        let error2 = probe.predict2(problem.params().k);
        (error2 <= SECOND_ORDER_MODEL_SHARE * tolerance).then(|| {
            let reason = format!(
                "k large enough: the second-order averaged model's error, probed at k = {:.0} \
                 and {:.0} (slope {:.2}), scales to {error2:.1e}",
                probe.k[0],
                probe.k[1],
                probe.slope2()
            );
            let plan = averaged_plan(problem, Method::Averaged2, error2, tolerance, t_end, reason);
            (plan, error2)
        })
    });
    let (averaged, model_error) = match second {
        Some((plan, error2)) if plan.predicted_seconds < averaged.predicted_seconds => {
            (plan, error2)
        }
        _ => (averaged, model_error),
    };
    let meets = |p: &Plan| p.predicted_error <= tolerance;
    let take_averaged = match (meets(&averaged), meets(&resolved)) {
        (true, true) => averaged.predicted_seconds < resolved.predicted_seconds,
        (true, false) => true,
        (false, true) => false,
        // Neither can: the more accurate.
        (false, false) => averaged.predicted_error < resolved.predicted_error,
    };
    if take_averaged {
        return Ok(Decision {
            plan: averaged,
            model_error,
            probe,
        });
    }
    let mut plan = resolved;
    let _ = write!(
        plan.reason,
        "; the averaged model's probed error here is {model_error:.1e}"
    );
    Ok(Decision {
        plan,
        model_error: 0.0,
        probe,
    })
}

/// An averaged model's plan with its probed `model_error`: the integration gets what the model
/// error leaves of the tolerance, at least half of it.
fn averaged_plan(
    problem: &Problem,
    method: Method,
    model_error: f64,
    tolerance: f64,
    t_end: f64,
    reason: String,
) -> Plan {
    let share = (tolerance - model_error).max(0.5 * tolerance);
    let local = averaged_local(share, t_end);
    Plan {
        method,
        tolerance: local,
        step: None,
        predicted_error: model_error + 0.5 * share,
        predicted_seconds: with_companion(problem, &Asked::new(method, local, None, t_end)),
        reason,
    }
}

/// Chooses the method for `problem` (see [`plan_cancellable`]), never cancelled.
#[must_use]
pub fn plan(problem: &Problem, tolerance: f64, t_end: f64) -> Plan {
    plan_cancellable(problem, tolerance, t_end, &mut |_| true)
        .map_or_else(|_| best_resolved(problem, tolerance, t_end), |d| d.plan)
}

/// A run chosen by `auto`, with its error estimate.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verified {
    /// The plan finally run (after refinements).
    pub plan: Plan,
    /// Its result.
    pub result: RunResult,
    /// Estimated error of `α(T)`, `α̇(T)` and the reversal times (the largest), model error
    /// and round-off floor included.
    pub error_estimate: f64,
    /// Whether `error_estimate` meets the tolerance.
    pub met: bool,
    /// Why not, when it does not.
    pub shortfall: Option<Shortfall>,
    /// The averaged model's probed error included in the estimate (0 for a resolved run).
    pub model_error: f64,
    /// How many times the first plan had to be refined.
    pub refinements: u32,
    /// The start's measured condition numbers, which scale the round-off floor in the
    /// estimate.
    pub condition: Conditioning,
    /// The round-off floors in `error_estimate` (the phase's and the start's conditioned
    /// one): where they alone pass the tolerance, `auto` says `met = false` after its first
    /// run, with [`Shortfall::Floor`].
    pub round_off_floor: f64,
    /// The settings of the returned run: integrating `plan.method` with these gives `result`
    /// bit for bit, which is how the explorer shows exactly what `simulate` reports.
    pub run_settings: Settings,
}

/// Plans, runs and verifies (see the module documentation).
///
/// # Errors
/// When an integration fails.
pub fn run_auto(
    problem: &Problem,
    tolerance: f64,
    t_end: f64,
    samples: usize,
    monitor_energy: bool,
) -> Result<Verified, StepError> {
    run_auto_cancellable(
        problem,
        &RunSpec {
            method: Method::Auto,
            tolerance,
            step: None,
            t_end,
            samples,
            monitor_energy,
        },
        f64::INFINITY,
        &mut |_| true,
    )
}

/// [`run_auto`] for `spec` (its `method` and `step` are ignored), within a work `budget` in
/// predicted seconds (see [`super::budget`]), asking `go_on` every few hundred steps whether
/// to continue.
///
/// # Errors
/// When an integration fails, [`StepError::OverBudget`] when the probes or the first plan are
/// predicted over `budget` (later refinements past it are not run: the result says
/// `met = false`), or [`StepError::Cancelled`] when `go_on` says stop.
///
/// # Panics
/// Never: a refinement exists whenever the loop goes on.
pub fn run_auto_cancellable(
    problem: &Problem,
    spec: &RunSpec,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Verified, StepError> {
    let (tolerance, t_end) = (spec.tolerance, spec.t_end);
    let probes = if considers_averaged(problem, tolerance, t_end) {
        probes_cost(problem, t_end)
    } else {
        0.0
    };
    over_budget("auto's probing of the averaged model", probes, budget)?;
    let Decision {
        plan, model_error, ..
    } = plan_cancellable(problem, tolerance, t_end, go_on)?;
    let mut candidate = Auto {
        problem,
        spec,
        model_error,
        measured: None,
    };
    let spent = probes + candidate.cost(&plan);
    over_budget(
        &format!("auto's run and verification with {}", plan.method),
        spent,
        budget,
    )?;
    // The rounds may spend what is left of the allowance after the probes.
    let allowance = budget.min(AUTO_SECONDS).max(spent);
    let v = verify(
        &POLICY,
        &mut candidate,
        plan,
        tolerance,
        allowance - probes,
        go_on,
    )?;
    let (reading, ran) = v.best;
    Ok(Verified {
        run_settings: reading.plan.settings(),
        plan: reading.plan,
        result: ran.result,
        error_estimate: reading.estimate,
        met: v.shortfall.is_none(),
        shortfall: v.shortfall,
        model_error: ran.model_error,
        refinements: u32::try_from(v.refinements).unwrap_or(u32::MAX),
        condition: ran.condition,
        round_off_floor: reading.floor,
    })
}

/// The rattleback's candidate for [`verify`]: a plan (any method, a tolerance or a step), the
/// averaged model's probed error it carries, and the start's condition numbers once measured
/// (again after a change from the averaged model to the full motion).
struct Auto<'a> {
    problem: &'a Problem,
    spec: &'a RunSpec,
    model_error: f64,
    measured: Option<Conditioning>,
}

/// What `auto` keeps of a round.
struct Ran {
    result: RunResult,
    condition: Conditioning,
    model_error: f64,
}

impl Candidate for Auto<'_> {
    type Plan = Plan;
    type Run = Ran;
    fn round(
        &mut self,
        plan: &Plan,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Outcome<Ran>, StepError> {
        let (result, condition, Checked { estimate, floor }) = run_and_check(
            self.problem,
            self.spec,
            plan,
            self.model_error,
            self.measured,
            go_on,
        )?;
        self.measured = Some(condition);
        Ok(Outcome {
            run: Ran {
                result,
                condition,
                model_error: self.model_error,
            },
            measured: estimate,
            floor,
        })
    }
    fn cost(&self, plan: &Plan) -> f64 {
        plan.predicted_seconds
            + if self.measured.is_none() {
                conditioning_cost(self.problem, self.spec.t_end, plan)
            } else {
                0.0
            }
    }
    fn refine(&mut self, plan: &Plan, estimate: f64, tolerance: f64) -> Result<Plan, Shortfall> {
        if plan.method.is_averaged()
            && plan.tolerance <= POLICY.tightest
            && self.model_error < 0.5 * tolerance
        {
            return Err(Shortfall::Clamped);
        }
        let t_end = self.spec.t_end;
        let next = refine(
            self.problem,
            plan,
            self.model_error,
            estimate,
            tolerance,
            t_end,
        )
        .ok_or(if plan.method.is_averaged() {
            Shortfall::Model
        } else {
            Shortfall::Clamped
        })?;
        if next.method != plan.method {
            // A new method carries no probed model error; leaving the averaged model, the start's
            // conditioning is measured again on the full motion, as a first resolved plan's is.
            self.model_error = 0.0;
            if plan.method.is_averaged() && !next.method.is_averaged() {
                self.measured = None;
            }
        }
        Ok(next)
    }
    fn continues(&self, plan: &Plan, next: &Plan) -> bool {
        plan.method == next.method
    }
    fn stalls(&self, plan: &Plan, _: &Policy) -> usize {
        super::policy::of(plan.method).stalls
    }
}

/// Runs `plan` as `spec` asks (samples, energy) and, beside it ([`fork::both`]: on another core
/// where the program has one), its coarser companion, after the start's condition numbers when
/// they are not `measured` yet (a series' companion is then the conditioning's base run); the
/// run, the condition numbers and the run's error estimate (their difference, the model error,
/// the round-off floors, the second conditioned by `kappa`), with the floors' part.
fn run_and_check(
    problem: &Problem,
    spec: &RunSpec,
    plan: &Plan,
    model_error: f64,
    measured: Option<Conditioning>,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunResult, Conditioning, Checked), StepError> {
    let run_spec = RunSpec {
        method: plan.method,
        tolerance: plan.tolerance,
        step: plan.step,
        ..*spec
    };
    let companion = plan.companion();
    let check_spec = RunSpec {
        tolerance: companion.tolerance,
        step: companion.step,
        samples: 0,
        monitor_energy: false,
        ..run_spec
    };
    let price = |s: &RunSpec| cost_seconds(problem, &s.asked());
    // Far in (an averaged plan at or above the start's conditioning stiffness), the reading of
    // the start there, kept across k, bounds its condition numbers where the floor it gives is
    // small: the verification is then the companion alone.
    let mut measured = measured;
    let mut family = None;
    if measured.is_none()
        && let Some(start) = conditioning_family(problem, plan)
    {
        match family_bound(&start, spec.t_end, false, go_on)? {
            Some(bound) => {
                let kappa = bound.at_angle(alpha_bound(problem, spec.t_end));
                if bound_serves(
                    &bound,
                    kappa,
                    generous_steps(problem, plan, spec.t_end),
                    spec.tolerance,
                ) {
                    measured = Some(bound);
                }
            }
            // Not read yet: read beside the run (and kept), in place of the reading at k.
            None => family = Some(start),
        }
    }
    let verifying = price(&check_spec)
        + if measured.is_some() {
            0.0
        } else {
            measuring_cost(problem, spec.t_end, plan)
        };
    let (here, there, plan_there) = (*problem, *problem, plan.clone());
    let (result, verification) = fork::dearer_here(
        go_on,
        (
            move |go_on: fork::GoOn<'_>| run_cancellable(&here, &run_spec, go_on),
            price(&run_spec),
        ),
        (
            move |go_on: fork::GoOn<'_>| -> Result<(Conditioning, RunResult), StepError> {
                let (kappa, made) = match (measured, family) {
                    (Some(kappa), _) => (kappa, None),
                    (None, Some(start)) => {
                        let bound = family_bound(&start, check_spec.t_end, true, go_on)?;
                        (bound.expect("computed when not kept"), None)
                    }
                    (None, None) => {
                        measure_conditioning(&there, check_spec.t_end, &plan_there, go_on)?
                    }
                };
                let check = match made {
                    Some(made) if made.spec == check_spec => made.result,
                    _ => run_cancellable(&there, &check_spec, go_on)?,
                };
                Ok((kappa, check))
            },
            verifying,
        ),
    );
    // The run's failure first (a cancellation stops both), then the verification's.
    let result = result?;
    let (mut kappa, check) = verification?;
    let steps = result.stats.steps as f64;
    if kappa.margin > 1.0
        && !bound_serves(
            &kappa,
            kappa.of_run(problem, &result),
            steps,
            spec.tolerance,
        )
    {
        // The bound would weigh on the estimate (more steps than predicted, a rotating start's
        // angle, a tight tolerance), or the start may be ill-conditioned: it is measured at its
        // own k after all.
        kappa = measure_conditioning(problem, spec.t_end, plan, go_on)?.0;
    }
    let floor = phase_round_off(problem, plan, steps, spec.t_end)
        + conditioned_round_off(steps, kappa.of_run(problem, &result));
    let estimate = difference(&result, &check) + model_error + floor;
    Ok((result, kappa, Checked { estimate, floor }))
}

/// A run's estimate, and the part of it that rounding alone sets.
#[derive(Clone, Copy, Debug)]
struct Checked {
    estimate: f64,
    /// The round-off floors in `estimate` (the phase's and the start's conditioned one): no
    /// refinement lowers them, since a refinement takes more steps.
    floor: f64,
}

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
fn conditioning_spec(problem: &Problem, t_end: f64, plan: &Plan, stage: Stage) -> RunSpec {
    let slow = |tolerance| RunSpec {
        method: CONDITIONING_MODEL,
        tolerance,
        step: None,
        t_end,
        samples: 0,
        monitor_energy: false,
    };
    if super::averaged::expansion_parameter(problem) <= CONDITIONING_AVERAGED_LIMIT {
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
enum Stage {
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
    fn at_angle(&self, alpha: f64) -> f64 {
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
struct Made {
    spec: RunSpec,
    result: RunResult,
}

/// [`conditioning`], with the base run it measured from (none at the equilibrium).
fn measure_conditioning(
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
fn conditioning_cost(problem: &Problem, t_end: f64, plan: &Plan) -> f64 {
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
fn measuring_cost(problem: &Problem, t_end: f64, plan: &Plan) -> f64 {
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
        super::averaged::expansion_parameter(&probe_problem(problem, k)) <= CONDITIONING_KEPT_X
    })
}

/// The start of `problem`'s family at its conditioning stiffness, where an averaged `plan` runs
/// above it (its condition numbers may then be bounded by that start's). None where the averaged
/// model is the exact motion (`ix = iy`: no ripple, and the start is measured at its own `k`).
fn conditioning_family(problem: &Problem, plan: &Plan) -> Option<Problem> {
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
fn family_bound(
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
fn bound_serves(bound: &Conditioning, kappa: f64, steps: f64, tolerance: f64) -> bool {
    bound.rate.max(bound.angle) <= CONDITIONING_RECHECK
        && conditioned_round_off(steps, kappa) <= CONDITIONING_KEPT_SHARE * tolerance
}

/// The largest `|α|` a start may reach over `[0, t_end]`, a priori: its limit's turning points
/// (and half a radian for the corrections), or what its spin covers in `t_end` when it rotates.
/// Only a kept bound's weighing before the run uses it; the run's own `α` decides after it.
fn alpha_bound(problem: &Problem, t_end: f64) -> f64 {
    let eff = Effective::new(problem);
    let start = problem.start().alpha.abs();
    match eff.turning_points() {
        Some((low, high)) => start.max(low.abs()).max(high.abs()) + 0.5,
        None => start + eff.spin_scale() * t_end,
    }
}

/// Steps an averaged `plan` is predicted to take, fourfold (where a kept bound is weighed before
/// the run).
fn generous_steps(problem: &Problem, plan: &Plan, t_end: f64) -> f64 {
    let periods = slow_rate(problem).max(1e-3) * t_end / std::f64::consts::TAU;
    4.0 * dop853_evaluations(plan.tolerance, periods) / 12.0
}

/// Nudges the energy's first non-zero carrier: the spin rate, else the tilt rate, else the tilt.
fn nudge_rate(s: &mut super::params::Start, nudge: f64) {
    if s.alpha_dot != 0.0 {
        s.alpha_dot *= 1.0 + nudge;
    } else if s.gamma_dot != 0.0 {
        s.gamma_dot *= 1.0 + nudge;
    } else {
        s.gamma *= 1.0 + nudge;
    }
}

/// Nudges the spin angle.
fn nudge_angle(s: &mut super::params::Start, nudge: f64) {
    s.alpha += nudge;
}

/// [`conditioning`]'s three runs with `spec`, and the first (the start as it is). On the slow
/// model the three starts are integrated together, the nudged ones on the first one's steps
/// ([`together`]): one run, and no truncation error left in their differences.
fn condition_numbers(
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
        let moved = |how: fn(&mut super::params::Start, f64)| {
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
fn sensitivity(
    problem: &Problem,
    spec: &RunSpec,
    base: &RunResult,
    go_on: &mut dyn FnMut(f64) -> bool,
    nudge_start: impl Fn(&mut super::params::Start, f64),
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

/// The round-off floor of a run of `steps` steps from a start of condition number `kappa`
/// ([`Conditioning::of_run`]): a few roundings per step, each amplified by at most `κ` by the
/// end, adding up like a random walk, `CONDITIONED_GAIN · ε · √steps · max(κ, 1)`.
#[must_use]
pub fn conditioned_round_off(steps: f64, kappa: f64) -> f64 {
    CONDITIONED_GAIN * f64::EPSILON * steps.max(1.0).sqrt() * kappa.max(1.0)
}

/// The phase's round-off floor in an estimate: [`round_off`] for the adaptive methods; nothing
/// for the fixed-step ones, which now add their steps to the time with a compensated sum
/// ([`crate::physics::method::TimeSum`]): what the floor was fitted to (their reversal times
/// drifting at 10⁵ steps and more) was that sum's rounding, and on the held-out starts of
/// `rattleback_honesty.toml` and `averaged.toml` every estimate still bounds its error without
/// it (`tests/it/honesty.rs`, `tests/it/auto_honest.rs`).
fn phase_round_off(problem: &Problem, plan: &Plan, steps: f64, t_end: f64) -> f64 {
    if plan.step.is_some() {
        0.0
    } else {
        round_off(problem, steps, t_end)
    }
}

/// The round-off floor of the phase for a run of `steps` steps over `[0, t_end]` (the planner's
/// whole prediction of round-off, before the start's conditioning is measured): a random walk
/// of one rounding per step (`ε √N`) in the energy, which the slow phase integrates, so that
/// reversal times (which feel it most: a crossing of `α̇` moves by `δα̇ / α̈`) drift like
/// `(s T)^{3/2}` in slow time (`s` the slow rate), times [`ROUND_OFF_GAIN`].
#[must_use]
pub fn round_off(problem: &Problem, steps: f64, t_end: f64) -> f64 {
    ROUND_OFF_GAIN
        * f64::EPSILON
        * steps.max(1.0).sqrt()
        * (slow_rate(problem) * t_end).max(1.0).powf(1.5)
}

fn over_budget(what: &str, predicted: f64, budget: f64) -> Result<(), StepError> {
    crate::physics::budget::check(predicted, budget).map_err(|over| StepError::OverBudget {
        what: what.to_owned(),
        over,
    })
}

/// The largest difference in `α(T)`, `α̇(T)` and reversal times (infinite when the reversal
/// counts differ).
#[must_use]
pub fn difference(a: &RunResult, b: &RunResult) -> f64 {
    if a.reversal_count != b.reversal_count {
        return f64::INFINITY;
    }
    let mut d = (a.final_state[1] - b.final_state[1])
        .abs()
        .max((a.final_state[3] - b.final_state[3]).abs());
    for (x, y) in a.reversals.iter().zip(&b.reversals) {
        d = d.max((x - y).abs());
    }
    d
}

/// The next plan after `plan` missed with `estimate`; `None` when nothing is predicted to do
/// better: the averaged model's own error misses and resolving would not beat it, or DOP853 is
/// at its tightest tolerance and the splitting's round-off floor is no lower.
fn refine(
    problem: &Problem,
    plan: &Plan,
    model_error: f64,
    estimate: f64,
    tolerance: f64,
    t_end: f64,
) -> Option<Plan> {
    if plan.method.is_averaged() && model_error > 0.5 * tolerance {
        let mut resolved = best_resolved(problem, tolerance, t_end);
        if resolved.predicted_error >= estimate {
            return None;
        }
        let _ = write!(
            resolved.reason,
            "; the averaged model missed ({estimate:.1e}), resolved instead"
        );
        return Some(resolved);
    }
    let share = (tolerance - model_error).max(0.1 * tolerance);
    // How far the estimate is over what the integration may spend: at least what the policy's
    // least refinement answers (2: a factor 4), and what its blind one answers when infinite.
    let excess = if estimate.is_finite() {
        ((estimate - model_error).max(0.0) / share).max(0.5 / POLICY.refine)
    } else {
        0.5 / POLICY.blind_refine
    };
    if matches!(plan.method, Method::Dop853 | Method::Taylor)
        && plan.tolerance / (2.0 * excess) < POLICY.tightest
    {
        // DOP853 or the series cannot be tightened that far: the splitting, whose error does not
        // stall at a tolerance clamp, at the step its model asks for this tolerance, then
        // refined as needed.
        let [_, mut bm, _] = resolved_plans(problem, tolerance, t_end);
        if bm.predicted_error >= estimate {
            // Its round-off floor over this horizon is no better than what DOP853 reached.
            return None;
        }
        let _ = write!(
            bm.reason,
            "; {} missed ({estimate:.1e}) at its tightest tolerance, resolved by the splitting instead",
            plan.method
        );
        return Some(bm);
    }
    let mut next = plan.clone();
    if let Some(h) = plan.step {
        let p = f64::from(plan.method.order().max(1));
        next.step = Some(h / (POLICY.step_safety * excess.powf(1.0 / p)));
    } else {
        // Twice the excess (at least 4: the excess is at least 2), at least the series' least
        // refinement for the series.
        let factor = (2.0 * excess).max(super::policy::of(plan.method).refine.recip());
        next.tolerance = (plan.tolerance / factor).max(POLICY.tightest);
    }
    next.predicted_seconds = with_companion(
        problem,
        &Asked::new(next.method, next.tolerance, next.step, t_end),
    );
    next.predicted_error = plan.predicted_error / excess;
    let _ = write!(next.reason, "; refined ×{excess:.1}");
    Some(next)
}
