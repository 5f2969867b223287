//! Issue 15, item 5: the session format is documented and its JSON Schema, generated from the
//! types, is checked in; the checked-in sessions and a fresh recording validate against it (an
//! independent validator, `jsonschema`), and broken lines do not.

use crate::common;

use common::Headless;
use rattleback::app::{Key, Outcome};
use rattleback::record::{self, Line, session_schema};

fn schema_path() -> String {
    format!("{}/docs/session.schema.json", root!())
}

fn validator() -> jsonschema::Validator {
    let schema: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(schema_path()).unwrap()).unwrap();
    jsonschema::validator_for(&schema).expect("a valid JSON Schema")
}

#[track_caller]
fn assert_valid(v: &jsonschema::Validator, text: &str, what: &str) {
    let value: serde_json::Value = serde_json::from_str(text).unwrap();
    let errors: Vec<String> = v.iter_errors(&value).map(|e| e.to_string()).collect();
    assert!(errors.is_empty(), "{what}: {errors:?}\n{text}");
}

#[test]
fn the_checked_in_schema_is_generated_from_the_types() {
    assert_eq!(
        std::fs::read_to_string(schema_path()).unwrap(),
        session_schema(),
        "run `cargo run --example session_schema > docs/session.schema.json`"
    );
}

#[test]
fn the_checked_in_sessions_validate_line_by_line() {
    let v = validator();
    for name in ["subcritical.jsonl", "lesson.jsonl", "kapitza.jsonl"] {
        let path = format!("{}/tests/fixtures/sessions/{name}", root!());
        let text = std::fs::read_to_string(&path).unwrap();
        for (i, line) in text.lines().enumerate() {
            assert_valid(&v, line, &format!("{name}:{}", i + 1));
        }
    }
}

#[test]
fn a_fresh_recording_validates_and_broken_lines_do_not() {
    let v = validator();
    let mut h = Headless::new("subcritical");
    h.app.on_key(Key::Char('R'));
    h.app
        .on_outcome(Outcome::Recording(Ok("fresh.jsonl".to_owned())));
    for k in [
        Key::Char(' '),
        Key::Char('M'),
        Key::Right,
        Key::Enter,
        Key::Esc,
        Key::Char('+'),
        Key::Char('z'),
        Key::Char(' '),
    ] {
        h.key(k);
    }
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    let journal = h.app.take_journal();
    assert!(journal.len() >= 6, "{journal:?}");
    for (t, generation, event) in journal {
        let line = Line {
            wall: 1.5,
            t,
            generation,
            chain: Some("0123456789abcdef".to_owned()),
            event,
        };
        assert_valid(&v, &serde_json::to_string(&line).unwrap(), "fresh line");
    }
    let header = record::Header {
        format: record::FORMAT.to_owned(),
        version: record::VERSION,
        program: "test".to_owned(),
        preset: String::new(),
        method: "auto".to_owned(),
        tolerance: 1e-9,
        terminal: record::Size {
            width: 80,
            height: 24,
        },
        theme: record::ThemeRef::Name("Default (16 colours)".to_owned()),
        fps: 30.0,
        lesson: None,
    };
    assert_valid(&v, &serde_json::to_string(&header).unwrap(), "header");
    for bad in [
        r#"{"wall":1.0,"t":0.0,"generation":1,"kind":"teleport"}"#,
        r#"{"wall":1.0,"generation":1,"kind":"play"}"#,
        r#"{"wall":"soon","t":0.0,"generation":1,"kind":"play"}"#,
        r#"{"wall":1.0,"t":0.0,"generation":1,"kind":"speed"}"#,
        r#"{"format":"rattleback-session","version":3}"#,
    ] {
        let value: serde_json::Value = serde_json::from_str(bad).unwrap();
        assert!(!v.is_valid(&value), "accepted: {bad}");
    }
}

#[test]
fn the_format_document_names_every_event_and_header_field() {
    let doc = std::fs::read_to_string(format!("{}/docs/session-format.md", root!())).unwrap();
    let schema: serde_json::Value = serde_json::from_str(&session_schema()).unwrap();
    let header = schema["$defs"]["Header"]["properties"].as_object().unwrap();
    for field in header.keys() {
        assert!(
            doc.contains(&format!("`{field}`")),
            "header field {field} undocumented"
        );
    }
    for kind in schema["$defs"]["Line"]["oneOf"].as_array().unwrap() {
        let name = kind["properties"]["kind"]["const"].as_str().unwrap();
        assert!(
            doc.contains(&format!("`{name}`")),
            "event {name} undocumented"
        );
    }
}

/// Issue 57: the plan key is read back as the model it was written for, whatever the model. Its
/// recorded form is untagged (files of every format read as before), so the guard is on the
/// shapes: no model's required fields may all stand in another model's key, for every model
/// (the list comes from `ModelKind::ALL`: a fourth model is checked without editing this test),
/// and every model's key round-trips to its own variant.
#[test]
fn every_models_plan_key_reads_back_as_its_own() {
    use rattleback::physics::ModelKind;
    use rattleback::sim::PlanKey;
    let schema = serde_json::to_value(schemars::schema_for!(PlanKey)).unwrap();
    let variants = schema["anyOf"].as_array().expect("one shape per model");
    assert_eq!(variants.len(), ModelKind::ALL.len(), "a shape per model");
    let fields = |v: &serde_json::Value, what: &str| -> std::collections::BTreeSet<String> {
        v[what]
            .as_array()
            .map(|a| a.iter().map(|x| x.as_str().unwrap().to_owned()).collect())
            .or_else(|| v[what].as_object().map(|o| o.keys().cloned().collect()))
            .unwrap_or_default()
    };
    for (i, a) in variants.iter().enumerate() {
        for (j, b) in variants.iter().enumerate() {
            if i != j {
                let (required, present) = (fields(a, "required"), fields(b, "properties"));
                assert!(!required.is_empty() && !present.is_empty(), "{a} {b}");
                assert!(
                    !required.is_subset(&present),
                    "the key of shape {i} would read shape {j}'s: {required:?} all in {present:?}"
                );
            }
        }
    }
    for kind in ModelKind::ALL {
        let name = rattleback::scenario::shipped::SHIPPED
            .iter()
            .map(|(n, _)| *n)
            .find(|n| {
                rattleback::scenario::shipped::resolve(n, &[]).is_ok_and(|p| p.model.kind() == kind)
            })
            .expect("a shipped preset of every model");
        let preset = rattleback::scenario::shipped::resolve(name, &[]).unwrap();
        let app = rattleback::app::App::new(&preset, rattleback::app::Options::at(30.0)).0;
        let key = PlanKey::of(&app.scenario.spec(false));
        let text = serde_json::to_string(&key).unwrap();
        let back: PlanKey = serde_json::from_str(&text).unwrap();
        assert_eq!(back, key, "{kind:?}: {text}");
    }
}
