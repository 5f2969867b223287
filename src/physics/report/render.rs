//! What every model's report shares: the work counters and the table's
//! method, comparison and work lines (each model's report keeps only its own sections, whose
//! names are a contract).

use std::fmt::Write as _;

use serde::Serialize;

use crate::physics::Method;
use crate::physics::numerics::dop853::Stats;
use crate::physics::scene::Words;

/// The work a run did.
#[derive(Serialize)]
pub(crate) struct StatsOut {
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evaluations: u64,
    pub wall_seconds: f64,
}

impl StatsOut {
    /// The counters of `stats`, with the run's wall time.
    pub fn of(stats: &Stats, wall_seconds: f64) -> Self {
        Self {
            steps: stats.steps,
            rejected: stats.rejected,
            rhs_evaluations: stats.rhs_evaluations,
            wall_seconds,
        }
    }
}

/// What `auto` chose, for the table.
pub(crate) struct Choice<'a> {
    pub method: Method,
    pub reason: &'a str,
    pub error_estimate: f64,
    pub met: bool,
}

impl<'a> Choice<'a> {
    /// `method`, chosen for `reason`, with its estimate and whether that met the tolerance.
    pub fn new(method: Method, reason: &'a str, error_estimate: f64, met: bool) -> Self {
        Self {
            method,
            reason,
            error_estimate,
            met,
        }
    }
}

/// The method line and, for `auto`, the line saying what it chose.
pub(crate) fn method_lines(
    o: &mut String,
    (method, tolerance, step): (Method, f64, Option<f64>),
    t_end: &str,
    auto: Option<Choice<'_>>,
) {
    let step = step.map(|h| format!(", step {h:.3e}")).unwrap_or_default();
    let _ = writeln!(
        o,
        "method        {method} (tolerance {tolerance:e}{step}), t_end = {t_end}"
    );
    if let Some(a) = auto {
        // An infinite estimate is no estimate: said in words (issue 56).
        let estimate = if a.error_estimate.is_finite() {
            format!("estimated error {:.1e}", a.error_estimate)
        } else {
            "no error estimate".to_owned()
        };
        let _ = writeln!(
            o,
            "auto chose    {}: {} ({estimate}{})",
            a.method,
            a.reason,
            if a.met { "" } else { ", tolerance NOT met" }
        );
    }
}

/// The slow state at `T` of the full model beside the limit's (`n/a` where it has none).
pub(crate) fn compare_rows(
    o: &mut String,
    limit_title: &str,
    words: Words,
    full: (f64, f64),
    limit: (Option<f64>, Option<f64>),
    comparison_error: Option<&str>,
) {
    let _ = writeln!(o);
    let _ = writeln!(o, "                   full model          {limit_title}");
    let shown = |v: Option<f64>| v.map_or_else(|| "n/a".to_owned(), |x| format!("{x:.9}"));
    for (name, f, l) in [
        (words.q_name, full.0, limit.0),
        (words.q_dot_name, full.1, limit.1),
    ] {
        let label = format!("{name}(T)");
        let _ = writeln!(o, "{label:<14}{f:>16.9}    {:>16}", shown(l));
    }
    if let Some(why) = comparison_error {
        let _ = writeln!(o, "  (no comparison with the limit: {why})");
    }
}

/// The work line.
pub(crate) fn work_line(o: &mut String, s: &StatsOut) {
    let _ = writeln!(
        o,
        "work          {} steps ({} rejected), {} rhs evaluations, {:.4} s",
        s.steps, s.rejected, s.rhs_evaluations, s.wall_seconds
    );
}

/// A report's energy when it is followed as a drift (the pendulum's `E_eff`, the celt's `E`):
/// both ends, the largest drift over the run, and where the scene says it, that drift relative
/// to the start (issue 69: one struct, not one per report).
#[derive(Serialize)]
pub(crate) struct DriftOut {
    pub initial: f64,
    #[serde(rename = "final")]
    pub final_: f64,
    pub max_drift: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rel_drift: Option<f64>,
}
