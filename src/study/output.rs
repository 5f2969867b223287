//! What `study map` writes and reads back: a chart's axes, its cells and its header as JSON
//! (and the text table and CSV made from them), and the shards a chart is split into. Below
//! `chart`, which builds them: nothing here computes a cell.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::ask::MAX_CELLS;
use super::map;
use crate::physics::ModelKind;

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
            ModelKind::Rattleback | ModelKind::Celt => {
                ". none, 1-9 reversals, + 10 or more, ? two tolerances disagree"
            }
        };
        let mut o = format!(
            "{} over {} ({} … {}) across, {} ({} … {}{}) up\n{key}; * {}; @ the preset\n",
            match self.model {
                ModelKind::Kapitza => "stability of the pendulum",
                ModelKind::Rattleback | ModelKind::Celt => "reversals",
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
