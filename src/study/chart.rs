//! Every scene's chart (issue 59), computed, written and read back: one grid of cells over two
//! of the preset's values, each cell a verified computation that depends on its own coordinates
//! alone, with the curve of the scene's theory drawn over it. What a chart is — its axes, a
//! cell, the curve, its cost, its cells' fields — is each scene's own (`physics::SCENE::chart`,
//! through [`SceneChart`] and the registry's [`Chart`]); this layer keeps what is common: the
//! grid's order, the parallel loop, the output, its shards.
//!
//! A chart is computed whole or in shards (cells `n` with `n mod N = I − 1`); `study merge`
//! puts shards back together into exactly what the unsharded run prints. Cells run in parallel
//! (rayon) and are collected in grid order, so nothing depends on the number of threads.

use rayon::prelude::*;

use crate::physics::StepError;

pub use super::output::{CellAt, ChartOutput, CurvePoint, Shard, shard_cells};
pub use crate::physics::chart::{
    Axis, CellOutput, NotItsFields, PaneAsk, SceneChart, StudyAsk, Verdict,
};
pub use crate::physics::models::Chart;
pub use crate::physics::scene::ChartWords;

/// The words of `kind`'s chart: the scene's own (`Studies::chart`, in its folder).
#[must_use]
pub fn words(kind: crate::physics::ModelKind) -> ChartWords {
    kind.studies().chart
}

/// A model's point on its chart's axes (the rattleback's `(α̇0²/γ̇0², iy/ix)`, the pendulum's
/// `(a, b)`, the celt's `(ω_z, D)`): the scene's own (`Posed::chart_point`).
#[must_use]
pub fn point_of(model: &crate::physics::Model) -> (f64, f64) {
    model.posed().chart_point()
}

/// The explorer's pane: the cells of each scene's chart there (each scene's own constants).
pub mod pane {
    pub use crate::physics::celt::chart::CELT_GRID;
    pub use crate::physics::kapitza::chart::PENDULUM_GRID;
    pub use crate::physics::rattleback::chart::{
        FULL_GRID, FULL_TOLERANCE, LIMIT_GRID, PANE_INERTIA,
    };

    /// The largest grid the pane draws for `kind`'s charts (a recorded cursor lies inside it).
    #[must_use]
    pub fn largest(kind: crate::physics::ModelKind) -> (usize, usize) {
        kind.studies().chart.pane
    }
}

impl Chart {
    /// The words of this chart's scene.
    #[must_use]
    pub fn words(&self) -> ChartWords {
        words(self.model())
    }

    /// Cells in all.
    #[must_use]
    pub fn len(&self) -> usize {
        let (x, y) = self.axes();
        x.cells * y.cells
    }

    /// Whether the chart has no cells.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The cell the preset sits in, if on the chart.
    #[must_use]
    pub fn preset_cell(&self) -> Option<(usize, usize)> {
        let (x, y) = self.axes();
        let (px, py) = self.preset_point();
        Some((x.cell_of(px)?, y.cell_of(py)?))
    }

    /// Computes the cells `indices` in parallel, in the order given; `go_on` is asked between
    /// cells and inside runs.
    ///
    /// # Errors
    /// The first cell that fails, or [`StepError::Cancelled`].
    pub fn cells(
        &self,
        indices: &[usize],
        go_on: &(dyn Fn(f64) -> bool + Sync),
        done: &(dyn Fn() + Sync),
    ) -> Result<Vec<Verdict>, StepError> {
        indices
            .par_iter()
            .map(|&n| {
                if !go_on(0.0) {
                    return Err(StepError::Cancelled { t: 0.0 });
                }
                let v = match self.cell(n, go_on) {
                    Err(StepError::Cancelled { t }) => Err(StepError::Cancelled { t }),
                    Err(e) => Ok(Verdict::Failed {
                        error: e.to_string(),
                    }),
                    Ok(v) => Ok(v),
                };
                done();
                v
            })
            .collect()
    }

    /// The cells `range` for a caller whose `go_on` cannot cross threads (the explorer's
    /// worker): the cells run on the pool while the calling thread asks `go_on` every half
    /// millisecond and cancels them when it says stop.
    ///
    /// # Errors
    /// The first cell that fails, or [`StepError::Cancelled`].
    pub fn cells_polled(
        &self,
        range: std::ops::Range<usize>,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Vec<Verdict>, StepError> {
        use std::sync::atomic::{AtomicBool, Ordering};
        let stop = AtomicBool::new(false);
        let keep_on = |_t: f64| !stop.load(Ordering::Relaxed);
        let indices: Vec<usize> = range.collect();
        std::thread::scope(|scope| {
            let cells = scope.spawn(|| self.cells(&indices, &keep_on, &|| ()));
            while !cells.is_finished() {
                if !stop.load(Ordering::Relaxed) && !go_on(0.0) {
                    stop.store(true, Ordering::Relaxed);
                }
                std::thread::sleep(std::time::Duration::from_micros(500));
            }
            let cells = cells.join().unwrap_or(Err(StepError::Cancelled { t: 0.0 }));
            if stop.load(Ordering::Relaxed) {
                return Err(StepError::Cancelled { t: 0.0 });
            }
            cells
        })
    }

    /// Predicted wall-clock seconds of `cells` cells on this machine (the cost model asked before
    /// a chart starts, and what `study map`'s JSON reports beside what they took): the work of
    /// [`Chart::cpu_seconds`] spread over the threads that share the cells.
    #[must_use]
    pub fn predicted_seconds(&self, cells: usize) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let threads = rayon::current_num_threads().clamp(1, cells.max(1)) as f64;
        self.cpu_seconds(cells) / threads
    }

    /// The output of the cells `indices` with their verdicts (`shard` when a slice), in the
    /// shape `schema_version` names (the program's outputs' version: this layer does not know
    /// it).
    #[must_use]
    pub fn output(
        &self,
        schema_version: u32,
        preset: &str,
        indices: &[usize],
        verdicts: &[Verdict],
        shard: Option<Shard>,
    ) -> ChartOutput {
        let (columns, rows) = self.axes();
        let cells = indices
            .iter()
            .zip(verdicts)
            .map(|(&n, v)| self.cell_output(n, v))
            .collect();
        // The curve once: the celt's costs an eigenvalue problem a sample.
        let curve = self.curve();
        let header = self.header();
        let critical = header.critical.then(|| {
            curve
                .iter()
                .map(|&(ratio, inertia_ratio)| super::map::CriticalPoint {
                    inertia_ratio,
                    ratio,
                })
                .collect()
        });
        ChartOutput {
            schema_version,
            model: self.model(),
            preset: preset.to_owned(),
            columns,
            rows,
            t_end: header.t_end,
            tolerance: header.tolerance,
            stiffness: header.stiffness,
            epsilon: header.epsilon,
            position: header.position.map(str::to_owned),
            preset_cell: self
                .preset_cell()
                .map(|(column, row)| CellAt { column, row }),
            cells,
            critical,
            curve: curve
                .into_iter()
                .map(|(x, y)| CurvePoint { x, y })
                .collect(),
            curve_meaning: self.curve_meaning().to_owned(),
            shard,
            description: None,
            predicted_seconds: self.predicted_seconds(indices.len()),
            wall_seconds: 0.0,
            digest: None,
        }
    }

    /// Cell `n`'s output with the verdict `v`: its index and coordinates, the fields the
    /// scene's cells carry (its columns, `ChartWords::csv`), and a failed cell's error.
    #[must_use]
    pub fn cell_output(&self, n: usize, v: &Verdict) -> CellOutput {
        let mut out = CellOutput {
            index: n,
            coords: self.coords(n),
            ..CellOutput::default()
        };
        let (x, y) = self.axes();
        let at = (x.at(n % x.cells), y.at(n / x.cells));
        crate::physics::chart::fill_cell(self.words().csv, v, at, &mut out);
        if let Verdict::Failed { error } = v {
            out.decided = Some(false);
            out.error = Some(error.clone());
        }
        out
    }

    /// The verdict a cell of this chart's output says, read back (`study merge`): a failed
    /// cell's, or the scene's (its columns).
    ///
    /// # Errors
    /// A field this scene's cells carry is missing.
    pub fn verdict_of(&self, cell: &CellOutput) -> Result<Verdict, NotItsFields> {
        if let Some(error) = &cell.error {
            return Ok(Verdict::Failed {
                error: error.clone(),
            });
        }
        crate::physics::chart::read_cell(self.words().csv, cell).ok_or(NotItsFields {
            index: cell.index,
            scene: self.model().name(),
        })
    }
}
