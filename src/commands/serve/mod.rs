//! `rattleback serve FILE`: checks what it is asked (the address, the token, the file), prints
//! the address to open as its first line, then runs the renderer ([`live`]) and the server
//! ([`http`]) until Ctrl-C or another ending signal; they meet in a [`Hub`].
//!
//! The renderer follows the session file as `follow` does (the same tail, replay and worker)
//! and draws each frame into memory as `--export-cast` does (`cast::MemoryScreen`):
//! the frames served are the replay's, which `replay --verify` checks. The server is hyper on
//! a small tokio runtime: `/` the page, `/events` a Server-Sent Events stream of the frames,
//! `/session.jsonl` the file so far; nothing else, and no path reaches the file system.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

pub mod http;
pub mod hub;
pub mod live;

use crate::commands::cli::ServeArgs;
use crate::commands::failure::{Failure, Outcome};
use hub::{Config, DEFAULT_MAX_PER_ADDRESS, DEFAULT_MAX_READERS, Hub};

/// Frames a second drawn for the readers, unless `--fps` says otherwise (the exported page's).
pub const DEFAULT_FPS: u32 = 10;
/// The most frames a second `serve` draws (each is sent to every reader).
pub const MAX_FPS: u32 = 30;

/// The address `--listen` defaults to: loopback, a free port.
#[must_use]
pub fn default_listen() -> std::net::SocketAddr {
    std::net::SocketAddr::from(([127, 0, 0, 1], 0))
}

/// What `serve` is asked, checked: the address, and the token it requires (`wanted`: one even
/// on loopback).
///
/// # Errors
/// `--no-token` on an address other than loopback; a failing random generator.
pub fn token_for(
    listen: &std::net::SocketAddr,
    no_token: bool,
    wanted: bool,
) -> Result<Option<String>, Failure> {
    if hub::tokenless_allowed(listen) && !wanted {
        return Ok(None);
    }
    if no_token {
        return Err(Failure::input(format!(
            "--no-token on {listen}: anyone who reaches that address could read the lecture; a token is required on every address but loopback (127.0.0.1, ::1). Drop --no-token (the address printed carries the token), or serve on 127.0.0.1 and reach it through an SSH tunnel or a reverse proxy"
        )));
    }
    hub::new_token()
        .map(Some)
        .map_err(|e| Failure::failed(format!("no random token: {e}")))
}

/// Runs `serve`.
///
/// # Errors
/// A refused address or file (exit 2); the server failing (exit 1); a signal (128 + n).
/// `rattleback serve` as the command line asks: drawn as the lecturer saw it, recording.
pub fn command(args: &ServeArgs) -> Outcome {
    let options = super::shared::cast_options(&args.look)?.as_recorded();
    serve(args, options)
}

/// Serves `args.file`, drawn with `ui`.
pub fn serve(args: &ServeArgs, ui: crate::ui::UiOptions) -> Outcome {
    if args.file.as_os_str() == "-" {
        return Err(Failure::input(
            "serve -: serve follows a session file as it grows; give its path",
        ));
    }
    // Only a regular file, by its name (issue 80, N4 and N5: a FIFO wedged the server, a link
    // served any file the lecturer can read): anything else there is refused now, and at every
    // open after.
    if let Ok(meta) = std::fs::symlink_metadata(&args.file)
        && !meta.is_file()
    {
        let what = if meta.is_dir() {
            "a folder"
        } else if meta.file_type().is_symlink() {
            "a symbolic link (serve reads the file named, never what a link points to)"
        } else {
            "not a regular file (a FIFO, a device or a socket)"
        };
        return Err(Failure::input(format!(
            "{}: {what}; give the session file itself",
            args.file.display()
        )));
    }
    // A file that is there must be a session now (one that is not yet is waited for).
    if args.file.metadata().is_ok_and(|m| m.len() > 0) {
        crate::record::tail::Tail::open_with(&args.file, crate::scenario::write::Links::Refuse)
            .map_err(Failure::input)?;
    }
    let fps = args.look.fps.unwrap_or(DEFAULT_FPS);
    if fps > MAX_FPS {
        return Err(Failure::input(format!(
            "--fps {fps}: serve draws at most {MAX_FPS} frames a second (each goes to every reader)"
        )));
    }
    let listen = args.listen.unwrap_or_else(default_listen);
    let token = token_for(&listen, args.no_token, args.token)?;
    let (listener, local) =
        http::bind(listen).map_err(|e| Failure::input(format!("--listen {listen}: {e}")))?;
    let config = Config {
        file: args.file.clone(),
        token,
        max_readers: args.max_readers.map_or(DEFAULT_MAX_READERS, |n| n as usize),
        max_per_address: (
            args.max_per_address
                .map_or(DEFAULT_MAX_PER_ADDRESS, |n| n as usize),
            args.max_per_address.is_some(),
        ),
        fps: f64::from(fps),
        ui,
        module: args.site.as_deref().map(site_module).transpose()?,
    };
    let url = hub::url(local, config.token.as_deref());
    // The first line, alone: scripts and the explorer read it.
    crate::commands::say(&url);
    let _ = std::io::Write::flush(&mut std::io::stdout());
    crate::scenario::text::warn(&format!(
        "rattleback serve: {} read-only at {url} ({} readers at most); Ctrl-C stops",
        args.file.display(),
        config.max_readers
    ));
    run(config, listener, args.with_parent)
}

/// The module of the site in `dir` (`rattleback web DIR`): a regular file, by its name, of at
/// most [`crate::commands::web::MAX_MODULE`] bytes, that is a WebAssembly module.
fn site_module(dir: &std::path::Path) -> Result<bytes::Bytes, Failure> {
    let path = dir.join("rattleback.wasm");
    let refuse = |why: String| {
        Failure::input(format!(
            "--site {}: {why}; rattleback web {} writes the site",
            dir.display(),
            dir.display()
        ))
    };
    let bytes = crate::scenario::write::read_bounded_bytes_with(
        &path,
        crate::commands::web::MAX_MODULE,
        crate::scenario::write::Links::Refuse,
    )
    .map_err(|e| refuse(format!("{}: {e}", path.display())))?;
    if !bytes.starts_with(b"\0asm") {
        return Err(refuse(format!(
            "{} is not a WebAssembly module",
            path.display()
        )));
    }
    Ok(bytes::Bytes::from(bytes))
}

/// The renderer and the server, until a signal (or, `with_parent`, until the explorer that
/// started it has ended, its standard input closed, and the end was served: issue 80, L1).
fn run(config: Config, listener: std::net::TcpListener, with_parent: bool) -> Outcome {
    let hub = Arc::new(Hub::new());
    let stop = Arc::new(AtomicBool::new(false));
    let gone = Arc::new(AtomicBool::new(false));
    if with_parent {
        let gone = Arc::clone(&gone);
        std::thread::spawn(move || {
            let _ = std::io::copy(&mut std::io::stdin().lock(), &mut std::io::sink());
            gone.store(true, Ordering::Relaxed);
        });
    }
    let renderer = {
        let (config, hub, stop, gone) = (
            config.clone(),
            Arc::clone(&hub),
            Arc::clone(&stop),
            Arc::clone(&gone),
        );
        std::thread::Builder::new()
            .name("rattleback-live".to_owned())
            .spawn(move || live::run(&config, &hub, &stop, &gone))
            .map_err(Failure::failed)?
    };
    let server = Arc::new(http::Server::new(hub, config, http::connection_limit()));
    let served = http::run(&server, listener, &stop);
    stop.store(true, Ordering::Relaxed);
    let _ = renderer.join();
    served.map_err(Failure::failed)?;
    match crate::interrupt::requested() {
        // Stopped as a server is stopped: nothing more to say; the exit says the signal.
        Some(n) => Err(Failure::signalled(n)),
        None => Ok(()),
    }
}

/// `serve` started beside the explorer (`--record FILE --serve [ADDR:PORT]`): a process of its
/// own (its own process group: the terminal's signals are the explorer's). When this is
/// dropped, or the explorer's process ends however it ends (its standard input, a pipe from
/// here, closes), it serves the lecture's end to every reader, goes on a few seconds for the
/// pages to load the finished lecture, and exits by itself (issue 80, L1: it was killed with
/// the explorer, and the pages spun "Live" for ever).
pub struct Beside {
    child: std::process::Child,
    /// The address it serves at (its first line).
    pub url: String,
}

/// How long `serve` may take to say its address.
const STARTING: std::time::Duration = std::time::Duration::from_secs(10);

impl Beside {
    /// Starts `rattleback serve FILE --listen ADDR` and reads its address.
    ///
    /// # Errors
    /// When it cannot start, or refuses (what it said, exit 2).
    pub fn start(file: &std::path::Path, listen: std::net::SocketAddr) -> Result<Self, Failure> {
        use std::io::{BufRead as _, Read as _};
        use std::os::unix::process::CommandExt as _;
        use std::process::Stdio;
        let exe = std::env::current_exe().map_err(Failure::failed)?;
        let mut child = std::process::Command::new(exe)
            .arg("serve")
            .arg(file)
            .arg("--listen")
            .arg(listen.to_string())
            .arg("--with-parent")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .process_group(0)
            .spawn()
            .map_err(|e| Failure::failed(format!("--serve: {e}")))?;
        let (Some(stdout), Some(mut stderr)) = (child.stdout.take(), child.stderr.take()) else {
            return Err(Failure::failed("--serve: no pipe to the server"));
        };
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = std::io::BufReader::new(stdout).read_line(&mut line);
            let _ = tx.send(line);
        });
        // What it says on stderr: read to its end (the server's lifetime), kept for a refusal.
        let said = std::thread::spawn(move || {
            let mut text = String::new();
            let _ = stderr.read_to_string(&mut text);
            text
        });
        match rx.recv_timeout(STARTING) {
            Ok(line) if line.starts_with("http://") => Ok(Self {
                child,
                url: line.trim_end().to_owned(),
            }),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                let text = said.join().unwrap_or_default();
                let why = text
                    .lines()
                    .map(|l| l.trim_start_matches("rattleback: error: "))
                    .collect::<Vec<_>>()
                    .join("; ");
                Err(Failure::input(format!(
                    "--serve {listen}: the server did not start: {}",
                    if why.is_empty() {
                        "it said nothing"
                    } else {
                        &why
                    }
                )))
            }
        }
    }
}

impl Drop for Beside {
    fn drop(&mut self) {
        // Its standard input closes: it ends the lecture in every page and exits by itself
        // (bounded: `live::GONE_SETTLE` then `live::GRACE`). Not waited for: the lecturer's
        // terminal is given back at once; the server's own process group outlives this one.
        drop(self.child.stdin.take());
    }
}
