//! The JSON outputs of the commands other than `simulate` (whose report is `simulate::Report`),
//! each an object that begins with `schema_version` and `model`, with its JSON Schema generated
//! from the type (`docs/schemas/NAME.schema.json`, made by `cargo run --example output_schemas`;
//! `tests/it/schemas.rs` checks the checked-in copies are this output and that real outputs
//! validate). `model` is `null` where an output is not about one scene (a list, `doctor`,
//! `check`); its entries then name their own.

use schemars::JsonSchema;
use serde::Serialize;

use crate::physics::ModelKind;

/// The version of every output's shape here; raised when a field changes or goes, not when one
/// is added.
pub const SCHEMA_VERSION: u32 = 1;

/// `rattleback presets --format json`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct PresetList {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// `null`: the presets name their own.
    pub model: Option<ModelKind>,
    /// Shipped, then the user's.
    pub presets: Vec<crate::scenario::shipped::Entry>,
}

/// One row of `rattleback themes`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ThemeEntry {
    /// What `--theme` takes.
    pub name: String,
    /// The theme's own name.
    pub title: String,
    /// `shipped` or `user`.
    pub source: &'static str,
    /// The file.
    pub path: String,
    /// What it is for.
    pub description: String,
}

/// `rattleback themes --format json`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ThemeList {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// `null`: themes belong to no scene.
    pub model: Option<ModelKind>,
    /// Shipped, then the user's.
    pub themes: Vec<ThemeEntry>,
}

/// `rattleback lessons --format json`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct LessonList {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// `null`: a lesson's presets name their own.
    pub model: Option<ModelKind>,
    /// Shipped, then the user's.
    pub lessons: Vec<crate::scenario::lesson::Entry>,
}

/// `rattleback study sweep --format json`: the rattleback's ladder is `stiffness`, the
/// pendulum's `epsilon` (the one present is the scene's small parameter).
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Sweep {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// The scene.
    pub model: ModelKind,
    /// The preset's name.
    pub preset: String,
    /// Final time.
    pub t_end: f64,
    /// `auto`'s tolerance for the full runs.
    pub tolerance: f64,
    /// The rattleback's ladder of Hooke constants.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<Vec<f64>>,
    /// The pendulum's ladder of ε.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub epsilon: Option<Vec<f64>>,
    /// The largest distance from the limit over `[0, T]`, per rung.
    pub sup_error: Vec<f64>,
    /// The fitted log–log slope (`null` when it cannot be fitted: fewer than two rungs with a
    /// positive distance).
    pub slope: Option<f64>,
    /// The method `auto` chose, per rung.
    pub methods: Vec<&'static str>,
    /// `auto`'s error estimate, per rung.
    pub estimates: Vec<f64>,
}

/// `rattleback study map --format json`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Map {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// The scene (the rattleback).
    pub model: ModelKind,
    /// The cells and the critical curve.
    #[serde(flatten)]
    pub map: crate::study::map::RegimeMap,
}

/// Every output's schema file name and text.
#[must_use]
pub fn schemas() -> Vec<(&'static str, String)> {
    fn text<T: JsonSchema>() -> String {
        let mut v = serde_json::to_value(schemars::schema_for!(T)).expect("schema serializes");
        // The version is a constant, so a reader can tell a shape it does not know.
        v["properties"]["schema_version"]["const"] = SCHEMA_VERSION.into();
        let mut s = serde_json::to_string_pretty(&v).expect("schema serializes");
        s.push('\n');
        s
    }
    vec![
        ("presets", text::<PresetList>()),
        ("themes", text::<ThemeList>()),
        ("lessons", text::<LessonList>()),
        ("sweep", text::<Sweep>()),
        ("map", text::<Map>()),
        ("doctor", text::<crate::doctor::Diagnosis>()),
    ]
}
