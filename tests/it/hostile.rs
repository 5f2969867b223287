//! Hostile input (issue "Never hang, never clobber, never inject"): escape sequences in files
//! never reach a terminal, planted links are not followed.

fn bin(args: &[&str], config: &std::path::Path) -> (i32, String, String) {
    let out = crate::common::rattleback()
        .args(args)
        .env("RATTLEBACK_CONFIG_DIR", config)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn temp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("rattleback-hostile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const EVIL: &str = "[preset]\nname = \"Evil \\u001b]0;pwned\\u0007 name\"\n\
description = \"clears \\u001b[2J the screen, copies \\u001b]52;c;aGk=\\u001b\\\\ too\"\n\
[body]\nix = 2.0\niy = 1.0\niz = 1.0\n[spring]\nk = 1e4\n[initial]\ngamma_dot = 1.0\n\
alpha_dot = 0.5\n[run]\nt_end = 1.0\n";

fn clean(text: &str) -> bool {
    !text
        .chars()
        .any(|c| c.is_control() && c != '\n' && c != '\t')
}

#[test]
fn escape_sequences_in_files_never_reach_the_terminal() {
    let config = temp("escapes");
    let presets = config.join("presets");
    std::fs::create_dir_all(&presets).unwrap();
    let evil = presets.join("evil.toml");
    std::fs::write(&evil, EVIL).unwrap();
    let path = evil.to_str().unwrap();
    for args in [
        vec!["simulate", "--preset", path, "--format", "table"],
        vec!["simulate", "--preset", path, "--format", "json"],
        vec!["presets"],
        vec!["presets", "--format", "json"],
    ] {
        let (code, out, err) = bin(&args, &config);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(
            clean(&out) && clean(&err),
            "{args:?} printed a control character"
        );
        assert!(
            out.contains("Evil") || out.contains("evil"),
            "{args:?}: {out}"
        );
    }
    // An invalid value is echoed in the error, cleaned.
    std::fs::write(&evil, "[body]\nix = \"\u{1b}[2J\u{7}\"\n").unwrap();
    let (code, out, err) = bin(&["check", path], &config);
    assert_eq!(code, 2);
    assert!(
        clean(&out) && clean(&err),
        "check echoed a control character: {err:?}"
    );
    let _ = std::fs::remove_dir_all(&config);
}

#[test]
fn saving_never_follows_a_planted_link() {
    let d = temp("links");
    let outside = d.join("outside.txt");
    std::fs::write(&outside, "keep").unwrap();
    let presets = d.join("presets");
    std::fs::create_dir_all(&presets).unwrap();
    // The old temporary name, and the target itself, planted as links.
    let pid_guess = std::process::id();
    std::os::unix::fs::symlink(
        &outside,
        presets.join(format!(".mine.toml.tmp-{pid_guess}")),
    )
    .unwrap();
    std::os::unix::fs::symlink(&outside, presets.join("linked.toml")).unwrap();
    let text = rattleback::scenario::shipped::resolve("tapping", &[])
        .unwrap()
        .to_toml();
    rattleback::scenario::store::save(Some(&presets), "mine", &text, false).unwrap();
    assert!(matches!(
        rattleback::scenario::store::save(Some(&presets), "linked", &text, false),
        Err(rattleback::scenario::store::SaveError::Exists(_))
    ));
    // Even asked to replace, a link is neither written through nor replaced (issue 80: only a
    // regular file is ever replaced).
    assert!(rattleback::scenario::store::save(Some(&presets), "linked", &text, true).is_err());
    assert_eq!(std::fs::read_to_string(&outside).unwrap(), "keep");
    assert!(
        std::fs::symlink_metadata(presets.join("linked.toml"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn numbers_that_cannot_be_honest_are_refused() {
    let config = temp("numbers");
    // NaN never reaches an output with exit 0: an effective method at a vanishing k.
    let (code, out, err) = bin(
        &[
            "simulate",
            "--set",
            "spring.k=1e-309",
            "--method",
            "effective",
            "--format",
            "json",
        ],
        &config,
    );
    assert_eq!(code, 1, "{out}");
    assert!(err.contains("gamma is not a finite number"), "{err}");
    assert!(!out.contains("null") && !out.contains("NaN"));
    // A step too small to advance time is refused before running, from the flag or a preset.
    let (code, _, err) = bin(
        &["simulate", "--method", "rk4", "--step", "1e-300"],
        &config,
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--step") && err.contains("cannot advance"),
        "{err}"
    );
    let tiny = config.join("tiny.toml");
    std::fs::write(
        &tiny,
        "[body]\nix = 2.0\niy = 1.0\niz = 1.0\n[spring]\nk = 1e4\n[initial]\ngamma_dot = 1.0\n\
         alpha_dot = 0.5\n[run]\nt_end = 30.0\nmethod = \"rk4\"\nstep = 1e-300\n",
    )
    .unwrap();
    let (code, _, err) = bin(&["simulate", "--preset", tiny.to_str().unwrap()], &config);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("run.step"), "{err}");
    // --set takes one value, not a TOML document smuggled in with a newline.
    let (code, _, err) = bin(
        &["simulate", "--set", "spring.k=1e4\n[body]\nix = -1"],
        &config,
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("spring.k"), "{err}");
    let _ = std::fs::remove_dir_all(&config);
}

#[test]
fn devices_and_fifos_are_refused_without_being_read() {
    let config = temp("fifo");
    let presets = config.join("presets");
    std::fs::create_dir_all(&presets).unwrap();
    let fifo = presets.join("stuck.toml");
    let made = crate::common::detached("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let start = std::time::Instant::now();
    let (code, out, err) = bin(&["presets"], &config);
    assert!(
        start.elapsed() < std::time::Duration::from_secs(5),
        "presets blocked"
    );
    // Listed without it; the folder's problem is reported (exit 2, as for any broken file).
    assert_eq!(code, 2, "{err}");
    assert!(out.contains("subcritical"));
    assert!(
        err.contains("stuck.toml") && err.contains("not a regular file"),
        "{err}"
    );
    let (code, _, err) = bin(&["simulate", "--preset", "/dev/zero"], &config);
    assert_eq!(code, 2);
    assert!(err.contains("not a regular file"), "{err}");
    let _ = std::fs::remove_dir_all(&config);
}

/// When only the extra comparison with the limit fails, the requested run is still reported
/// (exit 0), the comparison's values are `null` with the reason, and nothing is NaN.
#[test]
fn a_failed_comparison_does_not_discard_the_requested_run() {
    let config = temp("comparison");
    let (code, out, err) = bin(
        &[
            "simulate",
            "--set",
            "spring.k=1e-309",
            "--method",
            "dop853",
            "--t-end",
            "1",
            "--format",
            "json",
        ],
        &config,
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["final"]["alpha"].as_f64().is_some_and(f64::is_finite));
    assert!(v["effective"]["alpha"].is_null());
    assert!(
        v["effective"]["comparison_error"]
            .as_str()
            .is_some_and(|e| e.contains("not a finite number")),
        "{out}"
    );
    assert!(!out.contains("NaN"));
    let _ = std::fs::remove_dir_all(&config);
}

#[test]
fn schema_errors_name_a_line_and_describe_what_was_written() {
    let dir = temp("schema");
    let write = |name: &str, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p.to_str().unwrap().to_owned()
    };
    // A missing key points at its section; a missing section at the end of the file.
    let missing = write(
        "missing.toml",
        b"[preset]\nname = \"x\"\n[body]\nix = 2.0\niy = 1.0\n[spring]\nk = 1e4\n",
    );
    let (code, _, err) = bin(&["check", &missing], &dir);
    assert_eq!(code, 2);
    assert!(
        err.contains("missing.toml:3: body.iz: missing required value"),
        "{err}"
    );
    assert!(
        err.contains("missing.toml:7: initial.gamma_dot: missing required value")
            && err.contains("no [initial] section"),
        "{err}"
    );
    // A dotted key names its line.
    let dotted = write(
        "dotted.toml",
        b"[body]\nix = 2.0\niy = 1.0\niz = 1.0\n[spring]\nk = 1e4\n[initial]\ngamma_dot = 1.0\nalpha_dot = 0.5\n[run]\nt_end = 1.0\nfoo.bar = 1\n",
    );
    let (_, _, err) = bin(&["check", &dotted], &dir);
    assert!(
        err.contains("dotted.toml:12: run.foo: unknown key"),
        "{err}"
    );
    // Invalid UTF-8: its line, in presets and in sessions.
    let bad = write("utf8.toml", b"[preset]\nname = \"x\xff\"\n");
    let (code, _, err) = bin(&["check", &bad], &dir);
    assert_eq!(code, 2);
    assert!(err.contains("utf8.toml:2: not valid UTF-8"), "{err}");
    let session = write("s.jsonl", b"{\"format\":\"rattleback-session\"}\n\xfe\n");
    let (code, _, err) = bin(&["replay", &session, "--verify"], &dir);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(":2") && err.contains("not valid UTF-8"),
        "{err}"
    );
    // 1e400 is a number too large, not "text".
    let (code, _, err) = bin(&["simulate", "--set", "body.ix=1e400"], &dir);
    assert_eq!(code, 2);
    assert!(
        err.contains("not a finite number") && !err.contains("text"),
        "{err}"
    );
    // A bad colour is reported once, as bad, not also as missing.
    let theme = write(
        "theme.toml",
        b"[theme]\nname = \"t\"\n[colors]\ntrail = \"blorange\"\n",
    );
    let (code, _, err) = bin(&["check", &theme], &dir);
    assert_eq!(code, 2);
    assert_eq!(err.matches("colors.trail").count(), 1, "{err}");
    assert!(
        err.contains("theme.toml:4: colors.trail: unknown colour"),
        "{err}"
    );
    // `check` refuses a FIFO instead of blocking on it.
    let fifo = dir.join("fifo.toml");
    assert!(
        crate::common::detached("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let (code, _, err) = bin(&["check", fifo.to_str().unwrap()], &dir);
    assert_eq!(code, 2);
    assert!(err.contains("not a regular file"), "{err}");
}

/// Issue 56 (R5): a config file of a hundred thousand bad keys (under the 1 MiB limit) is read
/// in linear time and said in a few dozen lines, each cut, with a count of the rest; an echoed
/// list of 200,000 numbers is cut too. (The time is not asserted: a quadratic reading took a
/// minute, which the suite's own time would show.)
#[test]
fn a_huge_bad_config_is_read_at_once_and_said_in_a_few_lines() {
    let dir = temp("huge-config");
    let keys = dir.join("keys.toml");
    let text: String = std::iter::once("[keys]\n".to_owned())
        .chain((0..100_000).map(|i| format!("k{i}=1\n")))
        .collect();
    std::fs::write(&keys, &text).unwrap();
    let fps = dir.join("fps.toml");
    std::fs::write(&fps, format!("fps = [{}]\n", vec!["1"; 200_000].join(", "))).unwrap();
    for (file, what) in [(&keys, "k0"), (&fps, "fps")] {
        let f = file.to_str().unwrap();
        let (code, _, stderr) = crate::common::bin(&["--config", f, "simulate"]);
        assert_eq!(code, 2, "{stderr}");
        let lines: Vec<&str> = stderr.lines().collect();
        assert!(
            lines.len() <= rattleback::scenario::text::MAX_LINES + 1,
            "{} lines",
            lines.len()
        );
        assert!(lines[0].contains(what), "{}", lines[0]);
        for l in &lines {
            assert!(
                l.chars().count() <= rattleback::scenario::text::MAX_LINE + 80,
                "{} chars",
                l.len()
            );
        }
        let (_, doctor, _) = crate::common::bin(&["--config", f, "doctor"]);
        assert!(doctor.len() < 20_000, "doctor says {} bytes", doctor.len());
    }
    let (_, _, stderr) = crate::common::bin(&["--config", keys.to_str().unwrap(), "simulate"]);
    assert!(stderr.contains("… and 99970 more problem(s)"), "{stderr}");
}

/// Issue 56 (R9, R12): file names and TOML strings with control, bidirectional, zero-width and
/// separator characters reach no completion, listing or table raw; a name with a newline is
/// not split into two candidates (the file is refused with its name escaped).
#[test]
fn names_with_controls_reach_no_completion_listing_or_table() {
    let dir = temp("odd-names");
    std::fs::create_dir_all(dir.join("presets")).unwrap();
    let text = rattleback::scenario::shipped::source_text("subcritical").unwrap();
    std::fs::write(dir.join("presets/x\u{1b}]0;FN\u{7}.toml"), &text).unwrap();
    std::fs::write(dir.join("presets/nl\nfile.toml"), &text).unwrap();
    let evil = text.replace(
        "name = \"Subcritical start\"",
        "name = \"Evil\\nline\\u2028sep\\u202Ebidi\\u200Bzw\\uFEFFbom\"",
    );
    std::fs::write(dir.join("presets/evil.toml"), &evil).unwrap();
    let bad = |s: &str| {
        s.chars().any(|c| {
            (c.is_control() && c != '\n' && c != '\t')
                || matches!(
                    c,
                    '\u{2028}' | '\u{2029}' | '\u{202e}' | '\u{200b}' | '\u{feff}'
                )
        })
    };
    for shell in ["bash", "zsh", "fish"] {
        let out = crate::common::rattleback()
            .args(["--", "rattleback", "--preset", ""])
            .env("RATTLEBACK_CONFIG_DIR", &dir)
            .env("COMPLETE", shell)
            .env("_CLAP_IFS", "\n")
            .env("_CLAP_COMPLETE_INDEX", "2")
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&out.stdout);
        assert!(!bad(&said), "{shell}: {said:?}");
        assert!(
            !said.lines().any(|l| l.starts_with("file")),
            "{shell}: split: {said:?}"
        );
        assert!(said.contains("evil"), "{shell}: {said:?}");
    }
    let (_, listing, errors) = bin(&["presets"], &dir);
    assert!(!bad(&listing) && !bad(&errors), "{listing:?} {errors:?}");
    assert!(listing.contains("Evil line sep"), "{listing}");
    assert!(errors.contains("nl\\u{a}file.toml"), "{errors}");
    let (code, table, _) = bin(&["simulate", "--preset", "evil", "--t-end", "1"], &dir);
    assert_eq!(code, 0);
    assert!(!bad(&table), "{table:?}");
    assert!(
        table.lines().next().unwrap().contains("Evil line sep"),
        "{table}"
    );
}

/// Issue 56 (R16): a key's name with an escape sequence or a newline is refused (it was written
/// under one name and printed as another); a private key others can read is refused by
/// `--sign`, as ssh refuses it.
#[test]
fn keys_are_named_plainly_and_kept_private() {
    let dir = temp("keys");
    for name in ["n\u{1b}]0;PWNED\u{7}\u{1b}[2Jm", "a\nb", "x\u{202e}y"] {
        let stem = dir.join(name);
        let (code, out, err) = bin(&["keygen", stem.to_str().unwrap()], &dir);
        assert_eq!(code, 2, "{out}{err}");
        assert!(
            err.contains("cannot have control or invisible characters"),
            "{err}"
        );
        assert!(
            !err.contains('\u{1b}') && err.trim().lines().count() == 1,
            "{err:?}"
        );
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "a file was written"
    );
    let stem = dir.join("lecturer");
    assert_eq!(bin(&["keygen", stem.to_str().unwrap()], &dir).0, 0);
    let key = dir.join("lecturer.key");
    assert!(rattleback::record::sign::Signer::read(&key).is_ok());
    {
        use std::os::unix::fs::PermissionsExt as _;
        std::fs::set_permissions(&key, std::fs::Permissions::from_mode(0o644)).unwrap();
    }
    let e = rattleback::record::sign::Signer::read(&key)
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("mode 644") && e.contains("chmod 600"), "{e}");
}
