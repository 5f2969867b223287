//! The explorer's event loop: one inbox ([`AppEvent`]) fed by the input thread and the worker.
//! Keys go to the app (or to the replay), which returns effects; the loop executes them (the
//! worker, files, the recorder, the terminal) and reports the outcomes back. It never writes
//! the app's fields. A frame is drawn only when something changed, at most `fps` times a
//! second; paused and idle, it writes nothing.

pub mod recording;
pub mod replay;

use std::collections::VecDeque;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, SyncSender, sync_channel};
use std::time::{Duration, Instant};

use ratatui::crossterm::event;

use crate::app::{App, Effect, Key, Options, Outcome, RecState};
use crate::scenario::Preset;
use crate::scenario::shipped::{catalogue_in, resolve, user_preset_dir};
use crate::sim::{SimEvent, Worker};
use crate::terminal::{Input, Tty, translate};
use crate::ui::{self, Cache, UiOptions};
use recording::ActiveRecording;
use replay::Replayer;

/// Everything that wakes the loop.
#[derive(Debug)]
pub enum AppEvent {
    /// A key.
    Input(Key),
    /// The terminal was resized.
    Resize,
    /// A left click at `(column, row)`.
    Click(u16, u16),
    /// The wheel turned (`true`: up, zoom in).
    Wheel(bool),
    /// The worker reports.
    Sim(SimEvent),
}

/// Longest wall time one tick of the clock may cover.
const MAX_TICK: f64 = 0.25;

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
    /// Record from the start into this file (`--record`; the caller checked it is new or
    /// `--force` was given).
    pub record: Option<std::path::PathBuf>,
    /// Replay this session instead of exploring (`rattleback replay FILE`).
    pub replay: Option<crate::record::Recording>,
    /// Where `R` records and `x` exports (created when first used).
    pub sessions_dir: Option<std::path::PathBuf>,
    /// Mouse on (`--mouse` or `mouse = true`): a click in the portrait sets the start, the
    /// wheel zooms.
    pub mouse: bool,
    /// The user's extra keys.
    pub keys: crate::app::user_keys::UserKeys,
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
                        Some(Input::Click(c, r)) => tx.send(AppEvent::Click(c, r)),
                        Some(Input::Wheel(up)) => tx.send(AppEvent::Wheel(up)),
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

/// Carries out an effect on the preset files (saving, the catalogue, loading); `None` for
/// other effects. The loop and the tests share it.
#[must_use]
pub fn file_outcome(effect: &Effect, user_dir: Option<&std::path::Path>) -> Option<Outcome> {
    Some(match effect {
        Effect::SavePreset {
            name,
            text,
            overwrite,
        } => Outcome::Saved(crate::scenario::store::save(
            user_dir, name, text, *overwrite,
        )),
        Effect::ReadCatalogue => {
            let (entries, problems) = catalogue_in(user_dir);
            let broken = problems
                .iter()
                .map(|p| (p.file_name(), p.to_string()))
                .collect();
            Outcome::Catalogue(entries, broken)
        }
        Effect::LoadPreset(source) => {
            Outcome::Loaded(Box::new(resolve(source, &[]).map_err(|e| e.to_string())))
        }
        _ => return None,
    })
}

/// What the loop owns besides the app: the worker, the terminal, the recording.
struct Shell<'a> {
    worker: Worker,
    tty: Tty,
    recording: Option<ActiveRecording>,
    options: &'a ExplorerOptions,
    user_dir: Option<std::path::PathBuf>,
}

impl Shell<'_> {
    /// Executes effects, and the effects of their outcomes, in order.
    fn execute(&mut self, app: &mut App, effects: Vec<Effect>) -> std::io::Result<()> {
        let mut queue: VecDeque<Effect> = effects.into();
        while let Some(effect) = queue.pop_front() {
            let outcome = match effect {
                Effect::Sim(c) => {
                    self.worker.send(c);
                    None
                }
                Effect::StartRecording => Some(self.start_recording(app)),
                Effect::StopRecording => {
                    if let Some(r) = self.recording.as_mut() {
                        r.stopping = true;
                    }
                    None
                }
                e @ (Effect::SavePreset { .. } | Effect::ReadCatalogue | Effect::LoadPreset(_)) => {
                    file_outcome(&e, self.user_dir.as_deref())
                }
                Effect::Export { stem } => Some(Outcome::Exported(match &self.options.sessions_dir {
                    Some(dir) => crate::export::export(app, dir, &stem),
                    None => Err("no folder to export into (no home folder); set `sessions` in config.toml".to_owned()),
                })),
                Effect::Copy(text) => {
                    self.tty.copy(&text)?;
                    None
                }
                Effect::Redraw => {
                    self.tty.clear()?;
                    None
                }
                Effect::Suspend => {
                    self.tty.suspend()?;
                    None
                }
            };
            if let Some(o) = outcome {
                queue.extend(app.on_outcome(o));
            }
        }
        Ok(())
    }

    fn start_recording(&mut self, app: &App) -> Outcome {
        let path = match (&self.options.record, &self.options.sessions_dir) {
            (Some(p), _) => p.clone(),
            (None, Some(dir)) => {
                if let Err(e) = std::fs::create_dir_all(dir) {
                    return Outcome::Recording(Err(format!("{}: {e}", dir.display())));
                }
                crate::scenario::write::fresh_name(
                    dir,
                    &crate::app::slug(&app.scenario.name),
                    "jsonl",
                )
            }
            (None, None) => crate::scenario::write::fresh_name(
                std::path::Path::new("."),
                &crate::app::slug(&app.scenario.name),
                "jsonl",
            ),
        };
        let size = ratatui::crossterm::terminal::size().unwrap_or((80, 24));
        match ActiveRecording::start(app, &path, size, self.options.fps) {
            Ok(r) => {
                let p = r.path();
                self.recording = Some(r);
                Outcome::Recording(Ok(p))
            }
            Err(e) => Outcome::Recording(Err(e)),
        }
    }

    /// Checkpoints and writes the recording; returns whether the screen changed.
    fn keep_recording(&mut self, app: &mut App) -> std::io::Result<bool> {
        let Some(rec) = self.recording.as_mut() else {
            return Ok(false);
        };
        if app.journal.state == RecState::On
            && let Some(c) = rec.due(app)
        {
            self.execute(app, vec![c])?;
        }
        let Some(rec) = self.recording.as_mut() else {
            return Ok(false);
        };
        match rec.flush(app) {
            Ok(None) => Ok(false),
            Ok(Some(done)) | Err(done) => {
                self.recording = None;
                let effects = app.on_outcome(done);
                self.execute(app, effects)?;
                Ok(true)
            }
        }
    }
}

/// Ends a recording with a checkpoint at the final time: ask, wait briefly, write.
fn finish_recording(
    mut rec: ActiveRecording,
    worker: &Worker,
    app: &mut App,
    rx: &Receiver<AppEvent>,
) {
    worker.send(match app.checkpoint() {
        Effect::Sim(c) => c,
        _ => return,
    });
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
    let _ = rec.flush(app);
}

/// Signals that end the explorer: the terminal is restored, then the process exits with
/// `128 + n`.
pub const ENDING_SIGNALS: [i32; 6] = [
    signal_hook::consts::SIGTERM,
    signal_hook::consts::SIGHUP,
    signal_hook::consts::SIGINT,
    signal_hook::consts::SIGQUIT,
    signal_hook::consts::SIGUSR1,
    signal_hook::consts::SIGALRM,
];

/// Runs the explorer on `preset` until the user quits (`Ok(None)`) or a signal of
/// [`ENDING_SIGNALS`] arrives (`Ok(Some(n))`; the terminal is restored either way). A SIGTSTP
/// (`kill -TSTP`, or Ctrl-Z from outside raw mode) suspends like Ctrl-Z.
///
/// # Errors
/// When the terminal cannot be set up or written to.
pub fn run(preset: &Preset, options: &ExplorerOptions) -> std::io::Result<Option<i32>> {
    let signal = Arc::new(AtomicUsize::new(0));
    for n in ENDING_SIGNALS
        .into_iter()
        .chain([signal_hook::consts::SIGTSTP])
    {
        signal_hook::flag::register_usize(n, Arc::clone(&signal), n as usize)?;
    }
    let hangup = &*signal;
    let tty = Tty::enter(options.mouse)?;
    let (tx, rx) = sync_channel::<AppEvent>(INBOX);
    let book = options
        .replay
        .as_ref()
        .map(crate::record::plan_book)
        .unwrap_or_default();
    let worker = {
        let tx = tx.clone();
        Worker::spawn_with(book, move |e| tx.send(AppEvent::Sim(e)).is_ok())
    };
    let stop = Arc::new(AtomicBool::new(false));
    let input = input_thread(tx, Arc::clone(&stop));
    let app_options = Options {
        fps: options.fps,
        theme_names: options.ui.theme_names(),
        keys: options.keys.clone(),
    };
    let (mut app, effects) = App::new(preset, app_options.clone());
    let mut shell = Shell {
        worker,
        tty,
        recording: None,
        options,
        user_dir: user_preset_dir(),
    };
    let mut effects = effects;
    let mut replay = options.replay.as_ref().map(|r| {
        let mut replayer = Replayer::new(r.lines.iter().map(|(_, l)| l.clone()).collect());
        effects.extend(replayer.catch_up(&mut app));
        replayer
    });
    let rebuild = |old: &App| App::new_after(preset, app_options.clone(), old);
    if !options.startup_problems.is_empty() {
        app.show_dialog(&options.startup_problems.join("\n"));
    }
    if options.record.is_some() && replay.is_none() {
        effects.push(Effect::StartRecording);
    }
    let result = event_loop(
        &mut app,
        &mut shell,
        replay.as_mut(),
        &rebuild,
        effects,
        &rx,
        hangup,
    );
    stop.store(true, Ordering::Relaxed);
    // The terminal is restored before waiting for anything: the final checkpoint, the worker.
    let Shell {
        worker,
        tty,
        recording,
        ..
    } = shell;
    drop(tty);
    if let Some(rec) = recording {
        finish_recording(rec, &worker, &mut app, &rx);
    }
    drop(rx);
    worker.join();
    // The input thread is not joined: on a hung-up terminal crossterm's blocking read can spin
    // without returning, and the thread ends with the process anyway. A live terminal's thread
    // sees `stop` within 100 ms.
    drop(input);
    result
}

fn event_loop(
    app: &mut App,
    shell: &mut Shell<'_>,
    mut replay: Option<&mut Replayer>,
    rebuild: &dyn Fn(&App) -> (App, Vec<Effect>),
    start: Vec<Effect>,
    rx: &Receiver<AppEvent>,
    signal: &AtomicUsize,
) -> std::io::Result<Option<i32>> {
    let options = shell.options;
    shell.execute(app, start)?;
    let frame = Duration::from_secs_f64(1.0 / options.fps);
    let mut cache = Cache::default();
    let mut dirty = true;
    let mut last_frame = Instant::now()
        .checked_sub(frame)
        .unwrap_or_else(Instant::now);
    let mut last_tick = Instant::now();
    loop {
        match i32::try_from(signal.swap(0, Ordering::Relaxed)).unwrap_or(0) {
            0 => {}
            signal_hook::consts::SIGTSTP => {
                shell.tty.suspend()?;
                dirty = true;
            }
            n => return Ok(Some(n)),
        }
        if app.quit {
            return Ok(None);
        }
        let animating = app.run.playing || replay.as_ref().is_some_and(|r| r.running());
        let until_frame = frame.saturating_sub(last_frame.elapsed());
        let timeout = if animating || dirty {
            until_frame
        } else {
            // Idle: wake now and then to notice a signal or a vanished terminal within 100 ms.
            Duration::from_millis(100)
        };
        let event = rx.recv_timeout(timeout);
        if matches!(event, Err(RecvTimeoutError::Timeout))
            && ratatui::crossterm::terminal::size().is_err()
        {
            // The terminal went away without a signal: leave as on SIGHUP.
            return Ok(Some(signal_hook::consts::SIGHUP));
        }
        match event {
            Ok(AppEvent::Input(key)) => {
                let effects = match replay.as_deref_mut() {
                    Some(r) if app.mode == crate::app::Mode::Normal || key == Key::Ctrl('c') => {
                        r.key(key, app, rebuild)
                    }
                    _ => app.on_key(key),
                };
                shell.execute(app, effects)?;
                dirty = true;
            }
            Ok(AppEvent::Resize) => {
                shell.tty.autoresize()?;
                dirty = true;
            }
            // The mouse drives the explorer, never a replay (the recording does).
            Ok(AppEvent::Click(column, row))
                if replay.is_none() && app.mode == crate::app::Mode::Normal =>
            {
                if let Some((alpha, alpha_dot)) = ui::portrait_point(&cache, column, row) {
                    let effects = app.set_start_point(alpha, alpha_dot);
                    shell.execute(app, effects)?;
                    dirty = true;
                }
            }
            Ok(AppEvent::Wheel(up)) if replay.is_none() && app.mode == crate::app::Mode::Normal => {
                let action = if up {
                    crate::app::Action::ZoomIn
                } else {
                    crate::app::Action::ZoomOut
                };
                let effects = app.update(action);
                shell.execute(app, effects)?;
                dirty = true;
            }
            Ok(AppEvent::Sim(e)) => dirty |= app.on_sim(e),
            Ok(AppEvent::Click(..) | AppEvent::Wheel(_)) | Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => return Ok(None),
        }
        // The clocks move once a frame has passed.
        let dt = last_tick.elapsed();
        if dt >= frame {
            last_tick = Instant::now();
            // A long gap (suspended with Ctrl-Z, a stalled terminal) is not played through.
            let wall = dt.as_secs_f64().min(MAX_TICK);
            let effects = match replay.as_deref_mut() {
                Some(r) => r.advance(wall, app),
                None => app.tick(wall),
            };
            dirty |= !effects.is_empty();
            shell.execute(app, effects)?;
        }
        dirty |= shell.keep_recording(app)?;
        if dirty && last_frame.elapsed() >= frame {
            shell
                .tty
                .draw(|f| ui::draw(f, app, &options.ui, &mut cache))?;
            dirty = false;
            last_frame = Instant::now();
        }
    }
}
