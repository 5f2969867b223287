//! What every model's parameters share: the error a value outside the model's range gives.
//! Each model validates its own parameters (`rattleback::Params`, `kapitza::Params`) with it.

/// A value outside what the model allows.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParamError {
    /// The value is NaN or infinite.
    #[error("{field} = {} is not a finite number; allowed: {allowed}", super::Number(*.value))]
    NotFinite {
        /// Name of the field, as in presets (`ix`, `k`, `gamma_dot`, ...).
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// What the field accepts.
        allowed: &'static str,
    },
    /// The value is finite but out of range.
    #[error("{field} = {} is out of range; allowed: {allowed}", super::Number(*.value))]
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

/// What values a model parameter allows: one description shared by validation, presets, the
/// panel and the error messages.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Allowed {
    /// Any finite number.
    Finite,
    /// A finite number `> 0`.
    Positive,
    /// A finite number `>= 0`.
    NonNegative,
    /// A number in `[lo, hi]`, described by `text`.
    Between {
        /// Smallest value.
        lo: f64,
        /// Largest value.
        hi: f64,
        /// How the range reads in messages.
        text: &'static str,
    },
}

/// An angle: finite and of magnitude at most 1e6 rad. Beyond it a double resolves an angle to
/// no better than 1e-10 rad and a start is a turn of the same body modulo 2π anyway; a start of
/// 1e100 rad passed `check` and then failed its run at t = 0 (issue 66).
pub const ANGLE: Allowed = Allowed::Between {
    lo: -1e6,
    hi: 1e6,
    text: "an angle of magnitude at most 1e6 rad (a double resolves no finer beyond it; a start is the same modulo 2 pi)",
};

impl Allowed {
    /// How the range reads in messages.
    #[must_use]
    pub fn text(self) -> &'static str {
        match self {
            Self::Finite => "any finite number",
            Self::Positive => "a finite number > 0",
            Self::NonNegative => "a finite number >= 0",
            Self::Between { text, .. } => text,
        }
    }

    /// Whether `value` is allowed.
    #[must_use]
    pub fn contains(self, value: f64) -> bool {
        value.is_finite()
            && match self {
                Self::Finite => true,
                Self::Positive => value > 0.0,
                Self::NonNegative => value >= 0.0,
                Self::Between { lo, hi, .. } => (lo..=hi).contains(&value),
            }
    }

    /// Checks `value` of `field`.
    ///
    /// # Errors
    /// Not finite, or out of range.
    pub fn check(self, field: &'static str, value: f64) -> Result<(), ParamError> {
        let allowed = self.text();
        if !value.is_finite() {
            Err(ParamError::NotFinite {
                field,
                value,
                allowed,
            })
        } else if self.contains(value) {
            Ok(())
        } else {
            Err(ParamError::OutOfRange {
                field,
                value,
                allowed,
            })
        }
    }
}

/// How the panel steps a parameter and shows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// A tenth of a decade (fine) or a decade (coarse); shown in scientific notation.
    Log,
    /// Fixed increments; shown compactly, nudges rounded to 1e-9 against float dust.
    Linear {
        /// A fine step.
        fine: f64,
        /// A coarse step.
        coarse: f64,
    },
}

/// One parameter of a model, as presets, `--set`, the panel and the reports know it. Names are
/// a contract: add, never rename.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// The preset section (`body`, `spring`, `pendulum`, `initial`, …).
    pub section: &'static str,
    /// The key, also the panel's label and the field name in errors.
    pub key: &'static str,
    /// What values it allows.
    pub allowed: Allowed,
    /// Whether a preset must give it.
    pub required: bool,
    /// The value of an optional parameter a preset leaves out.
    pub default: f64,
    /// How the panel steps and shows it.
    pub scale: Scale,
    /// What it is, for the generated preset reference.
    pub doc: &'static str,
}

impl Scale {
    /// Steps of `fine` and `coarse`.
    #[must_use]
    pub const fn linear(fine: f64, coarse: f64) -> Self {
        Self::Linear { fine, coarse }
    }
}

impl ParamSpec {
    /// A row a preset must give.
    #[must_use]
    pub const fn required(
        (section, key): (&'static str, &'static str),
        allowed: Allowed,
        scale: Scale,
        doc: &'static str,
    ) -> Self {
        Self {
            required: true,
            ..Self::optional((section, key), allowed, 0.0, scale, doc)
        }
    }

    /// A row a preset may leave out, which is then `default`.
    #[must_use]
    pub const fn optional(
        (section, key): (&'static str, &'static str),
        allowed: Allowed,
        default: f64,
        scale: Scale,
        doc: &'static str,
    ) -> Self {
        Self {
            section,
            key,
            allowed,
            required: false,
            default,
            scale,
            doc,
        }
    }

    /// Checks every value of `values` (in the order of `specs`).
    ///
    /// # Errors
    /// The first value outside its range.
    pub fn check_all(specs: &[Self], values: &[f64]) -> Result<(), ParamError> {
        for (spec, v) in specs.iter().zip(values) {
            spec.allowed.check(spec.key, *v)?;
        }
        Ok(())
    }
}

/// Refuses a problem whose inputs are finite but whose derived quantities (`derived`, each
/// with what it is) are not, naming the input farthest from 1 in size among `inputs`.
///
/// # Errors
/// [`ParamError::Derived`] for the first derived quantity that is not finite.
pub fn check_derived(
    derived: &[(&'static str, f64)],
    inputs: &[(&'static str, f64)],
) -> Result<(), ParamError> {
    match derived.iter().find(|(_, v)| !v.is_finite()) {
        None => Ok(()),
        Some(&(what, value)) => {
            let (field, v) = super::extreme(inputs);
            Err(ParamError::Derived {
                field,
                value: v,
                what,
                derived: value,
            })
        }
    }
}

/// A model's validated problem's two accessors, its parameters and its start (fields `params`
/// and `start`, of the model's `Params` and `Start`), each documented by its own words.
macro_rules! params_and_start {
    ($params:literal, $start:literal) => {
        #[doc = $params]
        #[must_use]
        pub fn params(&self) -> &Params {
            &self.params
        }

        #[doc = $start]
        #[must_use]
        pub fn start(&self) -> &Start {
            &self.start
        }
    };
}
pub(crate) use params_and_start;
