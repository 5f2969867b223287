//! Issue 6: sessions recorded through the app's update function replay exactly; the checked-in
//! example verifies; truncated, corrupt, mismatched and tampered files are handled.

use crate::common;

use common::Headless;
use rattleback::app::journal::Event;
use rattleback::app::{Key, Outcome};
use rattleback::record::{self, Line, RecordError, Recorder};

fn bin(args: &[&str]) -> (i32, String, String) {
    let out = crate::common::rattleback().args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn example() -> String {
    format!("{}/tests/fixtures/sessions/subcritical.jsonl", root!())
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rattleback-rec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    let _ = std::fs::remove_file(&p);
    p
}

/// The end line of a recording written by hand after `last` (the recorder counts the lines), at
/// its time and run stamp as the explorer's recorder writes it.
fn end_line(last: Option<&Line>) -> Line {
    Line {
        wall: 60.0,
        t: last.map_or(0.0, |l| l.t),
        generation: last.map_or(0, |l| l.generation),
        chain: None,
        event: Event::end(),
    }
}

#[test]
#[allow(clippy::too_many_lines)] // one recording, written, read back and verified
fn recorded_through_update_replays_bit_for_bit_and_bytes_round_trip() {
    let mut h = Headless::new("subcritical");
    let app = &h.app;
    let header = crate::common::header_of(app);
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

    // Stopped as `R` stops it: the last frame and its checkpoint (format 10).
    let mut journal = journal;
    h.stop_recording();
    journal.extend(h.app.take_journal());
    let path = temp("recorded.jsonl");
    let mut rec = Recorder::create(&path, &header, None).unwrap();
    let lines: Vec<Line> = journal
        .into_iter()
        .enumerate()
        .map(|(i, (t, generation, event))| Line {
            wall: i as f64 * 0.5,
            t,
            generation,
            chain: None,
            event,
        })
        .collect();
    for l in &lines {
        rec.write(l).unwrap();
    }
    rec.write(&end_line(lines.last())).unwrap();
    drop(rec);
    let back = record::read(&path).unwrap();
    assert!(back.warnings.is_empty());
    assert_eq!(back.header, header);
    let counted = matches!(back.lines.last().unwrap().1.event, Event::End { lines: Some(n), .. } if n == lines.len() + 1);
    assert!(counted, "the end line counts the lines before it");
    assert_eq!(
        back.lines[..lines.len()]
            .iter()
            .map(|(_, l)| Line {
                chain: None,
                ..l.clone()
            })
            .collect::<Vec<_>>(),
        lines
    );
    assert!(
        back.lines.iter().all(|(_, l)| l.chain.is_some()),
        "every line chained"
    );
    // Bytes: writing what was read gives the same file.
    let again = temp("again.jsonl");
    let mut rec = Recorder::create(&again, &back.header, None).unwrap();
    for (_, l) in &back.lines {
        rec.write(l).unwrap();
    }
    drop(rec);
    assert_eq!(
        std::fs::read(&path).unwrap(),
        std::fs::read(&again).unwrap()
    );
    // The two taken while recording, then the two of the last frames (the pause's screen,
    // pending, and the stop's), each reproduced; the last frame is checked.
    let report = record::verify(&back, "recorded", None).unwrap();
    assert_eq!(report.checkpoints, 4);
    assert!(report.final_screen);
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

/// A pendulum session recorded in the explorer over a real terminal (a change of ε, a note,
/// the speed): its checkpoints are `(θ, θ̇)` and verify bit for bit.
#[test]
fn checked_in_pendulum_session_verifies() {
    let path = format!("{}/tests/fixtures/sessions/kapitza.jsonl", root!());
    let (code, out, err) = bin(&["replay", &path, "--verify"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("7 checkpoint(s) reproduced bit for bit"),
        "{out}"
    );
}

/// A format-2 recording made in the explorer (chapters, a note, a change of k, the series pane):
/// it records the plans `auto` resolved to, and verifies with them.
#[test]
fn checked_in_lesson_of_format_2_verifies_with_its_recorded_plans() {
    let path = format!("{}/tests/fixtures/sessions/lesson.jsonl", root!());
    let rec = record::read(std::path::Path::new(&path)).unwrap();
    assert_eq!(rec.header.version, 2);
    let book = record::plan_book(&rec);
    assert_eq!(book.recorded.len(), 2, "one plan per run");
    assert_eq!(record::verify(&rec, &path, None).unwrap().checkpoints, 6);
    // A recorded plan wins over what auto would choose today: record another plan (with a
    // valid chain) and the trajectory, hence the first checkpoint after it, changes.
    let tmp = temp("lesson-changed-plan.jsonl");
    let mut out = Recorder::create(&tmp, &rec.header, None).unwrap();
    let mut changed = false;
    for (_, line) in &rec.lines {
        let mut line = line.clone();
        if let Event::Plan { plan, .. } = &mut line.event
            && !changed
        {
            plan.method = rattleback::physics::Method::BlanesMoan4;
            changed = true;
        }
        out.write(&line).unwrap();
    }
    drop(out);
    let back = record::read(&tmp).unwrap();
    match record::verify(&back, "changed", None) {
        Err(record::VerifyError::Diverged(d)) => {
            assert!(d.expected.contains("state"), "{d:?}");
        }
        other => panic!("{other:?}"),
    }
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
    let next = record::VERSION + 1;
    future[0] = future[0].replace("\"version\":1", &format!("\"version\":{next}"));
    let path = temp("future.jsonl");
    std::fs::write(&path, future.join("\n") + "\n").unwrap();
    let (code, _, err) = bin(&["replay", path.to_str().unwrap(), "--verify"]);
    assert_eq!(code, 2);
    assert!(
        err.contains(&format!(
            "future.jsonl:1: format version {next} is not supported"
        )),
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
        Recorder::create(&path, &header, None),
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
    // Issue 15: timestamps to the microsecond, an idle limit, notes as markers too.
    assert_eq!(header["idle_time_limit"].as_f64(), Some(2.0));
    for t in &times {
        let micros = t * 1e6;
        assert!(
            (micros - micros.round()).abs() < 1e-6,
            "{t} has more than 6 decimals"
        );
    }
    let text_of = |e: &serde_json::Value| e[2].as_str().unwrap_or("").to_owned();
    assert!(
        events
            .iter()
            .any(|e| e[1] == "m" && text_of(e).starts_with("note: ")),
        "note marker"
    );

    // --cols/--rows/--fps set the cast's size and frame rate.
    let small = temp("small.cast");
    let (code, _, err) = bin(&[
        "replay",
        &example(),
        "--export-cast",
        small.to_str().unwrap(),
        "--cols",
        "80",
        "--rows",
        "24",
        "--fps",
        "5",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&small).unwrap();
    let header: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    assert_eq!(
        (header["width"].as_u64(), header["height"].as_u64()),
        (Some(80), Some(24))
    );
    let frames = text.lines().filter(|l| l.contains("\"o\"")).count();
    assert!(
        frames * 3 < events.iter().filter(|e| e[1] == "o").count() * 2,
        "fewer frames at 5 fps"
    );
    let (code, _, err) = bin(&["replay", &example(), "--cols", "80"]);
    assert_eq!(code, 2, "--cols needs --export-cast: {err}");
}

/// Item 8: an existing output is refused before anything starts (unless `--force`), the
/// session itself never, and `--verify --export-cast` does both.
#[test]
fn outputs_are_never_clobbered_and_verify_exports_too() {
    let out = temp("kept.cast");
    std::fs::write(&out, "keep me").unwrap();
    let (code, _, err) = bin(&["replay", &example(), "--export-cast", out.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("exists") && err.contains("--force"), "{err}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "keep me");
    // The session itself, even with --force.
    let copy = temp("self.jsonl");
    std::fs::copy(example(), &copy).unwrap();
    let (code, _, err) = bin(&[
        "replay",
        copy.to_str().unwrap(),
        "--export-cast",
        copy.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("session being read"), "{err}");
    assert_eq!(
        std::fs::read(&copy).unwrap(),
        std::fs::read(example()).unwrap()
    );
    // --verify --export-cast: both, and --force replaces.
    let (code, stdout, err) = bin(&[
        "replay",
        &example(),
        "--verify",
        "--export-cast",
        out.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        stdout.contains("reproduced bit for bit") && stdout.contains("frames"),
        "{stdout}"
    );
    assert!(std::fs::read_to_string(&out).unwrap().starts_with('{'));
    // --record to an existing file: exit 2 before the terminal is touched.
    let rec = temp("taken.jsonl");
    std::fs::write(&rec, "keep me").unwrap();
    let (code, _, err) = bin(&["--record", rec.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--record") && err.contains("exists"), "{err}");
    assert_eq!(std::fs::read_to_string(&rec).unwrap(), "keep me");
}

/// Item 6: replay shows notes and chapters at their time and keeps them; `]` and `[` move one
/// chapter each press, both ways; the end is a state; `?` opens the replay's help.
#[test]
fn replay_teaches_notes_chapters_and_its_end() {
    use rattleback::app::Mode;
    use rattleback::record::replayer::Replayer;

    // A recording with three chapters and a note, made through the app.
    let mut h = Headless::new("subcritical");
    h.app
        .on_outcome(Outcome::Recording(Ok("lesson.jsonl".to_owned())));
    let mut lines = Vec::new();
    let mut wall = 0.0;
    let mark = |h: &mut Headless, key: char, text: &str| {
        h.key(Key::Char(key));
        for c in text.chars() {
            h.key(Key::Char(c));
        }
        h.key(Key::Enter);
    };
    for (i, title) in ["Start", "First reversal", "Second"].iter().enumerate() {
        mark(&mut h, 'm', title);
        if i == 1 {
            mark(&mut h, 'n', "watch alpha_dot cross zero");
        }
        h.play_until(3.0 * (i as f64 + 1.0), 1.0);
        h.key(Key::Char(' '));
    }
    // One line a wall second (the clock lines, ten a second while playing, are left out here).
    for (t, generation, event) in h.app.take_journal() {
        if event == Event::Clock {
            continue;
        }
        wall += 1.0;
        lines.push(Line {
            wall,
            t,
            generation,
            chain: None,
            event,
        });
    }
    let preset = resolve_header(&h);
    let rebuild = |old: &rattleback::app::App| {
        rattleback::app::App::new_after(&preset, rattleback::app::Options::at(30.0), old)
    };
    let mut r = Replayer::new(lines);
    let mut replay = Headless::of(&preset);
    let _ = r.catch_up(&mut replay.app);
    let step = |r: &mut Replayer, h: &mut Headless, wall: f64| {
        let e = r.advance(wall, &mut h.app);
        h.exec(e);
    };
    let mut steps = 0;
    while replay.app.caption.is_none() {
        step(&mut r, &mut replay, 0.5);
        steps += 1;
        assert!(steps < 20, "no caption");
    }
    let c = replay.app.caption.clone().unwrap();
    assert!(c.chapter && c.text == "Start", "{c:?}");
    // The chapter stays while the replay plays on (the status line does not replace it)...
    for _ in 0..3 {
        step(&mut r, &mut replay, 0.5);
        assert!(replay.app.caption.is_some());
    }
    // ...until the next chapter, then the note.
    while !replay
        .app
        .caption
        .as_ref()
        .is_some_and(|c| c.text.contains("alpha_dot"))
    {
        step(&mut r, &mut replay, 0.5);
        steps += 1;
        assert!(steps < 60, "no note");
    }
    assert!(!replay.app.caption.as_ref().unwrap().chapter);
    let info = replay.app.replay.unwrap();
    assert_eq!((info.chapter, info.chapters), (2, 3));
    // ] goes to the third chapter, [ back to the second, [ again to the first: one per press.
    let press = |r: &mut Replayer, h: &mut Headless, k: char| {
        let e = r.key(Key::Char(k), &mut h.app, &rebuild);
        h.exec(e);
        h.app.replay.unwrap().chapter
    };
    assert_eq!(press(&mut r, &mut replay, ']'), 3);
    assert_eq!(press(&mut r, &mut replay, '['), 2);
    assert_eq!(press(&mut r, &mut replay, '['), 1);
    assert_eq!(replay.app.caption.as_ref().unwrap().text, "Start");
    assert_eq!(press(&mut r, &mut replay, '['), 0, "back to the start");
    assert_eq!(press(&mut r, &mut replay, ']'), 1);
    // ? opens the replay's help.
    let e = r.key(Key::Char('?'), &mut replay.app, &rebuild);
    replay.exec(e);
    assert!(matches!(replay.app.mode, Mode::Help(_)));
    replay.app.on_key(Key::Esc);
    // The end is a state, not a stop.
    for _ in 0..100 {
        step(&mut r, &mut replay, 1.0);
    }
    let info = replay.app.replay.unwrap();
    assert!(info.ended, "{info:?}");
    assert!(!r.running());
}

fn resolve_header(h: &Headless) -> rattleback::scenario::Preset {
    rattleback::scenario::Preset::parse(
        &h.app.to_preset(&h.app.scenario.name).to_toml(),
        "header",
        "recorded",
        &[],
    )
    .unwrap()
}

/// Every line is checked, not only checkpoints: an edit after the last checkpoint, a deleted
/// checkpoint and a changed header field are all found, named by line.
#[test]
fn verify_checks_every_line_through_the_hash_chain() {
    let path = format!("{}/tests/fixtures/sessions/lesson.jsonl", root!());
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let check = |name: &str, edited: Vec<String>, want_line: usize| {
        let p = temp(name);
        std::fs::write(&p, edited.join("\n") + "\n").unwrap();
        let (code, _, err) = bin(&["replay", p.to_str().unwrap(), "--verify"]);
        assert_eq!(code, 1, "{name}: {err}");
        assert!(
            err.contains(&format!(":{want_line}: divergence")),
            "{name}: {err}"
        );
    };
    let owned = |v: &[&str]| v.iter().map(|s| (*s).to_owned()).collect::<Vec<_>>();
    // A note's text changed after the last checkpoint.
    let last = lines.len();
    let mut edited = owned(&lines);
    let i = edited
        .iter()
        .rposition(|l| l.contains("\"kind\":\"panes\""))
        .expect("a panes line");
    edited[i] = edited[i].replace("\"series\":true", "\"series\":false");
    check("edited-late", edited, i + 1);
    // A checkpoint deleted: the next line is named.
    let mut edited = owned(&lines);
    let c = edited
        .iter()
        .position(|l| l.contains("checkpoint"))
        .unwrap();
    edited.remove(c);
    check("deleted", edited, c + 1);
    // An unused header field changed: the first event is named.
    let mut edited = owned(&lines);
    edited[0] = edited[0].replace("\"theme\":0", "\"theme\":3");
    assert_ne!(edited[0], lines[0]);
    check("header", edited, 2);
    assert!(last > 5);
}

/// Header fields and times out of any sane range are refused with their line, before anything
/// is allocated from them.
#[test]
fn absurd_headers_and_times_are_refused() {
    let text = std::fs::read_to_string(example()).unwrap();
    let lines: Vec<String> = text.lines().map(str::to_owned).collect();
    for (name, from, to, line, what) in [
        ("huge", "\"width\":100", "\"width\":65535", 0, "terminal"),
        ("fps", "\"fps\":30.0", "\"fps\":-30.0", 0, "fps"),
        ("fps-big", "\"fps\":30.0", "\"fps\":1e300", 0, "fps"),
        ("wall", "\"wall\":1.203068726", "\"wall\":1e300", 1, "wall"),
    ] {
        let mut edited = lines.clone();
        assert!(edited[line].contains(from), "{name}: fixture changed");
        edited[line] = edited[line].replace(from, to);
        let p = temp(&format!("{name}.jsonl"));
        std::fs::write(&p, edited.join("\n") + "\n").unwrap();
        for args in [vec!["--verify"], vec!["--export-cast", "/tmp/never.cast"]] {
            let mut all = vec!["replay", p.to_str().unwrap()];
            all.extend(args);
            let (code, _, err) = bin(&all);
            assert_eq!(code, 2, "{name}: {err}");
            assert!(
                err.contains(&format!(":{}: ", line + 1)) && err.contains(what),
                "{name}: {err}"
            );
        }
    }
}

#[test]
fn panes_and_a_map_cell_loaded_are_recorded_and_replayed() {
    use rattleback::app::panes::Pane;
    let mut h = Headless::new("subcritical");
    let first = h.app.to_preset(&h.app.scenario.name);
    h.app.on_key(Key::Char('R'));
    h.app
        .on_outcome(Outcome::Recording(Ok("panes.jsonl".to_owned())));
    h.key(Key::Char('M'));
    h.key(Key::Right);
    h.key(Key::Up);
    h.key(Key::Enter);
    h.key(Key::Esc);
    h.key(Key::Char('W'));
    let journal = h.app.take_journal();
    let panes: Vec<Vec<Pane>> = journal
        .iter()
        .filter_map(|(_, _, e)| match e {
            Event::Layout { panes, .. } => Some(panes.clone()),
            _ => None,
        })
        .collect();
    // The most recently opened last (the one in front where the column cannot show both).
    assert_eq!(panes, [vec![Pane::Map], vec![Pane::Map, Pane::Weak]]);
    assert!(
        journal
            .iter()
            .any(|(_, _, e)| matches!(e, Event::Preset { .. })),
        "the loaded cell is recorded as the preset it makes"
    );
    // Played back on a fresh explorer: the same panes, the same start.
    let mut r = Headless::of(&first);
    for (_, _, e) in &journal {
        let effects = r.app.apply_event(e, false);
        r.exec(effects);
    }
    assert_eq!(r.app.scenario.settings, h.app.scenario.settings);
    for pane in [Pane::Map, Pane::Weak] {
        assert!(r.app.view.panes.shows(pane), "{pane:?}");
    }
    assert!(!r.app.view.panes.shows(Pane::Sweep));
    assert_eq!(r.app.computed.map.cells, h.app.computed.map.cells);
    assert_eq!(
        r.app.mode,
        rattleback::app::Mode::Normal,
        "replay keeps its keys"
    );
    // A file of the older format (no pane fields) still reads: the panes default to hidden.
    let old: Event =
        serde_json::from_str(r#"{"kind":"panes","effective":true,"series":false}"#).unwrap();
    assert_eq!(
        old,
        Event::Panes {
            effective: true,
            series: false,
            sweep: false,
            weak: false,
            map: false,
            body: false
        }
    );
    // And an old line with panes replays as the list form does.
    let old: Event = serde_json::from_str(
        r#"{"kind":"panes","effective":false,"series":true,"weak":true,"body":true}"#,
    )
    .unwrap();
    let mut o = Headless::of(&first);
    let effects = o.app.apply_event(&old, false);
    o.exec(effects);
    assert!(!o.app.view.overlay);
    for pane in Pane::ALL {
        assert_eq!(
            o.app.view.panes.shows(pane),
            matches!(
                pane,
                Pane::Params | Pane::Portrait | Pane::Series | Pane::Weak | Pane::Body
            ),
            "{pane:?}"
        );
    }
}

/// Issue 14, item 4: a lecturer's view of the session file.
#[test]
fn replay_chapters_lists_the_chapters_with_their_times() {
    let lesson = format!("{}/tests/fixtures/sessions/lesson.jsonl", root!());
    let (code, out, err) = bin(&["replay", &lesson, "--chapters"]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert!(
        lines[0].contains("0:01.2") && lines[0].ends_with("Start"),
        "{out}"
    );
    assert!(
        lines[1].contains("t      9.02") && lines[1].ends_with("Higher k"),
        "{out}"
    );
    // With --verify it lists, then verifies.
    let (code, out, _) = bin(&["replay", &lesson, "--chapters", "--verify"]);
    assert_eq!(code, 0);
    assert!(out.contains("Higher k") && out.contains("reproduced bit for bit"));
}

/// The weak-* pane's averaging window is part of what was shown (format 7): `>` and `<` are
/// journaled, and a replay averages over the lecturer's window, not the default one.
#[test]
fn the_weak_window_the_lecturer_chose_is_replayed() {
    use rattleback::record::replayer::Replayer;
    let mut h = Headless::new("subcritical");
    h.app
        .on_outcome(Outcome::Recording(Ok("window.jsonl".to_owned())));
    h.key(Key::Char('W'));
    for k in ['>', '>', '>', '<'] {
        h.key(Key::Char(k));
    }
    let chosen = h.app.computed.weak.window;
    assert!((chosen - 4.0).abs() < 1e-12, "window {chosen}");
    let mut wall = 0.0;
    let lines: Vec<Line> = h
        .app
        .take_journal()
        .into_iter()
        .map(|(t, generation, event)| {
            wall += 0.5;
            Line {
                wall,
                t,
                generation,
                chain: None,
                event,
            }
        })
        .collect();
    let windows: Vec<f64> = lines
        .iter()
        .filter_map(|l| match l.event {
            Event::Window { value } => Some(value),
            _ => None,
        })
        .collect();
    assert_eq!(windows, vec![2.0, 4.0, 8.0, 4.0]);
    let preset = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
    let mut replay = Headless::of(&preset);
    let mut r = Replayer::new(lines);
    let e = r.catch_up(&mut replay.app);
    replay.exec(e);
    let e = r.advance(10.0, &mut replay.app);
    replay.exec(e);
    assert!(
        (replay.app.computed.weak.window - chosen).abs() < 1e-12,
        "the replay averages over {} s, the lecturer over {chosen} s",
        replay.app.computed.weak.window
    );
}

/// A lecture that changes the method in the panel (the key stays the same: body, start,
/// tolerance, horizon) replays the method the lecturer picked, not `auto`'s plan recorded first
/// for that key: changed at `t = 0`, twice in one frame, and mid-run after a pause, then back to
/// `auto`, which replays its own plan. Every checkpoint, bit for bit.
#[test]
fn a_method_changed_in_the_panel_replays_the_method_picked() {
    use rattleback::app::fields::Field;
    use rattleback::physics::Method;
    let mut h = Headless::new("subcritical");
    assert_eq!(h.app.scenario.settings.method, Method::Auto);
    let header = crate::common::header_of(&h.app);
    h.app.on_key(Key::Char('R'));
    h.app
        .on_outcome(Outcome::Recording(Ok("methods.jsonl".to_owned())));
    let row = Field::rows(h.app.scenario.settings.model.kind())
        .iter()
        .position(|f| *f == Field::Method)
        .unwrap();
    while h.app.scenario.selected < row {
        h.key(Key::Down);
    }
    let mut methods = Vec::new();
    let checkpoint = |h: &mut Headless, methods: &mut Vec<Method>| {
        let c = vec![h.app.checkpoint()];
        h.exec(c);
        methods.push(h.app.scenario.settings.method);
    };
    // rk4, then dop853 before anything is drawn.
    h.key(Key::Right);
    h.key(Key::Right);
    checkpoint(&mut h, &mut methods);
    h.play_until(1.0, 1.0);
    h.key(Key::Char(' '));
    checkpoint(&mut h, &mut methods);
    // taylor mid-run (a restart), played on at ×16.
    h.key(Key::Right);
    h.play_until(3.0, 16.0);
    h.key(Key::Char(' '));
    checkpoint(&mut h, &mut methods);
    // Back to auto: its own recorded plan.
    for _ in 0..3 {
        h.key(Key::Left);
    }
    h.play_until(2.0, 16.0);
    h.key(Key::Char(' '));
    checkpoint(&mut h, &mut methods);
    assert_eq!(
        methods,
        [Method::Dop853, Method::Dop853, Method::Taylor, Method::Auto]
    );
    let journal = h.app.take_journal();
    let plans: Vec<Method> = journal
        .iter()
        .filter_map(|(_, _, e)| match e {
            Event::Plan { plan, .. } => Some(plan.method),
            _ => None,
        })
        .collect();
    assert!(
        plans.contains(&Method::Dop853) && plans.contains(&Method::Taylor),
        "{plans:?}"
    );
    let checkpoints = journal
        .iter()
        .filter(|(_, _, e)| matches!(e, Event::Checkpoint { .. }))
        .count();
    assert!(checkpoints >= 4, "{checkpoints}");
    let mut journal = journal;
    h.stop_recording();
    journal.extend(h.app.take_journal());
    let back = crate::common::write_session(&temp("methods.jsonl"), &header, journal, 0.5);
    let report = record::verify(&back, "methods", None)
        .unwrap_or_else(|e| panic!("a lecture that changed its method: {e}"));
    // Those taken while recording, and the last frames'.
    assert_eq!(report.checkpoints, checkpoints + 2);
    assert!(report.final_screen);
}

/// Format 11 (issue 57): a plan line names its key's model. A version-11 file whose plan line
/// lacks it is refused by `--verify`; one that names another model than its key's is refused
/// on reading, never read as that model; named rightly, the same lecture verifies. Files of
/// version 10 and older verify as before (the checked-in sessions).
#[test]
fn a_format_11_plan_line_names_its_model_and_a_wrong_name_is_refused() {
    let path = format!(
        "{}/tests/fixtures/sessions/lesson-kapitza-threshold.jsonl",
        root!()
    );
    let rec = record::read(std::path::Path::new(&path)).unwrap();
    assert_eq!(rec.header.version, 10);
    let header = record::Header {
        version: 11,
        ..rec.header.clone()
    };
    let rewrite = |name: &str, model: &dyn Fn(&rattleback::sim::PlanKey) -> Option<String>| {
        let tmp = temp(name);
        let mut out = Recorder::create(&tmp, &header, None).unwrap();
        for (_, line) in &rec.lines {
            let mut line = line.clone();
            if let Event::Plan { model: m, key, .. } = &mut line.event {
                *m = model(key);
            }
            out.write(&line).unwrap();
        }
        drop(out);
        tmp
    };
    let untagged = rewrite("v11-untagged.jsonl", &|_| None);
    match record::verify(&record::read(&untagged).unwrap(), "untagged", None) {
        Err(record::VerifyError::Diverged(d)) => {
            assert!(d.got.contains("without its model"), "{d:?}");
        }
        other => panic!("{other:?}"),
    }
    let tagged = rewrite("v11-tagged.jsonl", &|k| Some(k.model().name().to_owned()));
    let text = std::fs::read_to_string(&tagged).unwrap();
    assert!(
        text.contains(r#""model":"kapitza""#),
        "the plan lines name the pendulum"
    );
    let back = record::read(&tagged).unwrap();
    assert!(record::verify(&back, "tagged", None).is_ok());
    let wrong = rewrite("v11-wrong.jsonl", &|_| Some("rattleback".to_owned()));
    match record::read(&wrong) {
        Err(e) => assert!(e.to_string().contains("whose key is the kapitza's"), "{e}"),
        Ok(_) => panic!("a pendulum's key read under the rattleback's name"),
    }
}
