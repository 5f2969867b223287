//! Generic numerics, shared by every model and owned by none: the adaptive DOP853 core (any
//! dimension, autonomous or forced), the symmetric compositions of two exactly solvable parts
//! over the [`compositions::Split`] trait, bracketed root finding for events, and Gauss–Legendre
//! quadrature, and what the Taylor-series integrators share ([`taylor`]).

pub mod compositions;
pub mod dop853;
pub mod dop853_lanes;
mod dop853_tableau;
pub mod eighth_power;
pub mod elementary;
pub mod lanes;
pub mod quadrature;
pub mod roots;
pub mod stepper;
pub mod taylor;
