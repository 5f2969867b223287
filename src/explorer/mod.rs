//! The explorer's event loop: one inbox ([`AppEvent`]) fed by the input thread and the worker.
//! Keys go to the app (or to the replay), which returns effects; the loop executes them (the
//! worker, files, the recorder, the terminal) and reports the outcomes back. It never writes
//! the app's fields. A frame is drawn only when something changed, at most `fps` times a
//! second; paused and idle, it writes nothing.

pub mod review;

use std::collections::VecDeque;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, SyncSender, sync_channel};
use std::time::{Duration, Instant};

use ratatui::crossterm::event;

use crate::app::{App, Effect, Key, Options, Outcome, RecState, ShellError};
use crate::record::active::ActiveRecording;
use crate::record::replayer::Replayer;
use crate::scenario::Preset;
use crate::scenario::shipped::{catalogue_in, resolve, user_preset_dir};
use crate::sim::{SimEvent, Worker};
use crate::terminal::{Input, Tty, translate};
use crate::ui::{self, Cache, UiOptions};

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
    /// The followed file changed.
    Follow(crate::record::tail::TailEvent),
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
    /// A lesson to open (`rattleback lesson`).
    pub lesson: Option<crate::scenario::lesson::Lesson>,
    /// A partner to compare the preset with (`rattleback compare A B`): the compare pane opens.
    pub partner: Option<crate::scenario::Preset>,
    /// Follow this session file as it is written (`rattleback follow FILE`; `replay` holds
    /// what it had when opened).
    pub follow: Option<std::path::PathBuf>,
    /// Sign recordings with this private key (`--sign KEYFILE`; checked at start-up).
    pub sign: Option<std::path::PathBuf>,
    /// The colours the terminal shows: every frame's colour codes are fitted to it.
    pub depth: crate::terminal::Depth,
    /// The address the recording is served at (`--serve`): shown at the start, with its QR
    /// code.
    pub served: Option<String>,
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

/// A click (`at`) sets the start under it in the portrait; the wheel (`at` is `None`) zooms.
/// Only in the keymap's mode (not while typing, a dialog or the help is open).
fn mouse(app: &mut App, cache: &Cache, at: Option<(u16, u16)>, up: bool) -> Vec<Effect> {
    if app.mode != crate::app::Mode::Normal {
        return Vec::new();
    }
    match at {
        Some((column, row)) => ui::portrait_point(cache, column, row)
            .map(|(alpha, alpha_dot)| app.set_start_point(alpha, alpha_dot))
            .unwrap_or_default(),
        None if up => app.update(crate::app::Action::ZoomIn),
        None => app.update(crate::app::Action::ZoomOut),
    }
}

/// The lecturer's clock now: the last line's wall plus the time since the file was written.
#[must_use]
pub fn lecturer_now(rec: &crate::record::Recording, path: &std::path::Path) -> f64 {
    let last = rec.lines.last().map_or(0.0, |(_, l)| l.wall);
    let since = std::fs::metadata(path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|m| m.elapsed().ok())
        .map_or(0.0, |d| d.as_secs_f64());
    last + since
}

/// How often the followed file is looked at (new lines appear within this, well under 0.5 s).
const FOLLOW_POLL: Duration = Duration::from_millis(40);

/// Looks at the followed file a few times a second and reports what changed.
fn follow_thread(
    path: &std::path::Path,
    tx: SyncSender<AppEvent>,
    stop: Arc<AtomicBool>,
) -> Option<std::thread::JoinHandle<()>> {
    let (mut tail, _) = crate::record::tail::Tail::open(path).ok()?;
    Some(std::thread::spawn(move || {
        while !stop.load(Ordering::Relaxed) {
            std::thread::sleep(FOLLOW_POLL);
            if let Some(event) = tail.poll()
                && tx.send(AppEvent::Follow(event)).is_err()
            {
                return;
            }
        }
    }))
}

/// `auto`'s plans among a followed file's new lines (those with an estimate, as
/// [`crate::record::plan_book`] keeps them), as commands that hand them to the worker, whose
/// verification ahead waits for them instead of verifying the lecturer's segments again.
fn forwarded_plans(lines: &[crate::record::Line]) -> Vec<Effect> {
    lines
        .iter()
        .filter_map(|l| match l.event {
            crate::app::journal::Event::Plan {
                key,
                plan,
                estimate: estimate @ Some(_),
                ..
            } => Some(Effect::Sim(crate::sim::Command::Book {
                key,
                plan,
                estimate,
            })),
            _ => None,
        })
        .collect()
}

/// New lines of a followed file, applied (`follow` and `serve` alike): the lecturer's plans go
/// to the worker first (what it waits for, it takes), then the lines to the replay; once the
/// `end` line is among them, what is missing is verified here (`true`: the recording ended).
pub fn follow_lines(
    lines: Vec<crate::record::Line>,
    app: &mut App,
    replay: &mut Replayer,
) -> (Vec<Effect>, bool) {
    let ended = lines
        .iter()
        .any(|l| matches!(l.event, crate::app::journal::Event::End { .. }));
    let mut effects = forwarded_plans(&lines);
    effects.extend(replay.push(lines, app));
    if ended {
        effects.push(Effect::Sim(crate::sim::Command::Release));
    }
    (effects, ended)
}

/// Applies what the followed file did: new lines, a restart from its beginning (truncated or
/// replaced: a fresh explorer on its header), or its absence.
fn follow_event(
    event: crate::record::tail::TailEvent,
    app: &mut App,
    replay: &mut Option<Replayer>,
    options: &ExplorerOptions,
) -> Vec<Effect> {
    use crate::record::tail::TailEvent;
    let Some(r) = replay.as_mut() else {
        return Vec::new(); // forked: the lecturer's file no longer matters
    };
    match event {
        TailEvent::Lines(lines) => {
            let (effects, ended) = follow_lines(lines, app, r);
            if ended {
                app.notice("the lecturer's recording ended; f forks, q quits");
            }
            effects
        }
        TailEvent::Restarted { why, recording } => {
            let preset = match Preset::parse(
                &recording.header.preset,
                "followed file (header)",
                "recorded",
                &[],
            ) {
                Ok(p) => p,
                Err(e) => {
                    app.notice(&format!("{why}, and its header is not valid: {e}"));
                    return Vec::new();
                }
            };
            let app_options = app.options.clone();
            let (mut fresh, mut effects) = App::new_after(&preset, app_options, app);
            if let Some(lesson) = recording
                .header
                .lesson
                .as_ref()
                .and_then(crate::scenario::lesson::RecordedLesson::lesson)
            {
                fresh.replay_lesson(lesson);
            }
            *app = fresh;
            let path = options.follow.clone().unwrap_or_default();
            let lines: Vec<_> = recording.lines.iter().map(|(_, l)| l.clone()).collect();
            effects.extend(forwarded_plans(&lines));
            if lines
                .last()
                .is_some_and(|l| matches!(l.event, crate::app::journal::Event::End { .. }))
            {
                effects.push(Effect::Sim(crate::sim::Command::Release));
            }
            let mut fresh_replay = Replayer::live(lines, lecturer_now(&recording, &path));
            effects.extend(fresh_replay.catch_up(app));
            *replay = Some(fresh_replay);
            app.notice(&format!("{why}: following it from its start"));
            effects
        }
        TailEvent::Missing(why) => {
            app.notice(&why);
            Vec::new()
        }
    }
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
            Outcome::Loaded(Box::new(resolve(source, &[]).map_err(ShellError::from)))
        }
        _ => return None,
    })
}

/// What the loop owns besides the app: the worker, the terminal, the recording.
struct Shell<'a> {
    worker: Worker,
    tty: Tty,
    recording: Option<ActiveRecording>,
    /// The recording's clock: seconds from here.
    clock: Instant,
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
                Effect::Export { stem } => {
                    Some(Outcome::Exported(match &self.options.sessions_dir {
                        Some(dir) => crate::export::export(app, dir, &stem),
                        None => Err(ShellError::NoFolder(
                            "no folder to export into (no home folder); set `sessions` in config.toml",
                        )),
                    }))
                }
                Effect::Copy(text) => {
                    self.tty.copy(&text)?;
                    Some(copied(text, self.options.sessions_dir.as_deref()))
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
                    return Outcome::Recording(Err(ShellError::Io {
                        path: dir.clone(),
                        source: e,
                    }));
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
        match ActiveRecording::start(
            app,
            &path,
            size,
            self.options.fps,
            self.options.sign.as_deref(),
            self.clock.elapsed().as_secs_f64(),
        ) {
            Ok(r) => {
                let p = r.path();
                self.recording = Some(r);
                Outcome::Recording(Ok(p))
            }
            Err(e) => Outcome::Recording(Err(ShellError::Recording(e))),
        }
    }

    /// Checkpoints and writes the recording; returns whether the screen changed.
    fn keep_recording(&mut self, app: &mut App) -> std::io::Result<bool> {
        let Some(rec) = self.recording.as_mut() else {
            return Ok(false);
        };
        if app.journal.state == RecState::On
            && let Some(c) = rec.due(app, self.clock.elapsed().as_secs_f64())
        {
            self.execute(app, vec![c])?;
        }
        let Some(rec) = self.recording.as_mut() else {
            return Ok(false);
        };
        match rec.flush(app, self.clock.elapsed().as_secs_f64()) {
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
    clock: Instant,
    worker: &Worker,
    app: &mut App,
    rx: &Receiver<AppEvent>,
) {
    let deadline = Instant::now() + Duration::from_secs(3);
    // The last frame, once settled (a step's plan resolved), whatever ended the recording:
    // `q`, Ctrl-C, a signal (issue 55: files ended with `q` had none, so it was never checked).
    if rec.stopping {
        // `R` already wrote it.
    } else {
        while !app.screen_settled() && Instant::now() < deadline {
            match rx.recv_timeout(Duration::from_millis(20)) {
                Ok(AppEvent::Sim(e)) => {
                    app.on_sim(e);
                }
                Ok(_) | Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break,
            }
        }
        app.log_last_frame();
    }
    worker.send(match app.checkpoint() {
        Effect::Sim(c) => c,
        _ => return,
    });
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
    rec.stopping = true;
    if let Ok(Some(outcome)) = rec.flush(app, clock.elapsed().as_secs_f64()) {
        app.on_outcome(outcome);
    }
}

/// What the explorer shows first: the address `--serve` serves at, then (above it) the
/// problems found at start-up.
fn startup_dialogs(app: &mut App, options: &ExplorerOptions) {
    if let Some(url) = &options.served {
        app.show_address(url);
    }
    if !options.startup_problems.is_empty() {
        app.show_dialog(&options.startup_problems.join("\n"));
    }
}

/// The worker's plan book: a replay's recorded plans; a followed lecture's runs bounded one by
/// one (it grows) and its later segments awaited from the lecturer, unless it has ended.
fn plan_book(options: &ExplorerOptions) -> crate::sim::PlanBook {
    match (&options.replay, &options.follow) {
        (Some(rec), Some(_)) => crate::record::replayer::follower_book(rec),
        (Some(rec), None) => crate::record::plan_book(rec),
        (None, _) => crate::sim::PlanBook::default(),
    }
}

/// Signals that end the explorer: the terminal is restored, then the process exits with
/// `128 + n`. Every signal whose default action ends the process and that can be caught safely
/// ([`crate::interrupt::ending`], the realtime ones included), and SIGPIPE and SIGABRT; the
/// faults (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGTRAP, SIGSYS) are [`crate::fault`]'s, which
/// restores the terminal and ends the process by the signal.
#[must_use]
pub fn ending_signals() -> Vec<i32> {
    let mut all = crate::interrupt::ending();
    all.extend([signal_hook::consts::SIGPIPE, signal_hook::consts::SIGABRT]);
    all
}

/// Runs the explorer on `preset` until the user quits (`Ok(None)`) or a signal of
/// [`ending_signals`] arrives (`Ok(Some(n))`; the terminal is restored either way). A SIGTSTP
/// (`kill -TSTP`, or Ctrl-Z from outside raw mode) suspends like Ctrl-Z.
///
/// # Errors
/// When the terminal cannot be set up or written to.
pub fn run(preset: &Preset, options: &ExplorerOptions) -> std::io::Result<Option<i32>> {
    let signal = Arc::new(AtomicUsize::new(0));
    crate::interrupt::register(
        ending_signals()
            .into_iter()
            .chain([signal_hook::consts::SIGTSTP]),
        &signal,
    )?;
    let hangup = &*signal;
    let tty = Tty::enter(options.mouse, options.depth)?;
    let (tx, rx) = sync_channel::<AppEvent>(INBOX);
    let book = plan_book(options);
    let worker = {
        let tx = tx.clone();
        Worker::spawn_with(book, move |e| tx.send(AppEvent::Sim(e)).is_ok())
    };
    let stop = Arc::new(AtomicBool::new(false));
    let tail = options
        .follow
        .as_ref()
        .map(|path| follow_thread(path, tx.clone(), Arc::clone(&stop)));
    let input = input_thread(tx, Arc::clone(&stop));
    let app_options = Options {
        fps: options.fps,
        theme_names: options.ui.theme_names(),
        keys: options.keys.clone(),
        served: options.served.clone(),
    };
    let (mut app, effects) = App::new(preset, app_options.clone());
    let mut shell = Shell {
        worker,
        tty,
        recording: None,
        clock: Instant::now(),
        options,
        user_dir: user_preset_dir(),
    };
    let mut effects = effects;
    // A recorded lesson's pane, as the lecturer saw it (format 10).
    let recorded_lesson = options
        .replay
        .as_ref()
        .and_then(|r| r.header.lesson.as_ref())
        .and_then(crate::scenario::lesson::RecordedLesson::lesson);
    if let Some(lesson) = &recorded_lesson {
        app.replay_lesson(lesson.clone());
    }
    let mut replay = options.replay.as_ref().map(|r| {
        let lines = r.lines.iter().map(|(_, l)| l.clone()).collect();
        let mut replayer = match &options.follow {
            Some(path) => Replayer::live(lines, lecturer_now(r, path)),
            None => Replayer::new(lines),
        };
        effects.extend(replayer.catch_up(&mut app));
        replayer
    });
    let rebuild = |old: &App| {
        let (mut fresh, effects) = App::new_after(preset, app_options.clone(), old);
        if let Some(lesson) = &recorded_lesson {
            fresh.replay_lesson(lesson.clone());
        }
        (fresh, effects)
    };
    if let Some(lesson) = &options.lesson {
        effects.extend(app.start_lesson(lesson.clone()));
    }
    if let Some(partner) = &options.partner {
        effects.extend(app.set_partner(partner));
    }
    startup_dialogs(&mut app, options);
    if options.record.is_some() && replay.is_none() {
        effects.push(Effect::StartRecording);
    }
    let result = event_loop(
        &mut app,
        &mut shell,
        &mut replay,
        &rebuild,
        effects,
        &rx,
        hangup,
    );
    stop.store(true, Ordering::Relaxed);
    drop(tail);
    // The terminal is restored before waiting for anything: the final checkpoint, the worker.
    let Shell {
        worker,
        tty,
        recording,
        clock,
        ..
    } = shell;
    drop(tty);
    if let Some(rec) = recording {
        finish_recording(rec, clock, &worker, &mut app, &rx);
    }
    // Where the files went, on the terminal the screen has given back (a terminal that hung
    // up takes nothing, and a failed write is no reason to panic).
    for line in &app.messages.written {
        crate::scenario::text::warn(&format!("rattleback: {line}"));
    }
    drop(rx);
    // Never wait on a worker stuck in a long step: the process ends with it.
    worker.join_within(Duration::from_millis(100));
    // The input thread is not joined: on a hung-up terminal crossterm's blocking read can spin
    // without returning, and the thread ends with the process anyway. A live terminal's thread
    // sees `stop` within 100 ms.
    drop(input);
    why_ended(result, hangup)
}

/// Where `y`'s command went besides OSC 52, which no terminal acknowledges: inside tmux, its
/// buffer (`tmux load-buffer -`, the text on its standard input, no shell; tmux ignores OSC 52
/// under its default `set-clipboard external`); else a file beside the sessions,
/// `last-command.sh`, so the command is never only on a clipboard that may not exist.
fn copied(text: String, sessions: Option<&std::path::Path>) -> Outcome {
    use std::io::Write as _;
    let tmux = std::env::var_os("TMUX").is_some_and(|v| !v.is_empty())
        && std::process::Command::new("tmux")
            .args(["load-buffer", "-"])
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .and_then(|mut child| {
                if let Some(mut stdin) = child.stdin.take() {
                    stdin.write_all(text.as_bytes())?;
                }
                child.wait()
            })
            .is_ok_and(|status| status.success());
    let file = (!tmux).then(|| match sessions {
        Some(dir) => {
            let path = dir.join("last-command.sh");
            std::fs::create_dir_all(dir)
                .and_then(|()| {
                    crate::scenario::write::write_atomic(
                        &path,
                        format!("{text}\n").as_bytes(),
                        true,
                    )
                })
                .map(|()| path.clone())
                .map_err(|source| ShellError::Io { path, source })
        }
        None => Err(ShellError::NoFolder("no sessions folder (no home folder)")),
    });
    Outcome::Copied { text, tmux, file }
}

/// A terminal that hung up (SSH dropped, tmux killed) fails the next frame, often before the
/// loop has seen its SIGHUP: the signal, not the failed write, is why the explorer ended.
fn why_ended(
    result: std::io::Result<Option<i32>>,
    signal: &AtomicUsize,
) -> std::io::Result<Option<i32>> {
    match (result, signal.load(Ordering::Relaxed)) {
        (Err(_), n) if ending_signals().iter().any(|&s| s as usize == n) => Ok(Some(
            i32::try_from(n).unwrap_or(signal_hook::consts::SIGHUP),
        )),
        (result, _) => result,
    }
}

/// One event from the terminal, the worker or the followed file; whether the screen changed.
fn handle_event(
    event: AppEvent,
    app: &mut App,
    shell: &mut Shell<'_>,
    replay: &mut Option<Replayer>,
    rebuild: &dyn Fn(&App) -> (App, Vec<Effect>),
    cache: &Cache,
) -> std::io::Result<bool> {
    let options = shell.options;
    match event {
        // `f` forks a follower: it keeps the state and explores on its own.
        AppEvent::Input(Key::Char('f'))
            if replay.as_ref().is_some_and(Replayer::following)
                && app.mode == crate::app::Mode::Normal =>
        {
            *replay = None;
            app.fork();
            // On its own now: it verifies what it runs.
            shell.worker.send(crate::sim::Command::Release);
            Ok(true)
        }
        AppEvent::Follow(event) => {
            let effects = follow_event(event, app, replay, options);
            shell.execute(app, effects)?;
            Ok(true)
        }
        AppEvent::Input(key) => {
            let effects = match replay.as_mut() {
                Some(r) if app.mode == crate::app::Mode::Normal || key == Key::Ctrl('c') => {
                    r.key(key, app, rebuild)
                }
                _ => app.on_key(key),
            };
            shell.execute(app, effects)?;
            Ok(true)
        }
        AppEvent::Resize => {
            shell.tty.autoresize()?;
            // While recording, the new size is journaled (format 14): the exports draw each
            // moment at the size the lecturer saw.
            if replay.is_none()
                && let Ok((width, height)) = ratatui::crossterm::terminal::size()
            {
                app.on_resize(width, height);
            }
            Ok(true)
        }
        // The mouse drives the explorer, never a replay (the recording does).
        AppEvent::Click(column, row) if replay.is_none() => {
            let effects = mouse(app, cache, Some((column, row)), false);
            let changed = !effects.is_empty();
            shell.execute(app, effects)?;
            Ok(changed)
        }
        AppEvent::Wheel(up) if replay.is_none() => {
            let effects = mouse(app, cache, None, up);
            shell.execute(app, effects)?;
            Ok(true)
        }
        AppEvent::Sim(e) => Ok(app.on_sim(e)),
        AppEvent::Click(..) | AppEvent::Wheel(_) => Ok(false),
    }
}

fn event_loop(
    app: &mut App,
    shell: &mut Shell<'_>,
    replay: &mut Option<Replayer>,
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
        let animating = app.run.playing || replay.as_ref().is_some_and(Replayer::running);
        let timeout = if dirty {
            frame.saturating_sub(last_frame.elapsed())
        } else if animating {
            // The clocks move once a frame: sleep until the next tick, not until a frame that
            // nothing will draw (a follower whose lecturer is paused would spin).
            frame.saturating_sub(last_tick.elapsed())
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
        let mut batch = match event {
            Ok(e) => vec![e],
            Err(RecvTimeoutError::Timeout) => Vec::new(),
            Err(RecvTimeoutError::Disconnected) => return Ok(None),
        };
        // Everything already waiting, keys first: a key is never queued behind the worker's
        // events (q quits at once however busy the worker is).
        while batch.len() < 4 * INBOX
            && let Ok(e) = rx.try_recv()
        {
            batch.push(e);
        }
        batch.sort_by_key(|e| !matches!(e, AppEvent::Input(_) | AppEvent::Resize));
        for event in batch {
            dirty |= handle_event(event, app, shell, replay, rebuild, &cache)?;
            if app.quit {
                return Ok(None);
            }
        }
        // The clocks move once a frame has passed.
        let dt = last_tick.elapsed();
        if dt >= frame {
            last_tick = Instant::now();
            // A long gap (suspended with Ctrl-Z, a stalled terminal) is not played through.
            let wall = dt.as_secs_f64().min(MAX_TICK);
            let effects = match replay.as_mut() {
                Some(r) => r.advance(wall, app),
                None => app.tick(wall),
            };
            dirty |= !effects.is_empty();
            shell.execute(app, effects)?;
        }
        dirty |= shell.keep_recording(app)?;
        if dirty && last_frame.elapsed() >= frame {
            let mut area = ratatui::layout::Rect::default();
            shell.tty.draw(|f| {
                area = f.area();
                ui::draw(f, app, &options.ui, &mut cache);
            })?;
            // The help scrolls no further than it fills the overlay.
            app.fit_help(ui::help::max_scroll(app, area, &options.ui));
            dirty = false;
            last_frame = Instant::now();
        }
    }
}
