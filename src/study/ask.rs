//! What a chart is asked (issue 66): the flags of `study map` ([`StudyAsk`]) and the whole
//! description a part carries ([`Description`]), from which `study merge` rebuilds the chart.
//! Below `chart` and `part`, importing neither.

use serde::{Deserialize, Serialize};

/// The largest cells per side.
pub const MAX_CELLS: usize = 2000;

pub use crate::physics::chart::StudyAsk;

/// The program and version that writes parts; a part of another is refused (its cells could
/// differ in their last bits, and the recomputation would call it edited).
pub const PROGRAM: &str = concat!("rattleback ", env!("CARGO_PKG_VERSION"));

/// The largest preset text a description may carry (a preset file's own cap is 1 MiB; one this
/// program writes is under 2 KiB).
pub const PRESET_BYTES: usize = 64 * 1024;

/// Everything that shapes a chart: `study merge` rebuilds the chart from this alone.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
#[serde(deny_unknown_fields)]
pub struct Description {
    /// The program and version that wrote the part (`rattleback 0.1.0`).
    pub program: String,
    /// The preset's values after `--set`, as a preset file (TOML).
    pub preset: String,
    /// Cells across and up.
    pub grid: [usize; 2],
    /// The window (the preset's `run.t_end` or `--t-end`).
    pub t_end: f64,
    /// `--t-end` as given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub asked_t_end: Option<f64>,
    /// The full model's tolerance (the preset's or `--tolerance`).
    pub tolerance: f64,
    /// `--tolerance` as given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub asked_tolerance: Option<f64>,
    /// `--ratio-max`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio_max: Option<f64>,
    /// `--inertia-min`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia_min: Option<f64>,
    /// `--inertia-max`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia_max: Option<f64>,
    /// `--k`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k: Option<f64>,
    /// `--columns`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub columns: Option<[f64; 2]>,
    /// `--rows`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rows: Option<[f64; 2]>,
    /// `--position`: `upright` or `hanging`.
    pub position: String,
    /// `--exhaustive`: every cell computed (a part's cells interleaved, `n mod N`), none
    /// inferred; absent when refined (a part holds whole blocks, issue 70).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub exhaustive: bool,
}

impl Description {
    /// The description of the chart `ask` makes of the preset written as `preset`.
    #[must_use]
    pub fn new(preset: String, ask: &StudyAsk) -> Self {
        Self {
            program: PROGRAM.to_owned(),
            preset,
            grid: [ask.grid.0, ask.grid.1],
            t_end: ask.t_end,
            asked_t_end: ask.asked_t_end,
            tolerance: ask.tolerance,
            asked_tolerance: ask.asked_tolerance,
            ratio_max: ask.ratio_max,
            inertia_min: ask.inertia_min,
            inertia_max: ask.inertia_max,
            k: ask.k,
            columns: ask.columns.map(|(a, b)| [a, b]),
            rows: ask.rows.map(|(a, b)| [a, b]),
            position: if ask.hanging == Some(true) {
                "hanging"
            } else {
                "upright"
            }
            .to_owned(),
            exhaustive: ask.exhaustive,
        }
    }

    /// The flags back, each checked as the command line checks it.
    ///
    /// # Errors
    /// Another program's part, or a value no command line could give.
    pub fn ask(&self, tolerance_range: (f64, f64)) -> Result<StudyAsk, DescriptionError> {
        use DescriptionError as E;
        if self.program != PROGRAM {
            return Err(E::Program(printable(&self.program)));
        }
        if self.preset.len() > PRESET_BYTES {
            return Err(E::PresetSize(self.preset.len()));
        }
        let [cols, rows] = self.grid;
        if !(1..=MAX_CELLS).contains(&cols) || !(1..=MAX_CELLS).contains(&rows) {
            return Err(E::Grid(cols, rows));
        }
        let positive = |name: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(v)
            } else {
                Err(E::NotPositive(name, v))
            }
        };
        let (lo, hi) = tolerance_range;
        let tolerance = |name: &'static str, v: f64| {
            if (lo..=hi).contains(&v) {
                Ok(v)
            } else {
                Err(E::Tolerance { name, v, lo, hi })
            }
        };
        let range = |name: &'static str, r: Option<[f64; 2]>| match r {
            None => Ok(None),
            Some([a, b])
                if a.is_finite()
                    && b.is_finite()
                    && a.abs() <= 1e12
                    && b.abs() <= 1e12
                    && a < b =>
            {
                Ok(Some((a, b)))
            }
            Some([a, b]) => Err(E::Range(name, a, b)),
        };
        // Upright is the default, as if not asked: a part says its position whatever its scene.
        let hanging = match self.position.as_str() {
            "upright" => None,
            "hanging" => Some(true),
            _ => return Err(E::Position),
        };
        let optional =
            |name: &'static str, v: Option<f64>| v.map(|v| positive(name, v)).transpose();
        Ok(StudyAsk {
            grid: (cols, rows),
            t_end: positive("t_end", self.t_end)?,
            asked_t_end: optional("asked_t_end", self.asked_t_end)?,
            tolerance: tolerance("tolerance", self.tolerance)?,
            asked_tolerance: self
                .asked_tolerance
                .map(|t| tolerance("asked_tolerance", t))
                .transpose()?,
            ratio_max: optional("ratio_max", self.ratio_max)?,
            inertia_min: optional("inertia_min", self.inertia_min)?,
            inertia_max: optional("inertia_max", self.inertia_max)?,
            k: optional("k", self.k)?,
            columns: range("columns", self.columns)?,
            rows: range("rows", self.rows)?,
            hanging,
            exhaustive: self.exhaustive,
        })
    }
}

/// Text from a file, shown: control characters dropped, at most 200 characters.
pub(super) fn printable(text: &str) -> String {
    text.chars().filter(|c| !c.is_control()).take(200).collect()
}
/// Why a part's description is not one a command line could give (issue 83: typed; each says
/// itself, and the caller names the file).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DescriptionError {
    /// Written by another program or build.
    #[error("written by `{0}`, not by this {PROGRAM}: run every shard with one build")]
    Program(String),
    /// A preset over the cap.
    #[error("its preset is {0} bytes (at most {PRESET_BYTES})")]
    PresetSize(usize),
    /// A grid out of bounds.
    #[error("grid {0}x{1}: each side a whole number from 1 to {MAX_CELLS}")]
    Grid(usize, usize),
    /// A value that must be a finite number > 0.
    #[error("{0} {1}: a finite number > 0")]
    NotPositive(&'static str, f64),
    /// A tolerance out of its range.
    #[error("{name} {v}: a number in [{lo:e}, {hi:e}]")]
    Tolerance {
        /// Which.
        name: &'static str,
        /// Its value.
        v: f64,
        /// The smallest allowed.
        lo: f64,
        /// The largest allowed.
        hi: f64,
    },
    /// A range out of bounds or out of order.
    #[error("{0} {1},{2}: finite numbers of magnitude at most 1e12, MIN below MAX")]
    Range(&'static str, f64, f64),
    /// A position that is neither.
    #[error("position: `upright` or `hanging`")]
    Position,
}
