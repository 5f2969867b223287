//! The pendulum's part of the scene contract: its run against an order-28 Taylor integration in
//! long double (`scripts/kapitza_taylor.c`, sharing no code with the crate), its chart's cells
//! against 30-digit Floquet traces (`scripts/chart_references.py`, mpmath).

use crate::physics::chart::StudyAsk;
use crate::physics::contract::{
    Contract, Mismatch, PresetText, chart_references, float as f, near, num,
};

/// The pendulum's case: `kapitza.toml`'s `upright_eps1e-3`, charted as `kapitza-upright`.
pub struct Case;

/// a = 1, b = 2, ε = 1e-3, θ = 0.3 upright, to t = 5.
const PRESET: &str = r#"
[preset]
name = "Kapitza: the contract's"
model = "kapitza"

[pendulum]
a = 1.0
b = 2.0
epsilon = 0.001

[initial]
theta = 0.3
theta_dot = 0.0

[run]
t_end = 5.0
tolerance = 1e-9
"#;

/// The Taylor reference's `(θ, θ̇)` at t = 5 (`tests/fixtures/reference/kapitza.toml`).
const AT_END: (f64, f64) = (0.026_960_167_219_073_763, 0.238_242_026_069_604_37);

impl Contract for Case {
    const PRESET: PresetText = PresetText::Toml(PRESET);

    fn events(json: &serde_json::Value) -> Option<u64> {
        json["events"]["swings"]["count"].as_u64()
    }

    fn check_run(json: &serde_json::Value) -> Result<(), Mismatch> {
        near("θ(5)", num(&json["final"]["theta"]), AT_END.0, 1e-6)?;
        near("θ̇(5)", num(&json["final"]["theta_dot"]), AT_END.1, 1e-6)
    }

    /// `kapitza-upright`'s chart in `tests/it/charts.rs`: 8×6, a in [0, 2], b in [0.2, 1000].
    fn chart(base: StudyAsk) -> StudyAsk {
        StudyAsk {
            grid: (8, 6),
            columns: Some((0.0, 2.0)),
            rows: Some((0.2, 1000.0)),
            ..base
        }
    }

    /// The trace within the cell's own estimate of the 30-digit one; a decided verdict the
    /// reference's.
    fn check_cell(cell: &serde_json::Value, _: &serde_json::Value) -> Result<(), Mismatch> {
        let (a, b) = (
            num(&cell["coords"]["pendulum.a"]),
            num(&cell["coords"]["pendulum.b"]),
        );
        let rows = chart_references("pendulum_grid");
        let Some(r) = rows.iter().find(|r| {
            (f(r, "a") - a).abs() <= 1e-12 * a.abs().max(1.0)
                && (f(r, "b") - b).abs() <= 1e-12 * b
                && (f(r, "epsilon") - 1e-3).abs() < 1e-15
        }) else {
            return Mismatch::err("no reference at this cell");
        };
        let (trace, error, truth) = (
            num(&cell["trace"]),
            num(&cell["trace_error"]),
            f(r, "trace"),
        );
        let scale = (0.5 * truth.abs()).max(1.0);
        near("trace", trace, truth, error.max(8.0 * f64::EPSILON * scale))?;
        let stable = r.get("stable").and_then(toml::Value::as_bool);
        if cell["decided"].as_bool() == Some(true) && cell["stable"].as_bool() != stable {
            return Mismatch::err(format!("stable {} against {stable:?}", cell["stable"]));
        }
        Ok(())
    }
}
