//! The editable parameters of the explorer: how each is shown, nudged and typed, validated by
//! the same domain types as presets. Each model has its rows ([`Field::rows`]); the run's rows
//! (`t_end`, `method`, `tolerance`) are shared.

use crate::physics::kapitza;
use crate::physics::rattleback::Problem;
use crate::physics::rattleback::integrators::Method;
use crate::physics::{Model, ModelKind};
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
    pub fn simulate_command(&self) -> String {
        use std::fmt::Write as _;
        let mut cmd = format!(
            "rattleback simulate --preset {}",
            crate::scenario::shipped::base_preset(self.model.kind())
        );
        for f in Field::rows(self.model.kind()) {
            let value = f.exact(self);
            let _ = match f {
                Field::Method => write!(cmd, " --method {value}"),
                Field::Tolerance => write!(cmd, " --tolerance {value}"),
                Field::TEnd => write!(cmd, " --t-end {value}"),
                _ => write!(cmd, " --set {}.{}={value}", f.section(), f.label()),
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
    /// The pendulum's gravity `a`.
    A,
    /// The pendulum's shaking `b`.
    B,
    /// The pendulum's fast time scale `ε`.
    Epsilon,
    /// The pendulum's initial angle from the upright.
    Theta,
    /// Its initial rate.
    ThetaDot,
    /// End time.
    TEnd,
    /// Method.
    Method,
    /// Tolerance.
    Tolerance,
}

const RATTLEBACK_ROWS: [Field; 11] = [
    Field::Ix,
    Field::Iy,
    Field::Iz,
    Field::K,
    Field::Gamma,
    Field::Alpha,
    Field::GammaDot,
    Field::AlphaDot,
    Field::TEnd,
    Field::Method,
    Field::Tolerance,
];

const KAPITZA_ROWS: [Field; 8] = [
    Field::A,
    Field::B,
    Field::Epsilon,
    Field::Theta,
    Field::ThetaDot,
    Field::TEnd,
    Field::Method,
    Field::Tolerance,
];

impl Field {
    /// Every field of every model.
    pub const ALL: [Self; 16] = [
        Self::Ix,
        Self::Iy,
        Self::Iz,
        Self::K,
        Self::Gamma,
        Self::Alpha,
        Self::GammaDot,
        Self::AlphaDot,
        Self::A,
        Self::B,
        Self::Epsilon,
        Self::Theta,
        Self::ThetaDot,
        Self::TEnd,
        Self::Method,
        Self::Tolerance,
    ];

    /// The panel's rows for `model`, in order.
    #[must_use]
    pub fn rows(model: ModelKind) -> &'static [Self] {
        match model {
            ModelKind::Rattleback => &RATTLEBACK_ROWS,
            ModelKind::Kapitza => &KAPITZA_ROWS,
        }
    }

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
            Self::A => "a",
            Self::B => "b",
            Self::Epsilon => "epsilon",
            Self::Theta => "theta",
            Self::ThetaDot => "theta_dot",
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
            Self::Ix | Self::Iy | Self::Iz => "body",
            Self::K => "spring",
            Self::A | Self::B | Self::Epsilon => "pendulum",
            Self::Gamma
            | Self::Alpha
            | Self::GammaDot
            | Self::AlphaDot
            | Self::Theta
            | Self::ThetaDot => "initial",
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
            Self::K | Self::Tolerance | Self::Epsilon => format!("{:.3e}", self.value(s)),
            _ => format_number(self.value(s)),
        }
    }

    fn value(self, s: &Settings) -> f64 {
        match (self, &s.model) {
            (Self::TEnd, _) => s.t_end,
            (Self::Tolerance, _) => s.tolerance,
            (Self::Ix, Model::Rattleback(p)) => p.params().ix,
            (Self::Iy, Model::Rattleback(p)) => p.params().iy,
            (Self::Iz, Model::Rattleback(p)) => p.params().iz,
            (Self::K, Model::Rattleback(p)) => p.params().k,
            (Self::Gamma, Model::Rattleback(p)) => p.start().gamma,
            (Self::Alpha, Model::Rattleback(p)) => p.start().alpha,
            (Self::GammaDot, Model::Rattleback(p)) => p.start().gamma_dot,
            (Self::AlphaDot, Model::Rattleback(p)) => p.start().alpha_dot,
            (Self::A, Model::Kapitza(p)) => p.params().a,
            (Self::B, Model::Kapitza(p)) => p.params().b,
            (Self::Epsilon, Model::Kapitza(p)) => p.params().epsilon,
            (Self::Theta, Model::Kapitza(p)) => p.start().theta,
            (Self::ThetaDot, Model::Kapitza(p)) => p.start().theta_dot,
            _ => f64::NAN,
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
    pub fn with_value(self, s: &Settings, value: f64) -> Result<Settings, String> {
        let mut n = *s;
        let kept = |e: crate::physics::ParamError| format!("{e}; old value kept");
        if !self.belongs_to(s.model.kind()) {
            return Err(format!(
                "`{}` is not a parameter of the {} model",
                self.label(),
                s.model.kind().name()
            ));
        }
        match (self, &s.model) {
            (Self::TEnd, _) => {
                if !(value.is_finite() && value > 0.0) {
                    return Err(format!(
                        "t_end = {value} refused; allowed: a finite number > 0"
                    ));
                }
                n.t_end = value;
            }
            (Self::Tolerance, _) => {
                let (lo, hi) = TOLERANCE_RANGE;
                if !(value.is_finite() && (lo..=hi).contains(&value)) {
                    return Err(format!(
                        "tolerance = {value} refused; allowed: [{lo:e}, {hi:e}]"
                    ));
                }
                n.tolerance = value;
            }
            (Self::Method, _) => {
                return Err("choose a method with ←/→ or type its name".to_owned());
            }
            (_, Model::Rattleback(p)) => {
                let (mut params, mut start) = (*p.params(), *p.start());
                match self {
                    Self::Ix => params.ix = value,
                    Self::Iy => params.iy = value,
                    Self::Iz => params.iz = value,
                    Self::K => params.k = value,
                    Self::Gamma => start.gamma = value,
                    Self::Alpha => start.alpha = value,
                    Self::GammaDot => start.gamma_dot = value,
                    _ => start.alpha_dot = value,
                }
                n.model = Model::Rattleback(Problem::new(params, start).map_err(kept)?);
            }
            (_, Model::Kapitza(p)) => {
                let (mut params, mut start) = (*p.params(), *p.start());
                match self {
                    Self::A => params.a = value,
                    Self::B => params.b = value,
                    Self::Epsilon => params.epsilon = value,
                    Self::Theta => start.theta = value,
                    _ => start.theta_dot = value,
                }
                n.model = Model::Kapitza(kapitza::Problem::new(params, start).map_err(kept)?);
            }
        }
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
            // Log scales.
            Self::K | Self::Tolerance | Self::Epsilon => {
                v * 10f64.powf(dir * if coarse { 1.0 } else { 0.1 })
            }
            Self::TEnd => {
                v * if coarse {
                    2f64.powf(dir)
                } else {
                    1.0 + 0.1 * dir
                }
            }
            Self::Ix | Self::Iy | Self::Iz | Self::A | Self::B => {
                v + dir * if coarse { 0.5 } else { 0.05 }
            }
            Self::Gamma => v + dir * if coarse { 1e-2 } else { 1e-3 },
            Self::Alpha | Self::Theta => {
                v + dir
                    * if coarse {
                        std::f64::consts::FRAC_PI_8
                    } else {
                        0.05
                    }
            }
            Self::GammaDot | Self::AlphaDot | Self::ThetaDot => {
                v + dir * if coarse { 0.1 } else { 0.01 }
            }
        };
        // Round away float dust from repeated nudges on linear fields.
        let next = if matches!(self, Self::K | Self::Tolerance | Self::TEnd | Self::Epsilon) {
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
            let kind = s.model.kind();
            return match Method::from_name(text) {
                Some(method) if kind.offers(method) => Ok(Settings { method, ..*s }),
                Some(method) => Err(format!(
                    "method {method} is not offered for the {} model; allowed: {}",
                    kind.name(),
                    kind.method_names()
                )),
                None => Err(format!(
                    "unknown method '{text}'; allowed: {}",
                    kind.method_names()
                )),
            };
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
    use crate::physics::rattleback::{Params, Start};

    fn settings() -> Settings {
        let params = Params {
            ix: 2.0,
            iy: 1.0,
            iz: 1.0,
            k: 1e4,
        };
        let start = Start {
            gamma: 0.0,
            alpha: 0.0,
            gamma_dot: 1.0,
            alpha_dot: 0.5,
        };
        Settings {
            model: Model::Rattleback(Problem::new(params, start).unwrap()),
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
            model: Model::Kapitza(kapitza::Problem::new(params, start).unwrap()),
            ..settings()
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
        let small = Field::Iz.with_value(&s, 0.05).unwrap();
        assert!(Field::Iz.nudge(&small, -1.0, false).is_err());
        let k = Field::K.nudge(&s, 1.0, true).unwrap();
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
        assert_eq!(Field::rows(ModelKind::Kapitza)[0], Field::A);
        let e = Field::Epsilon.nudge(&s, -1.0, true).unwrap();
        assert!((e.model.kapitza().unwrap().params().epsilon - 1e-4).abs() < 1e-15);
        let err = Field::Epsilon.with_text(&s, "0").unwrap_err();
        assert!(
            err.contains("epsilon") && err.contains("old value kept"),
            "{err}"
        );
        let err = Field::Method.with_text(&s, "locked").unwrap_err();
        assert!(err.contains("not offered for the kapitza model"), "{err}");
        let err = Field::K.with_text(&s, "3").unwrap_err();
        assert!(
            err.contains("not a parameter of the kapitza model"),
            "{err}"
        );
        // Nudging the method cycles through the pendulum's methods only.
        let mut m = s;
        for _ in 0..20 {
            m = Field::Method.nudge(&m, 1.0, false).unwrap();
            assert!(ModelKind::Kapitza.offers(m.method), "{}", m.method);
        }
        let cmd = s.simulate_command();
        assert!(
            cmd.contains("--preset kapitza-upright --set pendulum.a=1.0"),
            "{cmd}"
        );
    }
}
