//! What a chart's cells are: each scene's chart over its two axes (the pendulum's Floquet
//! chart, the celt's reversal chart) and a cell's verdict. The words a chart is described with
//! and a model's point on it are the scene's own (`Studies::chart`, `Posed::chart_point`).
//! Below `chart`, which dispatches over the scenes; above `output` (the axes).

use super::output::Axis;
use crate::physics::celt;
use crate::physics::kapitza;
use crate::physics::kapitza::floquet::Position;

/// What one cell found.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Spin reversals (the rattleback, the celt).
    Reversals {
        /// How many in the window.
        count: usize,
        /// The first one's time (the celt's; `None` for the rattleback's and when none).
        first: Option<f64>,
        /// Whether two tolerances agree on it.
        decided: bool,
        /// The growth rate of steady spin at the cell (the celt's; 1/s).
        growth: Option<f64>,
    },
    /// The linear stability of an equilibrium (the pendulum).
    Stability {
        /// `|tr M| < 2`.
        stable: bool,
        /// The monodromy matrix's trace.
        trace: f64,
        /// Its estimated error.
        error: f64,
        /// Whether `||tr| − 2|` exceeds the estimate.
        decided: bool,
    },
    /// The cell's integration failed (a step size that underflowed, a state no longer finite):
    /// the chart marks it undecided and says why, instead of failing whole (issue 66, H8).
    Failed {
        /// What went wrong, as the run said it.
        error: String,
    },
}

impl Verdict {
    /// The count of reversals (`None` for a stability verdict).
    #[must_use]
    pub fn count(&self) -> Option<usize> {
        match *self {
            Self::Reversals { count, .. } => Some(count),
            Self::Stability { .. } | Self::Failed { .. } => None,
        }
    }

    /// Whether the cell's verdict is certain at the chart's tolerance.
    #[must_use]
    pub fn decided(&self) -> bool {
        match *self {
            Self::Reversals { decided, .. } | Self::Stability { decided, .. } => decided,
            Self::Failed { .. } => false,
        }
    }
}

/// A pendulum chart: the stability of `position` over `(a, b)` at `ε`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PendulumChart {
    /// The preset's pendulum (its `ε`; its `a`, `b` are marked).
    pub params: kapitza::Params,
    /// Which equilibrium.
    pub position: Position,
    /// `a` across.
    pub columns: Axis,
    /// `b` up.
    pub rows: Axis,
    /// The trace's tolerance.
    pub tolerance: f64,
}

/// A celt chart: reversals over `(ω_z, D)` from the preset's body and tilt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CeltChart {
    /// The preset's problem (its `ω_z` and `D` are marked).
    pub problem: celt::Problem,
    /// `ω_z` across.
    pub columns: Axis,
    /// `D` up.
    pub rows: Axis,
    /// The window.
    pub t_end: f64,
    /// The reversal times' tolerance (s).
    pub tolerance: f64,
}

/// The pendulum's trace tolerance when none is asked: a cell within 1e-10 of `|tr| = 2` is too
/// close to call.
pub const PENDULUM_TOLERANCE: f64 = 1e-10;
/// The celt's reversal-time tolerance when none is asked (s): a count needs its times to a
/// small fraction of a wobble (tenths of a second), not a trajectory's tolerance.
pub const CELT_TOLERANCE: f64 = 1e-4;

impl PendulumChart {
    /// The default axes for `params`: `a` over `[0, 2a]` (or `[2a, 0]`, `[0, 2]` when `a = 0`),
    /// `b` log-spaced from a tenth of Kapitza's threshold at the largest `a` to well past where
    /// the shake destabilises the upright again (`εb ≈ 0.45`), so both edges of the stable band
    /// show.
    #[must_use]
    pub fn default_axes(p: &kapitza::Params, cols: usize, rows: usize) -> (Axis, Axis) {
        let (lo, hi) = if p.a > 0.0 {
            (0.0, 2.0 * p.a)
        } else if p.a < 0.0 {
            (2.0 * p.a, 0.0)
        } else {
            (0.0, 2.0)
        };
        let threshold = (2.0 * hi.abs().max(lo.abs())).sqrt();
        let b_lo = (0.1 * threshold).min(0.5 * p.b.max(1e-3));
        let b_hi = (1.0 / p.epsilon).max(4.0 * p.b).max(10.0 * b_lo);
        (
            Axis {
                name: "pendulum.a",
                min: lo,
                max: hi,
                cells: cols,
                log: false,
            },
            Axis {
                name: "pendulum.b",
                min: b_lo,
                max: b_hi,
                cells: rows,
                log: true,
            },
        )
    }

    pub(super) fn params(&self, i: usize, j: usize) -> kapitza::Params {
        kapitza::Params {
            a: self.columns.at(i),
            b: self.rows.at(j),
            ..self.params
        }
    }
}

impl CeltChart {
    /// The default axes for `problem`: `ω_z` over `±2|ω_z|` (both senses; `±10` rad/s for a start
    /// without spin), `D` over `±2|D|` (`±0.05 √(ix iy)` for a body without skew), kept inside
    /// the positive-definite range.
    #[must_use]
    pub fn default_axes(problem: &celt::Problem, cols: usize, rows: usize) -> (Axis, Axis) {
        let (p, s) = (problem.params(), problem.start());
        let w = if s.omega[2] == 0.0 {
            10.0
        } else {
            2.0 * s.omega[2].abs()
        };
        let limit = 0.9 * (p.ix * p.iy).sqrt();
        let d = if p.product == 0.0 {
            0.05 * (p.ix * p.iy).sqrt()
        } else {
            (2.0 * p.product.abs()).min(limit)
        };
        (
            Axis {
                name: "initial.omega_z",
                min: -w,
                max: w,
                cells: cols,
                log: false,
            },
            Axis {
                name: "celt.product",
                min: -d,
                max: d,
                cells: rows,
                log: false,
            },
        )
    }

    pub(super) fn problem(
        &self,
        i: usize,
        j: usize,
    ) -> Result<celt::Problem, crate::physics::ParamError> {
        with_spin_and_product(&self.problem, self.columns.at(i), self.rows.at(j))
    }
}

/// Seconds of CPU a pendulum cell takes, about (`scripts/chart_costs.py`).
pub const PENDULUM_CELL_SECONDS: f64 = 1e-4;

impl CeltChart {
    /// Predicted seconds of CPU one cell takes: its verification priced by the celt's cost model
    /// at the fastest corner, as pairs of runs at its first tolerance, more of them the longer
    /// the window ([`CELT_PAIRS_SHORT`] to [`CELT_PAIRS_LONG`]).
    #[must_use]
    pub fn cell_seconds(&self) -> f64 {
        let x = self.columns;
        let corner = self.problem(x.cells - 1, 0).unwrap_or(self.problem);
        let pairs = CELT_PAIRS_SHORT
            + (CELT_PAIRS_LONG - CELT_PAIRS_SHORT) * (self.t_end / CELT_DECISION_TIME).min(1.0);
        pairs * celt::reversal::first_round_seconds(&corner, self.t_end, self.tolerance)
    }
}

/// What a celt cell costs, in pairs of runs at its first tolerance, at a short window: a round
/// or two decide it. Fitted with `scripts/chart_costs.py` on the seven shipped celt presets at
/// their window, 10× and 100× (a fit to those 21 charts, not a held-out check): with these three
/// constants every one is within 2× (wall over predicted 0.5–1.5).
const CELT_PAIRS_SHORT: f64 = 2.9;
/// At a long window, where counts grow chaotic and the loop runs to its end with blind
/// refinements (a prediction of 2.5 runs a cell was 1.7–3.4× short there: issue 66, H3).
const CELT_PAIRS_LONG: f64 = 11.9;
/// The window (s) over which a cell goes from one to the other.
const CELT_DECISION_TIME: f64 = 50.0;

impl CeltChart {
    /// The growth rate (1/s) at which the start's tilt `θ0` reaches a radian within the window:
    /// `ln(1/θ0)/T` (`None` for an upright start, which never tilts).
    #[must_use]
    pub fn reversal_growth(&self) -> Option<f64> {
        let tilt = celt::tilt(&self.problem.initial_state());
        (tilt > 0.0 && tilt < 1.0).then(|| (1.0 / tilt).ln() / self.t_end)
    }
}

pub use crate::physics::scene::ChartWords;

/// The celt's `problem` spun at `omega_z` with the product of inertia `product`.
///
/// # Errors
/// When the body or start is not valid.
pub fn with_spin_and_product(
    problem: &celt::Problem,
    omega_z: f64,
    product: f64,
) -> Result<celt::Problem, crate::physics::ParamError> {
    let mut params = *problem.params();
    params.product = product;
    let mut start = *problem.start();
    start.omega[2] = omega_z;
    celt::Problem::new(params, start, problem.band())
}
