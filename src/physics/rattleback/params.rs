//! Validated physical parameters and initial values.
//!
//! Raw numbers come from presets or the command line; `Problem::new` is the only way to obtain
//! a `Problem`, so every integrator can assume finite values, strictly positive inertia moments
//! and a strictly positive Hooke constant.
use crate::physics::numerics::elementary::Elementary;

use serde::Serialize;

use crate::physics::params::{Allowed, ParamError, ParamSpec, Scale, check_derived};

/// Inertia moments and Hooke constant of the body (docs/physics.md §1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Params {
    /// Inertia moment about the body's x axis.
    pub ix: f64,
    /// Inertia moment about the body's y axis.
    pub iy: f64,
    /// Inertia moment about the vertical axis (the spin axis).
    pub iz: f64,
    /// Hooke constant of the spring holding the tilt `gamma`.
    pub k: f64,
}

/// Initial values of the coordinates and their rates.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Start {
    /// Stiff tilt angle.
    pub gamma: f64,
    /// Spin angle.
    pub alpha: f64,
    /// Rate of the tilt.
    pub gamma_dot: f64,
    /// Spin rate.
    pub alpha_dot: f64,
}

impl Params {
    /// `g(α) = ix cos²α + iy sin²α`, the tilt's inertia at spin angle `α` (docs/physics.md §1).
    #[must_use]
    #[inline]
    pub fn g(&self, alpha: f64) -> f64 {
        let (s, c) = alpha.e_sin_cos();
        self.ix * c * c + self.iy * s * s
    }

    /// `g'(α) = (iy − ix) sin 2α`.
    #[must_use]
    #[inline]
    pub fn g_prime(&self, alpha: f64) -> f64 {
        (self.iy - self.ix) * (2.0 * alpha).e_sin()
    }

    /// Fast frequency `ω(α) = sqrt(k / g(α))`.
    #[must_use]
    #[inline]
    pub fn omega(&self, alpha: f64) -> f64 {
        (self.k / self.g(alpha)).sqrt()
    }

    /// The largest fast frequency over all `α`, `sqrt(k / min(ix, iy))`.
    #[must_use]
    pub fn omega_max(&self) -> f64 {
        (self.k / self.ix.min(self.iy)).sqrt()
    }

    /// Total energy `E = ½ g(α) γ̇² + ½ iz α̇² + ½ k γ²` at a state, conserved exactly by the
    /// flow (`model::energy` of a state vector).
    #[must_use]
    #[inline]
    pub fn energy(&self, gamma: f64, alpha: f64, gamma_dot: f64, alpha_dot: f64) -> f64 {
        0.5 * self.g(alpha) * gamma_dot * gamma_dot
            + 0.5 * self.iz * alpha_dot * alpha_dot
            + 0.5 * self.k * gamma * gamma
    }
}

const INERTIA: Scale = Scale::linear(0.05, 0.5);
const RATE: Scale = Scale::linear(0.01, 0.1);

/// The rattleback's parameters, in the panel's order. Names are a contract: add, never rename.
pub const PARAMS: [ParamSpec; 8] = [
    ParamSpec::required(
        ("body", "ix"),
        Allowed::Positive,
        INERTIA,
        "inertia moment about the body's x axis",
    ),
    ParamSpec::required(
        ("body", "iy"),
        Allowed::Positive,
        INERTIA,
        "inertia moment about the body's y axis",
    ),
    ParamSpec::required(
        ("body", "iz"),
        Allowed::Positive,
        INERTIA,
        "inertia moment about the vertical (spin) axis",
    ),
    ParamSpec::required(
        ("spring", "k"),
        Allowed::Positive,
        Scale::Log,
        "Hooke constant of the spring holding the tilt",
    ),
    ParamSpec::optional(
        ("initial", "gamma"),
        crate::physics::params::ANGLE,
        0.0,
        Scale::linear(1e-3, 1e-2),
        "initial tilt",
    ),
    ParamSpec::optional(
        ("initial", "alpha"),
        crate::physics::params::ANGLE,
        0.0,
        Scale::linear(0.05, std::f64::consts::FRAC_PI_8),
        "initial spin angle",
    ),
    ParamSpec::required(
        ("initial", "gamma_dot"),
        Allowed::Finite,
        RATE,
        "initial tilt rate",
    ),
    ParamSpec::required(
        ("initial", "alpha_dot"),
        Allowed::Finite,
        RATE,
        "initial spin rate",
    ),
];

/// A validated pair of parameters and initial values: the input of every integrator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Problem {
    params: Params,
    start: Start,
}

impl Problem {
    /// Validates both parts.
    ///
    /// # Errors
    /// The first field out of its allowed range.
    pub fn new(params: Params, start: Start) -> Result<Self, ParamError> {
        let problem = Self { params, start };
        let values = crate::physics::scene::Posed::checked_values(&problem)?;
        let p = &params;
        let inputs: Vec<(&'static str, f64)> = PARAMS.iter().map(|s| s.key).zip(values).collect();
        check_derived(
            &[
                (
                    "the energy",
                    p.energy(start.gamma, start.alpha, start.gamma_dot, start.alpha_dot),
                ),
                (
                    "the critical ratio",
                    (p.ix / p.iz) * ((p.ix / p.iy).sqrt() - 1.0),
                ),
                ("the fast frequency", p.omega_max()),
            ],
            &inputs,
        )?;
        // Inertias twelve orders of magnitude apart are no body the runs can hold: `iy = 1e20`
        // beside `ix = 2` passed the field checks and failed its run at t = 0 (issue 66).
        let named = [("ix", p.ix), ("iy", p.iy), ("iz", p.iz)];
        let mut sorted = named;
        sorted.sort_by(|a, b| a.1.total_cmp(&b.1));
        let [lo, mid, hi] = sorted;
        if hi.1 > 1e12 * lo.1 {
            // The one farthest from the middle one is the odd one out.
            let (field, value) = if hi.1 / mid.1 >= mid.1 / lo.1 { hi } else { lo };
            return Err(ParamError::OutOfRange {
                field,
                value,
                allowed: "inertias within a factor 1e12 of each other (the largest over the smallest)",
            });
        }
        Ok(problem)
    }

    crate::physics::params::params_and_start!("The body and spring.", "The initial values.");

    /// The same problem with another Hooke constant.
    ///
    /// # Errors
    /// When `k` is not finite and positive.
    pub fn with_k(&self, k: f64) -> Result<Self, ParamError> {
        Self::new(Params { k, ..self.params }, self.start)
    }
}

/// Fifty varied starts of the paper's body at `k` (a tilt `∝ k^{-1/2}`, so that the fast
/// action stays put): the family the averaged models' round-trip tests share.
#[cfg(test)]
pub(crate) fn varied_starts(k: f64) -> impl Iterator<Item = Problem> {
    (0..50).map(move |i| {
        let x = f64::from(i);
        paper_body(
            k,
            [
                (0.7 * x).e_sin() / k.sqrt(),
                (1.3 * x).e_sin(),
                1.0 + 0.3 * (0.9 * x).e_cos(),
                0.8 * (0.4 * x).e_cos(),
            ],
        )
    })
}

/// The largest `|α − α0|`, `|α̇ − α̇0|` of `round_trip` (start → averaged → reconstructed) over
/// [`varied_starts`] at `k`.
#[cfg(test)]
pub(crate) fn worst_round_trip(k: f64, round_trip: impl Fn(&Problem) -> (f64, f64)) -> f64 {
    varied_starts(k).fold(0.0, |worst: f64, pr| {
        let (a, ad) = round_trip(&pr);
        let s = pr.start();
        worst.max((a - s.alpha).abs()).max((ad - s.alpha_dot).abs())
    })
}

/// The paper's body (`ix = 2`, `iy = iz = 1`) on a spring `k`, from `(γ, α, γ̇, α̇)`: the
/// start the unit tests share.
#[cfg(test)]
pub(crate) fn paper_body(k: f64, [gamma, alpha, gamma_dot, alpha_dot]: [f64; 4]) -> Problem {
    let params = Params {
        ix: 2.0,
        iy: 1.0,
        iz: 1.0,
        k,
    };
    let start = Start {
        gamma,
        alpha,
        gamma_dot,
        alpha_dot,
    };
    Problem::new(params, start).expect("the paper's body")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> Params {
        Params {
            ix: 2.0,
            iy: 1.0,
            iz: 1.0,
            k: 1e4,
        }
    }

    #[test]
    fn rejects_non_positive_inertia_and_k() {
        let start = Start {
            gamma: 0.0,
            alpha: 0.0,
            gamma_dot: 1.0,
            alpha_dot: 0.5,
        };
        let err = Problem::new(
            Params {
                iy: -1.0,
                ..params()
            },
            start,
        )
        .unwrap_err();
        assert_eq!(err.field(), "iy");
        assert!(err.to_string().contains("> 0"), "{err}");
        let err = Problem::new(Params { k: 0.0, ..params() }, start).unwrap_err();
        assert_eq!(err.field(), "k");
        let err = Problem::new(
            params(),
            Start {
                alpha_dot: f64::NAN,
                ..start
            },
        )
        .unwrap_err();
        assert_eq!(err.field(), "alpha_dot");
        assert!(err.to_string().contains("finite"), "{err}");
    }

    #[test]
    fn g_matches_definition_at_quarter_turns() {
        let p = params();
        assert!((p.g(0.0) - 2.0).abs() < 1e-15);
        assert!((p.g(std::f64::consts::FRAC_PI_2) - 1.0).abs() < 1e-15);
        assert!(p.g_prime(0.0).abs() < 1e-15);
        assert!((p.g_prime(std::f64::consts::FRAC_PI_4) + 1.0).abs() < 1e-15);
    }
}
