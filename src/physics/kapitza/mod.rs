//! Kapitza's inverted pendulum (docs/physics.md §5; the paper's introduction): a pendulum whose
//! pivot is shaken vertically at a high frequency `1/ε`, with `θ` measured from the upright.
//!
//! ```text
//!     full   θ̈_ε = (a + (b/ε) cos(t/ε)) sin θ_ε
//!     limit  θ̈ = a sin θ − (b²/4) sin 2θ,   E_eff = ½ θ̇² + a cos θ − (b²/8) cos 2θ
//! ```
//!
//! The fast shaking averages into the potential `−(b²/8) cos 2θ`, which makes the upright
//! `θ = 0` stable in the limit when `b² > 2a`. Positions converge as `ε → 0`; velocities only
//! weakly (`θ̇_ε` carries the O(1) ripple `b sin(t/ε) sin θ`).
//!
//! Everything about this model lives in this folder: parameters and validation (here), the
//! limit and its ripple (`limit`), the integrators (`flows`), the runner with its events
//! (`run`) and `auto` (`plan`). The state vector of the full model is `(θ, θ̇)` at time `t`;
//! no code outside this folder indexes it.
use crate::physics::numerics::elementary::Elementary;

pub mod averaged;
#[rustfmt::skip]
mod averaged3_terms;
pub mod budget;
pub mod chart;
#[cfg(test)]
pub mod contract;
pub mod floquet;
pub mod flows;
pub mod limit;
pub mod phase;
pub mod plan;
pub mod policy;
pub mod report;
pub mod run;
pub mod scene;
pub mod taylor;
pub mod weak;

pub use phase::FastPhase;

use serde::Serialize;

use super::params::{ParamError, check_derived};

/// The pendulum: gravity `a`, shaking amplitude `b`, fast period `2π ε`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Params {
    /// Gravity over length (`g/l`); the upright is unstable without shaking when `a > 0`.
    pub a: f64,
    /// Shaking strength: the pivot's acceleration is `(b/ε) cos(t/ε)` in units of `l`.
    pub b: f64,
    /// Fast time scale: the pivot oscillates with angular frequency `1/ε`.
    pub epsilon: f64,
}

/// The start, `θ` measured from the upright.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Start {
    /// Angle from the upright.
    pub theta: f64,
    /// Its rate.
    pub theta_dot: f64,
}

/// Largest `ε` accepted: beyond it the shaking is no longer fast against anything.
pub const EPSILON_MAX: f64 = 1.0;
/// Smallest `ε` accepted (below it `t/ε` loses its fractional part in a double within runs of
/// a few hundred time units).
pub const EPSILON_MIN: f64 = 1e-9;

impl Params {
    /// `b² − 2a`: the upright is stable in the limit when it is positive.
    #[must_use]
    pub fn threshold(&self) -> f64 {
        self.b * self.b - 2.0 * self.a
    }

    /// Whether the limit holds the upright (`b² > 2a`).
    #[must_use]
    pub fn stable_upright(&self) -> bool {
        self.threshold() > 0.0
    }

    /// The full model's forcing `a + (b/ε) cos(t/ε)`.
    #[must_use]
    #[inline]
    pub fn forcing(&self, t: f64) -> f64 {
        self.a + self.b / self.epsilon * (t / self.epsilon).e_cos()
    }

    /// `∫_t^{t+τ} forcing`: the exact kick over `τ` with `θ` frozen.
    #[must_use]
    #[inline]
    pub fn forcing_integral(&self, t: f64, tau: f64) -> f64 {
        self.a * tau + self.b * (((t + tau) / self.epsilon).e_sin() - (t / self.epsilon).e_sin())
    }
}

/// A validated pendulum and start.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Problem {
    params: Params,
    start: Start,
}

impl Problem {
    /// Validates and pairs.
    ///
    /// # Errors
    /// The first value outside what the model allows.
    pub fn new(params: Params, start: Start) -> Result<Self, ParamError> {
        let problem = Self { params, start };
        crate::physics::scene::Posed::checked_values(&problem)?;
        let p = &params;
        check_derived(
            &[
                ("the threshold b²−2a", p.b * p.b - 2.0 * p.a),
                ("the forcing b/ε", p.b / p.epsilon),
                (
                    "the limit's energy",
                    0.5 * start.theta_dot.powi(2) + p.a + p.b * p.b,
                ),
            ],
            &[
                ("a", p.a),
                ("b", p.b),
                ("epsilon", p.epsilon),
                ("theta_dot", start.theta_dot),
            ],
        )?;
        Ok(problem)
    }

    crate::physics::params::params_and_start!("The pendulum.", "The start.");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_names_the_field() {
        let ok = Params {
            a: 1.0,
            b: 2.0,
            epsilon: 1e-3,
        };
        let start = Start {
            theta: 0.1,
            theta_dot: 0.0,
        };
        assert!(Problem::new(ok, start).is_ok());
        for (p, field) in [
            (Params { b: -1.0, ..ok }, "b"),
            (Params { epsilon: 0.0, ..ok }, "epsilon"),
            (Params { epsilon: 2.0, ..ok }, "epsilon"),
            (Params { a: f64::NAN, ..ok }, "a"),
        ] {
            assert_eq!(Problem::new(p, start).unwrap_err().field(), field);
        }
        let bad = Start {
            theta: f64::INFINITY,
            theta_dot: 0.0,
        };
        assert_eq!(Problem::new(ok, bad).unwrap_err().field(), "theta");
    }

    #[test]
    fn the_kick_is_the_integral_of_the_forcing() {
        let p = Params {
            a: 0.7,
            b: 1.3,
            epsilon: 0.01,
        };
        let (t, tau) = (0.37, 0.004);
        let exact =
            crate::physics::numerics::quadrature::integrate_adaptive(t, t + tau, 1e-14, &mut |s| {
                p.forcing(s)
            });
        assert!((p.forcing_integral(t, tau) - exact).abs() < 1e-12);
    }
}
