//! Verification in segments (issue 27, item 4): how long the explorer waits before it draws a
//! long run. For each case, `auto` is resolved over the nested horizons the explorer verifies
//! (`sim::segments::horizons`), in order, each once and cold, as the explorer does: the first
//! is what the display waits for; the last is the run verified in one piece (what it waited for
//! before, and what `simulate` still does); their sum is the whole work, done on the second
//! core while the display plays.

use std::time::Instant;

use serde::Serialize;

use crate::physics::method::Method;
use crate::physics::plan::{AutoRules, PlanRequest};
use crate::scenario::preset::Override;
use crate::sim::segments::horizons;

/// The cases: shipped presets, each at a long horizon.
pub const CASES: [(&str, f64); 4] = [
    ("subcritical", 1000.0),
    ("subcritical", 10000.0),
    ("kapitza-falls", 1000.0),
    ("celt-clockwise", 1000.0),
];

/// One case measured.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The preset.
    pub preset: String,
    /// Its horizon here.
    pub t_end: f64,
    /// Its tolerance.
    pub tolerance: f64,
    /// The horizons verified, in order.
    pub segments: usize,
    /// The first horizon.
    pub first_horizon: f64,
    /// Seconds to verify the first segment: the wait before the first frame.
    pub first_seconds: f64,
    /// Seconds to verify the whole run in one piece (the last horizon).
    pub whole_seconds: f64,
    /// Seconds of all the horizons together.
    pub nested_seconds: f64,
    /// The method `auto` chose for the whole run.
    pub method: String,
    /// Whether the whole run met its tolerance.
    pub met: bool,
}

/// Measures every case (`quick`: the first only).
///
/// # Panics
/// When a shipped preset does not load (a build defect).
pub fn study(quick: bool, log: &mut dyn FnMut(&str)) -> Vec<Row> {
    let cases = if quick { &CASES[..1] } else { &CASES[..] };
    let mut rows = Vec::new();
    for &(name, t_end) in cases {
        let set = Override {
            key: "run.t_end".to_owned(),
            value: format!("{t_end}"),
        };
        let preset = crate::scenario::shipped::resolve(name, &[set]).expect("a shipped preset");
        let tolerance = preset
            .run
            .tolerance
            .unwrap_or(crate::physics::plan::DEFAULT_TOLERANCE);
        let all = horizons(t_end);
        let mut times = Vec::new();
        let mut last = None;
        for &h in &all {
            log(&format!("segments: {name} to {h}"));
            let request = PlanRequest {
                method: Method::Auto,
                tolerance,
                t_end: h,
                policy: AutoRules::Verified,
                budget: f64::INFINITY,
            };
            let start = Instant::now();
            let r = preset.model.resolve(&request, &mut |_| true);
            times.push(start.elapsed().as_secs_f64());
            last = r.ok();
        }
        let last = last.expect("the whole run resolves");
        rows.push(Row {
            preset: name.to_owned(),
            t_end,
            tolerance,
            segments: all.len(),
            first_horizon: all[0],
            first_seconds: times[0],
            whole_seconds: *times.last().unwrap_or(&0.0),
            nested_seconds: times.iter().sum(),
            method: last.plan.method.name().to_owned(),
            met: last.shortfall.is_none(),
        });
    }
    rows
}

/// The table printed.
#[must_use]
pub fn table(rows: &[Row]) -> String {
    use std::fmt::Write as _;
    let mut out = format!(
        "{:<16} {:>7} {:>5} {:>7} {:>10} {:>10} {:>10} {:>8} {:>7}  {}\n",
        "preset",
        "t_end",
        "segs",
        "first",
        "first s",
        "whole s",
        "nested s",
        "whole/1st",
        "nest/wh",
        "auto (whole)"
    );
    for r in rows {
        let _ = writeln!(
            out,
            "{:<16} {:>7} {:>5} {:>7} {:>10.3} {:>10.3} {:>10.3} {:>8.0}× {:>6.2}×  {}{}",
            r.preset,
            r.t_end,
            r.segments,
            r.first_horizon,
            r.first_seconds,
            r.whole_seconds,
            r.nested_seconds,
            r.whole_seconds / r.first_seconds.max(1e-9),
            r.nested_seconds / r.whole_seconds.max(1e-9),
            r.method,
            if r.met { "" } else { " (tolerance not met)" }
        );
    }
    out
}

/// Writes the rows as CSV.
///
/// # Errors
/// When the file cannot be written.
pub fn write_csv(rows: &[Row], path: &std::path::Path) -> std::io::Result<()> {
    super::write_csv_lines(
        path,
        "preset,t_end,tolerance,segments,first_horizon,first_seconds,whole_seconds,nested_seconds,method,met",
        rows,
        |r| {
            format!(
                "{},{},{:e},{},{},{:e},{:e},{:e},{},{}",
                r.preset,
                r.t_end,
                r.tolerance,
                r.segments,
                r.first_horizon,
                r.first_seconds,
                r.whole_seconds,
                r.nested_seconds,
                r.method,
                r.met
            )
        },
    )
}
