//! A recorded lecture's trust (split from `lecture.rs`, issue 69: no source file over 1,000
//! lines): an edited, downgraded, cut or signed session fails or verifies naming the line; a
//! follower waits for a file not yet written; the checked-in format-4 sessions verify.

use crate::lecture::{Lecture, lecture, temp, write};
use rattleback::app::journal::Event;
use rattleback::record::{self, Recorder};

fn one_lecture() -> Lecture {
    lecture("subcritical", 16.0, "k")
}

fn line_of(path: &std::path::Path, kind: &str) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .position(|l| l.contains(&format!("\"kind\":\"{kind}\"")))
        .unwrap()
}

fn edit(
    path: &std::path::Path,
    name: &str,
    f: impl Fn(usize, &str) -> Option<String>,
) -> std::path::PathBuf {
    let text = std::fs::read_to_string(path).unwrap();
    let out: Vec<String> = text
        .lines()
        .enumerate()
        .filter_map(|(i, l)| f(i, l))
        .collect();
    let p = temp(name);
    std::fs::write(&p, out.join("\n") + "\n").unwrap();
    p
}

fn diverged_at(path: &std::path::Path, key: Option<&record::sign::PublicKey>) -> usize {
    let rec = record::read(path).unwrap();
    match record::verify(&rec, "edited", key) {
        Err(record::VerifyError::Diverged(d)) => d.line,
        other => panic!("{other:?}"),
    }
}

#[test]
fn edits_downgrades_cuts_and_extra_fields_fail_naming_the_line() {
    let lecture = one_lecture();
    let path = write(&lecture, "intact.jsonl", None);
    assert!(record::verify(&record::read(&path).unwrap(), "intact", None).is_ok());
    // A note's text changed (a forged line, its chain left as it was).
    let note = line_of(&path, "note");
    let forged = edit(&path, "forged.jsonl", |i, l| {
        Some(if i == note {
            l.replace("watch", "skip")
        } else {
            l.to_owned()
        })
    });
    assert_eq!(diverged_at(&forged, None), note + 1);
    // The header says version 3: its rules refuse format-4 lines.
    let current = format!("\"version\":{}", record::VERSION);
    let downgraded = edit(&path, "downgraded.jsonl", |i, l| {
        Some(if i == 0 {
            l.replace(&current, "\"version\":3")
        } else {
            l.to_owned()
        })
    });
    let first = std::fs::read_to_string(&downgraded).unwrap();
    assert!(first.starts_with("{\"format\":\"rattleback-session\",\"version\":3"));
    diverged_at(&downgraded, None);
    // An extra field: covered by the chain and refused by the format.
    let extra = edit(&path, "extra.jsonl", |i, l| {
        Some(if i == note {
            l.replacen('{', "{\"x\":1,", 1)
        } else {
            l.to_owned()
        })
    });
    assert_eq!(diverged_at(&extra, None), note + 1);
    // The tail deleted (the end line and a few before it): intact but incomplete.
    let total = std::fs::read_to_string(&path).unwrap().lines().count();
    let cut = edit(&path, "cut.jsonl", |i, l| {
        (i + 4 < total).then(|| l.to_owned())
    });
    match record::verify(&record::read(&cut).unwrap(), "cut", None) {
        Err(record::VerifyError::Incomplete { through, .. }) => assert_eq!(through, total - 4),
        other => panic!("{other:?}"),
    }
    // Everything but the header: incomplete too.
    let bare = edit(&path, "bare.jsonl", |i, l| (i == 0).then(|| l.to_owned()));
    assert!(matches!(
        record::verify(&record::read(&bare).unwrap(), "bare", None),
        Err(record::VerifyError::Incomplete { .. })
    ));
    // And the command says so, with a non-zero exit.
    let out = crate::common::rattleback()
        .args(["replay", cut.to_str().unwrap(), "--verify"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(&format!("intact up to line {}", total - 4)),
        "{err}"
    );
    // Nothing claims the last frame the cut removed (issue 67: "the last frame, as recorded"
    // was printed before the failure).
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(!said.contains("the last frame, as recorded"), "{said}");
    assert!(said.contains("its last frame is not in the file"), "{said}");
}

#[test]
fn a_signed_session_verifies_with_its_key_and_fails_with_another() {
    let dir = temp("keys");
    std::fs::create_dir_all(&dir).unwrap();
    let (secret, public) = record::sign::keygen(&dir.join("lecturer")).unwrap();
    let (_, other) = record::sign::keygen(&dir.join("someone-else")).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        let mode = std::fs::metadata(&secret).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o600, "the private key is private");
    }
    assert!(
        record::sign::keygen(&dir.join("lecturer")).is_err(),
        "never overwritten"
    );
    let lecture = one_lecture();
    let signer = record::sign::Signer::read(&secret).unwrap();
    let path = write(&lecture, "signed.jsonl", Some(signer));
    let key = record::sign::PublicKey::read(&public).unwrap();
    let report = record::verify(&record::read(&path).unwrap(), "signed", Some(&key)).unwrap();
    assert!(report.signature.unwrap().starts_with("signed by lecturer"));
    let other = record::sign::PublicKey::read(&other).unwrap();
    let end = std::fs::read_to_string(&path).unwrap().lines().count();
    assert_eq!(diverged_at(&path, Some(&other)), end);
    // An unsigned session does not pass for a signed one.
    let unsigned = write(&lecture, "unsigned.jsonl", None);
    diverged_at(&unsigned, Some(&key));
    // Said at the end line's time, not at t = 0 (issue 56).
    let rec = record::read(&unsigned).unwrap();
    let last_t = rec.lines.last().unwrap().1.t;
    match record::verify(&rec, "unsigned", Some(&key)) {
        Err(record::VerifyError::Diverged(d)) => {
            assert_eq!(d.t.to_bits(), last_t.to_bits(), "{d:?}");
        }
        other => panic!("{other:?}"),
    }
    // An end line that counts wrong says its count in words, not as `Some(10)`.
    let miscounted = edit(&unsigned, "miscounted.jsonl", |_, l| {
        Some(if l.contains("\"kind\":\"end\"") {
            let at = l.find("\"lines\":").unwrap() + 8;
            let digits = l[at..].find(|c: char| !c.is_ascii_digit()).unwrap();
            format!("{}10{}", &l[..at], &l[at + digits..])
        } else {
            l.to_owned()
        })
    });
    let text = match record::verify(&record::read(&miscounted).unwrap(), "m", None) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("a wrong count verified"),
    };
    assert!(!text.contains("Some("), "{text}");
    // A line edited and the whole chain written again by someone without the key: the chain
    // holds, the signature does not.
    let rec = record::read(&path).unwrap();
    let forged = temp("reforged.jsonl");
    let mut out = Recorder::create(&forged, &rec.header, None).unwrap();
    for (_, l) in &rec.lines {
        let mut l = l.clone();
        if let Event::Note { text } = &mut l.event {
            *text = "forged".to_owned();
        }
        out.write(&l).unwrap();
    }
    drop(out);
    // Re-chained without a key: the end line is unsigned now, so a key check fails.
    diverged_at(&forged, Some(&key));
}

/// `follow` of a file that does not exist yet waits for it, saying so (students usually start
/// first), then reads it once it appears: here a file that is not a session, refused with exit 2
/// before the terminal is touched. In a pseudo-terminal of its own (`script`): `follow` refuses
/// at once where it has no terminal to draw on.
#[test]
fn follow_waits_for_a_file_that_does_not_exist_yet() {
    let path = temp("not-yet.jsonl");
    let log = temp("not-yet.pty");
    let command = format!(
        "exec {} follow {}",
        crate::common::program(),
        path.display()
    );
    let mut child = crate::common::in_pty(&command, &log)
        .stdin(std::process::Stdio::piped())
        .spawn()
        .expect("`script` (util-linux) gives follow a pseudo-terminal");
    std::thread::sleep(std::time::Duration::from_millis(700));
    assert!(
        child.try_wait().unwrap().is_none(),
        "it must wait, not exit"
    );
    std::fs::write(&path, "not a session\n").unwrap();
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "still waiting after the file appeared"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    let err = String::from_utf8_lossy(&std::fs::read(&log).unwrap()).into_owned();
    assert_eq!(status.code(), Some(2), "{err}");
    assert!(err.contains("waiting for"), "{err}");
    assert!(err.contains("not a session header"), "{err}");
    assert!(
        !err.contains("\u{1b}[?1049h"),
        "the terminal was not touched: {err}"
    );
}

/// Two format-4 sessions recorded in the explorer over a real terminal (tmux at 80×24): a
/// rattleback lecture at ×16 (pause, three steps, Esc twice, a chapter, play to the end) and a
/// pendulum lecture signed with `--sign` (its public key checked in beside it). Both verify, the
/// signed one with its key and not with another.
#[test]
fn checked_in_format_4_sessions_verify_and_the_signed_one_with_its_key() {
    let dir = format!("{}/tests/fixtures/sessions", root!());
    let bin = |args: &[&str]| {
        let out = crate::common::rattleback().args(args).output().unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let lecture = format!("{dir}/lecture.jsonl");
    let (code, out, err) = bin(&["replay", &lecture, "--verify"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("6 screen(s) as recorded"), "{out}");
    assert!(out.contains("format 4: SHA-256"), "{out}");
    let signed = format!("{dir}/kapitza-signed.jsonl");
    let key = format!("{dir}/lecturer.pub");
    let (code, out, err) = bin(&["replay", &signed, "--verify", "--key", &key]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("signed by lecturer"), "{out}");
    let other = temp("other");
    record::sign::keygen(&other).unwrap();
    let other_pub = format!("{}.pub", other.display());
    let (code, _, err) = bin(&["replay", &signed, "--verify", "--key", &other_pub]);
    assert_eq!(code, Some(1));
    assert!(err.contains("signed by another key"), "{err}");
}
