//! The explorer's event loop: one inbox ([`AppEvent`]) fed by the input thread and the worker;
//! keys become actions, actions become worker commands; a frame is drawn only when something
//! changed, at most `fps` times a second. Paused and idle, it writes nothing.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, SyncSender, sync_channel};
use std::time::{Duration, Instant};

use ratatui::crossterm::event;

use crate::app::journal::Event;
use crate::app::{App, Key, Options};
use crate::record::{Header, Line, Recorder, Size};
use crate::scenario::Preset;
use crate::sim::{Command, SimEvent, Worker};
use crate::terminal::{Input, Tty, translate};
use crate::ui::{self, UiOptions};

/// Everything that wakes the loop.
#[derive(Debug)]
pub enum AppEvent {
    /// A key.
    Input(Key),
    /// The terminal was resized.
    Resize,
    /// The worker reports.
    Sim(SimEvent),
}

/// Capacity of the inbox: bounded, so a slow terminal slows the worker.
const INBOX: usize = 64;

/// How the explorer runs.
#[derive(Clone, Debug)]
pub struct ExplorerOptions {
    /// Frame-rate cap.
    pub fps: f64,
    /// Drawing options.
    pub ui: UiOptions,
    /// Problems found at start-up (invalid user themes), shown in a dialog.
    pub startup_problems: Vec<String>,
    /// Record from the start into this file (`--record`).
    pub record: Option<std::path::PathBuf>,
    /// Replay this session instead of exploring (`rattleback replay FILE`).
    pub replay: Option<crate::record::Recording>,
}

/// Wall seconds between checkpoints while recording.
const CHECKPOINT_EVERY: f64 = 2.0;

/// A recording in progress.
struct Recording {
    recorder: Recorder,
    started: Instant,
    last_checkpoint: Instant,
    /// Stop asked: close once the final checkpoint is written.
    stopping: bool,
}

fn header(app: &App, size: (u16, u16), fps: f64) -> Header {
    Header {
        format: crate::record::FORMAT.to_owned(),
        version: crate::record::VERSION,
        program: env!("CARGO_PKG_VERSION").to_owned(),
        preset: app.to_preset(&app.name).to_toml(),
        method: app.settings.method.name().to_owned(),
        tolerance: app.settings.tolerance,
        terminal: Size {
            width: size.0,
            height: size.1,
        },
        theme: app.theme,
        fps,
    }
}

fn start_recording(app: &mut App, path: &std::path::Path, fps: f64) -> Option<Recording> {
    let size = ratatui::crossterm::terminal::size().unwrap_or((80, 24));
    match Recorder::create(path, &header(app, size, fps)) {
        Ok(recorder) => {
            app.recording = true;
            app.message = Some((format!("recording to {}", recorder.path()), false));
            let now = Instant::now();
            Some(Recording {
                recorder,
                started: now,
                last_checkpoint: now,
                stopping: false,
            })
        }
        Err(e) => {
            app.dialog = Some(e.to_string());
            None
        }
    }
}

/// Writes the journal; returns whether a checkpoint was among the lines. `Err` text goes to
/// a dialog and stops the recording.
fn flush_journal(app: &mut App, rec: &mut Recording) -> Result<bool, String> {
    let wall = rec.started.elapsed().as_secs_f64();
    let mut checkpoint = false;
    for (t, generation, event) in app.journal.drain(..) {
        checkpoint |= matches!(event, Event::Checkpoint { .. });
        rec.recorder
            .write(&Line {
                wall,
                t,
                generation,
                event,
            })
            .map_err(|e| e.to_string())?;
    }
    Ok(checkpoint)
}

/// Drives the app from a recording at its pace.
struct Replayer {
    lines: Vec<Line>,
    next: usize,
    clock: f64,
    speed: f64,
    paused: bool,
}

impl Replayer {
    fn chapters(&self) -> Vec<usize> {
        (0..self.lines.len())
            .filter(|&i| matches!(self.lines[i].event, Event::Chapter { .. }))
            .collect()
    }

    /// Handles a key in replay mode (the app itself is driven by the recording).
    fn key(
        &mut self,
        key: Key,
        app: &mut App,
        preset: &Preset,
        fps: f64,
        send: &dyn Fn(Vec<Command>),
    ) {
        match key {
            Key::Char(' ') => self.paused = !self.paused,
            Key::Char('+' | '=') => self.speed = (self.speed * 2.0).min(64.0),
            Key::Char('-' | '_') => self.speed = (self.speed / 2.0).max(1.0 / 16.0),
            Key::Char(']') => {
                if let Some(&i) = self.chapters().iter().find(|&&i| i >= self.next) {
                    self.clock = self.lines[i].wall;
                    self.catch_up(app, send);
                }
            }
            Key::Char('[') => {
                // Back: rebuild from the start and fast-forward to the previous chapter.
                let back = self.chapters().into_iter().rfind(|&i| i + 1 < self.next);
                let (fresh, commands) = App::new(preset, Options { fps });
                *app = fresh;
                app.replaying = true;
                send(commands);
                self.next = 0;
                self.clock = back.map_or(0.0, |i| self.lines[i].wall);
                self.catch_up(app, send);
            }
            Key::Char('q') | Key::Esc | Key::CtrlC => app.quit = true,
            _ => {}
        }
        app.message = Some((self.status(), false));
    }

    /// Applies every line up to `clock`.
    fn catch_up(&mut self, app: &mut App, send: &dyn Fn(Vec<Command>)) {
        while self.next < self.lines.len() && self.lines[self.next].wall <= self.clock {
            let line = &self.lines[self.next];
            app.target = line.t;
            send(app.apply_event(&line.event));
            self.next += 1;
        }
    }

    fn status(&self) -> String {
        let chapters = self.chapters();
        let done = chapters.iter().filter(|&&i| i < self.next).count();
        format!(
            "replay ×{} {} │ chapter {done}/{} │ space pause, +/- speed, [ ] chapters, q quit",
            self.speed,
            if self.paused { "paused" } else { "▶" },
            chapters.len()
        )
    }
}

fn input_thread(tx: SyncSender<AppEvent>, stop: Arc<AtomicBool>) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        while !stop.load(Ordering::Relaxed) {
            match event::poll(Duration::from_millis(100)) {
                Ok(true) => {
                    let Ok(ev) = event::read() else { return };
                    let sent = match translate(&ev) {
                        Some(Input::Key(k)) => tx.send(AppEvent::Input(k)),
                        Some(Input::Resize) => tx.send(AppEvent::Resize),
                        None => Ok(()),
                    };
                    if sent.is_err() {
                        return;
                    }
                }
                Ok(false) => {}
                Err(_) => return,
            }
        }
    })
}

/// Moves the replay's clock or, while playing, the app's own, once a frame has passed;
/// returns whether the screen changed.
fn advance_clock(
    app: &mut App,
    replay: Option<&mut Replayer>,
    last_tick: &mut Instant,
    frame: Duration,
    send: &dyn Fn(Vec<Command>),
) -> bool {
    let now = Instant::now();
    let dt = (now - *last_tick).as_secs_f64();
    if let Some(r) = replay.filter(|r| !r.paused) {
        if dt < frame.as_secs_f64() {
            return false;
        }
        r.clock += dt * r.speed;
        r.catch_up(app, send);
        if app.playing {
            send(app.tick(dt * r.speed));
        }
        app.message = Some((r.status(), false));
    } else if app.playing {
        if dt < frame.as_secs_f64() {
            return false;
        }
        send(app.tick(dt));
    } else {
        *last_tick = now;
        return false;
    }
    *last_tick = now;
    true
}

/// Starts, stops, checkpoints and writes the recording; returns whether the screen changed.
fn keep_recording(
    app: &mut App,
    recording: &mut Option<Recording>,
    options: &ExplorerOptions,
    replaying: bool,
    send: &dyn Fn(Vec<Command>),
) -> bool {
    let mut changed = false;
    if app.recording_requested {
        app.recording_requested = false;
        changed = true;
        if let Some(rec) = recording.as_mut() {
            if !rec.stopping {
                rec.stopping = true;
                send(vec![app.checkpoint()]);
            }
        } else if !replaying {
            let unix = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_secs());
            let path = options
                .record
                .clone()
                .unwrap_or_else(|| format!("session-{unix}.jsonl").into());
            *recording = start_recording(app, &path, options.fps);
        }
    }
    let Some(rec) = recording.as_mut() else {
        return changed;
    };
    if rec.last_checkpoint.elapsed().as_secs_f64() >= CHECKPOINT_EVERY {
        send(vec![app.checkpoint()]);
        rec.last_checkpoint = Instant::now();
    }
    match flush_journal(app, rec) {
        Err(e) => {
            app.dialog = Some(format!("recording stopped: {e}"));
            app.recording = false;
            *recording = None;
            true
        }
        Ok(true) if rec.stopping => {
            app.message = Some((format!("recording saved to {}", rec.recorder.path()), false));
            app.recording = false;
            *recording = None;
            true
        }
        Ok(_) => changed,
    }
}

/// Ends a recording with a checkpoint at the final time: ask, wait briefly, write.
fn finish_recording(
    app: &mut App,
    mut rec: Recording,
    rx: &Receiver<AppEvent>,
    send: &dyn Fn(Vec<Command>),
) {
    app.recording = true;
    send(vec![app.checkpoint()]);
    let deadline = Instant::now() + Duration::from_secs(3);
    while Instant::now() < deadline {
        match rx.recv_timeout(Duration::from_millis(50)) {
            Ok(AppEvent::Sim(e)) => {
                let checkpoint = matches!(e, SimEvent::Checkpoint { .. });
                app.on_sim(e);
                if checkpoint {
                    break;
                }
            }
            Ok(_) | Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => break,
        }
    }
    let _ = flush_journal(app, &mut rec);
}

/// Runs the explorer on `preset` until the user quits or a SIGTERM/SIGHUP arrives.
///
/// # Errors
/// When the terminal cannot be set up or written to.
pub fn run(preset: &Preset, options: &ExplorerOptions) -> std::io::Result<()> {
    let hangup = Arc::new(AtomicBool::new(false));
    for signal in [signal_hook::consts::SIGTERM, signal_hook::consts::SIGHUP] {
        signal_hook::flag::register(signal, Arc::clone(&hangup))?;
    }
    let mut tty = Tty::enter()?;
    let (tx, rx) = sync_channel::<AppEvent>(INBOX);
    let worker = {
        let tx = tx.clone();
        Worker::spawn(move |e| tx.send(AppEvent::Sim(e)).is_ok())
    };
    let stop = Arc::new(AtomicBool::new(false));
    let input = input_thread(tx, Arc::clone(&stop));
    let send = |commands: Vec<Command>| commands.into_iter().for_each(|c| worker.send(c));

    let (mut app, commands) = App::new(preset, Options { fps: options.fps });
    if !options.startup_problems.is_empty() {
        app.dialog = Some(options.startup_problems.join("\n"));
    }
    send(commands);
    app.replaying = options.replay.is_some();
    let mut replay = options.replay.as_ref().map(|r| Replayer {
        lines: r.lines.iter().map(|(_, l)| l.clone()).collect(),
        next: 0,
        clock: 0.0,
        speed: 1.0,
        paused: false,
    });
    let mut recording = options
        .record
        .as_deref()
        .and_then(|p| start_recording(&mut app, p, options.fps));
    let frame = Duration::from_secs_f64(1.0 / options.fps);
    let mut dirty = true;
    let mut last_frame = Instant::now()
        .checked_sub(frame)
        .unwrap_or_else(Instant::now);
    let mut last_tick = Instant::now();
    let result = loop {
        if hangup.load(Ordering::Relaxed) || app.quit {
            break Ok(());
        }
        let now = Instant::now();
        let until_frame = frame.saturating_sub(now - last_frame);
        let timeout = if app.playing || dirty || replay.is_some() {
            until_frame
        } else {
            Duration::from_millis(250)
        };
        let event = rx.recv_timeout(timeout);
        if matches!(event, Err(RecvTimeoutError::Timeout))
            && ratatui::crossterm::terminal::size().is_err()
        {
            // The terminal went away without a signal: leave as on SIGHUP.
            break Ok(());
        }
        match event {
            Ok(AppEvent::Input(key)) => {
                match replay.as_mut() {
                    Some(r) => r.key(key, &mut app, preset, options.fps, &send),
                    None => send(app.on_key(key)),
                }
                dirty = true;
            }
            Ok(AppEvent::Resize) => {
                let _ = tty.autoresize();
                dirty = true;
            }
            Ok(AppEvent::Sim(e)) => dirty |= app.on_sim(e),
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => break Ok(()),
        }
        let now = Instant::now();
        dirty |= advance_clock(&mut app, replay.as_mut(), &mut last_tick, frame, &send);
        dirty |= keep_recording(&mut app, &mut recording, options, replay.is_some(), &send);
        if dirty && now - last_frame >= frame {
            if let Err(e) = tty.draw(|f| ui::draw(f, &mut app, &options.ui)) {
                break Err(e);
            }
            dirty = false;
            last_frame = now;
        }
    };
    if let Some(rec) = recording.take() {
        finish_recording(&mut app, rec, &rx, &send);
    }
    stop.store(true, Ordering::Relaxed);
    drop(rx);
    worker.join();
    // The input thread is not joined: on a hung-up terminal crossterm's blocking read can spin
    // without returning, and the thread ends with the process anyway. A live terminal's thread
    // sees `stop` within 100 ms.
    drop(input);
    drop(tty);
    result
}
