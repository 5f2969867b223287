//! Issue 28, item 2: completions that stay true. In bash, zsh and fish (each run for real when
//! installed; `.ci/run` installs zsh and fish), the script of `rattleback completions SHELL` is
//! sourced, then a preset is made in the user's folder, then the shell completes `--preset`,
//! `--theme`, `lesson` and `presets show`: shipped names, the new preset (made after the script
//! was sourced), themes and lessons come back; `follow` completes files, not `-`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn installed(shell: &str) -> bool {
    crate::common::detached(shell)
        .args(["-c", "exit 0"])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// A config folder with no user preset yet, and the preset file to copy in later.
fn folder(shell: &str) -> (PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("rattleback-compl-{shell}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("presets")).unwrap();
    let text = rattleback::scenario::shipped::source_text("subcritical")
        .unwrap()
        .replace("name = \"Subcritical start\"", "name = \"Made later\"");
    let later = dir.join("later.toml");
    std::fs::write(&later, text).unwrap();
    (dir, later)
}

/// Runs `script` in `shell` with the user's folder set; its standard output.
fn run(shell: &str, dir: &Path, script: &str) -> String {
    let out = crate::common::detached(shell)
        .args(if shell == "zsh" {
            vec!["-f", "-c", script]
        } else {
            vec!["-c", script]
        })
        .env("RATTLEBACK_CONFIG_DIR", dir)
        .current_dir(concat!(root!(), "/tests/fixtures/sessions"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{shell}: {}\n{text}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// The script for `shell`: source the registration, make the preset, then complete each of
/// `lines` (a command line whose last word is being completed), printing the candidates of
/// each after a `== LINE` header.
fn script(shell: &str, later: &Path, dir: &Path, lines: &[&str]) -> String {
    let copy = format!(
        "cp '{}' '{}'",
        later.display(),
        dir.join("presets/mine-later.toml").display()
    );
    let bin = crate::common::program();
    let mut s = match shell {
        "bash" => format!("source <('{bin}' completions bash --binary '{bin}')\n{copy}\n"),
        // compinit is interactive machinery: stand in for compdef and _describe, print what
        // the completer would offer.
        "zsh" => format!(
            "compdef() {{ : }}\n_describe() {{ print -l -- ${{(P)${{@[-1]}}}} }}\nsource <('{bin}' completions zsh --binary '{bin}')\n{copy}\n"
        ),
        _ => format!("'{bin}' completions fish --binary '{bin}' | source\n{copy}\n"),
    };
    for line in lines {
        let words: Vec<&str> = line.split(' ').collect();
        let _ = writeln!(s, "echo '== {line}'");
        match shell {
            "bash" => {
                let quoted: Vec<String> = words.iter().map(|w| format!("'{w}'")).collect();
                let _ = writeln!(
                    s,
                    "COMP_WORDS=({}); COMP_CWORD={}; COMP_TYPE=9; _clap_complete_rattleback rattleback '{}' '{}'; printf '%s\\n' \"${{COMPREPLY[@]}}\"",
                    quoted.join(" "),
                    words.len() - 1,
                    words[words.len() - 1],
                    words[words.len().saturating_sub(2)]
                );
            }
            "zsh" => {
                let quoted: Vec<String> = words.iter().map(|w| format!("'{w}'")).collect();
                let _ = writeln!(
                    s,
                    "words=({}); CURRENT={}; _clap_dynamic_completer_rattleback",
                    quoted.join(" "),
                    words.len()
                );
            }
            _ => {
                let _ = writeln!(s, "complete -C '{line}'");
            }
        }
    }
    s
}

/// The candidates printed under `== line`, names only.
fn offered<'a>(out: &'a str, line: &str) -> Vec<&'a str> {
    let start = out
        .find(&format!("== {line}\n"))
        .unwrap_or_else(|| panic!("no {line} in {out}"))
        + line.len()
        + 4;
    out[start..]
        .lines()
        .take_while(|l| !l.starts_with("== "))
        .map(|l| l.split(['\t', ':']).next().unwrap_or(""))
        .collect()
}

#[test]
fn bash_zsh_and_fish_complete_names_made_after_the_script_was_sourced() {
    let lines = [
        "rattleback --preset sub",
        "rattleback --preset mine",
        "rattleback simulate --preset kapitza-up",
        "rattleback --theme high",
        "rattleback lesson first",
        "rattleback presets show stiff-",
        "rattleback follow lec",
    ];
    let mut ran = 0;
    for shell in ["bash", "zsh", "fish"] {
        if !installed(shell) {
            eprintln!("{shell} is not installed here: not checked (.ci/run installs it)");
            continue;
        }
        ran += 1;
        let (dir, later) = folder(shell);
        let out = run(shell, &dir, &script(shell, &later, &dir, &lines));
        let want: [(&str, &[&str]); 7] = [
            (lines[0], &["subcritical"]),
            (lines[1], &["mine-later"]),
            (lines[2], &["kapitza-upright"]),
            (lines[3], &["high-contrast"]),
            (lines[4], &["first-reversal"]),
            (lines[5], &["stiff-spring", "stiff-limit"][..1]),
            (lines[6], &["lecture.jsonl"]),
        ];
        for (line, names) in want {
            let got = offered(&out, line);
            for n in names {
                assert!(
                    got.contains(n),
                    "{shell}: `{line}` offered {got:?}, not {n}\n{out}"
                );
            }
            assert!(!got.contains(&"-"), "{shell}: `{line}` offered '-'");
        }
        std::fs::remove_dir_all(&dir).ok();
    }
    // bash is part of every CI image; at least it ran.
    assert!(ran >= 1, "no shell to complete in");
}

/// D-9 (issue 81): the script calls `rattleback` by name unless asked otherwise, so a binary
/// moved, installed or packaged (its scripts generated from a staged copy) still completes;
/// `--binary PATH` names one that is not on PATH.
#[test]
fn the_scripts_call_the_program_by_name_unless_asked() {
    let bin = crate::common::program();
    for shell in ["bash", "zsh", "fish"] {
        let (code, script, err) = crate::common::bin(&["completions", shell]);
        assert_eq!(code, 0, "{err}");
        assert!(!script.contains(bin), "{shell}: the script names {bin}");
        assert!(script.contains("rattleback"), "{shell}");
        let (code, named, err) = crate::common::bin(&["completions", shell, "--binary", bin]);
        assert_eq!(code, 0, "{err}");
        assert!(named.contains(bin), "{shell}: --binary not used");
    }
}
