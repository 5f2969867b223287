//! Issue 26, item 6: the comparison. The holonomic rattleback and the celt on one time axis in
//! the compare pane (`C`, `rattleback compare A B`), each with its own status line: what it
//! shows ends where `simulate` of the partner over the run's window ends, at ×1 and ×1024; the
//! pane's snapshots at 80×24 and 160×48 with the colours of its lanes; a recorded screen waits
//! for the partner; the partner is run again only when its window changes; bad input to
//! `compare` is refused with the name; a downgraded header cannot carry a layout line.
#![allow(clippy::float_cmp)] // counts and stamps compared exactly

use crate::common::{Headless, bin, simulate_json};
use crate::explorer_ui::{find, render, screen_text};
use rattleback::app::panes::Pane;
use rattleback::app::{Effect, Key};
use rattleback::scenario::shipped::{SHIPPED, resolve};
use rattleback::sim::{Command, JobKind};

/// `main` with `partner` in the compare pane (as `rattleback compare main partner` opens it).
fn comparing(main: &str, partner: &str) -> Headless {
    let mut h = Headless::new(main);
    let effects = h.app.set_partner(&resolve(partner, &[]).unwrap());
    h.exec(effects);
    assert!(h.app.view.panes.shows(Pane::Compare));
    h
}

/// What `simulate` says of `partner` over `window`: reversals, and crossings when it has them.
fn simulated(partner: &str, window: f64) -> (usize, Option<usize>) {
    let set = format!("run.t_end={window}");
    let json = simulate_json(&["--preset", partner, "--set", &set]);
    let count = |v: &serde_json::Value| v["count"].as_u64().map(|n| n as usize);
    // The celt's report holds its events together; the rattleback's has `reversals` on top.
    let reversals = count(&json["events"]["reversals"]).or_else(|| count(&json["reversals"]));
    (
        reversals.expect("a reversal count"),
        count(&json["events"]["crossings"]),
    )
}

#[test]
fn the_partner_ends_where_simulate_ends_at_x1_and_x1024() {
    let celts: Vec<&str> = SHIPPED
        .iter()
        .map(|(n, _)| *n)
        .filter(|n| n.starts_with("celt-"))
        .collect();
    assert!(celts.len() >= 5);
    // Every shipped celt beside the holonomic rattleback (window 30), at top speed; the pair
    // the lesson uses at ×1 too; and the holonomic rattleback beside the celt (window 10).
    let mut pairs: Vec<(&str, &str, f64)> =
        celts.iter().map(|c| ("subcritical", *c, 1024.0)).collect();
    pairs.push(("subcritical", "celt-clockwise", 1.0));
    pairs.push(("celt-clockwise", "subcritical", 1024.0));
    pairs.push(("celt-clockwise", "subcritical", 1.0));
    for (main, partner, speed) in pairs {
        let mut h = comparing(main, partner);
        h.play_until(f64::INFINITY, speed);
        let window = h.app.run.t_end;
        let shown = h
            .app
            .computed
            .compare
            .shown(h.app.run.shown)
            .expect("the partner ran");
        let (reversals, crossings) = simulated(partner, window);
        assert_eq!(
            (shown.events, shown.crossings),
            (reversals, crossings),
            "{main} beside {partner} at ×{speed}"
        );
        // The run's own lane says what the status bar says.
        let screen = screen_text(&h.app, 160, 48);
        let a = format!("reversals {}", h.app.run.reversals_shown());
        let lane_a = screen
            .lines()
            .find(|l| l.contains("│A "))
            .unwrap_or_default();
        assert!(lane_a.contains(&a), "{main}: {lane_a}");
        let lane_b = screen
            .lines()
            .find(|l| l.contains("│B "))
            .unwrap_or_default();
        assert!(
            lane_b.contains(&format!("reversals {reversals}")),
            "{partner}: {lane_b}"
        );
        if let Some(c) = crossings {
            assert!(lane_b.contains(&format!("crossings {c}")), "{lane_b}");
        }
    }
}

/// Mid-run, between the holonomic body's first reversal (t ≈ 2.22) and the celt's (≈ 3.02):
/// A has reversed, B has not; later both have. The lanes are cut at the displayed time.
#[test]
fn each_lane_counts_up_to_the_displayed_time() {
    let mut h = comparing("subcritical", "celt-clockwise");
    h.play_until(2.6, 1.0);
    h.key(Key::Char(' '));
    let shown = h.app.computed.compare.shown(h.app.run.shown).unwrap();
    assert_eq!(h.app.run.reversals_shown(), 1);
    assert_eq!(shown.events, 0, "the celt reverses near 3.02");
    assert!(shown.spin.unwrap() < 0.0, "still clockwise");
    h.play_until(3.5, 1.0);
    let shown = h.app.computed.compare.shown(h.app.run.shown).unwrap();
    assert_eq!(shown.events, 1);
    assert_eq!(shown.crossings, Some(3));
}

#[test]
fn the_compare_pane_at_80x24_and_160x48() {
    let mut h = comparing("subcritical", "celt-clockwise");
    h.play_until(5.0, 4.0);
    h.key(Key::Char(' '));
    let small = render(&h.app, 80, 24);
    let text = screen_text(&h.app, 80, 24);
    assert!(text.contains("compare: spin(t)"), "{text}");
    assert!(
        !text.contains("phase portrait"),
        "on a short terminal the comparison takes the portrait's place"
    );
    insta::assert_snapshot!("compare_80x24", text);
    let big = render(&h.app, 160, 48);
    insta::assert_snapshot!("compare_160x48", screen_text(&h.app, 160, 48));
    let theme = rattleback::ui::Theme::default();
    for buffer in [&small, &big] {
        let (x, y) = find(buffer, "A ").unwrap();
        assert_eq!(
            buffer[(x, y)].fg,
            theme.trail,
            "A is drawn as the run's trail"
        );
        let (x, y) = find(buffer, "B ").unwrap();
        assert_eq!(buffer[(x, y)].fg, theme.effective, "B has its own colour");
    }
    // `C` hides it; the portrait comes back.
    h.key(Key::Char('C'));
    assert!(screen_text(&h.app, 80, 24).contains("phase portrait"));
}

/// What a recording holds is what was shown: a pause while the partner is still computed is
/// journaled once it has arrived, with the partner's values.
#[test]
fn a_recorded_screen_waits_for_the_partner() {
    use rattleback::app::Outcome;
    use rattleback::app::journal::Event;
    let mut h = Headless::new("subcritical");
    let e = h
        .app
        .on_outcome(Outcome::Recording(Ok("waits.jsonl".to_owned())));
    h.exec(e);
    // `C`: the partner's command is held back (the worker has not answered yet).
    let effects = h.app.on_key(Key::Char('C'));
    let (compare, rest): (Vec<Effect>, Vec<Effect>) = effects.into_iter().partition(|e| {
        matches!(
            e,
            Effect::Sim(Command::Job {
                kind: JobKind::Partner,
                ..
            })
        )
    });
    assert_eq!(compare.len(), 1);
    h.exec(rest);
    h.key(Key::Char(' '));
    h.tick(1.0);
    h.key(Key::Char(' '));
    h.tick(0.04);
    h.tick(0.04);
    let screens = |j: &[(f64, u64, Event)]| {
        j.iter()
            .filter_map(|(_, _, e)| match e {
                Event::Screen(s) => Some(s.clone()),
                _ => None,
            })
            .collect::<Vec<_>>()
    };
    let early = h.app.take_journal();
    assert!(
        screens(&early).is_empty(),
        "no screen while the partner is computed"
    );
    assert!(
        screen_text(&h.app, 80, 24).contains("computing the partner"),
        "the pane says so"
    );
    h.exec(compare);
    h.tick(0.04);
    let late = h.app.take_journal();
    let s = screens(&late);
    assert_eq!(s.len(), 1, "{late:?}");
    let c = s[0]
        .compare
        .as_ref()
        .expect("the partner on the screen line");
    assert_eq!(c.partner, "Celt: clockwise, reverses");
    assert_eq!(c.events, 0);
    assert!(
        late.iter()
            .any(|(_, _, e)| matches!(e, Event::Plan { key, .. } if matches!(key, rattleback::sim::PlanKey::Celt(_)))),
        "the partner's plan is journaled for the replay"
    );
}

/// The partner runs over the run's window: a change of the run's `t_end` runs it again, any
/// other change keeps its run; a new partner replaces it.
#[test]
fn the_partner_runs_again_only_when_its_window_changes() {
    let mut h = comparing("subcritical", "celt-clockwise");
    let asked = |h: &Headless| h.app.computed.compare.asked().map(|s| s.t_end);
    assert_eq!(asked(&h), Some(30.0));
    let keep = |effects: &[Effect]| {
        effects
            .iter()
            .filter(|e| {
                matches!(
                    e,
                    Effect::Sim(Command::Job {
                        kind: JobKind::Partner,
                        ..
                    })
                )
            })
            .count()
    };
    // k: the panel's fourth row, one step up.
    for _ in 0..3 {
        h.key(Key::Down);
    }
    let effects = h.app.on_key(Key::Right);
    assert_eq!(keep(&effects), 0, "k does not change the partner's run");
    h.exec(effects);
    assert!(h.app.computed.compare.outcome.is_some());
    // t_end.
    while h.app.field().label() != "t_end" {
        h.key(Key::Down);
    }
    let effects = h.app.on_key(Key::Left);
    assert_eq!(keep(&effects), 1);
    h.exec(effects);
    assert!(asked(&h).unwrap() < 30.0);
    assert!(h.app.computed.compare.outcome.is_some());
    let effects = h.app.set_partner(&resolve("celt-stubby", &[]).unwrap());
    assert_eq!(keep(&effects), 2, "the old run stops, the new one starts");
    h.exec(effects);
    assert_eq!(
        h.app.computed.compare.shown(0.0).unwrap().partner,
        h.app
            .computed
            .compare
            .partner
            .as_ref()
            .unwrap()
            .scenario
            .name
    );
}

#[test]
fn compare_refuses_an_unknown_preset_by_name() {
    let (code, _, err) = bin(&["compare", "subcritical", "celt-clockwize"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("celt-clockwize") && err.contains("celt-clockwise"),
        "{err}"
    );
    let (code, _, err) = bin(&["compare", "subcritical"]);
    assert_eq!(code, 2, "{err}");
    // Headless (no terminal): refused in one line, after the presets are checked.
    let (code, out, err) = bin(&["compare", "subcritical", "celt-clockwise"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("standard output is not one"), "{err}");
    assert!(out.is_empty(), "no escape code into a pipe: {out:?}");
}

/// A file whose header says version 4 cannot carry a format-5 line (a downgraded header).
#[test]
fn a_layout_line_needs_format_5() {
    use rattleback::app::journal::Event;
    use rattleback::record::{self, Line, Recorder};
    let h = Headless::new("subcritical");
    let mut header = crate::common::header_of(&h.app);
    header.version = 4;
    let path = std::env::temp_dir().join(format!("layout-v4-{}.jsonl", std::process::id()));
    let _ = std::fs::remove_file(&path);
    let mut rec = Recorder::create(&path, &header, None).unwrap();
    for event in [
        Event::Layout {
            effective: true,
            panes: vec![Pane::Compare],
        },
        Event::end(),
    ] {
        rec.write(&Line {
            wall: 0.0,
            t: 0.0,
            generation: 1,
            chain: None,
            event,
        })
        .unwrap();
    }
    drop(rec);
    let rec = record::read(&path).unwrap();
    let err = record::verify(&rec, "v4", None).unwrap_err().to_string();
    assert!(err.contains("format 5"), "{err}");
    let _ = std::fs::remove_file(&path);
}

/// Issue 26, item 7: the lesson "two ways to reverse a spin", walked with the right answers and
/// recorded: its comparison steps open the pane with the celt beside the holonomic body, every
/// answer is right, and the recording verifies bit for bit.
#[test]
fn the_two_ways_lesson_is_right_and_its_recording_verifies() {
    use rattleback::app::Outcome;
    use rattleback::app::journal::Event;
    use rattleback::record;
    use rattleback::scenario::lesson::Question;
    let lesson = rattleback::scenario::lesson::resolve("two-ways").unwrap();
    let mut h = Headless::new("celt-clockwise");
    let header = crate::common::header_of(&h.app);
    h.app
        .on_outcome(Outcome::Recording(Ok("two-ways.jsonl".to_owned())));
    let e = h.app.start_lesson(lesson.clone());
    h.exec(e);
    for (i, step) in lesson.steps.iter().enumerate() {
        match &step.question {
            Some(Question::Choice {
                choices, answer, ..
            }) => {
                assert!(*answer < choices.len());
                h.key(Key::Char(char::from(b'1' + u8::try_from(*answer).unwrap())));
            }
            Some(Question::Number { answer, .. }) => {
                h.key(Key::Char('a'));
                for c in format!("{answer}").chars() {
                    h.key(Key::Char(c));
                }
                h.key(Key::Enter);
            }
            None => {}
        }
        if step.partner.is_some() {
            assert!(h.app.view.panes.shows(Pane::Compare), "step {}", i + 1);
        }
        // A threshold step: the parameter set where the condition asks (issue 67).
        if let Some(p) = &step.until.parameter {
            let value = p.at_least.or(p.at_most).unwrap();
            let e = h.app.apply_set(&[rattleback::scenario::preset::Override {
                key: p.key.clone(),
                value: format!("{value:?}"),
            }]);
            h.exec(e);
        }
        h.play_until(step.until.time.unwrap(), 64.0);
        for _ in 0..3 {
            h.tick(1.0 / 30.0);
        }
        let state = h.app.lesson.as_ref().unwrap();
        assert_eq!(
            state.correct(),
            Some(true),
            "step {}: {}",
            i + 1,
            step.title
        );
        if step.partner.is_some() {
            let b = h.app.computed.compare.shown(h.app.run.shown).unwrap();
            assert_eq!(
                b.events,
                1,
                "step {}: the celt reversed once by 10 s",
                i + 1
            );
        }
        h.key(Key::Char('n'));
    }
    assert!(h.app.lesson.as_ref().unwrap().finished);
    h.key(Key::Char('R'));
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    let journal = h.app.take_journal();
    assert!(
        journal.iter().any(|(_, _, e)| matches!(
            e,
            Event::Layout { panes, .. } if panes.contains(&Pane::Compare)
        )),
        "the comparison is recorded"
    );
    assert!(
        journal
            .iter()
            .filter(|(_, _, e)| matches!(e, Event::Answer { correct: true, .. }))
            .count()
            == lesson.steps.len()
    );
    let path = std::env::temp_dir().join(format!("two-ways-{}.jsonl", std::process::id()));
    let mut journal = journal;
    h.stop_recording();
    journal.extend(h.app.take_journal());
    let back = crate::common::write_session(&path, &header, journal, 0.1);
    let report = record::verify(&back, "two-ways", None).unwrap();
    assert!(report.screens >= lesson.steps.len(), "{}", report.screens);
    // The words name the file's own format, not the first with this chain.
    assert_eq!(report.format, record::VERSION);
    assert!(
        report
            .integrity
            .starts_with(&format!("format {}: SHA-256", record::VERSION)),
        "{}",
        report.integrity
    );
    let _ = std::fs::remove_file(&path);
}
