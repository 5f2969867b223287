//! The oscillator's chart: the crossings of `x = 0` in `(0, T]` over `(ω, v0)`, each cell a
//! DOP853 run, against the exact count's boundaries.
use crate::physics::numerics::elementary::Elementary;

use std::collections::BTreeMap;

use super::{Params, Problem, Start};
use crate::physics::chart::{
    Axis, ChartError, ChartOf, Column, Field, Header, Kind, PaneAsk, SceneChart, StudyAsk, Verdict,
    tick,
};
use crate::physics::method::{Asked, Method, RunSpec};
use crate::physics::{ParamError, StepError};

/// The fields of its cells, its own (issue 83): a count of crossings, not of reversals.
pub const COLUMNS: &[Column] = &[
    Column::Index,
    Column::X,
    Column::Y,
    Column::Answer(Field::new(
        "crossings",
        Kind::Count,
        "Crossings of `x = 0` in the window.",
    )),
    Column::Mark,
];

/// The pane's grid.
pub const GRID: (usize, usize) = (16, 8);
/// The axes' names.
pub const AXES: [&str; 2] = ["oscillator.omega", "initial.v"];
/// A cell's run tolerance.
const TOLERANCE: f64 = 1e-10;

/// A crossing chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossingChart {
    /// The preset's problem.
    pub problem: Problem,
    /// `ω` across.
    pub columns: Axis,
    /// `v0` up.
    pub rows: Axis,
    /// The window.
    pub t_end: f64,
}

impl CrossingChart {
    fn axes_of(problem: &Problem, cols: usize, rows: usize) -> (Axis, Axis) {
        let w = problem.params().omega;
        let v = problem.start().v.abs().max(1.0);
        (
            Axis {
                name: AXES[0],
                min: 0.5 * w,
                max: 2.0 * w,
                cells: cols,
                log: false,
            },
            Axis {
                name: AXES[1],
                min: -2.0 * v,
                max: 2.0 * v,
                cells: rows,
                log: false,
            },
        )
    }

    fn problem_at(&self, (x, y): (f64, f64)) -> Result<Problem, ParamError> {
        Problem::new(
            Params { omega: x },
            Start {
                v: y,
                ..*self.problem.start()
            },
        )
    }
}

impl SceneChart for CrossingChart {
    fn title(&self) -> String {
        format!("crossings (T {})", tick(self.t_end))
    }
    fn axes(&self) -> (Axis, Axis) {
        (self.columns, self.rows)
    }
    fn preset_point(&self) -> (f64, f64) {
        (self.problem.params().omega, self.problem.start().v)
    }
    fn coords(&self, n: usize) -> BTreeMap<String, f64> {
        crate::physics::chart::axis_coords(self.axes(), n)
    }
    fn cell(&self, n: usize, go_on: &(dyn Fn(f64) -> bool + Sync)) -> Result<Verdict, StepError> {
        let (x, y) = (self.columns, self.rows);
        let problem = self
            .problem_at((x.at(n % x.cells), y.at(n / x.cells)))
            .map_err(|_| StepError::NotFinite {
                what: "a cell's oscillator",
                t: 0.0,
            })?;
        let spec = RunSpec::new(Asked::new(Method::Dop853, TOLERANCE, None, self.t_end), 0);
        let r = super::flows::run(&problem, &spec, &mut |t| go_on(t))?;
        Ok(Verdict::counted(r.crossing_count))
    }
    fn curve(&self) -> Vec<(f64, f64)> {
        Vec::new()
    }
    fn curve_meaning(&self) -> &'static str {
        "none"
    }
    fn cheap_cells(&self) -> bool {
        true
    }
    fn cell_seconds(&self, n: usize) -> f64 {
        let (x, y) = (self.columns, self.rows);
        let problem = self
            .problem_at((x.at(n % x.cells), y.at(n / x.cells)))
            .unwrap_or(self.problem);
        super::flows::cost_seconds(
            &problem,
            &Asked::new(Method::Dop853, TOLERANCE, None, self.t_end),
        )
    }

    /// Every count: certified by the exact solution's phase.
    fn infers(&self) -> bool {
        true
    }

    /// The exact solution `x = A cos(ωt − φ)` crosses zero where `u(t) = (ωt − φ − π/2)/π` is
    /// a whole number: the count changes only where `u(T)` or `u(0)` does. The quantity is
    /// `u(T)`, the margin the nearer of the two ends' distances to a whole number.
    fn certainty(&self, n: usize, v: &Verdict) -> Option<crate::physics::chart::Certainty> {
        use std::f64::consts::PI;
        v.answer()?;
        let (x, y) = (self.columns, self.rows);
        let problem = self
            .problem_at((x.at(n % x.cells), y.at(n / x.cells)))
            .ok()?;
        let (w, s) = (problem.params().omega, problem.start());
        let phi = (s.v / w).e_atan2(s.x);
        let u0 = (-phi - PI / 2.0) / PI;
        let ut = u0 + w * self.t_end / PI;
        let off = |u: f64| (u - u.round()).abs();
        Some(crate::physics::chart::Certainty {
            value: ut,
            margin: off(ut).min(off(u0)),
        })
    }

    fn lines(&self) -> Vec<usize> {
        Vec::new()
    }
    fn header(&self) -> Header {
        Header {
            t_end: Some(self.t_end),
            tolerance: Some(TOLERANCE),
            ..Header::default()
        }
    }
}

impl ChartOf for CrossingChart {
    type Problem = Problem;

    fn for_pane(problem: &Problem, ask: PaneAsk) -> Self {
        let (columns, rows) = Self::axes_of(problem, GRID.0, GRID.1);
        Self {
            problem: *problem,
            columns,
            rows,
            t_end: ask.t_end,
        }
    }

    fn for_study(problem: &Problem, ask: &StudyAsk, _title: &str) -> Result<Self, ChartError> {
        let (columns, rows) = ask.ranged(Self::axes_of(problem, ask.grid.0, ask.grid.1));
        let chart = Self {
            problem: *problem,
            columns,
            rows,
            t_end: ask.t_end,
        };
        for w in [columns.min, columns.max] {
            for v in [rows.min, rows.max] {
                chart
                    .problem_at((w, v))
                    .map_err(|error| ChartError::Corner {
                        x_name: "omega",
                        x: w,
                        y_name: "v",
                        y: v,
                        error,
                    })?;
            }
        }
        Ok(chart)
    }

    fn load(&self, problem: &Problem, (x, y): (f64, f64)) -> Result<Problem, ParamError> {
        Problem::new(
            Params { omega: x },
            Start {
                v: y,
                ..*problem.start()
            },
        )
    }
}
