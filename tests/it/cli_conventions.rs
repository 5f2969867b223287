//! Issue 15, item 1: the command line follows the conventions of the tools users know.

use crate::common;

use common::bin;

#[test]
fn an_explorer_flag_before_a_subcommand_is_refused_not_ignored() {
    let (code, out, err) = bin(&["--preset", "supercritical", "simulate"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(out.is_empty());
    assert!(
        err.contains("'simulate' cannot be used with '--preset"),
        "{err}"
    );
    // The subcommand's own flag is the way.
    let (code, out, _) = bin(&["simulate", "--preset", "supercritical", "--format", "json"]);
    assert_eq!(code, 0);
    assert!(out.contains("\"preset\": \"Supercritical start\""));
}

#[test]
fn replay_takes_the_look_flags() {
    let session = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/sessions/subcritical.jsonl"
    );
    let (code, out, err) = bin(&["replay", session, "--theme", "light", "--verify"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("reproduced bit for bit"), "{out}");
    let (code, _, err) = bin(&["replay", session, "--theme", "nope", "--verify"]);
    assert_eq!(code, 2, "a bad theme is still an error: {err}");
}

#[test]
fn methods_are_listed_in_help_and_matched_in_any_case() {
    let (code, out, _) = bin(&["simulate", "--help"]);
    assert_eq!(code, 0);
    assert!(out.contains("[possible values: auto, rk4, dop853"), "{out}");
    let (code, upper, err) = bin(&["simulate", "--method", "DOP853", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let (_, lower, _) = bin(&["simulate", "--method", "dop853", "--format", "json"]);
    let run = |s: &str| s.split("\"stats\"").next().unwrap().to_owned();
    assert_eq!(run(&upper), run(&lower), "the same run whatever the case");
    assert!(upper.contains("\"method\": \"dop853\""), "{upper}");
    let (code, _, err) = bin(&["simulate", "--method", "euler"]);
    assert_eq!(code, 2);
    assert!(err.contains("possible values: auto"), "{err}");
    // Presets too.
    let (code, out, err) = bin(&["simulate", "--set", "run.method=DOP853", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("\"method\": \"dop853\""), "{out}");
}

/// Every shell's script registers dynamic completion: the shell asks this program (with
/// `COMPLETE=SHELL`), so the script holds no names that could go stale.
#[test]
fn completions_for_every_shell_register_the_program() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let (code, out, err) = bin(&["completions", shell]);
        assert_eq!(code, 0, "{shell}: {err}");
        assert!(out.contains("COMPLETE"), "{shell}: {out}");
        assert!(
            out.contains(env!("CARGO_BIN_EXE_rattleback")),
            "{shell}: {out}"
        );
        assert!(
            !out.contains("subcritical"),
            "{shell}: names are asked, not frozen"
        );
    }
    let (code, _, err) = bin(&["completions", "tcsh"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn the_manual_page_is_whole_and_man_has_no_warnings() {
    let (code, out, err) = bin(&["man"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains(".TH rattleback 1"), "{out}");
    for section in [
        "NAME",
        "SYNOPSIS",
        "OPTIONS",
        "COMMANDS",
        "KEYS",
        "ENVIRONMENT",
        "FILES",
        "EXIT STATUS",
        "EXAMPLES",
    ] {
        assert!(
            out.lines()
                .any(|l| l == format!(".SH {section}") || l == format!(".SH \"{section}\"")),
            "section {section} missing"
        );
    }
    // No page it names is missing: it names none but itself.
    assert!(!out.contains("(1)"), "refers to other pages");
    // Every subcommand has its subsection, the nested ones too.
    let cmd = <rattleback::cli::Cli as clap::CommandFactory>::command();
    for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
        let name = format!(".SS \"rattleback {}\"", sub.get_name());
        assert!(out.contains(&name), "{name} missing");
        for nested in sub.get_subcommands().filter(|s| s.get_name() != "help") {
            let name = format!(
                ".SS \"rattleback {} {}\"",
                sub.get_name(),
                nested.get_name()
            );
            assert!(out.contains(&name), "{name} missing");
        }
    }
    // The keys come from the keymap: every labelled binding's help is there.
    for b in rattleback::app::keys::KEYMAP
        .iter()
        .filter(|b| !b.label.is_empty())
    {
        let help = b.help.replace('-', "\\-");
        assert!(out.contains(&help), "key help {:?} missing", b.help);
    }
    for (var, _) in rattleback::manual::ENVIRONMENT {
        assert!(out.contains(var), "{var} missing");
    }
    // `--help` carries the same examples, environment and exit codes.
    let (code, help, _) = bin(&["--help"]);
    assert_eq!(code, 0);
    for (line, _) in rattleback::manual::EXAMPLES
        .iter()
        .chain(rattleback::manual::ENVIRONMENT)
        .chain(rattleback::manual::EXIT_STATUS)
    {
        assert!(help.contains(line), "--help lacks {line}");
    }
    assert!(help.contains("Exit status:") && help.contains("Environment:"));
    // man --warnings: silent on this page.
    let page = std::env::temp_dir().join(format!("rattleback-{}.1", std::process::id()));
    std::fs::write(&page, &out).unwrap();
    // Under a UTF-8 locale and under LANG=C (where groff has no ellipsis and no combining dot).
    for locale in ["C.UTF-8", "C"] {
        let run = crate::common::detached("man")
            .args(["--warnings", "-l"])
            .arg(&page)
            .env("MANWIDTH", "80")
            .env("MANPAGER", "cat")
            .env("PAGER", "cat")
            .env_remove("LC_ALL")
            .env_remove("LC_CTYPE")
            .env("LANG", locale)
            .output();
        match run {
            Ok(o) => {
                assert!(
                    o.status.success(),
                    "man failed: {}",
                    String::from_utf8_lossy(&o.stderr)
                );
                let warnings = String::from_utf8_lossy(&o.stderr);
                assert!(
                    warnings.trim().is_empty(),
                    "LANG={locale} man --warnings:\n{warnings}"
                );
                let text = String::from_utf8_lossy(&o.stdout);
                assert!(text.contains("EXIT STATUS"), "{text}");
            }
            // .ci/run installs man-db; a developer machine without it still runs the rest.
            Err(e) => eprintln!("man is not installed ({e}): the page was not formatted"),
        }
    }
    std::fs::remove_file(&page).ok();
}

#[test]
fn presets_show_prints_a_preset_to_copy_and_themes_lists_themes() {
    let (code, out, err) = bin(&["presets", "show", "just-below"]);
    assert_eq!(code, 0, "{err}");
    let shown = rattleback::scenario::Preset::parse(&out, "shown", "just-below", &[]).unwrap();
    let shipped = rattleback::scenario::shipped::resolve("just-below", &[]).unwrap();
    assert_eq!(shown, shipped, "what is printed is the preset itself");
    let (code, out, err) = bin(&["presets", "show", "nope"]);
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert!(err.contains("no preset named or at 'nope'"), "{err}");
    // The list still works as before.
    let (code, out, _) = bin(&["presets", "--format", "json"]);
    assert_eq!(code, 0);
    assert!(out.contains("\"name\": \"subcritical\""));

    let (code, out, err) = bin(&["themes", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let list: serde_json::Value = serde_json::from_str(&out).unwrap();
    let names: Vec<&str> = list["themes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["default", "dark", "light", "high-contrast"]);
    for key in ["title", "source", "path", "description"] {
        assert!(list["themes"][0].get(key).is_some(), "{key}");
    }
    let (code, out, _) = bin(&["themes"]);
    assert_eq!(code, 0);
    assert!(out.contains("high-contrast"));
}

/// A reader that goes away (`| head -1`) ends a printing command quietly, with success: every
/// line goes through one `say`, which used to be `println!` and panicked on the broken pipe.
/// The read end is closed right after the start, long before the first line is written.
#[test]
fn a_closed_pipe_ends_printing_commands_quietly() {
    let session = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/sessions/lecture.jsonl"
    );
    for args in [
        vec!["replay", session, "--verify"],
        vec!["presets"],
        vec!["lessons"],
    ] {
        let mut child = crate::common::rattleback()
            .args(&args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(out.status.code(), Some(0), "{args:?}: {err}");
    }
}

/// Issue 28: `-` is standard input wherever a file is read headless (a preset for `simulate`,
/// `study` and `presets show`, `check`, a session for `replay --verify`/`--chapters`), named
/// `stdin` in messages; where the explorer opens, `-` is refused (it reads its keys there).
#[test]
fn a_dash_reads_standard_input_where_a_file_is_read_headless() {
    use std::io::Write as _;
    let with_stdin = |args: &[&str], input: &[u8]| -> (i32, String, String) {
        let mut child = crate::common::rattleback()
            .args(args)
            .env("TERM", "xterm")
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        // A refusal may exit before reading: a closed pipe is not a failure of the test.
        let _ = child.stdin.take().unwrap().write_all(input);
        let out = child.wait_with_output().unwrap();
        (
            out.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let preset = rattleback::scenario::shipped::source_text("supercritical").unwrap();
    let from_file = crate::common::simulate_json(&["--preset", "supercritical", "--t-end", "2"]);
    let (code, out, err) = with_stdin(
        &[
            "simulate", "--preset", "-", "--t-end", "2", "--format", "json",
        ],
        preset.as_bytes(),
    );
    assert_eq!(code, 0, "{err}");
    let from_stdin: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(from_stdin["final"], from_file["final"], "the same run");
    let (code, out, _) = with_stdin(&["presets", "show", "-"], preset.as_bytes());
    assert_eq!((code, out.as_str()), (0, preset.as_str()));
    // Errors name stdin and the line.
    let (code, _, err) = with_stdin(
        &["check", "-"],
        b"[preset]\nname = \"x\"\n[spring]\nk = -1\n",
    );
    assert_eq!(code, 2);
    assert!(err.contains("stdin:4: spring.k"), "{err}");
    let session = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/sessions/subcritical.jsonl"
    ))
    .unwrap();
    let (code, out, err) = with_stdin(&["replay", "-", "--verify"], &session);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("stdin: 4 checkpoint(s) reproduced bit for bit"),
        "{out}"
    );
    // Where the explorer opens, `-` is refused before anything is read.
    for args in [
        &["--preset", "-"][..],
        &["replay", "-"],
        &["lesson", "-"],
        &["compare", "-", "subcritical"],
        &["follow", "-"],
    ] {
        let (code, _, err) = with_stdin(args, b"");
        assert_eq!(code, 2, "{args:?}");
        assert!(
            err.contains("reads its keys from standard input"),
            "{args:?}: {err}"
        );
    }
}

/// Issue 28: one error style. Whatever fails (clap's parsing, a preset, a session, a check, a
/// terminal, a study), stderr's first line is `rattleback: error: …`, and the exit status is
/// the documented one.
#[test]
fn every_failure_speaks_in_one_style() {
    let junk = std::env::temp_dir().join(format!("rattleback-style-{}.jsonl", std::process::id()));
    std::fs::write(&junk, "not a session\n").unwrap();
    let j = junk.to_str().unwrap();
    let bad = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/bad/k-zero.toml"
    );
    let cases: &[(&[&str], i32)] = &[
        (&["--frob"], 2),
        (&["simulate", "--method", "nope"], 2),
        (&["simulate", "--preset", "nonesuch"], 2),
        (&["simulate", "--preset", bad], 2),
        (
            &[
                "simulate",
                "--set",
                "spring.k=1e12",
                "--t-end",
                "1e9",
                "--method",
                "rk4",
            ],
            2,
        ),
        (&["replay", j, "--verify"], 2),
        (&["check", bad], 2),
        (&["--config", "/nonexistent.toml", "simulate"], 2),
        (&["study", "map", "--preset", "kapitza-upright"], 2),
        (&["study"], 2),
        (&["presets", "show", "nonesuch"], 2),
        (&["completions", "tcsh"], 2),
    ];
    for (args, want) in cases {
        let (code, _, err) = bin(args);
        assert_eq!(code, *want, "{args:?}: {err}");
        let first = err.lines().next().unwrap_or_default();
        assert!(
            first.starts_with("rattleback: error: "),
            "{args:?}: first line {first:?}"
        );
    }
    // The explorer without a terminal, and under TERM=dumb.
    let out = crate::common::rattleback()
        .env("TERM", "dumb")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("rattleback: error: TERM=dumb"), "{err}");
    std::fs::remove_file(&junk).ok();
}
