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
use crate::explorer::replay::Replayer;
use crate::record::tail::{Tail, TailEvent};
use crate::sim::Worker;

/// How often the file is looked at (as `follow`'s).
const POLL: Duration = Duration::from_millis(40);
/// After the `end` line, how long the screen may take to reach the lecturer's last before the
/// end is served anyway (a recording too old to hold its last screen, or one that cannot be
/// replayed to it).
const SETTLE: Duration = Duration::from_secs(30);
/// The largest terminal a recording may say it had (a forged header cannot make the server
/// draw a screen of billions of cells).
const MAX_SIDE: u16 = 1000;

/// Why a lecture stopped being followed.
enum Next {
    /// The file was truncated, replaced or is not readable: wait for it again.
    Again,
    /// `serve` is stopping.
    Stop,
}

/// Follows `config.file` until `stop`: each frame to `hub`.
pub fn run(config: &Config, hub: &Hub, stop: &AtomicBool) {
    while !stop.load(Ordering::Relaxed) {
        let opened = if config
            .file
            .metadata()
            .is_ok_and(|m| m.is_file() && m.len() > 0)
        {
            Tail::open(&config.file)
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
            Ok((tail, rec)) => match follow(config, hub, stop, tail, &rec) {
                Next::Stop => return,
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
    let rec = crate::record::read(file).ok()?;
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

/// Follows one recording (from its header to its end, or until the file is replaced).
fn follow(
    config: &Config,
    hub: &Hub,
    stop: &AtomicBool,
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
    let worker = Worker::spawn_with(crate::explorer::follower_book(rec), move |e| {
        tx.send(e).is_ok()
    });
    let lines: Vec<_> = rec.lines.iter().map(|(_, l)| l.clone()).collect();
    // The lecturer's last screen so far (format 10 on, a recording ends with it): the end is
    // served once the screen drawn here is that one, as `replay --verify` compares them.
    let mut lecturers = last_screen(&lines);
    // When the `end` line arrived (the follower's book awaits no more plans then).
    let mut ended_at = lines
        .last()
        .is_some_and(|l| matches!(l.event, crate::app::journal::Event::End { .. }))
        .then(Instant::now);
    if ended_at.is_some() {
        effects.push(crate::app::Effect::Sim(crate::sim::Command::Release));
    }
    let mut replay = Replayer::live(lines, crate::explorer::lecturer_now(rec, &config.file));
    effects.extend(replay.catch_up(&mut app));
    let frame = Duration::from_secs_f64(1.0 / config.fps);
    let mut last = Instant::now();
    let mut last_poll = Instant::now();
    // The end served; a page that could not be written, tried again a second later.
    let mut finished = false;
    let mut retry_at: Option<Instant> = None;
    let mut first = true;
    let next = loop {
        if stop.load(Ordering::Relaxed) || crate::interrupt::requested().is_some() {
            break Next::Stop;
        }
        while let Ok(e) = events.try_recv() {
            app.on_sim(e);
        }
        if last_poll.elapsed() >= POLL {
            last_poll = Instant::now();
            match tail.poll() {
                Some(TailEvent::Lines(lines)) => {
                    lecturers = last_screen(&lines).or(lecturers);
                    let (more, end) = crate::explorer::follow_lines(lines, &mut app, &mut replay);
                    effects.extend(more);
                    if end && ended_at.is_none() {
                        ended_at = Some(Instant::now());
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
        if !finished
            && let Some(at) = ended_at
            && replay.info().ended
            && retry_at.is_none_or(|t| Instant::now() >= t)
            && (lecturers.as_ref().map_or_else(
                || app.screen_settled() && !app.run.playing,
                |s| s.difference(&app.shown()).is_none(),
            ) || at.elapsed() > SETTLE)
        {
            match finished_page(config, &config.file) {
                Some(page) => {
                    hub.finish(page);
                    finished = true;
                }
                None => retry_at = Some(Instant::now() + Duration::from_secs(1)),
            }
        }
        std::thread::sleep(frame.saturating_sub(now.elapsed()));
    };
    worker.join_within(Duration::from_millis(100));
    next
}
