//! Issue 6: sessions recorded through the app's update function replay exactly; the checked-in
//! example verifies; truncated, corrupt, mismatched and tampered files are handled.

use std::process::Command as Process;

mod common;

use common::Headless;
use rattleback::app::journal::Event;
use rattleback::app::{Key, Outcome};
use rattleback::record::{self, FORMAT, Header, Line, RecordError, Recorder, Size, VERSION};

fn bin(args: &[&str]) -> (i32, String, String) {
    let out = Process::new(env!("CARGO_BIN_EXE_rattleback"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn example() -> String {
    format!(
        "{}/tests/fixtures/sessions/subcritical.jsonl",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rattleback-rec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    let _ = std::fs::remove_file(&p);
    p
}

#[test]
fn recorded_through_update_replays_bit_for_bit_and_bytes_round_trip() {
    let mut h = Headless::new("subcritical");
    let app = &h.app;
    let header = Header {
        format: FORMAT.to_owned(),
        version: VERSION,
        program: "test".to_owned(),
        preset: app.to_preset(&app.scenario.name).to_toml(),
        method: app.scenario.settings.method.name().to_owned(),
        tolerance: app.scenario.settings.tolerance,
        terminal: Size {
            width: 80,
            height: 24,
        },
        theme: 0,
        fps: 30.0,
    };
    assert_eq!(
        h.app.on_key(Key::Char('R')),
        vec![rattleback::app::Effect::StartRecording]
    );
    h.app
        .on_outcome(Outcome::Recording(Ok("recorded.jsonl".to_owned())));
    h.key(Key::Char(' '));
    h.tick(1.7);
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    for k in [Key::Char('j'), Key::Char('j'), Key::Char('L')] {
        h.key(k); // iz coarse up: restarts
    }
    for _ in 0..3 {
        h.tick(0.9);
    }
    // Paused after the worker ran ahead: the checkpoint is served at its step's end.
    h.key(Key::Char(' '));
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    let journal = h.app.take_journal();
    assert_eq!(
        journal
            .iter()
            .filter(|(_, _, e)| matches!(e, Event::Checkpoint { .. }))
            .count(),
        2
    );
    assert!(
        journal
            .iter()
            .any(|(_, _, e)| matches!(e, Event::Set { field, .. } if field == "iz"))
    );
    assert!(
        journal
            .iter()
            .any(|(_, _, e)| matches!(e, Event::Plan { .. })),
        "the resolved plan is recorded"
    );

    let path = temp("recorded.jsonl");
    let mut rec = Recorder::create(&path, &header).unwrap();
    let lines: Vec<Line> = journal
        .into_iter()
        .enumerate()
        .map(|(i, (t, generation, event))| Line {
            wall: i as f64 * 0.5,
            t,
            generation,
            event,
        })
        .collect();
    for l in &lines {
        rec.write(l).unwrap();
    }
    drop(rec);
    let back = record::read(&path).unwrap();
    assert!(back.warnings.is_empty());
    assert_eq!(back.header, header);
    assert_eq!(
        back.lines
            .iter()
            .map(|(_, l)| l.clone())
            .collect::<Vec<_>>(),
        lines
    );
    // Bytes: writing what was read gives the same file.
    let again = temp("again.jsonl");
    let mut rec = Recorder::create(&again, &back.header).unwrap();
    for (_, l) in &back.lines {
        rec.write(l).unwrap();
    }
    drop(rec);
    assert_eq!(
        std::fs::read(&path).unwrap(),
        std::fs::read(&again).unwrap()
    );
    assert_eq!(record::verify(&back, "recorded").unwrap(), 2);
}

#[test]
fn checked_in_example_verifies() {
    let (code, out, err) = bin(&["replay", &example(), "--verify"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("4 checkpoint(s) reproduced bit for bit"),
        "{out}"
    );
}

#[test]
fn truncated_last_line_is_ignored_with_a_warning() {
    let text = std::fs::read_to_string(example()).unwrap();
    let cut = &text[..text.len() - 40];
    let path = temp("truncated.jsonl");
    std::fs::write(&path, cut).unwrap();
    let (code, out, err) = bin(&["replay", path.to_str().unwrap(), "--verify"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warning") && err.contains(":11: truncated last line ignored"),
        "{err}"
    );
    assert!(out.contains("3 checkpoint(s)"), "{out}");
}

#[test]
fn corrupt_line_version_and_tampering_are_reported_by_line() {
    let text = std::fs::read_to_string(example()).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();

    let mut corrupt = lines.clone();
    corrupt[4] = "{\"wall\": oops".to_owned();
    let path = temp("corrupt.jsonl");
    std::fs::write(&path, corrupt.join("\n") + "\n").unwrap();
    let (code, _, err) = bin(&["replay", path.to_str().unwrap(), "--verify"]);
    assert_eq!(code, 2);
    assert!(err.contains("corrupt.jsonl:5: bad event"), "{err}");

    let mut future = lines.clone();
    future[0] = future[0].replace("\"version\":1", "\"version\":9");
    let path = temp("future.jsonl");
    std::fs::write(&path, future.join("\n") + "\n").unwrap();
    let (code, _, err) = bin(&["replay", path.to_str().unwrap(), "--verify"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("future.jsonl:1: format version 9 is not supported"),
        "{err}"
    );

    let (code, _, err) = bin(&["replay", "/nonexistent/session.jsonl", "--verify"]);
    assert_eq!(code, 2);
    assert!(err.contains("/nonexistent/session.jsonl"), "{err}");

    // A checkpoint whose state was changed in the last digit diverges, named by line.
    let i = lines
        .iter()
        .position(|l| l.contains("\"checkpoint\""))
        .unwrap();
    let value: serde_json::Value = serde_json::from_str(&lines[i]).unwrap();
    let alpha = value["state"][1].as_f64().unwrap();
    lines[i] = lines[i].replace(
        &format!("{alpha:?}"),
        &format!("{:?}", f64::from_bits(alpha.to_bits() + 1)),
    );
    let path = temp("tampered.jsonl");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    let (code, _, err) = bin(&["replay", path.to_str().unwrap(), "--verify"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains(&format!("tampered.jsonl:{}: divergence", i + 1)),
        "{err}"
    );
}

#[test]
fn nothing_is_overwritten() {
    let path = temp("exists.jsonl");
    std::fs::write(&path, "keep me").unwrap();
    let header = record::read(std::path::Path::new(&example()))
        .unwrap()
        .header;
    assert!(matches!(
        Recorder::create(&path, &header),
        Err(RecordError::Exists(_))
    ));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "keep me");
    // A cast that cannot be written leaves nothing behind.
    let (code, _, err) = bin(&[
        "replay",
        &example(),
        "--export-cast",
        "/nonexistent/dir/out.cast",
    ]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn exported_cast_is_asciicast_v2_with_chapters() {
    let out = temp("demo.cast");
    let (code, stdout, err) = bin(&["replay", &example(), "--export-cast", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("frames"));
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(header["version"], 2);
    assert_eq!(
        (header["width"].as_u64(), header["height"].as_u64()),
        (Some(100), Some(30))
    );
    let events: Vec<serde_json::Value> = lines.map(|l| serde_json::from_str(l).unwrap()).collect();
    assert!(
        events.iter().any(|e| e[1] == "m" && e[2] == "Higher k"),
        "chapter marker"
    );
    let times: Vec<f64> = events.iter().map(|e| e[0].as_f64().unwrap()).collect();
    assert!(
        times.windows(2).all(|w| w[0] <= w[1]),
        "time must not go back"
    );
    assert!(events.iter().filter(|e| e[1] == "o").count() > 50);
}
