//! Signals end the explorer with the terminal restored and exit `128 + n`; SIGTSTP suspends
//! and SIGCONT resumes it in raw mode on the alternate screen. The explorer runs in a real
//! pseudo-terminal (`script`, from util-linux, on every Debian system).

use std::io::Write as _;
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

const ENTER_ALT: &[u8] = b"\x1b[?1049h";
const LEAVE_ALT: &[u8] = b"\x1b[?1049l";
const SHOW_CURSOR: &[u8] = b"\x1b[?25h";

struct Explorer {
    script: Child,
    log: std::path::PathBuf,
}

fn ppid_and_comm(pid: u32) -> Option<(u32, String)> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let open = stat.find('(')?;
    let close = stat.rfind(')')?;
    let comm = stat[open + 1..close].to_owned();
    let ppid = stat[close + 2..].split_whitespace().nth(1)?.parse().ok()?;
    Some((ppid, comm))
}

fn state(pid: u32) -> char {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
    stat.rfind(')')
        .and_then(|i| stat[i + 2..].chars().next())
        .unwrap_or('?')
}

impl Explorer {
    fn start(name: &str) -> Self {
        Self::start_with(name, &[])
    }

    fn start_with(name: &str, args: &[&str]) -> Self {
        let log = std::env::temp_dir().join(format!(
            "rattleback-signal-{name}-{}.out",
            std::process::id()
        ));
        let _ = std::fs::remove_file(&log);
        // A 100×30 pseudo-terminal from the start (nobody answers a cursor query here).
        let command = format!(
            "stty rows 30 cols 100; exec {} {}",
            crate::common::program(),
            args.join(" ")
        );
        let script = crate::common::in_pty(&command, &log)
            .stdin(Stdio::piped())
            .spawn()
            .expect("`script` (util-linux) runs the explorer in a pseudo-terminal");
        let me = Self { script, log };
        me.wait_for(|out| out.windows(ENTER_ALT.len()).any(|w| w == ENTER_ALT));
        me
    }

    /// The explorer's pid: the `rattleback` process below `script`.
    fn pid(&self) -> u32 {
        let root = self.script.id();
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(5) {
            for entry in std::fs::read_dir("/proc").unwrap().filter_map(Result::ok) {
                let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else {
                    continue;
                };
                let Some((ppid, comm)) = ppid_and_comm(pid) else {
                    continue;
                };
                let grand = ppid_and_comm(ppid).map(|(p, _)| p);
                if comm == "rattleback" && (ppid == root || grand == Some(root)) {
                    return pid;
                }
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        panic!("no explorer process below script");
    }

    fn output(&self) -> Vec<u8> {
        std::fs::read(&self.log).unwrap_or_default()
    }

    fn wait_for(&self, done: impl Fn(&[u8]) -> bool) {
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(10) {
            if done(&self.output()) {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        panic!(
            "timed out; output: {:?}",
            String::from_utf8_lossy(&self.output())
        );
    }

    fn finish(mut self) -> i32 {
        let start = Instant::now();
        loop {
            if let Some(status) = self.script.try_wait().unwrap() {
                return status.code().unwrap_or(-1);
            }
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "the explorer did not exit"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

fn last(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).rposition(|w| w == needle)
}

fn kill(pid: u32, signal: &str) {
    let ok = crate::common::detached("kill")
        .args([&format!("-{signal}"), &pid.to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{signal}");
}

#[test]
fn ending_signals_restore_the_terminal_and_exit_128_plus_n() {
    for (signal, n) in [
        ("INT", 2),
        ("QUIT", 3),
        ("HUP", 1),
        ("USR1", 10),
        ("ALRM", 14),
        ("TERM", 15),
        // Issue 56 (R10): these left the terminal raw, and SEGV and BUS were swallowed (the
        // explorer ran on). The faults end the process by their signal after the terminal is
        // put back: the shell (here `script -e`) sees 128 + n all the same.
        ("PWR", 30),
        ("SYS", 31),
        ("STKFLT", 16),
        ("34", 34), // SIGRTMIN
        ("64", 64), // SIGRTMAX
        ("TRAP", 5),
        ("FPE", 8),
        ("ILL", 4),
        ("SEGV", 11),
        ("BUS", 7),
    ] {
        let e = Explorer::start(signal);
        let pid = e.pid();
        kill(pid, signal);
        let out_before = e.log.clone();
        let code = e.finish();
        assert_eq!(code, 128 + n, "SIGTERM-style exit for SIG{signal}");
        let out = std::fs::read(&out_before).unwrap();
        let entered = last(&out, ENTER_ALT).expect("alternate screen entered");
        let left = last(&out, LEAVE_ALT).expect("alternate screen left");
        assert!(left > entered, "SIG{signal}: still on the alternate screen");
        assert!(
            last(&out, SHOW_CURSOR).is_some_and(|c| c > entered),
            "SIG{signal}: cursor left hidden"
        );
    }
}

#[test]
fn tstp_suspends_and_cont_resumes_in_raw_mode() {
    let mut e = Explorer::start("tstp");
    let pid = e.pid();
    kill(pid, "TSTP");
    let start = Instant::now();
    while state(pid) != 'T' {
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "not stopped: {}",
            state(pid)
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    // The terminal was restored before stopping. (`script` may have stopped itself before
    // copying that last output to its log: let it run to copy it; resumed, it may resume its
    // child too, as a shell's `fg` would.)
    let start = Instant::now();
    while last(&e.output(), LEAVE_ALT).is_none() {
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "terminal not restored"
        );
        kill(e.script.id(), "CONT");
        std::thread::sleep(Duration::from_millis(100));
    }
    // Resume, as `fg` does. `script` stops itself when its child stops (job control) and may do
    // so after a first SIGCONT has arrived: continue both until the explorer is back on the
    // alternate screen.
    let back = |out: &[u8]| match (last(out, ENTER_ALT), last(out, LEAVE_ALT)) {
        (Some(a), Some(b)) => a > b,
        _ => false,
    };
    let start = Instant::now();
    while !back(&e.output()) {
        assert!(start.elapsed() < Duration::from_secs(10), "not resumed");
        kill(pid, "CONT");
        kill(e.script.id(), "CONT");
        std::thread::sleep(Duration::from_millis(200));
    }
    // Keys arrive one by one (raw mode): q without Enter.
    e.script.stdin.as_mut().unwrap().write_all(b"q").unwrap();
    e.script.stdin.as_mut().unwrap().flush().unwrap();
    assert_eq!(e.finish(), 0);
}

/// Quit and signals take effect at once even while `auto` verifies an enormous run (`t_end` =
/// 1e9 at k = 1e8): the verification is cancelled, the terminal restored, nothing waits.
#[test]
fn quit_and_signals_are_immediate_while_auto_verifies_a_huge_run() {
    // Within the work budget (a bigger one is refused at once, tests/it/budget.rs) but minutes
    // of verification before the first frame.
    let preset = std::env::temp_dir().join(format!("rattleback-heavy-{}.toml", std::process::id()));
    std::fs::write(
        &preset,
        "[preset]\nname = \"Heavy\"\n[body]\nix = 2.0\niy = 1.0\niz = 1.0\n[spring]\nk = 1e4\n\
         [initial]\ngamma_dot = 1.0\nalpha_dot = 0.5\n[run]\nt_end = 1e5\n",
    )
    .unwrap();
    let path = preset.to_str().unwrap();
    for how in ["q", "TERM"] {
        let mut e = Explorer::start_with(&format!("heavy-{how}"), &["--preset", path]);
        // Verifying its first segment (`verifying auto…`), or, drawn already, the later ones on
        // their thread (`verified to 48.828125`; the terminal is written cell by cell, so only
        // the word is sure to arrive whole).
        e.wait_for(|out| String::from_utf8_lossy(out).contains("verifi"));
        let start = Instant::now();
        if how == "q" {
            e.script.stdin.as_mut().unwrap().write_all(b"q").unwrap();
            e.script.stdin.as_mut().unwrap().flush().unwrap();
        } else {
            kill(e.pid(), how);
        }
        let code = e.finish();
        assert!(
            start.elapsed() < Duration::from_secs(5),
            "{how} took {:?}",
            start.elapsed()
        );
        assert_eq!(code, if how == "q" { 0 } else { 143 });
    }
    let _ = std::fs::remove_file(&preset);
}

/// Issue 55: whatever ends a recording writes its last frame and checkpoint, so `--verify`
/// checks the frame the audience last saw: SIGTERM, SIGHUP, SIGINT, `q`, and a terminal that
/// hangs up (its pseudo-terminal closed under it, as when SSH drops or tmux is killed: the
/// explorer's next frame failed, `eprintln!` panicked on the dead terminal, and the file had
/// no end).
#[test]
fn every_way_a_recording_ends_writes_and_verifies_its_last_frame() {
    for how in ["TERM", "HUP", "INT", "q", "hang-up"] {
        let file = std::env::temp_dir().join(format!(
            "rattleback-signal-end-{how}-{}.jsonl",
            std::process::id()
        ));
        let _ = std::fs::remove_file(&file);
        let mut e = Explorer::start_with(
            &format!("end-{how}"),
            &[
                "--preset",
                "kapitza-upright",
                "--record",
                file.to_str().unwrap(),
            ],
        );
        let pid = e.pid();
        let log = e.log.clone();
        // Playing when it ends: the last frame is not the first.
        e.script.stdin.as_mut().unwrap().write_all(b" ").unwrap();
        e.script.stdin.as_mut().unwrap().flush().unwrap();
        std::thread::sleep(Duration::from_millis(700));
        match how {
            "q" => {
                e.script.stdin.as_mut().unwrap().write_all(b"q").unwrap();
                e.script.stdin.as_mut().unwrap().flush().unwrap();
                assert_eq!(e.finish(), 0);
            }
            "hang-up" => {
                // The terminal goes away: `script` (the pseudo-terminal's master) is killed.
                kill(e.script.id(), "KILL");
                let _ = e.script.wait();
                let start = Instant::now();
                while std::path::Path::new(&format!("/proc/{pid}")).exists() && state(pid) != 'Z' {
                    assert!(
                        start.elapsed() < Duration::from_secs(10),
                        "the explorer lives on after its terminal hung up"
                    );
                    std::thread::sleep(Duration::from_millis(20));
                }
            }
            signal => {
                kill(pid, signal);
                let n = match signal {
                    "TERM" => 15,
                    "HUP" => 1,
                    _ => 2,
                };
                assert_eq!(e.finish(), 128 + n, "SIG{signal}");
            }
        }
        // Issue 68: where the file went is said on the terminal once the screen is given back
        // (a terminal that hung up hears nothing).
        if how != "hang-up" {
            let said =
                String::from_utf8_lossy(&std::fs::read(&log).unwrap_or_default()).into_owned();
            assert!(
                said.contains(&format!(
                    "rattleback: recording saved to {}",
                    file.display()
                )),
                "ended by {how}: {said}"
            );
        }
        let (code, out, err) = crate::common::bin(&["replay", file.to_str().unwrap(), "--verify"]);
        assert_eq!(code, 0, "ended by {how}: {err}");
        assert!(
            out.contains("the last frame, as recorded"),
            "ended by {how}: {out}"
        );
        let text = std::fs::read_to_string(&file).unwrap();
        let mut screens = text.lines().filter(|l| l.contains(r#""kind":"screen""#));
        assert!(
            screens
                .next_back()
                .is_some_and(|l| !l.contains(r#""t":0.0,"#)),
            "ended by {how}: the last frame is the one at the end, not the start"
        );
        let _ = std::fs::remove_file(&file);
    }
}

/// Issue 56 (R3, R11): an export busy in one frame's long run (a recording that loads the celt
/// at gravity 1e9: seconds a frame) ends on any ending signal at once, not after the frame,
/// with 128 + n and no temporary file left (USR1, USR2, ALRM and XCPU left one).
#[test]
fn an_export_busy_in_a_frame_ends_on_any_signal_without_leaving_a_file() {
    let dir = std::env::temp_dir().join(format!("rattleback-export-signal-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let root = root!();
    let header = std::fs::read_to_string(format!("{root}/tests/fixtures/sessions/kapitza.jsonl"))
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_owned();
    let celt: String = std::fs::read_to_string(format!("{root}/presets/celt-clockwise.toml"))
        .unwrap()
        .lines()
        .map(|l| {
            if l.trim_start().starts_with("gravity") {
                "gravity = 1e9\n".to_owned()
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    assert!(celt.contains("gravity = 1e9"));
    let lines = [
        header,
        serde_json::json!({"wall": 0.5, "t": 0.0, "generation": 1, "kind": "preset", "toml": celt})
            .to_string(),
        r#"{"wall":0.6,"t":0.0,"generation":2,"kind":"speed","value":64.0}"#.to_owned(),
        r#"{"wall":0.7,"t":0.0,"generation":2,"kind":"play"}"#.to_owned(),
        r#"{"wall":60.0,"t":0.0,"generation":2,"kind":"pause"}"#.to_owned(),
    ];
    let session = dir.join("heavy.jsonl");
    std::fs::write(&session, lines.join("\n") + "\n").unwrap();
    for (signal, n) in [
        ("INT", 2),
        ("TERM", 15),
        ("USR1", 10),
        ("USR2", 12),
        ("ALRM", 14),
        ("XCPU", 24),
    ] {
        let out = dir.join("x.cast");
        let mut child = crate::common::rattleback()
            .arg("replay")
            .arg(&session)
            .arg("--export-cast")
            .arg(&out)
            .arg("--force")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Into the frame's run: its temporary file exists.
        let start = Instant::now();
        while !std::fs::read_dir(&dir)
            .unwrap()
            .any(|e| e.unwrap().file_name().to_string_lossy().ends_with(".tmp"))
        {
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "no temporary file"
            );
            std::thread::sleep(Duration::from_millis(10));
        }
        std::thread::sleep(Duration::from_millis(300));
        kill(child.id(), signal);
        let start = Instant::now();
        let status = loop {
            if let Some(s) = child.try_wait().unwrap() {
                break s;
            }
            // A bound against a hang (it took 9-19 s, the frame's run): the watchdog's grace is
            // 60 ms.
            assert!(
                start.elapsed() < Duration::from_secs(5),
                "SIG{signal}: still running"
            );
            std::thread::sleep(Duration::from_millis(5));
        };
        assert_eq!(status.code(), Some(128 + n), "SIG{signal}");
        let left: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|f| f != "heavy.jsonl")
            .collect();
        assert!(left.is_empty(), "SIG{signal} left {left:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
