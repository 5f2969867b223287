//! Issue 82: a recording made in the browser's explorer (`R` starts it, `R` again hands the
//! page its bytes) is a session file that `rattleback replay FILE --verify` accepts natively:
//! played at top speed, paused, stepped, a value changed, played again.

use rattleback::app::Key;
use rattleback_web::Explorer;

/// Frames of 1/30 s until `done` says so (at most `limit`).
fn frames(e: &mut Explorer, limit: usize, done: impl Fn(&Explorer) -> bool) {
    for _ in 0..limit {
        if done(e) {
            return;
        }
        e.tick(1.0 / 30.0);
        e.draw();
    }
}

fn recorded(preset: &str, keys: &[Key]) -> (String, Vec<u8>) {
    let mut e = Explorer::new(preset, 80, 24).unwrap();
    e.key(Key::Char('R'));
    e.draw();
    assert!(e.text().contains("recording to"), "{}", e.text());
    for &k in keys {
        e.key(k);
        frames(&mut e, 20, |_| false);
    }
    frames(&mut e, 100_000, |e| {
        let t = e.text();
        t.contains("│ done │") || t.contains("| done |")
    });
    e.key(Key::Char('R'));
    let mut download = None;
    for _ in 0..300 {
        download = e.take_download();
        if download.is_some() {
            break;
        }
        e.tick(1.0 / 30.0);
    }
    let (name, bytes) = download.expect("R again ends the recording and hands it over");
    e.draw();
    assert!(e.text().contains("recording saved to"), "{}", e.text());
    (name, bytes)
}

/// What `replay FILE --verify` does with the file (the command's own reading and checking;
/// CI runs the command on a recording downloaded from the page in Chromium).
fn verifies(name: &str, bytes: &[u8]) -> rattleback::record::Report {
    let text = std::str::from_utf8(bytes).unwrap();
    let rec = rattleback::record::parse(text, name).unwrap();
    rattleback::record::verify(&rec, name, None).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn a_recording_made_in_the_page_verifies_natively() {
    let speed: Vec<Key> = std::iter::repeat_n(Key::Char('+'), 10).collect();
    for preset in [
        "subcritical",
        "kapitza-upright",
        "celt-clockwise",
        "soft-spring",
    ] {
        let mut keys = speed.clone();
        // Play, pause, a step, the selected value up (a new run), play.
        keys.extend([
            Key::Char(' '),
            Key::Char(' '),
            Key::Char('.'),
            Key::Char('l'),
            Key::Char(' '),
        ]);
        let (name, bytes) = recorded(preset, &keys);
        let text = String::from_utf8(bytes.clone()).unwrap();
        assert!(text.lines().count() > 5, "{preset}: {text}");
        assert!(
            text.lines().last().unwrap().contains("\"end\""),
            "{preset}: ends with its end line"
        );
        let report = verifies(&name, &bytes);
        assert!(
            report.checkpoints >= 2,
            "{preset}: {} checkpoints",
            report.checkpoints
        );
        assert!(
            report.screens >= 1 && report.final_screen,
            "{preset}: {report:?}"
        );
    }
}
