//! What a scene gives the scene contract (issue 83), in its own folder (`SCENE/contract.rs`,
//! the library's own tests only): a preset and independent references for its numbers. The
//! contract that takes them through every output is `crate::scene_contract`.

use super::chart::StudyAsk;

/// A preset: a shipped one by name, or TOML text.
#[derive(Clone, Copy, Debug)]
pub enum PresetText {
    /// `presets/NAME.toml`.
    Shipped(&'static str),
    /// The text of a preset.
    Toml(&'static str),
}

/// What differs from a reference.
#[derive(Debug, Clone, PartialEq)]
pub struct Mismatch(pub String);

impl Mismatch {
    /// `Err` with the text.
    ///
    /// # Errors
    /// Always.
    pub fn err<T>(text: impl Into<String>) -> Result<T, Self> {
        Err(Self(text.into()))
    }
}

/// A scene's part of the contract: one `impl` in its folder.
pub trait Contract {
    /// A preset of the scene, quick to run.
    const PRESET: PresetText;
    /// The count of the scene's events in `simulate`'s JSON (the explorer's status bar shows
    /// the same count).
    fn events(json: &serde_json::Value) -> Option<u64>;
    /// `simulate`'s JSON of the preset against a reference from outside this code (an exact
    /// solution, a high-precision run, an independent implementation).
    ///
    /// # Errors
    /// What differs.
    fn check_run(json: &serde_json::Value) -> Result<(), Mismatch>;
    /// The chart the contract computes, from `base` (the preset's horizon and tolerance): small,
    /// since every cell is checked.
    fn chart(base: StudyAsk) -> StudyAsk;
    /// One cell of the chart (the whole as `study map --format json` writes it: its tolerance,
    /// its horizon) against a reference.
    ///
    /// # Errors
    /// What differs.
    fn check_cell(cell: &serde_json::Value, chart: &serde_json::Value) -> Result<(), Mismatch>;
}

/// The rows named `name` of the charts' high-precision references
/// (`tests/fixtures/reference/charts.toml`, made by `scripts/chart_references.py`).
#[must_use]
pub fn chart_references(name: &str) -> Vec<toml::Table> {
    let text = include_str!("../../tests/fixtures/reference/charts.toml");
    let table: toml::Table = text.parse().unwrap_or_default();
    table
        .get(name)
        .and_then(|v| v.as_array())
        .map(|rows| rows.iter().filter_map(|r| r.as_table().cloned()).collect())
        .unwrap_or_default()
}

/// A number of a reference row (`NaN` when absent, so that every comparison with it fails).
#[must_use]
pub fn float(row: &toml::Table, key: &str) -> f64 {
    row.get(key)
        .and_then(toml::Value::as_float)
        .unwrap_or(f64::NAN)
}

/// A number of a JSON value (`NaN` when absent, so that every comparison with it fails).
#[must_use]
pub fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

/// `Err` unless `|got − want| ≤ within`.
///
/// # Errors
/// The two and the bound.
pub fn near(what: &str, got: f64, want: f64, within: f64) -> Result<(), Mismatch> {
    if (got - want).abs() <= within {
        Ok(())
    } else {
        Mismatch::err(format!("{what} {got} against {want} (within {within:e})"))
    }
}
