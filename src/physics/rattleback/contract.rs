//! The rattleback's part of the scene contract: its run against the public reference case
//! (`tests/fixtures/reference/cases.toml`, an adaptive 8th-order integration at 1e-13), its
//! chart's cells (the limit's counts) against the paper's theorem and an RK4 integration of the
//! effective equation written here from physics.md §2, sharing no code with the crate.

use crate::physics::chart::StudyAsk;
use crate::physics::contract::{Contract, Mismatch, PresetText, near, num};

/// The rattleback's case: `subcritical`, as shipped (ix = 2, iz = 1, γ̇0 = 1, to t = 30).
pub struct Case;

/// `cases.toml`'s `subcritical.full` at t = 30.
const ALPHA: f64 = 0.474_099_310_762;
const ALPHA_DOT: f64 = -0.370_025_529_631;
const TIMES: [f64; 7] = [
    2.216_603_809,
    6.649_818_919,
    11.083_057_386,
    15.516_338_030,
    19.949_685_798,
    24.383_137_801,
    28.816_757_190,
];

/// The reversal times of the effective motion `iz α̈ = θ g'(α) g(α)^{−3/2} / 2`,
/// `g = ix cos²α + iy sin²α`, `θ = ½ γ̇0² ix^{3/2}` (from α0 = γ0 = 0), by classical RK4 at
/// step 1e-3 with each sign change of α̇ placed by linear interpolation.
fn effective_reversals(ix: f64, iy: f64, iz: f64, alpha_dot0: f64, t_end: f64) -> Vec<f64> {
    let theta = 0.5 * ix.powf(1.5);
    let accel = |a: f64| {
        let g = ix * a.cos().powi(2) + iy * a.sin().powi(2);
        theta * (iy - ix) * (2.0 * a).sin() * g.powf(-1.5) / (2.0 * iz)
    };
    let h: f64 = 1e-3;
    let (mut t, mut a, mut v) = (0.0, 0.0, alpha_dot0);
    let mut out = Vec::new();
    while t < t_end - 1e-12 {
        let step = h.min(t_end - t);
        let (k1a, k1v) = (v, accel(a));
        let (k2a, k2v) = (v + 0.5 * step * k1v, accel(a + 0.5 * step * k1a));
        let (k3a, k3v) = (v + 0.5 * step * k2v, accel(a + 0.5 * step * k2a));
        let (k4a, k4v) = (v + step * k3v, accel(a + step * k3a));
        let a1 = a + step / 6.0 * (k1a + 2.0 * k2a + 2.0 * k3a + k4a);
        let v1 = v + step / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if v != 0.0 && v1.signum() != v.signum() {
            out.push(t + step * v / (v - v1));
        }
        (t, a, v) = (t + step, a1, v1);
    }
    out
}

impl Contract for Case {
    const PRESET: PresetText = PresetText::Shipped("subcritical");

    fn events(json: &serde_json::Value) -> Option<u64> {
        json["reversals"]["count"].as_u64()
    }

    fn check_run(json: &serde_json::Value) -> Result<(), Mismatch> {
        near("α(30)", num(&json["final"]["alpha"]), ALPHA, 1e-6)?;
        near("α̇(30)", num(&json["final"]["alpha_dot"]), ALPHA_DOT, 1e-6)?;
        let times = json["reversals"]["times"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        if times.len() != TIMES.len() {
            return Mismatch::err(format!("{} reversals against {}", times.len(), TIMES.len()));
        }
        for (got, want) in times.iter().zip(TIMES) {
            near("reversal time", num(got), want, 1e-6)?;
        }
        Ok(())
    }

    fn chart(base: StudyAsk) -> StudyAsk {
        StudyAsk {
            grid: (4, 3),
            ..base
        }
    }

    /// Theorem 1.1: the limit reverses when `α̇0² < (ix/iz)(√(ix/iy) − 1)` (here `γ̇0 = 1`), and
    /// then as often as the RK4 count, the first reversal within 1e-6 (a count is not judged
    /// when a reversal of the RK4 run falls within 1e-6 of the horizon).
    fn check_cell(cell: &serde_json::Value, _: &serde_json::Value) -> Result<(), Mismatch> {
        let (ix, iz) = (2.0, 1.0);
        let (iy, w) = (
            num(&cell["coords"]["body.iy"]),
            num(&cell["coords"]["initial.alpha_dot"]),
        );
        let trapped = iy < ix && w * w < (ix / iz) * ((ix / iy).sqrt() - 1.0);
        let got = cell["reversals"].as_u64();
        if trapped != got.is_some_and(|n| n > 0) {
            return Mismatch::err(format!(
                "{got:?} reversals, theorem 1.1 says trapped {trapped}"
            ));
        }
        let times = effective_reversals(ix, iy, iz, w, 30.0);
        if times.last().is_some_and(|t| 30.0 - t < 1e-6) {
            return Ok(());
        }
        if got != Some(times.len() as u64) {
            return Mismatch::err(format!("{got:?} reversals, RK4 {}", times.len()));
        }
        if let Some(first) = times.first() {
            near("first reversal", num(&cell["first_reversal"]), *first, 1e-6)?;
        }
        Ok(())
    }
}
