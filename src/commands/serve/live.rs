//! The renderer of `serve`: follows the session file as `rattleback follow` does (the same
//! [`Tail`], [`Replayer::live`], worker and plan book) and draws each frame into memory as
//! `--export-cast` does, handing the frames to the [`Hub`]. It waits for a file that does not
//! exist yet, starts again on a file truncated or replaced, and when the recording ends writes
//! the whole session's page (the exported page: poster, chapters) for the readers to replay.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::sync_channel;
use std::time::{Duration, Instant};

use ratatui::layout::Rect;

use super::hub::{Config, Hub};
use crate::app::effects::commands;
use crate::cast::MemoryScreen;
use crate::record::replayer::Replayer;
use crate::record::tail::{Tail, TailEvent};
use crate::sim::Worker;

/// How often the file is looked at (as `follow`'s).
const POLL: Duration = Duration::from_millis(40);
/// After the `end` line, how long the screen may take to reach the lecturer's last before the
/// end is served anyway (a recording too old to hold its last screen, or one that cannot be
/// replayed to it).
const SETTLE: Duration = Duration::from_secs(30);
/// Once the lecturer's explorer has ended (`--serve`: its pipe closed), how long the screen may
/// take to reach the lecturer's last before the end is served anyway.
const GONE_SETTLE: Duration = Duration::from_secs(5);
/// How long the server goes on after serving the end to a hall whose lecturer has gone: the
/// pages load the finished lecture from it.
pub const GRACE: Duration = Duration::from_secs(5);
/// The largest terminal a recording may say it had (a forged header cannot make the server
/// draw a screen of billions of cells).
const MAX_SIDE: u16 = 1000;

/// After the lecturer acts (lines arrive), how long the screen is drawn as soon as it changes,
/// [`PROMPT_GAP`] apart, rather than at `--fps`: the pause, the step, the parameter changed and
/// the worker's first answers to it reach the readers at once (issue 82, L3), while an
/// animation stays at `--fps`.
const PROMPT: Duration = Duration::from_millis(400);
/// The shortest time between two frames drawn promptly: `--fps`'s ceiling, so a lecturer who
/// holds a key (or a forged file of key lines) never sends more than [`super::MAX_FPS`] frames
/// a second to each reader.
const PROMPT_GAP: Duration = Duration::from_millis(1000 / super::MAX_FPS as u64);

/// When the served screen is drawn: at `--fps` while it animates, promptly for a while after
/// the lecturer acts.
struct Pace {
    /// One frame at `--fps`.
    frame: Duration,
    /// When a frame was last drawn.
    last_draw: Instant,
    /// Until when frames are drawn promptly.
    prompt_until: Instant,
}

impl Pace {
    fn new(frame: Duration) -> Self {
        let now = Instant::now();
        Self {
            frame,
            last_draw: now.checked_sub(frame).unwrap_or(now),
            prompt_until: now,
        }
    }

    /// The lecturer acted: draw as soon as [`PROMPT_GAP`] allows, and promptly for
    /// [`PROMPT`].
    fn acted(&mut self) {
        self.prompt_until = Instant::now() + PROMPT;
    }

    /// The gap between frames now.
    fn gap(&self) -> Duration {
        if Instant::now() < self.prompt_until {
            PROMPT_GAP
        } else {
            self.frame
        }
    }

    /// Whether a frame is due.
    fn due(&self) -> bool {
        self.last_draw.elapsed() >= self.gap()
    }

    fn drawn(&mut self) {
        self.last_draw = Instant::now();
    }

    /// The worker's answers: waits for one until the next look at the file or the next frame,
    /// whichever is first (an answer wakes the loop at once, drawn at once if the lecturer has
    /// just acted), then takes every one waiting.
    fn take_answers(
        &self,
        events: &std::sync::mpsc::Receiver<crate::sim::SimEvent>,
        last_poll: Instant,
        app: &mut crate::app::App,
    ) {
        match events.recv_timeout(self.wait(last_poll)) {
            Ok(e) => {
                app.on_sim(e);
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                std::thread::sleep(self.wait(last_poll));
            }
        }
        while let Ok(e) = events.try_recv() {
            app.on_sim(e);
        }
    }

    /// How long to wait for the worker before the next frame or the next look at the file
    /// (last looked at `last_poll`).
    fn wait(&self, last_poll: Instant) -> Duration {
        let to_frame = self.gap().saturating_sub(self.last_draw.elapsed());
        let to_poll = POLL.saturating_sub(last_poll.elapsed());
        to_frame.min(to_poll).max(Duration::from_millis(1))
    }
}

/// Whether a line is the lecturer acting (a key's effect), not the recorder's bookkeeping
/// (clock, screen, plan, checkpoint lines come while a run plays and are drawn at `--fps`).
fn is_act(event: &crate::app::journal::Event) -> bool {
    use crate::app::journal::Event;
    !matches!(
        event,
        Event::Clock | Event::Screen(_) | Event::Plan { .. } | Event::Checkpoint { .. }
    )
}

/// Why a lecture stopped being followed.
enum Next {
    /// The file was truncated, replaced or is not readable: wait for it again.
    Again,
    /// `serve` is stopping.
    Stop,
    /// The lecturer has gone and the end was served.
    Served,
}

/// Follows `config.file` until `stop`: each frame to `hub`. Once `gone` (the explorer that
/// started this `serve` has ended, however: issue 80, L1), the lecture ends: what the file
/// holds is the whole lecture, its end is served to every reader (within `GONE_SETTLE`),
/// the server goes on [`GRACE`] more for the pages to load the finished lecture, then `stop`
/// is set.
pub fn run(config: &Config, hub: &Hub, stop: &AtomicBool, gone: &AtomicBool) {
    let started = Instant::now();
    while !stop.load(Ordering::Relaxed) {
        // Gone before the file held a lecture: nothing to end.
        if gone.load(Ordering::Relaxed)
            && !std::fs::symlink_metadata(&config.file).is_ok_and(|m| m.is_file() && m.len() > 0)
            && started.elapsed() > POLL
        {
            stop.store(true, Ordering::Relaxed);
            return;
        }
        let opened = if std::fs::symlink_metadata(&config.file).is_ok_and(|m| m.len() > 0) {
            Tail::open_with(&config.file, crate::scenario::write::Links::Refuse)
        } else {
            // The file's name, not its folder (the lecturer's, not the hall's business).
            hub.waiting(&format!(
                "rattleback serve: waiting for the lecturer to start recording {}",
                config
                    .file
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
            ));
            std::thread::sleep(Duration::from_millis(200));
            continue;
        };
        match opened {
            Ok((tail, rec)) => match follow(config, hub, (stop, gone), tail, &rec) {
                Next::Stop => return,
                Next::Served => {
                    let end = Instant::now() + GRACE;
                    while Instant::now() < end && !stop.load(Ordering::Relaxed) {
                        std::thread::sleep(Duration::from_millis(50));
                    }
                    stop.store(true, Ordering::Relaxed);
                    return;
                }
                Next::Again => {}
            },
            Err(e) => {
                hub.waiting(&format!("rattleback serve: {e}"));
                std::thread::sleep(Duration::from_millis(500));
            }
        }
    }
}

/// The screen a recording says its terminal had, bounded.
fn area_of(rec: &crate::record::Recording) -> Rect {
    let t = rec.header.terminal;
    Rect::new(
        0,
        0,
        t.width.clamp(1, MAX_SIDE),
        t.height.clamp(1, MAX_SIDE),
    )
}

/// The page of the whole session in `file` (read again, as `replay --export-html` reads it),
/// written into a temporary file.
fn finished_page(config: &Config, file: &Path) -> Option<tempfile::TempPath> {
    let rec = crate::record::read_with(file, crate::scenario::write::Links::Refuse).ok()?;
    let path = file.display().to_string();
    let size = crate::cast::CastSize {
        cols: None,
        rows: None,
        fps: config.fps,
    };
    let (cast, _) = crate::cast::cast_text(&rec, &path, &config.ui, size, &mut |_| {}).ok()?;
    let name = crate::commands::outputs::recorded_preset(&rec).map_or(path, |p| p.name);
    let page = crate::commands::page::served_page(
        &rec,
        &crate::record::title(&rec, &name),
        &cast,
        config.token.as_deref(),
    );
    let mut out = tempfile::NamedTempFile::new().ok()?;
    std::io::Write::write_all(&mut out, page.as_bytes()).ok()?;
    Some(out.into_temp_path())
}

/// The last screen the lecturer's explorer wrote among `lines`.
fn last_screen(lines: &[crate::record::Line]) -> Option<crate::app::journal::Shown> {
    lines.iter().rev().find_map(|l| match &l.event {
        crate::app::journal::Event::Screen(s) => Some(s.clone()),
        _ => None,
    })
}

/// When a followed lecture's end is served.
struct Ending {
    /// The lecturer's last screen so far (format 10 on, a recording ends with it): the end is
    /// served once the screen drawn here is that one, as `replay --verify` compares them.
    lecturers: Option<crate::app::journal::Shown>,
    /// When the `end` line arrived, or the lecturer was seen gone (the follower's book awaits
    /// no more plans then).
    ended_at: Option<Instant>,
    /// When the lecturer's going was seen (`--serve`: the explorer ended).
    gone_at: Option<Instant>,
    /// Whether the file was read once after that.
    read_after_gone: bool,
    /// The end served.
    finished: bool,
    /// A page that could not be written, tried again then.
    retry_at: Option<Instant>,
}

impl Ending {
    fn new(lines: &[crate::record::Line]) -> Self {
        Self {
            lecturers: last_screen(lines),
            ended_at: lines
                .last()
                .is_some_and(|l| matches!(l.event, crate::app::journal::Event::End { .. }))
                .then(Instant::now),
            gone_at: None,
            read_after_gone: false,
            finished: false,
            retry_at: None,
        }
    }

    /// The lecturer's explorer ended: no more lines will come, whatever the file holds is the
    /// lecture; the effects that say so to the worker.
    fn lecturer_gone(&mut self) -> Vec<crate::app::Effect> {
        self.gone_at = Some(Instant::now());
        if self.ended_at.is_some() {
            return Vec::new();
        }
        self.ended_at = Some(Instant::now());
        vec![crate::app::Effect::Sim(crate::sim::Command::Release)]
    }

    /// Whether the file must be read at once (the lecturer has gone since it was last read).
    fn unread(&self) -> bool {
        self.gone_at.is_some() && !self.read_after_gone
    }

    /// Whether the end is to be served now: the recording ended (or its lecturer went, and the
    /// file was read since), the replay applied every line (`caught_up`), and the screen is
    /// the lecturer's last, or it has had its time to settle.
    fn due(&self, caught_up: bool, app: &crate::app::App) -> bool {
        let settle = if self.gone_at.is_some() {
            GONE_SETTLE
        } else {
            SETTLE
        };
        !self.finished
            && self.ended_at.is_some_and(|at| {
                caught_up
                    && (self.gone_at.is_none() || self.read_after_gone)
                    && self.retry_at.is_none_or(|t| Instant::now() >= t)
                    && (self.lecturers.as_ref().map_or_else(
                        || app.screen_settled() && !app.run.playing,
                        |s| s.difference(&app.shown()).is_none(),
                    ) || at.elapsed() > settle)
            })
    }

    /// Serves the end: the whole session's page (tried again a second later if it cannot be
    /// written).
    fn finish(&mut self, config: &Config, hub: &Hub) {
        match finished_page(config, &config.file) {
            Some(page) => {
                hub.finish(page);
                self.finished = true;
            }
            None => self.retry_at = Some(Instant::now() + Duration::from_secs(1)),
        }
    }
}

/// Follows one recording (from its header to its end, or until the file is replaced).
fn follow(
    config: &Config,
    hub: &Hub,
    (stop, gone): (&AtomicBool, &AtomicBool),
    mut tail: Tail,
    rec: &crate::record::Recording,
) -> Next {
    let path = config.file.display().to_string();
    let (mut app, mut effects) = match crate::record::start(rec, &path) {
        Ok(x) => x,
        Err(e) => {
            hub.waiting(&format!("rattleback serve: {e}"));
            std::thread::sleep(Duration::from_millis(500));
            return Next::Again;
        }
    };
    let Ok(mut screen) = MemoryScreen::new(area_of(rec)) else {
        return Next::Again;
    };
    let (tx, events) = sync_channel(256);
    let worker = Worker::spawn_with(crate::record::replayer::follower_book(rec), move |e| {
        tx.send(e).is_ok()
    });
    let lines: Vec<_> = rec.lines.iter().map(|(_, l)| l.clone()).collect();
    let mut ending = Ending::new(&lines);
    if ending.ended_at.is_some() {
        effects.push(crate::app::Effect::Sim(crate::sim::Command::Release));
    }
    let mut replay = Replayer::live(lines, crate::explorer::lecturer_now(rec, &config.file));
    effects.extend(replay.catch_up(&mut app));
    let frame = Duration::from_secs_f64(1.0 / config.fps);
    let mut last = Instant::now();
    let mut last_poll = Instant::now();
    let mut pace = Pace::new(frame);
    let mut first = true;
    let next = loop {
        if stop.load(Ordering::Relaxed) || crate::interrupt::requested().is_some() {
            break Next::Stop;
        }
        if ending.finished && ending.gone_at.is_some() {
            break Next::Served;
        }
        if ending.gone_at.is_none() && gone.load(Ordering::Relaxed) {
            effects.extend(ending.lecturer_gone());
        }
        pace.take_answers(&events, last_poll, &mut app);
        if last_poll.elapsed() >= POLL || ending.unread() {
            last_poll = Instant::now();
            ending.read_after_gone = ending.gone_at.is_some();
            match tail.poll() {
                Some(TailEvent::Lines(lines)) => {
                    if lines.iter().any(|l| is_act(&l.event)) {
                        pace.acted();
                    }
                    ending.lecturers = last_screen(&lines).or(ending.lecturers.take());
                    let (more, end) = crate::explorer::follow_lines(lines, &mut app, &mut replay);
                    effects.extend(more);
                    if end && ending.ended_at.is_none() {
                        ending.ended_at = Some(Instant::now());
                    }
                }
                Some(TailEvent::Restarted { .. }) => break Next::Again,
                Some(TailEvent::Missing(_)) | None => {}
            }
        }
        let now = Instant::now();
        effects.extend(replay.advance((now - last).as_secs_f64(), &mut app));
        last = now;
        for c in commands(std::mem::take(&mut effects)) {
            worker.send(c);
        }
        // The lecturer's size at this moment (format 14): the hub restarts every reader's
        // terminal at a new size.
        if let Some(now) = app.lecturer_terminal
            && screen
                .resize_to(now, Rect::new(0, 0, MAX_SIDE, MAX_SIDE))
                .is_err()
        {
            break Next::Again;
        }
        // The end is served after the screen it ends on.
        let end = ending.due(replay.info().ended, &app);
        if pace.due() || end {
            pace.drawn();
            match screen.frame(&mut app, &config.ui) {
                // The first frame of a lecture sets every reader's terminal (its size may differ).
                Ok(Some(_)) if first => {
                    first = false;
                    hub.restart(screen.last());
                }
                Ok(Some(bytes)) => hub.frame(&bytes, screen.last()),
                Ok(None) => {}
                Err(_) => break Next::Again,
            }
        }
        if end {
            ending.finish(config, hub);
        }
    };
    worker.join_within(Duration::from_millis(100));
    next
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::journal::Event;

    #[test]
    fn frames_come_at_the_rate_until_the_lecturer_acts_then_promptly() {
        let frame = Duration::from_millis(100);
        let mut pace = Pace::new(frame);
        assert!(pace.due(), "the first frame is drawn at once");
        pace.drawn();
        assert!(!pace.due(), "the next waits for --fps");
        assert_eq!(pace.gap(), frame);
        assert!(
            pace.wait(Instant::now()) <= POLL,
            "the file is looked at every POLL"
        );
        pace.acted();
        assert_eq!(
            pace.gap(),
            PROMPT_GAP,
            "the act and the answers after it promptly"
        );
        assert!(pace.wait(Instant::now()) <= PROMPT_GAP);
        std::thread::sleep(PROMPT_GAP);
        assert!(pace.due(), "drawn within the gap");
    }

    #[test]
    fn prompt_frames_keep_under_the_rate_ceiling() {
        // However often the lecturer acts, frames stay MAX_FPS a second at most.
        assert!(PROMPT_GAP.as_secs_f64() >= 1.0 / f64::from(super::super::MAX_FPS) - 1e-3);
        let mut pace = Pace::new(Duration::from_millis(100));
        pace.acted();
        pace.drawn();
        pace.acted();
        // Acting again right after a frame waits the gap.
        assert!(!pace.due());
    }

    #[test]
    fn the_recorders_bookkeeping_is_not_an_act() {
        assert!(is_act(&Event::Pause));
        assert!(is_act(&Event::Step));
        assert!(is_act(&Event::Set {
            field: "k".into(),
            value: "1".into()
        }));
        assert!(!is_act(&Event::Clock));
    }
}
