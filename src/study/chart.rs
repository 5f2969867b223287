//! Every scene's chart (issue 59), computed, written and read back: one grid of cells over two
//! of the preset's values, each cell a verified computation that depends on its own coordinates
//! alone, with the curve of the scene's theory drawn over it. What a chart is — its axes, a
//! cell, the curve, its cost, its cells' fields — is each scene's own (`physics::SCENE::chart`,
//! through [`SceneChart`] and the registry's [`Chart`]); this layer keeps what is common: the
//! grid's order, the parallel loop, the output, its shards.
//!
//! A chart is computed where its answer changes (issue 70, [`super::refine`]: a lattice, then
//! the blocks whose cells disagree; `--exhaustive` every cell), whole or in shards (whole
//! blocks; exhaustive: cells `n` with `n mod N = I − 1`); `study merge` puts shards back
//! together into exactly what the unsharded run prints. Cells run in parallel (rayon) and are
//! collected in grid order, so nothing depends on the number of threads.

use rayon::prelude::*;

use crate::physics::StepError;

pub use super::output::{CellAt, ChartOutput, CurvePoint, Shard, shard_cells};
pub use super::refine::Refine;
pub use crate::physics::chart::{
    Answer, Axis, CellOutput, Mark, NotItsFields, PaneAsk, SceneChart, StudyAsk, Verdict,
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

/// What the cost model expects a refined chart to compute, over its first pass: the shipped
/// presets' default charts compute 1.8 (the pendulum's) to 2.6 (the full model's) times their
/// first pass, the rattleback's limit maps 2.1 to 2.8 (`scripts/refine_check.py` counts them; docs/benchmarks.md, issue 70).
pub const REFINED_OVER_FIRST: f64 = 2.6;

/// What a cell a refined chart computes costs over the chart's average cell: it lies where the
/// answer changes, where the motion does most (the full model's bands of reversals cost 1.5×
/// its cells on average, measured on `subcritical --k 1e4 --grid 100x50`: 7.1 ms against
/// 4.6 ms of CPU).
pub const REFINED_CELL_COST: f64 = 1.5;

/// The most cells a chart's price prices one by one; beyond, an evenly spread sample of them.
pub const PRICED_CELLS: usize = 4096;

/// What a chart's cells came to: the cells (grid order) and their verdicts (each computed or
/// inferred, [`Verdict::mark`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Computed {
    /// The cells, in grid order.
    pub indices: Vec<usize>,
    /// Their verdicts.
    pub verdicts: Vec<Verdict>,
}

/// What a chart's computation tells its progress line.
pub struct Tally<'a> {
    /// A cell was computed.
    pub done: &'a (dyn Fn() + Sync),
    /// The cells the whole computation is now expected to compute.
    pub expect: &'a dyn Fn(usize),
}

impl Tally<'static> {
    /// A tally that tells nothing (tests, the merge's own runs).
    pub const QUIET: Self = Self {
        done: &|| (),
        expect: &|_| (),
    };
}

impl super::refine::Certifies for Chart {
    fn certainty(&self, n: usize, v: &Verdict) -> Option<crate::physics::chart::Certainty> {
        SceneChart::certainty(&**self, n, v)
    }
}

/// Most cells a chunk of [`Chart::cells`] hands a scene at once: enough that a scene computing
/// its cells in lanes keeps them full (four lanes, two runs a cell and a round), few enough that
/// a cancel or a progress line is not long in coming.
pub const CHUNK: usize = 64;

/// A cell the refinement left without a verdict: never, as its walk covers every cell.
fn unsettled() -> Verdict {
    Verdict::Failed {
        error: "left unsettled by the refinement".to_owned(),
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
    /// chunks of cells and inside runs. Each chunk is the scene's to compute as it can
    /// ([`SceneChart::cells`]: the celt's side by side in lanes, issue 84), at most
    /// [`CHUNK`] cells and few enough that every thread has several chunks.
    ///
    /// # Errors
    /// The first cell that fails, or [`StepError::Cancelled`].
    pub fn cells(
        &self,
        indices: &[usize],
        go_on: &(dyn Fn(f64) -> bool + Sync),
        done: &(dyn Fn() + Sync),
    ) -> Result<Vec<Verdict>, StepError> {
        let threads = rayon::current_num_threads().max(1);
        let chunk = (indices.len() / (8 * threads)).clamp(self.together().clamp(1, CHUNK), CHUNK);
        let chunks: Vec<Vec<Verdict>> = indices
            .par_chunks(chunk)
            .map(|ns| {
                if !go_on(0.0) {
                    return Err(StepError::Cancelled { t: 0.0 });
                }
                let mut found: Vec<Option<Result<Verdict, StepError>>> = vec![None; ns.len()];
                SceneChart::cells(&**self, ns, go_on, &mut |k, v| {
                    found[k] = Some(v);
                    done();
                });
                found
                    .into_iter()
                    .map(
                        |v| match v.unwrap_or(Err(StepError::Cancelled { t: 0.0 })) {
                            Err(StepError::Cancelled { t }) => Err(StepError::Cancelled { t }),
                            Err(e) => Ok(Verdict::Failed {
                                error: e.to_string(),
                            }),
                            Ok(v) => Ok(v),
                        },
                    )
                    .collect()
            })
            .collect::<Result<_, _>>()?;
        Ok(chunks.into_iter().flatten().collect())
    }

    /// The refinement of this chart's grid (`study::refine`): certified by the scene where it
    /// infers, its lines computed whole.
    #[must_use]
    pub fn refine(&self) -> Refine<'_> {
        let (x, y) = self.axes();
        Refine::new(x.cells, y.cells)
            .certified_by(
                self.infers()
                    .then_some(self as &dyn super::refine::Certifies),
            )
            .with_lines(self.lines())
    }

    /// The cells of `shard` (every cell without one), in grid order: each cell when
    /// `exhaustive` (a shard's cells interleaved, `n mod N`), otherwise the refinement's (a
    /// shard's whole blocks), computed pass by pass in parallel. `tally` hears of each cell
    /// computed and, before each pass, how many cells the whole is now expected to compute.
    ///
    /// # Errors
    /// [`StepError::Cancelled`] (a failed cell is a verdict, not an error).
    pub fn compute(
        &self,
        exhaustive: bool,
        shard: Option<Shard>,
        go_on: &(dyn Fn(f64) -> bool + Sync),
        tally: &Tally<'_>,
    ) -> Result<Computed, StepError> {
        let total = self.len();
        if exhaustive || !self.infers() {
            let indices = match shard {
                Some(s) => self.shard_indices(exhaustive, s),
                None => (0..total).collect(),
            };
            (tally.expect)(indices.len());
            let verdicts = self.cells(&indices, go_on, tally.done)?;
            return Ok(Computed { indices, verdicts });
        }
        let refine = self.refine();
        let blocks = refine.blocks_of(shard);
        let expected = self.expected_cells(false, shard);
        let mut known: Vec<Option<Verdict>> = vec![None; total];
        let mut computed = 0;
        // Each pass's walk says what to compute next and, at the last, every cell's verdict.
        let settled = loop {
            let (pending, settled) = refine.step(&known, &blocks);
            if pending.is_empty() {
                break settled;
            }
            (tally.expect)(expected.max(computed + pending.len()));
            let verdicts = self.cells(&pending, go_on, tally.done)?;
            computed += pending.len();
            for (n, v) in pending.into_iter().zip(verdicts) {
                known[n] = Some(v);
            }
        };
        let indices = refine.owned(&blocks);
        let verdicts = indices
            .iter()
            .map(|&n| settled[n].clone().unwrap_or_else(unsettled))
            .collect();
        Ok(Computed { indices, verdicts })
    }

    /// The cells a part of `shard` holds: interleaved (`n mod N`) when `exhaustive`, else the
    /// cells its blocks own.
    #[must_use]
    pub fn shard_indices(&self, exhaustive: bool, shard: Shard) -> Vec<usize> {
        if exhaustive {
            shard_cells(self.len(), shard)
        } else {
            let refine = self.refine();
            refine.owned(&refine.blocks_of(Some(shard)))
        }
    }

    /// How many cells of `shard` (all without one) the cost model expects a run to compute:
    /// every one when `exhaustive`; else the refinement's first pass (exact) times what the
    /// passes after it add on the shipped charts ([`REFINED_OVER_FIRST`]), at most every cell.
    #[must_use]
    pub fn expected_cells(&self, exhaustive: bool, shard: Option<Shard>) -> usize {
        let owned = match shard {
            Some(s) => self.shard_indices(exhaustive, s).len(),
            None => self.len(),
        };
        if exhaustive || !self.infers() {
            return owned;
        }
        let refine = self.refine();
        let first = refine.first_pass(&refine.blocks_of(shard));
        let expected = (first as f64 * REFINED_OVER_FIRST).ceil() as usize;
        expected.min(owned).max(first.min(owned))
    }

    /// Predicted wall-clock seconds of the cells of `shard` (all without one): the cells the
    /// cost model expects to compute ([`Chart::expected_cells`]) at the average price of the
    /// slice's cells (each priced from its own parameters), times [`REFINED_CELL_COST`] when
    /// refined.
    #[must_use]
    pub fn price(&self, exhaustive: bool, shard: Option<Shard>) -> f64 {
        let owned = match shard {
            Some(s) => self.shard_indices(exhaustive, s),
            None => (0..self.len()).collect(),
        };
        self.price_of(
            &owned,
            self.expected_cells(exhaustive, shard),
            !exhaustive && self.infers(),
        )
    }

    /// Predicted wall-clock seconds of the whole chart's cells still to compute when `computed`
    /// are (the explorer's pane: its budget and its time left).
    #[must_use]
    pub fn price_left(&self, computed: usize) -> f64 {
        let all: Vec<usize> = (0..self.len()).collect();
        self.price_of(
            &all,
            self.expected_cells(false, None).saturating_sub(computed),
            self.infers(),
        )
    }

    /// Predicted wall-clock seconds of `count` cells drawn from `cells` at their average price,
    /// computed where the answer changes when `refined`.
    fn price_of(&self, cells: &[usize], count: usize, refined: bool) -> f64 {
        let mean = self.cpu_seconds(cells) / cells.len().max(1) as f64;
        let threads = rayon::current_num_threads().clamp(1, count.max(1)) as f64;
        let seconds = mean * count as f64 / threads;
        if refined {
            seconds * REFINED_CELL_COST
        } else {
            seconds
        }
    }

    /// The cells `range` for a caller whose `go_on` cannot cross threads (the explorer's
    /// worker): the cells run on the pool while the calling thread asks `go_on` every half
    /// millisecond and cancels them when it says stop.
    ///
    /// # Errors
    /// The first cell that fails, or [`StepError::Cancelled`].
    pub fn cells_polled(
        &self,
        indices: &[usize],
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Vec<Verdict>, StepError> {
        // The browser's module starts no thread: the cells run here, `go_on` asked before
        // them (the job's slices are a cell or a row).
        #[cfg(target_arch = "wasm32")]
        {
            if !go_on(0.0) {
                return Err(StepError::Cancelled { t: 0.0 });
            }
            self.cells(indices, &|_| true, &|| ())
        }
        #[cfg(not(target_arch = "wasm32"))]
        self.cells_beside(indices, go_on)
    }

    /// [`Chart::cells_polled`] on a thread beside the caller's, which polls `go_on`.
    #[cfg(not(target_arch = "wasm32"))]
    fn cells_beside(
        &self,
        indices: &[usize],
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Vec<Verdict>, StepError> {
        use std::sync::atomic::{AtomicBool, Ordering};
        let stop = AtomicBool::new(false);
        let keep_on = |_t: f64| !stop.load(Ordering::Relaxed);
        std::thread::scope(|scope| {
            let cells = scope.spawn(|| self.cells(indices, &keep_on, &|| ()));
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

    /// Predicted wall-clock seconds of the cells `cells` on this machine: their work
    /// ([`Chart::cpu_seconds`]) spread over the threads that share them.
    #[must_use]
    pub fn predicted_seconds(&self, cells: &[usize]) -> f64 {
        let threads = rayon::current_num_threads().clamp(1, cells.len().max(1)) as f64;
        self.cpu_seconds(cells) / threads
    }

    /// Seconds of one core's work for the cells `cells`, each priced from its own parameters
    /// ([`SceneChart::cell_seconds`]): summed, or, past [`PRICED_CELLS`] cells, the sum of an
    /// evenly spread sample scaled up (a price must cost nothing next to the chart).
    #[must_use]
    pub fn cpu_seconds(&self, cells: &[usize]) -> f64 {
        if cells.len() <= PRICED_CELLS {
            return cells.iter().map(|&n| self.cell_seconds(n)).sum();
        }
        let step = cells.len().div_ceil(PRICED_CELLS);
        let sampled: Vec<usize> = cells.iter().copied().step_by(step).collect();
        let scale = cells.len() as f64 / sampled.len() as f64;
        sampled.iter().map(|&n| self.cell_seconds(n)).sum::<f64>() * scale
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
        exhaustive: bool,
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
            predicted_seconds: self.price(exhaustive, shard),
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
    /// A field that is not this scene's, or one its cells carry missing or of another kind.
    pub fn verdict_of(&self, cell: &CellOutput) -> Result<Verdict, NotItsFields> {
        if let Some(error) = &cell.error {
            return Ok(Verdict::Failed {
                error: error.clone(),
            });
        }
        crate::physics::chart::read_cell(self.words().csv, cell).map_err(|(field, fault)| {
            NotItsFields {
                index: cell.index,
                scene: self.model().name(),
                field,
                fault,
            }
        })
    }
}
