//! The regime map over all cores (the rattleback's chart as a whole, for the tests and the
//! benches): every cell of a [`Grid`] from a [`Source`], computed in parallel (rayon) and
//! collected in grid order, so the result does not depend on the number of threads. The grid,
//! a cell and the critical curve are the rattleback's own (`physics::rattleback::map`).

use rayon::prelude::*;
use serde::Serialize;

use crate::physics::StepError;
pub use crate::physics::rattleback::map::*;

/// One cell.
#[derive(Clone, Copy, Debug, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Cell {
    /// `α̇0²/γ̇0²`.
    pub ratio: f64,
    /// `iy/ix`.
    pub inertia_ratio: f64,
    /// Reversals in `(0, T]`.
    pub reversals: usize,
}

/// A computed map, cells row by row (row 0 the smallest inertia ratio).
#[derive(Clone, Debug, Serialize, schemars::JsonSchema)]
pub struct RegimeMap {
    /// The cells.
    pub cells: Vec<Cell>,
    /// The critical curve at every row's inertia ratio below 1.
    pub critical: Vec<CriticalPoint>,
}

/// Computes the map; `go_on` is asked between cells (and inside full runs) whether to go on.
///
/// # Errors
/// The first cell whose run fails, or [`StepError::Cancelled`].
pub fn regime_map(
    grid: &Grid,
    source: Source,
    go_on: &(dyn Fn(f64) -> bool + Sync),
) -> Result<RegimeMap, StepError> {
    let indices: Vec<(usize, usize)> = (0..grid.rows)
        .flat_map(|j| (0..grid.cols).map(move |i| (i, j)))
        .collect();
    let cells = indices
        .par_iter()
        .map(|&(i, j)| {
            if !go_on(0.0) {
                return Err(StepError::Cancelled { t: 0.0 });
            }
            Ok(Cell {
                ratio: grid.ratio(i),
                inertia_ratio: grid.inertia_ratio(j),
                reversals: cell_reversals(grid, source, i, j, go_on)?.count,
            })
        })
        .collect::<Result<Vec<Cell>, StepError>>()?;
    let critical = (0..grid.rows)
        .filter_map(|j| {
            let inertia_ratio = grid.inertia_ratio(j);
            grid.critical(inertia_ratio).map(|ratio| CriticalPoint {
                inertia_ratio,
                ratio,
            })
        })
        .collect();
    Ok(RegimeMap { cells, critical })
}
