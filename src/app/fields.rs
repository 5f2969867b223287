//! The editable parameters of the explorer: how each is shown, nudged and typed, validated by
//! the same domain types as presets.

use crate::physics::integrators::Method;
use crate::physics::{Params, Problem, Start};
use crate::scenario::preset::TOLERANCE_RANGE;

/// Everything the parameter panel edits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Body and spring.
    pub params: Params,
    /// Start.
    pub start: Start,
    /// End of the run.
    pub t_end: f64,
    /// Integrator.
    pub method: Method,
    /// Tolerance.
    pub tolerance: f64,
}

impl Settings {
    /// These settings as a `rattleback simulate` command line that runs exactly them (every
    /// value as text that parses back to the same bits, whatever preset is the default).
    #[must_use]
    pub fn simulate_command(&self) -> String {
        use std::fmt::Write as _;
        let mut cmd = String::from("rattleback simulate");
        for f in Field::ALL {
            let value = f.exact(self);
            let _ = match f {
                Field::Method => write!(cmd, " --method {value}"),
                Field::Tolerance => write!(cmd, " --tolerance {value}"),
                Field::TEnd => write!(cmd, " --t-end {value}"),
                _ => write!(cmd, " --set {}.{}={value}", f.section(), f.label()),
            };
        }
        cmd
    }

    /// The validated problem (settings are kept valid, so this only fails on a bug).
    ///
    /// # Panics
    /// If the settings were made invalid, which every edit path prevents.
    #[must_use]
    pub fn problem(&self) -> Problem {
        Problem::new(self.params, self.start).expect("settings are kept valid")
    }
}

/// One row of the parameter panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// `ix`.
    Ix,
    /// `iy`.
    Iy,
    /// `iz`.
    Iz,
    /// Hooke constant.
    K,
    /// Initial tilt.
    Gamma,
    /// Initial spin angle.
    Alpha,
    /// Initial tilt rate.
    GammaDot,
    /// Initial spin rate.
    AlphaDot,
    /// End time.
    TEnd,
    /// Method.
    Method,
    /// Tolerance.
    Tolerance,
}

impl Field {
    /// Panel order.
    pub const ALL: [Self; 11] = [
        Self::Ix,
        Self::Iy,
        Self::Iz,
        Self::K,
        Self::Gamma,
        Self::Alpha,
        Self::GammaDot,
        Self::AlphaDot,
        Self::TEnd,
        Self::Method,
        Self::Tolerance,
    ];

    /// The name, as in presets.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Ix => "ix",
            Self::Iy => "iy",
            Self::Iz => "iz",
            Self::K => "k",
            Self::Gamma => "gamma",
            Self::Alpha => "alpha",
            Self::GammaDot => "gamma_dot",
            Self::AlphaDot => "alpha_dot",
            Self::TEnd => "t_end",
            Self::Method => "method",
            Self::Tolerance => "tolerance",
        }
    }

    /// The current value as text that parses back to exactly the same value.
    #[must_use]
    pub fn exact(self, s: &Settings) -> String {
        match self {
            Self::Method => s.method.name().to_owned(),
            _ => format!("{:?}", self.value(s)),
        }
    }

    /// The preset section the field belongs to (`body`, `spring`, `initial`, `run`).
    #[must_use]
    pub fn section(self) -> &'static str {
        match self {
            Self::Ix | Self::Iy | Self::Iz => "body",
            Self::K => "spring",
            Self::Gamma | Self::Alpha | Self::GammaDot | Self::AlphaDot => "initial",
            Self::TEnd | Self::Method | Self::Tolerance => "run",
        }
    }

    /// The field called `name`.
    #[must_use]
    pub fn named(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.label() == name)
    }

    /// The current value as shown.
    #[must_use]
    pub fn show(self, s: &Settings) -> String {
        match self {
            Self::Method => s.method.name().to_owned(),
            Self::K | Self::Tolerance => format!("{:.3e}", self.value(s)),
            _ => format_number(self.value(s)),
        }
    }

    fn value(self, s: &Settings) -> f64 {
        match self {
            Self::Ix => s.params.ix,
            Self::Iy => s.params.iy,
            Self::Iz => s.params.iz,
            Self::K => s.params.k,
            Self::Gamma => s.start.gamma,
            Self::Alpha => s.start.alpha,
            Self::GammaDot => s.start.gamma_dot,
            Self::AlphaDot => s.start.alpha_dot,
            Self::TEnd => s.t_end,
            Self::Tolerance => s.tolerance,
            Self::Method => 0.0,
        }
    }

    /// Validates `value` for this field and returns the new settings.
    ///
    /// # Errors
    /// What is wrong and what is allowed, for display in place.
    pub fn with_value(self, s: &Settings, value: f64) -> Result<Settings, String> {
        let mut n = *s;
        match self {
            Self::Ix => n.params.ix = value,
            Self::Iy => n.params.iy = value,
            Self::Iz => n.params.iz = value,
            Self::K => n.params.k = value,
            Self::Gamma => n.start.gamma = value,
            Self::Alpha => n.start.alpha = value,
            Self::GammaDot => n.start.gamma_dot = value,
            Self::AlphaDot => n.start.alpha_dot = value,
            Self::TEnd => {
                if !(value.is_finite() && value > 0.0) {
                    return Err(format!(
                        "t_end = {value} refused; allowed: a finite number > 0"
                    ));
                }
                n.t_end = value;
            }
            Self::Tolerance => {
                let (lo, hi) = TOLERANCE_RANGE;
                if !(value.is_finite() && (lo..=hi).contains(&value)) {
                    return Err(format!(
                        "tolerance = {value} refused; allowed: [{lo:e}, {hi:e}]"
                    ));
                }
                n.tolerance = value;
            }
            Self::Method => return Err("choose a method with ←/→ or type its name".to_owned()),
        }
        Problem::new(n.params, n.start).map_err(|e| format!("{e}; old value kept"))?;
        Ok(n)
    }

    /// The settings after a fine (`coarse = false`) or coarse nudge in direction `dir` (±1).
    ///
    /// # Errors
    /// When the nudge would leave the allowed range.
    pub fn nudge(self, s: &Settings, dir: f64, coarse: bool) -> Result<Settings, String> {
        let v = self.value(s);
        let next = match self {
            Self::Method => {
                let all = Method::ALL;
                let i = all.iter().position(|m| *m == s.method).unwrap_or(0);
                let n = all.len();
                let j = if dir > 0.0 {
                    (i + 1) % n
                } else {
                    (i + n - 1) % n
                };
                return Ok(Settings {
                    method: all[j],
                    ..*s
                });
            }
            // Log scales.
            Self::K | Self::Tolerance => v * 10f64.powf(dir * if coarse { 1.0 } else { 0.1 }),
            Self::TEnd => {
                v * if coarse {
                    2f64.powf(dir)
                } else {
                    1.0 + 0.1 * dir
                }
            }
            Self::Ix | Self::Iy | Self::Iz => v + dir * if coarse { 0.5 } else { 0.05 },
            Self::Gamma => v + dir * if coarse { 1e-2 } else { 1e-3 },
            Self::Alpha => {
                v + dir
                    * if coarse {
                        std::f64::consts::FRAC_PI_8
                    } else {
                        0.05
                    }
            }
            Self::GammaDot | Self::AlphaDot => v + dir * if coarse { 0.1 } else { 0.01 },
        };
        // Round away float dust from repeated nudges on linear fields.
        let next = if matches!(self, Self::K | Self::Tolerance | Self::TEnd) {
            next
        } else {
            (next * 1e9).round() / 1e9
        };
        self.with_value(s, next)
    }

    /// Parses typed text for this field.
    ///
    /// # Errors
    /// Not a number, or not allowed.
    pub fn with_text(self, s: &Settings, text: &str) -> Result<Settings, String> {
        let text = text.trim();
        if self == Self::Method {
            return Method::from_name(text)
                .map(|method| Settings { method, ..*s })
                .ok_or_else(|| format!("unknown method '{text}'; allowed: {}", Method::names()));
        }
        let value: f64 = text
            .parse()
            .map_err(|_| format!("'{text}' is not a number; old value kept"))?;
        self.with_value(s, value)
    }
}

/// A compact number: up to 6 significant digits, no trailing zeros.
#[must_use]
pub fn format_number(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e6) {
        return format!("{v:.4e}");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings() -> Settings {
        Settings {
            params: Params {
                ix: 2.0,
                iy: 1.0,
                iz: 1.0,
                k: 1e4,
            },
            start: Start {
                gamma: 0.0,
                alpha: 0.0,
                gamma_dot: 1.0,
                alpha_dot: 0.5,
            },
            t_end: 30.0,
            method: Method::Auto,
            tolerance: 1e-8,
        }
    }

    #[test]
    fn invalid_values_are_refused_with_the_reason() {
        let s = settings();
        let err = Field::Iy.with_text(&s, "-1").unwrap_err();
        assert!(
            err.contains("> 0") && err.contains("old value kept"),
            "{err}"
        );
        let err = Field::K.with_text(&s, "abc").unwrap_err();
        assert!(err.contains("not a number"), "{err}");
        assert!(
            Field::Iz
                .nudge(
                    &Settings {
                        params: Params {
                            iz: 0.05,
                            ..s.params
                        },
                        ..s
                    },
                    -1.0,
                    false
                )
                .is_err()
        );
        assert!((Field::K.nudge(&s, 1.0, true).unwrap().params.k - 1e5).abs() < 1e-9);
        assert_eq!(
            Field::Method.with_text(&s, "locked").unwrap().method,
            Method::Locked
        );
        assert_eq!(format_number(0.5), "0.5");
        assert_eq!(format_number(-0.0), "0");
    }
}
