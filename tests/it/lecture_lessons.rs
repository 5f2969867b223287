//! Every shipped lesson as a lecture (split from `lecture.rs`, issue 69: no source file over
//! 1,000 lines): recorded as a teacher gives it, replayed, followed and verified frame for frame.

use crate::common;
use crate::lecture::*;

use common::Headless;
use rattleback::app::journal::Event;
use rattleback::app::{Key, Outcome};
use rattleback::record;
use rattleback::ui::UiOptions;

/// Issue 55: a lesson is a lecture too. Each shipped lesson is recorded as a teacher gives it:
/// the questions answered (right, or wrong), values typed, a pane toggled, `n` pressed while the
/// run plays wherever the step's condition allows it, the recording stopped; at ×1 and ×16.
/// The file then replays and follows line by line with the lecturer's frame at every screen
/// line, the lesson's pane included; it verifies (its last frame too) and exports as a cast
/// and a page.
#[allow(clippy::too_many_lines)] // one lesson, given step by step
fn lesson_lecture(name: &str, speed: f64, wrong: bool) -> Lecture {
    use rattleback::scenario::lesson::Question;
    let lesson = rattleback::scenario::lesson::resolve(name).unwrap();
    let first = lesson.steps[0]
        .preset
        .clone()
        .unwrap_or_else(|| rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap());
    let mut l = Lecturer {
        h: Headless::of(&first),
        wall: 0.0,
        lines: Vec::new(),
        frames: Vec::new(),
    };
    let effects = l.h.app.start_lesson(lesson.clone());
    l.h.exec(effects);
    let header = rattleback::record::active::header(&l.h.app, (80, 24), 30.0);
    assert!(header.lesson.is_some(), "the header carries the lesson");
    let effects =
        l.h.app
            .on_outcome(Outcome::Recording(Ok("lesson.jsonl".into())));
    l.h.exec(effects);
    l.collect();
    for (i, step) in lesson.steps.iter().enumerate() {
        assert_eq!(l.h.app.lesson.as_ref().unwrap().step, i, "{name}");
        l.tick();
        // The question: right, or wrong (alternately when `wrong`).
        let wrong_here = wrong && i % 2 == 0;
        match &step.question {
            Some(Question::Choice {
                choices, answer, ..
            }) => {
                let pick = if wrong_here {
                    (answer + 1) % choices.len()
                } else {
                    *answer
                };
                l.key(Key::Char(char::from(b'1' + pick as u8)));
            }
            Some(Question::Number { answer, .. }) => {
                let typed = if wrong_here {
                    answer * 3.0 + 1.0
                } else {
                    *answer
                };
                l.text('a', &format!("{typed}"));
            }
            None => {}
        }
        l.tick();
        // A step about another pane leaves the arrows to the panel, not to a map it may hide.
        if step.pane.as_deref().is_some_and(|p| p != "map") {
            assert_ne!(
                l.h.app.mode,
                rattleback::app::Mode::Map,
                "{name} step {}",
                i + 1
            );
        }
        // The chart read as the step asks (its map has the arrows): the cursor moved up two
        // cells, a format-12 line each, which the replay, the follower and the cast draw.
        if step.pane.as_deref() == Some("map") {
            assert_eq!(
                l.h.app.mode,
                rattleback::app::Mode::Map,
                "{name} step {}",
                i + 1
            );
            let before = l.h.app.computed.map.cursor;
            l.key(Key::Up);
            l.tick();
            l.key(Key::Up);
            l.tick();
            assert_eq!(l.h.app.computed.map.cursor.1, before.1 + 2, "{name}");
        }
        // A pane toggled and back (layout lines).
        l.key(Key::Char('t'));
        l.tick();
        l.key(Key::Char('t'));
        l.tick();
        // A value typed where the step asks for one.
        if let Some(p) = &step.until.parameter {
            let label = p.key.rsplit('.').next().unwrap();
            // The step's map has the arrows: Esc gives them back, as its text says.
            if l.h.app.mode == rattleback::app::Mode::Map {
                l.key(Key::Esc);
            }
            let mut presses = 0;
            while l.h.app.field().label() != label {
                l.key(Key::Down);
                presses += 1;
                assert!(presses < 100, "{name}: no field {label} under the arrows");
            }
            let value = p.at_least.or(p.at_most).unwrap();
            l.key(Key::Enter);
            for c in format!("{value}").chars() {
                l.key(Key::Char(c));
            }
            l.key(Key::Enter);
            l.tick();
        }
        while l.h.app.run.speed < speed {
            l.key(Key::Char('+'));
        }
        l.key(Key::Char(' '));
        // Until the step's condition holds: then `n`, while the run still plays where it does.
        let mut frames = 0;
        while l.h.app.lesson_missing().is_some() {
            l.tick();
            frames += 1;
            assert!(frames < 200_000, "{name} step {}: never ready", i + 1);
            assert!(
                !l.h.app.run.done() || l.h.app.lesson_missing().is_none(),
                "{name} step {}: done, still waiting for {:?}",
                i + 1,
                l.h.app.lesson_missing()
            );
        }
        l.key(Key::Char('n'));
        l.tick();
    }
    assert!(
        l.h.app.lesson.as_ref().unwrap().finished,
        "{name}: finished"
    );
    l.stop();
    Lecture {
        header,
        lines: l.lines,
        frames: l.frames,
    }
}

/// A lesson whose steps read the map records its cursor (format 12); one without, none.
fn map_cursor_lines_are_there(name: &str, lecture: &Lecture) {
    let maps = lecture
        .lines
        .iter()
        .filter(|l| matches!(l.event, Event::MapCursor { .. }))
        .count();
    let asks_map = rattleback::scenario::lesson::resolve(name)
        .unwrap()
        .steps
        .iter()
        .any(|s| s.pane.as_deref() == Some("map"));
    assert_eq!(asks_map, maps > 0, "{name}: {maps} map cursor lines");
}

/// One test per shipped lesson (they run side by side: one test of all eight took four
/// minutes alone); a lesson shipped without its test fails
/// `every_shipped_lesson_has_its_lecture_test`.
macro_rules! lesson_lectures {
    ($($test:ident: $name:literal,)*) => {
        $(
            #[test]
            fn $test() {
                a_shipped_lesson_records_replays_follows_and_verifies_frame_for_frame($name);
            }
        )*
        const LECTURED: &[&str] = &[$($name),*];
    };
}

lesson_lectures! {
    lecture_first_reversal: "first-reversal",
    lecture_stiff_limit: "stiff-limit",
    lecture_tapping: "tapping",
    lecture_kapitza_threshold: "kapitza-threshold",
    lecture_kapitza_ripple: "kapitza-ripple",
    lecture_two_ways: "two-ways",
    lecture_kapitza_chart: "kapitza-chart",
    lecture_celt_chart: "celt-chart",
}

#[test]
fn every_shipped_lesson_has_its_lecture_test() {
    let shipped: Vec<&str> = rattleback::scenario::lesson::SHIPPED_LESSONS
        .iter()
        .map(|(n, _)| *n)
        .collect();
    assert_eq!(shipped, LECTURED);
}

/// A shipped lesson recorded as a lecturer gives it (at ×1 and ×16, answers right and wrong),
/// replayed, followed, verified and exported, frame for frame.
#[allow(clippy::too_many_lines)] // every way the lecture is read back, one after the other
fn a_shipped_lesson_records_replays_follows_and_verifies_frame_for_frame(name: &str) {
    {
        for (speed, wrong) in [(1.0, false), (16.0, true)] {
            let lecture = lesson_lecture(name, speed, wrong);
            let screens = lecture.frames.len();
            // `n` pressed while playing leaves a pause in the file before the next step's screen.
            let steps = lecture
                .lines
                .iter()
                .filter(|l| matches!(l.event, Event::LessonStep { .. }))
                .count();
            assert!(steps >= 3, "{name}: {steps} steps recorded");
            assert!(
                lecture
                    .lines
                    .iter()
                    .any(|l| matches!(l.event, Event::Given { .. })),
                "{name}: the answers given are recorded"
            );
            assert!(
                lecture.lines.iter().any(|l| l.event == Event::LessonDone),
                "{name}: the end of the lesson is recorded"
            );
            map_cursor_lines_are_there(name, &lecture);
            assert_eq!(
                replay_and_compare(name, &lecture, false),
                screens,
                "{name} ×{speed}: replay"
            );
            assert_eq!(
                replay_and_compare(name, &lecture, true),
                screens,
                "{name} ×{speed}: follow"
            );
            let path = write(&lecture, &format!("lesson-{name}-{speed}.jsonl"), None);
            let rec = record::read(&path).unwrap();
            let report =
                record::verify(&rec, name, None).unwrap_or_else(|e| panic!("{name} ×{speed}: {e}"));
            assert_eq!(report.screens, screens, "{name} ×{speed}");
            assert!(report.final_screen, "{name} ×{speed}: the last frame");
            // The binary's own verify, and both exports.
            let (code, out, err) = common::bin(&["replay", path.to_str().unwrap(), "--verify"]);
            assert_eq!(code, 0, "{name} ×{speed}: {err}");
            assert!(out.contains("the last frame, as recorded"), "{out}");
            let cast = temp(&format!("lesson-{name}-{speed}.cast"));
            rattleback::cast::export_cast(
                &rec,
                "lesson",
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
            let text = std::fs::read_to_string(&cast).unwrap();
            assert_eq!(
                cast_screens(&text, &lecture),
                screens,
                "{name} ×{speed}: cast"
            );
            let page = temp(&format!("lesson-{name}-{speed}.html"));
            let (code, _, err) = common::bin(&[
                "replay",
                path.to_str().unwrap(),
                "--verify",
                "--export-html",
                page.to_str().unwrap(),
            ]);
            assert_eq!(code, 0, "{name} ×{speed}: {err}");
            // The page opens on the last frame: its poster is the inlined cast's last frame,
            // and that frame is the lecturer's last screen.
            let html = std::fs::read_to_string(&page).unwrap();
            let inlined = html
                .split_once("<script type=\"application/json\" id=\"cast\">")
                .and_then(|(_, rest)| rest.split_once("</script>"))
                .map(|(json, _)| serde_json::from_str::<String>(json).unwrap())
                .expect("the page inlines its cast");
            let last = rattleback::cast::last_frame_time(&inlined);
            assert!(last > 0.0, "{name} ×{speed}");
            let poster = rattleback::commands::page::poster_time(&inlined);
            assert!(
                poster > last && poster - last < 0.01,
                "{name} ×{speed}: the poster ({poster}) is not the last frame ({last})"
            );
            assert!(
                html.contains(&format!("poster: \"npt:{poster:.6}\"")),
                "{name} ×{speed}: the page's poster is not the last frame"
            );
            // Titled by the lesson, not its first preset; its description under the title;
            // each step's chapter at the step's own start (issue 67).
            let title = &lecture.header.lesson.as_ref().unwrap().title;
            assert!(
                html.contains(&format!(
                    "<h1>rattleback: {}</h1>",
                    title
                        .replace('&', "&amp;")
                        .replace('<', "&lt;")
                        .replace('>', "&gt;")
                        .replace('\'', "&#39;")
                )),
                "{name}: the page's title"
            );
            assert!(html.contains("<p class=\"description\">"), "{name}");
            let header: serde_json::Value =
                serde_json::from_str(text.lines().next().unwrap()).unwrap();
            assert_eq!(
                header["title"],
                format!("rattleback: {title}"),
                "{name}: cast"
            );
            let steps_with_preset: Vec<bool> = rattleback::scenario::lesson::resolve(name)
                .unwrap()
                .steps
                .iter()
                .map(|s| s.preset.is_some())
                .collect();
            let chapters = record::chapter_list(&rec);
            assert_eq!(chapters.len(), steps_with_preset.len(), "{name}");
            for (c, fresh) in chapters.iter().zip(steps_with_preset) {
                if fresh {
                    assert!(
                        c.t.abs() < f64::MIN_POSITIVE,
                        "{name}: {} starts its own run at 0 (t {})",
                        c.title,
                        c.t
                    );
                }
            }
            let strip = |s: &str| s.lines().take(18).collect::<Vec<_>>().join("\n");
            assert_eq!(
                strip(&cast_last_screen(&inlined)),
                strip(&lecture.frames.last().unwrap().1),
                "{name} ×{speed}: the page's last frame"
            );
        }
    }
}
