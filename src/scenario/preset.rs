//! Preset files: a scenario in TOML. `[preset] model` names the model (`rattleback` when
//! absent, so every older file keeps its meaning); the rattleback's sections are `[preset]`,
//! `[body]`, `[spring]`, `[initial]`, `[run]`, `[view]`, Kapitza's pendulum's `[preset]`,
//! `[pendulum]`, `[initial]`, `[run]`, `[view]` ([`schema`]).
//!
//! Parse raw, then validate against one schema ([`SCHEMA`]): the text is parsed into a TOML
//! table (syntax errors stop there), command-line overrides (`--set section.key=value`) are
//! applied to the table, then every section and key is checked: unknown names, wrong types,
//! missing required values, non-finite or out-of-range numbers. All problems are collected
//! ([`check`] reports them all, [`Preset::parse`] the first), each with file, line and key.

use serde::Serialize;
use toml::{Table, Value};

use super::error::{PresetError, SourceMap};
use crate::physics::kapitza;
use crate::physics::rattleback::{Params, Problem, Start};
use crate::physics::{Method, Model, ModelKind};

/// Smallest and largest tolerance accepted.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-1);
/// Most energy levels a view may ask for.
pub const MAX_CONTOURS: i64 = 40;

/// What a key holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Free text.
    Text,
    /// Any finite number.
    Number,
    /// A finite number > 0.
    Positive,
    /// A method name.
    Method,
    /// A tolerance in [`TOLERANCE_RANGE`].
    Tolerance,
    /// `true` or `false`.
    Bool,
    /// `[low, high]`, finite, `low < high`.
    Range,
    /// A whole number of energy levels, 0 to [`MAX_CONTOURS`].
    Count,
    /// A model name.
    Model,
    /// A finite number >= 0.
    NonNegative,
    /// `ε`, in `[kapitza::EPSILON_MIN, kapitza::EPSILON_MAX]`.
    Epsilon,
}

impl Kind {
    fn allowed(self) -> String {
        match self {
            Self::Text => "text in quotes".to_owned(),
            Self::Number => "any finite number".to_owned(),
            Self::Positive => "a finite number > 0".to_owned(),
            Self::Method => format!("one of {}", Method::names()),
            Self::Tolerance => format!(
                "a number in [{:e}, {:e}]",
                TOLERANCE_RANGE.0, TOLERANCE_RANGE.1
            ),
            Self::Bool => "true or false".to_owned(),
            Self::Range => "[low, high] with finite low < high".to_owned(),
            Self::Count => format!("a whole number from 0 to {MAX_CONTOURS}"),
            Self::Model => format!("one of {}", ModelKind::names()),
            Self::NonNegative => "a finite number >= 0".to_owned(),
            Self::Epsilon => format!(
                "a number in [{:e}, {}]",
                kapitza::EPSILON_MIN,
                kapitza::EPSILON_MAX
            ),
        }
    }
}

/// One key of the schema.
#[derive(Clone, Copy, Debug)]
pub struct KeySpec {
    /// Section.
    pub section: &'static str,
    /// Key.
    pub key: &'static str,
    /// What it holds.
    pub kind: Kind,
    /// Whether a preset must give it.
    pub required: bool,
}

const fn spec(section: &'static str, key: &'static str, kind: Kind, required: bool) -> KeySpec {
    KeySpec {
        section,
        key,
        kind,
        required,
    }
}

/// Every key a rattleback preset may hold. Names are a contract: add, never rename.
pub const SCHEMA: &[KeySpec] = &[
    spec("preset", "name", Kind::Text, false),
    spec("preset", "description", Kind::Text, false),
    spec("preset", "model", Kind::Model, false),
    spec("body", "ix", Kind::Positive, true),
    spec("body", "iy", Kind::Positive, true),
    spec("body", "iz", Kind::Positive, true),
    spec("spring", "k", Kind::Positive, true),
    spec("initial", "gamma", Kind::Number, false),
    spec("initial", "alpha", Kind::Number, false),
    spec("initial", "gamma_dot", Kind::Number, true),
    spec("initial", "alpha_dot", Kind::Number, true),
    spec("run", "t_end", Kind::Positive, true),
    spec("run", "method", Kind::Method, false),
    spec("run", "tolerance", Kind::Tolerance, false),
    spec("run", "step", Kind::Positive, false),
    spec("view", "alpha_range", Kind::Range, false),
    spec("view", "alpha_dot_range", Kind::Range, false),
    spec("view", "contours", Kind::Count, false),
    spec("view", "effective_overlay", Kind::Bool, false),
    spec("view", "series", Kind::Bool, false),
    spec("view", "wrap", Kind::Bool, false),
];

const SECTIONS: &[&str] = &["preset", "body", "spring", "initial", "run", "view"];

/// Every key a Kapitza preset may hold. Names are a contract: add, never rename.
pub const KAPITZA_SCHEMA: &[KeySpec] = &[
    spec("preset", "name", Kind::Text, false),
    spec("preset", "description", Kind::Text, false),
    spec("preset", "model", Kind::Model, true),
    spec("pendulum", "a", Kind::Number, true),
    spec("pendulum", "b", Kind::NonNegative, true),
    spec("pendulum", "epsilon", Kind::Epsilon, true),
    spec("initial", "theta", Kind::Number, true),
    spec("initial", "theta_dot", Kind::Number, false),
    spec("run", "t_end", Kind::Positive, true),
    spec("run", "method", Kind::Method, false),
    spec("run", "tolerance", Kind::Tolerance, false),
    spec("run", "step", Kind::Positive, false),
    spec("view", "theta_range", Kind::Range, false),
    spec("view", "theta_dot_range", Kind::Range, false),
    spec("view", "contours", Kind::Count, false),
    spec("view", "effective_overlay", Kind::Bool, false),
    spec("view", "series", Kind::Bool, false),
    spec("view", "wrap", Kind::Bool, false),
];

const KAPITZA_SECTIONS: &[&str] = &["preset", "pendulum", "initial", "run", "view"];

/// The keys of `model`'s presets.
#[must_use]
pub fn schema(model: ModelKind) -> &'static [KeySpec] {
    match model {
        ModelKind::Rattleback => SCHEMA,
        ModelKind::Kapitza => KAPITZA_SCHEMA,
    }
}

fn sections(model: ModelKind) -> &'static [&'static str] {
    match model {
        ModelKind::Rattleback => SECTIONS,
        ModelKind::Kapitza => KAPITZA_SECTIONS,
    }
}

/// How a preset asks to be run; absent values fall back to the command line or defaults.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunConfig {
    /// Final time of a run.
    pub t_end: f64,
    /// Integrator, if the preset names one.
    pub method: Option<Method>,
    /// Tolerance, if given.
    pub tolerance: Option<f64>,
    /// Fixed step for fixed-step methods, if given.
    pub step: Option<f64>,
}

/// How a preset asks to be shown; absent values keep the explorer's defaults.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ViewConfig {
    /// Fixed range of the slow coordinate (`alpha_range`, `theta_range`; else automatic).
    pub alpha_range: Option<[f64; 2]>,
    /// Fixed range of its rate (`alpha_dot_range`, `theta_dot_range`; else automatic).
    pub alpha_dot_range: Option<[f64; 2]>,
    /// Number of background energy levels.
    pub contours: Option<usize>,
    /// Effective overlay on or off.
    pub effective_overlay: Option<bool>,
    /// Time-series pane on or off.
    pub series: Option<bool>,
    /// `alpha` wrapped to one period.
    pub wrap: Option<bool>,
}

/// A validated scenario.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Preset {
    /// Display name (defaults to the file stem).
    pub name: String,
    /// What to look for.
    pub description: String,
    /// The model and its validated problem.
    pub model: Model,
    /// Run settings.
    pub run: RunConfig,
    /// View settings.
    pub view: ViewConfig,
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
        let v = value.trim();
        // A quoted value must be one whole TOML string (an unbalanced quote is a typo, not text).
        if (v.starts_with('"') || v.starts_with('\''))
            && toml::from_str::<toml::Table>(&format!("v = {v}")).is_err()
        {
            return Err(format!(
                "'{s}': the value {v} is not one quoted TOML string (a quote is unbalanced?)"
            ));
        }
        Ok(Self {
            key: key.trim().to_owned(),
            value: value.trim().to_owned(),
        })
    }
}

/// Collects problems with their location.
struct Problems<'a> {
    map: SourceMap<'a>,
    label: &'a str,
    overridden: Vec<String>,
    found: Vec<PresetError>,
}

impl Problems<'_> {
    fn at_key(&mut self, section: &str, key: &str, message: String) {
        let full = format!("{section}.{key}");
        let overridden = self.overridden.contains(&full);
        self.found.push(PresetError::Invalid {
            path: if overridden {
                "--set".to_owned()
            } else {
                self.label.to_owned()
            },
            line: if overridden {
                None
            } else {
                Some(self.map.locate(section, key))
            },
            key: Some(full),
            message,
        });
    }

    fn at_section(&mut self, section: &str, message: String) {
        self.found.push(PresetError::Invalid {
            path: self.label.to_owned(),
            line: Some(self.map.locate(section, "")),
            key: Some(section.to_owned()),
            message,
        });
    }
}

fn allowed_keys(schema: &[KeySpec], section: &str) -> String {
    schema
        .iter()
        .filter(|s| s.section == section)
        .map(|s| format!("`{}`", s.key))
        .collect::<Vec<_>>()
        .join(", ")
}

fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Float(f) => Some(*f),
        #[allow(clippy::cast_precision_loss)]
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

fn type_name(v: &Value) -> &'static str {
    match v {
        Value::String(_) => "text",
        Value::Integer(_) | Value::Float(_) => "a number",
        Value::Boolean(_) => "a boolean",
        Value::Array(_) => "an array",
        Value::Table(_) => "a table",
        Value::Datetime(_) => "a date",
    }
}

/// Checks one value against its kind for `model`; `Err` is the message.
fn check_value(model: ModelKind, kind: Kind, v: &Value) -> Result<(), String> {
    let expected = || format!("expected {}, found {}", kind.allowed(), type_name(v));
    match kind {
        Kind::Text => v.as_str().map(|_| ()).ok_or_else(expected),
        Kind::Bool => v.as_bool().map(|_| ()).ok_or_else(expected),
        Kind::Model => {
            let name = v.as_str().ok_or_else(expected)?;
            ModelKind::from_name(name).map(|_| ()).ok_or_else(|| {
                format!(
                    "unknown model '{name}'; allowed: {}{}",
                    ModelKind::names(),
                    crate::scenario::text::did_you_mean(name, ModelKind::ALL.map(ModelKind::name))
                )
            })
        }
        Kind::Method => {
            let name = v.as_str().ok_or_else(expected)?;
            let offered = model.methods().iter().map(|m| m.name());
            match Method::from_name(name) {
                Some(m) if model.offers(m) => Ok(()),
                Some(m) => Err(format!(
                    "method '{m}' is not offered for the {} model; allowed: {}",
                    model.name(),
                    model.method_names()
                )),
                None => Err(format!(
                    "unknown method '{name}'; allowed: {}{}",
                    model.method_names(),
                    crate::scenario::text::did_you_mean(name, offered)
                )),
            }
        }
        Kind::Count => {
            let n = v.as_integer().ok_or_else(expected)?;
            if (0..=MAX_CONTOURS).contains(&n) {
                Ok(())
            } else {
                Err(format!("{n} is out of range; allowed: {}", kind.allowed()))
            }
        }
        Kind::Range => {
            let a = v.as_array().ok_or_else(expected)?;
            let pair: Vec<f64> = a.iter().filter_map(number).collect();
            if a.len() == 2
                && pair.len() == 2
                && pair.iter().all(|x| x.is_finite())
                && pair[0] < pair[1]
            {
                Ok(())
            } else {
                Err(format!("not allowed; allowed: {}", kind.allowed()))
            }
        }
        Kind::Number | Kind::Positive | Kind::Tolerance | Kind::NonNegative | Kind::Epsilon => {
            let x = number(v).ok_or_else(expected)?;
            if !x.is_finite() {
                return Err(format!(
                    "{x} is not a finite number; allowed: {}",
                    kind.allowed()
                ));
            }
            let ok = match kind {
                Kind::Positive => x > 0.0,
                Kind::Tolerance => (TOLERANCE_RANGE.0..=TOLERANCE_RANGE.1).contains(&x),
                Kind::NonNegative => x >= 0.0,
                Kind::Epsilon => (kapitza::EPSILON_MIN..=kapitza::EPSILON_MAX).contains(&x),
                _ => true,
            };
            if ok {
                Ok(())
            } else {
                Err(format!("{x} is out of range; allowed: {}", kind.allowed()))
            }
        }
    }
}

/// Turns a `--set` value into a TOML value of the key's kind.
fn parse_override(kind: Kind, text: &str) -> Value {
    let text = text.trim();
    match kind {
        Kind::Text | Kind::Method | Kind::Model => Value::String(text.trim_matches('"').to_owned()),
        // One TOML value on one line: anything else (a newline smuggling in more keys, a
        // control character) stays text and fails the type check with its reason.
        _ if text.chars().any(char::is_control) => Value::String(text.to_owned()),
        _ => format!("v = {text}")
            .parse::<Table>()
            .ok()
            .filter(|t| t.len() == 1)
            .and_then(|mut t| t.remove("v"))
            // A number too large for a float (`1e400`) is a number, not text: it fails as
            // not finite.
            .or_else(|| text.parse::<f64>().ok().map(Value::Float))
            .unwrap_or_else(|| Value::String(text.to_owned())),
    }
}

/// Every problem of a preset text (empty when it is valid).
#[must_use]
pub fn check(src: &str, label: &str) -> Vec<PresetError> {
    match collect(src, label, &[]) {
        Ok(_) => Vec::new(),
        Err(problems) => problems,
    }
}

/// The model a preset table names (`[preset] model`, the rattleback when absent); `Err` when
/// it names none (the schema check reports it with its location).
fn model_of(table: &Table) -> Result<ModelKind, ()> {
    match table
        .get("preset")
        .and_then(Value::as_table)
        .and_then(|t| t.get("model"))
    {
        None => Ok(ModelKind::Rattleback),
        Some(v) => v.as_str().and_then(ModelKind::from_name).ok_or(()),
    }
}

/// The model first (a `--set preset.model=...` included): it decides the schema. `None` (with
/// the problem recorded) when the file names no known model.
fn decide_model(
    table: &mut Table,
    overrides: &[Override],
    problems: &mut Problems<'_>,
) -> Option<ModelKind> {
    for o in overrides.iter().filter(|o| o.key == "preset.model") {
        let section = table
            .entry("preset")
            .or_insert_with(|| Value::Table(Table::new()));
        if let Value::Table(t) = section {
            t.insert("model".to_owned(), parse_override(Kind::Model, &o.value));
        }
    }
    if let Ok(m) = model_of(table) {
        return Some(m);
    }
    let v = &table["preset"]["model"];
    let message = check_value(ModelKind::Rattleback, Kind::Model, v)
        .err()
        .unwrap_or_default();
    problems.at_key("preset", "model", message);
    None
}

fn collect(
    src: &str,
    label: &str,
    overrides: &[Override],
) -> Result<(Table, ModelKind), Vec<PresetError>> {
    let map = SourceMap::new(src);
    let mut table = map.parse_table(label).map_err(|e| vec![e])?;
    let mut problems = Problems {
        map,
        label,
        overridden: overrides.iter().map(|o| o.key.clone()).collect(),
        found: Vec::new(),
    };
    let Some(model) = decide_model(&mut table, overrides, &mut problems) else {
        return Err(problems.found);
    };
    let schema = schema(model);
    for o in overrides {
        let Some(spec) = schema
            .iter()
            .find(|s| format!("{}.{}", s.section, s.key) == o.key)
        else {
            let keys: Vec<String> = schema
                .iter()
                .map(|s| format!("{}.{}", s.section, s.key))
                .collect();
            return Err(vec![PresetError::Invalid {
                path: "--set".to_owned(),
                line: None,
                key: Some(o.key.clone()),
                message: format!(
                    "unknown key '{}'; allowed: {}{}",
                    o.key,
                    keys.join(", "),
                    crate::scenario::text::did_you_mean(&o.key, keys.iter().map(String::as_str))
                ),
            }]);
        };
        let section = table
            .entry(spec.section)
            .or_insert_with(|| Value::Table(Table::new()));
        if let Value::Table(t) = section {
            t.insert(spec.key.to_owned(), parse_override(spec.kind, &o.value));
        }
    }
    check_sections(&table, model, &mut problems);
    for spec in schema.iter().filter(|s| s.required) {
        let present = table
            .get(spec.section)
            .and_then(Value::as_table)
            .is_some_and(|t| t.contains_key(spec.key));
        if !present {
            let where_ = if table.contains_key(spec.section) {
                String::new()
            } else {
                format!("; the file has no [{}] section", spec.section)
            };
            problems.at_key(
                spec.section,
                spec.key,
                format!("missing required value ({}){where_}", spec.kind.allowed()),
            );
        }
    }
    if problems.found.is_empty() {
        Ok((table, model))
    } else {
        Err(problems.found)
    }
}

/// ` (… belongs to the X model; set model = "X" in [preset])` when another model has the key.
fn other_model_hint(model: ModelKind, section: &str, key: &str) -> String {
    ModelKind::ALL
        .into_iter()
        .find(|m| {
            *m != model
                && schema(*m)
                    .iter()
                    .any(|s| s.section == section && s.key == key)
        })
        .map(|m| {
            format!(
                " (`{section}.{key}` belongs to the {} model; set model = \"{}\" in [preset])",
                m.name(),
                m.name()
            )
        })
        .unwrap_or_default()
}

/// Checks every section and key of `table` against `model`'s schema.
fn check_sections(table: &Table, model: ModelKind, problems: &mut Problems<'_>) {
    let schema = schema(model);
    let section_names = sections(model);
    for (name, value) in table {
        if !section_names.contains(&name.as_str()) {
            let allowed = section_names
                .iter()
                .map(|s| format!("`{s}`"))
                .collect::<Vec<_>>()
                .join(", ");
            let other = ModelKind::ALL
                .into_iter()
                .find(|m| *m != model && sections(*m).contains(&name.as_str()))
                .map(|m| {
                    format!(
                        " ([{name}] belongs to the {} model{})",
                        m.name(),
                        if m == ModelKind::Rattleback {
                            ", which is the default".to_owned()
                        } else {
                            format!("; set model = \"{}\" in [preset]", m.name())
                        }
                    )
                })
                .unwrap_or_default();
            problems.at_section(
                name,
                format!(
                    "unknown section `{name}` for the {} model, expected one of {allowed}{}{other}",
                    model.name(),
                    crate::scenario::text::did_you_mean(name, section_names.iter().copied())
                ),
            );
            continue;
        }
        let Value::Table(section) = value else {
            problems.at_section(name, format!("`{name}` must be a [{name}] table"));
            continue;
        };
        for (key, v) in section {
            match schema.iter().find(|s| s.section == name && s.key == key) {
                None => problems.at_key(
                    name,
                    key,
                    format!(
                        "unknown key `{key}` for the {} model, expected one of {}{}{}",
                        model.name(),
                        allowed_keys(schema, name),
                        crate::scenario::text::did_you_mean(
                            key,
                            schema.iter().filter(|s| s.section == name).map(|s| s.key)
                        ),
                        other_model_hint(model, name, key)
                    ),
                ),
                Some(spec) => {
                    if let Err(message) = check_value(model, spec.kind, v) {
                        problems.at_key(name, key, message);
                    }
                }
            }
        }
    }
}

/// Reads a validated table (every lookup below was checked by `collect`).
struct Reader<'a>(&'a Table);

impl Reader<'_> {
    fn get(&self, section: &str, key: &str) -> Option<&Value> {
        self.0.get(section)?.as_table()?.get(key)
    }
    fn num(&self, section: &str, key: &str) -> Option<f64> {
        self.get(section, key).and_then(number)
    }
    fn text(&self, section: &str, key: &str) -> Option<String> {
        self.get(section, key)
            .and_then(Value::as_str)
            .map(str::to_owned)
    }
    fn flag(&self, section: &str, key: &str) -> Option<bool> {
        self.get(section, key).and_then(Value::as_bool)
    }
    fn range(&self, section: &str, key: &str) -> Option<[f64; 2]> {
        let a = self.get(section, key)?.as_array()?;
        Some([number(&a[0])?, number(&a[1])?])
    }
}

impl Preset {
    /// Reads and validates a preset file, applying `overrides`.
    ///
    /// # Errors
    /// An unreadable file or the first problem found.
    pub fn load(path: &std::path::Path, overrides: &[Override]) -> Result<Self, PresetError> {
        let label = path.display().to_string();
        let src = PresetError::read(path)?;
        let stem = path
            .file_stem()
            .map_or_else(|| label.clone(), |s| s.to_string_lossy().into_owned());
        Self::parse(&src, &label, &stem, overrides)
    }

    /// Validates preset text; `label` names it in errors, `fallback_name` is used when the
    /// file has no `preset.name`.
    ///
    /// # Errors
    /// The first problem found (see [`check`] for all of them).
    pub fn parse(
        src: &str,
        label: &str,
        fallback_name: &str,
        overrides: &[Override],
    ) -> Result<Self, PresetError> {
        let (table, kind) = collect(src, label, overrides).map_err(|mut p| p.swap_remove(0))?;
        let r = Reader(&table);
        let n = |s: &str, k: &str| r.num(s, k).unwrap_or(0.0);
        // A value whose combination with the others is out of range (a derived quantity that
        // overflows) is found only here: it is named at its line too.
        let map = SourceMap::new(src);
        let invalid = |e: crate::physics::ParamError| {
            let field = e.field();
            let section = SCHEMA
                .iter()
                .chain(KAPITZA_SCHEMA)
                .find(|k| k.key == field && !matches!(k.section, "preset" | "run" | "view"))
                .map_or("", |k| k.section);
            PresetError::Invalid {
                path: label.to_owned(),
                line: (!section.is_empty()).then(|| map.locate(section, field)),
                key: Some(if section.is_empty() {
                    field.to_owned()
                } else {
                    format!("{section}.{field}")
                }),
                message: e.to_string(),
            }
        };
        let model = match kind {
            ModelKind::Rattleback => {
                let params = Params {
                    ix: n("body", "ix"),
                    iy: n("body", "iy"),
                    iz: n("body", "iz"),
                    k: n("spring", "k"),
                };
                let start = Start {
                    gamma: n("initial", "gamma"),
                    alpha: n("initial", "alpha"),
                    gamma_dot: n("initial", "gamma_dot"),
                    alpha_dot: n("initial", "alpha_dot"),
                };
                Model::Rattleback(Problem::new(params, start).map_err(invalid)?)
            }
            ModelKind::Kapitza => {
                let params = kapitza::Params {
                    a: n("pendulum", "a"),
                    b: n("pendulum", "b"),
                    epsilon: n("pendulum", "epsilon"),
                };
                let start = kapitza::Start {
                    theta: n("initial", "theta"),
                    theta_dot: n("initial", "theta_dot"),
                };
                Model::Kapitza(kapitza::Problem::new(params, start).map_err(invalid)?)
            }
        };
        let (x_range, y_range) = match kind {
            ModelKind::Rattleback => ("alpha_range", "alpha_dot_range"),
            ModelKind::Kapitza => ("theta_range", "theta_dot_range"),
        };
        let (t_end, step) = (n("run", "t_end"), r.num("run", "step"));
        if let Some(h) = step {
            crate::physics::rattleback::run::check_step(h, t_end).map_err(|message| {
                PresetError::Invalid {
                    path: label.to_owned(),
                    line: Some(map.locate("run", "step")),
                    key: Some("run.step".to_owned()),
                    message,
                }
            })?;
        }
        Ok(Self {
            name: r
                .text("preset", "name")
                .unwrap_or_else(|| fallback_name.to_owned()),
            description: r.text("preset", "description").unwrap_or_default(),
            model,
            run: RunConfig {
                t_end: n("run", "t_end"),
                method: r.text("run", "method").and_then(|m| Method::from_name(&m)),
                tolerance: r.num("run", "tolerance"),
                step: r.num("run", "step"),
            },
            view: ViewConfig {
                alpha_range: r.range("view", x_range),
                alpha_dot_range: r.range("view", y_range),
                contours: r
                    .get("view", "contours")
                    .and_then(Value::as_integer)
                    .and_then(|c| usize::try_from(c).ok()),
                effective_overlay: r.flag("view", "effective_overlay"),
                series: r.flag("view", "series"),
                wrap: r.flag("view", "wrap"),
            },
        })
    }

    /// The rattleback's problem, when this is a rattleback preset.
    #[must_use]
    pub fn problem(&self) -> Option<&Problem> {
        self.model.rattleback()
    }

    /// The preset as TOML, in the schema's order; parsing it gives the same preset back.
    #[must_use]
    pub fn to_toml(&self) -> String {
        use std::fmt::Write as _;
        let q = |t: &str| Value::String(t.to_owned()).to_string();
        let mut o = String::new();
        let _ = writeln!(
            o,
            "[preset]\nname = {}\ndescription = {}",
            q(&self.name),
            q(&self.description)
        );
        match &self.model {
            Model::Rattleback(problem) => {
                let (p, s) = (problem.params(), problem.start());
                let _ = writeln!(
                    o,
                    "\n[body]\nix = {:?}\niy = {:?}\niz = {:?}\n",
                    p.ix, p.iy, p.iz
                );
                let _ = writeln!(o, "[spring]\nk = {:?}\n", p.k);
                let _ = writeln!(
                    o,
                    "[initial]\ngamma = {:?}\nalpha = {:?}\ngamma_dot = {:?}\nalpha_dot = {:?}\n",
                    s.gamma, s.alpha, s.gamma_dot, s.alpha_dot
                );
            }
            Model::Kapitza(problem) => {
                let (p, s) = (problem.params(), problem.start());
                let _ = writeln!(o, "model = \"kapitza\"\n");
                let _ = writeln!(
                    o,
                    "[pendulum]\na = {:?}\nb = {:?}\nepsilon = {:?}\n",
                    p.a, p.b, p.epsilon
                );
                let _ = writeln!(
                    o,
                    "[initial]\ntheta = {:?}\ntheta_dot = {:?}\n",
                    s.theta, s.theta_dot
                );
            }
        }
        let _ = writeln!(o, "[run]\nt_end = {:?}", self.run.t_end);
        if let Some(m) = self.run.method {
            let _ = writeln!(o, "method = {}", q(m.name()));
        }
        if let Some(t) = self.run.tolerance {
            let _ = writeln!(o, "tolerance = {t:?}");
        }
        if let Some(h) = self.run.step {
            let _ = writeln!(o, "step = {h:?}");
        }
        let v = &self.view;
        let mut view = String::new();
        let (x_range, y_range) = match self.model.kind() {
            ModelKind::Rattleback => ("alpha_range", "alpha_dot_range"),
            ModelKind::Kapitza => ("theta_range", "theta_dot_range"),
        };
        if let Some([a, b]) = v.alpha_range {
            let _ = writeln!(view, "{x_range} = [{a:?}, {b:?}]");
        }
        if let Some([a, b]) = v.alpha_dot_range {
            let _ = writeln!(view, "{y_range} = [{a:?}, {b:?}]");
        }
        if let Some(c) = v.contours {
            let _ = writeln!(view, "contours = {c}");
        }
        for (key, flag) in [
            ("effective_overlay", v.effective_overlay),
            ("series", v.series),
            ("wrap", v.wrap),
        ] {
            if let Some(f) = flag {
                let _ = writeln!(view, "{key} = {f}");
            }
        }
        if !view.is_empty() {
            let _ = write!(o, "\n[view]\n{view}");
        }
        o
    }
}
