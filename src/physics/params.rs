//! What every model's parameters share: the error a value outside the model's range gives.
//! Each model validates its own parameters (`rattleback::Params`, `kapitza::Params`) with it.

/// A value outside what the model allows.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParamError {
    /// The value is NaN or infinite.
    #[error("{field} = {value} is not a finite number; allowed: {allowed}")]
    NotFinite {
        /// Name of the field, as in presets (`ix`, `k`, `gamma_dot`, ...).
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// What the field accepts.
        allowed: &'static str,
    },
    /// The value is finite but out of range.
    #[error("{field} = {value} is out of range; allowed: {allowed}")]
    OutOfRange {
        /// Name of the field.
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// What the field accepts.
        allowed: &'static str,
    },
    /// Every value is finite, but a quantity the model derives from them is not (an overflow):
    /// the combination is out of what double precision can compute.
    #[error(
        "{field} = {value:e} makes {what} not a finite number ({derived}); choose values within about 1e-100 to 1e100"
    )]
    Derived {
        /// The value that drives it (the largest in size).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What overflowed.
        what: &'static str,
        /// Its value.
        derived: f64,
    },
}

impl ParamError {
    /// The name of the offending field.
    #[must_use]
    pub fn field(&self) -> &'static str {
        match self {
            Self::NotFinite { field, .. }
            | Self::OutOfRange { field, .. }
            | Self::Derived { field, .. } => field,
        }
    }
}
