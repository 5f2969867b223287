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
    let session = concat!(root!(), "/tests/fixtures/sessions/subcritical.jsonl");
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
        // By name (issue 81, D-9): a script that named the binary's path broke when it moved.
        assert!(out.contains("rattleback"), "{shell}: {out}");
        assert!(
            !out.contains(crate::common::program()),
            "{shell}: the script names the build's path"
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
    let cmd = <rattleback::commands::cli::Cli as clap::CommandFactory>::command();
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
    for (var, _) in rattleback::commands::manual::ENVIRONMENT {
        assert!(out.contains(var), "{var} missing");
    }
    // `--help` carries the same examples, and says the manual has the environment and the
    // exit codes (issue 68: two screens at 80 columns).
    let (code, help, _) = bin(&["--help"]);
    assert_eq!(code, 0);
    for (line, _) in rattleback::commands::manual::EXAMPLES {
        assert!(help.contains(line), "--help lacks {line}");
        // roff escapes `-` as `\-`.
        assert!(
            out.replace("\\-", "-").contains(line),
            "the manual lacks {line}"
        );
    }
    assert!(
        help.contains("environment, exit status: rattleback man"),
        "{help}"
    );
    for (line, _) in rattleback::commands::manual::ENVIRONMENT
        .iter()
        .chain(rattleback::commands::manual::EXIT_STATUS)
    {
        assert!(
            out.replace("\\-", "-").contains(line),
            "the manual lacks {line}"
        );
    }
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
    let session = concat!(root!(), "/tests/fixtures/sessions/lecture.jsonl");
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
        root!(),
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
    let bad = concat!(root!(), "/tests/fixtures/bad/k-zero.toml");
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
        (
            &["study", "map", "--preset", "kapitza-upright", "--k", "1e4"],
            2,
        ),
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

/// Every `--flag` a command's help mentions is one of that command's options, unless it is
/// written after another command's name (`replay --verify --key NAME.pub`): issue 54 found
/// `study sweep --help` pointing at a `--samples` it refuses, and `--export-cast` in the
/// explorer's help. Every example of `--help` and the manual parses, and the headless ones run
/// and succeed.
#[test]
fn every_help_text_is_true() {
    let root = rattleback::commands::cli::command();
    // (path, command) for every command and subcommand.
    let mut all = vec![(Vec::<String>::new(), root.clone())];
    let mut i = 0;
    while i < all.len() {
        let (path, cmd) = all[i].clone();
        for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
            let mut p = path.clone();
            p.push(sub.get_name().to_owned());
            all.push((p, sub.clone()));
        }
        i += 1;
    }
    let longs = |cmd: &clap::Command| -> Vec<String> {
        cmd.get_arguments()
            .filter_map(|a| a.get_long().map(|l| format!("--{l}")))
            .chain(["--help".to_owned(), "--version".to_owned()])
            .collect()
    };
    let find = |name: &str| {
        all.iter()
            .find(|(p, _)| p.last().is_some_and(|l| l == name))
    };
    let mut wrong = Vec::new();
    for (path, cmd) in &all {
        // Unwrapped (a wrapped line would part a flag from the command it belongs to).
        let mut cmd = cmd.clone().term_width(0);
        let help = cmd.render_long_help().to_string();
        let own = longs(&cmd);
        for line in help.lines() {
            // The command a flag belongs to: the last command name written before it on the
            // line (`rattleback replay FILE --verify`, `` `replay --verify` ``), else this one.
            let mut owner: Option<&clap::Command> = None;
            for word in line.split(|c: char| c.is_whitespace() || c == '`' || c == '(') {
                if let Some((_, c)) = find(word) {
                    owner = Some(c);
                    continue;
                }
                let Some(flag) = word
                    .trim_end_matches(|c: char| !c.is_ascii_alphanumeric())
                    .strip_prefix("--")
                else {
                    continue;
                };
                if flag.is_empty() || !flag.chars().next().unwrap().is_ascii_lowercase() {
                    continue;
                }
                let flag = format!("--{flag}");
                let known = match owner {
                    Some(c) => longs(c).contains(&flag),
                    None => own.contains(&flag) || longs(&root).contains(&flag),
                };
                if !known {
                    wrong.push(format!("{path:?}: {flag} in: {}", line.trim()));
                }
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "help texts name options that are not there:\n{}",
        wrong.join("\n")
    );
    // Every example parses; the headless ones run.
    let dir = std::env::temp_dir().join(format!("rattleback-examples-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (line, _) in rattleback::commands::manual::EXAMPLES {
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some(at) = words.iter().position(|w| w.ends_with("rattleback")) else {
            continue;
        };
        let args: Vec<&str> = words[at..]
            .iter()
            .map(|w| w.trim_end_matches(')'))
            .collect();
        let parsed = <rattleback::commands::cli::Cli as clap::Parser>::try_parse_from(&args);
        assert!(
            parsed.is_ok(),
            "{line}: {:?}",
            parsed.err().map(|e| e.to_string())
        );
        let headless = [
            "simulate",
            "study",
            "completions",
            "presets",
            "check",
            "man",
        ];
        if args.get(1).is_some_and(|a| headless.contains(a)) {
            let (code, _, err) = crate::common::bin_in(&dir, &args[1..]);
            assert_eq!(code, 0, "{line}: {err}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// clap's "a similar argument exists" tip only where the argument is close to a typo:
/// `--bogus` is not `--mouse` (issue 54), `--presett` is `--preset`.
#[test]
fn the_parser_suggests_only_what_is_close() {
    let (code, _, err) = bin(&["--bogus"]);
    assert_eq!(code, 2);
    assert!(!err.contains("--mouse") && !err.contains("tip"), "{err}");
    assert!(err.contains("Usage: rattleback [OPTIONS]"), "{err}");
    let (code, _, err) = bin(&["--presett", "x"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("tip: a similar argument exists: '--preset'"),
        "{err}"
    );
    let (_, _, err) = bin(&["simulate", "--tolerence", "1e-6"]);
    assert!(err.contains("'--tolerance'"), "{err}");
}

/// Every command reads the configuration the same way: a broken `--config` is refused by
/// `presets` and `simulate` as by the explorer, every problem with its `file:line` in one run,
/// the unknown theme among them (issue 54: said last, without a line; `presets` said nothing).
#[test]
fn every_command_refuses_a_broken_config_with_every_problem() {
    let dir = std::env::temp_dir().join(format!("rattleback-brokenconf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.toml");
    std::fs::write(
        &file,
        "theme = \"nope\"\nfsp = 20\n[keys]\nzoom_in = \"j\"\n",
    )
    .unwrap();
    let f = file.to_str().unwrap();
    for args in [
        vec!["--config", f, "presets"],
        vec!["--config", f, "simulate"],
        vec!["--config", f, "lessons"],
        vec!["--config", f, "study", "sweep"],
        vec!["--config", f, "config", "show"],
        vec!["--config", f],
    ] {
        let (code, out, err) = crate::common::bin_in(&dir, &args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}: {out}");
        for at in [":1: theme", ":2: fsp", ":4: keys.zoom_in"] {
            assert!(err.contains(at), "{args:?} lacks {at}: {err}");
        }
    }
    // doctor reports it, whole, and exits 0.
    let (code, out, _) = crate::common::bin_in(&dir, &["--config", f, "doctor"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("invalid") && out.contains(":4: keys.zoom_in"),
        "{out}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The lists line up whatever the names' lengths (issue 54: `kapitza-threshold shipped` one
/// column right of the others).
#[test]
fn list_columns_line_up() {
    for list in ["lessons", "presets", "themes"] {
        let (code, out, err) = bin(&[list]);
        assert_eq!(code, 0, "{err}");
        let columns: std::collections::BTreeSet<usize> = out
            .lines()
            .filter(|l| !l.is_empty() && !l.starts_with(' '))
            .map(|l| l.find(" shipped").or_else(|| l.find(" user")).unwrap_or(0))
            .collect();
        assert_eq!(columns.len(), 1, "{list}: the source column moves:\n{out}");
    }
}

/// Issue 68: a global flag before its command is refused with the order that works, written
/// out to copy.
#[test]
fn a_flag_before_its_command_is_told_the_order_that_works() {
    let (code, _, err) = bin(&["--preset", "supercritical", "simulate", "--format", "json"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("tip: a command's flags go after its name: `rattleback simulate --preset supercritical --format json`"),
        "{err}"
    );
    // What the tip says runs.
    let (code, _, err) = bin(&["simulate", "--preset", "supercritical", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    // A word with a space is quoted for the shell.
    let (_, _, err) = bin(&["--preset", "my preset.toml", "simulate"]);
    assert!(
        err.contains("`rattleback simulate --preset 'my preset.toml'`"),
        "{err}"
    );
}

/// Issue 68: `--help` wraps to the terminal (clap's `wrap_help`, `COLUMNS` as a terminal sets
/// it): at 80 columns no line is longer, the top level fits in two screens, and every
/// subcommand ends with examples that parse.
#[test]
fn help_fits_80_columns_and_ends_with_examples() {
    let help = |args: &[&str]| {
        let out = common::rattleback()
            .args(args)
            .env("COLUMNS", "80")
            .env("LINES", "24")
            .output()
            .unwrap();
        assert!(out.status.success(), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    for flag in ["--help", "-h"] {
        let text = help(&[flag]);
        let long: Vec<&str> = text.lines().filter(|l| l.chars().count() > 80).collect();
        assert!(
            long.is_empty(),
            "rattleback {flag}: over 80 columns: {long:?}"
        );
        let n = text.lines().count();
        assert!(
            n <= 48,
            "rattleback {flag} is {n} lines, more than two 24-line screens"
        );
        assert!(text.contains("Examples:"), "{text}");
    }
    let root = rattleback::commands::cli::command();
    for sub in root.get_subcommands().filter(|s| s.get_name() != "help") {
        let name = sub.get_name();
        let text = help(&[name, "--help"]);
        let long: Vec<&str> = text.lines().filter(|l| l.chars().count() > 80).collect();
        assert!(
            long.is_empty(),
            "rattleback {name} --help: over 80 columns: {long:?}"
        );
        let examples = text
            .split("Examples:\n")
            .nth(1)
            .unwrap_or_else(|| panic!("rattleback {name} --help has no examples:\n{text}"));
        assert!(
            examples.contains(&format!("rattleback {name}")),
            "{name}: {examples}"
        );
    }
    // Every example is a command the parser takes.
    let all = rattleback::commands::manual::EXAMPLES.iter().chain(
        rattleback::commands::manual::SUBCOMMAND_EXAMPLES
            .iter()
            .flat_map(|(_, rows)| rows.iter()),
    );
    for (line, _) in all {
        let words: Vec<&str> = line
            .trim_start_matches("source <(")
            .trim_end_matches(')')
            .split(" > ")
            .next()
            .unwrap()
            .split(" && ")
            .next()
            .unwrap()
            .split_whitespace()
            .collect();
        assert_eq!(words[0], "rattleback", "{line}");
        if let Err(e) = rattleback::commands::cli::parse_from(&words) {
            assert!(
                matches!(e.kind(), clap::error::ErrorKind::DisplayHelp),
                "the example `{line}` does not parse: {e}"
            );
        }
    }
}

/// Issue 68: a preset with several problems is refused by `simulate` with every one, as
/// `check` lists them, each on its own line.
#[test]
fn simulate_says_every_problem_of_a_preset_as_check_does() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(
        &file,
        "[preset]\nname = \"x\"\n[body]\nix = -1\niy = \"a\"\nfoo = 1\n",
    )
    .unwrap();
    let path = file.to_str().unwrap();
    let (code, _, simulate) = bin(&["simulate", "--preset", path]);
    assert_eq!(code, 2);
    let (code, _, check) = bin(&["check", path]);
    assert_eq!(code, 2);
    let lines = |text: &str| -> Vec<String> {
        text.lines()
            .map(|l| l.trim_start_matches("rattleback: error: ").to_owned())
            .collect()
    };
    assert!(lines(&simulate).len() >= 4, "{simulate}");
    assert_eq!(
        lines(&simulate),
        lines(&check),
        "simulate:\n{simulate}\ncheck:\n{check}"
    );
    // A list in an error is cut between names, never inside one.
    let (_, _, err) = bin(&["simulate", "--preset", "subcritcal"]);
    let names: Vec<String> = rattleback::scenario::shipped::SHIPPED
        .iter()
        .map(|(n, _)| (*n).to_owned())
        .collect();
    let list = err
        .split("available: ")
        .nth(1)
        .unwrap()
        .split("; did you mean")
        .next()
        .unwrap();
    let list: String = match (list.find(" … ("), list.rfind(") … ")) {
        (Some(a), Some(b)) => format!("{}, {}", &list[..a], &list[b + 5..]),
        _ => list.to_owned(),
    };
    for word in list.split([',', ' ']).filter(|w| {
        w.len() > 3 && !w.contains('…') && w.chars().all(|c| c.is_ascii_lowercase() || c == '-')
    }) {
        assert!(
            names.iter().any(|n| n == word),
            "`{word}` is not a whole name: {err}"
        );
    }
}

/// Issue 68: every scene's CSV names its model (the rattleback's had no `# model` line), and
/// the pendulum's table prints an event's times only when there are some.
#[test]
fn every_csv_names_its_model_and_no_table_line_is_empty() {
    for (preset, model) in [
        ("subcritical", "rattleback"),
        ("kapitza-upright", "kapitza"),
        ("celt-clockwise", "celt"),
    ] {
        let (code, out, err) = bin(&[
            "simulate",
            "--preset",
            preset,
            "--format",
            "csv",
            "--samples",
            "3",
        ]);
        assert_eq!(code, 0, "{err}");
        assert!(
            out.lines().any(|l| l == format!("# model = {model}")),
            "{preset}: {out}"
        );
        let (_, table, _) = bin(&["simulate", "--preset", preset]);
        for line in table.lines() {
            assert!(
                !(line.trim().ends_with(" at")),
                "{preset}: an empty line of times: `{line}`\n{table}"
            );
        }
    }
}

/// Issue 68: the lists say a shipped file is built in, and how to see it, instead of a path in
/// the source tree that an installed binary does not have.
#[test]
fn lists_say_shipped_files_are_built_in() {
    for (args, show) in [
        (
            &["presets"][..],
            "built in (rattleback presets show subcritical)",
        ),
        (
            &["lessons"][..],
            "built in (rattleback lessons show first-reversal)",
        ),
        (&["themes"][..], "built in (rattleback themes show default)"),
    ] {
        let (code, out, err) = bin(args);
        assert_eq!(code, 0, "{err}");
        assert!(out.contains(show), "{args:?}: {out}");
        for dir in ["presets/", "lessons/", "themes/"] {
            assert!(
                !out.lines().any(|l| l.trim_start().starts_with(dir)),
                "{args:?} prints a source-tree path: {out}"
            );
        }
    }
}
