//! The work budget: how long a run is predicted to take, from the cost model `auto` plans
//! with, before anything runs. Headless commands refuse a run predicted over
//! [`BUDGET_SECONDS`](crate::physics::budget::BUDGET_SECONDS) unless forced; `auto` checks each verification run against the budget
//! it is given before starting it (so a refinement that would take hours is refused, not run);
//! the explorer gives `auto` the same budget and offers a concrete method instead, which it
//! integrates a slice at a time.
//!
//! Seconds are on the calibration machine (docs/benchmarks.md). The prediction is a guide:
//! `cargo run --release --example budget_check` compares it with measured runs (concrete
//! methods within 0.8–3× on every shipped preset; `auto` as planned within 3×, its
//! refinements are checked one by one as they come). Pure: no clock.
use crate::physics::numerics::elementary::Elementary;

use super::integrators::default_step;

use super::params::Problem;
use crate::physics::method::Asked;
use crate::physics::method::Method;

/// Nanoseconds per right-hand-side evaluation of the full model (DOP853, RK4).
pub const NS_DOP853_EVAL: f64 = 36.0;
/// Nanoseconds per step of the Taylor series (order 20: six convolutions an order), measured
/// 0.50–0.52 µs a step on the averaging note's starts, k = 1e2 … 1e5
/// (`cargo run --release --example rattleback_taylor cost`).
pub const NS_TAYLOR_STEP: f64 = 520.0;
/// Nanoseconds per exact fast sub-flow of a splitting.
pub const NS_FAST_FLOW: f64 = 70.0;
/// Nanoseconds per unit of time of the effective models at the shipped presets' slow rates
/// (how `auto` ranks the corrected limit; [`cost_seconds`] scales it with the slow rate).
pub const NS_EFFECTIVE_PER_TIME: f64 = 3_000.0;
/// Nanoseconds per right-hand-side evaluation of the effective models.
pub const NS_EFFECTIVE_EVAL: f64 = 200.0;

/// Nanoseconds per right-hand-side evaluation of `averaged3` (its generated terms take 1.8–2.1×
/// the time of `averaged2`'s). With the evaluation count of [`dop853_evaluations`] this
/// predicts 1.1–1.9× the measured time of a run (the trapped and rotating starts of the
/// averaging note at k = 4e2 and 1e8, tolerances 1e-9 and 1e-12, T = 30): `auto` weighs its
/// probes against resolving with it.
pub const NS_AVERAGED3_EVAL: f64 = 180.0;
/// The same for `averaged2`, priced as [`NS_AVERAGED3_EVAL`] is against what it measures: a whole
/// run takes 47 ns per evaluation (the trapped start at k = 1e8, tolerance 2.4e-12: 1 629
/// evaluations in 76 µs) against `averaged3`'s 108 (175 µs), driver and reversal location
/// included. `auto` weighs it against `averaged3` at large `k` (issue 27).
pub const NS_AVERAGED2_EVAL: f64 = 80.0;

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
    155.0 * (1e-10 / tol.max(1e-14)).e_powf(0.125) * periods.max(1.0)
}

/// Steps the Taylor series is predicted to take at local tolerance `tol` over `periods`
/// periods of the fastest rate: 3.6–6.0 a period at 1e-12 (the averaging note's starts,
/// k = 1e2 … 1e5), its step growing like `tol^{1/20}`.
#[must_use]
pub fn taylor_steps(tol: f64, periods: f64) -> f64 {
    6.0 * (1e-12 / tol.max(1e-16)).e_powf(0.05) * periods.max(1.0)
}

/// Predicted seconds of one run of a concrete `method` with these settings over `[0, t_end]`
/// (`auto` is planned above: [`crate::physics::rattleback::plan::predicted_seconds`]).
#[must_use]
pub fn cost_seconds(problem: &Problem, ask: &Asked) -> f64 {
    let (method, tolerance, step, t_end) = (ask.method, ask.tolerance, ask.step, ask.t_end);
    let nu = fastest_rate(problem);
    let h = || step.unwrap_or_else(|| default_step(method, problem, tolerance, t_end));
    let periods = |rate: f64| rate * t_end / std::f64::consts::TAU;
    let ns = match method {
        Method::Taylor => taylor_steps(tolerance, periods(nu)) * NS_TAYLOR_STEP,
        // `dop853-projected` is not offered here (refused by `Model::resolve`): priced as DOP853.
        Method::Dop853 | Method::Dop853Projected | Method::Auto => {
            dop853_evaluations(tolerance, periods(nu)) * NS_DOP853_EVAL
        }
        Method::Effective | Method::EffectiveCorrected | Method::Averaged2 | Method::Averaged3 => {
            let per_eval = match method {
                Method::Averaged3 => NS_AVERAGED3_EVAL,
                Method::Averaged2 => NS_AVERAGED2_EVAL,
                _ => NS_EFFECTIVE_EVAL,
            };
            (dop853_evaluations(tolerance, periods(slow_rate(problem).max(1e-3))) * per_eval)
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
