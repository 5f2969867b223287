//! The editable parameters of the explorer: how each is shown, nudged and typed, validated by
//! the same domain types as presets. Each model has its rows ([`Field::rows`]); the run's rows
//! (`t_end`, `method`, `tolerance`) are shared.
use crate::physics::numerics::elementary::Elementary;

use crate::physics::params::{ParamSpec, Scale};
use crate::physics::rattleback::Problem;
use crate::physics::{Method, Model, ModelKind};
use crate::scenario::preset::TOLERANCE_RANGE;

/// Everything the parameter panel edits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The model and its validated problem.
    pub model: Model,
    /// End of the run.
    pub t_end: f64,
    /// Integrator.
    pub method: Method,
    /// Tolerance.
    pub tolerance: f64,
    /// The preset's fixed step (`run.step`), used by a fixed-step method asked by name.
    pub step: Option<f64>,
}

impl Settings {
    /// These settings as a `rattleback simulate` command line that runs exactly them (every
    /// value as text that parses back to the same bits, whatever preset is the default).
    #[must_use]
    pub fn simulate_command(&self, preset: Option<&str>) -> String {
        use std::fmt::Write as _;
        let preset =
            preset.unwrap_or_else(|| crate::scenario::shipped::base_preset(self.model.kind()));
        // A name with a space or a quote, quoted for the shell.
        let preset = crate::scenario::text::shell_word(preset);
        let mut cmd = format!("rattleback simulate --preset {preset}");
        for f in Field::rows(self.model.kind()) {
            let value = f.exact(self);
            let _ = match f {
                Field::Method => write!(cmd, " --method {value}"),
                Field::Tolerance => write!(cmd, " --tolerance {value}"),
                Field::TEnd => write!(cmd, " --t-end {value}"),
                Field::Param(_) => write!(cmd, " --set {}.{}={value}", f.section(), f.label()),
            };
        }
        if let Some(h) = self.step {
            let _ = write!(cmd, " --step {h:?}");
        }
        cmd
    }

    /// The rattleback's problem, when the model is the rattleback.
    #[must_use]
    pub fn rattleback(&self) -> Option<&Problem> {
        self.model.rattleback()
    }
}

/// One row of the parameter panel: one of the model's parameters (from its scene's table), or
/// one of the run's rows shared by every model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Field {
    /// A parameter of the model, as its scene describes it.
    Param(&'static ParamSpec),
    /// End time.
    TEnd,
    /// Method.
    Method,
    /// Tolerance.
    Tolerance,
}

/// The rows every model shares, after its own.
const RUN_ROWS: [Field; 3] = [Field::TEnd, Field::Method, Field::Tolerance];

impl Field {
    /// The panel's rows for `model`, in order: its parameters, then the run's.
    #[must_use]
    pub fn rows(model: ModelKind) -> Vec<Self> {
        model
            .params()
            .iter()
            .map(Self::Param)
            .chain(RUN_ROWS)
            .collect()
    }

    /// The name, as in presets.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Param(spec) => spec.key,
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

    /// The preset section the field belongs to (`body`, `spring`, `pendulum`, `initial`, `run`).
    #[must_use]
    pub fn section(self) -> &'static str {
        match self {
            Self::Param(spec) => spec.section,
            Self::TEnd | Self::Method | Self::Tolerance => "run",
        }
    }

    /// The field called `name`: a row of `model`'s panel, else a parameter of another model
    /// (which `with_value` then refuses with the reason).
    #[must_use]
    pub fn named(model: ModelKind, name: &str) -> Option<Self> {
        Self::rows(model)
            .into_iter()
            .chain(
                ModelKind::ALL
                    .iter()
                    .flat_map(|m| m.params().iter().map(Self::Param)),
            )
            .find(|f| f.label() == name)
    }

    /// The field `section.key` (as `--set` and a lesson's condition name it) of `model`'s
    /// panel; `None` for a key it has not (another scene's parameter of the same name too).
    #[must_use]
    pub fn keyed(model: ModelKind, key: &str) -> Option<Self> {
        let (section, name) = key.split_once('.')?;
        Self::rows(model)
            .into_iter()
            .find(|f| f.section() == section && f.label() == name)
    }

    /// The current value as shown.
    #[must_use]
    pub fn show(self, s: &Settings) -> String {
        match self {
            Self::Method => s.method.name().to_owned(),
            Self::Tolerance
            | Self::Param(ParamSpec {
                scale: Scale::Log, ..
            }) => format!("{:.3e}", self.value(s)),
            _ => format_number(self.value(s)),
        }
    }

    /// The value (NaN for a parameter of another model, a row no panel shows).
    fn value(self, s: &Settings) -> f64 {
        match self {
            Self::TEnd => s.t_end,
            Self::Tolerance => s.tolerance,
            Self::Method => f64::NAN,
            Self::Param(spec) => s.model.value(spec.key).unwrap_or(f64::NAN),
        }
    }

    /// Whether the field is a row of `model`'s panel.
    #[must_use]
    pub fn belongs_to(self, model: ModelKind) -> bool {
        Self::rows(model).contains(&self)
    }

    /// Validates `value` for this field and returns the new settings.
    ///
    /// # Errors
    /// What is wrong and what is allowed, for display in place.
    pub fn with_value(self, s: &Settings, value: f64) -> Result<Settings, EditError> {
        if !self.belongs_to(s.model.kind()) {
            return Err(EditError::NotHere {
                label: self.label().to_owned(),
                model: s.model.kind().name(),
            });
        }
        let mut n = *s;
        match self {
            Self::TEnd => {
                if !(value.is_finite() && value > 0.0) {
                    return Err(EditError::TEnd(value));
                }
                n.t_end = value;
            }
            Self::Tolerance => {
                let (lo, hi) = TOLERANCE_RANGE;
                if !(value.is_finite() && (lo..=hi).contains(&value)) {
                    return Err(EditError::Tolerance(value));
                }
                n.tolerance = value;
            }
            Self::Method => {
                return Err(EditError::MethodByName);
            }
            Self::Param(spec) => {
                n.model = s
                    .model
                    .with_value(spec.key, value)
                    .map_err(EditError::Param)?;
            }
        }
        Ok(n)
    }

    /// The settings after a fine (`coarse = false`) or coarse nudge in direction `dir` (±1).
    ///
    /// # Errors
    /// When the nudge would leave the allowed range.
    pub fn nudge(self, s: &Settings, dir: f64, coarse: bool) -> Result<Settings, EditError> {
        let v = self.value(s);
        let decades = || 10f64.e_powf(dir * if coarse { 1.0 } else { 0.1 });
        let next = match self {
            Self::Method => {
                let all = s.model.kind().methods();
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
            Self::Tolerance
            | Self::Param(ParamSpec {
                scale: Scale::Log, ..
            }) => v * decades(),
            Self::TEnd => {
                v * if coarse {
                    2f64.e_powf(dir)
                } else {
                    1.0 + 0.1 * dir
                }
            }
            Self::Param(ParamSpec {
                scale: Scale::Linear { fine, coarse: big },
                ..
            }) => {
                let next = v + dir * if coarse { *big } else { *fine };
                // Round away float dust from repeated nudges.
                (next * 1e9).round() / 1e9
            }
        };
        self.with_value(s, next)
    }

    /// Parses typed text for this field.
    ///
    /// # Errors
    /// Not a number, or not allowed.
    pub fn with_text(self, s: &Settings, text: &str) -> Result<Settings, EditError> {
        let text = text.trim();
        if self == Self::Method {
            let kind = s.model.kind();
            return match Method::from_name(text) {
                Some(method) if kind.offers(method) => Ok(Settings { method, ..*s }),
                Some(method) => Err(EditError::NotOffered {
                    method,
                    model: kind.name(),
                    offered: kind.method_names(),
                }),
                None => Err(EditError::UnknownMethod {
                    text: text.to_owned(),
                    offered: kind.method_names(),
                }),
            };
        }
        let value: f64 = text
            .parse()
            .map_err(|_| EditError::NotANumber(text.to_owned()))?;
        self.with_value(s, value)
    }
}

pub use crate::scenario::text::format_number;

/// Why an edit of the panel was refused (issue 83: typed; each says itself in place, and the
/// old value is kept).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EditError {
    /// A field of another scene.
    #[error("`{label}` is not a parameter of the {model} model")]
    NotHere {
        /// The field.
        label: String,
        /// The scene's name.
        model: &'static str,
    },
    /// A horizon that is not a finite number > 0.
    #[error("t_end = {} refused; allowed: a finite number > 0", crate::physics::Number(*.0))]
    TEnd(f64),
    /// A tolerance out of its range.
    #[error(
        "tolerance = {} refused; allowed: [{:e}, {:e}]",
        crate::physics::Number(*.0),
        TOLERANCE_RANGE.0,
        TOLERANCE_RANGE.1
    )]
    Tolerance(f64),
    /// A number given to the method's row.
    #[error("choose a method with ←/→ or type its name")]
    MethodByName,
    /// A parameter value the scene refuses.
    #[error("{0}; old value kept")]
    Param(crate::physics::ParamError),
    /// A method the scene does not offer.
    #[error("method {method} is not offered for the {model} model; allowed: {offered}")]
    NotOffered {
        /// The method.
        method: Method,
        /// The scene's name.
        model: &'static str,
        /// What it offers.
        offered: String,
    },
    /// A name that is no method.
    #[error("unknown method '{text}'; allowed: {offered}")]
    UnknownMethod {
        /// As typed.
        text: String,
        /// What the scene offers.
        offered: String,
    },
    /// Text that is not a number.
    #[error("'{0}' is not a number; old value kept")]
    NotANumber(String),
    /// A chart's cell loaded before the chart exists.
    #[error("no map yet")]
    NoMap,
    /// A chart's cell that is not a problem of the scene.
    #[error(transparent)]
    Cell(#[from] crate::physics::chart::ChartError),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::kapitza;

    fn settings() -> Settings {
        Settings {
            model: crate::physics::rattleback::paper_body(1e4, [0.0, 0.0, 1.0, 0.5]).into(),
            t_end: 30.0,
            method: Method::Auto,
            tolerance: 1e-8,
            step: None,
        }
    }

    fn pendulum() -> Settings {
        let params = kapitza::Params {
            a: 1.0,
            b: 2.0,
            epsilon: 1e-3,
        };
        let start = kapitza::Start {
            theta: 0.3,
            theta_dot: 0.0,
        };
        Settings {
            model: kapitza::Problem::new(params, start).unwrap().into(),
            ..settings()
        }
    }

    #[test]
    fn invalid_values_are_refused_with_the_reason() {
        let s = settings();
        let f = |name| Field::named(s.model.kind(), name).unwrap();
        let err = f("iy").with_text(&s, "-1").unwrap_err().to_string();
        assert!(
            err.contains("> 0") && err.contains("old value kept"),
            "{err}"
        );
        let err = f("k").with_text(&s, "abc").unwrap_err().to_string();
        assert!(err.contains("not a number"), "{err}");
        let small = f("iz").with_value(&s, 0.05).unwrap();
        assert!(f("iz").nudge(&small, -1.0, false).is_err());
        let k = f("k").nudge(&s, 1.0, true).unwrap();
        assert!((k.rattleback().unwrap().params().k - 1e5).abs() < 1e-9);
        assert_eq!(
            Field::Method.with_text(&s, "locked").unwrap().method,
            Method::Locked
        );
        assert_eq!(format_number(0.5), "0.5");
        assert_eq!(format_number(-0.0), "0");
    }

    #[test]
    fn the_pendulum_has_its_own_rows_and_methods() {
        let s = pendulum();
        let pendulum = s.model.kind();
        let f = |name| Field::named(pendulum, name).unwrap();
        assert_eq!(Field::rows(pendulum)[0].label(), "a");
        let e = f("epsilon").nudge(&s, -1.0, true).unwrap();
        assert!((e.model.kapitza().unwrap().params().epsilon - 1e-4).abs() < 1e-15);
        // Typed (issue 83): each refusal is its own variant, and says itself.
        let err = f("epsilon").with_text(&s, "0").unwrap_err();
        assert!(matches!(err, EditError::Param(_)), "{err:?}");
        let said = err.to_string();
        assert!(
            said.contains("epsilon") && said.contains("old value kept"),
            "{said}"
        );
        let err = Field::Method.with_text(&s, "locked").unwrap_err();
        assert!(
            matches!(
                err,
                EditError::NotOffered {
                    model: "kapitza",
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(
            err.to_string()
                .contains("not offered for the kapitza model")
        );
        let err = f("k").with_text(&s, "3").unwrap_err();
        assert!(
            matches!(
                err,
                EditError::NotHere {
                    model: "kapitza",
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(
            err.to_string()
                .contains("not a parameter of the kapitza model")
        );
        // Nudging the method cycles through the pendulum's methods only.
        let mut m = s;
        for _ in 0..20 {
            m = Field::Method.nudge(&m, 1.0, false).unwrap();
            assert!(pendulum.offers(m.method), "{}", m.method);
        }
        let cmd = s.simulate_command(None);
        assert!(
            cmd.contains("--preset kapitza-upright --set pendulum.a=1.0"),
            "{cmd}"
        );
    }
}
