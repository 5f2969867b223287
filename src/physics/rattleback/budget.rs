//! The work budget: how long a run is predicted to take, from the cost model `auto` plans
//! with, before anything runs. Headless commands refuse a run predicted over
//! [`BUDGET_SECONDS`] unless forced; `auto` checks each verification run against the budget
//! it is given before starting it (so a refinement that would take hours is refused, not run);
//! the explorer gives `auto` the same budget and offers a concrete method instead, which it
//! integrates a slice at a time.
//!
//! Seconds are on the calibration machine (docs/benchmarks.md). The prediction is a guide:
//! `cargo run --release --example budget_check` compares it with measured runs (concrete
//! methods within 0.8–3× on every shipped preset; `auto` as planned within 3×, its
//! refinements are checked one by one as they come). Pure: no clock.

use super::integrators::{Method, default_step};
use super::params::Problem;

/// Largest predicted run time, in seconds, accepted without `--force`.
pub const BUDGET_SECONDS: f64 = 60.0;

/// Nanoseconds per right-hand-side evaluation of the full model (DOP853, RK4).
pub const NS_DOP853_EVAL: f64 = 36.0;
/// Nanoseconds per exact fast sub-flow of a splitting.
pub const NS_FAST_FLOW: f64 = 70.0;
/// Nanoseconds per unit of time of the effective models at the shipped presets' slow rates
/// (how `auto` ranks the corrected limit; [`cost_seconds`] scales it with the slow rate).
pub const NS_EFFECTIVE_PER_TIME: f64 = 3_000.0;
/// Nanoseconds per right-hand-side evaluation of the effective models.
pub const NS_EFFECTIVE_EVAL: f64 = 200.0;

/// The slow rate of the problem: `sqrt(2E / min I)`, how fast the body turns on its energy.
#[must_use]
pub fn slow_rate(problem: &Problem) -> f64 {
    let p = problem.params();
    let y0 = super::model::initial_state(problem.start());
    let e = super::model::energy(p, &y0);
    (2.0 * e / p.ix.min(p.iy).min(p.iz)).sqrt()
}

/// The fastest rate of the problem: its largest fast frequency, or its slow rate at small `k`.
#[must_use]
pub fn fastest_rate(problem: &Problem) -> f64 {
    problem
        .params()
        .omega_max()
        .max(slow_rate(problem))
        .max(1e-3)
}

/// Right-hand-side evaluations DOP853 is predicted to need at local tolerance `tol` over
/// `periods` periods of the fastest rate.
#[must_use]
pub fn dop853_evaluations(tol: f64, periods: f64) -> f64 {
    155.0 * (1e-10 / tol.max(1e-14)).powf(0.125) * periods.max(1.0)
}

/// Predicted seconds of one run of a concrete `method` with these settings over `[0, t_end]`
/// (`auto` is planned above: [`crate::physics::plan::predicted_seconds`]).
#[must_use]
pub fn cost_seconds(
    problem: &Problem,
    method: Method,
    tolerance: f64,
    step: Option<f64>,
    t_end: f64,
) -> f64 {
    let nu = fastest_rate(problem);
    let h = || step.unwrap_or_else(|| default_step(method, problem, tolerance, t_end));
    let periods = |rate: f64| rate * t_end / std::f64::consts::TAU;
    let ns = match method {
        Method::Dop853 | Method::Auto => {
            dop853_evaluations(tolerance, periods(nu)) * NS_DOP853_EVAL
        }
        Method::Effective | Method::EffectiveCorrected | Method::Averaged2 => {
            (dop853_evaluations(tolerance, periods(slow_rate(problem).max(1e-3)))
                * NS_EFFECTIVE_EVAL)
                .max(NS_EFFECTIVE_PER_TIME * t_end * 0.1)
        }
        Method::Rk4 => 4.0 * NS_DOP853_EVAL * t_end / h(),
        Method::Strang | Method::Locked => NS_FAST_FLOW * t_end / h(),
        Method::Yoshida4 => 3.0 * NS_FAST_FLOW * t_end / h(),
        Method::BlanesMoan4 => 6.0 * NS_FAST_FLOW * t_end / h(),
        Method::Yoshida6 => 7.0 * NS_FAST_FLOW * t_end / h(),
        Method::Suzuki8 => 15.0 * NS_FAST_FLOW * t_end / h(),
    };
    ns * 1e-9
}

/// A run predicted over the budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OverBudget {
    /// Predicted seconds.
    pub predicted: f64,
    /// The budget.
    pub budget: f64,
}

impl std::fmt::Display for OverBudget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "predicted to take about {} (budget {})",
            duration(self.predicted),
            duration(self.budget)
        )
    }
}

/// Checks a prediction against `budget` seconds.
///
/// # Errors
/// [`OverBudget`] when the prediction exceeds it (or is not a number).
pub fn check(predicted: f64, budget: f64) -> Result<(), OverBudget> {
    if predicted <= budget {
        Ok(())
    } else {
        Err(OverBudget { predicted, budget })
    }
}

/// A duration for people: `40 s`, `12 min`, `3.1 h`, `5 days`, `2e9 years`.
#[must_use]
pub fn duration(seconds: f64) -> String {
    const MINUTE: f64 = 60.0;
    const HOUR: f64 = 3600.0;
    const DAY: f64 = 86_400.0;
    const YEAR: f64 = 365.25 * DAY;
    if !seconds.is_finite() {
        "forever".to_owned()
    } else if seconds < 1.0 {
        format!("{seconds:.2} s")
    } else if seconds < 2.0 * MINUTE {
        format!("{seconds:.0} s")
    } else if seconds < 2.0 * HOUR {
        format!("{:.0} min", seconds / MINUTE)
    } else if seconds < 2.0 * DAY {
        format!("{:.1} h", seconds / HOUR)
    } else if seconds < YEAR {
        format!("{:.0} days", seconds / DAY)
    } else if seconds < 1e4 * YEAR {
        format!("{:.0} years", seconds / YEAR)
    } else {
        format!("{:.0e} years", seconds / YEAR)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_well() {
        assert_eq!(duration(0.5), "0.50 s");
        assert_eq!(duration(40.0), "40 s");
        assert_eq!(duration(720.0), "12 min");
        assert_eq!(duration(3.1 * 3600.0), "3.1 h");
        assert_eq!(duration(5.0 * 86_400.0), "5 days");
        assert_eq!(duration(3e17), "1e10 years");
        assert_eq!(duration(f64::INFINITY), "forever");
        assert_eq!(duration(f64::NAN), "forever");
    }

    #[test]
    fn the_check_refuses_what_exceeds_and_what_is_not_a_number() {
        assert!(check(59.0, 60.0).is_ok());
        assert!(check(61.0, 60.0).is_err());
        assert!(check(f64::NAN, 60.0).is_err());
        assert!(check(f64::INFINITY, 60.0).is_err());
    }
}
