//! Preset files: a scenario in TOML (`[preset]`, `[body]`, `[spring]`, `[initial]`, `[run]`).
//!
//! Parse raw, then validate: the raw structs accept any shape serde can read (every value
//! optional, unknown keys refused), command-line overrides (`--set section.key=value`) are
//! applied to them, and `validate` turns them into a [`Preset`] or a [`PresetError`] that names
//! the file, line and key.

use serde::{Deserialize, Serialize};

use super::error::{PresetError, SourceMap};
use crate::physics::{Method, Params, Problem, Start};

/// Smallest and largest tolerance accepted.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-1);

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPreset {
    preset: Option<RawMeta>,
    body: Option<RawBody>,
    spring: Option<RawSpring>,
    initial: Option<RawInitial>,
    run: Option<RawRun>,
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMeta {
    name: Option<String>,
    description: Option<String>,
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    ix: Option<f64>,
    iy: Option<f64>,
    iz: Option<f64>,
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpring {
    k: Option<f64>,
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInitial {
    gamma: Option<f64>,
    alpha: Option<f64>,
    gamma_dot: Option<f64>,
    alpha_dot: Option<f64>,
}

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRun {
    t_end: Option<f64>,
    method: Option<String>,
    tolerance: Option<f64>,
    step: Option<f64>,
}

/// Every key a preset may hold, as `section.key`, with whether it is required.
pub const KEYS: [(&str, bool); 14] = [
    ("preset.name", false),
    ("preset.description", false),
    ("body.ix", true),
    ("body.iy", true),
    ("body.iz", true),
    ("spring.k", true),
    ("initial.gamma", false),
    ("initial.alpha", false),
    ("initial.gamma_dot", true),
    ("initial.alpha_dot", true),
    ("run.t_end", true),
    ("run.method", false),
    ("run.tolerance", false),
    ("run.step", false),
];

/// How a preset asks to be run; absent values fall back to the command line or defaults.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunConfig {
    /// Final time of a headless run (the explorer runs on past it).
    pub t_end: f64,
    /// Integrator, if the preset names one.
    pub method: Option<Method>,
    /// Tolerance, if given.
    pub tolerance: Option<f64>,
    /// Fixed step for fixed-step methods, if given.
    pub step: Option<f64>,
}

/// A validated scenario.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Preset {
    /// Display name (defaults to the file stem).
    pub name: String,
    /// What to look for.
    pub description: String,
    /// Body, spring and start.
    pub problem: Problem,
    /// Run settings.
    pub run: RunConfig,
}

/// One `--set section.key=value` override.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Override {
    /// `section.key`.
    pub key: String,
    /// The value as typed.
    pub value: String,
}

impl std::str::FromStr for Override {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (key, value) = s
            .split_once('=')
            .ok_or_else(|| format!("'{s}' is not of the form section.key=value"))?;
        Ok(Self {
            key: key.trim().to_owned(),
            value: value.trim().to_owned(),
        })
    }
}

impl Preset {
    /// Reads and validates a preset file, applying `overrides`.
    ///
    /// # Errors
    /// An unreadable file or any [`PresetError::Invalid`] problem.
    pub fn load(path: &std::path::Path, overrides: &[Override]) -> Result<Self, PresetError> {
        let label = path.display().to_string();
        let src = std::fs::read_to_string(path).map_err(|source| PresetError::Unreadable {
            path: label.clone(),
            source,
        })?;
        let stem = path
            .file_stem()
            .map_or_else(|| label.clone(), |s| s.to_string_lossy().into_owned());
        Self::parse(&src, &label, &stem, overrides)
    }

    /// Validates preset text; `label` names it in errors, `fallback_name` is used when the
    /// file has no `preset.name`.
    ///
    /// # Errors
    /// Syntax errors, unknown keys, wrong types, missing or out-of-range values.
    pub fn parse(
        src: &str,
        label: &str,
        fallback_name: &str,
        overrides: &[Override],
    ) -> Result<Self, PresetError> {
        let map = SourceMap::new(src);
        let mut raw: RawPreset = toml::from_str(src).map_err(|e| toml_error(&map, label, &e))?;
        for o in overrides {
            raw.set(&o.key, &o.value)
                .map_err(|message| PresetError::Invalid {
                    path: "--set".to_owned(),
                    line: None,
                    key: Some(o.key.clone()),
                    message,
                })?;
        }
        raw.validate(&map, label, fallback_name, overrides)
    }
}

fn toml_error(map: &SourceMap<'_>, label: &str, e: &toml::de::Error) -> PresetError {
    let line = e.span().map(|s| map.line_of(s.start));
    // On a section header there is no key; the message then names the section.
    let key = line.and_then(|l| {
        let key = map.key_at(l)?;
        Some(match map.section_at(l) {
            Some(section) => format!("{section}.{key}"),
            None => key,
        })
    });
    let mut message = e
        .message()
        .trim()
        .replace("expected f64", "expected a number");
    if message.starts_with("unknown field") {
        message = format!("{message}; see the preset schema in README.md");
    }
    PresetError::Invalid {
        path: label.to_owned(),
        line,
        key,
        message,
    }
}

fn parse_number(value: &str) -> Result<f64, String> {
    let v = value.trim();
    v.parse::<f64>()
        .map_err(|_| format!("'{v}' is not a number"))
}

impl RawPreset {
    /// Applies `section.key = value` from the command line.
    fn set(&mut self, key: &str, value: &str) -> Result<(), String> {
        let text = || value.trim().trim_matches('"').to_owned();
        match key {
            "preset.name" => self.preset.get_or_insert_default().name = Some(text()),
            "preset.description" => {
                self.preset.get_or_insert_default().description = Some(text());
            }
            "body.ix" => self.body.get_or_insert_default().ix = Some(parse_number(value)?),
            "body.iy" => self.body.get_or_insert_default().iy = Some(parse_number(value)?),
            "body.iz" => self.body.get_or_insert_default().iz = Some(parse_number(value)?),
            "spring.k" => self.spring.get_or_insert_default().k = Some(parse_number(value)?),
            "initial.gamma" => {
                self.initial.get_or_insert_default().gamma = Some(parse_number(value)?);
            }
            "initial.alpha" => {
                self.initial.get_or_insert_default().alpha = Some(parse_number(value)?);
            }
            "initial.gamma_dot" => {
                self.initial.get_or_insert_default().gamma_dot = Some(parse_number(value)?);
            }
            "initial.alpha_dot" => {
                self.initial.get_or_insert_default().alpha_dot = Some(parse_number(value)?);
            }
            "run.t_end" => self.run.get_or_insert_default().t_end = Some(parse_number(value)?),
            "run.method" => self.run.get_or_insert_default().method = Some(text()),
            "run.tolerance" => {
                self.run.get_or_insert_default().tolerance = Some(parse_number(value)?);
            }
            "run.step" => self.run.get_or_insert_default().step = Some(parse_number(value)?),
            other => {
                let keys: Vec<&str> = KEYS.iter().map(|(k, _)| *k).collect();
                return Err(format!(
                    "unknown key '{other}'; allowed: {}",
                    keys.join(", ")
                ));
            }
        }
        Ok(())
    }

    fn validate(
        self,
        map: &SourceMap<'_>,
        label: &str,
        fallback_name: &str,
        overrides: &[Override],
    ) -> Result<Preset, PresetError> {
        // Locates `section.key`: on the command line if overridden, else in the file.
        let invalid = |key: &str, message: String| {
            let overridden = overrides.iter().any(|o| o.key == key);
            let (section, name) = key.split_once('.').unwrap_or(("", key));
            PresetError::Invalid {
                path: if overridden {
                    "--set".to_owned()
                } else {
                    label.to_owned()
                },
                line: if overridden {
                    None
                } else {
                    map.find_key(section, name)
                },
                key: Some(key.to_owned()),
                message,
            }
        };
        let required = |key: &str, v: Option<f64>| {
            v.ok_or_else(|| invalid(key, "missing required value (a number)".to_owned()))
        };
        let body = self.body.unwrap_or_default();
        let spring = self.spring.unwrap_or_default();
        let initial = self.initial.unwrap_or_default();
        let run = self.run.unwrap_or_default();
        let meta = self.preset.unwrap_or_default();
        let params = Params {
            ix: required("body.ix", body.ix)?,
            iy: required("body.iy", body.iy)?,
            iz: required("body.iz", body.iz)?,
            k: required("spring.k", spring.k)?,
        };
        let start = Start {
            gamma: initial.gamma.unwrap_or(0.0),
            alpha: initial.alpha.unwrap_or(0.0),
            gamma_dot: required("initial.gamma_dot", initial.gamma_dot)?,
            alpha_dot: required("initial.alpha_dot", initial.alpha_dot)?,
        };
        let problem = Problem::new(params, start).map_err(|e| {
            let section = match e.field() {
                "ix" | "iy" | "iz" => "body",
                "k" => "spring",
                _ => "initial",
            };
            invalid(&format!("{section}.{}", e.field()), e.to_string())
        })?;
        let t_end = required("run.t_end", run.t_end)?;
        if !(t_end.is_finite() && t_end > 0.0) {
            return Err(invalid(
                "run.t_end",
                format!("t_end = {t_end} is not allowed; allowed: a finite number > 0"),
            ));
        }
        let method = run
            .method
            .map(|name| {
                Method::from_name(&name).ok_or_else(|| {
                    invalid(
                        "run.method",
                        format!("unknown method '{name}'; allowed: {}", Method::names()),
                    )
                })
            })
            .transpose()?;
        if let Some(tol) = run.tolerance {
            let (lo, hi) = TOLERANCE_RANGE;
            if !(tol.is_finite() && (lo..=hi).contains(&tol)) {
                return Err(invalid(
                    "run.tolerance",
                    format!(
                        "tolerance = {tol} is not allowed; allowed: a number in [{lo:e}, {hi:e}]"
                    ),
                ));
            }
        }
        if let Some(step) = run.step
            && !(step.is_finite() && step > 0.0)
        {
            return Err(invalid(
                "run.step",
                format!("step = {step} is not allowed; allowed: a finite number > 0"),
            ));
        }
        Ok(Preset {
            name: meta.name.unwrap_or_else(|| fallback_name.to_owned()),
            description: meta.description.unwrap_or_default(),
            problem,
            run: RunConfig {
                t_end,
                method,
                tolerance: run.tolerance,
                step: run.step,
            },
        })
    }
}
