//! Every command the README and the docs show is one a user can type (issue 68): each shell
//! line of a ` ```sh ` block and each `` `cargo …` `` in the prose is read as cargo or the
//! program would read it, and the ones that run quickly and headless are run, a block at a time
//! in a scratch home of its own; each ` ```text ` block that opens with `$ rattleback …` is that
//! command's output, run again and compared.
//!
//! How a command is checked:
//! - `cargo test`, `run`, `bench`, `build`, `install`: its flags are cargo's, at most one test
//!   filter before `--`, every `--test`, `--example`, `--bench` and `--features` names one this
//!   package has, and a filter of the `it` suite selects a test (`it --list`, this very binary);
//!   a `--lib` filter names a unit test's path. `cargo run -- ARGS` is checked as `rattleback ARGS`.
//! - `rattleback …`: parsed by the program's own parser (`Cli`); the headless commands that take
//!   under a few seconds are run and must exit 0 (`> FILE` writes the file); the ones that need a
//!   terminal, a live recording or minutes (`bench`) are parsed only.
//! - Anything else (`tmux`, `echo`, `parallel`, a loop) is the shell's, not checked.

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(root!())
}

/// README.md and every page under docs/ (the changelog is history: it keeps old commands).
fn pages() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|x| x == "md") {
                out.push(path);
            }
        }
    }
    let mut out = vec![root().join("README.md")];
    walk(&root().join("docs"), &mut out);
    out
}

/// Where a command was found, for the failure message.
#[derive(Clone, Debug)]
struct Place {
    file: String,
    line: usize,
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.file, self.line)
    }
}

/// A shell block: its commands in order.
struct Block {
    place: Place,
    lines: Vec<(Place, String)>,
}

/// A text block that opens with `$ rattleback …`: the command and the output shown.
struct Sample {
    place: Place,
    command: String,
    shown: String,
}

#[derive(Default)]
struct Found {
    blocks: Vec<Block>,
    inline: Vec<(Place, String)>,
    samples: Vec<Sample>,
}

fn relative(path: &Path) -> String {
    path.strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string()
}

/// The comment of a shell line cut off: a `#` that starts a word outside quotes.
fn strip_comment(line: &str) -> String {
    let mut out = String::new();
    let mut quote = None;
    let mut previous = ' ';
    for c in line.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            None if c == '\'' || c == '"' => quote = Some(c),
            None if c == '#' && previous.is_whitespace() => break,
            _ => {}
        }
        out.push(c);
        previous = c;
    }
    out.trim_end().to_owned()
}

fn find(path: &Path) -> Found {
    let text = std::fs::read_to_string(path).unwrap();
    let file = relative(path);
    let place = |line: usize| Place {
        file: file.clone(),
        line,
    };
    let mut found = Found::default();
    let lines: Vec<&str> = text.lines().collect();
    let mut i = 0;
    let mut prose = String::new();
    let mut prose_lines: Vec<(usize, usize)> = Vec::new(); // (byte offset, line number)
    while i < lines.len() {
        let line = lines[i];
        if let Some(info) = line.strip_prefix("```") {
            let info = info.trim();
            let start = i + 1;
            let mut body = Vec::new();
            i += 1;
            while i < lines.len() && !lines[i].starts_with("```") {
                body.push((i + 1, lines[i]));
                i += 1;
            }
            i += 1;
            match info.split_whitespace().next().unwrap_or("") {
                "sh" | "bash" | "shell" => {
                    let mut block = Block {
                        place: place(start),
                        lines: Vec::new(),
                    };
                    let mut pending: Option<(usize, String)> = None;
                    for (n, l) in body {
                        let (first, mut joined) = pending.take().unwrap_or((n, String::new()));
                        if let Some(cont) = l.trim_end().strip_suffix('\\') {
                            joined.push_str(cont);
                            joined.push(' ');
                            pending = Some((first, joined));
                            continue;
                        }
                        joined.push_str(l);
                        let command = strip_comment(&joined);
                        if !command.trim().is_empty() {
                            block.lines.push((place(first), command.trim().to_owned()));
                        }
                    }
                    found.blocks.push(block);
                }
                "text" => {
                    if let Some(command) = body
                        .first()
                        .and_then(|(_, l)| l.strip_prefix("$ "))
                        .filter(|c| c.starts_with("rattleback "))
                    {
                        let shown: Vec<&str> = body[1..].iter().map(|(_, l)| *l).collect();
                        found.samples.push(Sample {
                            place: place(start),
                            command: command.to_owned(),
                            shown: shown.join("\n"),
                        });
                    }
                }
                _ => {}
            }
            continue;
        }
        prose_lines.push((prose.len(), i + 1));
        prose.push_str(line);
        prose.push('\n');
        i += 1;
    }
    // Inline spans, which may run over a line break.
    let mut rest = prose.as_str();
    let mut offset = 0;
    while let Some(open) = rest.find('`') {
        let after = &rest[open + 1..];
        let Some(close) = after.find('`') else { break };
        let span = &after[..close];
        let at = offset + open;
        let line = prose_lines
            .iter()
            .rev()
            .find(|(o, _)| *o <= at)
            .map_or(1, |(_, n)| *n);
        let span = span.split_whitespace().collect::<Vec<_>>().join(" ");
        if span.starts_with("cargo ") {
            found.inline.push((place(line), span));
        }
        let used = open + 1 + close + 1;
        offset += used;
        rest = &rest[used..];
    }
    found
}

/// Words as the shell splits them (quotes kept together and removed; no expansions).
fn words(segment: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word = String::new();
    let mut quote = None;
    let mut any = false;
    for c in segment.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            None if c == '\'' || c == '"' => {
                quote = Some(c);
                any = true;
            }
            None if c.is_whitespace() => {
                if any || !word.is_empty() {
                    out.push(std::mem::take(&mut word));
                }
                any = false;
            }
            _ => word.push(c),
        }
    }
    if any || !word.is_empty() {
        out.push(word);
    }
    out
}

/// A line's segments between unquoted `&&`, `;` and `|`.
fn segments(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut current = String::new();
    let mut quote = None;
    let chars: Vec<char> = line.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        match quote {
            Some(q) if c == q => quote = None,
            None if c == '\'' || c == '"' => quote = Some(c),
            None if c == ';' || c == '|' || (c == '&' && chars.get(i + 1) == Some(&'&')) => {
                out.push(std::mem::take(&mut current).trim().to_owned());
                if c == '&' || (c == '|' && chars.get(i + 1) == Some(&'|')) {
                    i += 1;
                }
                i += 1;
                continue;
            }
            _ => {}
        }
        current.push(c);
        i += 1;
    }
    out.push(current.trim().to_owned());
    out.retain(|s| !s.is_empty());
    out
}

/// The names of this package's `[[bench]]`, `[[example]]` and features, from Cargo.toml and
/// the folders.
struct Package {
    benches: Vec<String>,
    examples: Vec<String>,
    features: Vec<String>,
}

fn package() -> Package {
    let manifest: toml::Table = std::fs::read_to_string(root().join("Cargo.toml"))
        .unwrap()
        .parse()
        .unwrap();
    let names = |dir: &str| -> Vec<String> {
        std::fs::read_dir(root().join(dir))
            .map(|d| {
                d.filter_map(|e| {
                    let p = e.ok()?.path();
                    (p.extension()? == "rs").then(|| p.file_stem()?.to_str().map(str::to_owned))?
                })
                .collect()
            })
            .unwrap_or_default()
    };
    Package {
        benches: names("benches"),
        examples: names("examples"),
        features: manifest["features"]
            .as_table()
            .unwrap()
            .keys()
            .cloned()
            .collect(),
    }
}

/// The `it` suite's test names, from this binary itself.
fn it_tests() -> Vec<String> {
    let out = crate::common::detached(std::env::current_exe().unwrap())
        .args(["--list", "--format", "terse"])
        .output()
        .unwrap();
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| l.strip_suffix(": test"))
        .map(str::to_owned)
        .collect()
}

/// The unit tests' paths (`module::path::tests::name`), read from the sources.
fn unit_tests() -> Vec<String> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    let mut files = Vec::new();
    walk(&root().join("src"), &mut files);
    let mut out = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let module = file
            .strip_prefix(root().join("src"))
            .unwrap()
            .with_extension("")
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .filter(|c| c != "mod" && c != "lib")
            .collect::<Vec<_>>()
            .join("::");
        let lines: Vec<&str> = text.lines().collect();
        for (i, l) in lines.iter().enumerate() {
            if l.trim() == "#[test]" {
                let name = lines[i + 1..]
                    .iter()
                    .find_map(|l| {
                        l.trim()
                            .strip_prefix("fn ")
                            .and_then(|r| r.split('(').next())
                    })
                    .unwrap_or("");
                out.push(format!("{module}::tests::{name}"));
            }
        }
    }
    out
}

struct Checker {
    package: Package,
    it: Vec<String>,
    units: Vec<String>,
}

impl Checker {
    fn new() -> Self {
        Self {
            package: package(),
            it: it_tests(),
            units: unit_tests(),
        }
    }

    /// Whether cargo takes `words` (`cargo` first) as written; for `cargo run`, the program's
    /// arguments.
    fn cargo(&self, words: &[String]) -> Result<(), String> {
        // A redirection is the shell's.
        let words = &words[..words.iter().position(|w| w == ">").unwrap_or(words.len())];
        let sub = words.get(1).map_or("", String::as_str);
        let (ours, theirs) = match words.iter().position(|w| w == "--") {
            Some(i) => (&words[2..i], &words[i + 1..]),
            None => (&words[2..], &[][..]),
        };
        let mut positional = Vec::new();
        let mut target: Option<(&str, &str)> = None;
        let mut it = ours.iter();
        while let Some(w) = it.next() {
            let w = w.as_str();
            match w {
                "--release" | "--no-run" | "--locked" | "--quiet" | "-q" | "--all-targets"
                | "--lib" | "--doc" | "--timings" | "--all-features" => {
                    if w == "--lib" {
                        target = Some(("lib", ""));
                    }
                }
                "--test" | "--example" | "--bench" | "--features" | "--path" | "--profile"
                | "--bin" => {
                    let value = it
                        .next()
                        .ok_or_else(|| format!("`{w}` needs a value"))?
                        .as_str();
                    let known = match w {
                        "--test" => value == "it",
                        "--example" => self.package.examples.iter().any(|e| e == value),
                        "--bench" => self.package.benches.iter().any(|e| e == value),
                        "--features" => self.package.features.iter().any(|e| e == value),
                        "--bin" => value == "rattleback",
                        "--profile" => ["dev", "release", "test", "bench"].contains(&value),
                        _ => true,
                    };
                    if !known {
                        return Err(format!("no {} named `{value}` in this package", &w[2..]));
                    }
                    if matches!(w, "--test" | "--example" | "--bench") {
                        target = Some((w, value));
                    }
                }
                _ if w.starts_with('-') => return Err(format!("cargo {sub} has no flag `{w}`")),
                _ => positional.push(w),
            }
        }
        match sub {
            "test" => {
                if positional.len() > 1 {
                    return Err(format!(
                        "two test filters before `--` ({}): cargo takes one (`unexpected argument`)",
                        positional.join(", ")
                    ));
                }
                let mut filters: Vec<&str> = positional.clone();
                let mut harness = theirs.iter();
                while let Some(w) = harness.next() {
                    match w.as_str() {
                        "--nocapture" | "--ignored" | "--include-ignored" | "--exact"
                        | "--list" => {}
                        "--test-threads" | "--skip" => {
                            harness.next();
                        }
                        w if w.starts_with('-') => {
                            return Err(format!("the test harness has no flag `{w}`"));
                        }
                        w => filters.push(w),
                    }
                }
                let names: &[String] = match target {
                    Some(("--test", _)) => &self.it,
                    Some(("lib", _)) => &self.units,
                    _ => &[],
                };
                for filter in filters {
                    if !names.is_empty() && !names.iter().any(|n| n.contains(filter)) {
                        return Err(format!("the filter `{filter}` selects no test"));
                    }
                }
                Ok(())
            }
            "run" => {
                // `cargo run [ARGS]… [-- ARGS…]`: both are the program's.
                if target.is_none() {
                    let mut args = vec!["rattleback".to_owned()];
                    args.extend(positional.iter().map(|w| (*w).to_owned()));
                    args.extend(theirs.iter().cloned());
                    parse(&args)?;
                }
                Ok(())
            }
            "bench" | "build" | "install" | "check" | "clippy" | "fmt" => Ok(()),
            other => Err(format!(
                "`cargo {other}` is not a command this project uses"
            )),
        }
    }
}

/// Whether the program's parser takes `args` (`rattleback` first).
fn parse(args: &[String]) -> Result<(), String> {
    match rattleback::commands::cli::parse_from(args) {
        Ok(_) => Ok(()),
        Err(e)
            if matches!(
                e.kind(),
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion
            ) =>
        {
            Ok(())
        }
        Err(e) => Err(e.to_string().lines().next().unwrap_or("").to_owned()),
    }
}

/// Commands that run headless in a moment (the others are parsed only).
fn runs_headless(args: &[String]) -> bool {
    let words: Vec<&str> = args.iter().skip(1).map(String::as_str).collect();
    match words.first().copied() {
        Some(
            "--help" | "-h" | "--version" | "-V" | "simulate" | "study" | "presets" | "themes"
            | "lessons" | "doctor" | "check" | "man" | "completions" | "keygen" | "config",
        ) => true,
        Some("lesson") => words.get(1) == Some(&"new"),
        _ => false,
    }
}

/// Runs `args` in `home` as a user would; `> FILE` takes its standard output.
fn run(args: &[String], home: &Path) -> Result<String, String> {
    let mut args: Vec<String> = args[1..]
        .iter()
        .map(|a| {
            a.strip_prefix("~/")
                .map_or_else(|| a.clone(), |r| home.join(r).display().to_string())
        })
        .collect();
    let mut out_file = None;
    if let Some(i) = args.iter().position(|a| a == ">") {
        out_file = Some(home.join(args.get(i + 1).ok_or("`>` without a file")?));
        args.truncate(i);
    }
    let out = crate::common::rattleback()
        .args(&args)
        .current_dir(home)
        .env("HOME", home)
        .env("XDG_CONFIG_HOME", home.join(".config"))
        .env_remove("RATTLEBACK_CONFIG_DIR")
        .env("COLUMNS", "80")
        .output()
        .map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(format!(
            "exit {:?}: {}",
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    if let Some(file) = out_file {
        std::fs::write(&file, &stdout).map_err(|e| format!("{}: {e}", file.display()))?;
    }
    Ok(stdout)
}

/// Checks one shell segment; `Ok(true)` when it was run.
fn check_segment(checker: &Checker, segment: &str, home: &Path) -> Result<bool, String> {
    let words = words(segment);
    let program = words.first().map_or("", String::as_str);
    match program {
        "cargo" => checker.cargo(&words).map(|()| false),
        "rattleback" | "./target/release/rattleback" | "target/release/rattleback" => {
            if words.iter().any(|w| w.contains(['$', '`', '*', '?'])) {
                return Ok(false); // the shell's variables and globs: read by a person, not here
            }
            let mut args = words.clone();
            "rattleback".clone_into(&mut args[0]);
            let end = args.iter().position(|a| a == ">").unwrap_or(args.len());
            parse(&args[..end])?;
            if runs_headless(&args) {
                run(&args, home)?;
                return Ok(true);
            }
            Ok(false)
        }
        "mkdir" => {
            for dir in words.iter().skip(1).filter(|w| !w.starts_with('-')) {
                let dir = dir
                    .strip_prefix("~/")
                    .map_or_else(|| home.join(dir), |r| home.join(r));
                std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
            }
            Ok(false)
        }
        _ => Ok(false),
    }
}

#[test]
fn every_command_in_the_readme_and_the_docs_is_taken_as_written() {
    let checker = Checker::new();
    assert!(
        checker.it.len() > 100,
        "`it --list`: {} tests",
        checker.it.len()
    );
    let scratch = tempfile::tempdir().unwrap();
    let (mut checked, mut ran, mut problems) = (0, 0, Vec::new());
    for (n, page) in pages().iter().enumerate() {
        let found = find(page);
        for (b, block) in found.blocks.iter().enumerate() {
            let home = scratch.path().join(format!("{n}-{b}"));
            std::fs::create_dir_all(&home).unwrap();
            let _ = &block.place;
            for (place, line) in &block.lines {
                for segment in segments(line) {
                    checked += 1;
                    match check_segment(&checker, &segment, &home) {
                        Ok(true) => ran += 1,
                        Ok(false) => {}
                        Err(e) => problems.push(format!("{place}: `{segment}`: {e}")),
                    }
                }
            }
        }
        for (place, span) in &found.inline {
            checked += 1;
            for segment in segments(span) {
                if let Err(e) = check_segment(&checker, &segment, scratch.path()) {
                    problems.push(format!("{place}: `{segment}`: {e}"));
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "{} of {checked} commands in the docs are not taken as written:\n{}",
        problems.len(),
        problems.join("\n")
    );
    assert!(checked > 100 && ran > 15, "checked {checked}, ran {ran}");
}

/// Seconds and dates change from run to run: masked in both texts.
fn volatile(text: &str) -> String {
    text.lines()
        .map(|l| {
            let l = l.trim_end();
            match l.rfind(", ") {
                Some(i) if l.starts_with("work") && l.ends_with(" s") => {
                    format!("{}, … s", &l[..i])
                }
                _ => l.to_owned(),
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn every_sample_output_in_the_docs_is_what_the_command_prints() {
    let scratch = tempfile::tempdir().unwrap();
    let mut samples = 0;
    let mut stale = Vec::new();
    for page in pages() {
        for sample in find(&page).samples {
            samples += 1;
            let args = words(&sample.command);
            let printed = run(&args, scratch.path())
                .unwrap_or_else(|e| panic!("{}: `{}`: {e}", sample.place, sample.command));
            if volatile(&printed).trim_end() != volatile(&sample.shown).trim_end() {
                stale.push(format!(
                    "{}: `{}` now prints:\n{}",
                    sample.place, sample.command, printed
                ));
            }
        }
    }
    assert!(samples >= 3, "{samples} samples found");
    assert!(stale.is_empty(), "stale samples:\n{}", stale.join("\n"));
}

#[test]
fn the_checker_refuses_what_cargo_refuses() {
    let checker = Checker::new();
    let w = |s: &str| words(s);
    for bad in [
        "cargo test --test it explorer_app:: every_shipped_preset",
        "cargo test --test studies",
        "cargo test --test it no_such_test_anywhere",
        "cargo bench --bench nope",
        "cargo run --release -- simulate --no-such-flag",
    ] {
        assert!(checker.cargo(&w(bad)).is_err(), "taken: {bad}");
    }
    for good in [
        "cargo test --test it explorer_app::every_shipped_preset",
        "cargo test --release --test it -- explorer_app:: every_shipped_preset",
        "cargo run --release -- simulate --preset kapitza-upright",
        "cargo bench --bench methods",
    ] {
        assert_eq!(checker.cargo(&w(good)), Ok(()), "{good}");
    }
    assert!(parse(&w("rattleback study sweep [--preset NAME|PATH]")).is_err());
    assert_eq!(segments("a && b | c; d"), ["a", "b", "c", "d"]);
    assert_eq!(strip_comment("x 'a # b' # c"), "x 'a # b'");
}
