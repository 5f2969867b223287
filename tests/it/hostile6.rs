//! The sixth reviews' reproductions (shared/docs/reviews/reliability.md N1–N11, lecturer.md L1,
//! copied into tests/fixtures/hostile6/), each failing on the build they were found in (issue
//! 80): a session whose clock runs backwards, writers onto what is not a regular file, a lesson's
//! walk that is priced, logins that are ssh options, and `serve` against FIFOs, links and
//! greedy clients (those in `serve.rs`).

use crate::common::bin;

fn fixture(name: &str) -> String {
    format!("{}/tests/fixtures/hostile6/{name}", root!())
}

#[test]
fn a_session_whose_clock_runs_backwards_is_refused() {
    // N11: one clock line's t moved a second ahead of the next, the chain recomputed.
    let (code, out, err) = bin(&[
        "replay",
        &fixture("clock-backwards-rechained.jsonl"),
        "--verify",
    ]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        err.contains(":9:") && err.contains("ran backwards"),
        "{err}"
    );
}

#[test]
fn the_shard_script_refuses_a_login_that_is_an_ssh_option() {
    // N1: a login whose host or user begins with `-` reached ssh as an option; `..` makes GNU
    // parallel read a file of its own. Each is refused before parallel runs, and nothing runs.
    let lines = std::fs::read_to_string(fixture("sshlogin-option/hostile-lines.txt")).unwrap();
    let dir = std::env::temp_dir().join(format!("rattleback-logins-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(fixture("sshlogin-option/evil.conf"), dir.join("evil.conf")).unwrap();
    let script = format!("{}/scripts/shard-parallel.sh", root!());
    for line in lines.lines() {
        let logins = dir.join("logins.txt");
        std::fs::write(&logins, format!("{line}\n")).unwrap();
        let out = crate::common::detached("bash")
            .arg(&script)
            .args([
                "2",
                "o.json",
                "--preset",
                "kapitza-upright",
                "--grid",
                "4x3",
            ])
            .current_dir(&dir)
            .env("RATTLEBACK", crate::common::program())
            .env("RATTLEBACK_SSHLOGINFILE", &logins)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{line:?}: {err}");
        assert!(err.contains("not a login"), "{line:?}: {err}");
        assert!(
            !dir.join("PWNED_F").exists(),
            "{line:?} ran evil.conf's command"
        );
    }
    // Plain logins still pass the check (the run itself needs GNU parallel and ssh: CI's).
    for good in ["host1", "2/user@host-2.example:2222", ":", "4/:"] {
        let ok = regex_accepts(good);
        assert!(ok, "{good} refused");
    }
}

/// Whether the script's check accepts the login `line` (its own regular expression, run by
/// bash).
fn regex_accepts(line: &str) -> bool {
    let script = std::fs::read_to_string(format!("{}/scripts/shard-parallel.sh", root!())).unwrap();
    let re = script
        .lines()
        .find_map(|l| l.trim().strip_prefix("if ! [[ $line =~ "))
        .and_then(|l| l.strip_suffix(" ]]; then"))
        .expect("the script's login check");
    crate::common::detached("bash")
        .args(["-c", &format!("[[ $1 =~ {re} ]]"), "check", line])
        .status()
        .unwrap()
        .success()
}

#[test]
fn a_writer_replaces_only_a_regular_file_even_with_force() {
    // N8: `lesson new --out PATH --force` renamed its file over a device node. A FIFO, a link
    // and a folder stand in for the device here (the same refusal; a test must not risk a real
    // device), for every writer that takes --force.
    let dir = std::env::temp_dir().join(format!("rattleback-writers-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("fifo");
    assert!(
        crate::common::detached("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let target = dir.join("target.txt");
    std::fs::write(&target, "keep").unwrap();
    let link = dir.join("link");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let session = format!("{}/tests/fixtures/sessions/lecture.jsonl", root!());
    for path in [&fifo, &link] {
        let p = path.to_str().unwrap();
        for args in [
            vec!["lesson", "new", "x", "--out", p, "--force"],
            vec!["replay", &session, "--export-cast", p, "--force"],
            vec!["replay", &session, "--export-html", p, "--force"],
        ] {
            let (code, _, err) = bin(&args);
            assert_eq!(code, 2, "{args:?}: {err}");
            assert!(
                err.contains("only a regular file is ever replaced"),
                "{args:?}: {err}"
            );
        }
    }
    let meta = std::fs::symlink_metadata(&fifo).unwrap();
    assert!(std::os::unix::fs::FileTypeExt::is_fifo(&meta.file_type()));
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
    // A regular file is still replaced when asked.
    let (code, _, err) = bin(&[
        "lesson",
        "new",
        "x",
        "--out",
        target.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn check_prices_a_lessons_runs_and_says_what_they_cannot_meet() {
    // N7: a step's run of 1e6 s was played unbudgeted (110 CPU-s); it is refused by its price.
    let (code, _, err) = bin(&["check", &fixture("lesson-set-long.toml")]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("predicted to take") && err.contains("budget 60 s"),
        "{err}"
    );
    // L2, L10: a run the step leads to that auto cannot meet at its tolerance is said.
    let (code, _, err) = bin(&["check", &fixture("lesson-tolerance.toml")]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("cannot meet its tolerance"), "{err}");
    // L4: a "threshold" that is the window's edge (two-ways' step 3 before issue 80).
    let (code, _, err) = bin(&["check", &fixture("two-ways-window.toml")]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("depends on the window"), "{err}");
}
