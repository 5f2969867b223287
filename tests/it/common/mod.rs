//! Helpers shared by the integration tests.
#![allow(dead_code)]

use rattleback::physics::rattleback::{Params, Problem, Start};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The program's binary the tests drive: `rattleback` in the target folder this test binary
/// was built in (`target/PROFILE/deps/it-HASH` → `target/PROFILE/rattleback`). The tests are a
/// package of their own (issue 68), so cargo does not hand them `CARGO_BIN_EXE_rattleback`;
/// the program's package names its own integration test `it` too (`tests/built.rs`), so that
/// `cargo test` and `cargo test --test it ...` build the binary first. A binary older than any
/// source file is refused with the command that builds it, never driven stale.
pub fn program() -> &'static str {
    static BIN: OnceLock<String> = OnceLock::new();
    BIN.get_or_init(|| {
        let exe = std::env::current_exe().expect("the test binary's path");
        let dir = exe
            .parent()
            .and_then(Path::parent)
            .expect("the test binary lives in target/PROFILE/deps");
        let bin = dir.join(format!("rattleback{}", std::env::consts::EXE_SUFFIX));
        let built = std::fs::metadata(&bin)
            .and_then(|m| m.modified())
            .unwrap_or_else(|e| {
                panic!(
                    "{}: {e}; build it with `cargo test` from the repository's root \
                     (or `cargo build` in the same profile)",
                    bin.display()
                )
            });
        if let Some((source, _)) = newest_source().filter(|(_, t)| *t > built) {
            let source = source.strip_prefix(root!()).unwrap_or(&source).to_owned();
            panic!(
                "{} is older than {}: build it with `cargo test` from the repository's root \
                 (or `cargo build` in the same profile); a stale binary is never tested",
                bin.display(),
                source.display()
            );
        }
        bin.to_string_lossy().into_owned()
    })
}

/// The most recently modified source file of the program (`src/**/*.rs`; cargo rebuilds the
/// binary after any of them changes, not after every change to `Cargo.toml`).
fn newest_source() -> Option<(PathBuf, std::time::SystemTime)> {
    fn walk(dir: &Path, best: &mut Option<(PathBuf, std::time::SystemTime)>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, best);
            } else if path.extension().is_some_and(|e| e == "rs")
                && let Ok(t) = entry.metadata().and_then(|m| m.modified())
                && best.as_ref().is_none_or(|(_, b)| t > *b)
            {
                *best = Some((path, t));
            }
        }
    }
    let mut best = None;
    walk(&Path::new(root!()).join("src"), &mut best);
    best
}

/// Path of the reference cases: the copy carried in `tests/fixtures/reference/cases.toml`
/// (from `../shared/reference/cases.toml`), overridable with `RATTLEBACK_REFERENCE`.
pub fn reference_path() -> std::path::PathBuf {
    std::env::var_os("RATTLEBACK_REFERENCE").map_or_else(
        || std::path::Path::new(root!()).join("tests/fixtures/reference/cases.toml"),
        Into::into,
    )
}

/// The shared original of the carried reference cases, when a `../shared` is beside the clone.
pub fn shared_reference_path() -> Option<std::path::PathBuf> {
    let p = std::path::Path::new(root!()).join("../shared/reference/cases.toml");
    p.is_file().then_some(p)
}

/// The parsed reference file; a missing file is a failure, not a skip.
#[track_caller]
pub fn reference_cases() -> toml::Table {
    let path = reference_path();
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read reference cases {}: {e}", path.display()));
    text.parse::<toml::Table>()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[track_caller]
pub fn num(t: &toml::Table, key: &str) -> f64 {
    match t.get(key) {
        Some(toml::Value::Float(f)) => *f,
        Some(toml::Value::Integer(i)) => *i as f64,
        other => panic!("reference key {key}: expected a number, got {other:?}"),
    }
}

/// A problem built from raw numbers.
#[track_caller]
pub fn problem(ix: f64, iy: f64, iz: f64, k: f64, start: [f64; 4]) -> Problem {
    Problem::new(
        Params { ix, iy, iz, k },
        Start {
            gamma: start[0],
            alpha: start[1],
            gamma_dot: start[2],
            alpha_dot: start[3],
        },
    )
    .expect("valid test problem")
}

/// The problem of one reference case.
#[track_caller]
pub fn case_problem(case: &toml::Table) -> Problem {
    problem(
        num(case, "ix"),
        num(case, "iy"),
        num(case, "iz"),
        num(case, "k"),
        [
            num(case, "gamma"),
            num(case, "alpha"),
            num(case, "gamma_dot"),
            num(case, "alpha_dot"),
        ],
    )
}

/// The explorer driven headless through the worker's own interpreter: the app decides, the
/// engine integrates, nothing depends on a clock (each tick is a given wall time).
pub struct Headless {
    /// The explorer state.
    pub app: rattleback::app::App,
    /// The worker's interpreter.
    pub engine: rattleback::sim::Engine,
    /// Effects other than worker commands, in order (for assertions).
    pub effects: Vec<rattleback::app::Effect>,
}

impl Headless {
    /// A paused explorer on `preset` (a shipped name), started like the real one.
    pub fn new(preset: &str) -> Self {
        let preset = rattleback::scenario::shipped::resolve(preset, &[]).expect("preset");
        Self::of(&preset)
    }

    /// A paused explorer on `preset`.
    pub fn of(preset: &rattleback::scenario::Preset) -> Self {
        let (app, effects) = rattleback::app::App::new(preset, rattleback::app::Options::at(30.0));
        let mut h = Self {
            app,
            engine: rattleback::sim::Engine::new(rattleback::sim::PlanBook::default()),
            effects: Vec::new(),
        };
        h.exec(effects);
        h
    }

    /// Executes effects: worker commands run to completion on the engine.
    pub fn exec(&mut self, effects: Vec<rattleback::app::Effect>) {
        for e in effects {
            match e {
                rattleback::app::Effect::Sim(c) => {
                    let app = &mut self.app;
                    rattleback::sim::drive(&mut self.engine, vec![c], &mut |ev| {
                        app.on_sim(ev);
                    });
                }
                other => self.effects.push(other),
            }
        }
    }

    /// Presses a key.
    pub fn key(&mut self, key: rattleback::app::Key) {
        let effects = self.app.on_key(key);
        self.exec(effects);
    }

    /// Stops the recording as `R` does: the key, then frames until the last frame is settled
    /// and journaled with its checkpoint (the explorer then writes the end line).
    pub fn stop_recording(&mut self) {
        use rattleback::app::RecState;
        if self.app.journal.state == RecState::On {
            self.key(rattleback::app::Key::Char('R'));
        }
        let mut frames = 0;
        while self.app.journal.state == RecState::On {
            self.tick(0.0);
            frames += 1;
            assert!(frames < 1000, "the recording never closed");
        }
    }

    /// One frame of `wall` seconds.
    pub fn tick(&mut self, wall: f64) {
        let effects = self.app.tick(wall);
        self.exec(effects);
    }

    /// Plays at `speed` (a power of two) at 30 frames per second until the display reaches
    /// `t` (or the end of the run); returns the number of frames.
    pub fn play_until(&mut self, t: f64, speed: f64) -> usize {
        while self.app.run.speed < speed {
            self.key(rattleback::app::Key::Char('+'));
        }
        while self.app.run.speed > speed {
            self.key(rattleback::app::Key::Char('-'));
        }
        if !self.app.run.playing {
            self.key(rattleback::app::Key::Char(' '));
        }
        let mut frames = 0;
        while self.app.run.shown < t && !self.app.run.done() {
            self.tick(1.0 / 30.0);
            frames += 1;
            assert!(frames < 10_000_000, "the display never reached {t}");
        }
        frames
    }
}

/// One case of `tests/fixtures/reference/averaged.toml` (independent references for the
/// averaged model and `auto`, generated by `scripts/averaged_references.py`).
pub struct AveragedCase {
    /// `A_k1e04` and so on.
    pub name: String,
    /// The note's start letter (A–E), or the shape of a held-out start.
    pub start: String,
    /// Hooke constant.
    pub k: f64,
    /// The problem.
    pub problem: Problem,
    /// `rk8-long-double` (the full model) or `note-averaged-model`.
    pub source: String,
    /// `α(T)`, `α̇(T)` at `T = t_end`.
    pub end: (f64, f64),
    /// Final time.
    pub t_end: f64,
    /// Reversal times in `(0, T]`.
    pub reversals: Vec<f64>,
    /// `(t, α, α̇)` at `t = i T / 60` (full-model cases only).
    pub samples: Vec<(f64, f64, f64)>,
    /// How far the reference itself may be off (`rattleback_honesty.toml`; 0 where the file
    /// does not say, whose own floors the tests state).
    pub uncertainty: f64,
    /// The start's condition number, where the file gives it.
    pub condition: Option<f64>,
}

/// Every case of the averaged references; a missing file is a failure, not a skip.
#[track_caller]
pub fn averaged_cases() -> Vec<AveragedCase> {
    cases_from("averaged.toml")
}

/// Every case of a reference file of `tests/fixtures/reference/` in the averaged references'
/// format (`averaged.toml`, `rattleback_honesty.toml`).
#[track_caller]
pub fn cases_from(file: &str) -> Vec<AveragedCase> {
    let path = std::path::Path::new(root!())
        .join("tests/fixtures/reference")
        .join(file);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let table: toml::Table = text
        .parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let cases = table["case"].as_table().expect("[case.*] tables");
    let floats = |c: &toml::Table, key: &str| -> Vec<f64> {
        c.get(key)
            .and_then(toml::Value::as_array)
            .map(|a| a.iter().map(|v| v.as_float().expect("a float")).collect())
            .unwrap_or_default()
    };
    cases
        .iter()
        .map(|(name, c)| {
            let c = c.as_table().expect("a case table");
            let t_end = num(c, "t_end");
            let alpha = floats(c, "sample_alpha");
            let alpha_dot = floats(c, "sample_alpha_dot");
            let samples = alpha
                .iter()
                .zip(&alpha_dot)
                .enumerate()
                .map(|(i, (&a, &ad))| (t_end * i as f64 / alpha.len() as f64, a, ad))
                .collect();
            AveragedCase {
                name: name.clone(),
                start: c["start"].as_str().expect("start letter").to_owned(),
                k: num(c, "k"),
                problem: problem(
                    num(c, "ix"),
                    num(c, "iy"),
                    num(c, "iz"),
                    num(c, "k"),
                    [
                        num(c, "gamma0"),
                        num(c, "alpha0"),
                        num(c, "gamma_dot0"),
                        num(c, "alpha_dot0"),
                    ],
                ),
                source: c["source"].as_str().expect("source").to_owned(),
                end: (num(c, "alpha_end"), num(c, "alpha_dot_end")),
                t_end,
                reversals: floats(c, "reversals"),
                samples,
                uncertainty: c.get("uncertainty").map_or(0.0, |_| num(c, "uncertainty")),
                condition: c.get("condition").map(|_| num(c, "condition")),
            }
        })
        .collect()
}

/// Runs the binary with a private config folder; `(exit code, stdout, stderr)`.
pub fn bin(args: &[&str]) -> (i32, String, String) {
    bin_in(
        &std::env::temp_dir().join(format!("rattleback-test-{}", std::process::id())),
        args,
    )
}

/// Runs the binary with `config_dir` as its config folder; `(exit code, stdout, stderr)`.
pub fn bin_in(config_dir: &std::path::Path, args: &[&str]) -> (i32, String, String) {
    let out = rattleback()
        .args(args)
        .env("RATTLEBACK_CONFIG_DIR", config_dir)
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `rattleback simulate --format json` with these arguments (no user folder): its report.
/// Panics with stderr when the command fails.
pub fn simulate_json(args: &[&str]) -> serde_json::Value {
    let out = rattleback()
        .args(["simulate", "--format", "json"])
        .args(args)
        .env(
            "RATTLEBACK_CONFIG_DIR",
            std::env::temp_dir().join("rattleback-no-user-folder"),
        )
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The header a test recording of `app` starts with (80×24, the default theme, 30 fps).
pub fn header_of(app: &rattleback::app::App) -> rattleback::record::Header {
    use rattleback::record::{FORMAT, Header, Size, VERSION};
    Header {
        format: FORMAT.to_owned(),
        version: VERSION,
        program: "test".to_owned(),
        preset: app.to_preset(&app.scenario.name).to_toml(),
        method: app.scenario.settings.method.name().to_owned(),
        tolerance: app.scenario.settings.tolerance,
        terminal: Size {
            width: 80,
            height: 24,
        },
        theme: rattleback::record::ThemeRef::Name("Default (16 colours)".to_owned()),
        fps: 30.0,
        lesson: None,
    }
}

/// Writes `journal` (what `App::take_journal` gave) as a session file at `path`, a line every
/// `spacing` wall seconds, then its end line; returns the file read back.
pub fn write_session(
    path: &std::path::Path,
    header: &rattleback::record::Header,
    journal: Vec<(f64, u64, rattleback::app::journal::Event)>,
    spacing: f64,
) -> rattleback::record::Recording {
    use rattleback::app::journal::Event;
    use rattleback::record::{Line, Recorder};
    let _ = std::fs::remove_file(path);
    let mut rec = Recorder::create(path, header, None).unwrap();
    let n = journal.len();
    // The end line as the explorer's recorder writes it: at the last line's time and run stamp.
    let last = journal.last().map_or((0.0, 0), |(t, g, _)| (*t, *g));
    for (i, (t, generation, event)) in journal.into_iter().enumerate() {
        rec.write(&Line {
            wall: i as f64 * spacing,
            t,
            generation,
            chain: None,
            event,
        })
        .unwrap();
    }
    rec.write(&Line {
        wall: n as f64 * spacing + 1.0,
        t: last.0,
        generation: last.1,
        chain: None,
        event: Event::end(),
    })
    .unwrap();
    drop(rec);
    rattleback::record::read(path).unwrap()
}

/// A command for `program` that can never reach the terminal the tests run in: it starts in a
/// session of its own (`setsid`, util-linux), so it has no controlling terminal and cannot open
/// `/dev/tty`, put it in raw mode or be stopped by SIGTTOU under `timeout`. Every process a test
/// starts goes through here (`hygiene::tests_start_processes_only_through_common` checks it);
/// a test that needs a terminal gives the program a pseudo-terminal of its own (`script`).
pub fn detached(program: impl AsRef<std::ffi::OsStr>) -> std::process::Command {
    let mut command = std::process::Command::new("setsid");
    command.arg(program);
    // Not over ssh, whatever the developer's shell is: a test that wants ssh sets these.
    for name in [
        "SSH_CONNECTION",
        "SSH_CLIENT",
        "SSH_TTY",
        "TMUX",
        "TMUX_PANE",
    ] {
        command.env_remove(name);
    }
    command
}

/// `command` (a shell line) in a pseudo-terminal of its own (util-linux `script`), what it
/// draws written to `log`, [`detached`], its stdout and stderr to nothing: a test never reaches
/// the terminal it runs in. The caller says what stdin is.
pub fn in_pty(command: &str, log: &std::path::Path) -> std::process::Command {
    let mut script = detached("script");
    script
        .args(["-qfec", command])
        .arg(log)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null());
    script
}

/// The binary under test, [`detached`], with no locale of the developer's (taken as UTF-8, as
/// in CI): a test that needs one sets it.
pub fn rattleback() -> std::process::Command {
    let mut command = detached(crate::common::program());
    for name in ["LC_ALL", "LC_CTYPE", "LANG"] {
        command.env_remove(name);
    }
    command
}

/// A seeded generator for the tests of promises on generated cases (issue 80): the seed is
/// `RATTLEBACK_SEED` when set (to replay a failure), else the clock's, and every failure
/// message should carry it (`Seeded::tag`) so that a failing case can be run again.
pub struct Seeded {
    /// The seed it started from.
    pub seed: u64,
    state: u64,
}

impl Seeded {
    /// A generator seeded from `RATTLEBACK_SEED` or the clock; the seed is printed to the test's
    /// output (shown on failure).
    #[must_use]
    pub fn new(what: &str) -> Self {
        let seed = std::env::var("RATTLEBACK_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| {
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(1, |d| d.as_nanos() as u64)
            });
        println!("{what}: seed {seed} (RATTLEBACK_SEED={seed} replays it)");
        Self { seed, state: seed }
    }

    /// The next 64 random bits (`SplitMix64`).
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }

    /// A number log-uniform in `[lo, hi)` (both positive).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.uniform(lo.ln(), hi.ln()).exp()
    }

    /// A whole number in `lo..=hi`.
    pub fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as usize
    }

    /// One of `choices`.
    pub fn pick<'a, T>(&mut self, choices: &'a [T]) -> &'a T {
        &choices[self.int(0, choices.len() - 1)]
    }

    /// `RATTLEBACK_SEED=…`, for a failure's message.
    #[must_use]
    pub fn tag(&self) -> String {
        format!("RATTLEBACK_SEED={}", self.seed)
    }
}
