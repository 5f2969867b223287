//! A recorded session is the lecture, frame for frame. A lecturer's explorer is driven headless
//! through a scripted key sequence (play; pause just before a reversal; three steps; a change of
//! `k` or `b`; a chapter; a note; play to the end; play again from the start and pause) at ×1,
//! ×16 and ×1024 in both scenes, and
//! recorded. The file is then fed to the replay, to a follower (line by line as it grows) and to
//! `replay --verify`: at every recorded screen, the frame above the status bar (rendered through
//! ratatui's `TestBackend` at 80×24) and the status bar's values equal the lecturer's, and the
//! follower never shows a time the lecturer has not shown. Tampered, downgraded, cut and signed
//! files are checked too.

use crate::common;

use common::Headless;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use rattleback::app::journal::{Event, Shown};
use rattleback::app::{App, Key, Outcome};
use rattleback::record::replayer::Replayer;
use rattleback::record::{self, Line, Recorder};
use rattleback::ui::{self, Cache, UiOptions};

const FRAME: f64 = 1.0 / 30.0;
/// The replay's frames are finer than the lecturer's, so each recorded line is shown alone.
const REPLAY_FRAME: f64 = 0.0005;

pub(crate) fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rattleback-lecture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A preset given by its path names its files after the path.
    let p = dir.join(name.replace(std::path::MAIN_SEPARATOR, "_"));
    let _ = std::fs::remove_file(&p);
    p
}

/// The screen at 80×24 above the status bar (the status bar and the key footer say "replay" or
/// "following" in a replay; their numbers are compared through [`Shown`]); messages are left out
/// (the lecturer's "recording to …" is not the student's).
fn frame(app: &mut App) -> String {
    let status = app.status.take();
    let mut terminal = Terminal::new(TestBackend::new(80, 24)).unwrap();
    terminal
        .draw(|f| ui::draw(f, app, &UiOptions::default(), &mut Cache::default()))
        .unwrap();
    app.status = status;
    let b = terminal.backend().buffer();
    let mut out = String::new();
    for y in 0..22 {
        for x in 0..80 {
            out.push_str(b[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

/// What the lecturer recorded: the lines, and at each `screen` line the frame drawn then.
pub(crate) struct Lecture {
    pub(crate) header: record::Header,
    pub(crate) lines: Vec<Line>,
    pub(crate) frames: Vec<(usize, String, Shown)>,
}

pub(crate) struct Lecturer {
    pub(crate) h: Headless,
    pub(crate) wall: f64,
    pub(crate) lines: Vec<Line>,
    pub(crate) frames: Vec<(usize, String, Shown)>,
}

impl Lecturer {
    /// Stopped as `R` stops it: the last frame once settled, its checkpoint, then the end.
    pub(crate) fn stop(&mut self) {
        self.key(Key::Char('R'));
        while self.h.app.journal.state == rattleback::app::RecState::On {
            self.tick();
        }
        assert!(
            matches!(
                self.lines.last().map(|x| &x.event),
                Some(Event::Checkpoint { .. })
            ),
            "the stop ends with the last frame's checkpoint"
        );
    }

    pub(crate) fn collect(&mut self) {
        for (t, generation, event) in self.h.app.take_journal() {
            if let Event::Screen(shown) = &event {
                if std::env::var_os("DEBUG_FRAMES").is_some() {
                    eprintln!(
                        "lecturer screen at line {} wall {}: trail {} shown {} last {:?}",
                        self.lines.len(),
                        self.wall,
                        self.h.app.run.trail_shown().len(),
                        self.h.app.run.shown,
                        self.h.app.run.trail_shown().last().map(|p| p.t)
                    );
                }
                let f = frame(&mut self.h.app);
                assert!(
                    shown.difference(&self.h.app.shown()).is_none(),
                    "a screen line that is not the screen"
                );
                self.frames.push((self.lines.len(), f, shown.clone()));
            }
            self.lines.push(Line {
                wall: self.wall,
                t,
                generation,
                chain: None,
                event,
            });
        }
    }
    pub(crate) fn tick(&mut self) {
        self.wall += FRAME;
        self.h.tick(FRAME);
        self.collect();
    }
    pub(crate) fn key(&mut self, key: Key) {
        // A key comes after the frame before it (the recorder stamps it later).
        self.wall += 0.01;
        self.h.key(key);
        self.collect();
    }
    pub(crate) fn text(&mut self, key: char, text: &str) {
        self.key(Key::Char(key));
        for c in text.chars() {
            self.key(Key::Char(c));
        }
        self.key(Key::Enter);
    }
}

/// The time of the first reversal (or swing) of `preset`'s run.
fn first_event(preset: &str) -> f64 {
    let mut h = Headless::new(preset);
    h.play_until(f64::INFINITY, 1024.0);
    h.app
        .run
        .reversals
        .kept()
        .first()
        .copied()
        .unwrap_or(0.5 * h.app.run.t_end)
}

pub(crate) fn lecture(preset: &str, speed: f64, field: &str) -> Lecture {
    lecture_with(preset, speed, field, false)
}

/// [`lecture`], with the compare pane opened (`C`, the scene's counterpart beside the run) as
/// the recording starts.
fn lecture_with(preset: &str, speed: f64, field: &str, compare: bool) -> Lecture {
    let before = first_event(preset);
    let mut l = Lecturer {
        h: Headless::new(preset),
        wall: 0.0,
        lines: Vec::new(),
        frames: Vec::new(),
    };
    let header = rattleback::record::active::header(&l.h.app, (80, 24), 30.0);
    let effects =
        l.h.app
            .on_outcome(Outcome::Recording(Ok("lecture.jsonl".into())));
    l.h.exec(effects);
    l.collect();
    if compare {
        l.key(Key::Char('C'));
        assert!(
            l.h.app.computed.compare.outcome.is_some(),
            "the partner ran"
        );
    }
    while l.h.app.run.speed < speed {
        l.key(Key::Char('+'));
    }
    l.key(Key::Char(' '));
    // Pause just before the first event: the frame after would pass it.
    while l.h.app.run.shown + speed * FRAME < before && !l.h.app.run.done() {
        l.tick();
    }
    l.key(Key::Char(' '));
    l.tick();
    for _ in 0..3 {
        l.key(Key::Char('.'));
        l.tick();
    }
    // Select the field (recorded) and change it.
    while l.h.app.field().label() != field {
        l.key(Key::Down);
    }
    l.key(Key::Char('+'));
    l.tick();
    l.text('m', "after the change");
    l.tick();
    l.text('n', "watch the next reversal");
    l.tick();
    l.key(Key::Char(' '));
    let mut frames = 0;
    while !l.h.app.run.done() {
        l.tick();
        frames += 1;
        assert!(frames < 200_000, "never reached the end");
    }
    l.tick();
    // The end, when the screen showed it: a clock line at `t_end` (no clock line follows, and a
    // follower showed the last one until the next checkpoint, up to 2 s later).
    let t_end = l.h.app.run.t_end;
    let last_clock = l.lines.iter().rev().find(|x| x.event == Event::Clock);
    assert_eq!(
        last_clock.map(|x| x.t.to_bits()),
        Some(t_end.to_bits()),
        "{preset} ×{speed}: the last clock line is at {:?}, not the end {t_end}",
        last_clock.map(|x| x.t)
    );
    // Play again from the end (the run starts over), then pause a few frames in: a replay
    // must start over too.
    l.key(Key::Char(' '));
    // A few frames in, fewer at a speed that would reach the end again.
    for _ in 0..(5.0 / speed).floor() as usize {
        l.tick();
    }
    l.key(Key::Char(' '));
    l.tick();
    assert!(
        l.h.app.run.shown < l.h.app.run.t_end,
        "{preset} ×{speed}: playing again did not start over"
    );
    l.stop();
    // With the comparison, every screen recorded the partner as the pane showed it.
    let with_partner =
        |(_, f, s): &(usize, String, Shown)| s.compare.is_some() && f.contains("compare: spin(t)");
    assert!(
        !compare || l.frames.iter().all(with_partner),
        "{preset} ×{speed}: a screen without the partner"
    );
    Lecture {
        header,
        lines: l.lines,
        frames: l.frames,
    }
}

/// Plays `lines` through a replayer (`live`: pushed as they were written, as `follow` reads
/// them); at every screen line applied, compares the frame with the lecturer's.
pub(crate) fn replay_and_compare(preset: &str, lecture: &Lecture, live: bool) -> usize {
    let _ = preset;
    // The replay starts from the header, as `replay` and `follow` do (its preset, its lesson).
    let preset =
        rattleback::scenario::Preset::parse(&lecture.header.preset, "header", "recorded", &[])
            .unwrap();
    let mut h = Headless::of(&preset);
    if let Some(lesson) = lecture
        .header
        .lesson
        .as_ref()
        .and_then(rattleback::scenario::lesson::RecordedLesson::lesson)
    {
        h.app.replay_lesson(lesson);
    }
    let mut r = if live {
        Replayer::live(Vec::new(), 0.0)
    } else {
        Replayer::new(lecture.lines.clone())
    };
    let effects = r.catch_up(&mut h.app);
    h.exec(effects);
    let screens: std::collections::HashMap<usize, (&String, &Shown)> = lecture
        .frames
        .iter()
        .map(|(i, f, s)| (*i, (f, s)))
        .collect();
    let (mut wall, mut pushed, mut compared, mut done) = (0.0, 0, 0, 0);
    let mut guard = 0;
    while done < lecture.lines.len() {
        wall += REPLAY_FRAME;
        if live {
            let upto = lecture.lines.partition_point(|l| l.wall <= wall + 1e-9);
            let new = lecture.lines[pushed..upto].to_vec();
            pushed = upto;
            let e = r.push(new, &mut h.app);
            h.exec(e);
        }
        let e = r.advance(REPLAY_FRAME, &mut h.app);
        h.exec(e);
        let now = r.position();
        for i in done..now {
            if let Some((f, s)) = screens.get(&i) {
                let got = h.app.shown();
                if s.difference(&got).is_some() {
                    for (j, l) in lecture
                        .lines
                        .iter()
                        .enumerate()
                        .take(i + 2)
                        .skip(i.saturating_sub(12))
                    {
                        eprintln!(
                            "{j}: wall {:.4} t {} g {} {:?}",
                            l.wall, l.t, l.generation, l.event
                        );
                    }
                    eprintln!(
                        "replay shown {} goal {} ceiling {:?}",
                        h.app.run.shown, h.app.run.goal, h.app.run.ceiling
                    );
                }
                assert!(
                    s.difference(&got).is_none(),
                    "line {i}: {:?}",
                    s.difference(&got)
                );
                let mine = frame(&mut h.app);
                assert_eq!(
                    &mine,
                    *f,
                    "line {}: the frame differs from the lecturer's",
                    i + 2
                );
                compared += 1;
            }
        }
        if live && pushed > 0 && r.position() == pushed {
            // Never a time the lecturer has not shown: at most the last line's.
            let last = &lecture.lines[pushed - 1];
            assert!(
                h.app.run.shown <= last.t + 1e-12,
                "the follower shows t = {} past the lecturer's {}",
                h.app.run.shown,
                last.t
            );
        }
        done = now;
        guard += 1;
        assert!(guard < 20_000_000, "the replay never ended");
    }
    compared
}

/// Frames per second of the cast checked against the lecturer: fine enough that each recorded
/// line (ticks 1/30 s apart, keys 10 ms after them) lands in a frame of its own.
pub(crate) const CAST_FPS: f64 = 240.0;

/// Plays the cast's output through a terminal emulator (`vt100`) and, at each screen line's
/// frame, compares the screen above the status bar with the lecturer's frame; returns how many.
pub(crate) fn cast_screens(cast: &str, lecture: &Lecture) -> usize {
    let events: Vec<(f64, String)> = cast
        .lines()
        .skip(1)
        .filter_map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).ok()?;
            (v[1] == "o").then(|| (v[0].as_f64().unwrap(), v[2].as_str().unwrap().to_owned()))
        })
        .collect();
    let n = |x: u16| std::num::NonZeroU16::new(x).unwrap();
    let mut parser = vt100::Parser::new(n(24), n(80), 0);
    let mut next = 0;
    let mut compared = 0;
    for (i, f, _) in &lecture.frames {
        // The first frame at or after the line: the line is applied there.
        // (The cast's times are rounded to microseconds.)
        let at = (lecture.lines[*i].wall * CAST_FPS).ceil() / CAST_FPS + 1e-6;
        while next < events.len() && events[next].0 <= at {
            parser.process(events[next].1.as_bytes());
            next += 1;
        }
        let mine = vt_rows(&parser);
        // The cast shows the lecturer's messages: compare the rows above any message line.
        let strip = |s: &str| s.lines().take(18).collect::<Vec<_>>().join("\n");
        assert_eq!(strip(&mine), strip(f), "line {}: the cast's frame", i + 2);
        compared += 1;
    }
    compared
}

/// The 80x24 terminal's first 22 rows, as `lecture.frames` holds them.
fn vt_rows(parser: &vt100::Parser) -> String {
    let screen = parser.screen();
    let mut rows = String::new();
    for row in 0..22 {
        for col in 0..80 {
            let c = screen
                .cell(row, col)
                .map(|c| c.contents().to_owned())
                .unwrap_or_default();
            rows.push_str(if c.is_empty() { " " } else { &c });
        }
        rows.push('\n');
    }
    rows
}

/// The screen a cast shows at its end.
pub(crate) fn cast_last_screen(cast: &str) -> String {
    let n = |x: u16| std::num::NonZeroU16::new(x).unwrap();
    let mut parser = vt100::Parser::new(n(24), n(80), 0);
    for l in cast.lines().skip(1) {
        let v: serde_json::Value = serde_json::from_str(l).unwrap();
        if v[1] == "o" {
            parser.process(v[2].as_str().unwrap().as_bytes());
        }
    }
    vt_rows(&parser)
}

pub(crate) fn write(
    lecture: &Lecture,
    name: &str,
    signer: Option<record::sign::Signer>,
) -> std::path::PathBuf {
    let path = temp(name);
    let mut rec = Recorder::create(&path, &lecture.header, signer).unwrap();
    for l in &lecture.lines {
        rec.write(l).unwrap();
    }
    rec.write(&Line {
        wall: lecture.lines.last().map_or(0.0, |l| l.wall),
        t: lecture.lines.last().map_or(0.0, |l| l.t),
        // As the explorer's recorder writes it: the last line's run stamp.
        generation: lecture.lines.last().map_or(0, |l| l.generation),
        chain: None,
        event: Event::end(),
    })
    .unwrap();
    path
}

/// Files written before the fix journaled the play that started the run over from its end as a
/// play alone (in the new run): without the reset, the lecture verifies too.
fn older_file_verifies(lecture: &Lecture, what: &str) {
    let mut older = Lecture {
        header: lecture.header.clone(),
        lines: lecture.lines.clone(),
        frames: Vec::new(),
    };
    let again = older
        .lines
        .windows(2)
        .rposition(|w| w[0].event == Event::Reset && w[1].event == Event::Play)
        .expect("a reset before the play again");
    older.lines.remove(again);
    let path = write(
        &older,
        &format!("{}-older.jsonl", what.replace(' ', "-")),
        None,
    );
    let rec = record::read(&path).unwrap();
    record::verify(&rec, "older", None).unwrap_or_else(|e| panic!("{what}: an older file: {e:?}"));
}

fn check(preset: &str, field: &str) {
    check_with(preset, field, false);
}

fn check_with(preset: &str, field: &str, compare: bool) {
    for speed in [1.0, 16.0, 1024.0] {
        let lecture = lecture_with(preset, speed, field, compare);
        let screens = lecture.frames.len();
        assert!(
            screens >= 7,
            "{preset} ×{speed}: only {screens} screens recorded"
        );
        let pauses = lecture
            .lines
            .iter()
            .filter(|l| l.event == Event::Pause)
            .count();
        assert!(pauses >= 1);
        assert_eq!(
            replay_and_compare(preset, &lecture, false),
            screens,
            "{preset} ×{speed}: replay"
        );
        assert_eq!(
            replay_and_compare(preset, &lecture, true),
            screens,
            "{preset} ×{speed}: follow"
        );
        let path = write(&lecture, &format!("{preset}-{speed}.jsonl"), None);
        let rec = record::read(&path).unwrap();
        // `]` lands on the chapter at the time it was marked.
        let base = rattleback::scenario::shipped::resolve(preset, &[]).unwrap();
        let mut h = Headless::of(&base);
        let mut r = Replayer::new(lecture.lines.clone());
        let e = r.catch_up(&mut h.app);
        h.exec(e);
        let rebuild = |old: &App| App::new_after(&base, rattleback::app::Options::at(30.0), old);
        let e = r.key(Key::Char(']'), &mut h.app, &rebuild);
        h.exec(e);
        let chapter_t = lecture
            .lines
            .iter()
            .find(|l| matches!(l.event, Event::Chapter { .. }))
            .unwrap()
            .t;
        assert_eq!(
            h.app.run.shown.to_bits(),
            chapter_t.to_bits(),
            "{preset} ×{speed}: ]"
        );
        // The cast export goes through the same replay: it writes the chapter and the note as
        // markers at the lecturer's wall times.
        let cast = temp(&format!("{preset}-{speed}.cast"));
        let frames = rattleback::cast::export_cast(
            &rec,
            "lecture",
            &cast,
            &UiOptions::default(),
            rattleback::cast::CastSize {
                fps: CAST_FPS,
                ..rattleback::cast::CastSize::default()
            },
            true,
            &mut |_| {},
        )
        .unwrap();
        assert!(frames > 10, "{preset} ×{speed}: {frames} frames");
        let text = std::fs::read_to_string(&cast).unwrap();
        assert_eq!(
            cast_screens(&text, &lecture),
            screens,
            "{preset} ×{speed}: cast"
        );
        let chapter = lecture
            .lines
            .iter()
            .find(|l| matches!(l.event, Event::Chapter { .. }))
            .unwrap();
        assert!(
            text.contains(&format!(
                "[{},\"m\",\"after the change\"]",
                (chapter.wall * 1e6).round() / 1e6
            )),
            "{preset} ×{speed}: the chapter's marker"
        );
        let report = record::verify(&rec, "lecture", None).unwrap();
        assert_eq!(report.screens, screens);
        older_file_verifies(&lecture, &format!("{preset} ×{speed}"));
        assert!(
            report.checkpoints >= screens,
            "a checkpoint with every screen"
        );
        // Checkpoints are at displayed times: each has a screen line at the same t.
        for l in &lecture.lines {
            if matches!(l.event, Event::Checkpoint { .. }) {
                assert!(
                    lecture
                        .lines
                        .iter()
                        .any(|s| matches!(s.event, Event::Screen(_))
                            && s.t.to_bits() == l.t.to_bits()),
                    "{preset} ×{speed}: a checkpoint at t = {} that no screen showed",
                    l.t
                );
            }
        }
    }
}

#[test]
fn a_rattleback_lecture_replays_and_follows_frame_for_frame() {
    check("subcritical", "k");
}

/// Issue 27: a run longer than the first segment is verified and shown in segments (each
/// segment's plan recorded); its lecture replays, follows and casts frame for frame too.
#[test]
fn a_lecture_verified_in_segments_replays_and_follows_frame_for_frame() {
    let src =
        include_str!("../../presets/subcritical.toml").replace("t_end = 30.0", "t_end = 100.0");
    assert!(src.contains("t_end = 100.0"));
    let path =
        std::env::temp_dir().join(format!("rattleback-segmented-{}.toml", std::process::id()));
    std::fs::write(&path, src).unwrap();
    let preset = path.to_str().unwrap();
    check(preset, "k");
    // Each run of the lecture recorded the plans of both its segments.
    let lecture = lecture(preset, 1024.0, "k");
    let horizons: Vec<f64> = lecture
        .lines
        .iter()
        .filter_map(|l| match &l.event {
            Event::Plan {
                key:
                    rattleback::sim::PlanKey::Rattleback(
                        rattleback::physics::rattleback::scene::PlanKey { t_end, .. },
                    ),
                ..
            } => Some(*t_end),
            _ => None,
        })
        .collect();
    assert!(
        horizons.contains(&50.0) && horizons.contains(&100.0),
        "{horizons:?}"
    );
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_pendulum_lecture_replays_and_follows_frame_for_frame() {
    check("kapitza-upright", "b");
}

/// Issue 26: the comparison is recorded and replayed like any other pane: the holonomic
/// rattleback beside the celt, and the celt beside the holonomic rattleback (its spin changed).
#[test]
fn a_comparison_lecture_replays_and_follows_frame_for_frame() {
    check_with("subcritical", "k", true);
    check_with("celt-clockwise", "omega_z", true);
}

/// Issue 55: a student's fork is a live explorer at the lecturer's state: after `f` in a
/// follower paused just before a reversal, `.` steps three times and space plays on, from the
/// fork's time, in all three scenes (it was frozen until a restart).
#[test]
fn a_fork_explores_on_its_own_from_the_lecturers_time() {
    for (preset, field) in [
        ("subcritical", "k"),
        ("kapitza-upright", "b"),
        ("celt-clockwise", "omega_z"),
    ] {
        let lecture = lecture(preset, 8.0, field);
        // Followed up to the first pause (and its screen), as it was written.
        let upto = lecture
            .lines
            .iter()
            .position(|l| l.event == Event::Pause)
            .unwrap()
            + 2;
        let start =
            rattleback::scenario::Preset::parse(&lecture.header.preset, "h", "r", &[]).unwrap();
        let mut h = Headless::of(&start);
        let mut r = Replayer::live(Vec::new(), 0.0);
        let e = r.push(lecture.lines[..upto].to_vec(), &mut h.app);
        h.exec(e);
        for _ in 0..200 {
            let e = r.advance(REPLAY_FRAME * 20.0, &mut h.app);
            h.exec(e);
        }
        let paused_at = h.app.run.shown;
        assert!(paused_at > 0.0, "{preset}: followed to the pause");
        // `f`: what the explorer's loop does.
        h.app.fork();
        h.exec(vec![rattleback::app::Effect::Sim(
            rattleback::sim::Command::Release,
        )]);
        let mut t = paused_at;
        for i in 0..3 {
            h.key(Key::Char('.'));
            assert!(
                h.app.run.shown > t,
                "{preset}: `.` {} did not step from t = {t}",
                i + 1
            );
            t = h.app.run.shown;
        }
        h.key(Key::Char(' '));
        assert!(h.app.run.playing, "{preset}: space plays");
        for _ in 0..10 {
            h.tick(FRAME);
        }
        assert!(h.app.run.shown > t, "{preset}: playing moves the clock on");
    }
}

/// Issue 55: a later segment verified while the recording closes (between its last frame and
/// the checkpoint) wrote its plan line after the last frame, and `--verify` then said the file
/// had no last frame (a flaky test of a lecture verified in segments). What comes after the last
/// frame is not part of the lecture: only the checkpoint follows it.
#[test]
fn a_segment_verified_while_the_recording_closes_comes_after_nothing() {
    let mut l = Lecturer {
        h: Headless::new("subcritical"),
        wall: 0.0,
        lines: Vec::new(),
        frames: Vec::new(),
    };
    let effects =
        l.h.app
            .on_outcome(Outcome::Recording(Ok("lecture.jsonl".into())));
    l.h.exec(effects);
    l.collect();
    l.key(Key::Char(' '));
    l.tick();
    l.key(Key::Char('R'));
    while l.h.app.journal.state == rattleback::app::RecState::On {
        l.tick();
    }
    assert!(
        matches!(
            l.lines
                .iter()
                .rev()
                .find(|x| !matches!(x.event, Event::Checkpoint { .. }))
                .map(|x| &x.event),
            Some(Event::Screen(_))
        ),
        "the last frame is written"
    );
    // A segment verified now, as the verification ahead may report at any moment.
    let generation = l.h.app.run.generation;
    let rattleback::app::PlanState::Running { plan, .. } = l.h.app.run.plan else {
        panic!("the run is planned");
    };
    l.h.app.on_sim(rattleback::sim::SimEvent::Verified {
        generation,
        from: 30.0,
        until: 60.0,
        plan,
        error_estimate: Some(1e-9),
    });
    l.collect();
    l.tick();
    let after: Vec<&Event> = l
        .lines
        .iter()
        .rev()
        .take_while(|x| !matches!(x.event, Event::Screen(_)))
        .map(|x| &x.event)
        .collect();
    assert!(
        after.iter().all(|e| matches!(e, Event::Checkpoint { .. })),
        "after the last frame: {after:?}"
    );
}

/// shared/docs/reviews/newcomer.md D-1 (issue 80): a recording begun in a terminal too small
/// for the explorer and then enlarged holds the resize (format 14), and its cast draws each
/// moment at the size the lecturer saw: the refusal first, then the explorer, on a screen as
/// large as the largest the lecturer had.
#[test]
fn a_recording_begun_small_exports_each_moment_at_the_lecturers_size() {
    let mut l = Lecturer {
        h: Headless::new("subcritical"),
        wall: 0.0,
        lines: Vec::new(),
        frames: Vec::new(),
    };
    let header = rattleback::record::active::header(&l.h.app, (80, 20), 30.0);
    let effects =
        l.h.app
            .on_outcome(Outcome::Recording(Ok("small.jsonl".into())));
    l.h.exec(effects);
    l.collect();
    l.tick();
    l.h.app.on_resize(80, 24);
    l.tick();
    l.key(Key::Char(' '));
    for _ in 0..30 {
        l.tick();
    }
    l.key(Key::Char(' '));
    l.tick();
    l.stop();
    let lecture = Lecture {
        header,
        lines: l.lines,
        frames: l.frames,
    };
    let path = write(&lecture, "small.jsonl", None);
    let rec = record::read(&path).unwrap();
    record::verify(&rec, "small", None).unwrap();
    let (cast, frames) = rattleback::cast::cast_text(
        &rec,
        "small",
        &UiOptions::default(),
        rattleback::cast::CastSize::default(),
        &mut |_| {},
    )
    .unwrap();
    assert!(frames > 5, "{frames} frames");
    let header: serde_json::Value = serde_json::from_str(cast.lines().next().unwrap()).unwrap();
    assert_eq!(
        (header["width"].as_u64(), header["height"].as_u64()),
        (Some(80), Some(24))
    );
    let first = cast.lines().nth(1).unwrap();
    assert!(first.contains("too") && first.contains("small"), "{first}");
    let last = cast_last_screen(&cast);
    assert!(
        last.contains("phase portrait") && !last.contains("too small"),
        "{last}"
    );
    // A file of format 13 cannot hold a terminal line.
    let mut older = std::fs::read_to_string(&path).unwrap();
    older = older.replacen("\"version\":15", "\"version\":13", 1);
    let older_path = temp("small-13.jsonl");
    std::fs::write(&older_path, older).unwrap();
    let (code, _, err) = crate::common::bin(&["replay", older_path.to_str().unwrap(), "--verify"]);
    assert_ne!(code, 0);
    assert!(
        err.contains("format 14") || err.contains("edited") || err.contains("chain"),
        "{err}"
    );
}
