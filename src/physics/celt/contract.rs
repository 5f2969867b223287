//! The celt's part of the scene contract: its run and its chart's cells against the independent
//! implementation (`scripts/celt_reference.py`, scipy's DOP853 on equations derived apart).

use crate::physics::chart::StudyAsk;
use crate::physics::contract::{
    Contract, Mismatch, PresetText, chart_references, float as f, near, num,
};

/// The celt's case: `celt-clockwise`, as shipped.
pub struct Case;

fn reference() -> serde_json::Value {
    let text = include_str!("../../../tests/fixtures/celt/references.json");
    let all: serde_json::Value = serde_json::from_str(text).unwrap_or_default();
    all["cases"]
        .as_array()
        .and_then(|c| c.iter().find(|c| c["preset"] == "celt-clockwise"))
        .map_or(serde_json::Value::Null, |c| c["reference"].clone())
}

impl Contract for Case {
    const PRESET: PresetText = PresetText::Shipped("celt-clockwise");

    fn events(json: &serde_json::Value) -> Option<u64> {
        json["events"]["reversals"]["count"].as_u64()
    }

    fn check_run(json: &serde_json::Value) -> Result<(), Mismatch> {
        let want = reference();
        for i in 0..3 {
            near(
                &format!("ω[{i}](10)"),
                num(&json["final"]["omega"][i]),
                num(&want["omega"][i]),
                1e-6,
            )?;
        }
        for key in ["reversals", "crossings"] {
            if json["events"][key]["count"] != want[key] {
                return Mismatch::err(format!(
                    "{} {key} against {}",
                    json["events"][key]["count"], want[key]
                ));
            }
        }
        Ok(())
    }

    /// `tests/it/charts.rs`'s coarse chart: 6×4 over the preset's own window.
    fn chart(base: StudyAsk) -> StudyAsk {
        StudyAsk {
            grid: (6, 4),
            ..base
        }
    }

    /// The count the reference's, or short by a pair whose reversal is then the reference's
    /// later one (a grazing dip, issue 82); the first reversal within the chart's tolerance;
    /// the growth rate of steady spin to 1e-6.
    fn check_cell(cell: &serde_json::Value, chart: &serde_json::Value) -> Result<(), Mismatch> {
        let (w, d) = (
            num(&cell["coords"]["initial.omega_z"]),
            num(&cell["coords"]["celt.product"]),
        );
        let rows = chart_references("celt_grid");
        let Some(r) = rows
            .iter()
            .find(|r| (f(r, "omega_z") - w).abs() < 1e-12 && (f(r, "product") - d).abs() < 1e-12)
        else {
            return Mismatch::err("no reference at this cell");
        };
        let want = r
            .get("reversals")
            .and_then(toml::Value::as_integer)
            .and_then(|n| u64::try_from(n).ok());
        let (got, first) = (cell["reversals"].as_u64(), f(r, "first_reversal"));
        let (Some(got), Some(want)) = (got, want) else {
            return Mismatch::err("no count");
        };
        if got == want {
            if first >= 0.0 {
                near(
                    "first reversal",
                    num(&cell["first_reversal"]),
                    first,
                    num(&chart["tolerance"]),
                )?;
            }
        } else {
            let later = cell["first_reversal"].as_f64().unwrap_or(f64::INFINITY);
            if !(want > got && (want - got) % 2 == 0 && later > first) {
                return Mismatch::err(format!("{got} reversals against {want}"));
            }
        }
        let truth = f(r, "growth_rate");
        near(
            "growth rate",
            num(&cell["growth_rate"]),
            truth,
            1e-6 * truth.abs().max(1e-3),
        )
    }
}
