//! Issue 82: `f` on a served lecture's page forks the lecture into the browser's explorer:
//! the lecture's lines so far are replayed to the last one (as `follow` shows it), then the
//! explorer is the student's own from there (as `follow`'s `f`).

use rattleback::app::Key;
use rattleback_web::Explorer;

const LECTURE: &str = include_str!("../../tests/fixtures/sessions/lecture.jsonl");

/// The first `n` lines of the lecture (the header included): the file as it was being written.
fn cut(n: usize) -> String {
    LECTURE.split_inclusive('\n').take(n).collect()
}

fn shown_t(e: &Explorer) -> f64 {
    e.app().run.shown
}

#[test]
fn a_fork_starts_where_the_lecture_was_and_is_the_students_own() {
    for n in [2, 10, 21, 30, LECTURE.lines().count()] {
        let text = cut(n);
        let rec = rattleback::record::parse(&text, "lecture").unwrap();
        let last = rec.lines.last().map(|(_, l)| l.t).unwrap();
        let (mut e, at) = Explorer::forked(&text, 80, 24).unwrap();
        assert_eq!(
            at.to_bits(),
            last.to_bits(),
            "{n} lines: forked at the last line's time"
        );
        // A lecture that was playing plays on in the fork (from there); a paused one holds.
        let playing = e.app().run.playing;
        assert!(shown_t(&e) >= last, "{n} lines");
        if !playing {
            assert_eq!(shown_t(&e).to_bits(), last.to_bits(), "{n} lines");
        }
        let screen = e.text();
        assert!(screen.contains("forked at t"), "{n} lines:\n{screen}");
        // The student's own: a step moves on from there, past where the lecture stopped.
        if playing {
            e.key(Key::Char(' '));
        }
        let was = shown_t(&e);
        for _ in 0..3 {
            e.key(Key::Char('.'));
            e.tick(1.0 / 30.0);
        }
        let t_end = e.app().scenario.settings.t_end;
        assert!(
            shown_t(&e) > was || was >= t_end,
            "{n} lines: {was} → {}",
            shown_t(&e)
        );
    }
}

#[test]
fn a_fork_of_what_is_not_a_lecture_is_refused_with_the_reason() {
    for (text, says) in [
        ("", "empty"),
        (
            "{\"format\":\"something else\"}\n",
            "not a rattleback session",
        ),
        ("not json\n", "not a session header"),
    ] {
        let Err(e) = Explorer::forked(text, 80, 24) else {
            panic!("{text:?} forked");
        };
        assert!(e.contains(says), "{text:?}: {e}");
    }
    // A preset in the header that is not valid is named as the header's.
    let bad = LECTURE.replacen("ix = 2.0", "ix = -2.0", 1);
    let Err(e) = Explorer::forked(&bad, 80, 24) else {
        panic!("a negative inertia forked");
    };
    assert!(e.contains("ix"), "{e}");
}
