//! The celt's chart (issue 59; its own since issue 69): reversals in `[0, T]` and the first
//! one's time over the initial spin `ω_z` (both senses) and the product of inertia `D`, from the
//! preset's tilt, against the spin rates where steady spin turns from decaying to growing
//! ([`super::linear`]).
use crate::physics::numerics::elementary::Elementary;

use std::collections::BTreeMap;

use super::{Params, Problem};
use crate::physics::chart::{
    Answer, Axis, ChartError, ChartOf, Column, Field, Header, Kind, PaneAsk, SceneChart, StudyAsk,
    Value, Verdict, tick,
};
use crate::physics::{ParamError, StepError};

/// The fields of its cells (issue 83: declared here, written and read back from this list).
pub const COLUMNS: &[Column] = &[
    Column::Index,
    Column::X,
    Column::Y,
    Column::Answer(Field::new(
        "reversals",
        Kind::Count,
        "Reversals in the window.",
    )),
    Column::Value(FIRST),
    Column::Value(GROWTH),
    Column::Decided,
    Column::Mark,
];

/// The first reversal.
const FIRST: Field = Field::new(
    "first_reversal",
    Kind::Time,
    "The first reversal (s), `null` when none.",
);
/// The linear theory's rate at the cell.
const GROWTH: Field = Field::new(
    "growth_rate",
    Kind::Number,
    "The growth rate of steady spin at the cell's `ω_z` and `D` (1/s; positive: a small tilt grows).",
);

/// The names of the axes, across and up (preset keys, or the rattleback's two ratios).
pub const AXES: [&str; 2] = ["initial.omega_z", "celt.product"];

/// The pane's grid (two to four runs of the window a cell).
pub const CELT_GRID: (usize, usize) = (32, 16);
/// The celt's reversal-time tolerance when none is asked (s): a count needs its times to a
/// small fraction of a wobble (tenths of a second), not a trajectory's tolerance.
pub const CELT_TOLERANCE: f64 = 1e-4;

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

/// What a cell computed in lanes costs of its scalar price (issue 84): the CPU of
/// `celt-clockwise`'s default chart in lanes over the same cells computed alone, measured on
/// this project's 2-core machine (AVX2): 45.6 s of CPU against 100.1 s (docs/benchmarks.md).
/// Kept when the chart came to 0.37 of the scalar CPU (stop 94): a machine without AVX runs the
/// lanes at the baseline's width (0.81 of the scalar time), and the watchdog stops a chart at
/// twice its price, so the price errs on the long side.
const LANES_SHARE: f64 = 0.48;
/// The cells from which a chart's lanes are kept full: a smaller chart's chunks hold a few
/// cells each, whose runs leave lanes empty when a round asks one run a cell (8×4 at T = 100:
/// 0.58 of the scalar CPU, 4×3 at T = 200: 0.79; with chunks of at least four cells,
/// [`SceneChart::together`], 8×4 takes 2.7 s of CPU where it took 3.5–4.3 s), and it keeps the
/// scalar price, which errs on the safe side of the watchdog.
const LANES_FULL: usize = 1024;

/// A celt chart: reversals over `(ω_z, D)` from the preset's body and tilt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CeltChart {
    /// The preset's problem (its `ω_z` and `D` are marked).
    pub problem: Problem,
    /// `ω_z` across.
    pub columns: Axis,
    /// `D` up.
    pub rows: Axis,
    /// The window.
    pub t_end: f64,
    /// The reversal times' tolerance (s).
    pub tolerance: f64,
}

impl CeltChart {
    /// The default axes for `problem`: `ω_z` over `±2|ω_z|` (both senses; `±10` rad/s for a start
    /// without spin), `D` over `±2|D|` (`±0.05 √(ix iy)` for a body without skew), kept inside
    /// the positive-definite range.
    #[must_use]
    pub fn default_axes(problem: &Problem, cols: usize, rows: usize) -> (Axis, Axis) {
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
                name: AXES[0],
                min: -w,
                max: w,
                cells: cols,
                log: false,
            },
            Axis {
                name: AXES[1],
                min: -d,
                max: d,
                cells: rows,
                log: false,
            },
        )
    }

    /// The problem of cell `(i, j)`.
    ///
    /// # Errors
    /// When the body or start is not valid.
    pub fn problem(&self, i: usize, j: usize) -> Result<Problem, ParamError> {
        with_spin_and_product(&self.problem, self.columns.at(i), self.rows.at(j))
    }

    /// Predicted seconds of CPU cell `(i, j)` takes: its verification priced by the celt's cost
    /// model at the cell's own body and spin, as pairs of runs at its first tolerance (the run's
    /// own, [`super::reversal::first_round_seconds`]), more of them the longer the window.
    #[must_use]
    pub fn seconds_of(&self, i: usize, j: usize) -> f64 {
        let problem = self.problem(i, j).unwrap_or(self.problem);
        let pairs = CELT_PAIRS_SHORT
            + (CELT_PAIRS_LONG - CELT_PAIRS_SHORT) * (self.t_end / CELT_DECISION_TIME).min(1.0);
        let share = if self.columns.cells * self.rows.cells >= LANES_FULL {
            LANES_SHARE
        } else {
            1.0
        };
        share * pairs * super::reversal::first_round_seconds(&problem, self.t_end, self.tolerance)
    }

    /// The growth rate (1/s) at which the start's tilt `θ0` reaches a radian within the window:
    /// `ln(1/θ0)/T` (`None` for an upright start, which never tilts).
    #[must_use]
    pub fn reversal_growth(&self) -> Option<f64> {
        let tilt = super::tilt(&self.problem.initial_state());
        (tilt > 0.0 && tilt < 1.0).then(|| (1.0 / tilt).e_ln() / self.t_end)
    }
}

impl CeltChart {
    /// The problem of cell `n`, refused as a run would refuse it.
    fn problem_of(&self, n: usize) -> Result<Problem, StepError> {
        let (i, j) = (n % self.columns.cells, n / self.columns.cells);
        self.problem(i, j).map_err(|_| StepError::NotFinite {
            what: "a cell's body",
            t: 0.0,
        })
    }
}

/// A cell's verdict: its verified reversals and the growth rate of steady spin at its start.
fn verdict(problem: &Problem, r: super::reversal::Reversals) -> Verdict {
    let growth = super::linear::growth_rate(problem.params(), problem.start().omega[2]);
    Verdict::found(
        Answer::Count(r.count),
        r.decided,
        vec![
            (FIRST.name, Value::Time(r.first)),
            (GROWTH.name, Value::Number(Some(growth))),
        ],
    )
}

/// The celt's `problem` spun at `omega_z` with the product of inertia `product`.
///
/// # Errors
/// When the body or start is not valid.
pub fn with_spin_and_product(
    problem: &Problem,
    omega_z: f64,
    product: f64,
) -> Result<Problem, ParamError> {
    let mut params: Params = *problem.params();
    params.product = product;
    let mut start = *problem.start();
    start.omega[2] = omega_z;
    Problem::new(params, start, problem.band())
}

impl SceneChart for CeltChart {
    fn title(&self) -> String {
        format!("reversals (T {})", tick(self.t_end))
    }

    fn axes(&self) -> (Axis, Axis) {
        (self.columns, self.rows)
    }

    fn preset_point(&self) -> (f64, f64) {
        (self.problem.start().omega[2], self.problem.params().product)
    }

    fn coords(&self, n: usize) -> BTreeMap<String, f64> {
        crate::physics::chart::axis_coords(self.axes(), n)
    }

    fn cell(&self, n: usize, go_on: &(dyn Fn(f64) -> bool + Sync)) -> Result<Verdict, StepError> {
        let problem = self.problem_of(n)?;
        let r =
            super::reversal::reversals(&problem, self.t_end, self.tolerance, &mut |t| go_on(t))?;
        Ok(verdict(&problem, r))
    }

    /// Side by side, in lanes (issue 84): each cell's verification replayed over its runs as
    /// they come back, so each verdict is [`SceneChart::cell`]'s, bit for bit.
    fn cells(
        &self,
        ns: &[usize],
        go_on: &(dyn Fn(f64) -> bool + Sync),
        each: &mut dyn FnMut(usize, Result<Verdict, StepError>),
    ) {
        let mut problems = Vec::with_capacity(ns.len());
        let mut at = Vec::with_capacity(ns.len());
        for (k, &n) in ns.iter().enumerate() {
            match self.problem_of(n) {
                Ok(p) => {
                    problems.push(p);
                    at.push(k);
                }
                Err(e) => each(k, Err(e)),
            }
        }
        super::reversal::reversals_in_lanes(
            &problems,
            self.t_end,
            self.tolerance,
            go_on,
            &mut |i, r| each(at[i], r.map(|r| verdict(&problems[i], r))),
        );
    }

    fn curve(&self) -> Vec<(f64, f64)> {
        let (x, y) = (self.columns, self.rows);
        let Some(level) = self.reversal_growth() else {
            return Vec::new();
        };
        (0..y.cells)
            .flat_map(|j| {
                let mut p = *self.problem.params();
                p.product = y.at(j);
                super::linear::crossings(&p, x.min, x.max, 4 * x.cells + 1, level)
                    .into_iter()
                    .map(move |w| (w, y.at(j)))
            })
            .collect()
    }

    fn curve_meaning(&self) -> &'static str {
        "linear stability: where the steady spin's growth rate lifts the start's tilt to 1 rad within T"
    }

    fn cheap_cells(&self) -> bool {
        false
    }

    /// Enough cells a thread to keep its lanes full: a cell's first round asks two runs (the
    /// fine one and its companion), and later rounds one or two.
    fn together(&self) -> usize {
        crate::physics::numerics::lanes::LANES
    }

    fn cell_seconds(&self, n: usize) -> f64 {
        self.seconds_of(n % self.columns.cells, n / self.columns.cells)
    }

    /// None: every cell is computed. The celt's charts hold lone cells that no region's
    /// corners, edges or samples foretell, in every kind of region: on `celt-clockwise`'s
    /// default chart 13 cells count 3 or stay undecided inside regions of 1s, and on
    /// `celt-fast-spin`'s 24 undecided cells sit alone inside regions without a reversal whose
    /// every computed cell is quiet (as many raw sign changes of the spin as reversals).
    /// Inferring any region would change answers that `--exhaustive` gives.
    fn infers(&self) -> bool {
        false
    }

    fn certainty(&self, _: usize, _: &Verdict) -> Option<crate::physics::chart::Certainty> {
        None
    }

    fn lines(&self) -> Vec<usize> {
        Vec::new()
    }

    fn header(&self) -> Header {
        Header {
            t_end: Some(self.t_end),
            tolerance: Some(self.tolerance),
            ..Header::default()
        }
    }
}

impl ChartOf for CeltChart {
    type Problem = Problem;

    fn for_pane(problem: &Problem, ask: PaneAsk) -> Self {
        let anchored =
            with_spin_and_product(problem, ask.axes_from.0, ask.axes_from.1).unwrap_or(*problem);
        let (columns, rows) = Self::default_axes(&anchored, CELT_GRID.0, CELT_GRID.1);
        Self {
            problem: *problem,
            columns,
            rows,
            t_end: ask.t_end,
            tolerance: CELT_TOLERANCE,
        }
    }

    fn for_study(problem: &Problem, ask: &StudyAsk, _title: &str) -> Result<Self, ChartError> {
        let (columns, rows) = ask.ranged(Self::default_axes(problem, ask.grid.0, ask.grid.1));
        // Every corner is a body and start the scene accepts.
        for w in [columns.min, columns.max] {
            for d in [rows.min, rows.max] {
                with_spin_and_product(problem, w, d).map_err(|error| ChartError::Corner {
                    x_name: "omega_z",
                    x: w,
                    y_name: "product",
                    y: d,
                    error,
                })?;
            }
        }
        Ok(Self {
            problem: *problem,
            columns,
            rows,
            t_end: ask.t_end,
            tolerance: ask.asked_tolerance.unwrap_or(CELT_TOLERANCE),
        })
    }

    fn load(&self, problem: &Problem, (x, y): (f64, f64)) -> Result<Problem, ParamError> {
        with_spin_and_product(problem, x, y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::Model;

    /// Every shipped celt preset's problem and window.
    fn shipped() -> Vec<(&'static str, Problem, f64)> {
        crate::scenario::shipped::SHIPPED
            .iter()
            .filter_map(|(name, text)| {
                let p = crate::scenario::Preset::parse(text, name, name, &[]).ok()?;
                match p.model {
                    Model::Celt(c) => Some((*name, c, p.run.t_end)),
                    _ => None,
                }
            })
            .collect()
    }

    /// Every cell of `chart` computed in lanes and alone: the same verdicts, their numbers bit
    /// for bit (`{:?}` prints the shortest text that reads back as the same bits, and `-0`).
    fn lanes_are_lone_runs(chart: &CeltChart, what: &str) {
        let n = chart.columns.cells * chart.rows.cells;
        let ns: Vec<usize> = (0..n).collect();
        let mut lanes = vec![None; n];
        SceneChart::cells(chart, &ns, &|_| true, &mut |k, v| lanes[k] = Some(v));
        for (k, batched) in lanes.into_iter().enumerate() {
            let lone = chart.cell(k, &|_| true);
            assert_eq!(
                format!("{batched:?}"),
                format!("{:?}", Some(lone)),
                "{what}: cell {k}"
            );
        }
    }

    /// Issue 84: the cells of every shipped celt preset's chart (8×4 over its default axes, its
    /// window and tolerance) are in lanes what they are alone, bit for bit.
    #[test]
    fn every_shipped_chart_in_lanes_is_its_lone_cells() {
        let presets = shipped();
        assert!(presets.len() >= 7, "{} celt presets", presets.len());
        for (name, problem, t_end) in presets {
            let (columns, rows) = CeltChart::default_axes(&problem, 8, 4);
            let chart = CeltChart {
                problem,
                columns,
                rows,
                t_end,
                tolerance: CELT_TOLERANCE,
            };
            lanes_are_lone_runs(&chart, name);
        }
    }

    /// Issue 84: held-out windows, drawn from a printed seed over the shipped bodies and starts
    /// (spin ranges, products, windows and tolerances nobody chose): in lanes as alone.
    #[test]
    fn held_out_windows_in_lanes_are_their_lone_cells() {
        let seed: u64 = std::env::var("RATTLEBACK_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0x84_84);
        eprintln!("seed {seed} (RATTLEBACK_SEED to draw others)");
        let mut x = seed | 1;
        let mut uniform = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let presets = shipped();
        for window in 0..6 {
            let (name, problem, _) = presets[(uniform() * presets.len() as f64) as usize];
            let p = problem.params();
            let limit = 0.9 * (p.ix * p.iy).sqrt();
            let w = 1.0 + 25.0 * uniform();
            let d = limit * (0.05 + 0.9 * uniform());
            let (lo, hi) = (-d * uniform(), d * uniform());
            let chart = CeltChart {
                problem,
                columns: Axis {
                    name: AXES[0],
                    min: -w * uniform(),
                    max: w,
                    cells: 5,
                    log: false,
                },
                rows: Axis {
                    name: AXES[1],
                    min: lo,
                    max: hi.max(lo + 1e-3 * d),
                    cells: 3,
                    log: false,
                },
                t_end: 2.0 + 14.0 * uniform(),
                tolerance: 10f64.e_powf(-2.0 - 4.0 * uniform()),
            };
            lanes_are_lone_runs(
                &chart,
                &format!("seed {seed} window {window} ({name}): {chart:?}"),
            );
        }
    }
}
