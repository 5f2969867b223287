//! The regime map: the number of spin reversals in `(0, T]` over a grid of the paper's two
//! numbers, the ratio `α̇0²/γ̇0²` (columns) and the inertia ratio `iy/ix` (rows, log-spaced),
//! with the critical curve `α̇0²/γ̇0² = (ix/iz)(√(ix/iy) − 1)` of Theorems 1.1–1.2 (for
//! `iy < ix`; for `iy ≥ ix` the start at α = 0 sits on the potential's maximum and never
//! reverses).
//!
//! From the limit each cell is two quadratures (its first reversal time and half period); at a
//! finite `k` each cell is a verified `auto` run, to show where finite `k` departs from the
//! theorem. The map over all cores is `study::map`'s; a cell is computed here.
use crate::physics::numerics::elementary::Elementary;

use serde::Serialize;

use super::auto::run_auto_cancellable;
use super::effective::Effective;
use super::{Params, Problem, Start};
use crate::physics::method::RunSpec;
use crate::physics::{Method, StepError};

/// What the map is computed from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Source {
    /// The limit `k → ∞`, by quadrature.
    Limit,
    /// The full model at this `k`, through `auto` at this tolerance.
    Full {
        /// Hooke constant.
        k: f64,
        /// `auto`'s tolerance.
        tolerance: f64,
    },
}

/// The grid and the body it is drawn for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// Columns (ratio axis).
    pub cols: usize,
    /// Rows (inertia-ratio axis).
    pub rows: usize,
    /// Largest `α̇0²/γ̇0²` (the columns span `(0, ratio_max]`).
    pub ratio_max: f64,
    /// Smallest and largest `iy/ix` (log-spaced rows).
    pub inertia: (f64, f64),
    /// `ix` and `iz` of the body; `iy = ix · (iy/ix)`.
    pub ix: f64,
    /// `iz`.
    pub iz: f64,
    /// `γ̇0` of every start (`γ0 = α0 = 0`).
    pub gamma_dot: f64,
    /// Horizon.
    pub t_end: f64,
}

/// The ratio axis `study map` and the tests use by default: `(0, 2]`.
pub const DEFAULT_RATIO_MAX: f64 = 2.0;
/// The inertia-ratio axis by default: `[0.1, 10]`, log-spaced.
pub const DEFAULT_INERTIA: (f64, f64) = (0.1, 10.0);

impl Grid {
    /// A `cols × rows` grid over the default axes for a body (`ix`, `iz`), starts with `γ̇0`,
    /// to `t_end`.
    #[must_use]
    pub fn new(cols: usize, rows: usize, ix: f64, iz: f64, gamma_dot: f64, t_end: f64) -> Self {
        Self {
            cols,
            rows,
            ratio_max: DEFAULT_RATIO_MAX,
            inertia: DEFAULT_INERTIA,
            ix,
            iz,
            gamma_dot,
            t_end,
        }
    }

    /// The ratio at the centre of column `i`.
    #[must_use]
    pub fn ratio(&self, i: usize) -> f64 {
        let f = (i as f64 + 0.5) / self.cols as f64;
        f * self.ratio_max
    }

    /// The inertia ratio at the centre of row `j`.
    #[must_use]
    pub fn inertia_ratio(&self, j: usize) -> f64 {
        let f = (j as f64 + 0.5) / self.rows as f64;
        let (lo, hi) = self.inertia;
        (lo.e_ln() + f * (hi / lo).e_ln()).e_exp()
    }

    /// The start of a cell at stiffness `k`.
    ///
    /// # Errors
    /// When the values are not a valid problem.
    pub fn problem(&self, ratio: f64, inertia_ratio: f64, k: f64) -> Result<Problem, StepError> {
        self.params_of(ratio, inertia_ratio, k)
            .map_err(|_| StepError::NotFinite {
                what: "a cell's parameters",
                t: 0.0,
            })
    }

    /// The problem of one cell, or why the model refuses it (the validator presets use).
    ///
    /// # Errors
    /// A value, or a quantity derived from them, out of range.
    pub fn params_of(
        &self,
        ratio: f64,
        inertia_ratio: f64,
        k: f64,
    ) -> Result<Problem, crate::physics::ParamError> {
        Problem::new(
            Params {
                ix: self.ix,
                iy: self.ix * inertia_ratio,
                iz: self.iz,
                k,
            },
            Start {
                gamma: 0.0,
                alpha: 0.0,
                gamma_dot: self.gamma_dot,
                alpha_dot: ratio.sqrt() * self.gamma_dot,
            },
        )
    }

    /// The paper's critical ratio at an inertia ratio, `(ix/iz)(√(ix/iy) − 1)` (`None` for
    /// `iy ≥ ix`).
    #[must_use]
    pub fn critical(&self, inertia_ratio: f64) -> Option<f64> {
        (inertia_ratio < 1.0).then(|| self.ix / self.iz * (1.0 / inertia_ratio.sqrt() - 1.0))
    }
}

/// Seconds of CPU one cell of the limit takes, about (quadrature of the reversal count;
/// measured again with `scripts/chart_costs.py`, issue 66: 200×100 charts of every shipped
/// rattleback preset in 0.10–0.15 s of wall time on two threads).
pub const LIMIT_CELL_SECONDS: f64 = 1.3e-5;

/// Predicted seconds of CPU cell `(i, j)` of `grid` from `source` takes (the map's cost model,
/// asked by `study map` and the explorer's map pane before they start, cell by cell, issue 80):
/// the limit's cells cost the same whatever the horizon (the count is a quotient); a full
/// model's cell is priced as a lone `auto` run at its own body and start, times
/// [`FULL_CELL_OVER_RUN`]; infinite when the cell is no problem.
#[must_use]
pub fn cell_seconds(grid: &Grid, source: Source, i: usize, j: usize) -> f64 {
    match source {
        Source::Limit => LIMIT_CELL_SECONDS,
        Source::Full { k, tolerance } => grid
            .params_of(grid.ratio(i), grid.inertia_ratio(j), k)
            .map_or(f64::INFINITY, |cell| {
                crate::physics::rattleback::plan::expected_seconds(
                    &cell,
                    &crate::physics::method::Asked::new(
                        crate::physics::Method::Auto,
                        tolerance,
                        None,
                        grid.t_end,
                    ),
                ) * FULL_CELL_OVER_RUN
            }),
    }
}

/// A full-model chart cell's time over a lone `auto` run's price, the median of 150 random
/// cells (`k` 1e2–1e6, tolerances 1e-6–1e-10, T 10–100, inertia ratios 1e-3–1e3: `cargo run
/// --release --example chart_price full`, issue 80). The spread is wide (0.1× to 400× on
/// ill-conditioned starts, where `auto`'s conditioning and probes dominate): `study map`'s
/// watchdog stops a chart that runs past twice its price.
pub const FULL_CELL_OVER_RUN: f64 = 1.3;

/// A point of the critical curve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct CriticalPoint {
    /// `iy/ix`.
    pub inertia_ratio: f64,
    /// The critical `α̇0²/γ̇0²`.
    pub ratio: f64,
}

/// What a cell of the map found: its reversals in `(0, T]` and the first and last of their times
/// (the certificate of a refined chart, issue 80).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellReversals {
    /// How many.
    pub count: usize,
    /// The first one's time (`None`: none).
    pub first: Option<f64>,
    /// The last one's time in the window (`None`: none, or more than a run keeps).
    pub last: Option<f64>,
}

/// The reversals in `(0, T]` of cell `(i, j)`; `go_on` may cancel a full run.
///
/// # Errors
/// When the cell's run fails, or [`StepError::Cancelled`].
pub fn cell_reversals(
    grid: &Grid,
    source: Source,
    i: usize,
    j: usize,
    go_on: &(dyn Fn(f64) -> bool + Sync),
) -> Result<CellReversals, StepError> {
    let (ratio, inertia_ratio) = (grid.ratio(i), grid.inertia_ratio(j));
    match source {
        Source::Limit => {
            let p = grid.problem(ratio, inertia_ratio, 1.0)?;
            let (count, first, last) = Effective::new(&p).reversal_window(grid.t_end);
            Ok(CellReversals { count, first, last })
        }
        Source::Full { k, tolerance } => {
            let p = grid.problem(ratio, inertia_ratio, k)?;
            let spec = RunSpec {
                method: Method::Auto,
                tolerance,
                step: None,
                t_end: grid.t_end,
                samples: 0,
                monitor_energy: false,
            };
            let r = run_auto_cancellable(&p, &spec, f64::INFINITY, &mut |t| go_on(t))?.result;
            // The last time is the window's only when the run kept every time.
            let whole = r.reversals.len() == r.reversal_count;
            Ok(CellReversals {
                count: r.reversal_count,
                first: r.reversals.first().copied(),
                last: r.reversals.last().copied().filter(|_| whole),
            })
        }
    }
}
