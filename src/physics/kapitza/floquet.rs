//! The pendulum's linear stability by Floquet theory (issue 59; docs/charts.md).
//!
//! Linearised about the upright, `θ̈ = (a + (b/ε) cos(t/ε)) θ`; in the fast time `τ = t/ε` this
//! is Mathieu's equation `θ'' + (δ + q cos τ) θ = 0` with `δ = −ε² a`, `q = ε b` (the sign of `q`
//! does not matter: a shift of `τ` by `π`). About the hanging position the sign of the whole
//! coefficient flips: `δ = +ε² a`. The two fundamental solutions, `(θ, θ') = (1, 0)` and
//! `(0, 1)` at `τ = 0`, integrated over one period `2π`, are the monodromy matrix's columns; its
//! determinant is 1 (no damping), so its multipliers are the roots of `λ² − tr λ + 1`: the
//! position is stable when `|tr| < 2`, unstable when `|tr| > 2`.
//!
//! The trace is verified by the one loop (`physics::verify`): DOP853 at a local tolerance
//! against a companion 16× looser, refined until their difference (plus a round-off floor)
//! meets the tolerance. A cell is *decided* when `||tr| − 2|` exceeds that estimate; otherwise it
//! is too close to call at this tolerance, and says so.
//!
//! Kapitza's criterion `b² > 2a` is the limit `ε → 0` of this chart's lower boundary
//! `δ = −q²/2 + 7q⁴/32 + …`; at larger `ε b` the resonance tongues (leaving `δ = n²/4`) bring
//! instability back.
use crate::physics::numerics::elementary::Elementary;

use nalgebra::SVector;

use super::Params;
use crate::physics::fork::GoOn;
use crate::physics::method::StepError;
use crate::physics::numerics::dop853::Dop853;
use crate::physics::verify::{AtTolerance, Policy, Rounds, verify};

/// Which equilibrium is linearised.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Position {
    /// `θ = 0`, the upright (the scene's).
    #[default]
    Upright,
    /// `θ = π`, hanging down.
    Hanging,
}

impl Position {
    /// Its name in outputs and on the command line.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Upright => "upright",
            Self::Hanging => "hanging",
        }
    }
}

/// Mathieu's equation `θ'' + (δ + q cos τ) θ = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mathieu {
    /// `δ`.
    pub delta: f64,
    /// `q`.
    pub q: f64,
}

impl Mathieu {
    /// The DOP853 steps a trace verified to `tolerance` is predicted to take ([`floquet`]'s
    /// whole work: every round's run and its two companions, and the last run), from the
    /// coefficients alone: issue 80's chart prices, cell by cell. A run over the period takes
    /// steps in proportion to the radians of the fastest oscillation, `2π ω`
    /// (`ω = √(|δ| + |q|)`), times DOP853's `l^(-1/8)` at the first local tolerance `l`; how many
    /// rounds the loop then takes depends on `ω` and the tolerance as measured
    /// ([`PRICE_FACTORS`], interpolated).
    #[must_use]
    pub fn price_steps(&self, tolerance: f64) -> f64 {
        let w = (self.delta.abs() + self.q.abs()).sqrt();
        let first = (tolerance * FIRST).clamp(POLICY.tightest, 1e-3);
        let radians = 2.0 * std::f64::consts::PI * w * first.e_powf(-0.125);
        price_factor(w, tolerance) * (radians + PRICE_FIXED_STEPS)
    }

    /// The linearisation of the pendulum `p` about `position`.
    #[must_use]
    pub fn of(p: &Params, position: Position) -> Self {
        let e2a = p.epsilon * p.epsilon * p.a;
        Self {
            delta: match position {
                Position::Upright => -e2a,
                Position::Hanging => e2a,
            },
            q: p.epsilon * p.b,
        }
    }

    /// The monodromy matrix's trace at DOP853's local tolerance `local`, with the steps taken
    /// and the largest entry the fundamental matrix reached (its rounding is relative to it).
    ///
    /// # Errors
    /// A failed step (a coefficient so large the solutions overflow).
    pub fn trace(&self, local: f64) -> Result<(f64, u64, f64), StepError> {
        type S = SVector<f64, 5>;
        let (delta, q) = (self.delta, self.q);
        // (y1, y1', y2, y2', τ): the two fundamental solutions side by side.
        let field = move |y: &S| {
            let c = -(delta + q * y[4].e_cos());
            S::new(y[1], c * y[0], y[3], c * y[2], 1.0)
        };
        let period = 2.0 * std::f64::consts::PI;
        let mut d = Dop853::new(field, 0.0, S::new(1.0, 0.0, 0.0, 1.0, 0.0), local);
        let mut size: f64 = 1.0;
        while d.time() < period {
            d.step(period)?;
            let y = d.state();
            size = size.max(y[0].abs().max(y[1].abs()).max(y[2].abs()).max(y[3].abs()));
        }
        let y = d.state();
        let trace = y[0] + y[3];
        if !trace.is_finite() {
            return Err(StepError::NotFinite {
                what: "the monodromy matrix",
                t: d.time(),
            });
        }
        Ok((trace, d.stats().steps, size))
    }
}

/// The continuous quantity behind a trace's verdict (issue 80, a refined chart's certificate):
/// inside the stable band (`|tr| < 2`) the Floquet angle `θ = acos(tr/2)` in `(0, π)`, its margin
/// the distance to the band's edges `0` and `π`; outside, the Floquet exponent
/// `μ = acosh(|tr|/2)`, signed as the trace (a block holding both signs spans a stable band),
/// its margin `μ`. Both vanish exactly where the answer changes and vary smoothly elsewhere,
/// unlike the trace itself (exponentially large outside the band).
#[must_use]
pub fn certainty(trace: f64) -> Option<crate::physics::chart::Certainty> {
    use crate::physics::chart::Certainty;
    let h = 0.5 * trace;
    if !h.is_finite() {
        return None;
    }
    Some(if h.abs() < 1.0 {
        let theta = h.e_acos();
        Certainty {
            value: theta,
            margin: theta.min(std::f64::consts::PI - theta),
        }
    } else {
        let mu = h.abs().e_acosh();
        Certainty {
            value: mu.copysign(h),
            margin: mu,
        }
    })
}

/// The verification of a trace: the pendulum's run's policy (refined 4× at least, 16× when
/// blind, to 1e-14 at the tightest, five rounds at most, one stall stops it) with a companion
/// 16× looser, and a round-off floor above the tolerance stops it (one period of a smooth
/// linear equation: DOP853 converges cleanly down to rounding, so a stall is the floor).
pub const POLICY: Policy = Policy {
    companion_looser: 16.0,
    companion_error: 14.0,
    floor_stops: true,
    ..super::policy::POLICY
};

/// The estimate is the two runs' difference (plus the floor) times this margin. Measured
/// (issue 59) against 30-digit traces (`scripts/chart_references.py`) on the 96 cells of two coarse
/// charts at tolerances 1e-8, 1e-10 and 1e-12: the error over the bare difference reached 2.9
/// (kapitza-coarse's ε = 0.15 at 1e-10; 0.23 at most on kapitza-upright's ε = 1e-3), where the
/// two runs' errors happen to nearly cancel; 4 covers it (`scripts/floquet_margin.py` measures it
/// again).
pub const MARGIN: f64 = 4.0;

/// The first local tolerance of a trace verified to `tolerance`.
const FIRST: f64 = 0.1;

/// The steps of a verified trace that do not grow with the frequency (each run's start and end).
pub const PRICE_FIXED_STEPS: f64 = 40.0;

/// A verified trace's steps over `2π ω l^(-1/8) + 40`, measured (issue 80) as the mean over
/// 4,500 random cells of the charts `study map` can be asked for (ε from 1e-3 to 0.5, both
/// positions, `a` and `b` over twelve decades, tolerances 1e-6 to 1e-12:
/// `cargo run --release --example chart_price pendulum`): rows `log10 ω` = −1, 0, …, 4, columns
/// `log10 tolerance` = −12, −10, −8, −6. It folds in how many rounds the loop takes: one at
/// high frequencies and tight tolerances, two or three at middling ones.
pub const PRICE_FACTORS: [[f64; 4]; 6] = [
    [1.61, 1.14, 0.83, 0.55],
    [1.41, 1.36, 1.21, 1.05],
    [1.01, 1.74, 1.54, 1.60],
    [0.59, 1.20, 2.06, 1.99],
    [0.65, 0.65, 2.07, 3.62],
    [0.67, 0.67, 2.10, 4.00],
];

/// [`PRICE_FACTORS`] at `ω` and `tolerance`, interpolated linearly in both logarithms (and held
/// beyond the table's edges).
fn price_factor(w: f64, tolerance: f64) -> f64 {
    let at = |x: f64, lo: f64, n: usize| {
        let x = (x - lo).clamp(0.0, (n - 1) as f64);
        let i = (x.floor() as usize).min(n - 2);
        (i, x - i as f64)
    };
    let (i, fi) = at(w.max(1e-300).e_log10(), -1.0, 6);
    let (j, fj) = at(0.5 * tolerance.max(1e-300).e_log10(), -6.0, 4);
    let f = |i: usize, j: usize| PRICE_FACTORS[i][j];
    let lo = f(i, j) * (1.0 - fj) + f(i, j + 1) * fj;
    let hi = f(i + 1, j) * (1.0 - fj) + f(i + 1, j + 1) * fj;
    lo * (1.0 - fi) + hi * fi
}

/// A verified trace.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Floquet {
    /// The monodromy matrix's trace.
    pub trace: f64,
    /// Its estimated error (absolute).
    pub error: f64,
    /// `|tr| < 2`.
    pub stable: bool,
    /// Whether `||tr| − 2|` exceeds the estimate (the verdict is certain at this tolerance).
    pub decided: bool,
    /// DOP853 steps taken in all (every round's runs and companions, and the last run): the
    /// work the cost model ([`Mathieu::price_steps`]) predicts.
    pub steps: u64,
    /// Rounds of the verification loop after the first.
    pub refinements: usize,
}

/// The candidate of the loop: DOP853 over one period at a local tolerance. Differences are
/// relative to `max(1, |tr|/2)` so that a deeply unstable cell (`|tr|` of 1e30) is verified to
/// the same number of digits as one near the boundary.
#[derive(Clone)]
struct Trace(Mathieu, std::sync::Arc<std::sync::atomic::AtomicU64>);

/// The scale of a trace's difference.
fn scale(trace: f64) -> f64 {
    (0.5 * trace.abs()).max(1.0)
}

/// A trace run: the trace, the steps, the largest entry of the matrix, and the trace again at a
/// tolerance [`SECOND_LOOSER`]× looser.
type TraceRun = (f64, u64, f64, f64);

/// The second companion's ratio. With one companion 16× looser, a run and its companion that
/// erred alike cancelled in their difference (issue 66: a trace 5.9e-12 off, estimated 5.6e-12,
/// while the run 4× looser differs by 5e-11): two companions must both cancel to mislead.
const SECOND_LOOSER: f64 = 4.0;

impl AtTolerance for Trace {
    type Result = TraceRun;
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn run(&self, local: f64, _: GoOn<'_>) -> Result<TraceRun, StepError> {
        let (trace, steps, size) = self.0.trace(local)?;
        let (second, second_steps, _) = self.0.trace(local * SECOND_LOOSER)?;
        self.1
            .fetch_add(steps + second_steps, std::sync::atomic::Ordering::Relaxed);
        Ok((trace, steps, size, second))
    }
    fn difference(&self, fine: &TraceRun, coarse: &TraceRun) -> f64 {
        (fine.0 - coarse.0).abs().max((fine.0 - fine.3).abs()) / scale(fine.0)
    }
    fn floor(&self, fine: &TraceRun) -> f64 {
        let steps = fine.1 as f64;
        // Each step rounds the four components once or twice: a few units of rounding a step,
        // each relative to the largest entry the matrix reaches, not to the trace (issue 66: near
        // |tr| = 2 a matrix with entries of 30 rounds 15× more than the trace's size says).
        4.0 * f64::EPSILON * (steps + 1.0) * fine.2 / scale(fine.0)
    }
    fn estimate(&self, measured: f64, _: f64, _: Option<&(f64, f64)>) -> f64 {
        MARGIN * measured
    }
    fn run_cost(&self, local: f64) -> f64 {
        // About 2 µs a step; DOP853's steps grow as local^(-1/8) with the fastest frequency;
        // the second companion's run beside it.
        let w = (self.0.delta.abs() + self.0.q.abs()).sqrt().max(1.0);
        let one = |l: f64| 2e-6 * 8.0 * w * l.e_powf(-0.125);
        one(local) + one(local * SECOND_LOOSER)
    }
}

/// The trace of `m`, verified to `tolerance` (relative to `max(1, |tr|/2)`).
///
/// # Errors
/// A failed step.
pub fn floquet(m: Mathieu, tolerance: f64) -> Result<Floquet, StepError> {
    let mut candidate = Trace(m, std::sync::Arc::default());
    let first = (tolerance * FIRST).clamp(POLICY.tightest, 1e-3);
    // Its best run again: the loop keeps what it measured, not the trace.
    let v = verify(
        &mut candidate,
        Rounds::unbudgeted(first, tolerance),
        &mut |_| true,
    )?;
    let plan = v.best.0.plan;
    let (trace, last, _) = m.trace(plan)?;
    let error = v.best.0.estimate * scale(trace);
    let margin = (trace.abs() - 2.0).abs();
    Ok(Floquet {
        trace,
        error,
        stable: trace.abs() < 2.0,
        decided: margin > error,
        steps: candidate.1.load(std::sync::atomic::Ordering::Relaxed) + last,
        refinements: v.refinements,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_coefficients_give_the_closed_form_trace() {
        // q = 0: θ'' + δθ = 0, tr = 2 cos(2π√δ) for δ > 0 and 2 cosh(2π√−δ) for δ < 0.
        for delta in [0.1, 0.3, 2.0, -0.05, -0.5] {
            let f = floquet(Mathieu { delta, q: 0.0 }, 1e-11).unwrap();
            let exact = if delta > 0.0 {
                2.0 * (2.0 * std::f64::consts::PI * f64::sqrt(delta)).e_cos()
            } else {
                2.0 * (2.0 * std::f64::consts::PI * f64::sqrt(-delta)).e_cosh()
            };
            assert!(
                (f.trace - exact).abs() <= f.error.max(1e-13) * 2.0 + 1e-12,
                "δ {delta}: {} against {exact}, estimate {}",
                f.trace,
                f.error
            );
            assert_eq!(f.stable, exact.abs() < 2.0);
            assert!(f.decided);
        }
    }

    #[test]
    fn the_upright_of_a_shaken_pendulum_is_stable_above_kapitzas_threshold() {
        let p = |b: f64| Params {
            a: 1.0,
            b,
            epsilon: 0.01,
        };
        let above = floquet(Mathieu::of(&p(1.6), Position::Upright), 1e-10).unwrap();
        let below = floquet(Mathieu::of(&p(1.2), Position::Upright), 1e-10).unwrap();
        assert!(above.stable && above.decided, "{above:?}");
        assert!(!below.stable && below.decided, "{below:?}");
        // The hanging position of the same pendulum is stable either way.
        assert!(
            floquet(Mathieu::of(&p(1.2), Position::Hanging), 1e-10)
                .unwrap()
                .stable
        );
    }
}
