//! The pendulum's chart (issue 59; its own since issue 69): the stability of the upright (or the
//! hanging position) over `(a, b)` at the preset's `ε`, by the monodromy matrix of one forcing
//! period ([`super::floquet`]), against Kapitza's criterion `b² = 2a`.

use std::collections::BTreeMap;

use super::floquet::{Mathieu, Position, floquet};
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
        "stable",
        Kind::Flag,
        "The verdict: `|tr M| < 2`.",
    )),
    Column::Value(TRACE),
    Column::Value(TRACE_ERROR),
    Column::Decided,
    Column::Mark,
];

/// The monodromy matrix's trace.
const TRACE: Field = Field::new("trace", Kind::Number, "The monodromy trace.");
/// Its estimated error.
const TRACE_ERROR: Field = Field::new("trace_error", Kind::Number, "Its estimated error.");

/// A cell's verdict from its Floquet computation.
fn verdict(f: &super::floquet::Floquet) -> Verdict {
    Verdict::found(
        Answer::Stable(f.stable),
        f.decided,
        vec![
            (TRACE.name, Value::Number(Some(f.trace))),
            (TRACE_ERROR.name, Value::Number(Some(f.error))),
        ],
    )
}

/// The names of the axes, across and up (preset keys, or the rattleback's two ratios).
pub const AXES: [&str; 2] = ["pendulum.a", "pendulum.b"];

/// The pane's grid (one period's trace a cell: instant).
pub const PENDULUM_GRID: (usize, usize) = (48, 24);
/// The pendulum's trace tolerance when none is asked: a cell within 1e-10 of `|tr| = 2` is too
/// close to call.
pub const PENDULUM_TOLERANCE: f64 = 1e-10;
/// Seconds of CPU a DOP853 step of the trace takes (its five components, the cosine, the
/// tableau), measured over random cells (`cargo run --release --example chart_price pendulum`,
/// docs/benchmarks.md, issue 80): a cell's price is its predicted steps
/// ([`super::floquet::Mathieu::price_steps`]) at this rate.
pub const PENDULUM_STEP_SECONDS: f64 = 6e-7;

/// A pendulum chart: the stability of `position` over `(a, b)` at `ε`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PendulumChart {
    /// The preset's pendulum (its `ε`; its `a`, `b` are marked).
    pub params: Params,
    /// Which equilibrium.
    pub position: Position,
    /// `a` across.
    pub columns: Axis,
    /// `b` up.
    pub rows: Axis,
    /// The trace's tolerance.
    pub tolerance: f64,
}

impl PendulumChart {
    /// The default axes for `params`: `a` over `[0, 2a]` (or `[2a, 0]`, `[0, 2]` when `a = 0`),
    /// `b` log-spaced from a tenth of Kapitza's threshold at the largest `a` to well past where
    /// the shake destabilises the upright again (`εb ≈ 0.45`), so both edges of the stable band
    /// show.
    #[must_use]
    pub fn default_axes(p: &Params, cols: usize, rows: usize) -> (Axis, Axis) {
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
                name: AXES[0],
                min: lo,
                max: hi,
                cells: cols,
                log: false,
            },
            Axis {
                name: AXES[1],
                min: b_lo,
                max: b_hi,
                cells: rows,
                log: true,
            },
        )
    }

    /// The pendulum of cell `(i, j)`.
    #[must_use]
    pub fn params(&self, i: usize, j: usize) -> Params {
        Params {
            a: self.columns.at(i),
            b: self.rows.at(j),
            ..self.params
        }
    }
}

impl SceneChart for PendulumChart {
    fn title(&self) -> String {
        format!("stability (eps {})", tick(self.params.epsilon))
    }

    fn axes(&self) -> (Axis, Axis) {
        (self.columns, self.rows)
    }

    fn preset_point(&self) -> (f64, f64) {
        (self.params.a, self.params.b)
    }

    fn coords(&self, n: usize) -> BTreeMap<String, f64> {
        crate::physics::chart::axis_coords(self.axes(), n)
    }

    fn cell(&self, n: usize, go_on: &(dyn Fn(f64) -> bool + Sync)) -> Result<Verdict, StepError> {
        let (i, j) = (n % self.columns.cells, n / self.columns.cells);
        if !go_on(0.0) {
            return Err(StepError::Cancelled { t: 0.0 });
        }
        let f = crate::physics::fork::sequentially(|| {
            floquet(
                Mathieu::of(&self.params(i, j), self.position),
                self.tolerance,
            )
        })?;
        Ok(verdict(&f))
    }

    fn curve(&self) -> Vec<(f64, f64)> {
        let (x, y) = (self.columns, self.rows);
        if self.position == Position::Hanging {
            return Vec::new();
        }
        // Kapitza's curve sampled finely along a (four points a column).
        let n = 4 * x.cells;
        (0..=n)
            .filter_map(|k| {
                let a = x.min + (x.max - x.min) * k as f64 / n as f64;
                let b = (2.0 * a).sqrt();
                (a >= 0.0 && y.cell_of(b).is_some()).then_some((a, b))
            })
            .collect()
    }

    fn curve_meaning(&self) -> &'static str {
        match self.position {
            Position::Hanging => "none (the hanging position)",
            Position::Upright => "Kapitza's criterion b^2 = 2a (the limit eps -> 0)",
        }
    }

    fn cheap_cells(&self) -> bool {
        true
    }

    fn cell_seconds(&self, n: usize) -> f64 {
        let (i, j) = (n % self.columns.cells, n / self.columns.cells);
        PENDULUM_STEP_SECONDS
            * Mathieu::of(&self.params(i, j), self.position).price_steps(self.tolerance)
    }

    /// Every verdict, certified by its trace ([`super::floquet::certainty`]).
    fn infers(&self) -> bool {
        true
    }

    /// A decided trace: its Floquet angle inside the stable band, its exponent outside
    /// ([`super::floquet::certainty`]).
    fn certainty(&self, _: usize, v: &Verdict) -> Option<crate::physics::chart::Certainty> {
        let found = v.computed().filter(|f| f.decided)?;
        super::floquet::certainty(found.number(TRACE)?)
    }

    /// The columns where Mathieu's tongues leave the axis `q = 0`, `δ = n²/4` (`n = 0, 1, …`):
    /// `a = ± n²/(4ε²)`, positive for the hanging position, negative for the upright. A tongue
    /// there is exponentially thin at small `b` (its width goes as `qⁿ`).
    fn lines(&self) -> Vec<usize> {
        let x = self.columns;
        let e2 = self.params.epsilon * self.params.epsilon;
        let sign = match self.position {
            Position::Hanging => 1.0,
            Position::Upright => -1.0,
        };
        let mut lines = Vec::new();
        for n in 0..=x.cells.max(1) {
            let a = sign * (n as f64).powi(2) / (4.0 * e2);
            let beyond = if sign > 0.0 {
                a > x.max.max(x.min)
            } else {
                a < x.min.min(x.max)
            };
            if !a.is_finite() || beyond {
                break;
            }
            // The column holding the root, and its neighbour on the root's other side.
            if let Some(c) = x.cell_of(a) {
                lines.push(c);
                let centre = x.at(c);
                let other = if a > centre { c + 1 } else { c.wrapping_sub(1) };
                if other < x.cells {
                    lines.push(other);
                }
            }
        }
        lines
    }

    fn header(&self) -> Header {
        Header {
            tolerance: Some(self.tolerance),
            epsilon: Some(self.params.epsilon),
            position: Some(self.position.name()),
            ..Header::default()
        }
    }
}

impl ChartOf for PendulumChart {
    type Problem = Problem;

    fn for_pane(problem: &Problem, ask: PaneAsk) -> Self {
        let p = *problem.params();
        let (a, b) = ask.axes_from;
        let axes_of = Params { a, b, ..p };
        let (columns, rows) = Self::default_axes(&axes_of, PENDULUM_GRID.0, PENDULUM_GRID.1);
        Self {
            params: p,
            position: Position::Upright,
            columns,
            rows,
            tolerance: PENDULUM_TOLERANCE,
        }
    }

    fn for_study(problem: &Problem, ask: &StudyAsk, _title: &str) -> Result<Self, ChartError> {
        let params = *problem.params();
        if let Some((lo, hi)) = ask.rows.filter(|r| r.0 <= 0.0) {
            return Err(ChartError::Refused(format!(
                "--rows {lo},{hi}: the pendulum's b is log-spaced; both ends must be positive"
            )));
        }
        let (columns, rows) = ask.ranged(Self::default_axes(&params, ask.grid.0, ask.grid.1));
        // Every corner is a pendulum the scene accepts (the same validator as a preset's).
        for a in [columns.min, columns.max] {
            for b in [rows.min, rows.max] {
                Problem::new(Params { a, b, ..params }, *problem.start()).map_err(|error| {
                    ChartError::Corner {
                        x_name: "a",
                        x: a,
                        y_name: "b",
                        y: b,
                        error,
                    }
                })?;
            }
        }
        Ok(Self {
            params,
            position: if ask.hanging == Some(true) {
                Position::Hanging
            } else {
                Position::Upright
            },
            columns,
            rows,
            tolerance: ask.asked_tolerance.unwrap_or(PENDULUM_TOLERANCE),
        })
    }

    fn load(&self, problem: &Problem, (x, y): (f64, f64)) -> Result<Problem, ParamError> {
        let params = Params {
            a: x,
            b: y,
            ..*problem.params()
        };
        Problem::new(params, *problem.start())
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A pendulum chart for tests (this module's and `study::part`'s).
    pub(crate) fn pendulum(cols: usize, rows: usize) -> PendulumChart {
        let params = Params {
            a: 1.0,
            b: 2.0,
            epsilon: 0.1,
        };
        let (columns, rows) = PendulumChart::default_axes(&params, cols, rows);
        PendulumChart {
            params,
            position: Position::Upright,
            columns,
            rows,
            tolerance: PENDULUM_TOLERANCE,
        }
    }

    #[test]
    fn a_cell_is_a_function_of_its_coordinates_alone() {
        // Every cell of two grids equals the trace computed from its coordinates by itself.
        for c in [pendulum(9, 9), pendulum(4, 7)] {
            let len = c.columns.cells * c.rows.cells;
            for n in [0, 5, len - 1] {
                let coords = c.coords(n);
                let params = Params {
                    a: coords["pendulum.a"],
                    b: coords["pendulum.b"],
                    ..c.params
                };
                let f = floquet(Mathieu::of(&params, Position::Upright), c.tolerance).unwrap();
                assert_eq!(c.cell(n, &|_| true).unwrap(), verdict(&f));
            }
        }
    }
}
