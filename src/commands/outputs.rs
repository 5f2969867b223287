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

/// `rattleback study map --format json` (every scene's chart, a shard's part file and `study
/// merge`'s output; the rattleback's cells keep the fields they had before issue 59).
pub type Map = crate::study::chart::ChartOutput;

/// `rattleback replay FILE --chapters --format json`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Chapters {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// The recording's scene (`null` when its header's preset cannot be read).
    pub model: Option<ModelKind>,
    /// The session file (`stdin` for `-`).
    pub file: String,
    /// Chapter markers and lesson steps, in order.
    pub chapters: Vec<crate::record::Chapter>,
}

/// Where a replay first differed from the recording.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Divergence {
    /// 1-based line of the file.
    pub line: usize,
    /// Its simulated time.
    pub t: f64,
    /// What the file says.
    pub expected: String,
    /// What this build computes.
    pub got: String,
}

/// `rattleback replay FILE --verify --format json`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Verification {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// The recording's scene (`null` when its header's preset cannot be read).
    pub model: Option<ModelKind>,
    /// The session file (`stdin` for `-`).
    pub file: String,
    /// Reproduced bit for bit, intact and ended (the exit status is 0 exactly then).
    pub verified: bool,
    /// The format the header claims (`null` when the file could not be checked that far).
    pub format: Option<u32>,
    /// Checkpoints reproduced bit for bit.
    pub checkpoints: usize,
    /// Screens (status-bar values) reproduced.
    pub screens: usize,
    /// The last frame before the end was recorded and reproduced (always from format 10 on).
    pub final_screen: bool,
    /// What the integrity check covers, in words (`null` when it did not run).
    pub integrity: Option<String>,
    /// Who signed it and whether it was checked against a key (`null`: not signed).
    pub signature: Option<String>,
    /// Intact up to this line but with no end line (cut short).
    pub incomplete_through: Option<usize>,
    /// The first checkpoint or screen that differs.
    pub divergence: Option<Divergence>,
    /// Any other reason it did not verify (a bad file, a bad signature…).
    pub error: Option<String>,
}

/// One problem `check` found.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Problem {
    /// The file (`stdin` for `-`).
    pub path: Option<String>,
    /// 1-based line, when it has one.
    pub line: Option<usize>,
    /// `section.key`, when it concerns one.
    pub key: Option<String>,
    /// The whole message, as the table prints it.
    pub message: String,
}

/// `rattleback check FILE… --format json`.
#[derive(Debug, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Check {
    /// The version of this output's shape.
    pub schema_version: u32,
    /// `null`: the files name their own scenes.
    pub model: Option<ModelKind>,
    /// The files checked.
    pub files: Vec<String>,
    /// Every problem (none: all valid; the exit status is 2 otherwise).
    pub problems: Vec<Problem>,
}

/// The preset a recording's header holds (`None` when it cannot be read).
#[must_use]
pub fn recorded_preset(rec: &crate::record::Recording) -> Option<crate::scenario::Preset> {
    crate::scenario::Preset::parse(&rec.header.preset, "header", "recorded", &[]).ok()
}

/// The scene of a recording, from its header's preset (`None` when that cannot be read).
#[must_use]
pub fn recorded_model(rec: &crate::record::Recording) -> Option<ModelKind> {
    recorded_preset(rec).map(|p| p.model.kind())
}

impl Chapters {
    /// The chapters of `rec`, read from `file`.
    #[must_use]
    pub fn of(rec: &crate::record::Recording, file: &str) -> Self {
        Self {
            schema_version: SCHEMA_VERSION,
            model: recorded_model(rec),
            file: file.to_owned(),
            chapters: crate::record::chapter_list(rec),
        }
    }
}

impl Verification {
    /// What `verify` found for `rec` (or `error`, when the file could not be read).
    #[must_use]
    pub fn of(
        rec: Option<&crate::record::Recording>,
        file: &str,
        result: Result<&crate::record::Report, &crate::record::VerifyError>,
    ) -> Self {
        use crate::record::VerifyError;
        let mut v = Self {
            schema_version: SCHEMA_VERSION,
            model: rec.and_then(recorded_model),
            file: file.to_owned(),
            verified: result.is_ok(),
            format: rec.map(|r| r.header.version),
            checkpoints: 0,
            screens: 0,
            final_screen: false,
            integrity: None,
            signature: None,
            incomplete_through: None,
            divergence: None,
            error: None,
        };
        let report = match result {
            Ok(r) | Err(VerifyError::Incomplete { report: r, .. }) => Some(r),
            _ => None,
        };
        if let Some(r) = report {
            v.format = Some(r.format);
            v.checkpoints = r.checkpoints;
            v.screens = r.screens;
            v.final_screen = r.final_screen;
            v.integrity = Some(r.integrity.clone());
            v.signature.clone_from(&r.signature);
        }
        match result {
            Err(VerifyError::Incomplete { through, .. }) => v.incomplete_through = Some(*through),
            Err(VerifyError::Diverged(d)) => {
                v.divergence = Some(Divergence {
                    line: d.line,
                    t: d.t,
                    expected: d.expected.clone(),
                    got: d.got.clone(),
                });
            }
            Err(e @ VerifyError::Record(_)) => v.error = Some(e.to_string()),
            Ok(_) => {}
        }
        v
    }
}

impl Problem {
    /// A problem as `check` reports it.
    #[must_use]
    pub fn of(e: &crate::scenario::PresetError) -> Self {
        use crate::scenario::PresetError;
        let (path, line, key) = match e {
            PresetError::Invalid {
                path, line, key, ..
            } => (Some(path.clone()), *line, key.clone()),
            PresetError::Unreadable { path, .. } => (Some(path.clone()), None, None),
            PresetError::NotFound { .. } => (None, None, None),
            // `check` lists a file's problems one by one, never as one.
            PresetError::Several(all) => match all.first() {
                Some(first) => {
                    let p = Self::of(first);
                    (p.path, p.line, p.key)
                }
                None => (None, None, None),
            },
        };
        Self {
            path,
            line,
            key,
            message: e.to_string(),
        }
    }
}

/// Every output's schema file name and text: one per command, and `study map`'s narrowed to
/// each scene (`map-NAME`, `scene_map`).
#[must_use]
pub fn schemas() -> Vec<(String, String)> {
    fn value<T: JsonSchema>() -> serde_json::Value {
        let mut v = serde_json::to_value(schemars::schema_for!(T)).expect("schema serializes");
        // The version is a constant, so a reader can tell a shape it does not know.
        v["properties"]["schema_version"]["const"] = SCHEMA_VERSION.into();
        // Every output says its scene, `null` where it is about none: required, second, as
        // printed (schemars leaves an `Option` out of `required`).
        if let Some(required) = v["required"].as_array_mut() {
            required.retain(|k| k != "schema_version" && k != "model");
            required.insert(0, "model".into());
            required.insert(0, "schema_version".into());
        }
        v
    }
    fn text(v: &serde_json::Value) -> String {
        let mut s = serde_json::to_string_pretty(v).expect("schema serializes");
        s.push('\n');
        s
    }
    let mut map = value::<Map>();
    scene_fields(&mut map);
    let mut all: Vec<(String, String)> = vec![
        ("presets".to_owned(), text(&value::<PresetList>())),
        ("themes".to_owned(), text(&value::<ThemeList>())),
        ("lessons".to_owned(), text(&value::<LessonList>())),
        ("sweep".to_owned(), text(&value::<Sweep>())),
        ("map".to_owned(), text(&map)),
        (
            "doctor".to_owned(),
            text(&value::<crate::commands::doctor::Diagnosis>()),
        ),
        ("chapters".to_owned(), text(&value::<Chapters>())),
        ("verify".to_owned(), text(&value::<Verification>())),
        ("check".to_owned(), text(&value::<Check>())),
    ];
    for kind in ModelKind::ALL {
        all.push((format!("map-{}", kind.name()), text(&scene_map(kind, &map))));
    }
    all
}

/// The fields of every registered scene's cells (issue 83: each declared in its folder, a
/// [`Field`](crate::physics::chart::Field) of its columns) added to the cell's shared schema,
/// which then takes no other field; a field two scenes share is described by the first.
fn scene_fields(map: &mut serde_json::Value) {
    use crate::physics::chart::Kind;
    let cell = &mut map["$defs"]["CellOutput"];
    cell["additionalProperties"] = false.into();
    for kind in ModelKind::ALL {
        for f in kind.studies().chart.csv.iter().filter_map(|c| c.field()) {
            let mut p = match f.kind {
                Kind::Count => {
                    serde_json::json!({"type": "integer", "format": "uint", "minimum": 0})
                }
                Kind::Time => serde_json::json!({"type": ["number", "null"], "format": "double"}),
                Kind::Number => serde_json::json!({
                    "anyOf": [{"$ref": "#/$defs/Number"}, {"type": "null"}]
                }),
                Kind::Flag => serde_json::json!({"type": "boolean"}),
            };
            p["description"] = f.doc.into();
            if let Some(props) = cell["properties"].as_object_mut() {
                props.entry(f.name).or_insert(p);
            }
        }
    }
}

/// `study map`'s schema narrowed to one scene's chart (issue 83: a scene's cell is its own
/// shape, said by its folder's `ChartWords::csv`): `model` is that scene, and a cell holds its
/// index and coordinates, the fields the scene's cells carry and nothing else, and either the
/// scene's answer (`reversals` or `stable`) or a failed run's `error`.
fn scene_map(kind: ModelKind, map: &serde_json::Value) -> serde_json::Value {
    use crate::physics::chart::Column;
    let mut v = map.clone();
    let words = kind.studies().chart;
    v["title"] = format!(
        "{} ({} chart)",
        map["title"].as_str().unwrap_or("map"),
        kind.name()
    )
    .into();
    v["properties"]["model"] = serde_json::json!({
        "const": kind.name(),
        "description": format!("The scene: always `{}` in this schema.", kind.name()),
    });
    // Every cell has these; a failed one also `decided: false` and its `error`.
    let mut keep = vec!["index", "coords", "error", "decided"];
    keep.extend(
        words
            .csv
            .iter()
            .filter(|c| !matches!(c, Column::Index | Column::X | Column::Y))
            .map(|c| c.heading("", "")),
    );
    let cell = &mut v["$defs"]["CellOutput"];
    if let Some(props) = cell["properties"].as_object_mut() {
        props.retain(|k, _| keep.contains(&k.as_str()));
    }
    let answer = crate::physics::chart::answer_field(words.csv).map_or("error", |f| f.name);
    cell["anyOf"] = serde_json::json!([{ "required": [answer] }, { "required": ["error"] }]);
    v
}
