//! Habits of the test suite itself: it runs wherever `cargo test` is typed (a terminal, under
//! `timeout`, over `ssh -t`, CI) and never touches the terminal it runs in.

/// Every process a test starts goes through `common::detached` (a session of its own, no
/// controlling terminal): one `Command::new` in the whole suite. A child that reached the
/// developer's `/dev/tty` once put it in raw mode and waited for keys (issue 54).
#[test]
fn tests_start_processes_only_through_common() {
    let root = std::path::Path::new(root!());
    let mut offenders = Vec::new();
    for dir in ["tests", "examples"] {
        for path in rust_files(&root.join(dir)) {
            // tests/built.rs is the program's own test target (it cannot reach `common`): it
            // runs `rattleback --version` with no terminal, and nothing else.
            if path.ends_with("tests/it/common/mod.rs")
                || path.ends_with("tests/it/hygiene.rs")
                || path.ends_with("tests/built.rs")
            {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            for (i, line) in text.lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                if code.contains("Command::new(") || code.contains("process::Command") {
                    offenders.push(format!(
                        "{}:{}: {}",
                        path.strip_prefix(root).unwrap().display(),
                        i + 1,
                        line.trim()
                    ));
                }
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "start processes with common::detached or common::rattleback:\n{}",
        offenders.join("\n")
    );
}

/// A child started by a test has no controlling terminal: `/dev/tty` cannot be opened.
#[test]
fn a_detached_child_has_no_terminal() {
    let out = crate::common::detached("sh")
        .args([
            "-c",
            "if true 3</dev/tty 2>/dev/null; then echo reached; else echo none; fi",
        ])
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        "none",
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn rust_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return out;
    };
    for entry in entries.filter_map(Result::ok) {
        let path = entry.path();
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out
}

/// The interactive commands, as a user types them.
const INTERACTIVE: &[&[&str]] = &[
    &[],
    &["--preset", "kapitza-upright"],
    &["compare", "subcritical", "celt-clockwise"],
    &["lesson", "first-reversal"],
    &["replay", "tests/fixtures/sessions/lecture.jsonl"],
    &["follow", "tests/fixtures/sessions/lecture.jsonl"],
];

/// Waits at most `limit` for `child`; kills it and fails past that.
#[track_caller]
fn finish(mut child: std::process::Child, limit: std::time::Duration, what: &str) -> i32 {
    let start = std::time::Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status.code().unwrap_or(-1);
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{what}: still running after {limit:?}");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// `rattleback compare A B > out.txt` (and every other interactive command): refused in one line,
/// exit 2, nothing written into the file, at once (issue 54: 3–11 kB of escape codes and a raw
/// terminal).
#[test]
fn interactive_commands_refuse_a_redirected_output() {
    let dir = std::env::temp_dir().join(format!("rattleback-redirect-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (i, args) in INTERACTIVE.iter().enumerate() {
        let out = dir.join(format!("out{i}.txt"));
        let err = dir.join(format!("err{i}.txt"));
        let child = crate::common::rattleback()
            .args(*args)
            .current_dir(root!())
            .env("RATTLEBACK_CONFIG_DIR", &dir)
            .stdin(std::process::Stdio::null())
            .stdout(std::fs::File::create(&out).unwrap())
            .stderr(std::fs::File::create(&err).unwrap())
            .spawn()
            .unwrap();
        let code = finish(
            child,
            std::time::Duration::from_secs(20),
            &format!("{args:?}"),
        );
        let said = std::fs::read_to_string(&err).unwrap();
        assert_eq!(code, 2, "{args:?}: {said}");
        assert_eq!(
            std::fs::metadata(&out).unwrap().len(),
            0,
            "{args:?} wrote into the file"
        );
        assert_eq!(said.lines().count(), 1, "{args:?}: {said}");
        assert!(
            said.contains("standard output is not one"),
            "{args:?}: {said}"
        );
    }
}

/// In a terminal of its own (`script`) but with standard input redirected: refused, and the
/// terminal is never switched to the alternate screen.
#[test]
fn interactive_commands_refuse_a_redirected_input() {
    let dir = std::env::temp_dir().join(format!("rattleback-redirect-in-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (i, args) in INTERACTIVE.iter().enumerate() {
        let log = dir.join(format!("pty{i}.out"));
        let command = format!(
            "exec {} {} < /dev/null",
            crate::common::program(),
            args.join(" ")
        );
        let child = crate::common::detached("script")
            .args(["-qec", &command])
            .arg(&log)
            .current_dir(root!())
            .env("RATTLEBACK_CONFIG_DIR", &dir)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("`script` (util-linux) gives the command a pseudo-terminal");
        let code = finish(
            child,
            std::time::Duration::from_secs(20),
            &format!("{args:?}"),
        );
        let seen = String::from_utf8_lossy(&std::fs::read(&log).unwrap()).into_owned();
        assert_eq!(code, 2, "{args:?}: {seen}");
        assert!(
            seen.contains("standard input is not one"),
            "{args:?}: {seen}"
        );
        assert!(
            !seen.contains("\u{1b}[?1049h"),
            "{args:?} entered the alternate screen"
        );
    }
}

/// Issue 56: `unsafe` code lives in one module, `src/fault.rs` (a handler for SIGSEGV, SIGILL and
/// SIGFPE, which no safe interface installs); `Cargo.toml` denies it and no other file allows it.
#[test]
fn unsafe_code_lives_in_the_faults_module_only() {
    let root = std::path::Path::new(root!());
    let mut found = Vec::new();
    for dir in ["src", "tests", "examples"] {
        for file in rust_files(&root.join(dir)) {
            let text = std::fs::read_to_string(&file).unwrap();
            let uses = text.lines().any(|l| {
                let code = l.split("//").next().unwrap_or("");
                code.contains("unsafe ") || code.contains("unsafe{") || code.contains("unsafe_code")
            });
            if uses {
                found.push(file.strip_prefix(root).unwrap().display().to_string());
            }
        }
    }
    // This file names the lint in its checks.
    found.retain(|f| f != "tests/it/hygiene.rs");
    assert_eq!(found, ["src/fault.rs"]);
    // Issue 82: the browser's module exports its functions by name, an attribute Rust calls
    // unsafe (`#[unsafe(no_mangle)]`); that attribute, under one allowance, is all it has.
    for file in rust_files(&root.join("web")) {
        let text = std::fs::read_to_string(&file).unwrap();
        for l in text.lines() {
            let code = l.split("//").next().unwrap_or("").trim();
            if code.contains("unsafe") {
                assert!(
                    code == "#[unsafe(no_mangle)]" || code == "#[allow(unsafe_code)]",
                    "{}: {code}",
                    file.display()
                );
            }
        }
    }
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    assert!(
        manifest.contains("unsafe_code = \"deny\""),
        "the lint is denied"
    );
}

/// Issue 56 (R3, R11): a headless command stops within its watchdog's grace whatever it is
/// doing, here blocked reading standard input (`replay - --verify` of a pipe nobody writes),
/// and says it was interrupted: exit 128 + n.
#[test]
fn a_headless_command_blocked_anywhere_ends_within_the_grace_of_a_signal() {
    for (signal, n) in [("TERM", 15), ("USR1", 10), ("PWR", 30), ("40", 40)] {
        let mut child = crate::common::rattleback()
            .args(["replay", "-", "--verify"])
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(300));
        let ok = crate::common::detached("kill")
            .args([format!("-{signal}"), child.id().to_string()])
            .status()
            .unwrap()
            .success();
        assert!(ok, "kill -{signal}");
        // Without the watchdog it waited for its input for ever (a bound, not a speed target:
        // the grace is 60 ms).
        let code = finish_child(&mut child, std::time::Duration::from_secs(5));
        let mut err = String::new();
        std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut err).unwrap();
        assert_eq!(code, 128 + n, "SIG{signal}: {err}");
        assert!(err.contains("interrupted"), "SIG{signal}: {err}");
    }
}

fn finish_child(child: &mut std::process::Child, limit: std::time::Duration) -> i32 {
    let start = std::time::Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status.code().unwrap_or(-1);
        }
        assert!(start.elapsed() < limit, "did not end");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

/// Over ssh without `-t` (issue 68): neither standard stream is a terminal, and the refusal
/// names ssh's flag, the fix, rather than a redirection the user did not make.
#[test]
fn over_ssh_without_a_terminal_the_refusal_names_ssh_t() {
    let run = |args: &[&str], ssh: bool| {
        let mut command = crate::common::rattleback();
        if ssh {
            command.env("SSH_CONNECTION", "10.0.0.2 50000 10.0.0.1 22");
        }
        command
            .args(args)
            .env(
                "RATTLEBACK_CONFIG_DIR",
                std::env::temp_dir().join("rattleback-no-user-folder"),
            )
            .stdin(std::process::Stdio::null())
            .output()
            .unwrap()
    };
    for args in [
        &[][..],
        &["lesson", "first-reversal"][..],
        &["compare", "subcritical", "celt-clockwise"][..],
    ] {
        let out = run(args, true);
        let said = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {said}");
        assert!(said.contains("ssh -t HOST rattleback"), "{args:?}: {said}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // Without ssh the same run is told about its redirection.
    let out = run(&[], false);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("ssh"));
}

/// Issue 82: the program takes its elementary functions from one implementation on every
/// platform (`physics::numerics::elementary`), so the native build and the browser's module
/// compute the same bits; a call of the platform's `sin`, `ln`, `powf`, … anywhere else in the
/// program's code (tests aside) would part them again.
#[test]
fn elementary_functions_come_from_one_implementation() {
    const NAMES: &[&str] = &[
        "sin_cos", "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh",
        "asinh", "acosh", "atanh", "exp", "exp2", "exp_m1", "ln", "ln_1p", "log", "log2", "log10",
        "powf", "hypot", "cbrt",
    ];
    let root = std::path::Path::new(root!());
    let mut found = Vec::new();
    for dir in ["src", "web/src"] {
        for file in rust_files(&root.join(dir)) {
            // The scenes' contract impls are test code whose references are written apart from
            // the crate on purpose (the platform's functions, not the crate's portable ones).
            if file.ends_with("numerics/elementary.rs") || file.ends_with("contract.rs") {
                continue;
            }
            let text = std::fs::read_to_string(&file).unwrap();
            // The program's code: what comes before a file's test module.
            let program = text.split("#[cfg(test)]").next().unwrap_or("");
            for (n, line) in program.lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                for name in NAMES {
                    let call = format!(".{name}(");
                    let path = format!("f64::{name}");
                    let named_call = code.match_indices(&call).any(|(i, _)| {
                        // `self.log(…)` is the app's journal, not a logarithm.
                        !(*name == "log" && code[..i].ends_with("self"))
                    });
                    let as_path = code.match_indices(&path).any(|(i, _)| {
                        !code[i + path.len()..]
                            .starts_with(|c: char| c.is_alphanumeric() || c == '_')
                    });
                    if named_call || as_path {
                        found.push(format!(
                            "{}:{}: {}",
                            file.strip_prefix(root).unwrap().display(),
                            n + 1,
                            code.trim()
                        ));
                    }
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "the platform's elementary functions called:\n{}",
        found.join("\n")
    );
}

/// Issue 83: an allowance of a lint the workspace already allows does nothing and hides what
/// the file really allows; every `#[allow(…)]` in the project names a lint that would fire.
#[test]
fn no_allowance_repeats_the_workspaces() {
    let root = std::path::Path::new(root!());
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let table: toml::Table = manifest.parse().unwrap();
    let allowed: Vec<String> = table["workspace"]["lints"]["clippy"]
        .as_table()
        .unwrap()
        .iter()
        .filter(|(_, v)| v.as_str() == Some("allow"))
        .map(|(k, _)| format!("clippy::{k}"))
        .collect();
    assert!(
        allowed.iter().any(|l| l == "clippy::cast_precision_loss"),
        "{allowed:?}"
    );
    let mut inert = Vec::new();
    for dir in ["src", "tests", "examples", "benches", "web"] {
        for file in rust_files(&root.join(dir)) {
            let text = std::fs::read_to_string(&file).unwrap();
            for (n, line) in text.lines().enumerate() {
                let Some(at) = line.find("allow(") else {
                    continue;
                };
                let names = line[at + 6..].split(')').next().unwrap_or("");
                for name in names.split(',').map(str::trim) {
                    if allowed.iter().any(|a| a == name) {
                        let file = file.strip_prefix(root).unwrap().display();
                        inert.push(format!("{file}:{}: {name}", n + 1));
                    }
                }
            }
        }
    }
    // This file names them in its own check only through the manifest.
    assert!(
        inert.is_empty(),
        "allowances the workspace already gives:\n{}",
        inert.join("\n")
    );
}

/// Issue 83: errors callers match are typed (`thiserror`); a `Result<_, String>` is a message
/// for a person. Their number only goes down (45 at this writing, the goal 10).
#[test]
fn string_errors_only_go_down() {
    let root = std::path::Path::new(root!());
    let mut count = 0;
    for file in rust_files(&root.join("src")) {
        let text = std::fs::read_to_string(&file).unwrap();
        for line in text.lines() {
            let code = line.split("//").next().unwrap_or("");
            if let Some(at) = code.find("Result<") {
                let rest = &code[at..];
                let head = rest.split(['{', ';']).next().unwrap_or("");
                if head.contains(", String>") {
                    count += 1;
                }
            }
        }
    }
    assert!(count <= 10, "{count} Result<_, String> in src (at most 10)");
}

/// Issue 83: a scene is one folder (`physics/NAME/`, its contract impl and its report inside)
/// and one registry line. The test scene (the oscillator) is held to it:
/// outside those files and the contract that runs it, the one line of code that names it is its
/// registry line (comments aside). Adding a sixth scene the same way edits no shared file.
#[test]
fn the_test_scene_costs_its_folder_and_one_registry_line() {
    let root = std::path::Path::new(root!());
    let word = |code: &str| {
        code.match_indices("scillator").any(|(i, m)| {
            let before = code[..i].chars().last();
            let after = code[i + m.len()..].chars().next();
            matches!(before, Some('o' | 'O'))
                && !code[..i - 1].ends_with(|c: char| c.is_alphanumeric() || c == '_')
                && !after.is_some_and(|c| c.is_alphanumeric() || c == '_')
        })
    };
    let mut named = Vec::new();
    for file in rust_files(&root.join("src")) {
        let rel = file.strip_prefix(root).unwrap().display().to_string();
        if rel.starts_with("src/physics/oscillator/") || rel == "src/scene_contract.rs" {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            if word(code) {
                named.push(format!("{rel}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    assert_eq!(
        named,
        ["src/physics/models.rs:238: Oscillator: oscillator, CrossingChart;"],
        "the test scene is named outside its folder"
    );
}
