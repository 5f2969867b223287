//! Studies of the limit `k → ∞` (issue 12): what the paper proves, made measurable.
//!
//! - [`sweep`]: the full motion at a ladder of stiffnesses against the limit, `sup |α_k − α_eff|`
//!   over `[0, T]` against `k` and its fitted slope (the paper: `α_k → α_eff` uniformly on
//!   compact intervals; measured O(1/k) on trapped starts);
//! - [`weak`]: the weak-* convergence of `γ̇² g^{3/2}` to `θ`: pointwise it keeps swinging
//!   between 0 and `2θ`, its moving averages settle;
//! - [`map`]: the number of reversals over a grid of `(α̇0²/γ̇0², iy/ix)` with the critical
//!   curve of Theorems 1.1–1.2, from the limit by quadrature (cheap) or the full model at a
//!   finite `k` (through `auto`).
//!
//! This layer sits above `physics` (it may use threads: the map spreads over all cores with
//! rayon) and below the commands and the explorer; it never draws on a terminal. Every
//! computation is deterministic: parallel cells are independent and collected in order.
use crate::physics::numerics::elementary::Elementary;

pub mod ask;
pub mod chart;
pub mod map;
pub mod output;
pub mod part;
pub mod refine;
pub mod sweep;
pub mod weak;

#[cfg(not(target_arch = "wasm32"))]
pub mod svg;

pub use crate::physics::chart::tick;

/// Least-squares slope of `log10 y` against `log10 x` over the points where both are finite and
/// positive (`None` with fewer than two).
#[must_use]
pub fn log_log_slope(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
        .map(|&(x, y)| (x.e_log10(), y.e_log10()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    #[test]
    fn slope_of_a_power_law() {
        let pts: Vec<(f64, f64)> = (1..6)
            .map(|i| {
                let x = 10f64.powi(i);
                (x, 3.0 / x)
            })
            .collect();
        assert!((super::log_log_slope(&pts).unwrap() + 1.0).abs() < 1e-12);
        assert!(super::log_log_slope(&pts[..1]).is_none());
    }
}
