//! The work budget every scene shares: the largest predicted run accepted without `--force`,
//! the refusal, and durations for people. Each model predicts its own cost
//! (`rattleback::budget`, `kapitza::budget`).

/// Largest predicted run time, in seconds, accepted without `--force`.
pub const BUDGET_SECONDS: f64 = 60.0;

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
