//! The JSON Schemas of `simulate --format json` (`docs/schemas/`) against real reports: every
//! shipped preset of both scenes, and the starts whose reports hold the `null`s the schemas
//! allow (issue 24: "the JSON schema says which fields may be null and why"). A schema that
//! misses a field, allows one that is not there, or forbids a `null` that occurs fails here;
//! and a report bent out of shape is shown to fail the schema, so the check can fail.

use rattleback::physics::ModelKind;
use rattleback::physics::chart::{Kind, answer_field};
use serde_json::Value;

fn schema(name: &str) -> jsonschema::Validator {
    let path = format!("{}/docs/schemas/simulate-{name}.schema.json", root!());
    let text = std::fs::read_to_string(&path).unwrap();
    let value: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(
        value["properties"]["schema_version"]["const"],
        u64::from(rattleback::simulate::SCHEMA_VERSION),
        "{path}: schema_version"
    );
    jsonschema::draft202012::new(&value).unwrap()
}

fn report(args: &[&str]) -> Value {
    crate::common::simulate_json(args)
}

fn check(validator: &jsonschema::Validator, what: &str, value: &Value) {
    let errors: Vec<String> = validator
        .iter_errors(value)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect();
    assert!(errors.is_empty(), "{what}: {errors:#?}");
}

/// Whether `report` (a `simulate --format json` report of any scene) is valid against its scene's
/// schema: the errors, said, when not.
pub(crate) fn valid_report(report: &Value) -> Result<(), String> {
    let v = schema(scene(report));
    let errors: Vec<String> = v
        .iter_errors(report)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect();
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors.join("; "))
    }
}

fn scene(value: &Value) -> &str {
    value["model"]
        .as_str()
        .expect("every report names its model")
}

#[test]
fn every_shipped_preset_matches_its_schema() {
    let validators: Vec<_> = ModelKind::ALL
        .iter()
        .map(|k| (k.name(), schema(k.name())))
        .collect();
    for (name, _) in rattleback::scenario::shipped::SHIPPED {
        let r = report(&["--preset", name]);
        let (_, v) = validators
            .iter()
            .find(|(n, _)| *n == scene(&r))
            .expect("a schema per scene");
        check(v, name, &r);
        // `schema_version` then `model` first, as every JSON output begins; `model` required.
        let (_, text, _) = crate::common::bin(&["simulate", "--preset", name, "--format", "json"]);
        let keys: Vec<&str> = text
            .lines()
            .filter_map(|l| l.trim_start().strip_prefix('"'))
            .filter_map(|l| l.split('"').next())
            .take(2)
            .collect();
        assert_eq!(keys, ["schema_version", "model"], "{name}");
        let mut without = r.clone();
        without.as_object_mut().unwrap().remove("model");
        assert!(!v.is_valid(&without), "{name}: valid without model");
    }
    // The celt's null: a chaotic run whose companion counts other crossings has no bound.
    let celt = &validators.iter().find(|(n, _)| *n == "celt").unwrap().1;
    let mut bent = report(&["--preset", "celt-clockwise"]);
    bent["auto"]["error_estimate"] = Value::Null;
    check(celt, "celt with no bound", &bent);
    bent["final"]["omega"] = serde_json::json!([1.0, 2.0]);
    assert!(
        !celt.is_valid(&bent),
        "a bent celt report passes its schema"
    );
}

#[test]
fn the_nulls_the_schemas_allow_occur_and_validate() {
    let (rattleback, kapitza) = (schema("rattleback"), schema("kapitza"));
    // No spin: no critical ratio, no start ratio; uniform regime, no turning points.
    let r = report(&["--set", "initial.gamma_dot=0"]);
    assert!(r["effective"]["critical_ratio"].is_null());
    assert!(r["effective"]["turning_points"].is_null());
    check(&rattleback, "gamma_dot = 0", &r);
    // A fixed-step method: `step` is a number, `auto` absent.
    let r = report(&["--method", "strang", "--step", "1e-3"]);
    assert!(r["step"].is_number() && r.get("auto").is_none());
    check(&rattleback, "strang", &r);
    // Rotating start: no half period, the averaged block of a direct averaged2 run.
    let r = report(&[
        "--preset",
        "supercritical",
        "--method",
        "averaged2",
        "--set",
        "spring.k=1e6",
    ]);
    assert!(r["effective"]["half_period"].is_null() && r["averaged"].is_object());
    check(&rattleback, "rotating averaged2", &r);
    // The pendulum below its threshold: no upright frequency.
    let r = report(&["--preset", "kapitza-falls"]);
    assert!(r["effective"]["upright_frequency"].is_null());
    check(&kapitza, "kapitza-falls", &r);
    let r = report(&["--preset", "kapitza-upright", "--method", "rk4"]);
    check(&kapitza, "kapitza rk4", &r);
}

#[test]
fn a_report_bent_out_of_shape_fails_its_schema() {
    let v = schema("rattleback");
    let good = report(&[]);
    check(&v, "default", &good);
    let bend = |f: &dyn Fn(&mut Value)| {
        let mut r = good.clone();
        f(&mut r);
        assert!(!v.is_valid(&r), "accepted: {r}");
    };
    bend(&|r| {
        r.as_object_mut().unwrap().remove("energy");
    });
    bend(&|r| r["surprise"] = Value::from(1));
    bend(&|r| r["final"]["alpha"] = Value::Null);
    bend(&|r| r["model"] = Value::from("kapitza"));
    bend(&|r| r["schema_version"] = Value::from(2));
    bend(&|r| r["reversals"]["count"] = Value::from(-1));
    // The pendulum's schema does not accept the rattleback's report.
    assert!(!schema("kapitza").is_valid(&good));
}

/// Issue 25: the refactor of the model seam changes no byte of any shipped preset's report
/// (`wall_seconds` aside, the one field that differs between identical runs). Regenerate only
/// for a deliberate change of output:
/// `for p in presets/*.toml; do n=$(basename $p .toml); rattleback simulate --preset $n --format json | sed -E 's/"wall_seconds": [0-9.e-]+/"wall_seconds": 0/' > tests/fixtures/golden/$n.json; done`
#[test]
fn every_shipped_preset_reports_the_pinned_bytes() {
    let wall = |text: &str| -> String {
        text.lines()
            .map(|l| {
                if l.trim_start().starts_with("\"wall_seconds\":") {
                    "    \"wall_seconds\": 0".to_owned()
                } else {
                    l.to_owned()
                }
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    for (name, _) in rattleback::scenario::shipped::SHIPPED {
        let out = crate::common::rattleback()
            .args(["simulate", "--format", "json", "--preset", name])
            .output()
            .unwrap();
        let got = wall(&String::from_utf8(out.stdout).unwrap());
        let path = format!("{}/tests/fixtures/golden/{name}.json", root!());
        let want = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            got.trim_end(),
            want.trim_end(),
            "{name}: differs from {path}"
        );
    }
}

/// Issue 25: presets are read and written from each model's parameter table; every shipped
/// preset, parsed and written again, gives the pinned bytes (`tests/fixtures/golden/NAME.toml`)
/// and parses back to the same preset. Regenerate only for a deliberate change of the format:
/// `UPDATE_GOLDEN=1 cargo test --test it schemas::every_shipped_preset_writes_the_pinned_toml`.
#[test]
fn every_shipped_preset_writes_the_pinned_toml() {
    use rattleback::scenario::Preset;
    for (name, text) in rattleback::scenario::shipped::SHIPPED {
        let preset = Preset::parse(text, name, name, &[]).unwrap();
        let toml = preset.to_toml();
        let path = format!("{}/tests/fixtures/golden/{name}.toml", root!());
        if std::env::var_os("UPDATE_GOLDEN").is_some() {
            std::fs::write(&path, &toml).unwrap();
        }
        let want = std::fs::read_to_string(&path).unwrap();
        assert_eq!(toml, want, "{name}: differs from {path}");
        let again = Preset::parse(&toml, name, name, &[]).unwrap();
        assert_eq!(again, preset, "{name}: does not read back");
    }
}

/// Issue 25: docs/reference/presets.md is generated from the parameter tables and kept true.
#[test]
fn the_preset_reference_is_generated_from_the_tables() {
    let text = rattleback::scenario::preset::reference();
    let path = format!("{}/docs/reference/presets.md", root!());
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, &text).unwrap();
    }
    let want = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        text, want,
        "{path} is stale: regenerate it (see the file's first lines)"
    );
    for key in [
        "body.ix",
        "spring.k",
        "pendulum.epsilon",
        "view.theta_range",
    ] {
        assert!(want.contains(&format!("`{key}`")), "{key}");
    }
}

const LECTURE: &str = concat!(root!(), "/tests/fixtures/sessions/lecture.jsonl");
const LECTURE_PRESET: &str = concat!(root!(), "/presets/subcritical.toml");

/// Issue 28: `--format json` where a check fails says how, in the same shape: a session that
/// diverges (exit 1), one cut short (exit 1), one that cannot be read (exit 2), files with
/// problems (exit 2); each validates against its schema.
#[test]
fn failed_checks_in_json_say_how_and_validate() {
    let load = |name: &str| {
        let text = rattleback::commands::outputs::schemas()
            .into_iter()
            .find(|(n, _)| *n == name)
            .unwrap()
            .1;
        jsonschema::draft202012::new(&serde_json::from_str::<Value>(&text).unwrap()).unwrap()
    };
    let (verify, check_schema) = (load("verify"), load("check"));
    let dir = std::env::temp_dir().join(format!("rattleback-json-fail-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(LECTURE).unwrap();
    // A checkpoint's state changed in its last digit: diverged.
    let lines: Vec<&str> = text.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.contains("\"kind\":\"checkpoint\""))
        .expect("a checkpoint");
    let mut bent: Vec<String> = lines.iter().map(|l| (*l).to_owned()).collect();
    bent[at] = bent[at].replacen("\"state\":[", "\"state\":[1e-3,", 1);
    let cases: [(&str, String, i32, &str); 3] = [
        ("bent.jsonl", bent.join("\n") + "\n", 1, "divergence"),
        (
            "cut.jsonl",
            lines[..lines.len() - 1].join("\n") + "\n",
            1,
            "incomplete_through",
        ),
        ("junk.jsonl", "not a session\n".to_owned(), 2, "error"),
    ];
    for (name, content, want, field) in cases {
        let file = dir.join(name);
        std::fs::write(&file, content).unwrap();
        let (code, out, err) = crate::common::bin(&[
            "replay",
            file.to_str().unwrap(),
            "--verify",
            "--format",
            "json",
        ]);
        assert_eq!(code, want, "{name}: {err}");
        let v: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("{name}: {e}: {out}"));
        assert_eq!(v["verified"], false, "{name}");
        assert!(!v[field].is_null(), "{name}: {field} is null: {v}");
        check(&verify, name, &v);
    }
    let bad = concat!(root!(), "/tests/fixtures/bad/many-problems.toml");
    let (code, out, _) = crate::common::bin(&["check", bad, "--format", "json"]);
    assert_eq!(code, 2);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert!(v["problems"].as_array().unwrap().len() > 1, "{v}");
    assert!(v["problems"][0]["line"].is_number(), "{v}");
    check(&check_schema, "many problems", &v);
    // json with both, or neither, is refused.
    let (code, _, err) = crate::common::bin(&[
        "replay",
        LECTURE,
        "--chapters",
        "--verify",
        "--format",
        "json",
    ]);
    assert_eq!(code, 2, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 28: every JSON output begins with `schema_version` and `model` and has a JSON Schema,
/// generated from its type and checked in (`cargo run --example output_schemas`); real outputs
/// of each command validate, and a bent one does not.
#[test]
#[allow(clippy::too_many_lines)] // the table of every command whose JSON is checked
fn every_other_json_output_has_its_version_model_and_schema() {
    let dir = std::path::Path::new(root!()).join("docs/schemas");
    let mut validators = std::collections::BTreeMap::new();
    for (name, text) in rattleback::commands::outputs::schemas() {
        let path = dir.join(format!("{name}.schema.json"));
        let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
        assert_eq!(
            on_disk,
            text,
            "{}: regenerate with `cargo run --example output_schemas`",
            path.display()
        );
        let value: Value = serde_json::from_str(&text).unwrap();
        validators.insert(name, jsonschema::draft202012::new(&value).unwrap());
    }
    // A user preset, theme and lesson, so the lists hold both sources.
    let config = std::env::temp_dir().join(format!("rattleback-outputs-{}", std::process::id()));
    for sub in ["presets", "themes", "lessons"] {
        std::fs::create_dir_all(config.join(sub)).unwrap();
    }
    let preset = rattleback::scenario::shipped::source_text("subcritical").unwrap();
    let preset = preset.replace("name = \"Subcritical start\"", "name = \"Mine\"");
    assert!(preset.contains("\"Mine\""));
    std::fs::write(config.join("presets/mine.toml"), preset).unwrap();
    let runs: &[(&str, &[&str])] = &[
        ("presets", &["presets", "--format", "json"]),
        ("themes", &["themes", "--format", "json"]),
        ("lessons", &["lessons", "--format", "json"]),
        (
            "sweep",
            &[
                "study", "sweep", "--format", "json", "--ladder", "10,100", "--t-end", "2",
            ],
        ),
        (
            "sweep",
            &[
                "study",
                "sweep",
                "--preset",
                "kapitza-upright",
                "--format",
                "json",
                "--ladder",
                "0.1,0.05",
                "--t-end",
                "2",
            ],
        ),
        (
            "map",
            &[
                "study", "map", "--format", "json", "--grid", "4x3", "--t-end", "2",
            ],
        ),
        (
            "map",
            &[
                "study",
                "map",
                "--preset",
                "kapitza-coarse",
                "--format",
                "json",
                "--grid",
                "4x3",
            ],
        ),
        (
            "map",
            &[
                "study",
                "map",
                "--preset",
                "celt-clockwise",
                "--format",
                "json",
                "--grid",
                "3x2",
                "--t-end",
                "4",
            ],
        ),
        (
            "map",
            &[
                "study",
                "map",
                "--preset",
                "kapitza-coarse",
                "--format",
                "json",
                "--grid",
                "4x3",
                "--shard",
                "2/3",
            ],
        ),
        ("doctor", &["doctor", "--format", "json"]),
        (
            "chapters",
            &["replay", LECTURE, "--chapters", "--format", "json"],
        ),
        (
            "verify",
            &["replay", LECTURE, "--verify", "--format", "json"],
        ),
        ("check", &["check", LECTURE_PRESET, "--format", "json"]),
    ];
    for &(schema, args) in runs {
        let (code, out, err) = crate::common::bin_in(&config, args);
        assert_eq!(code, 0, "{args:?}: {err}");
        // The first two keys, as printed.
        let keys: Vec<&str> = out
            .lines()
            .filter_map(|l| l.trim_start().strip_prefix('"'))
            .filter_map(|l| l.split('"').next())
            .take(2)
            .collect();
        let compact_first = out.trim_start().starts_with("{\"schema_version\":");
        assert!(
            keys == ["schema_version", "model"] || compact_first,
            "{args:?}: begins with {keys:?}"
        );
        let value: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(
            value["schema_version"],
            rattleback::commands::outputs::SCHEMA_VERSION
        );
        assert!(value.get("model").is_some(), "{args:?}: no model");
        check(&validators[schema], &format!("{args:?}"), &value);
        if schema == "map" {
            // Issue 83: and against its own scene's narrowed schema.
            let own = format!("map-{}", scene(&value));
            check(
                &validators[own.as_str()],
                &format!("{args:?} ({own})"),
                &value,
            );
        }
        let mut bent = value.clone();
        bent["surprise"] = Value::from(1);
        assert!(
            !validators[schema].is_valid(&bent),
            "{args:?}: accepts a stray field"
        );
        // `model` is required everywhere, `null` where the output is about no scene.
        let mut without = value.clone();
        without.as_object_mut().unwrap().remove("model");
        assert!(
            !validators[schema].is_valid(&without),
            "{args:?}: accepts a document without model"
        );
    }
    std::fs::remove_dir_all(&config).ok();
}

/// Issue 83: each scene's chart has its own schema (`docs/schemas/map-NAME.schema.json`): a
/// real chart of every shipped scene validates against its own, is refused by every other
/// scene's (another scene's name, another scene's fields), and is refused by its own when a
/// cell loses its answer or gains another scene's field; the shared `map` schema takes all.
#[test]
fn each_scene_chart_validates_against_its_own_schema_and_no_other() {
    let schemas: std::collections::BTreeMap<String, jsonschema::Validator> =
        rattleback::commands::outputs::schemas()
            .into_iter()
            .filter(|(n, _)| n.starts_with("map"))
            .map(|(n, t)| {
                let v: Value = serde_json::from_str(&t).unwrap();
                (n, jsonschema::draft202012::new(&v).unwrap())
            })
            .collect();
    assert_eq!(
        schemas.len(),
        ModelKind::ALL.len() + 1,
        "{:?}",
        schemas.keys()
    );
    for kind in ModelKind::ALL {
        let preset = rattleback::scenario::shipped::base_preset(kind);
        let (code, out, err) = crate::common::bin(&[
            "study", "map", "--preset", preset, "--format", "json", "--grid", "3x2", "--force",
        ]);
        assert_eq!(code, 0, "{preset}: {err}");
        let chart: Value = serde_json::from_str(&out).unwrap();
        let own = format!("map-{}", kind.name());
        check(&schemas["map"], preset, &chart);
        check(&schemas[own.as_str()], preset, &chart);
        for other in ModelKind::ALL.iter().filter(|&&o| o != kind) {
            let name = format!("map-{}", other.name());
            assert!(
                !schemas[name.as_str()].is_valid(&chart),
                "{preset} passes {name}"
            );
        }
        // The scene's answer, and a field of another scene's cells.
        let csv = kind.studies().chart.csv;
        let answer = answer_field(csv).unwrap().name;
        let fields: Vec<&str> = csv
            .iter()
            .filter_map(|c| c.field())
            .map(|f| f.name)
            .collect();
        let stray = ModelKind::ALL
            .iter()
            .flat_map(|o| o.studies().chart.csv.iter().filter_map(|c| c.field()))
            .find(|f| !fields.contains(&f.name))
            .unwrap();
        let stray_value = match stray.kind {
            Kind::Flag => Value::from(true),
            Kind::Count | Kind::Time | Kind::Number => Value::from(1),
        };
        let stray = stray.name;
        let mut lost = chart.clone();
        lost["cells"][0].as_object_mut().unwrap().remove(answer);
        assert!(
            !schemas[own.as_str()].is_valid(&lost),
            "{preset}: a cell without {answer}"
        );
        let mut gained = chart.clone();
        gained["cells"][0][stray] = stray_value;
        assert!(
            !schemas[own.as_str()].is_valid(&gained),
            "{preset}: a cell with {stray}"
        );
        assert!(
            schemas["map"].is_valid(&gained),
            "{preset}: the shared schema takes {stray}"
        );
    }
}
