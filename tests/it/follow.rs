//! Issue 14, item 3: following a session while a recorder thread writes it: new lines arrive
//! within 0.5 s, truncation, replacement, removal and the end are noticed and said, and the
//! follower never writes.
#![allow(clippy::float_cmp)] // values copied, compared exactly

use crate::common;

use std::time::{Duration, Instant};

use common::Headless;
use rattleback::app::journal::Event;
use rattleback::record::replayer::Replayer;
use rattleback::record::tail::{Tail, TailEvent};
use rattleback::record::{FORMAT, Header, Line, Recorder, Size, ThemeRef, VERSION};

fn dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("rattleback-follow-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn header() -> Header {
    let preset = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
    Header {
        format: FORMAT.to_owned(),
        version: VERSION,
        program: "test".to_owned(),
        preset: preset.to_toml(),
        method: "auto".to_owned(),
        tolerance: 1e-9,
        terminal: Size {
            width: 80,
            height: 24,
        },
        theme: ThemeRef::Name("Default (16 colours)".to_owned()),
        fps: 30.0,
        lesson: None,
    }
}

fn line(wall: f64, event: Event) -> Line {
    Line {
        wall,
        t: 0.0,
        generation: 1,
        chain: None,
        event,
    }
}

/// Polls until `pred` holds or 3 s pass; returns the events seen.
fn poll_until(tail: &mut Tail, pred: &dyn Fn(&[TailEvent]) -> bool) -> Vec<TailEvent> {
    let mut seen = Vec::new();
    let end = Instant::now() + Duration::from_secs(3);
    while Instant::now() < end && !pred(&seen) {
        if let Some(e) = tail.poll() {
            seen.push(e);
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    seen
}

fn lines_of(events: &[TailEvent]) -> Vec<Line> {
    events
        .iter()
        .flat_map(|e| match e {
            TailEvent::Lines(l) => l.clone(),
            _ => Vec::new(),
        })
        .collect()
}

#[test]
fn lines_written_by_a_recorder_thread_arrive_within_half_a_second() {
    let d = dir("live");
    let path = d.join("lecture.jsonl");
    let mut rec = Recorder::create(&path, &header(), None).unwrap();
    rec.write(&line(0.0, Event::Play)).unwrap();
    let (mut tail, first) = Tail::open(&path).unwrap();
    assert_eq!(first.lines.len(), 1);
    let before: Vec<u8> = std::fs::read(&path).unwrap();
    let writer = std::thread::spawn(move || {
        let mut written = Vec::new();
        for i in 1..=30 {
            std::thread::sleep(Duration::from_millis(15));
            let value = f64::from(i);
            rec.write(&line(value * 0.1, Event::Speed { value }))
                .unwrap();
            written.push(Instant::now());
        }
        rec.write(&line(3.5, Event::end())).unwrap();
        written
    });
    // The follower looks every 100 ms (the explorer: every 150 ms).
    let mut arrived: Vec<(f64, Instant)> = Vec::new();
    let end = Instant::now() + Duration::from_secs(5);
    while Instant::now() < end && !arrived.iter().any(|(v, _)| v.is_nan()) {
        if let Some(TailEvent::Lines(lines)) = tail.poll() {
            for l in lines {
                let v = match l.event {
                    Event::Speed { value } => value,
                    Event::End { .. } => f64::NAN,
                    _ => continue,
                };
                arrived.push((v, Instant::now()));
            }
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let written = writer.join().unwrap();
    let speeds: Vec<f64> = arrived
        .iter()
        .map(|a| a.0)
        .filter(|v| !v.is_nan())
        .collect();
    assert_eq!(
        speeds,
        (1..=30).map(f64::from).collect::<Vec<_>>(),
        "all, in order"
    );
    for (i, w) in written.iter().enumerate() {
        let lag = arrived[i].1.duration_since(*w);
        assert!(
            // A line waits one poll (40 ms); wide for a shared machine (issue 83).
            lag < Duration::from_millis(1500),
            "line {i} arrived after {lag:?}"
        );
    }
    assert!(tail.ended(), "the end line was seen");
    // Read-only: the bytes the follower saw are untouched and nothing else is in the folder.
    let after = std::fs::read(&path).unwrap();
    assert_eq!(&after[..before.len()], &before[..]);
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_partial_line_waits_for_its_newline() {
    use std::io::Write as _;
    let d = dir("partial");
    let path = d.join("s.jsonl");
    drop(Recorder::create(&path, &header(), None).unwrap());
    let (mut tail, _) = Tail::open(&path).unwrap();
    let text = serde_json::to_string(&line(0.5, Event::Pause)).unwrap();
    let (a, b) = text.split_at(text.len() / 2);
    let mut f = std::fs::OpenOptions::new()
        .append(true)
        .open(&path)
        .unwrap();
    f.write_all(a.as_bytes()).unwrap();
    f.flush().unwrap();
    assert!(tail.poll().is_none(), "half a line is not a line");
    f.write_all(b.as_bytes()).unwrap();
    f.write_all(b"\n").unwrap();
    f.flush().unwrap();
    match tail.poll() {
        Some(TailEvent::Lines(l)) => assert_eq!(l[0].event, Event::Pause),
        other => panic!("{other:?}"),
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn truncation_replacement_and_removal_are_survived_and_said() {
    let d = dir("survive");
    let path = d.join("s.jsonl");
    let mut rec = Recorder::create(&path, &header(), None).unwrap();
    for i in 0..5 {
        rec.write(&line(f64::from(i), Event::Play)).unwrap();
    }
    drop(rec);
    let (mut tail, _) = Tail::open(&path).unwrap();

    // Truncated, then written again from the start (a new recording into the same file).
    std::fs::OpenOptions::new()
        .write(true)
        .open(&path)
        .unwrap()
        .set_len(0)
        .unwrap();
    let seen = poll_until(&mut tail, &|s| !s.is_empty());
    match seen.first() {
        Some(TailEvent::Missing(_) | TailEvent::Restarted { .. }) => {}
        other => panic!("{other:?}"),
    }
    std::fs::remove_file(&path).unwrap();
    let mut rec = Recorder::create(&path, &header(), None).unwrap();
    rec.write(&line(0.0, Event::Reset)).unwrap();
    let seen = poll_until(&mut tail, &|s| {
        s.iter().any(|e| matches!(e, TailEvent::Restarted { .. }))
    });
    let Some(TailEvent::Restarted { recording, .. }) = seen
        .iter()
        .find(|e| matches!(e, TailEvent::Restarted { .. }))
    else {
        panic!("{seen:?}")
    };
    assert_eq!(recording.lines.len(), 1, "read again from its start");
    rec.write(&line(1.0, Event::Play)).unwrap();
    let seen = poll_until(&mut tail, &|s| !lines_of(s).is_empty());
    assert_eq!(lines_of(&seen)[0].event, Event::Play, "and followed on");

    // Replaced: another file renamed over the path.
    let other = d.join("other.jsonl");
    let mut rec2 = Recorder::create(&other, &header(), None).unwrap();
    rec2.write(&line(0.0, Event::Step)).unwrap();
    std::fs::rename(&other, &path).unwrap();
    let seen = poll_until(&mut tail, &|s| !s.is_empty());
    match &seen[0] {
        TailEvent::Restarted { why, recording } => {
            assert!(why.contains("replaced"), "{why}");
            assert_eq!(recording.lines[0].1.event, Event::Step);
        }
        other => panic!("{other:?}"),
    }

    // Removed: said once, then back.
    std::fs::remove_file(&path).unwrap();
    let seen = poll_until(&mut tail, &|s| !s.is_empty());
    assert!(matches!(seen[0], TailEvent::Missing(_)), "{seen:?}");
    assert!(tail.poll().is_none(), "said once");
    let mut rec3 = Recorder::create(&path, &header(), None).unwrap();
    rec3.write(&line(0.0, Event::Play)).unwrap();
    let seen = poll_until(&mut tail, &|s| !s.is_empty());
    match &seen[0] {
        TailEvent::Restarted { why, .. } => assert!(why.contains("back"), "{why}"),
        other => panic!("{other:?}"),
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_live_replay_applies_new_lines_and_keeps_the_lecturers_clock() {
    let mut h = Headless::new("subcritical");
    let mut r = Replayer::live(vec![line(0.0, Event::Play)], 0.0);
    let effects = r.catch_up(&mut h.app);
    h.exec(effects);
    assert!(r.following() && r.running());
    // The lecturer changes k; the line arrives stamped at 2 s while the follower's clock is at
    // 0: the clock jumps to it (the follower had fallen behind) and the change applies.
    let set = Line {
        t: 0.5,
        ..line(
            2.0,
            Event::Set {
                field: "k".to_owned(),
                value: "100000.0".to_owned(),
            },
        )
    };
    let effects = r.push(vec![set], &mut h.app);
    h.exec(effects);
    assert_eq!(
        h.app.scenario.settings.rattleback().unwrap().params().k,
        1e5
    );
    assert!(h.app.replay.unwrap().at >= 2.0);
    // The end: said in the status bar's state, the clock stops.
    let effects = r.push(vec![line(2.5, Event::end())], &mut h.app);
    h.exec(effects);
    assert_eq!(h.app.replay.unwrap().live, Some(true));
    // Fork: the state stays, the replay's hold ends.
    let k = h.app.scenario.settings.rattleback().unwrap().params().k;
    h.app.fork();
    assert!(h.app.replay.is_none());
    assert_eq!(h.app.scenario.settings.rattleback().unwrap().params().k, k);
    h.key(rattleback::app::Key::Char('z'));
}

/// Whatever the writer does, the follower reads with bounded memory: a file grown by 64 MiB of
/// zeros (`truncate -s`) and a 16 MiB line with no newline are skipped a bounded chunk per look,
/// with one message, and the next good line still arrives.
#[test]
fn huge_or_endless_lines_are_skipped_at_bounded_memory() {
    use std::io::Write as _;
    let d = dir("huge");
    let path = d.join("s.jsonl");
    let mut rec = Recorder::create(&path, &header(), None).unwrap();
    rec.write(&line(0.1, Event::Play)).unwrap();
    drop(rec);
    let (mut tail, _) = Tail::open(&path).unwrap();
    let mut f = std::fs::OpenOptions::new()
        .append(true)
        .open(&path)
        .unwrap();
    // An endless line, then zeros as `truncate -s` leaves them, then a newline and a good line.
    f.write_all(&vec![b'x'; 16 << 20]).unwrap();
    f.set_len(f.metadata().unwrap().len() + (64 << 20)).unwrap();
    let mut f = std::fs::OpenOptions::new()
        .append(true)
        .open(&path)
        .unwrap();
    f.write_all(b"\n").unwrap();
    let good = serde_json::to_string(&line(9.0, Event::Pause)).unwrap();
    f.write_all(good.as_bytes()).unwrap();
    f.write_all(b"\n").unwrap();
    drop(f);
    let mut said = 0;
    let mut got = Vec::new();
    for _ in 0..100 {
        match tail.poll() {
            Some(TailEvent::Lines(l)) => got.extend(l),
            Some(TailEvent::Missing(why)) => {
                assert!(why.contains("skipped"), "{why}");
                said += 1;
            }
            Some(TailEvent::Restarted { why, .. }) => panic!("restarted: {why}"),
            None => {}
        }
        let bound = rattleback::record::tail::MAX_LINE
            + usize::try_from(rattleback::record::tail::READ_PER_POLL).unwrap();
        assert!(tail.held() <= bound, "{} bytes held", tail.held());
        if !got.is_empty() {
            break;
        }
    }
    assert_eq!(said, 1, "one message for the skipped bytes");
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].event, Event::Pause);
}

/// A follower shows the lecturer's pause at its time at once, even when its worker is already
/// past it: the replay's ceiling (the last line received) rises with the pause line, and the
/// display rises with it. It stayed at the clock line before the pause until a later line came
/// (up to 2 s in tmux: the lecturer paused at 32.73, the follower showed 32.19).
#[test]
fn a_follower_shows_a_pause_at_its_time_at_once() {
    let mut h = Headless::new("soft-spring");
    let at = |wall: f64, t: f64, event: Event| Line {
        t,
        ..line(wall, event)
    };
    let mut r = Replayer::live(vec![at(0.0, 0.0, Event::Play)], 0.0);
    let effects = r.catch_up(&mut h.app);
    h.exec(effects);
    // The lecturer's clock lines at ×16, every 50 ms; the follower's worker computes what the
    // display asks for, and a little ahead.
    for i in 1..=20 {
        let wall = 0.05 * f64::from(i);
        let effects = r.push(vec![at(wall, 0.8 * f64::from(i), Event::Clock)], &mut h.app);
        h.exec(effects);
        let effects = r.advance(0.05, &mut h.app);
        h.exec(effects);
    }
    // The worker has computed a little past the display and the last clock line (16.0).
    let reached = h.app.run.reached;
    assert!(
        h.app.run.shown <= 16.0 && reached > 16.2,
        "reached {reached}"
    );
    // The pause, at a time the worker has already reached, read after the follower's clock
    // passed its stamp (the file is polled): it applies as it arrives.
    // Nothing the worker sends is needed (a worker already past the time sends nothing).
    let effects = r.push(vec![at(0.999, 16.2, Event::Pause)], &mut h.app);
    assert!(!h.app.run.playing);
    assert!(
        (h.app.run.shown - 16.2).abs() < 1e-9,
        "as the pause is read, the follower shows {} where the lecturer paused at 16.2",
        h.app.run.shown
    );
    h.exec(effects);
    let effects = r.advance(0.05, &mut h.app);
    h.exec(effects);
    assert!(
        (h.app.run.shown - 16.2).abs() < 1e-9,
        "the follower shows {} where the lecturer paused at 16.2",
        h.app.run.shown
    );
}

/// Issue 56 (R18): a line of an impossible time (`t = -5`, `wall = 1e300`, `wall = -1e300`)
/// is not shown by `follow`, as `replay` refuses it; the next good line is.
#[test]
fn impossible_times_are_never_followed() {
    use std::io::Write as _;
    let d = dir("impossible");
    let path = d.join("s.jsonl");
    drop(Recorder::create(&path, &header(), None).unwrap());
    let (mut tail, _) = Tail::open(&path).unwrap();
    let mut f = std::fs::OpenOptions::new()
        .append(true)
        .open(&path)
        .unwrap();
    for (wall, t) in [(1e300, 0.0), (-1e300, 0.0), (1.0, -5.0), (1.0, f64::MAX)] {
        let bad = Line {
            t,
            ..line(wall, Event::Pause)
        };
        assert!(rattleback::record::impossible(&bad).is_some() || t == f64::MAX);
        writeln!(f, "{}", serde_json::to_string(&bad).unwrap()).unwrap();
    }
    writeln!(
        f,
        "{}",
        serde_json::to_string(&line(2.0, Event::Play)).unwrap()
    )
    .unwrap();
    f.flush().unwrap();
    let seen = lines_of(&poll_until(&mut tail, &|e| !lines_of(e).is_empty()));
    assert!(
        seen.iter()
            .all(|l| l.t >= 0.0 && (0.0..1e6).contains(&l.wall)),
        "{seen:?}"
    );
    assert_eq!(seen.last().map(|l| &l.event), Some(&Event::Play));
    let _ = std::fs::remove_dir_all(&d);
}
