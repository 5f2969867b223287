//! How a number that need not be finite is written in a file this program reads back (issue
//! 80): JSON has no infinity and no NaN, and serde writes both as `null`, which reads back as
//! "none" — a session whose `auto` estimate was infinite was then refused by its own
//! `--verify` as edited. Here a finite number is a JSON number, and the others are the strings
//! `"inf"`, `"-inf"` and `"nan"`; reading takes either (and `null` as none, as before).
//!
//! Use with serde's `with`: [`option`] for `Option<f64>`, [`triple`] for `Option<[f64; 3]>`;
//! the JSON Schema of such a field is [`Number`]'s.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A number as written: finite, or one of the three words (its JSON Schema).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Number {
    /// A finite number.
    Finite(f64),
    /// Not finite.
    Word(NonFinite),
}

/// The words for the numbers JSON cannot write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub enum NonFinite {
    /// `+∞`.
    #[serde(rename = "inf")]
    Inf,
    /// `−∞`.
    #[serde(rename = "-inf")]
    NegInf,
    /// Not a number.
    #[serde(rename = "nan")]
    NaN,
}

impl From<f64> for Number {
    fn from(x: f64) -> Self {
        if x.is_finite() {
            Self::Finite(x)
        } else if x.is_nan() {
            Self::Word(NonFinite::NaN)
        } else if x > 0.0 {
            Self::Word(NonFinite::Inf)
        } else {
            Self::Word(NonFinite::NegInf)
        }
    }
}

impl From<Number> for f64 {
    fn from(n: Number) -> Self {
        match n {
            Number::Finite(x) => x,
            Number::Word(NonFinite::Inf) => f64::INFINITY,
            Number::Word(NonFinite::NegInf) => f64::NEG_INFINITY,
            Number::Word(NonFinite::NaN) => f64::NAN,
        }
    }
}

/// The bits a number is compared by once written and read back: every NaN alike (the word
/// `"nan"` keeps no payload).
#[must_use]
pub fn bits(x: f64) -> u64 {
    if x.is_nan() {
        f64::NAN.to_bits()
    } else {
        x.to_bits()
    }
}

/// `Option<f64>`: absent or `null` for none, else a [`Number`].
pub mod option {
    use super::{Deserialize, Deserializer, Number, Serialize, Serializer};

    /// Writes `v`.
    ///
    /// # Errors
    /// The serializer's.
    #[allow(clippy::ref_option)] // serde's `with` hands a reference to the field
    pub fn serialize<S: Serializer>(v: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        v.map(Number::from).serialize(s)
    }

    /// Reads a value.
    ///
    /// # Errors
    /// Neither a number, one of the words, nor `null`.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        Ok(Option::<Number>::deserialize(d)?.map(f64::from))
    }
}

/// `Option<[f64; 3]>`: absent or `null` for none, else three [`Number`]s.
pub mod triple {
    use super::{Deserialize, Deserializer, Number, Serialize, Serializer};

    /// Writes `v`.
    ///
    /// # Errors
    /// The serializer's.
    #[allow(clippy::ref_option)] // serde's `with` hands a reference to the field
    pub fn serialize<S: Serializer>(v: &Option<[f64; 3]>, s: S) -> Result<S::Ok, S::Error> {
        v.map(|a| a.map(Number::from)).serialize(s)
    }

    /// Reads a value.
    ///
    /// # Errors
    /// Not three numbers or words, nor `null`.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 3]>, D::Error> {
        Ok(Option::<[Number; 3]>::deserialize(d)?.map(|a| a.map(f64::from)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct T {
        #[serde(default, with = "option", skip_serializing_if = "Option::is_none")]
        x: Option<f64>,
        #[serde(default, with = "triple", skip_serializing_if = "Option::is_none")]
        p: Option<[f64; 3]>,
    }

    #[test]
    fn every_number_reads_back_as_written() {
        for x in [
            0.0,
            -0.0,
            1.5e-300,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            let t = T {
                x: Some(x),
                p: Some([x, 1.0, x]),
            };
            let text = serde_json::to_string(&t).unwrap();
            let back: T = serde_json::from_str(&text).unwrap();
            assert_eq!(back.x.map(bits), Some(bits(x)), "{text}");
            assert_eq!(serde_json::to_string(&back).unwrap(), text);
        }
        let none = T { x: None, p: None };
        assert_eq!(serde_json::to_string(&none).unwrap(), "{}");
        let null: T = serde_json::from_str(r#"{"x":null}"#).unwrap();
        assert_eq!(null, none);
        assert_eq!(
            serde_json::to_string(&T {
                x: Some(f64::INFINITY),
                p: None
            })
            .unwrap(),
            r#"{"x":"inf"}"#
        );
        assert!(serde_json::from_str::<T>(r#"{"x":"infinity"}"#).is_err());
    }
}
