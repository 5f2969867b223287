//! The rattleback's chart (issue 12's regime map; its own since issue 69): reversals in
//! `(0, T]` over `(α̇0²/γ̇0², iy/ix)` against the critical curve of Theorems 1.1–1.2, from the
//! limit by quadrature or from the full model at a finite `k` ([`super::map`]).

use std::collections::BTreeMap;

use super::map::{self, DEFAULT_INERTIA, DEFAULT_RATIO_MAX, Grid, Source};
use super::{Params, Problem, Start};
use crate::physics::chart::{
    Answer, Axis, ChartError, ChartOf, Column, Field, Header, Kind, PaneAsk, SceneChart, StudyAsk,
    Value, Verdict, tick,
};
use crate::physics::{ParamError, Posed as _, StepError};

/// The fields of its cells (issue 83: declared here, written and read back from this list):
/// the two ratios at the cell's centre, its reversals and, since issue 80, the first and last.
pub const COLUMNS: &[Column] = &[
    Column::Across(Field::new(
        "ratio",
        Kind::Number,
        "The rattleback's `α̇0²/γ̇0²`.",
    )),
    Column::Up(Field::new(
        "inertia_ratio",
        Kind::Number,
        "The rattleback's `iy/ix`.",
    )),
    Column::Answer(REVERSALS),
    Column::Mark,
    Column::Value(FIRST),
    Column::Value(LAST),
];

/// Reversals in `(0, T]`.
const REVERSALS: Field = Field::new("reversals", Kind::Count, "Reversals in the window.");
/// The first reversal.
const FIRST: Field = Field::new(
    "first_reversal",
    Kind::Time,
    "The first reversal (s), `null` when none (since issue 80).",
);
/// The last reversal in the window: the certificate of a refined chart.
const LAST: Field = Field::new(
    "last_reversal",
    Kind::Time,
    "The last reversal in the window (s), `null` when none (issue 80).",
);

/// The names of the axes, across and up (preset keys, or the rattleback's two ratios).
pub const AXES: [&str; 2] = ["ratio", "inertia_ratio"];

/// The pane's map from the limit (two quadratures a cell: instant).
pub const LIMIT_GRID: (usize, usize) = (48, 24);
/// The pane's map from the full model (a verified `auto` run a cell).
pub const FULL_GRID: (usize, usize) = (24, 12);
/// The pane's inertia-ratio axis: the critical curve lives below `iy/ix = 1`; the strip
/// above it shows that nothing reverses there.
pub const PANE_INERTIA: (f64, f64) = (0.1, 1.25);
/// Loosest tolerance of the full map's runs: a count of reversals needs their times to a
/// fraction of a half period, not the run's own tolerance.
pub const FULL_TOLERANCE: f64 = 1e-6;
/// The largest grid the pane draws (a recorded cursor lies inside it).
pub const PANE_LARGEST: (usize, usize) = (
    if LIMIT_GRID.0 > FULL_GRID.0 {
        LIMIT_GRID.0
    } else {
        FULL_GRID.0
    },
    if LIMIT_GRID.1 > FULL_GRID.1 {
        LIMIT_GRID.1
    } else {
        FULL_GRID.1
    },
);

/// How far above the critical curve a cell without a reversal must be, over `ix/iz`, for the
/// full model's count to be certified by the curve (the full motion departs from the limit's by
/// an amount that falls with `k`; the block's own computed cells must all agree besides).
pub const FINITE_K_ALLOWANCE: f64 = 0.05;

/// The rattleback's regime map: the limit, or the full model at a `k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegimeChart {
    /// The grid.
    pub grid: Grid,
    /// The limit or the full model.
    pub source: Source,
    /// The preset's `(ratio, iy/ix)`.
    pub at: (f64, f64),
}

impl SceneChart for RegimeChart {
    fn title(&self) -> String {
        match self.source {
            Source::Full { k, .. } => format!("map (full model, k {})", tick(k)),
            Source::Limit => "map (limit)".to_owned(),
        }
    }

    fn axes(&self) -> (Axis, Axis) {
        let grid = &self.grid;
        (
            Axis {
                name: AXES[0],
                min: 0.0,
                max: grid.ratio_max,
                cells: grid.cols,
                log: false,
            },
            Axis {
                name: AXES[1],
                min: grid.inertia.0,
                max: grid.inertia.1,
                cells: grid.rows,
                log: true,
            },
        )
    }

    fn preset_point(&self) -> (f64, f64) {
        self.at
    }

    fn coords(&self, n: usize) -> BTreeMap<String, f64> {
        let grid = &self.grid;
        let (i, j) = (n % grid.cols, n / grid.cols);
        BTreeMap::from([
            (
                "initial.alpha_dot".to_owned(),
                grid.ratio(i).sqrt() * grid.gamma_dot,
            ),
            ("body.iy".to_owned(), grid.ix * grid.inertia_ratio(j)),
        ])
    }

    fn cell(&self, n: usize, go_on: &(dyn Fn(f64) -> bool + Sync)) -> Result<Verdict, StepError> {
        let (i, j) = (n % self.grid.cols, n / self.grid.cols);
        let r = map::cell_reversals(&self.grid, self.source, i, j, go_on)?;
        Ok(Verdict::found(
            Answer::Count(r.count),
            true,
            vec![
                (FIRST.name, Value::Time(r.first)),
                (LAST.name, Value::Time(r.last)),
            ],
        ))
    }

    fn curve(&self) -> Vec<(f64, f64)> {
        let grid = &self.grid;
        (0..grid.rows)
            .filter_map(|j| {
                let r = grid.inertia_ratio(j);
                grid.critical(r).map(|c| (c, r))
            })
            .collect()
    }

    fn curve_meaning(&self) -> &'static str {
        "the critical ratio of Theorems 1.1-1.2"
    }

    fn cheap_cells(&self) -> bool {
        matches!(self.source, Source::Limit)
    }

    fn cell_seconds(&self, n: usize) -> f64 {
        map::cell_seconds(
            &self.grid,
            self.source,
            n % self.grid.cols,
            n / self.grid.cols,
        )
    }

    /// The full model's counts, certified ([`RegimeChart::certainty`]); the limit's cells are
    /// two quadratures each, cheaper than any certificate: every one is computed.
    fn infers(&self) -> bool {
        matches!(self.source, Source::Full { .. })
    }

    /// A count of the full model, certified where it cannot change inside a block: none, far
    /// above the critical curve (the quantity is the distance `α̇0²/γ̇0² − critical` of
    /// Theorems 1.1–1.2, less an allowance for finite `k`, [`FINITE_K_ALLOWANCE`] of `ix/iz`);
    /// two or more, by the phase of the window's end between reversals (the quantity is
    /// `(T − t₁)/h`, `h` the mean spacing of the reversals, the margin the end's distance from
    /// the last reversal and from the next, in spacings). A single reversal, or none below the
    /// curve, certifies nothing.
    fn certainty(&self, n: usize, v: &Verdict) -> Option<crate::physics::chart::Certainty> {
        use crate::physics::chart::Certainty;
        if self.source == Source::Limit {
            return None;
        }
        let found = v.computed().filter(|f| f.decided)?;
        let Answer::Count(count) = found.answer else {
            return None;
        };
        let (first, last) = (found.time(FIRST)?, found.time(LAST)?);
        let g = &self.grid;
        match count {
            0 => {
                let r = g.inertia_ratio(n / g.cols);
                // The critical ratio continued past iy = ix (negative there: every start
                // rotates).
                let critical = g.ix / g.iz * (1.0 / r.sqrt() - 1.0);
                let d = g.ratio(n % g.cols) - critical;
                let allowance = FINITE_K_ALLOWANCE * g.ix / g.iz;
                (d > allowance).then_some(Certainty {
                    value: d,
                    margin: d - allowance,
                })
            }
            1 => None,
            _ => {
                let (first, last) = (first?, last?);
                let h = (last - first) / (count - 1) as f64;
                if !(h.is_finite() && h > 0.0) {
                    return None;
                }
                let phase = (g.t_end - last) / h;
                Some(Certainty {
                    value: (g.t_end - first) / h,
                    margin: phase.min(1.0 - phase),
                })
            }
        }
    }

    fn lines(&self) -> Vec<usize> {
        Vec::new()
    }

    fn header(&self) -> Header {
        let (tolerance, stiffness) = match self.source {
            Source::Limit => (None, None),
            Source::Full { k, tolerance } => (Some(tolerance), Some(k)),
        };
        Header {
            t_end: Some(self.grid.t_end),
            tolerance,
            stiffness,
            critical: true,
            ..Header::default()
        }
    }
}

impl ChartOf for RegimeChart {
    type Problem = Problem;

    fn for_pane(problem: &Problem, ask: PaneAsk) -> Self {
        let (cols, rows) = if ask.full { FULL_GRID } else { LIMIT_GRID };
        let (p, s) = (problem.params(), problem.start());
        let gamma_dot = if s.gamma_dot == 0.0 { 1.0 } else { s.gamma_dot };
        // The ratio axis spans `(0, ix/iz]`: the critical curve crosses the plot from
        // `iy/ix = 1/4` (where it equals `ix/iz`) to `iy/ix = 1` (where it is 0). It depends on
        // `ix` and `iz` only, so loading a cell (which sets `iy`) keeps the axes.
        let grid = Grid {
            ratio_max: p.ix / p.iz,
            inertia: PANE_INERTIA,
            ..Grid::new(cols, rows, p.ix, p.iz, gamma_dot, ask.t_end)
        };
        let source = if ask.full {
            Source::Full {
                k: p.k,
                tolerance: ask.tolerance.max(FULL_TOLERANCE),
            }
        } else {
            Source::Limit
        };
        Self {
            grid,
            source,
            at: problem.chart_point(),
        }
    }

    fn for_study(problem: &Problem, ask: &StudyAsk, _title: &str) -> Result<Self, ChartError> {
        if ask.k.is_none() && ask.asked_tolerance.is_some() {
            return Err(ChartError::Refused("--tolerance sets the full model's runs (with --k); the limit's cells are quadratures"
                    .to_owned()));
        }
        let inertia = (
            ask.inertia_min.unwrap_or(DEFAULT_INERTIA.0),
            ask.inertia_max.unwrap_or(DEFAULT_INERTIA.1),
        );
        if inertia.0 >= inertia.1 {
            return Err(ChartError::Refused(format!(
                "--inertia-min ({}) must be below --inertia-max ({})",
                inertia.0, inertia.1
            )));
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
                let first_column = grid.ratio_max / grid.cols.max(1) as f64;
                for (ratio, i) in [
                    (first_column, grid.inertia.0),
                    (first_column, grid.inertia.1),
                    (grid.ratio_max, grid.inertia.1),
                    (grid.ratio_max, grid.inertia.0),
                ] {
                    grid.params_of(ratio, i, k).map_err(|e| {
                        ChartError::Refused(format!("--k {}: {e}", crate::physics::Number(k)))
                    })?;
                }
                Source::Full {
                    k,
                    tolerance: ask.tolerance,
                }
            }
        };
        Ok(Self {
            grid,
            source,
            at: problem.chart_point(),
        })
    }

    fn load(&self, problem: &Problem, (x, y): (f64, f64)) -> Result<Problem, ParamError> {
        let g = &self.grid;
        let params = Params {
            iy: g.ix * y,
            ..*problem.params()
        };
        let start = Start {
            gamma: 0.0,
            alpha: 0.0,
            gamma_dot: g.gamma_dot,
            alpha_dot: x.sqrt() * g.gamma_dot,
        };
        Problem::new(params, start)
    }
}
