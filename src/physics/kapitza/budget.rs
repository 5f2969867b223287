//! The pendulum's cost model: how long a run is predicted to take, from the work each method
//! does, before anything runs. It sees every parameter that sets the work: `ε` (the forcing's
//! period), `b` (the forcing's strength `b/ε` and the ripple's velocity `b sin θ`), `a`, the
//! start's `θ̇`, the tolerance and the step. Seconds are on the calibration machine (release
//! build); `simulate`, the explorer and every replay ask it before a run starts.
use crate::physics::numerics::elementary::Elementary;

use super::{Problem, flows};
use crate::physics::method::Asked;
use crate::physics::method::Method;

/// Seconds one right-hand-side evaluation takes, about (this machine, release build).
pub const SECONDS_PER_EVALUATION: f64 = 4e-8;

/// The fastest rate of the full motion: the forcing's frequency `1/ε`, the frequency
/// `sqrt(|a| + b/ε)` of the forcing's peak, and the largest rate `|θ̇|` can reach
/// (`|θ̇0| + b + sqrt(|a| + b²)`: the start, the ripple's velocity, the limit's swing).
#[must_use]
pub fn fastest_rate(problem: &Problem) -> f64 {
    let p = problem.params();
    let s = problem.start();
    let swing = s.theta_dot.abs() + p.b + (p.a.abs() + p.b * p.b).sqrt();
    (1.0 / p.epsilon)
        .max((p.a.abs() + p.b / p.epsilon).sqrt())
        .max(swing)
        .max(1e-3)
}

/// The slow rate of the limit's motion.
#[must_use]
pub fn slow_rate(problem: &Problem) -> f64 {
    let p = problem.params();
    (1.0 + p.b * p.b + p.a.abs())
        .sqrt()
        .max(problem.start().theta_dot.abs())
}

/// Predicted seconds of one run of a concrete `method` over `[0, t_end]` (`auto` is priced by
/// `plan::predicted_seconds`, which knows what it resolves to).
#[must_use]
pub fn cost_seconds(problem: &Problem, ask: &Asked) -> f64 {
    let (method, tolerance, step, t_end) = (ask.method, ask.tolerance, ask.step, ask.t_end);
    let per_tol = tolerance.max(1e-16).e_powf(-0.125);
    let evaluations = match method {
        Method::Effective | Method::EffectiveCorrected | Method::Averaged2 | Method::Averaged3 => {
            12.0 * t_end * slow_rate(problem) * per_tol
        }
        Method::Dop853 => 7.2 * fastest_rate(problem) * t_end * per_tol,
        // Measured 29–48 µs over ε = 1e-1, T = 5 (tolerance 1e-9 … 1e-14) and 185–344 µs at
        // 1e-2 (`cargo run --release --example taylor_against_dop853`): about 5 evaluations'
        // time per unit of `rate · t` times `tol^(-1/20)` (28–50 µs and 280–500 µs).
        Method::Taylor => 5.0 * fastest_rate(problem) * t_end * tolerance.max(1e-16).e_powf(-0.05),
        m => {
            let h = step.unwrap_or_else(|| flows::default_step(m, problem, tolerance, t_end));
            let stages = match m {
                Method::Rk4 | Method::Strang => 4.0,
                Method::Yoshida4 => 3.0,
                Method::BlanesMoan4 => 6.0,
                Method::Yoshida6 => 7.0,
                _ => 15.0,
            };
            stages * t_end / h
        }
    };
    evaluations * SECONDS_PER_EVALUATION
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::kapitza::{Params, Start};

    fn problem(a: f64, b: f64, epsilon: f64, theta_dot: f64) -> Problem {
        Problem::new(
            Params { a, b, epsilon },
            Start {
                theta: 0.3,
                theta_dot,
            },
        )
        .unwrap()
    }

    /// The runs the reliability review found accepted and taking minutes are predicted over
    /// the minute now; the shipped presets' runs stay well under it.
    #[test]
    fn b_and_theta_dot_count() {
        let base = problem(1.0, 2.0, 1e-3, 0.0);
        let cheap = cost_seconds(&base, &Asked::new(Method::Dop853, 1e-8, None, 20.0));
        assert!(cheap < 1.0, "{cheap}");
        for hard in [problem(1.0, 1e6, 1e-3, 0.0), problem(1.0, 2.0, 1e-3, 1e9)] {
            for m in [Method::Dop853, Method::Auto] {
                let s =
                    super::super::plan::predicted_seconds(&hard, &Asked::new(m, 1e-8, None, 20.0));
                assert!(s > 60.0, "{m:?}: {s}");
            }
        }
        let tiny_step = cost_seconds(&base, &Asked::new(Method::Rk4, 1e-8, Some(1e-300), 20.0));
        assert!(tiny_step > 1e100, "{tiny_step}");
    }
}
