//! The scene contract's test-only scene (issue 69): a harmonic oscillator `x'' = −ω² x`, whose
//! exact solution is known, registered only in the library's own test build (`cfg(test)`), so
//! that what a new scene costs outside its folder is measured by a test
//! (`scene_contract`), not estimated in a review. Its events are the sign changes of `x`; its
//! `auto` is the one verification loop with DOP853 against a companion; its chart counts the
//! crossings over `(ω, v0)`.
//!
//! Outside this folder it needs its registry line (`physics/models.rs`, which also declares
//! this module and generates `simulate`'s dispatch to its report, `report.rs`).
use crate::physics::numerics::elementary::Elementary;

pub mod chart;
pub mod contract;
pub mod flows;
pub mod report;
pub mod scene;

use serde::{Deserialize, Serialize};

use crate::physics::params::ParamError;

/// The spring: `ω` (rad/s).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Params {
    /// The angular frequency.
    pub omega: f64,
}

/// The start.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Start {
    /// Position.
    pub x: f64,
    /// Velocity.
    pub v: f64,
}

/// A validated oscillator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Problem {
    params: Params,
    start: Start,
}

impl Problem {
    /// Validates and pairs.
    ///
    /// # Errors
    /// The first value outside what the table allows.
    pub fn new(params: Params, start: Start) -> Result<Self, ParamError> {
        let problem = Self { params, start };
        crate::physics::scene::Posed::checked_values(&problem)?;
        Ok(problem)
    }

    /// `ω`.
    #[must_use]
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The start.
    #[must_use]
    pub fn start(&self) -> &Start {
        &self.start
    }

    /// The exact `(x, v)` at `t`.
    #[must_use]
    pub fn exact(&self, t: f64) -> (f64, f64) {
        let (w, s) = (self.params.omega, self.start);
        let (sin, cos) = (w * t).e_sin_cos();
        (s.x * cos + s.v / w * sin, -s.x * w * sin + s.v * cos)
    }

    /// The energy per unit mass at `(x, v)`.
    #[must_use]
    pub fn energy(&self, x: f64, v: f64) -> f64 {
        0.5 * (v * v + self.params.omega.powi(2) * x * x)
    }

    /// The exact number of sign changes of `x` in `(0, t_end]` (a start on zero is none).
    #[must_use]
    pub fn exact_crossings(&self, t_end: f64) -> usize {
        // x = A cos(ωt − φ): zero where ωt − φ = π/2 + nπ.
        let (w, s) = (self.params.omega, self.start);
        let phi = (s.v / w).e_atan2(s.x);
        let first = (std::f64::consts::FRAC_PI_2 + phi).rem_euclid(std::f64::consts::PI);
        let first = if first == 0.0 && s.x == 0.0 {
            std::f64::consts::PI
        } else {
            first
        };
        let span = w * t_end;
        if span < first {
            0
        } else {
            let n = ((span - first) / std::f64::consts::PI).floor() as usize;
            n + 1
        }
    }
}
