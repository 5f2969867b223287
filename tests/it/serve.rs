//! Issue 71: `rattleback serve`, a new door built to the old doors' rules. Its first line is the
//! address; a token guards every address but loopback (and `--no-token` there is refused);
//! only three paths answer, none reaching the file system; oversized headers get 431, invalid
//! bytes and wrong tokens are refused; a thousand half-open connections do not keep a new
//! reader out; three hundred readers each get the last frame within 5 s while the server stays
//! under 300 MB; a reader that never reads slows nobody; the frames are the replay's; the
//! lecturer's frame rate is measured with and without the readers. On loopback only, bounded
//! in count and time. The clients here are raw sockets (a test may forge any request; the
//! server's side is hyper's).

use std::io::{BufRead as _, BufReader, Read as _, Write as _};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rattleback-serve-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join(name);
    let _ = std::fs::remove_file(&p);
    p
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures/sessions")
        .join(name)
}

/// A running `serve`, stopped when dropped.
struct Served {
    child: Child,
    url: String,
    addr: SocketAddr,
}

impl Served {
    fn start(file: &Path, args: &[&str]) -> Self {
        let mut child = crate::common::rattleback()
            .arg("serve")
            .arg(file)
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut first = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut first)
            .unwrap();
        let url = first.trim_end().to_owned();
        let hostport = url
            .strip_prefix("http://")
            .and_then(|r| r.split('/').next())
            .unwrap_or_else(|| panic!("the first line is not an address: {first:?}"));
        let port: u16 = hostport.rsplit(':').next().unwrap().parse().unwrap();
        Self {
            child,
            url,
            addr: SocketAddr::from(([127, 0, 0, 1], port)),
        }
    }

    /// The server's peak resident memory so far, in bytes (Linux).
    fn peak_memory(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).unwrap();
        let kb: u64 = status
            .lines()
            .find_map(|l| l.strip_prefix("VmHWM:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
            .unwrap();
        kb * 1024
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Sends `request` (raw bytes) and reads the whole answer (the server closes, or 5 s pass).
fn raw(addr: SocketAddr, request: &[u8]) -> String {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    s.write_all(request).unwrap();
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    String::from_utf8_lossy(&out).into_owned()
}

fn get(addr: SocketAddr, target: &str) -> String {
    raw(
        addr,
        format!("GET {target} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n").as_bytes(),
    )
}

fn status(answer: &str) -> u16 {
    answer
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no status line: {answer:?}"))
}

#[test]
fn the_first_line_is_the_address_and_only_its_paths_answer() {
    let s = Served::start(&fixture("lecture.jsonl"), &[]);
    assert!(
        s.url.starts_with("http://127.0.0.1:") && s.url.ends_with('/'),
        "{}",
        s.url
    );
    let page = get(s.addr, "/");
    assert_eq!(status(&page), 200, "{}", &page[..200.min(page.len())]);
    assert!(
        page.contains("content-security-policy"),
        "the page's own policy"
    );
    assert!(!page.contains("src=\"http"), "no outside request");
    for path in [
        "/nope",
        "/../Cargo.toml",
        "/%2e%2e/%2e%2e/etc/passwd",
        "//etc/passwd",
        "/events/../session.jsonl/../../etc/passwd",
        "/session.jsonl/x",
        "/index.html",
    ] {
        let a = get(s.addr, path);
        assert_eq!(status(&a), 404, "{path}: {a}");
    }
    let post = raw(
        s.addr,
        b"POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 2\r\nConnection: close\r\n\r\nhi",
    );
    assert_eq!(status(&post), 405, "{post}");
    // A page elsewhere whose name was turned into 127.0.0.1 (DNS rebinding) says its own name.
    let rebound = raw(
        s.addr,
        b"GET /session.jsonl HTTP/1.1\r\nHost: evil.example:80\r\nConnection: close\r\n\r\n",
    );
    assert_eq!(status(&rebound), 403, "{rebound}");
    // The file so far: its complete lines, as written.
    let file = get(s.addr, "/session.jsonl");
    assert_eq!(status(&file), 200);
    let body = file.split("\r\n\r\n").nth(1).unwrap();
    assert_eq!(
        body.as_bytes(),
        std::fs::read(fixture("lecture.jsonl")).unwrap().as_slice()
    );
}

#[test]
fn a_token_guards_every_address_but_loopback_and_cannot_be_waived_there() {
    let (code, out, err) =
        crate::common::bin(&["serve", "x.jsonl", "--listen", "0.0.0.0:0", "--no-token"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(out.is_empty(), "no address printed: {out}");
    assert!(
        err.contains("--no-token on 0.0.0.0:0") && err.contains("loopback"),
        "{err}"
    );
    let s = Served::start(&fixture("lecture.jsonl"), &["--listen", "0.0.0.0:0"]);
    let token = s
        .url
        .split("?token=")
        .nth(1)
        .unwrap_or_else(|| panic!("no token in {}", s.url));
    assert_eq!(token.len(), 32, "{token}");
    assert!(!s.url.contains("0.0.0.0"), "a reachable host: {}", s.url);
    for target in ["/", "/events", "/session.jsonl", "/nope"] {
        for query in ["", "?token=", "?token=0123", &format!("?token={token}x")] {
            let a = get(s.addr, &format!("{target}{query}"));
            assert_eq!(status(&a), 403, "{target}{query}: {a}");
        }
    }
    let page = get(s.addr, &format!("/?token={token}"));
    assert_eq!(status(&page), 200);
    assert!(
        page.contains(&format!("session.jsonl?token={token}")),
        "the page's links carry the token"
    );
    let file = get(s.addr, &format!("/session.jsonl?token={token}"));
    assert_eq!(status(&file), 200);
}

#[test]
fn oversized_headers_invalid_bytes_and_too_many_readers_are_refused_clearly() {
    let s = Served::start(&fixture("lecture.jsonl"), &["--max-readers", "2"]);
    let big = format!(
        "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Big: {}\r\n\r\n",
        "a".repeat(20_000)
    );
    let a = raw(s.addr, big.as_bytes());
    assert_eq!(status(&a), 431, "{a}");
    let a = raw(
        s.addr,
        b"GET /\xff\xfe/../\xc0\xaf HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n",
    );
    let code = status(&a);
    assert!(code == 400 || code == 404, "{a}");
    let a = raw(
        s.addr,
        b"\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03garbage\r\n\r\n",
    );
    assert!(a.is_empty() || status(&a) == 400, "{a}");
    // Two readers, then a third is told why.
    let mut readers = Vec::new();
    for _ in 0..2 {
        let mut r = TcpStream::connect(s.addr).unwrap();
        r.write_all(b"GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            .unwrap();
        let mut buf = [0u8; 256];
        r.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
        let n = r.read(&mut buf).unwrap();
        assert!(String::from_utf8_lossy(&buf[..n]).starts_with("HTTP/1.1 200"));
        readers.push(r);
    }
    let third = get(s.addr, "/events");
    assert_eq!(status(&third), 503, "{third}");
    assert!(third.contains("--max-readers"), "{third}");
    drop(readers);
    // The server goes on serving.
    assert_eq!(status(&get(s.addr, "/")), 200);
}

/// A reader of `/events`: everything it received, and when it saw the stream's end.
fn reader(addr: SocketAddr, limit: Duration) -> (String, Option<Instant>) {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_millis(500)))
        .unwrap();
    s.write_all(b"GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .unwrap();
    let end = Instant::now() + limit;
    let mut got = Vec::new();
    let mut buf = [0u8; 16384];
    while Instant::now() < end {
        match s.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => {
                got.extend_from_slice(&buf[..n]);
                if got.windows(11).any(|w| w == b"event: done") {
                    return (
                        String::from_utf8_lossy(&got).into_owned(),
                        Some(Instant::now()),
                    );
                }
            }
            Err(_) => {}
        }
    }
    (String::from_utf8_lossy(&got).into_owned(), None)
}

/// The screen a stream ends on (its last reset and every frame after it), as a terminal
/// shows it.
fn last_screen(stream: &str) -> String {
    let n = |x: u16| std::num::NonZeroU16::new(x.max(1)).unwrap();
    let mut parser = vt100::Parser::new(n(24), n(80), 0);
    for line in stream.lines() {
        let Some(data) = line.strip_prefix("data: ") else {
            continue;
        };
        // Frames and resets are JSON; the end says `ended`.
        let Ok(v) = serde_json::from_str::<serde_json::Value>(data) else {
            continue;
        };
        if let Some(init) = v.get("init").and_then(|i| i.as_str()) {
            let rows = v["rows"].as_u64().unwrap() as u16;
            let cols = v["cols"].as_u64().unwrap() as u16;
            parser = vt100::Parser::new(n(rows), n(cols), 0);
            parser.process(init.as_bytes());
        } else if let Some(text) = v.get(2).and_then(|t| t.as_str()) {
            parser.process(text.as_bytes());
        }
    }
    parser.screen().contents()
}

/// The frames served are the replay's: a finished lecture's stream ends on the screen its
/// exported page ends on (the lecturer's own last status bar, checked by `replay --verify`).
#[test]
fn a_finished_lecture_is_served_as_its_replay_ends_then_as_its_page() {
    let s = Served::start(&fixture("lecture.jsonl"), &[]);
    let (stream, done) = reader(s.addr, Duration::from_secs(30));
    assert!(
        done.is_some(),
        "the stream says the recording ended: {stream}"
    );
    assert!(stream.starts_with("HTTP/1.1 200"), "{stream}");
    assert!(
        stream.contains("content-type: text/event-stream"),
        "{stream}"
    );
    let screen = last_screen(&stream);
    for want in ["● REC │ t 30.00/30 │ done", "reversals 7 limit 7"] {
        assert!(screen.contains(want), "{want}:\n{screen}");
    }
    let page = get(s.addr, "/");
    assert!(
        page.contains("The lecture has ended"),
        "the whole session's page"
    );
    assert!(page.contains("chapter one"), "with its chapters");
    // A reader who joins after the end gets the end at once.
    let (late, done) = reader(s.addr, Duration::from_secs(5));
    assert!(done.is_some(), "{late}");
    assert!(last_screen(&late).contains("t 30.00/30"));
}

/// Copies `from` to `to` a line every `spacing`, with each line's wall clock set to when it is
/// written, as the lecturer's explorer writes it.
fn record_live(from: &Path, to: &Path, spacing: Duration) {
    let text = std::fs::read_to_string(from).unwrap();
    let mut out = std::fs::File::create(to).unwrap();
    for line in text.lines() {
        out.write_all(line.as_bytes()).unwrap();
        out.write_all(b"\n").unwrap();
        out.flush().unwrap();
        std::thread::sleep(spacing);
    }
}

#[test]
fn three_hundred_readers_each_get_the_last_frame_and_the_server_stays_small() {
    let file = temp("hall.jsonl");
    let s = Served::start(&file, &[]);
    // Readers who came before the lecturer.
    let readers: Vec<_> = (0..300)
        .map(|_| {
            let addr = s.addr;
            std::thread::spawn(move || reader(addr, Duration::from_secs(60)))
        })
        .collect();
    std::thread::sleep(Duration::from_millis(500));
    record_live(&fixture("lecture.jsonl"), &file, Duration::from_millis(5));
    let results: Vec<_> = readers.into_iter().map(|r| r.join().unwrap()).collect();
    let ends: Vec<Instant> = results.iter().filter_map(|(_, d)| *d).collect();
    assert_eq!(ends.len(), 300, "every reader is told the lecture ended");
    let first = *ends.iter().min().unwrap();
    let last = *ends.iter().max().unwrap();
    assert!(
        last - first < Duration::from_secs(5),
        "the last reader got the end {:?} after the first",
        last - first
    );
    for (stream, _) in &results {
        let screen = last_screen(stream);
        assert!(
            screen.contains("t 30.00/30") && screen.contains("reversals 7 limit 7"),
            "{screen}"
        );
    }
    let peak = s.peak_memory();
    eprintln!(
        "300 readers: the end reached all within {:?}; server peak memory {} MB",
        last - first,
        peak >> 20
    );
    assert!(peak < 300 << 20, "peak memory {} MB", peak >> 20);
}

#[test]
fn a_thousand_half_open_connections_do_not_keep_a_new_reader_out() {
    let s = Served::start(&fixture("lecture.jsonl"), &[]);
    let mut idle: Vec<TcpStream> = (0..1000)
        .map(|i| {
            let mut c = TcpStream::connect(s.addr).unwrap();
            // Half a request, or nothing at all.
            if i % 2 == 0 {
                c.write_all(b"GET / HTTP/1.1\r\nHost: 12").unwrap();
            }
            c
        })
        .collect();
    let start = Instant::now();
    let page = get(s.addr, "/");
    let took = start.elapsed();
    assert_eq!(status(&page), 200);
    // Under the 5 s a half-open connection is kept (issue 83: wide for a shared machine).
    assert!(took < Duration::from_secs(4), "the page took {took:?}");
    // A few seconds on, the server has closed them (header read time, 5 s).
    std::thread::sleep(Duration::from_secs(7));
    let closed = idle
        .iter_mut()
        .map(|c| {
            c.set_read_timeout(Some(Duration::from_millis(20))).unwrap();
            let mut b = [0u8; 512];
            match c.read(&mut b) {
                Ok(0) => true,
                Ok(_) => c.read(&mut b).is_ok_and(|n| n == 0),
                Err(e) => e.kind() == std::io::ErrorKind::ConnectionReset,
            }
        })
        .filter(|closed| *closed)
        .count();
    assert!(closed >= 990, "{closed} of 1000 idle connections closed");
    eprintln!("1000 half-open connections: a new reader's page in {took:?}; {closed} closed");
}

#[test]
fn a_reader_that_never_reads_slows_nobody() {
    let file = temp("stalled.jsonl");
    let s = Served::start(&file, &["--fps", "30"]);
    let mut stalled = TcpStream::connect(s.addr).unwrap();
    stalled
        .write_all(b"GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .unwrap();
    let addr = s.addr;
    let reading = std::thread::spawn(move || reader(addr, Duration::from_secs(60)));
    record_live(&fixture("lecture.jsonl"), &file, Duration::from_millis(5));
    let (stream, done) = reading.join().unwrap();
    assert!(done.is_some(), "the reading reader got the end");
    assert!(last_screen(&stream).contains("t 30.00/30"));
    drop(stalled);
}

/// The lecturer's explorer, playing at ×1 in a pseudo-terminal for 4 s while recording: the
/// frames it drew (each begins a synchronised update).
/// The lecturer's explorer recording `subcritical` into `record` in an 80x24 pseudo-terminal
/// (its output in `log`), and its keys.
fn recording_lecturer(record: &Path, log: &Path) -> (Killed, std::process::ChildStdin) {
    let command = format!(
        "stty rows 24 cols 80; exec {} --record {} --preset subcritical",
        crate::common::program(),
        record.display()
    );
    let mut child = Killed(
        crate::common::in_pty(&command, log)
            .env("TERM", "xterm-256color")
            .stdin(Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let keys = child.0.stdin.take().unwrap();
    (child, keys)
}

fn lecturer_frames(record: &Path, log: &Path) -> usize {
    let (mut child, mut keys) = recording_lecturer(record, log);
    std::thread::sleep(Duration::from_millis(800));
    let before = std::fs::read(log).map_or(0, |b| count_frames(&b));
    keys.write_all(b" ").unwrap();
    std::thread::sleep(Duration::from_secs(4));
    keys.write_all(b" ").unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let after = count_frames(&std::fs::read(log).unwrap());
    keys.write_all(b"q").unwrap();
    let _ = child.0.wait();
    after - before
}

fn count_frames(bytes: &[u8]) -> usize {
    bytes.windows(8).filter(|w| w == b"\x1b[?2026h").count()
}

#[test]
fn the_lecturers_frame_rate_with_and_without_three_hundred_readers() {
    let alone_file = temp("alone.jsonl");
    let alone = lecturer_frames(&alone_file, &temp("alone.pty"));
    let file = temp("watched.jsonl");
    let s = Served::start(&file, &[]);
    let addr = s.addr;
    let readers: Vec<_> = (0..300)
        .map(|_| std::thread::spawn(move || reader(addr, Duration::from_secs(20))))
        .collect();
    let watched = lecturer_frames(&file, &temp("watched.pty"));
    let results: Vec<_> = readers.into_iter().map(|r| r.join().unwrap()).collect();
    eprintln!("the lecturer's frames in 4 s at x1: {alone} alone, {watched} with 300 readers");
    assert!(alone > 40, "the explorer drew {alone} frames in 4 s");
    // Both recordings verify; the readers saw the lecture end.
    for f in [alone_file, file] {
        let (code, out, err) = crate::common::bin(&["replay", f.to_str().unwrap(), "--verify"]);
        assert_eq!(code, 0, "{out}{err}");
    }
    assert!(
        results.iter().all(|(_, d)| d.is_some()),
        "every reader saw the end"
    );
    // Not a timing target (the machines are shared): a lecturer slowed to half would show.
    assert!(
        watched * 2 >= alone,
        "{watched} frames with the readers against {alone} alone"
    );
}

#[test]
fn a_token_can_be_asked_for_on_loopback_too() {
    let s = Served::start(&fixture("lecture.jsonl"), &["--token"]);
    let token = s
        .url
        .split("?token=")
        .nth(1)
        .unwrap_or_else(|| panic!("{}", s.url));
    assert_eq!(status(&get(s.addr, "/")), 403);
    assert_eq!(status(&get(s.addr, &format!("/?token={token}"))), 200);
}

/// A child killed when the test ends, passed or not (an explorer left running in its
/// pseudo-terminal would keep its server too).
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The explorer's `--serve`: the server starts beside it, the explorer opens on the address
/// (with its QR code), the address serves the page; when the explorer quits, a reader gets the
/// lecture's end (issue 80, L1: the server died with the explorer and the pages spun "Live"),
/// and the server stops by itself soon after. An address it cannot listen at is refused before
/// the terminal is touched.
#[test]
fn the_explorer_serves_its_recording_and_stops_its_server_when_it_quits() {
    let file = temp("beside.jsonl");
    let log = temp("beside.pty");
    let command = format!(
        "stty rows 24 cols 80; exec {} --record {} --serve",
        crate::common::program(),
        file.display()
    );
    let mut child = Killed(
        crate::common::in_pty(&command, &log)
            .env("TERM", "xterm-256color")
            .stdin(Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let mut keys = child.0.stdin.take().unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    let url = loop {
        let drawn = String::from_utf8_lossy(&std::fs::read(&log).unwrap_or_default()).into_owned();
        if let Some(at) = drawn.find("http://127.0.0.1:") {
            let rest = &drawn[at..];
            let end = rest
                .find('/')
                .map(|i| i + 2 + rest[i + 2..].find('/').unwrap_or(0));
            if let Some(end) = end.filter(|&e| e > 17) {
                assert!(
                    drawn.contains("served") && drawn.contains("closes)"),
                    "{drawn}"
                );
                assert!(
                    drawn.contains('▀') || drawn.contains('▄'),
                    "a QR code is drawn"
                );
                break rest[..=end].to_owned();
            }
        }
        assert!(Instant::now() < deadline, "no address shown: {drawn}");
        std::thread::sleep(Duration::from_millis(100));
    };
    let port: u16 = url
        .trim_end_matches('/')
        .rsplit(':')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|e| panic!("{url}: {e}"));
    let addr = SocketAddr::from(([127, 0, 0, 1], port));
    assert_eq!(status(&get(addr, "/")), 200);
    let hall = std::thread::spawn(move || reader(addr, Duration::from_secs(30)));
    std::thread::sleep(Duration::from_millis(300));
    // Esc closes the address; space plays a moment; q quits.
    keys.write_all(b"\x1b").unwrap();
    std::thread::sleep(Duration::from_millis(600));
    keys.write_all(b" ").unwrap();
    std::thread::sleep(Duration::from_millis(800));
    keys.write_all(b"q").unwrap();
    let _ = child.0.wait();
    let (stream, ended) = hall.join().unwrap();
    assert!(
        ended.is_some(),
        "the reader was not told the lecture ended: {stream}"
    );
    // The finished page is served, then the server goes (its grace is a few seconds).
    let deadline = Instant::now() + Duration::from_secs(20);
    while TcpStream::connect(addr).is_ok() {
        assert!(
            Instant::now() < deadline,
            "the server outlived the explorer by more than its grace"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    let (code, out, err) = crate::common::bin(&["replay", file.to_str().unwrap(), "--verify"]);
    assert_eq!(code, 0, "{out}{err}");

    let log = temp("refused.pty");
    let command = format!(
        "stty rows 24 cols 80; exec {} --record {} --serve 203.0.113.9:8080",
        crate::common::program(),
        temp("refused.jsonl").display()
    );
    let status = crate::common::in_pty(&command, &log)
        .stdin(Stdio::null())
        .status()
        .unwrap();
    let said = String::from_utf8_lossy(&std::fs::read(&log).unwrap()).into_owned();
    assert_eq!(status.code(), Some(2), "{said}");
    assert!(
        said.contains("--serve 203.0.113.9:8080: the server did not start"),
        "{said}"
    );
    assert!(
        !said.contains("\u{1b}[?1049h"),
        "the terminal was not touched: {said}"
    );
}

/// The address dialog through the `TestBackend`: at 80×24 the QR code and the address whole
/// (the code read back module by module is `ui::qr`'s unit test), in ASCII at 160×48 too (a module two characters wide, a line tall); where
/// the code does not fit, the address alone; at 20×5 nothing panics.
#[test]
fn the_address_dialog_shows_the_code_where_it_fits_and_the_address_always() {
    use ratatui::Terminal;
    use ratatui::backend::TestBackend;
    use rattleback::ui::glyphs::Charset;
    use rattleback::ui::{self, Cache, UiOptions};
    let url = "http://192.168.10.20:8080/?token=0123456789abcdef0123456789abcdef";
    let (mut app, _) = rattleback::app::App::new(
        &rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap(),
        rattleback::app::Options::at(30.0),
    );
    app.show_address(url);
    let draw = |app: &rattleback::app::App, w: u16, h: u16, charset: Charset| {
        let options = UiOptions::default().with_charset(charset);
        let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
        terminal
            .draw(|f| ui::draw(f, app, &options, &mut Cache::default()))
            .unwrap();
        let b = terminal.backend().buffer().clone();
        (0..h)
            .map(|y| (0..w).map(|x| b[(x, y)].symbol()).collect::<String>())
            .collect::<Vec<_>>()
            .join("\n")
    };
    let screen = draw(&app, 80, 24, Charset::Unicode);
    assert!(screen.contains(url), "{screen}");
    assert!(screen.contains("served at (any key closes)"), "{screen}");
    assert!(screen.matches('▀').count() > 20, "a QR code:\n{screen}");
    let ascii = draw(&app, 160, 48, Charset::Ascii);
    assert!(ascii.contains(url) && ascii.contains("####"), "{ascii}");
    assert!(ascii.lines().all(str::is_ascii), "{ascii}");
    let narrow = draw(&app, 80, 24, Charset::Ascii);
    assert!(narrow.contains(url), "the address alone: {narrow}");
    assert!(narrow.contains("served at (any key closes)"), "{narrow}");
    let _ = draw(&app, 20, 5, Charset::Unicode);
    // Any key closes it and acts; Esc only closes; `U` shows it again where it was served.
    app.on_key(rattleback::app::Key::Esc);
    assert!(!draw(&app, 80, 24, Charset::Unicode).contains(url));
    app.on_key(rattleback::app::Key::Char('U'));
    let said = draw(&app, 80, 24, Charset::Unicode);
    assert!(!said.contains(url) && said.contains("not served"), "{said}");
    let (mut served, _) = rattleback::app::App::new(
        &rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap(),
        rattleback::app::Options {
            served: Some(url.to_owned()),
            ..rattleback::app::Options::at(30.0)
        },
    );
    served.on_key(rattleback::app::Key::Char('U'));
    assert!(draw(&served, 80, 24, Charset::Unicode).contains(url));
}

/// shared/docs/reviews/reliability.md N4 and N5 (issue 80): `serve` reads only a regular file,
/// by its name. A FIFO, a link or a folder is refused at start; one put at the path later is
/// never opened through (the file is 404), a thread is never parked on it, and the server
/// answers as before.
#[test]
fn only_a_regular_file_is_served_never_a_fifo_a_link_or_a_folder() {
    let dir = temp("kinds");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("fifo.jsonl");
    assert!(
        crate::common::detached("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let link = dir.join("link.jsonl");
    std::os::unix::fs::symlink("/etc/passwd", &link).unwrap();
    for (path, words) in [
        (&fifo, "not a regular file"),
        (&link, "a symbolic link"),
        (&dir, "a folder"),
    ] {
        let (code, _, err) = crate::common::bin(&["serve", path.to_str().unwrap()]);
        assert_eq!(code, 2, "{path:?}: {err}");
        assert!(err.contains(words), "{path:?}: {err}");
    }
    // Swapped in while served.
    let file = dir.join("mut.jsonl");
    std::fs::copy(fixture("lecture.jsonl"), &file).unwrap();
    let s = Served::start(&file, &[]);
    assert_eq!(status(&get(s.addr, "/session.jsonl")), 200);
    std::fs::remove_file(&file).unwrap();
    std::os::unix::fs::symlink("/etc/passwd", &file).unwrap();
    let a = get(s.addr, "/session.jsonl");
    assert_eq!(status(&a), 404, "{a}");
    assert!(!a.contains("root:"), "{a}");
    std::fs::remove_file(&file).unwrap();
    assert!(
        crate::common::detached("mkfifo")
            .arg(&file)
            .status()
            .unwrap()
            .success()
    );
    // More requests than tokio's blocking pool has threads (512): none waits on the FIFO.
    let requests: Vec<_> = (0..600)
        .map(|_| {
            let addr = s.addr;
            std::thread::spawn(move || status(&get(addr, "/session.jsonl")))
        })
        .collect();
    for r in requests {
        assert_eq!(r.join().unwrap(), 404);
    }
    let page = get(s.addr, "/");
    assert_eq!(status(&page), 200, "the server still answers");
}

/// N10 (issue 80): one address cannot take every reader's place; the refusal names the flag.
#[test]
fn one_address_cannot_take_every_readers_place() {
    let s = Served::start(&fixture("lecture.jsonl"), &["--max-per-address", "3"]);
    let mut readers = Vec::new();
    for _ in 0..3 {
        let mut r = TcpStream::connect(s.addr).unwrap();
        r.write_all(b"GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            .unwrap();
        let mut buf = [0u8; 256];
        r.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
        let n = r.read(&mut buf).unwrap();
        assert!(String::from_utf8_lossy(&buf[..n]).starts_with("HTTP/1.1 200"));
        readers.push(r);
    }
    let fourth = get(s.addr, "/events");
    assert_eq!(status(&fourth), 503, "{fourth}");
    assert!(fourth.contains("--max-per-address"), "{fourth}");
    // A place given back is taken again.
    drop(readers.pop());
    std::thread::sleep(Duration::from_millis(300));
    let mut r = TcpStream::connect(s.addr).unwrap();
    r.write_all(b"GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        .unwrap();
    let mut buf = [0u8; 256];
    r.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    let n = r.read(&mut buf).unwrap();
    assert!(String::from_utf8_lossy(&buf[..n]).starts_with("HTTP/1.1 200"));
}

/// L1 (issue 80) with a signal: the explorer recording with `--serve` ended by SIGTERM (as a
/// closing terminal or a session manager ends it); a reader of `/events` still gets the end, and
/// the server exits by itself.
#[test]
fn a_lecture_ended_by_a_signal_still_ends_in_every_page() {
    let file = temp("signalled.jsonl");
    let log = temp("signalled.pty");
    let port = {
        let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        l.local_addr().unwrap().port()
    };
    let command = format!(
        "stty rows 24 cols 80; exec {} --record {} --serve 127.0.0.1:{port}",
        crate::common::program(),
        file.display()
    );
    let mut child = Killed(
        crate::common::in_pty(&command, &log)
            .env("TERM", "xterm-256color")
            .stdin(Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let mut keys = child.0.stdin.take().unwrap();
    let addr = SocketAddr::from(([127, 0, 0, 1], port));
    let deadline = Instant::now() + Duration::from_secs(10);
    while TcpStream::connect(addr).is_err() {
        assert!(Instant::now() < deadline, "the server never listened");
        std::thread::sleep(Duration::from_millis(100));
    }
    let hall = std::thread::spawn(move || reader(addr, Duration::from_secs(30)));
    std::thread::sleep(Duration::from_millis(500));
    keys.write_all(b"\x1b").unwrap();
    std::thread::sleep(Duration::from_millis(500));
    keys.write_all(b" ").unwrap();
    std::thread::sleep(Duration::from_millis(800));
    let pattern = format!("record {}", file.display());
    let killed = crate::common::detached("pkill")
        .args(["-TERM", "-f", &pattern])
        .status()
        .unwrap();
    assert!(killed.success(), "no explorer to signal");
    let _ = child.0.wait();
    let (stream, ended) = hall.join().unwrap();
    assert!(
        ended.is_some(),
        "the reader was not told the lecture ended: {stream}"
    );
    let deadline = Instant::now() + Duration::from_secs(20);
    while TcpStream::connect(addr).is_ok() {
        assert!(
            Instant::now() < deadline,
            "the server did not exit by itself"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// Issue 82: `serve --site DIR` serves the browser explorer's module (read once; a fork
/// computes in the reader's browser, so the server gives the module and the session and
/// nothing more), and its page carries the fork (`f`, the worker, Esc back). Without `--site`
/// the module's address says why there is none and how to add it. A site that is not one (no
/// module, a link, a FIFO, a file that is not WebAssembly) is refused before serving, naming
/// the file.
#[test]
fn a_site_is_served_for_forks_and_refused_when_it_is_not_one() {
    let dir = temp("site");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let module = dir.join("rattleback.wasm");
    // The smallest valid module: its magic and version.
    let bytes = b"\0asm\x01\0\0\0".to_vec();
    std::fs::write(&module, &bytes).unwrap();
    let s = Served::start(
        &fixture("lecture.jsonl"),
        &["--site", dir.to_str().unwrap()],
    );
    let got = get(s.addr, "/rattleback.wasm");
    assert_eq!(status(&got), 200, "{got}");
    assert!(
        got.to_ascii_lowercase()
            .contains("content-type: application/wasm"),
        "{got}"
    );
    assert!(got.ends_with("\0asm\u{1}\0\0\0"), "{got:?}");
    let page = get(s.addr, "/");
    for part in [
        "fork (f)",
        "rattlebackExplorer",
        "rb_fork",
        "worker-src blob:",
        "Escape",
    ] {
        assert!(page.contains(part), "the page has {part}");
    }
    drop(s);
    let bare = Served::start(&fixture("lecture.jsonl"), &[]);
    let none = get(bare.addr, "/rattleback.wasm");
    assert_eq!(status(&none), 404, "{none}");
    assert!(none.contains("--site DIR"), "{none}");
    drop(bare);
    // Not a site.
    std::fs::write(&module, b"<html>not a module</html>").unwrap();
    let lecture = fixture("lecture.jsonl");
    let serve = |site: &Path| {
        crate::common::bin(&[
            "serve",
            lecture.to_str().unwrap(),
            "--site",
            site.to_str().unwrap(),
        ])
    };
    let (code, _, err) = serve(&dir);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("not a WebAssembly module") && err.contains("rattleback web"),
        "{err}"
    );
    std::fs::remove_file(&module).unwrap();
    let (code, _, err) = serve(&dir);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("rattleback.wasm"), "{err}");
    std::os::unix::fs::symlink("/etc/passwd", &module).unwrap();
    let (code, _, err) = serve(&dir);
    assert_eq!(code, 2, "a link is not followed: {err}");
    std::fs::remove_file(&module).unwrap();
    assert!(
        crate::common::detached("mkfifo")
            .arg(&module)
            .status()
            .unwrap()
            .success()
    );
    let (code, _, err) = serve(&dir);
    assert_eq!(code, 2, "a FIFO is refused without blocking: {err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 82, L3: what the lecturer does is served without waiting for `--fps`'s next frame,
/// yet a lecturer holding keys (a key line every few milliseconds) never makes the server send
/// more than its ceiling of 30 frames a second to a reader: the frames' own times, in any
/// second, number at most 30 (with the prompt frames 10 ms apart and the file read every 5 ms,
/// this test counted more and failed).
#[test]
fn a_lecturer_holding_keys_is_served_promptly_under_the_frame_ceiling() {
    let file = temp("held.jsonl");
    let s = Served::start(&file, &[]);
    let addr = s.addr;
    let stream = std::thread::spawn(move || reader(addr, Duration::from_secs(12)));
    let (mut child, mut keys) = recording_lecturer(&file, &temp("held.pty"));
    std::thread::sleep(Duration::from_millis(800));
    // Playing (the time moves every frame), a selection moved up and down a few milliseconds
    // apart: each a line the lecturer acted on, so the server draws promptly throughout.
    keys.write_all(b"\x1b").unwrap();
    std::thread::sleep(Duration::from_millis(200));
    keys.write_all(b" ").unwrap();
    let held = Instant::now();
    while held.elapsed() < Duration::from_secs(3) {
        keys.write_all(b"j").unwrap();
        std::thread::sleep(Duration::from_millis(4));
        keys.write_all(b"k").unwrap();
        std::thread::sleep(Duration::from_millis(4));
    }
    keys.write_all(b"q").unwrap();
    let _ = child.0.wait();
    let (text, done) = stream.join().unwrap();
    assert!(done.is_some(), "the reader saw the lecture end");
    let times: Vec<f64> = text
        .lines()
        .filter_map(|l| l.strip_prefix("data: ["))
        .filter_map(|l| l.split(',').next()?.parse().ok())
        .collect();
    assert!(times.len() > 10, "{} frames", times.len());
    let most = (0..times.len())
        .map(|i| {
            times[i..]
                .iter()
                .take_while(|t| **t < times[i] + 1.0)
                .count()
        })
        .max()
        .unwrap();
    eprintln!(
        "frames served: {} in all, at most {most} in one second",
        times.len()
    );
    assert!(most <= 30, "{most} frames in one second (ceiling 30)");
}
