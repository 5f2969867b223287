//! The explorer's event loop: one inbox ([`AppEvent`]) fed by the input thread and the worker;
//! keys become actions, actions become worker commands; a frame is drawn only when something
//! changed, at most `fps` times a second. Paused and idle, it writes nothing.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{RecvTimeoutError, SyncSender, sync_channel};
use std::time::{Duration, Instant};

use ratatui::crossterm::event;

use crate::app::{App, Key, Options};
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
        let timeout = if app.playing || dirty {
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
                send(app.on_key(key));
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
        if app.playing {
            if now - last_tick >= frame {
                send(app.tick((now - last_tick).as_secs_f64()));
                last_tick = now;
                dirty = true;
            }
        } else {
            last_tick = now;
        }
        if dirty && now - last_frame >= frame {
            if let Err(e) = tty.draw(|f| ui::draw(f, &mut app, &options.ui)) {
                break Err(e);
            }
            dirty = false;
            last_frame = now;
        }
    };
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
