//! Every scene's chart (issue 59): one grid of cells over two of the preset's values, each cell
//! a verified computation that depends on its own coordinates alone, with the curve of the
//! scene's theory drawn over it.
//!
//! - the rattleback: reversals in `(0, T]` over `(α̇0²/γ̇0², iy/ix)` against the critical curve
//!   of Theorems 1.1–1.2 ([`super::map`]);
//! - Kapitza's pendulum: the stability of the upright (or the hanging position) over `(a, b)`
//!   at the preset's `ε`, by the monodromy matrix of one forcing period
//!   (`physics::kapitza::floquet`), against Kapitza's criterion `b² = 2a`;
//! - the celt: reversals in `[0, T]` and the first one's time over the initial spin `ω_z` (both
//!   senses) and the product of inertia `D`, from the preset's tilt, against the spin rates
//!   where steady spin turns from decaying to growing (`physics::celt::linear`).
//!
//! A chart is computed whole or in shards (cells `n` with `n mod N = I − 1`); [`merge`] puts
//! shards back together into exactly what the unsharded run prints. Cells run in parallel
//! (rayon) and are collected in grid order, so nothing depends on the number of threads.

use std::collections::BTreeMap;

use rayon::prelude::*;

use super::ask::StudyAsk;
use super::map::{self, Grid, Source};
use crate::physics::celt;
use crate::physics::kapitza;
use crate::physics::kapitza::floquet::{Mathieu, Position, floquet};
use crate::physics::{Model, ModelKind, StepError};

pub use super::cells::{
    CELT_TOLERANCE, CeltChart, ChartWords, PENDULUM_CELL_SECONDS, PENDULUM_TOLERANCE,
    PendulumChart, Verdict, with_spin_and_product,
};
pub use super::output::{Axis, CellAt, CellOutput, ChartOutput, CurvePoint, Shard, shard_cells};

/// A chart of one scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Chart {
    /// The rattleback's regime map.
    Rattleback {
        /// The grid.
        grid: Grid,
        /// The limit or the full model.
        source: Source,
        /// The preset's `(ratio, iy/ix)`.
        at: (f64, f64),
    },
    /// The pendulum's stability chart.
    Kapitza(PendulumChart),
    /// The celt's reversal chart.
    Celt(CeltChart),
}

/// The words of `kind`'s chart: the scene's own (`Studies::chart`, in its folder).
#[must_use]
pub fn words(kind: ModelKind) -> ChartWords {
    kind.studies().chart
}

/// A model's point on its chart's axes (the rattleback's `(α̇0²/γ̇0², iy/ix)`, the pendulum's
/// `(a, b)`, the celt's `(ω_z, D)`): the scene's own (`Posed::chart_point`).
#[must_use]
pub fn point_of(model: &Model) -> (f64, f64) {
    model.posed().chart_point()
}

/// The explorer's pane: the cells of each scene's chart there.
pub mod pane {
    /// The rattleback's map from the limit (two quadratures a cell: instant).
    pub const LIMIT_GRID: (usize, usize) = (48, 24);
    /// The rattleback's map from the full model (a verified `auto` run a cell).
    pub const FULL_GRID: (usize, usize) = (24, 12);
    /// The pendulum's chart (one period's trace a cell: instant).
    pub const PENDULUM_GRID: (usize, usize) = (48, 24);
    /// The celt's chart (two to four runs of the window a cell).
    pub const CELT_GRID: (usize, usize) = (32, 16);
    /// The pane's inertia-ratio axis: the critical curve lives below `iy/ix = 1`; the strip
    /// above it shows that nothing reverses there.
    pub const PANE_INERTIA: (f64, f64) = (0.1, 1.25);
    /// Loosest tolerance of the full map's runs: a count of reversals needs their times to a
    /// fraction of a half period, not the run's own tolerance.
    pub const FULL_TOLERANCE: f64 = 1e-6;

    /// The largest grid the pane draws for `kind`'s charts (a recorded cursor lies inside it).
    #[must_use]
    pub fn largest(kind: crate::physics::ModelKind) -> (usize, usize) {
        use crate::physics::ModelKind;
        match kind {
            ModelKind::Rattleback => (LIMIT_GRID.0.max(FULL_GRID.0), LIMIT_GRID.1.max(FULL_GRID.1)),
            ModelKind::Kapitza => PENDULUM_GRID,
            ModelKind::Celt => CELT_GRID,
        }
    }
}

impl Chart {
    /// The map pane's chart of `model` over `t_end` (the rattleback's from the full model at
    /// its `k` when `full`, at `tolerance`), its axes drawn from the point `axes_from`.
    #[must_use]
    pub fn for_pane(
        model: &Model,
        t_end: f64,
        tolerance: f64,
        full: bool,
        axes_from: (f64, f64),
    ) -> Self {
        use pane::{CELT_GRID, FULL_GRID, FULL_TOLERANCE, LIMIT_GRID, PANE_INERTIA, PENDULUM_GRID};
        match model {
            Model::Rattleback(problem) => {
                let (cols, rows) = if full { FULL_GRID } else { LIMIT_GRID };
                let (p, s) = (problem.params(), problem.start());
                let gamma_dot = if s.gamma_dot == 0.0 { 1.0 } else { s.gamma_dot };
                // The ratio axis spans `(0, ix/iz]`: the critical curve crosses the plot from
                // `iy/ix = 1/4` (where it equals `ix/iz`) to `iy/ix = 1` (where it is 0). It
                // depends on `ix` and `iz` only, so loading a cell (which sets `iy`) keeps
                // the axes.
                let grid = Grid {
                    ratio_max: p.ix / p.iz,
                    inertia: PANE_INERTIA,
                    ..Grid::new(cols, rows, p.ix, p.iz, gamma_dot, t_end)
                };
                let source = if full {
                    Source::Full {
                        k: p.k,
                        tolerance: tolerance.max(FULL_TOLERANCE),
                    }
                } else {
                    Source::Limit
                };
                Self::Rattleback {
                    grid,
                    source,
                    at: point_of(model),
                }
            }
            Model::Kapitza(problem) => {
                let p = *problem.params();
                let (a, b) = axes_from;
                let axes_of = kapitza::Params { a, b, ..p };
                let (columns, rows) =
                    PendulumChart::default_axes(&axes_of, PENDULUM_GRID.0, PENDULUM_GRID.1);
                Self::Kapitza(PendulumChart {
                    params: p,
                    position: Position::Upright,
                    columns,
                    rows,
                    tolerance: PENDULUM_TOLERANCE,
                })
            }
            Model::Celt(problem) => {
                let anchored =
                    with_spin_and_product(problem, axes_from.0, axes_from.1).unwrap_or(*problem);
                let (columns, rows) = CeltChart::default_axes(&anchored, CELT_GRID.0, CELT_GRID.1);
                Self::Celt(CeltChart {
                    problem: *problem,
                    columns,
                    rows,
                    t_end,
                    tolerance: CELT_TOLERANCE,
                })
            }
        }
    }

    /// `model` moved to the point `(x, y)` of this chart's axes: the rattleback's `iy = ix · y`
    /// and start `(0, 0, γ̇0, √x · γ̇0)`; the pendulum's `a = x`, `b = y`; the celt's `ω_z = x`,
    /// `D = y`.
    ///
    /// # Errors
    /// When the model is another scene's or the point is not a valid problem.
    pub fn load(&self, model: &Model, (x, y): (f64, f64)) -> Result<Model, String> {
        use crate::physics::rattleback;
        let bad = |e: crate::physics::ParamError| format!("this cell: {e}");
        match (self, model) {
            (Self::Rattleback { grid: g, .. }, Model::Rattleback(problem)) => {
                let params = rattleback::Params {
                    iy: g.ix * y,
                    ..*problem.params()
                };
                let start = rattleback::Start {
                    gamma: 0.0,
                    alpha: 0.0,
                    gamma_dot: g.gamma_dot,
                    alpha_dot: x.sqrt() * g.gamma_dot,
                };
                Ok(rattleback::Problem::new(params, start).map_err(bad)?.into())
            }
            (Self::Kapitza(_), Model::Kapitza(problem)) => {
                let params = kapitza::Params {
                    a: x,
                    b: y,
                    ..*problem.params()
                };
                Ok(Model::Kapitza(
                    kapitza::Problem::new(params, *problem.start()).map_err(bad)?,
                ))
            }
            (Self::Celt(_), Model::Celt(problem)) => Ok(Model::Celt(
                with_spin_and_product(problem, x, y).map_err(bad)?,
            )),
            // Each chart with another scene's model (each chart is named: a new one must say
            // what it loads; issue 69).
            (Self::Rattleback { .. } | Self::Kapitza(_) | Self::Celt(_), _) => {
                Err("the map is of another scene".to_owned())
            }
        }
    }

    /// `study map`'s chart of `model` as `ask` says.
    ///
    /// # Errors
    /// A flag of another scene's chart, a range out of order, or a corner the model refuses
    /// (said as a preset value would be).
    pub fn for_study(model: &Model, ask: &StudyAsk) -> Result<Self, String> {
        match model {
            Model::Rattleback(problem) => rattleback_chart(ask, problem),
            Model::Kapitza(problem) => {
                refuse_rattleback_flags(ask, ModelKind::Kapitza)?;
                pendulum_chart(ask, problem)
            }
            Model::Celt(problem) => {
                refuse_rattleback_flags(ask, ModelKind::Celt)?;
                celt_chart(ask, problem)
            }
        }
    }

    /// What the chart is, in a few words (the pane's heading; `study map`'s refusal): `map
    /// (limit)`, `map (full model, k 1e4)`, `stability (eps 0.001)`, `reversals (T 10)`.
    #[must_use]
    pub fn title(&self) -> String {
        let tick = super::tick;
        match self {
            Self::Rattleback {
                source: Source::Full { k, .. },
                ..
            } => format!("map (full model, k {})", tick(*k)),
            Self::Rattleback { .. } => "map (limit)".to_owned(),
            Self::Kapitza(c) => format!("stability (eps {})", tick(c.params.epsilon)),
            Self::Celt(c) => format!("reversals (T {})", tick(c.t_end)),
        }
    }

    /// The words of this chart's scene.
    #[must_use]
    pub fn words(&self) -> ChartWords {
        words(self.model())
    }

    /// The scene.
    #[must_use]
    pub fn model(&self) -> ModelKind {
        match self {
            Self::Rattleback { .. } => ModelKind::Rattleback,
            Self::Kapitza(_) => ModelKind::Kapitza,
            Self::Celt(_) => ModelKind::Celt,
        }
    }

    /// The axes, across and up.
    #[must_use]
    pub fn axes(&self) -> (Axis, Axis) {
        match self {
            Self::Rattleback { grid, .. } => (
                Axis {
                    name: "ratio",
                    min: 0.0,
                    max: grid.ratio_max,
                    cells: grid.cols,
                    log: false,
                },
                Axis {
                    name: "inertia_ratio",
                    min: grid.inertia.0,
                    max: grid.inertia.1,
                    cells: grid.rows,
                    log: true,
                },
            ),
            Self::Kapitza(c) => (c.columns, c.rows),
            Self::Celt(c) => (c.columns, c.rows),
        }
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

    /// The preset's point, in the axes' values.
    #[must_use]
    pub fn preset_point(&self) -> (f64, f64) {
        match self {
            Self::Rattleback { at, .. } => *at,
            Self::Kapitza(c) => (c.params.a, c.params.b),
            Self::Celt(c) => (c.problem.start().omega[2], c.problem.params().product),
        }
    }

    /// The cell the preset sits in, if on the chart.
    #[must_use]
    pub fn preset_cell(&self) -> Option<(usize, usize)> {
        let (x, y) = self.axes();
        let (px, py) = self.preset_point();
        Some((x.cell_of(px)?, y.cell_of(py)?))
    }

    /// The preset keys cell `n` sets, and their values.
    #[must_use]
    pub fn coords(&self, n: usize) -> BTreeMap<String, f64> {
        let (x, y) = self.axes();
        let (i, j) = (n % x.cells, n / x.cells);
        match self {
            Self::Rattleback { grid, .. } => BTreeMap::from([
                (
                    "initial.alpha_dot".to_owned(),
                    grid.ratio(i).sqrt() * grid.gamma_dot,
                ),
                ("body.iy".to_owned(), grid.ix * grid.inertia_ratio(j)),
            ]),
            Self::Kapitza(_) | Self::Celt(_) => {
                BTreeMap::from([(x.name.to_owned(), x.at(i)), (y.name.to_owned(), y.at(j))])
            }
        }
    }

    /// Cell `n` (row by row from the bottom); `go_on` may cancel it.
    ///
    /// # Errors
    /// A failed run (a cell the model refuses is a failed cell, named), or
    /// [`StepError::Cancelled`].
    pub fn cell(
        &self,
        n: usize,
        go_on: &(dyn Fn(f64) -> bool + Sync),
    ) -> Result<Verdict, StepError> {
        let (x, _) = self.axes();
        let (i, j) = (n % x.cells, n / x.cells);
        match self {
            Self::Rattleback { grid, source, .. } => {
                let count = map::cell_reversals(grid, *source, i, j, go_on)?;
                Ok(Verdict::Reversals {
                    count,
                    first: None,
                    decided: true,
                    growth: None,
                })
            }
            Self::Kapitza(c) => {
                if !go_on(0.0) {
                    return Err(StepError::Cancelled { t: 0.0 });
                }
                let f = crate::physics::fork::sequentially(|| {
                    floquet(Mathieu::of(&c.params(i, j), c.position), c.tolerance)
                })?;
                Ok(Verdict::Stability {
                    stable: f.stable,
                    trace: f.trace,
                    error: f.error,
                    decided: f.decided,
                })
            }
            Self::Celt(c) => {
                let problem = c.problem(i, j).map_err(|_| StepError::NotFinite {
                    what: "a cell's body",
                    t: 0.0,
                })?;
                let r =
                    celt::reversal::reversals(&problem, c.t_end, c.tolerance, &mut |t| go_on(t))?;
                Ok(Verdict::Reversals {
                    count: r.count,
                    first: r.first,
                    decided: r.decided,
                    growth: Some(celt::linear::growth_rate(
                        problem.params(),
                        problem.start().omega[2],
                    )),
                })
            }
        }
    }

    /// The theory's curve in the axes' values, `(x, y)` points row by row: the rattleback's
    /// critical ratio, Kapitza's `b = √(2a)` (the upright; none for the hanging position), the
    /// celt's spin rates where steady spin turns from decaying to growing.
    #[must_use]
    pub fn curve(&self) -> Vec<(f64, f64)> {
        let (x, y) = self.axes();
        match self {
            Self::Rattleback { grid, .. } => (0..grid.rows)
                .filter_map(|j| {
                    let r = grid.inertia_ratio(j);
                    grid.critical(r).map(|c| (c, r))
                })
                .collect(),
            Self::Kapitza(c) => {
                if c.position == Position::Hanging {
                    return Vec::new();
                }
                // Kapitza's curve sampled finely along a (four points a column).
                let n = 4 * x.cells;
                (0..=n)
                    .filter_map(|k| {
                        #[allow(clippy::cast_precision_loss)]
                        let a = x.min + (x.max - x.min) * k as f64 / n as f64;
                        let b = (2.0 * a).sqrt();
                        (a >= 0.0 && y.cell_of(b).is_some()).then_some((a, b))
                    })
                    .collect()
            }
            Self::Celt(c) => {
                let Some(level) = c.reversal_growth() else {
                    return Vec::new();
                };
                (0..y.cells)
                    .flat_map(|j| {
                        let mut p = *c.problem.params();
                        p.product = y.at(j);
                        celt::linear::crossings(&p, x.min, x.max, 4 * x.cells + 1, level)
                            .into_iter()
                            .map(move |w| (w, y.at(j)))
                    })
                    .collect()
            }
        }
    }

    /// What the curve is, in words.
    #[must_use]
    pub fn curve_meaning(&self) -> &'static str {
        match self {
            Self::Rattleback { .. } => "the critical ratio of Theorems 1.1-1.2",
            Self::Kapitza(c) if c.position == Position::Hanging => "none (the hanging position)",
            Self::Kapitza(_) => "Kapitza's criterion b^2 = 2a (the limit eps -> 0)",
            Self::Celt(_) => {
                "linear stability: where the steady spin's growth rate lifts the start's tilt to 1 rad within T"
            }
        }
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

    /// Whether a cell is cheap enough (a quadrature, one period's trace) that the explorer's
    /// worker takes a row a slice; otherwise as many cells as the pool has threads.
    #[must_use]
    pub fn cheap_cells(&self) -> bool {
        match self {
            Self::Rattleback { source, .. } => matches!(source, Source::Limit),
            Self::Kapitza(_) => true,
            Self::Celt(_) => false,
        }
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

    /// Predicted seconds of one core's work for `cells` cells.
    #[must_use]
    pub fn cpu_seconds(&self, cells: usize) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let n = cells as f64;
        match self {
            Self::Rattleback { grid, source, .. } => map::predicted_seconds(grid, *source, cells),
            // Measured: a 200×100 chart of kapitza-upright in about 2 s of CPU (two to four
            // one-period runs a cell, each with its second companion: issue 66).
            Self::Kapitza(_) => n * PENDULUM_CELL_SECONDS,
            Self::Celt(c) => n * c.cell_seconds(),
        }
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
        let has_critical = match self {
            Self::Rattleback { .. } => true,
            Self::Kapitza(_) | Self::Celt(_) => false,
        };
        let critical = has_critical.then(|| {
            curve
                .iter()
                .map(|&(ratio, inertia_ratio)| map::CriticalPoint {
                    inertia_ratio,
                    ratio,
                })
                .collect()
        });
        let (t_end, tolerance, stiffness, epsilon, position) = match self {
            Self::Rattleback { grid, source, .. } => match *source {
                Source::Limit => (Some(grid.t_end), None, None, None, None),
                Source::Full { k, tolerance } => {
                    (Some(grid.t_end), Some(tolerance), Some(k), None, None)
                }
            },
            Self::Kapitza(c) => (
                None,
                Some(c.tolerance),
                None,
                Some(c.params.epsilon),
                Some(c.position.name().to_owned()),
            ),
            Self::Celt(c) => (Some(c.t_end), Some(c.tolerance), None, None, None),
        };
        ChartOutput {
            schema_version,
            model: self.model(),
            preset: preset.to_owned(),
            columns,
            rows,
            t_end,
            tolerance,
            stiffness,
            epsilon,
            position,
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

    /// Cell `n`'s output with the verdict `v`.
    #[must_use]
    pub fn cell_output(&self, n: usize, v: &Verdict) -> CellOutput {
        let (x, _) = self.axes();
        let (i, j) = (n % x.cells, n / x.cells);
        let mut out = CellOutput {
            index: n,
            coords: self.coords(n),
            ..CellOutput::default()
        };
        // The fields only some scenes' cells have, each scene named (issue 69: an `if let`
        // dropped a new chart's fields silently).
        let (axes_named, reversal_details) = match self {
            Self::Rattleback { grid, .. } => (Some((grid.ratio(i), grid.inertia_ratio(j))), false),
            Self::Kapitza(_) => (None, false),
            Self::Celt(_) => (None, true),
        };
        if let Some((ratio, inertia_ratio)) = axes_named {
            out.ratio = Some(ratio);
            out.inertia_ratio = Some(inertia_ratio);
        }
        match *v {
            Verdict::Reversals {
                count,
                first,
                decided,
                growth,
            } => {
                out.reversals = Some(count);
                if reversal_details {
                    out.first_reversal = Some(first);
                    out.decided = Some(decided);
                    out.growth_rate = growth;
                }
            }
            Verdict::Stability {
                stable,
                trace,
                error,
                decided,
            } => {
                out.stable = Some(stable);
                out.trace = Some(trace);
                out.trace_error = Some(error);
                out.decided = Some(decided);
            }
            Verdict::Failed { ref error } => {
                out.decided = Some(false);
                out.error = Some(error.clone());
            }
        }
        out
    }

    /// The verdict a cell of this chart's output says, read back (`study merge`): the cell must
    /// have exactly the fields this scene's cells have, or those of a failed cell.
    ///
    /// # Errors
    /// A field missing, or one this scene's cells do not have.
    pub fn verdict_of(&self, cell: &CellOutput) -> Result<Verdict, String> {
        let c = cell;
        if let Some(error) = &c.error {
            return Ok(Verdict::Failed {
                error: error.clone(),
            });
        }
        let missing = || {
            format!(
                "cell {}: not the fields of a {} chart's cell",
                c.index,
                self.model().name()
            )
        };
        match self {
            Self::Rattleback { .. } => Ok(Verdict::Reversals {
                count: c.reversals.ok_or_else(missing)?,
                first: None,
                decided: true,
                growth: None,
            }),
            Self::Kapitza(_) => Ok(Verdict::Stability {
                stable: c.stable.ok_or_else(missing)?,
                trace: c.trace.ok_or_else(missing)?,
                error: c.trace_error.ok_or_else(missing)?,
                decided: c.decided.ok_or_else(missing)?,
            }),
            Self::Celt(_) => Ok(Verdict::Reversals {
                count: c.reversals.ok_or_else(missing)?,
                first: c.first_reversal.ok_or_else(missing)?,
                decided: c.decided.ok_or_else(missing)?,
                growth: c.growth_rate,
            }),
        }
    }
}

/// The rattleback's regime map: the limit, or the full model at `--k`.
fn rattleback_chart(
    ask: &StudyAsk,
    problem: &crate::physics::rattleback::Problem,
) -> Result<Chart, String> {
    use super::map::{DEFAULT_INERTIA, DEFAULT_RATIO_MAX};
    for (given, flag) in [
        (ask.columns.is_some(), "--columns"),
        (ask.rows.is_some(), "--rows"),
    ] {
        if given {
            return Err(format!(
                "{flag} sets the pendulum's and the celt's axes; the rattleback's are --ratio-max, --inertia-min and --inertia-max"
            ));
        }
    }
    if ask.hanging {
        return Err(
            "--position is the pendulum's (which equilibrium); the rattleback's map has none"
                .to_owned(),
        );
    }
    let inertia = (
        ask.inertia_min.unwrap_or(DEFAULT_INERTIA.0),
        ask.inertia_max.unwrap_or(DEFAULT_INERTIA.1),
    );
    if inertia.0 >= inertia.1 {
        return Err(format!(
            "--inertia-min ({}) must be below --inertia-max ({})",
            inertia.0, inertia.1
        ));
    }
    let (p, s) = (problem.params(), problem.start());
    let gamma_dot = if s.gamma_dot == 0.0 { 1.0 } else { s.gamma_dot };
    let grid = Grid {
        cols: ask.grid.0,
        rows: ask.grid.1,
        ratio_max: ask.ratio_max.unwrap_or(DEFAULT_RATIO_MAX),
        inertia,
        ix: p.ix,
        iz: p.iz,
        gamma_dot,
        t_end: ask.t_end,
    };
    let source = match ask.k {
        None => Source::Limit,
        Some(k) => {
            // Every corner is a problem the model accepts (`--k 5e307` overflows the fast
            // frequency): refused as any preset value would be, by the same validator.
            #[allow(clippy::cast_precision_loss)]
            let first_column = grid.ratio_max / grid.cols.max(1) as f64;
            for (ratio, i) in [
                (first_column, grid.inertia.0),
                (first_column, grid.inertia.1),
                (grid.ratio_max, grid.inertia.1),
                (grid.ratio_max, grid.inertia.0),
            ] {
                grid.params_of(ratio, i, k)
                    .map_err(|e| format!("--k {}: {e}", crate::physics::Number(k)))?;
            }
            Source::Full {
                k,
                tolerance: ask.tolerance,
            }
        }
    };
    Ok(Chart::Rattleback {
        grid,
        source,
        at: ((s.alpha_dot / gamma_dot).powi(2), p.iy / p.ix),
    })
}

/// The flags of the rattleback's map are refused on another scene's chart, by name.
fn refuse_rattleback_flags(ask: &StudyAsk, kind: ModelKind) -> Result<(), String> {
    for (given, flag) in [
        (ask.ratio_max.is_some(), "--ratio-max"),
        (ask.inertia_min.is_some(), "--inertia-min"),
        (ask.inertia_max.is_some(), "--inertia-max"),
        (ask.k.is_some(), "--k"),
    ] {
        if given {
            return Err(format!(
                "{flag} is the rattleback's map; the {}'s chart takes --columns MIN,MAX and --rows MIN,MAX",
                kind.title()
            ));
        }
    }
    Ok(())
}

/// The pendulum's stability chart over `(a, b)` at the preset's `ε`.
fn pendulum_chart(ask: &StudyAsk, problem: &kapitza::Problem) -> Result<Chart, String> {
    let params = *problem.params();
    let (mut columns, mut rows) = PendulumChart::default_axes(&params, ask.grid.0, ask.grid.1);
    if let Some((lo, hi)) = ask.columns {
        (columns.min, columns.max) = (lo, hi);
    }
    if let Some((lo, hi)) = ask.rows {
        if lo <= 0.0 {
            return Err(format!(
                "--rows {lo},{hi}: the pendulum's b is log-spaced; both ends must be positive"
            ));
        }
        (rows.min, rows.max) = (lo, hi);
    }
    // Every corner is a pendulum the scene accepts (the same validator as a preset's).
    for a in [columns.min, columns.max] {
        for b in [rows.min, rows.max] {
            kapitza::Problem::new(kapitza::Params { a, b, ..params }, *problem.start())
                .map_err(|e| format!("the chart's corner a = {a}, b = {b}: {e}"))?;
        }
    }
    Ok(Chart::Kapitza(PendulumChart {
        params,
        position: if ask.hanging {
            Position::Hanging
        } else {
            Position::Upright
        },
        columns,
        rows,
        tolerance: ask.asked_tolerance.unwrap_or(PENDULUM_TOLERANCE),
    }))
}

/// The celt's reversal chart over `(ω_z, D)` from the preset's body and tilt.
fn celt_chart(ask: &StudyAsk, problem: &celt::Problem) -> Result<Chart, String> {
    if ask.hanging {
        return Err(
            "--position is the pendulum's (which equilibrium); the celt's chart has none"
                .to_owned(),
        );
    }
    let (mut columns, mut rows) = CeltChart::default_axes(problem, ask.grid.0, ask.grid.1);
    if let Some((lo, hi)) = ask.columns {
        (columns.min, columns.max) = (lo, hi);
    }
    if let Some((lo, hi)) = ask.rows {
        (rows.min, rows.max) = (lo, hi);
    }
    // Every corner is a body and start the scene accepts.
    for w in [columns.min, columns.max] {
        for d in [rows.min, rows.max] {
            with_spin_and_product(problem, w, d)
                .map_err(|e| format!("the chart's corner omega_z = {w}, product = {d}: {e}"))?;
        }
    }
    Ok(Chart::Celt(CeltChart {
        problem: *problem,
        columns,
        rows,
        t_end: ask.t_end,
        tolerance: ask.asked_tolerance.unwrap_or(CELT_TOLERANCE),
    }))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A pendulum chart for tests (this module's and `part`'s).
    pub(crate) fn pendulum(cols: usize, rows: usize) -> Chart {
        let params = kapitza::Params {
            a: 1.0,
            b: 2.0,
            epsilon: 0.1,
        };
        let (columns, rows) = PendulumChart::default_axes(&params, cols, rows);
        Chart::Kapitza(PendulumChart {
            params,
            position: Position::Upright,
            columns,
            rows,
            tolerance: PENDULUM_TOLERANCE,
        })
    }

    #[test]
    fn a_cell_is_a_function_of_its_coordinates_alone() {
        // Every cell of two grids equals the trace computed from its coordinates by itself.
        for chart in [pendulum(9, 9), pendulum(4, 7)] {
            let Chart::Kapitza(c) = chart else { panic!() };
            for n in [0, 5, chart.len() - 1] {
                let coords = chart.coords(n);
                let params = kapitza::Params {
                    a: coords["pendulum.a"],
                    b: coords["pendulum.b"],
                    ..c.params
                };
                let f = floquet(Mathieu::of(&params, Position::Upright), c.tolerance).unwrap();
                assert_eq!(
                    chart.cell(n, &|_| true).unwrap(),
                    Verdict::Stability {
                        stable: f.stable,
                        trace: f.trace,
                        error: f.error,
                        decided: f.decided
                    }
                );
            }
        }
    }
}
