//! Turning a requested method into the concrete integration that runs: `auto` is resolved
//! here, above [`run`](mod@super::run) and the integrators, so nothing below calls back up into the
//! planner. The explorer and `simulate` both go through [`resolve`], which is what makes them
//! show the same trajectory.
//!
//! A [`Resolved`] plan is plain data (method, tolerance, step): recordings store it, and replay
//! integrates the recorded plan, so a later change of `auto` never breaks an old session.

use super::auto;
use super::budget;
use super::params::Problem;
use super::policy::POLICY;
use crate::physics::method::Asked;
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::method::StepError;
use crate::physics::numerics::elementary::Elementary as _;
use crate::physics::plan::{AutoRules, Resolution, Resolved};

/// Resolves `method` for `problem` over `[0, t_end]` at `tolerance`; `go_on(t)` is asked every
/// few hundred steps of `auto`'s probes and verification runs whether to continue, and none of
/// them starts if it would take the predicted total over `budget` seconds.
///
/// # Errors
/// When a verification run fails, [`StepError::OverBudget`], or [`StepError::Cancelled`].
pub fn resolve(
    problem: &Problem,
    method: Method,
    tolerance: f64,
    t_end: f64,
    policy: AutoRules,
    budget: f64,
    go_on: &mut dyn FnMut(f64) -> bool,
) -> Result<Resolution, StepError> {
    if method != Method::Auto {
        return Ok(Resolution::named(method, tolerance));
    }
    match policy {
        AutoRules::Legacy => {
            let p = auto::legacy::plan_cancellable(problem, tolerance, t_end, go_on)?;
            Ok(Resolution::unverified(Resolved {
                method: p.method,
                tolerance: p.tolerance,
                step: p.step,
            }))
        }
        AutoRules::Verified => {
            let v = auto::run_auto_cancellable(
                problem,
                &RunSpec {
                    method,
                    tolerance,
                    step: None,
                    t_end,
                    samples: 0,
                    monitor_energy: false,
                },
                budget,
                go_on,
            )?;
            Ok(Resolution {
                plan: Resolved {
                    method: v.plan.method,
                    tolerance: v.run_settings.tolerance,
                    step: v.run_settings.step,
                },
                estimate: Some(v.error_estimate),
                shortfall: v.shortfall,
                floor: Some(v.round_off_floor),
            })
        }
    }
}

/// Predicted seconds of a whole run of `method` (for `auto`: its probes, when `k` calls for
/// them, then its first plan, run and verified by its companion; the averaged model counted as
/// admitted by the probes). Checked against the budget before anything starts; `auto` checks
/// its actual plan again, and stops refining past the time it allows itself.
#[must_use]
pub fn predicted_seconds(problem: &Problem, ask: &Asked) -> f64 {
    priced(problem, ask, 0.0)
}

/// The share of the starts whose probes `auto` runs that end resolved after all (the probes
/// measure a model error the tolerance cannot take, and the resolved plan runs after them), at
/// `k` up to [`REFUSED_AT_K`]; above it the share falls as `k^−1.5` (the averaged model's
/// error falls with `k`). Measured on the full model's chart (`cargo run --release --example
/// chart_price chart 7 K`, the `subcritical` preset's axes at 1e-9): 159 of 518 probed cells
/// at k = 1e4, 6 of 676 at k = 1e5 (issue 84). It is a fit over one family of starts: the
/// watchdog (twice the price) covers the rest.
pub const REFUSED_SHARE: f64 = 0.3;

/// See [`REFUSED_SHARE`].
pub const REFUSED_AT_K: f64 = 1e4;

/// The share of the probed starts of stiffness `k` expected to end resolved.
#[must_use]
pub fn refused_share(k: f64) -> f64 {
    REFUSED_SHARE * (REFUSED_AT_K / k).min(1.0).e_powf(1.5)
}

/// A chart cell's expected seconds: [`predicted_seconds`], except that where the probes decide
/// between the averaged model and resolving, the resolved plan's price counts with the
/// probability that they refuse the averaged model ([`refused_share`]). A chart adds up
/// thousands of cells, so an expectation prices it; a lone run's budget keeps the optimistic
/// price (its own plan is checked again once probed).
#[must_use]
pub fn expected_seconds(problem: &Problem, ask: &Asked) -> f64 {
    let refused = if auto::averaged_is_exact(problem) {
        0.0
    } else {
        refused_share(problem.params().k)
    };
    priced(problem, ask, refused)
}

/// [`predicted_seconds`] with the averaged model refused by the probes with probability
/// `refused`.
fn priced(problem: &Problem, ask: &Asked, refused: f64) -> f64 {
    let (method, tolerance, step, t_end) = (ask.method, ask.tolerance, ask.step, ask.t_end);
    if method != Method::Auto {
        return budget::cost_seconds(problem, &Asked::new(method, tolerance, step, t_end));
    }
    let resolved = auto::best_resolved(problem, tolerance, t_end).predicted_seconds;
    if auto::considers_averaged(problem, tolerance, t_end) {
        let local = (tolerance / (2.0 * POLICY.companion_error * auto::AVERAGED_GROWTH))
            .max(POLICY.tightest);
        let averaged =
            budget::cost_seconds(problem, &Asked::new(auto::AVERAGED, local, None, t_end))
                * (1.0 + VERIFY_FRACTION);
        let kept = resolved.min(averaged);
        // Nothing added where nothing is refused, where resolving is what is kept, or where it
        // cannot be priced at all (`0 · ∞` and `∞ − ∞` are not prices; a run past every
        // budget is refused when `auto` checks its own plan).
        let refusal = if refused > 0.0 && resolved > kept && resolved.is_finite() {
            refused * (resolved - kept)
        } else {
            0.0
        };
        auto::probes_cost(problem, t_end) + kept + refusal
    } else {
        resolved
    }
}

/// What `auto`'s verification adds to a run: a companion at twice the step (half the cost) or
/// at a 16× looser tolerance (about 0.7×).
pub const VERIFY_FRACTION: f64 = 0.7;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::rattleback::map::{FULL_CELL_OVER_RUN, Grid, Source, cell_seconds};

    /// A cell of `study map --grid 100x50 --k 1e4` on the `subcritical` preset's axes (column
    /// 82, row 4: `α̇0 ≈ 1.28`, `iy/ix ≈ 0.15`), whose probes refuse the averaged model (its
    /// model error about 2e-9 against 1e-9): it resolves. The chart prices it counting that
    /// chance (it was priced as the averaged model, and the chart ran past its watchdog); a
    /// lone run's budget keeps the optimistic price. Where the averaged model is exact
    /// (`ix = iy`), nothing is refused and both prices agree.
    #[test]
    fn a_chart_cell_prices_the_chance_that_the_probes_refuse_the_averaged_model() {
        let (k, tolerance) = (1e4, 1e-9);
        let grid = Grid {
            ratio_max: 2.0,
            inertia: (0.1, 10.0),
            ..Grid::new(100, 50, 2.0, 1.0, 1.0, 30.0)
        };
        let cell = grid
            .problem(grid.ratio(82), grid.inertia_ratio(4), k)
            .unwrap();
        let ask = Asked::new(Method::Auto, tolerance, None, 30.0);
        assert!(auto::considers_averaged(&cell, tolerance, 30.0));
        let decision = auto::plan_cancellable(&cell, tolerance, 30.0, &mut |_| true).unwrap();
        assert!(
            !decision.plan.method.is_averaged() && decision.probe.is_some(),
            "the probes refuse the averaged model here: {:?}",
            decision.plan
        );
        let resolved = auto::best_resolved(&cell, tolerance, 30.0).predicted_seconds;
        let optimistic = predicted_seconds(&cell, &ask);
        assert!(optimistic < 0.5 * resolved, "{optimistic} {resolved}");
        // The chart's price: at least a quarter of the resolved plan beyond the optimistic one
        // (a third of the probed cells resolve at this k, measured: docs/benchmarks.md).
        let price = cell_seconds(&grid, Source::Full { k, tolerance }, 82, 4) / FULL_CELL_OVER_RUN;
        assert!(
            price >= optimistic + 0.25 * (resolved - optimistic),
            "{price} {optimistic} {resolved}"
        );

        let exact = grid.problem(0.25, 1.0, k).unwrap();
        assert!(auto::averaged_is_exact(&exact));
        assert_eq!(
            predicted_seconds(&exact, &ask).to_bits(),
            expected_seconds(&exact, &ask).to_bits()
        );
    }

    proptest::proptest! {
    /// A chart cell's price is a price wherever a chart can ask one (issue 84: `0 · ∞` once
    /// gave NaN): never NaN, never below a lone run's optimistic price, and equal to it for a
    /// named method; `k` over three hundred decades, tolerances, horizons and starts as
    /// `study map` takes them.
    #[test]
    fn a_chart_cells_price_is_never_below_a_lone_runs_nor_nan(
        log_k in 0.0f64..300.0, log_tol in -14.0f64..-2.0, log_t in 0.0f64..5.0,
        log_ratio in -4.0f64..2.0, log_inertia in -3.0f64..3.0, named in proptest::bool::ANY,
    ) {
        let grid = Grid::new(1, 1, 2.0, 1.0, 1.0, 10f64.e_powf(log_t));
        let cell = grid.problem(10f64.e_powf(log_ratio), 10f64.e_powf(log_inertia), 10f64.e_powf(log_k));
        proptest::prop_assume!(cell.is_ok());
        let cell = cell.unwrap();
        let method = if named { Method::Dop853 } else { Method::Auto };
        let ask = Asked::new(method, 10f64.e_powf(log_tol), None, grid.t_end);
        let (lone, chart) = (predicted_seconds(&cell, &ask), expected_seconds(&cell, &ask));
        proptest::prop_assert!(!chart.is_nan() && chart >= 0.0, "{chart}");
        proptest::prop_assert!(chart >= lone, "{chart} {lone}");
        if named {
            proptest::prop_assert_eq!(chart.to_bits(), lone.to_bits());
        }
    }
    }
}
