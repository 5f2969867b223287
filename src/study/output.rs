//! What `study map` writes and reads back: a chart's axes, its cells and its header as JSON
//! (and the text table and CSV made from them), and the shards a chart is split into. Below
//! `chart`, which builds them: nothing here computes a cell.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::ask::MAX_CELLS;
use super::map;
use crate::physics::ModelKind;

use crate::physics::chart::{Answer, Column};
pub use crate::physics::chart::{Axis, CellOutput};

/// The name of an axis a chart has, as `name` spells it (a part file is read back into [`Axis`]):
/// every scene's, from the registry.
fn known_axis(name: &str) -> Option<&'static str> {
    ModelKind::ALL
        .into_iter()
        .flat_map(|k| k.studies().chart.axis_keys)
        .find(|n| *n == name)
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
        let Some(name) = known_axis(&r.name) else {
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
    pub fn glyph(columns: &[Column], cell: &CellOutput) -> char {
        if cell.decided == Some(false) {
            return '?';
        }
        match cell.answer(columns) {
            Some(Answer::Stable(true)) => '#',
            Some(Answer::Stable(false) | Answer::Count(0)) | None => '.',
            Some(Answer::Count(n @ 1..=9)) => char::from_digit(n as u32, 10).unwrap_or('+'),
            Some(Answer::Count(_)) => '+',
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
        let words = self.model.studies().chart;
        let key = words.legend;
        let mut o = format!(
            "{} over {} ({} … {}) across, {} ({} … {}{}) up\n{key}; * {}; @ the preset\n",
            words.heading,
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
                        .map_or(' ', |cell| Self::glyph(words.csv, cell))
                };
                o.push(ch);
            }
            o.push('\n');
        }
        o
    }

    /// The chart in CSV, a row a cell, in the scene's columns (`ChartWords::csv`): the
    /// rattleback's as before issue 59 (`ratio,inertia_ratio,reversals`); the pendulum's `index`,
    /// its two keys, `stable, trace, trace_error, decided`; the celt's `index`, its two keys,
    /// `reversals, first_reversal, growth_rate, decided` (an empty `first_reversal` when none).
    #[must_use]
    pub fn csv(&self) -> String {
        let columns = self.model.studies().chart.csv;
        let (x, y) = (self.columns.name, self.rows.name);
        let line = |cell: &dyn Fn(crate::physics::chart::Column) -> String| {
            let mut l = columns
                .iter()
                .map(|&c| cell(c))
                .collect::<Vec<_>>()
                .join(",");
            l.push('\n');
            l
        };
        let mut o = line(&|c| c.heading(x, y).to_owned());
        for cell in &self.cells {
            o.push_str(&line(&|c| c.value(cell, x, y)));
        }
        o
    }
}
