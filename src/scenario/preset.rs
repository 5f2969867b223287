//! Preset files: a scenario in TOML. `[preset] model` names the model (`rattleback` when
//! absent, so every older file keeps its meaning). The keys are `[preset]`, the model's own
//! parameters from its scene's table (`physics::scene`: the rattleback's `[body]`, `[spring]`,
//! `[initial]`; the pendulum's `[pendulum]`, `[initial]`), then `[run]` and `[view]`
//! ([`schema`]); docs/reference/presets.md is generated from the same tables.
//!
//! Parse raw, then validate against the model's schema: the text is parsed into a TOML
//! table (syntax errors stop there), command-line overrides (`--set section.key=value`) are
//! applied to the table, then every section and key is checked: unknown names, wrong types,
//! missing required values, non-finite or out-of-range numbers. All problems are collected
//! ([`check`] reports them all, [`Preset::parse`] the first), each with file, line and key.

use serde::Serialize;
use toml::{Table, Value};

use super::error::{PresetError, SourceMap};
use crate::physics::params::Allowed;
use crate::physics::rattleback::Problem;
use crate::physics::{Method, Model, ModelKind};

/// Smallest and largest tolerance accepted.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-14, 1e-1);
/// Most energy levels a view may ask for.
pub const MAX_CONTOURS: i64 = 40;

/// What a key holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Free text.
    Text,
    /// A model parameter: a number its scene allows.
    Param(Allowed),
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
}

impl Kind {
    fn allowed(self) -> String {
        match self {
            Self::Text => "text in quotes".to_owned(),
            Self::Param(allowed) => allowed.text().to_owned(),
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

/// The run's keys, shared by every model. Names are a contract: add, never rename.
const RUN: [KeySpec; 4] = [
    spec("run", "t_end", Kind::Positive, true),
    spec("run", "method", Kind::Method, false),
    spec("run", "tolerance", Kind::Tolerance, false),
    spec("run", "step", Kind::Positive, false),
];

/// The view's keys after the two ranges (named after the model's slow coordinate).
const VIEW: [KeySpec; 4] = [
    spec("view", "contours", Kind::Count, false),
    spec("view", "effective_overlay", Kind::Bool, false),
    spec("view", "series", Kind::Bool, false),
    spec("view", "wrap", Kind::Bool, false),
];

/// The names of the view's two ranges for `model`, after its slow coordinate
/// (`alpha_range`, `alpha_dot_range`; `theta_range`, `theta_dot_range`): made once per model.
fn range_keys(model: ModelKind) -> (&'static str, &'static str) {
    type Keys = Vec<(ModelKind, &'static str, &'static str)>;
    static KEYS: std::sync::OnceLock<Keys> = std::sync::OnceLock::new();
    let leak = |s: String| -> &'static str { Box::leak(s.into_boxed_str()) };
    KEYS.get_or_init(|| {
        ModelKind::ALL
            .iter()
            .map(|m| {
                let w = m.words();
                let q = leak(format!("{}_range", w.q_name));
                (*m, q, leak(format!("{}_range", w.q_dot_name)))
            })
            .collect()
    })
    .iter()
    .find(|(m, _, _)| *m == model)
    .map_or(("", ""), |(_, q, q_dot)| (*q, *q_dot))
}

/// Every key a preset of `model` may hold, in the order presets print them: `[preset]`, the
/// model's parameters (its scene's table), `[run]`, `[view]`. Names are a contract: add, never
/// rename.
#[must_use]
pub fn schema(model: ModelKind) -> Vec<KeySpec> {
    let (q_range, q_dot_range) = range_keys(model);
    let mut keys = vec![
        spec("preset", "name", Kind::Text, false),
        spec("preset", "description", Kind::Text, false),
        spec("preset", "model", Kind::Model, model.scene().model_required),
    ];
    keys.extend(
        model
            .params()
            .iter()
            .map(|p| spec(p.section, p.key, Kind::Param(p.allowed), p.required)),
    );
    keys.extend(RUN);
    keys.push(spec("view", q_range, Kind::Range, false));
    keys.push(spec("view", q_dot_range, Kind::Range, false));
    keys.extend(VIEW);
    keys
}

/// The sections of `model`'s presets, in order.
fn sections(model: ModelKind) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for k in schema(model) {
        if !out.contains(&k.section) {
            out.push(k.section);
        }
    }
    out
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
    #[serde(rename = "alpha_range")]
    pub slow_range: Option<[f64; 2]>,
    /// Fixed range of its rate (`alpha_dot_range`, `theta_dot_range`; else automatic).
    #[serde(rename = "alpha_dot_range")]
    pub rate_range: Option<[f64; 2]>,
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
#[derive(Clone, Debug, Serialize)]
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
    /// How to name it again on a command line (`--preset ORIGIN`): the shipped or user
    /// preset's name, or the file's path, when it was resolved from one
    /// ([`super::shipped::resolve`]); not part of the scenario (a recording's preset has none).
    #[serde(skip)]
    pub origin: Option<String>,
}

/// Two presets are the same scenario whatever they were read from.
impl PartialEq for Preset {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
            && self.description == other.description
            && self.model == other.model
            && self.run == other.run
            && self.view == other.view
    }
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
        Kind::Param(_) | Kind::Positive | Kind::Tolerance => {
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
                Kind::Param(allowed) => allowed.contains(x),
                _ => true,
            };
            if ok {
                Ok(())
            } else {
                Err(format!(
                    "{} is out of range; allowed: {}",
                    crate::physics::Number(x),
                    kind.allowed()
                ))
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
        // Every key is valid alone: then what `simulate` checks of their combination (a derived
        // quantity that overflows, a step that cannot advance time), by the same code.
        Ok(_) => Preset::parse(src, label, label, &[])
            .err()
            .into_iter()
            .collect(),
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
        None => Ok(ModelKind::default_kind()),
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
    let message = check_value(ModelKind::default_kind(), Kind::Model, v)
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
                        if m == ModelKind::default_kind() {
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
                        allowed_keys(&schema, name),
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
        let label = super::write::label(path);
        let src = PresetError::read(path)?;
        let stem = if super::write::is_stdin(path) {
            label.clone()
        } else {
            path.file_stem()
                .map_or_else(|| label.clone(), |s| s.to_string_lossy().into_owned())
        };
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
        let (table, kind) = collect(src, label, overrides).map_err(|mut p| {
            if p.len() == 1 {
                p.swap_remove(0)
            } else {
                PresetError::Several(p)
            }
        })?;
        let r = Reader(&table);
        let n = |s: &str, k: &str| r.num(s, k).unwrap_or(0.0);
        // A value whose combination with the others is out of range (a derived quantity that
        // overflows) is found only here: it is named at its line too.
        let map = SourceMap::new(src);
        // Where a combination's problem is: a key given with `--set` is blamed on `--set`, not
        // on the file's line it replaced; a key of the file made wrong by a `--set` of another
        // says which (`celt.product` is fine until `--set celt.ix=1e-300`).
        let located = |section: &str, field: &str, message: String| {
            let full = format!("{section}.{field}");
            if overrides.iter().any(|o| o.key == full) {
                return PresetError::Invalid {
                    path: "--set".to_owned(),
                    line: None,
                    key: Some(full),
                    message,
                };
            }
            let with = if overrides.is_empty() {
                String::new()
            } else {
                let given: Vec<String> = overrides
                    .iter()
                    .map(|o| format!("{}={}", o.key, o.value))
                    .collect();
                format!(" (with --set {})", given.join(" --set "))
            };
            PresetError::Invalid {
                path: label.to_owned(),
                line: (!section.is_empty()).then(|| map.locate(section, field)),
                key: Some(if section.is_empty() {
                    field.to_owned()
                } else {
                    full
                }),
                message: message + &with,
            }
        };
        let invalid = |e: crate::physics::ParamError| {
            let field = e.field();
            let section = kind
                .params()
                .iter()
                .find(|k| k.key == field)
                .map_or("", |k| k.section);
            located(section, field, e.to_string())
        };
        let values: Vec<f64> = kind
            .params()
            .iter()
            .map(|p| r.num(p.section, p.key).unwrap_or(p.default))
            .collect();
        let model = kind.problem(&values).map_err(invalid)?;
        let (x_range, y_range) = range_keys(kind);
        let (t_end, step) = (n("run", "t_end"), r.num("run", "step"));
        if let Some(h) = step {
            crate::physics::method::check_step(h, t_end)
                .map_err(|e| located("run", "step", e.to_string()))?;
        }
        Ok(Self {
            name: r
                .text("preset", "name")
                .unwrap_or_else(|| fallback_name.to_owned()),
            description: r.text("preset", "description").unwrap_or_default(),
            origin: None,
            model,
            run: RunConfig {
                t_end: n("run", "t_end"),
                method: r.text("run", "method").and_then(|m| Method::from_name(&m)),
                tolerance: r.num("run", "tolerance"),
                step: r.num("run", "step"),
            },
            view: ViewConfig {
                slow_range: r.range("view", x_range),
                rate_range: r.range("view", y_range),
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
        let kind = self.model.kind();
        if kind.scene().model_required {
            let _ = writeln!(o, "model = {}", q(kind.name()));
        }
        let mut section = "";
        // A model's `[run]` rows (the celt's `spin_band`) go into the one `[run]` table below.
        let rows: Vec<_> = kind.params().iter().zip(self.model.values()).collect();
        for (spec, value) in rows.iter().filter(|(s, _)| s.section != "run") {
            if spec.section != section {
                section = spec.section;
                let _ = write!(o, "\n[{section}]\n");
            }
            let _ = writeln!(o, "{} = {value:?}", spec.key);
        }
        o.push('\n');
        let _ = writeln!(o, "[run]\nt_end = {:?}", self.run.t_end);
        for (spec, value) in rows.iter().filter(|(s, _)| s.section == "run") {
            let _ = writeln!(o, "{} = {value:?}", spec.key);
        }
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
        let (x_range, y_range) = range_keys(kind);
        if let Some([a, b]) = v.slow_range {
            let _ = writeln!(view, "{x_range} = [{a:?}, {b:?}]");
        }
        if let Some([a, b]) = v.rate_range {
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

/// docs/reference/presets.md: every key of every model's presets, generated from the same
/// tables the parser reads (a test pins the file to this text).
#[must_use]
pub fn reference() -> String {
    use std::fmt::Write as _;
    let mut o = String::from(
        "# Preset keys\n\nGenerated from the parameter tables the parser reads \
         (`src/physics/*/scene.rs`, `src/scenario/preset.rs`); \
         `tests/it/schemas.rs` fails when this file and the code disagree. Regenerate with \
         `UPDATE_GOLDEN=1 cargo test --test it schemas::the_preset_reference_is_generated_from_the_tables`.\n\n\
         Names are a contract: keys are added, never renamed. An optional model parameter \
         left out is 0; an optional `[run]` or `[view]` key left out keeps the default.\n",
    );
    for model in ModelKind::ALL {
        let required = if model.scene().model_required {
            format!("`model = \"{}\"` in `[preset]` is required", model.name())
        } else {
            "`[preset] model` may be left out: this is the default model".to_owned()
        };
        let _ = write!(
            o,
            "\n## {} (`{}`)\n\n{required}.\n\n| key | required | allowed | what |\n|---|---|---|---|\n",
            model.title(),
            model.name()
        );
        let docs: std::collections::HashMap<&str, &str> =
            model.params().iter().map(|p| (p.key, p.doc)).collect();
        for k in schema(model) {
            let what = docs
                .get(k.key)
                .copied()
                .unwrap_or_else(|| common_doc(k.key));
            let allowed = if k.kind == Kind::Method {
                format!("one of {}", model.method_names())
            } else {
                k.kind.allowed()
            };
            let _ = writeln!(
                o,
                "| `{}.{}` | {} | {allowed} | {what} |",
                k.section,
                k.key,
                if k.required { "yes" } else { "no" },
            );
        }
    }
    o
}

/// What a key shared by every model holds, for [`reference`](fn@reference).
fn common_doc(key: &str) -> &'static str {
    match key {
        "name" => "display name (default: the file's stem)",
        "description" => "what to look for, shown in the explorer",
        "model" => "the scene",
        "t_end" => "end of the run",
        "method" => "integrator (default auto)",
        "tolerance" => "tolerance (default 1e-9)",
        "step" => "fixed step, for fixed-step methods only",
        "contours" => "background energy levels",
        "effective_overlay" => "the limit drawn over the full motion",
        "series" => "the time-series pane",
        "wrap" => "the slow coordinate wrapped to one period",
        k if k.ends_with("_dot_range") => "fixed axis of the rate instead of the automatic range",
        k if k.ends_with("_range") => {
            "fixed axis of the slow coordinate instead of the automatic range"
        }
        _ => "",
    }
}
