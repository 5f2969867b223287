//! Bounded everywhere: each reproduction of the reliability review (`docs/reviews`, N1–N15) run
//! as a user or an attacker with a bad file would, in both scenes and through every entry point
//! (`simulate`, `study`, `replay --verify`, `--export-cast`, `bench`, the explorer and `follow`
//! under a pseudo-terminal). Every process runs under a 1 GiB address-space limit (`ulimit -v`:
//! an allocation past it aborts, which fails the test) and must end within the work budget plus
//! 5 s, refused or finished, leaving no temporary file behind.

use rattleback::physics::method::Asked;
use std::io::Write as _;
use std::process::Stdio;
use std::time::{Duration, Instant};

use rattleback::app::journal::Event;
use rattleback::record::{FORMAT, Header, Line, Recorder, Size, ThemeRef, VERSION};

/// The work budget plus 5 s.
const WALL: Duration = Duration::from_secs(65);
/// 1 GiB, in the KiB `ulimit -v` takes.
const MEMORY_KIB: u64 = 1 << 20;

struct Outcome {
    code: Option<i32>,
    out: String,
    err: String,
    took: Duration,
}

fn dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("rattleback-bounded-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs the binary with `args` under the memory limit and the wall limit.
fn limited(args: &[&str]) -> Outcome {
    let mut cmd = format!(
        "ulimit -v {MEMORY_KIB}; exec '{}'",
        crate::common::program()
    );
    for a in args {
        cmd.push_str(" '");
        cmd.push_str(a);
        cmd.push('\'');
    }
    let start = Instant::now();
    let mut child = crate::common::detached("sh")
        .args(["-c", &cmd])
        .env("RATTLEBACK_CONFIG_DIR", dir("config"))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read while it runs: a full pipe would stop the child and look like a hang.
    let drain = |mut r: Box<dyn std::io::Read + Send>| {
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            let _ = r.read_to_end(&mut buf);
            String::from_utf8_lossy(&buf).into_owned()
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > WALL {
            let _ = child.kill();
            panic!("{args:?}: still running after {WALL:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let took = start.elapsed();
    let o = Outcome {
        code: status.code(),
        out: out.join().unwrap(),
        err: err.join().unwrap(),
        took,
    };
    assert!(
        !o.err.contains("memory allocation") && o.code.is_some(),
        "{args:?}: ran out of its 1 GiB or died by a signal: {} {:?}",
        o.err,
        o.code
    );
    assert!(!o.err.contains("panicked"), "{args:?}: {}", o.err);
    o
}

fn refused(args: &[&str], needle: &str) {
    let o = limited(args);
    assert_eq!(o.code, Some(2), "{args:?}: {}{}", o.out, o.err);
    assert!(o.err.contains(needle), "{args:?}: {}", o.err);
    assert!(
        o.took < Duration::from_secs(10),
        "{args:?}: refused only after {:?}",
        o.took
    );
}

/// N5, N13: the pendulum's cost model sees `b`, `θ̇0` and the step; the rattleback's long runs.
#[test]
fn simulate_refuses_what_would_run_away_in_both_scenes() {
    let k = ["--preset", "kapitza-upright"];
    for set in ["pendulum.b=1e6", "pendulum.b=1e10", "initial.theta_dot=1e9"] {
        for method in ["auto", "dop853", "effective-corrected"] {
            refused(
                &["simulate", k[0], k[1], "--set", set, "--method", method],
                "predicted",
            );
        }
        // A fixed step is capped at 2·10⁶ steps: refused, or done within the budget.
        for method in ["rk4", "strang", "suzuki8"] {
            let o = limited(&["simulate", k[0], k[1], "--set", set, "--method", method]);
            assert!(o.took < WALL, "{set} {method}");
        }
    }
    refused(
        &["simulate", k[0], k[1], "--set", "pendulum.b=1e300"],
        "not a finite number",
    );
    refused(
        &[
            "simulate", k[0], k[1], "--method", "strang", "--step", "1e-300",
        ],
        "",
    );
    refused(
        &["simulate", "--t-end", "1e12", "--method", "strang"],
        "predicted",
    );
    refused(
        &["simulate", "--set", "body.ix=1e300"],
        "not a finite number",
    );
    // A correction expanded in 1/k at a vanishing k: fails at once instead of looping.
    let o = limited(&[
        "simulate",
        "--set",
        "spring.k=5e-324",
        "--method",
        "effective-corrected",
    ]);
    assert_eq!(o.code, Some(1), "{}", o.err);
    assert!(o.took < Duration::from_secs(10), "{:?}", o.took);
    // N10: predicted under the budget, refused while probing: within the budget, not after.
    let o = limited(&["simulate", "--set", "spring.k=1e8", "--t-end", "9e5"]);
    assert!(o.took < WALL, "{:?}", o.took);
    // N13: a long run whose energy means nothing says so.
    let o = limited(&[
        "simulate",
        "--method",
        "blanes-moan4",
        "--t-end",
        "1e5",
        "--format",
        "json",
    ]);
    assert!(o.err.contains("warning: the energy drifted"), "{}", o.err);
    assert!(o.out.contains("\"exceeds_bound\": true"), "{}", o.out);
}

/// Issue 29: a small trapped swing at a huge k made the averaged half period's quadrature
/// bisect rounding noise for hours (`--format csv`, which skips the report, returned at once).
/// Every format now returns well within the budget; the half period is a number or `null`.
#[test]
fn every_report_of_a_tiny_swing_at_huge_k_returns() {
    let starts: [&[&str]; 2] = [
        &["--set", "spring.k=1e8", "--set", "initial.alpha_dot=0.05"],
        &[
            "--set",
            "body.ix=80",
            "--set",
            "body.iy=20",
            "--set",
            "body.iz=40",
            "--set",
            "spring.k=1e10",
            "--set",
            "initial.alpha_dot=0.05",
            "--t-end",
            "300",
        ],
    ];
    for start in starts {
        for format in ["json", "table", "csv"] {
            let mut args = vec!["simulate", "--format", format];
            args.extend_from_slice(start);
            let o = limited(&args);
            assert!(matches!(o.code, Some(0 | 1)), "{args:?}: {}", o.err);
            assert!(o.took < Duration::from_secs(10), "{args:?}: {:?}", o.took);
            if format == "json" {
                assert!(o.out.contains("\"half_period\""), "{}", o.out);
            }
        }
    }
}

/// N6: `study sweep` validates and budgets its ladder; extreme rungs finish at bounded memory.
#[test]
fn study_sweep_is_bounded() {
    for ladder in ["5e-324,1e308", "1e308"] {
        let o = limited(&["study", "sweep", "--ladder", ladder]);
        assert_eq!(o.code, Some(0), "{ladder}: {}", o.err);
        let out = dir("sweep");
        let o = limited(&[
            "study",
            "sweep",
            "--ladder",
            ladder,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.code, Some(0), "{ladder}: {}", o.err);
        assert!(out.join("sweep.svg").exists());
    }
    refused(
        &["study", "sweep", "--ladder", "1e2,1e4", "--t-end", "1e12"],
        "predicted",
    );
}

fn header(preset: &str) -> Header {
    Header {
        format: FORMAT.to_owned(),
        version: VERSION,
        program: "test".to_owned(),
        preset: preset.to_owned(),
        method: "auto".to_owned(),
        tolerance: 1e-9,
        terminal: Size {
            width: 80,
            height: 24,
        },
        theme: ThemeRef::Name("default".to_owned()),
        fps: 30.0,
        lesson: None,
    }
}

fn line(wall: f64, t: f64, event: Event) -> Line {
    Line {
        wall,
        t,
        generation: 1,
        chain: None,
        event,
    }
}

fn set(field: &str, value: &str) -> Event {
    Event::Set {
        field: field.to_owned(),
        value: value.to_owned(),
    }
}

/// The hostile sessions of N1–N3, written with a valid chain (anyone can).
fn hostile_sessions(d: &std::path::Path) -> Vec<std::path::PathBuf> {
    let base = rattleback::scenario::shipped::resolve("subcritical", &[])
        .unwrap()
        .to_toml();
    let tiny_iz = base.replace("iz = 1.0", "iz = 2e-12");
    assert_ne!(tiny_iz, base);
    let pendulum = rattleback::scenario::shipped::resolve("kapitza-upright", &[])
        .unwrap()
        .to_toml();
    let plan: rattleback::sim::PlanKey = {
        let p = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
        rattleback::sim::PlanKey::Rattleback(rattleback::physics::rattleback::scene::PlanKey::of(
            p.problem().unwrap(),
            1e-9,
            30.0,
        ))
    };
    let cases: Vec<(&str, String, Vec<Event>)> = vec![
        ("tiny-iz", tiny_iz, vec![Event::Play]),
        (
            "ix-strang",
            base.clone(),
            vec![set("method", "strang"), set("ix", "1e12"), Event::Play],
        ),
        (
            "plan-step",
            base.clone(),
            vec![
                Event::plan(
                    plan,
                    rattleback::physics::Resolved {
                        method: rattleback::physics::Method::Rk4,
                        tolerance: 1e-9,
                        step: Some(1e-300),
                    },
                    None,
                ),
                Event::Play,
            ],
        ),
        (
            "long-stiff",
            base,
            vec![set("t_end", "1e9"), set("k", "1e8"), Event::Play],
        ),
        ("pendulum-b", pendulum, vec![set("b", "1e10"), Event::Play]),
    ];
    cases
        .into_iter()
        .map(|(name, preset, events)| {
            let path = d.join(format!("{name}.jsonl"));
            let mut rec = Recorder::create(&path, &header(&preset), None).unwrap();
            let mut wall = 0.0;
            for e in events {
                wall += 0.5;
                rec.write(&line(wall, 0.0, e)).unwrap();
            }
            for i in 1..=20 {
                rec.write(&line(wall + f64::from(i) * 0.1, f64::from(i), Event::Clock))
                    .unwrap();
            }
            rec.write(&line(wall + 3.0, 20.0, Event::end())).unwrap();
            path
        })
        .collect()
}

/// N1–N3: `replay --verify` and `--export-cast` of hostile sessions end within the budget at
/// bounded memory, and an export leaves nothing behind.
#[test]
fn hostile_sessions_verify_and_export_within_their_bounds() {
    let d = dir("sessions");
    for path in hostile_sessions(&d) {
        let p = path.to_str().unwrap();
        let o = limited(&["replay", p, "--verify"]);
        assert!(o.took < WALL, "{p}");
        let cast = d.join("out.cast");
        let _ = std::fs::remove_file(&cast);
        let o = limited(&["replay", p, "--export-cast", cast.to_str().unwrap()]);
        assert!(o.took < WALL, "{p}");
        let stray: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(stray.is_empty(), "{p}: {stray:?}");
    }
}

/// N14: a signal during `--export-cast` leaves no temporary file and exits 128 + n.
#[test]
fn an_interrupted_export_leaves_nothing() {
    let d = dir("interrupt");
    let session = format!("{}/tests/fixtures/sessions/lesson.jsonl", root!());
    let out = d.join("big.cast");
    let mut child = crate::common::rattleback()
        .args(["replay", &session, "--export-cast"])
        .arg(&out)
        .args(["--fps", "240", "--cols", "400", "--rows", "200"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(400));
    let pid = child.id().to_string();
    let killed = crate::common::detached("kill")
        .args(["-TERM", &pid])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    let left: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    if status.code() == Some(0) {
        // The export won the race: the file is whole and alone.
        assert_eq!(left, vec!["big.cast".to_owned()]);
    } else {
        assert_eq!(status.code(), Some(128 + 15));
        assert!(left.is_empty(), "{left:?}");
    }
}

/// N12: `bench --out` refuses to replace an earlier run's files without `--force`, at once.
#[test]
fn bench_never_overwrites_without_force() {
    let d = dir("bench");
    std::fs::write(d.join("stability.csv"), "keep").unwrap();
    let o = limited(&[
        "bench",
        "--quick",
        "--only",
        "stability",
        "--out",
        d.to_str().unwrap(),
    ]);
    assert_eq!(o.code, Some(2), "{}", o.err);
    assert!(o.err.contains("--force"), "{}", o.err);
    assert_eq!(
        std::fs::read_to_string(d.join("stability.csv")).unwrap(),
        "keep"
    );
}

/// N11: strings from files reach no terminal raw through JSON.
#[test]
fn json_carries_no_c1_or_bidi_control() {
    let d = dir("json");
    let preset = rattleback::scenario::shipped::resolve("subcritical", &[])
        .unwrap()
        .to_toml()
        .replace(
            "name = \"Subcritical start\"",
            "name = \"x\\u009b31m\\u202eevil\\u2066\"",
        );
    let path = d.join("evil.toml");
    std::fs::write(&path, preset).unwrap();
    let o = limited(&[
        "simulate",
        "--preset",
        path.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(o.code, Some(0), "{}", o.err);
    assert!(
        !o.out
            .chars()
            .any(|c| ('\u{80}'..='\u{9f}').contains(&c) || ('\u{202a}'..='\u{2069}').contains(&c)),
        "{}",
        o.out
    );
    let v: serde_json::Value = serde_json::from_str(&o.out).unwrap();
    assert_eq!(
        v["preset"], "x\u{9b}31m\u{202e}evil\u{2066}",
        "the same string, escaped"
    );
}

/// Messages: the right noun, an unbalanced quote refused, a session with a byte-order mark read.
#[test]
fn messages_name_the_right_thing() {
    let o = limited(&["--theme", "nosuch"]);
    assert!(o.err.contains("no theme named"), "{}", o.err);
    let o = limited(&["lesson", "nosuch"]);
    assert!(o.err.contains("no lesson named"), "{}", o.err);
    let o = limited(&["simulate", "--set", "run.method=\"auto"]);
    assert_eq!(o.code, Some(2));
    assert!(o.err.contains("unbalanced"), "{}", o.err);
    let d = dir("bom");
    let session =
        std::fs::read(format!("{}/tests/fixtures/sessions/lesson.jsonl", root!())).unwrap();
    let path = d.join("bom.jsonl");
    let mut f = std::fs::File::create(&path).unwrap();
    f.write_all("\u{feff}".as_bytes()).unwrap();
    f.write_all(&session).unwrap();
    drop(f);
    let o = limited(&["replay", path.to_str().unwrap(), "--verify"]);
    assert_eq!(o.code, Some(0), "{}", o.err);
}

const LEAVE_ALT: &[u8] = b"\x1b[?1049l";

/// The explorer in a pseudo-terminal (`script`), under the memory limit.
struct Pty {
    child: std::process::Child,
    log: std::path::PathBuf,
}

impl Pty {
    fn start(name: &str, args: &str) -> Self {
        let log = dir(name).join("pty.out");
        let command = format!(
            "stty rows 30 cols 100; ulimit -v {MEMORY_KIB}; exec {} {args}",
            crate::common::program()
        );
        let child = crate::common::in_pty(&command, &log)
            .env("RATTLEBACK_CONFIG_DIR", dir("config"))
            .stdin(Stdio::piped())
            .spawn()
            .expect("`script` (util-linux) runs the explorer in a pseudo-terminal");
        std::thread::sleep(Duration::from_millis(800));
        Self { child, log }
    }
    fn keys(&mut self, keys: &[u8]) {
        let stdin = self.child.stdin.as_mut().unwrap();
        stdin.write_all(keys).unwrap();
        stdin.flush().unwrap();
    }
    fn explorer_pid(&self) -> Option<u32> {
        let out = crate::common::detached("pgrep")
            .args(["-P", &self.child.id().to_string()])
            .output()
            .ok()?;
        String::from_utf8_lossy(&out.stdout)
            .split_whitespace()
            .next()?
            .parse()
            .ok()
    }
    /// Waits for the process to end; how long it took.
    fn ended_within(&mut self, limit: Duration) -> Duration {
        let start = Instant::now();
        while start.elapsed() < limit {
            if self.child.try_wait().unwrap().is_some() {
                return start.elapsed();
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        let _ = self.child.kill();
        panic!("still running after {limit:?}");
    }
    fn restored(&self) -> bool {
        let out = std::fs::read(&self.log).unwrap_or_default();
        out.windows(LEAVE_ALT.len()).any(|w| w == LEAVE_ALT)
    }
}

fn rss_kib(pid: u32) -> u64 {
    std::fs::read_to_string(format!("/proc/{pid}/status"))
        .unwrap_or_default()
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        .unwrap_or(0)
}

/// N1, N8: the explorer on a degenerate body with a concrete method (and the pendulum shaken
/// at b = 1e10) keeps its memory, refuses what it cannot do, and `q` or a signal ends it at once
/// with the terminal restored.
#[test]
fn the_explorer_stays_bounded_and_quits_at_once() {
    let d = dir("explorer");
    let preset = d.join("ix.toml");
    std::fs::write(
        &preset,
        rattleback::scenario::shipped::resolve("subcritical", &[])
            .unwrap()
            .to_toml()
            .replace("ix = 2.0", "ix = 1e12")
            .replace("method = \"auto\"", "method = \"strang\""),
    )
    .unwrap();
    let pendulum = d.join("b.toml");
    std::fs::write(
        &pendulum,
        rattleback::scenario::shipped::resolve("kapitza-upright", &[])
            .unwrap()
            .to_toml()
            .replace("b = 2.0", "b = 1e10"),
    )
    .unwrap();
    for p in [&preset, &pendulum] {
        let mut pty = Pty::start("q", &format!("--preset {}", p.display()));
        pty.keys(b" ");
        std::thread::sleep(Duration::from_secs(2));
        let pid = pty.explorer_pid().expect("the explorer runs");
        assert!(rss_kib(pid) < MEMORY_KIB / 4, "{} KiB", rss_kib(pid));
        pty.keys(b"q");
        let took = pty.ended_within(Duration::from_secs(5));
        // A hang guard, wide for a shared machine (issue 83): the run itself would take hours.
        assert!(took < Duration::from_secs(2), "q took {took:?}");
        assert!(pty.restored(), "the terminal is restored");
    }
    for signal in ["USR2", "XCPU", "TERM"] {
        let mut pty = Pty::start(signal, &format!("--preset {}", preset.display()));
        pty.keys(b" ");
        std::thread::sleep(Duration::from_millis(500));
        let pid = pty.explorer_pid().expect("the explorer runs").to_string();
        crate::common::detached("kill")
            .args([&format!("-{signal}"), &pid])
            .status()
            .unwrap();
        pty.ended_within(Duration::from_secs(5));
        assert!(pty.restored(), "{signal}: the terminal is restored");
    }
}

/// N1 through a file anyone can write: `follow` of a hostile session keeps its memory and quits.
#[test]
fn following_a_hostile_session_stays_bounded() {
    let d = dir("follow");
    let sessions = hostile_sessions(&d);
    for s in &sessions[..2] {
        let mut pty = Pty::start("follower", &format!("follow {}", s.display()));
        std::thread::sleep(Duration::from_secs(2));
        let pid = pty.explorer_pid().expect("the follower runs");
        assert!(rss_kib(pid) < MEMORY_KIB / 4, "{} KiB", rss_kib(pid));
        pty.keys(b"q");
        let took = pty.ended_within(Duration::from_secs(5));
        // A hang guard, wide for a shared machine (issue 83): the run itself would take hours.
        assert!(took < Duration::from_secs(2), "q took {took:?}");
        assert!(pty.restored());
    }
}

/// The runs of a replay are bounded as a whole too: each within the budget, but past the
/// session's total (priced before they start) the next is refused, with nothing computed.
#[test]
fn a_replays_runs_are_bounded_as_a_whole() {
    use rattleback::sim::{Command as C, Engine, PlanBook, SessionSpec, SimEvent, drive};
    let preset = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
    let model = preset.model;
    let spec = SessionSpec {
        model,
        method: rattleback::physics::Method::Dop853,
        tolerance: 1e-9,
        t_end: 3e4,
        effective: false,
        sample_dt: 0.05,
        step: None,
    };
    let one = model.predicted_seconds(&Asked::new(spec.method, spec.tolerance, None, spec.t_end));
    assert!(one > 1.0 && one < 60.0, "{one}");
    let mut engine = Engine::new(PlanBook {
        total: 2.5 * one + 1.0,
        ..PlanBook::default()
    });
    let mut outcomes = Vec::new();
    for generation in 1..=4 {
        drive(
            &mut engine,
            vec![C::Restart { generation, spec }],
            &mut |e| match e {
                SimEvent::Started { .. } => outcomes.push(Ok(())),
                SimEvent::Failed { message, .. } => outcomes.push(Err(message)),
                _ => {}
            },
        );
    }
    assert_eq!(outcomes.len(), 4);
    assert!(outcomes[0].is_ok() && outcomes[1].is_ok(), "{outcomes:?}");
    assert!(
        outcomes[2..]
            .iter()
            .all(|o| o.as_ref().is_err_and(|m| m.contains("budget"))),
        "{outcomes:?}"
    );
}
