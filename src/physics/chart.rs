//! What every scene's chart is made of (issue 69): its axes, what `study map` asks, and the
//! two traits a scene implements in its own folder (`rattleback/chart.rs`, `kapitza/chart.rs`,
//! `celt/chart.rs`); a cell's verdict and its written fields are the scene's own words
//! ([`super::cell`], re-exported here):
//!
//! - [`SceneChart`], a built chart's facts: its title, axes, the cell at an index, the theory's
//!   curve, its cost;
//! - [`ChartOf`], how the scene builds one from its problem (for the explorer's pane or for
//!   `study map`) and loads a cell back into a problem.
//!
//! Neither trait has a default method for a fact of the scene, so a scene that forgets one does
//! not compile (`SceneChart::cells`, a way to compute the cells, defaults to one by one). The
//! registry (`models.rs`, [`super::models::Chart`]) is the one dispatch to them; what is common
//! to every chart (the grid's order, shards, the parallel loop, formats, progress) is the
//! `study` layer's, above this one.
use crate::physics::numerics::elementary::Elementary;

use std::collections::BTreeMap;

use serde::Serialize;

pub use super::cell::{
    Answer, CellOutput, Certainty, Column, Field, FieldFault, Findings, Kind, Mark, NotItsFields,
    Value, Verdict, answer_field, check_columns, fill_cell, read_cell,
};
use super::method::StepError;
use super::params::ParamError;

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
        let f = (i as f64 + 0.5) / self.cells as f64;
        if self.log {
            (self.min.e_ln() + f * (self.max / self.min).e_ln()).e_exp()
        } else {
            self.min + f * (self.max - self.min)
        }
    }

    /// The fraction of the axis at `x` (0 at `min`, 1 at `max`).
    #[must_use]
    pub fn fraction(&self, x: f64) -> f64 {
        if self.log {
            (x / self.min).e_ln() / (self.max / self.min).e_ln()
        } else {
            (x - self.min) / (self.max - self.min)
        }
    }

    /// The cell holding `x`, if within the axis.
    #[must_use]
    pub fn cell_of(&self, x: f64) -> Option<usize> {
        let f = self.fraction(x);
        let i = (f * self.cells as f64).floor();
        (f.is_finite() && (0.0..1.0).contains(&f)).then(|| (i as usize).min(self.cells - 1))
    }
}

/// What `study map` asks of a chart: the grid, the window, the tolerance, and each scene's own
/// flags (a scene refuses another's by name).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StudyAsk {
    /// Columns and rows.
    pub grid: (usize, usize),
    /// The window.
    pub t_end: f64,
    /// The full model's tolerance (the rattleback's `--k` cells).
    pub tolerance: f64,
    /// `--tolerance` when given (the pendulum's trace, the celt's reversal times).
    pub asked_tolerance: Option<f64>,
    /// The rattleback's `--ratio-max`.
    pub ratio_max: Option<f64>,
    /// The rattleback's `--inertia-min`.
    pub inertia_min: Option<f64>,
    /// The rattleback's `--inertia-max`.
    pub inertia_max: Option<f64>,
    /// The rattleback's `--k` (the full model).
    pub k: Option<f64>,
    /// `--columns MIN,MAX` (the pendulum's and the celt's).
    pub columns: Option<(f64, f64)>,
    /// `--rows MIN,MAX` (the pendulum's and the celt's).
    pub rows: Option<(f64, f64)>,
    /// `--position`: `Some(true)` hanging, `Some(false)` upright as asked, `None` not asked
    /// (the pendulum's; upright).
    pub hanging: Option<bool>,
    /// `--t-end` when given (the window: the rattleback's and the celt's).
    pub asked_t_end: Option<f64>,
    /// `--exhaustive`: every cell computed, none inferred (the chart is the same; how its
    /// cells are found is not).
    pub exhaustive: bool,
}

impl StudyAsk {
    /// `axes` (a scene's default) with `--columns` and `--rows` where given.
    #[must_use]
    pub fn ranged(&self, (mut columns, mut rows): (Axis, Axis)) -> (Axis, Axis) {
        if let Some((lo, hi)) = self.columns {
            (columns.min, columns.max) = (lo, hi);
        }
        if let Some((lo, hi)) = self.rows {
            (rows.min, rows.max) = (lo, hi);
        }
        (columns, rows)
    }
}

/// What the explorer's map pane asks of a chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaneAsk {
    /// The run's horizon.
    pub t_end: f64,
    /// The run's tolerance.
    pub tolerance: f64,
    /// The rattleback's map from the full model (at its `k`) rather than the limit.
    pub full: bool,
    /// The point the axes are drawn around (a loaded cell keeps the axes it was picked from).
    pub axes_from: (f64, f64),
}

/// The header fields a chart's output carries beside its cells (absent ones are not the
/// scene's).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Header {
    /// The window.
    pub t_end: Option<f64>,
    /// The cells' tolerance.
    pub tolerance: Option<f64>,
    /// The rattleback's `k` when from the full model.
    pub stiffness: Option<f64>,
    /// The pendulum's `ε`.
    pub epsilon: Option<f64>,
    /// The pendulum's equilibrium.
    pub position: Option<&'static str>,
    /// Whether the curve is also written as the rattleback's `critical` points (its shape since
    /// issue 59).
    pub critical: bool,
}

/// A built chart of one scene: everything `study` needs to compute, draw and write it.
pub trait SceneChart: std::fmt::Debug + Send + Sync {
    /// What the chart is, in a few words (the pane's heading; `study map`'s refusal).
    fn title(&self) -> String;
    /// The axes, across and up.
    fn axes(&self) -> (Axis, Axis);
    /// The preset's point, in the axes' values.
    fn preset_point(&self) -> (f64, f64);
    /// The preset keys cell `n` sets, and their values.
    fn coords(&self, n: usize) -> BTreeMap<String, f64>;
    /// Cell `n` (row by row from the bottom); `go_on` may cancel it.
    ///
    /// # Errors
    /// A failed run, or [`StepError::Cancelled`].
    fn cell(&self, n: usize, go_on: &(dyn Fn(f64) -> bool + Sync)) -> Result<Verdict, StepError>;
    /// Cells `ns`, each what [`SceneChart::cell`] gives, bit for bit; `each(k, …)` hears of
    /// `ns[k]` as it is found, in any order. One by one, unless the scene integrates its cells
    /// side by side in lanes (issue 84: the celt's). One of the two default methods (with
    /// [`SceneChart::together`]): not a fact of the scene but a way to compute its facts, right
    /// by construction (a scene that forgets to override it is only slower).
    fn cells(
        &self,
        ns: &[usize],
        go_on: &(dyn Fn(f64) -> bool + Sync),
        each: &mut dyn FnMut(usize, Result<Verdict, StepError>),
    ) {
        for (k, &n) in ns.iter().enumerate() {
            each(k, self.cell(n, go_on));
        }
    }
    /// How many cells one thread best takes at once through [`SceneChart::cells`]: 1, or as
    /// many as keep a scene's lanes full (the celt's: its cells' runs four at a time). The
    /// explorer's map pane hands each thread this many a slice, `study map` at least this many
    /// a chunk.
    fn together(&self) -> usize {
        1
    }
    /// The theory's curve in the axes' values, `(x, y)` points.
    fn curve(&self) -> Vec<(f64, f64)>;
    /// What the curve is, in words.
    fn curve_meaning(&self) -> &'static str;
    /// Whether a cell is cheap enough (a quadrature, one period's trace) that the explorer's
    /// worker takes a row a slice; otherwise as many cells as the pool has threads.
    fn cheap_cells(&self) -> bool;
    /// Predicted seconds of one core's work for cell `n`, from its own parameters (issue 80: a
    /// chart is priced from its window, cell by cell).
    fn cell_seconds(&self, n: usize) -> f64;
    /// Whether a region may be inferred at all (`study::refine`): only where the scene can
    /// certify its cells' answers ([`SceneChart::certainty`]); not where lone cells break a
    /// region's answer (the celt's chaotic wobbles) or every cell is cheaper than certifying.
    fn infers(&self) -> bool;
    /// The continuous quantity behind computed cell `n`'s verdict `v`, when the scene can say
    /// how far the cell is from changing its answer (`None`: the cell certifies nothing, and no
    /// region around it is inferred).
    fn certainty(&self, n: usize, v: &Verdict) -> Option<Certainty>;
    /// Columns where the scene's theory puts the root of a thin region (the pendulum's Mathieu
    /// tongues at `b → 0`): every block computes them whole, so a region thinner than a cell
    /// is met where it starts.
    fn lines(&self) -> Vec<usize>;
    /// The output's header fields.
    fn header(&self) -> Header;
}

/// How a scene builds its chart from its problem, and loads a cell back.
pub trait ChartOf: SceneChart + Sized {
    /// The scene's validated problem.
    type Problem;
    /// The explorer's pane chart of `problem`.
    fn for_pane(problem: &Self::Problem, ask: PaneAsk) -> Self;
    /// `study map`'s chart of `problem` as `ask` says (`title` the scene's, for refusals).
    ///
    /// # Errors
    /// A flag of another scene's chart, a range out of order, or a corner the scene refuses
    /// (said as a preset value would be).
    fn for_study(problem: &Self::Problem, ask: &StudyAsk, title: &str) -> Result<Self, ChartError>;
    /// `problem` moved to the point `(x, y)` of this chart's axes.
    ///
    /// # Errors
    /// When the point is not a valid problem.
    fn load(&self, problem: &Self::Problem, point: (f64, f64))
    -> Result<Self::Problem, ParamError>;
}

/// The preset keys cell `n` of `axes` sets, when the axes are preset keys: each axis's name
/// and the value at the cell's centre.
#[must_use]
pub fn axis_coords((x, y): (Axis, Axis), n: usize) -> BTreeMap<String, f64> {
    let (i, j) = (n % x.cells, n / x.cells);
    BTreeMap::from([(x.name.to_owned(), x.at(i)), (y.name.to_owned(), y.at(j))])
}

/// `1e-5`, `0.3`, `30`: short tick labels, never `9.999999999999999e-5`.
#[must_use]
pub fn tick(x: f64) -> String {
    if x == 0.0 {
        "0".to_owned()
    } else if (1e-3..1e4).contains(&x.abs()) {
        let s = format!("{x:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        let s = format!("{x:.1e}");
        s.replace(".0e", "e")
    }
}

/// A flag of `study map` that only some scenes' charts take (issue 80: each scene lists its
/// own in `ChartWords::flags`; any other given is refused in one place, [`refuse_flags`], naming
/// the scene, never accepted and ignored).
#[derive(Clone, Copy, Debug, PartialEq, Eq, strum::EnumIter)]
pub enum MapFlag {
    /// `--ratio-max` (the rattleback's columns).
    RatioMax,
    /// `--inertia-min` (the rattleback's rows).
    InertiaMin,
    /// `--inertia-max` (the rattleback's rows).
    InertiaMax,
    /// `--k` (the rattleback's full model).
    K,
    /// `--columns MIN,MAX`.
    Columns,
    /// `--rows MIN,MAX`.
    Rows,
    /// `--position` (the pendulum's equilibrium).
    Position,
    /// `--t-end` (a window the cells run over).
    TEnd,
    /// `--tolerance` (the cells' own).
    Tolerance,
}

impl MapFlag {
    /// The flag as typed.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::RatioMax => "--ratio-max",
            Self::InertiaMin => "--inertia-min",
            Self::InertiaMax => "--inertia-max",
            Self::K => "--k",
            Self::Columns => "--columns",
            Self::Rows => "--rows",
            Self::Position => "--position",
            Self::TEnd => "--t-end",
            Self::Tolerance => "--tolerance",
        }
    }

    /// Whether `ask` gives it.
    #[must_use]
    pub fn given(self, ask: &StudyAsk) -> bool {
        match self {
            Self::RatioMax => ask.ratio_max.is_some(),
            Self::InertiaMin => ask.inertia_min.is_some(),
            Self::InertiaMax => ask.inertia_max.is_some(),
            Self::K => ask.k.is_some(),
            Self::Columns => ask.columns.is_some(),
            Self::Rows => ask.rows.is_some(),
            Self::Position => ask.hanging.is_some(),
            Self::TEnd => ask.asked_t_end.is_some(),
            Self::Tolerance => ask.asked_tolerance.is_some(),
        }
    }
}

/// A `study map` flag the scene's chart does not take.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{} means nothing to the chart of the {title}, which takes {}", .flag.name(), takes_text(.takes))]
pub struct RefusedFlag {
    /// The flag given.
    pub flag: MapFlag,
    /// The scene's chart, as titled.
    pub title: String,
    /// The flags it does take.
    pub takes: Vec<MapFlag>,
}

fn takes_text(takes: &[MapFlag]) -> String {
    if takes.is_empty() {
        "none of the scenes' flags".to_owned()
    } else {
        takes
            .iter()
            .map(|f| f.name())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Why a chart was not made or a cell not loaded (issue 83: typed where callers match; each
/// says itself to a person).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ChartError {
    /// A flag of another scene's chart.
    #[error(transparent)]
    Flag(#[from] RefusedFlag),
    /// A corner of the chart is not a problem the scene accepts.
    #[error("the chart's corner {x_name} = {x}, {y_name} = {y}: {error}")]
    Corner {
        /// The across axis's parameter.
        x_name: &'static str,
        /// Its value at the corner.
        x: f64,
        /// The up axis's parameter.
        y_name: &'static str,
        /// Its value at the corner.
        y: f64,
        /// Why the scene refuses it.
        error: ParamError,
    },
    /// A value of a flag the scene's chart refuses, with what it allows.
    #[error("{0}")]
    Refused(String),
    /// The chart is of another scene than the problem.
    #[error("the map is of another scene")]
    OtherScene,
    /// The cell's point is not a valid problem.
    #[error("this cell: {0}")]
    Cell(ParamError),
}

/// The first flag `ask` gives that a scene's chart does not take (it takes `takes`), refused
/// with the scene's `title` and the flags it does take.
///
/// # Errors
/// That flag, as a [`RefusedFlag`].
pub fn refuse_flags(ask: &StudyAsk, takes: &[MapFlag], title: &str) -> Result<(), RefusedFlag> {
    use strum::IntoEnumIterator as _;
    match MapFlag::iter().find(|f| f.given(ask) && !takes.contains(f)) {
        Some(flag) => Err(RefusedFlag {
            flag,
            title: title.to_owned(),
            takes: takes.to_vec(),
        }),
        None => Ok(()),
    }
}
