//! The averaged model's probes: its error measured at two soft stiffnesses and scaled to the
//! asked one, and when it is worth probing at all.
use crate::physics::numerics::elementary::Elementary;

use super::memo;
use crate::physics::method::Asked;

use serde::Serialize;

use super::super::budget::cost_seconds;
use super::super::effective::Effective;
use super::super::params::Problem;
use super::super::run::run_cancellable;
use crate::physics::fork;
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::method::StepError;

use super::super::policy::{
    AVERAGED, AVERAGED_MIN_RATIO, MODEL_ORDER, PROBE_FULL_METHOD, PROBE_FULL_TOLERANCE,
    PROBE_RUNGS, PROBE_SAFETY, PROBE_SAMPLES, PROBE_TOLERANCE, PROBE_VALIDITY,
};
use super::measure::difference;
use super::resolved::best_resolved;

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
    ///
    /// [`SECOND_ORDER_MODEL_SHARE`]: super::SECOND_ORDER_MODEL_SHARE
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
        let s = (lo / hi).e_ln() / (self.k[1] / self.k[0]).e_ln();
        if s.is_finite() {
            s.clamp(0.5, MODEL_ORDER)
        } else {
            0.5
        }
    }

    /// The measured slope, unclamped (NaN or infinite when a gap is not finite).
    #[must_use]
    pub fn raw_slope(&self) -> f64 {
        (self.gap[0] / self.gap[1]).e_ln() / (self.k[1] / self.k[0]).e_ln()
    }

    /// The model error predicted at `k ≥ k_hi`, with the safety factor.
    #[must_use]
    pub fn predict(&self, k: f64) -> f64 {
        if !self.gap[1].is_finite() {
            return f64::INFINITY;
        }
        PROBE_SAFETY * self.gap[1] * (self.k[1] / k).min(1.0).e_powf(self.slope())
    }

    /// `averaged2`'s measured slope, clamped to `[0.5, 2]` (its order; 2 where the gaps are at
    /// the floor).
    #[must_use]
    pub fn slope2(&self) -> f64 {
        let [lo, hi] = self.gap2;
        if hi < 1e-12 {
            return 2.0;
        }
        let s = (lo / hi).e_ln() / (self.k[1] / self.k[0]).e_ln();
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
        PROBE_SAFETY * self.gap2[1] * (self.k[1] / k).min(1.0).e_powf(self.slope2())
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
/// where every correction vanishes ([`super::super::averaged::expansion_parameter`] is 0). No probe is
/// needed there, and its model error is 0.
#[must_use]
pub fn averaged_is_exact(problem: &Problem) -> bool {
    super::super::averaged::expansion_parameter(problem) == 0.0
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
        super::super::params::Params {
            k,
            ..*problem.params()
        },
        start,
    )
    .expect("probe k is valid")
}

/// The gaps of `averaged3` and `averaged2` to the full model at the probe stiffness `k`.
pub(super) fn probe_gap(
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
