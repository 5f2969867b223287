//! The oscillator's part of the scene contract: its numbers against the exact solution
//! `x(t) = x0 cos ωt + (v0/ω) sin ωt`, its chart's cells against the exact count of crossings.

use super::{Params, Problem, Start};
use crate::physics::chart::StudyAsk;
use crate::physics::contract::{Contract, Mismatch, PresetText, near, num};

/// The oscillator's case.
pub struct Case;

/// ω = 2, (x, v) = (1, 0.5), to t = 10.
const PRESET: &str = r#"
[preset]
name = "Oscillator: the contract's"
model = "oscillator"

[oscillator]
omega = 2.0

[initial]
x = 1.0
v = 0.5

[run]
t_end = 10.0
tolerance = 1e-8
"#;

fn exact(omega: f64, v: f64) -> Result<Problem, Mismatch> {
    Problem::new(Params { omega }, Start { x: 1.0, v }).map_err(|e| Mismatch(e.to_string()))
}

impl Contract for Case {
    const PRESET: PresetText = PresetText::Toml(PRESET);

    fn events(json: &serde_json::Value) -> Option<u64> {
        json["events"]["count"].as_u64()
    }

    fn check_run(json: &serde_json::Value) -> Result<(), Mismatch> {
        let p = exact(2.0, 0.5)?;
        let (x, v) = p.exact(10.0);
        near("x(10)", num(&json["final"][0]), x, 1e-6)?;
        near("v(10)", num(&json["final"][1]), v, 1e-6)?;
        let count = Self::events(json).unwrap_or(u64::MAX);
        if count != p.exact_crossings(10.0) as u64 {
            return Mismatch::err(format!("{count} crossings"));
        }
        Ok(())
    }

    fn chart(base: StudyAsk) -> StudyAsk {
        StudyAsk {
            grid: (6, 4),
            ..base
        }
    }

    fn check_cell(cell: &serde_json::Value, _: &serde_json::Value) -> Result<(), Mismatch> {
        let c = &cell["coords"];
        let p = exact(num(&c["oscillator.omega"]), num(&c["initial.v"]))?;
        let (got, want) = (cell["crossings"].as_u64(), p.exact_crossings(10.0) as u64);
        if got == Some(want) {
            Ok(())
        } else {
            Mismatch::err(format!("{got:?} crossings, exactly {want}"))
        }
    }
}
