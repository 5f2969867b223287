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
use serde::{Deserialize, Serialize};

use super::ask::{MAX_CELLS, StudyAsk};
use super::map::{self, Grid, Source};
use crate::physics::celt;
use crate::physics::kapitza;
use crate::physics::kapitza::floquet::{Mathieu, Position, floquet};
use crate::physics::{Model, ModelKind, StepError};

/// One axis of a chart: cell centres evenly spaced (or log-spaced) over `[min, max]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Axis {
    /// What is along it: a preset key (`pendulum.a`) or the rattleback's `ratio` / `inertia_ratio`.
    pub name: &'static str,
    /// The lower edge.
    pub min: f64,
    /// The upper edge.
    pub max: f64,
    /// Cells along it.
    pub cells: usize,
    /// Log-spaced.
    pub log: bool,
}

impl Axis {
    /// The value at the centre of cell `i`.
    #[must_use]
    pub fn at(&self, i: usize) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let f = (i as f64 + 0.5) / self.cells as f64;
        if self.log {
            (self.min.ln() + f * (self.max / self.min).ln()).exp()
        } else {
            self.min + f * (self.max - self.min)
        }
    }

    /// The fraction of the axis at `x` (0 at `min`, 1 at `max`).
    #[must_use]
    pub fn fraction(&self, x: f64) -> f64 {
        if self.log {
            (x / self.min).ln() / (self.max / self.min).ln()
        } else {
            (x - self.min) / (self.max - self.min)
        }
    }

    /// The cell holding `x`, if within the axis.
    #[must_use]
    pub fn cell_of(&self, x: f64) -> Option<usize> {
        let f = self.fraction(x);
        #[allow(clippy::cast_precision_loss)]
        let i = (f * self.cells as f64).floor();
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        (f.is_finite() && (0.0..1.0).contains(&f)).then(|| (i as usize).min(self.cells - 1))
    }

    /// The name of an axis a chart has, as `name` spells it (a part file is read back into
    /// this type).
    fn known_name(name: &str) -> Option<&'static str> {
        [
            "ratio",
            "inertia_ratio",
            "pendulum.a",
            "pendulum.b",
            "initial.omega_z",
            "celt.product",
        ]
        .into_iter()
        .find(|n| *n == name)
    }
}

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

    fn params(&self, i: usize, j: usize) -> kapitza::Params {
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

    fn problem(&self, i: usize, j: usize) -> Result<celt::Problem, crate::physics::ParamError> {
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
        let run = |local: f64| {
            celt::budget::cost_seconds(
                &corner,
                &crate::physics::method::Asked::new(
                    crate::physics::Method::Dop853,
                    local,
                    None,
                    self.t_end,
                ),
            )
        };
        let first = (self.tolerance * celt::policy::FIRST).clamp(1e-12, 1e-6);
        let pairs = CELT_PAIRS_SHORT
            + (CELT_PAIRS_LONG - CELT_PAIRS_SHORT) * (self.t_end / CELT_DECISION_TIME).min(1.0);
        pairs * (run(first) + run(celt::policy::POLICY.companion(first)))
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

/// The words of a scene's chart, for the map pane's legend and heading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChartWords {
    /// The legend's heading.
    pub title: &'static str,
    /// Whether a cell is a stability verdict (else a count of reversals).
    pub stability: bool,
    /// What the curve is.
    pub curve: &'static str,
    /// The axes, in a line.
    pub note: &'static str,
    /// Short names of the axes.
    pub axes: (&'static str, &'static str),
    /// Whether `f` switches the source (the rattleback's limit or full model).
    pub sources: bool,
}

/// The words of `kind`'s chart.
#[must_use]
pub fn words(kind: ModelKind) -> ChartWords {
    match kind {
        ModelKind::Rattleback => ChartWords {
            title: "regime map (M)",
            stability: false,
            curve: "the critical ratio of the paper's theorems",
            note: "across: alpha_dot0^2/gamma_dot0^2; up: iy/ix (log); f: limit or full model",
            axes: ("alpha_dot0^2/gamma_dot0^2", "iy/ix"),
            sources: true,
        },
        ModelKind::Kapitza => ChartWords {
            title: "stability chart (M)",
            stability: true,
            curve: "Kapitza's criterion b^2 = 2a (the limit eps -> 0)",
            note: "across: a; up: b (log), at the current eps; Enter loads a and b",
            axes: ("a", "b"),
            sources: false,
        },
        ModelKind::Celt => ChartWords {
            title: "reversal chart (M)",
            stability: false,
            curve: "linear theory: the tilt reaches 1 rad within T at the steady spin's growth rate",
            note: "across: initial omega_z (both senses); up: product of inertia",
            axes: ("omega_z", "D"),
            sources: false,
        },
    }
}

/// A model's point on its chart's axes (the rattleback's `(α̇0²/γ̇0², iy/ix)`, the pendulum's
/// `(a, b)`, the celt's `(ω_z, D)`).
#[must_use]
pub fn point_of(model: &Model) -> (f64, f64) {
    match model {
        Model::Rattleback(p) => {
            let (params, s) = (p.params(), p.start());
            let gamma_dot = if s.gamma_dot == 0.0 { 1.0 } else { s.gamma_dot };
            ((s.alpha_dot / gamma_dot).powi(2), params.iy / params.ix)
        }
        Model::Kapitza(p) => (p.params().a, p.params().b),
        Model::Celt(p) => (p.start().omega[2], p.params().product),
    }
}

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
            _ => Err("the map is of another scene".to_owned()),
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
        matches!(
            self,
            Self::Rattleback {
                source: Source::Limit,
                ..
            } | Self::Kapitza(_)
        )
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
        let critical = matches!(self, Self::Rattleback { .. }).then(|| {
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
        if let Self::Rattleback { grid, .. } = self {
            out.ratio = Some(grid.ratio(i));
            out.inertia_ratio = Some(grid.inertia_ratio(j));
        }
        match *v {
            Verdict::Reversals {
                count,
                first,
                decided,
                growth,
            } => {
                out.reversals = Some(count);
                if let Self::Celt(_) = self {
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

/// The cells of shard `index` of `count` (1-based): every cell `n` with `n mod count = index − 1`
/// (interleaved, so every shard gets a share of every region's cost).
#[must_use]
pub fn shard_cells(total: usize, shard: Shard) -> Vec<usize> {
    (0..total)
        .filter(|n| n % shard.count == shard.index - 1)
        .collect()
}

/// A slice of a chart: `index` of `count`, 1-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Shard {
    /// Which slice (1 to `count`).
    pub index: usize,
    /// How many slices.
    pub count: usize,
}

/// A cell's place.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct CellAt {
    /// Column (0 at the axis's `min`).
    pub column: usize,
    /// Row (0 at the axis's `min`).
    pub row: usize,
}

/// A point of the theory's curve, in the axes' values.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct CurvePoint {
    /// Across.
    pub x: f64,
    /// Up.
    pub y: f64,
}

/// One cell of `study map`'s JSON. Every cell has `index` and `coords`; the verdict's fields
/// are the scene's (the others are absent).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
#[serde(deny_unknown_fields)]
pub struct CellOutput {
    /// The cell's place in the grid, row by row from the bottom-left (`row · columns + column`).
    pub index: usize,
    /// The preset keys the cell sets, and their values.
    pub coords: BTreeMap<String, f64>,
    /// The rattleback's `α̇0²/γ̇0²`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio: Option<f64>,
    /// The rattleback's `iy/ix`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia_ratio: Option<f64>,
    /// Reversals in the window (the rattleback, the celt).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reversals: Option<usize>,
    /// The celt's first reversal (s), `null` when none.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "double_option"
    )]
    #[schemars(with = "Option<f64>")]
    #[allow(clippy::option_option)] // absent (not the celt), `null` (no reversal), a time
    pub first_reversal: Option<Option<f64>>,
    /// The celt's growth rate of steady spin at the cell's `ω_z` and `D` (1/s; positive: a small
    /// tilt grows).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub growth_rate: Option<f64>,
    /// The pendulum's verdict: `|tr M| < 2`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stable: Option<bool>,
    /// The pendulum's monodromy trace.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trace: Option<f64>,
    /// Its estimated error.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trace_error: Option<f64>,
    /// Whether the verdict is certain at the chart's tolerance (the pendulum: the trace's
    /// distance from ±2 exceeds its error; the celt: two tolerances agree on the count and the
    /// times). `false` on a failed cell.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decided: Option<bool>,
    /// Why the cell's integration failed (a failed cell has this, `decided: false` and no
    /// verdict).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// `Option<Option<T>>` as absent / `null` / a value.
#[allow(clippy::option_option)] // the three cases are the JSON's: absent, `null`, a time
mod double_option {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[allow(clippy::ref_option)] // serde's `with` hands a reference to the field
    pub fn serialize<S: Serializer, T: Serialize>(
        v: &Option<Option<T>>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        match v {
            Some(inner) => inner.serialize(s),
            None => s.serialize_none(),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
        d: D,
    ) -> Result<Option<Option<T>>, D::Error> {
        Option::<T>::deserialize(d).map(Some)
    }
}

/// `rattleback study map --format json` for every scene (and a shard's part file).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
#[serde(deny_unknown_fields)]
pub struct ChartOutput {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// The scene.
    pub model: ModelKind,
    /// A part's provenance (`study map --shard`): the chart's whole description, from which
    /// `study merge` rebuilds the grid and recomputes cells (absent from a whole chart). Written
    /// before the cells, so a reader knows how large the part can be before it reads them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<super::ask::Description>,
    /// The slice this file holds (absent from a whole chart and a merge).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<Shard>,
    /// The preset's name.
    pub preset: String,
    /// Across.
    pub columns: Axis,
    /// Up.
    pub rows: Axis,
    /// The window (the rattleback, the celt).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_end: Option<f64>,
    /// The cells' tolerance (the full model's, the trace's, the reversal times').
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// The rattleback's `k` when the cells are of the full model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// The pendulum's `ε`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub epsilon: Option<f64>,
    /// The pendulum's equilibrium: `upright` or `hanging`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<String>,
    /// The cell the preset sits in (`null` when off the chart).
    pub preset_cell: Option<CellAt>,
    /// The cells, in grid order (a shard's: its own, in grid order).
    pub cells: Vec<CellOutput>,
    /// The rattleback's critical curve (as before issue 59).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub critical: Option<Vec<map::CriticalPoint>>,
    /// The theory's curve in the axes' values.
    pub curve: Vec<CurvePoint>,
    /// What the curve is.
    pub curve_meaning: String,
    /// What the cost model predicted these cells would take, wall-clock on this machine's
    /// threads (s; the budget admits a chart by it).
    pub predicted_seconds: f64,
    /// What they took, wall-clock (s; a merge: the parts' sum). The one field that differs
    /// between runs of the same chart.
    pub wall_seconds: f64,
    /// A part's SHA-256 over its every other field, as this program serialises them (hex):
    /// catches a part cut or changed by accident. Anyone can recompute it, so it proves nothing
    /// against a forger; `study merge` recomputes cells for that.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub digest: Option<String>,
}

impl<'de> Deserialize<'de> for Axis {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Read {
            name: String,
            min: f64,
            max: f64,
            cells: usize,
            log: bool,
        }
        let r = Read::deserialize(d)?;
        let Some(name) = Axis::known_name(&r.name) else {
            let shown: String = r
                .name
                .chars()
                .filter(|c| !c.is_control())
                .take(40)
                .collect();
            return Err(serde::de::Error::custom(format!(
                "an axis named `{shown}`: not one a chart has"
            )));
        };
        if r.cells == 0 || r.cells > MAX_CELLS {
            return Err(serde::de::Error::custom(format!(
                "an axis of {} cells: 1 to {MAX_CELLS}",
                r.cells
            )));
        }
        Ok(Axis {
            name,
            min: r.min,
            max: r.max,
            cells: r.cells,
            log: r.log,
        })
    }
}

impl ChartOutput {
    /// The verdict of cell `(i, j)` as one character: reversals `.` (none), `1`–`9`, `+` (10 or
    /// more); stability `#` (stable), `.` (unstable); `?` a cell not decided at the tolerance.
    #[must_use]
    pub fn glyph(cell: &CellOutput) -> char {
        if cell.decided == Some(false) {
            return '?';
        }
        if let Some(stable) = cell.stable {
            return if stable { '#' } else { '.' };
        }
        match cell.reversals {
            Some(0) | None => '.',
            #[allow(clippy::cast_possible_truncation)]
            Some(n @ 1..=9) => char::from_digit(n as u32, 10).unwrap_or('+'),
            Some(_) => '+',
        }
    }

    /// The chart in text: at most 60 columns and 20 rows of [`ChartOutput::glyph`], the largest
    /// row value on top, `*` where the theory's curve passes, `@` the preset's cell.
    #[must_use]
    pub fn table(&self) -> String {
        use std::fmt::Write as _;
        let (x, y) = (self.columns, self.rows);
        let (cols, rows) = (x.cells.min(60), y.cells.min(20));
        let by_index: BTreeMap<usize, &CellOutput> =
            self.cells.iter().map(|c| (c.index, c)).collect();
        let key = match self.model {
            ModelKind::Kapitza => "# stable, . unstable, ? too close to call",
            _ => ". none, 1-9 reversals, + 10 or more, ? two tolerances disagree",
        };
        let mut o = format!(
            "{} over {} ({} … {}) across, {} ({} … {}{}) up\n{key}; * {}; @ the preset\n",
            match self.model {
                ModelKind::Kapitza => "stability of the pendulum",
                _ => "reversals",
            },
            x.name,
            super::tick(x.min),
            super::tick(x.max),
            y.name,
            super::tick(y.min),
            super::tick(y.max),
            if y.log { ", log" } else { "" },
            self.curve_meaning,
        );
        // The curve's points by the printed cell they fall in.
        let printed_cell = |px: f64, py: f64| -> Option<(usize, usize)> {
            let (i, j) = (x.cell_of(px)?, y.cell_of(py)?);
            Some((i * cols / x.cells, j * rows / y.cells))
        };
        let curve: std::collections::BTreeSet<(usize, usize)> = self
            .curve
            .iter()
            .filter_map(|p| printed_cell(p.x, p.y))
            .collect();
        let preset = self
            .preset_cell
            .map(|c| (c.column * cols / x.cells, c.row * rows / y.cells));
        for r in (0..rows).rev() {
            let j = r * y.cells / rows;
            let _ = write!(o, "{:>9} ", super::tick(y.at(j)));
            for c in 0..cols {
                let i = c * x.cells / cols;
                let ch = if preset == Some((c, r)) {
                    '@'
                } else if curve.contains(&(c, r)) {
                    '*'
                } else {
                    by_index
                        .get(&(j * x.cells + i))
                        .map_or(' ', |cell| Self::glyph(cell))
                };
                o.push(ch);
            }
            o.push('\n');
        }
        o
    }

    /// The chart in CSV, a row a cell: the rattleback's columns as before issue 59
    /// (`ratio,inertia_ratio,reversals`); the pendulum's `index`, its two keys, `stable, trace,
    /// trace_error, decided`; the celt's `index`, its two keys, `reversals, first_reversal,
    /// growth_rate, decided` (an empty `first_reversal` when none).
    #[must_use]
    pub fn csv(&self) -> String {
        use std::fmt::Write as _;
        let opt = |v: Option<f64>| v.map_or_else(String::new, |v| v.to_string());
        let (x, y) = (self.columns.name, self.rows.name);
        let mut o = match self.model {
            ModelKind::Rattleback => String::from("ratio,inertia_ratio,reversals\n"),
            ModelKind::Kapitza => format!("index,{x},{y},stable,trace,trace_error,decided\n"),
            ModelKind::Celt => {
                format!("index,{x},{y},reversals,first_reversal,growth_rate,decided\n")
            }
        };
        for c in &self.cells {
            let (cx, cy) = (
                c.coords.get(x).copied().unwrap_or(f64::NAN),
                c.coords.get(y).copied().unwrap_or(f64::NAN),
            );
            let _ = match self.model {
                ModelKind::Rattleback => writeln!(
                    o,
                    "{},{},{}",
                    opt(c.ratio),
                    opt(c.inertia_ratio),
                    c.reversals.unwrap_or(0)
                ),
                ModelKind::Kapitza => writeln!(
                    o,
                    "{},{cx},{cy},{},{},{},{}",
                    c.index,
                    c.stable.unwrap_or(false),
                    opt(c.trace),
                    opt(c.trace_error),
                    c.decided.unwrap_or(false)
                ),
                ModelKind::Celt => writeln!(
                    o,
                    "{},{cx},{cy},{},{},{},{}",
                    c.index,
                    c.reversals.unwrap_or(0),
                    opt(c.first_reversal.flatten()),
                    opt(c.growth_rate),
                    c.decided.unwrap_or(false)
                ),
            };
        }
        o
    }
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
