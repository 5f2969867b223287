//! Replay of a recording, in the terminal's explorer, `follow`, the served page and the
//! browser's fork: the recording drives the app at its own pace; keys (from the replay keymap)
//! pause, change the pace and jump between chapters.

use crate::app::keys::{ReplayAction, replay_action_for};
use crate::app::{App, Effect, Key, ReplayInfo};
use crate::record::Line;

/// The replay's clock and position in the file.
pub struct Replayer {
    lines: Vec<Line>,
    chapters: Vec<usize>,
    next: usize,
    clock: f64,
    pace: f64,
    paused: bool,
    /// Following a file being written: the clock runs past the last line (the lecturer's own
    /// clock), and `Some(true)` once its `end` line arrived.
    live: Option<bool>,
}

/// Pace limits (×).
const PACE: (f64, f64) = (1.0 / 16.0, 64.0);

impl Replayer {
    /// A replay of `lines` from its start.
    #[must_use]
    pub fn new(lines: Vec<Line>) -> Self {
        let chapters = (0..lines.len())
            .filter(|&i| lines[i].event.starts_chapter())
            .collect();
        Self {
            lines,
            chapters,
            next: 0,
            clock: 0.0,
            pace: 1.0,
            paused: false,
            live: None,
        }
    }

    /// A replay that follows a recording being written, its clock at `now` (the lecturer's
    /// clock: the last line's wall plus the time since it was written).
    #[must_use]
    pub fn live(lines: Vec<Line>, now: f64) -> Self {
        let ended = lines
            .last()
            .is_some_and(|l| matches!(l.event, crate::app::journal::Event::End { .. }));
        let mut me = Self::new(lines);
        me.live = Some(ended);
        me.clock = now;
        me
    }

    /// New lines of the followed file. A line stamped well ahead of the clock means the
    /// follower fell behind the lecturer: the clock jumps to it (paced to the lecturer's clock).
    pub fn push(&mut self, lines: Vec<Line>, app: &mut App) -> Vec<Effect> {
        for line in lines {
            if line.event.starts_chapter() {
                self.chapters.push(self.lines.len());
            }
            if matches!(line.event, crate::app::journal::Event::End { .. }) {
                self.live = Some(true);
            }
            if !self.paused && line.wall > self.clock + 0.5 {
                self.clock = line.wall;
            }
            self.lines.push(line);
        }
        self.catch_up(app)
    }

    /// How many lines have been applied.
    #[must_use]
    pub fn position(&self) -> usize {
        self.next
    }

    /// Whether this follows a file being written.
    #[must_use]
    pub fn following(&self) -> bool {
        self.live.is_some()
    }

    /// Chapters already passed.
    fn passed(&self) -> usize {
        self.chapters.iter().filter(|&&i| i < self.next).count()
    }

    /// What the status bar shows.
    #[must_use]
    pub fn info(&self) -> ReplayInfo {
        let length = self.lines.last().map_or(0.0, |l| l.wall);
        ReplayInfo {
            pace: self.pace,
            paused: self.paused,
            chapter: self.passed(),
            chapters: self.chapters.len(),
            ended: self.next >= self.lines.len(),
            at: if self.live.is_some() {
                self.clock
            } else {
                self.clock.min(length)
            },
            length,
            live: self.live,
        }
    }

    /// Whether the clock runs.
    #[must_use]
    pub fn running(&self) -> bool {
        !self.paused && (self.live == Some(false) || self.next < self.lines.len())
    }

    /// Applies every line up to the clock.
    pub fn catch_up(&mut self, app: &mut App) -> Vec<Effect> {
        let mut effects = Vec::new();
        while self.next < self.lines.len() && self.lines[self.next].wall <= self.clock {
            let line = &self.lines[self.next];
            let rose = self
                .next
                .checked_sub(1)
                .is_some_and(|i| line.generation > self.lines[i].generation);
            effects.extend(app.seek(line.t));
            effects.extend(app.apply_event(&line.event, rose));
            self.next += 1;
        }
        // The display moves between recorded displayed times, never past the next one (while
        // following, past the last one received). A next line of a later run (a reset, a
        // change) says nothing of this run's times: this run holds at its last line's. Past
        // the last line the recording says nothing more: the display holds there too (issue
        // 55: a replay played on, alone, after "replay ended").
        let last = self.next.checked_sub(1).map(|i| &self.lines[i]);
        app.run
            .set_ceiling(match (self.lines.get(self.next), last) {
                (Some(next), Some(last)) if next.generation != last.generation => Some(last.t),
                (Some(next), _) => Some(next.t),
                (None, last) => last.map(|l| l.t),
            });
        app.set_replay(self.info());
        effects
    }

    /// Advances the clock by `wall` seconds (scaled by the pace).
    pub fn advance(&mut self, wall: f64, app: &mut App) -> Vec<Effect> {
        let mut effects = Vec::new();
        if self.running() {
            self.clock += wall * self.pace;
            effects.extend(self.catch_up(app));
        }
        if app.run.playing {
            effects.extend(app.tick(wall * self.pace));
        }
        effects
    }

    /// Jumps to the wall time of line `index` (the start when `None`), replaying from the
    /// beginning when that is behind: `rebuild` gives a fresh app at the recording's start.
    fn jump(
        &mut self,
        index: Option<usize>,
        app: &mut App,
        rebuild: &dyn Fn(&App) -> (App, Vec<Effect>),
    ) -> Vec<Effect> {
        let mut effects = Vec::new();
        let back = index.is_none_or(|i| i < self.next);
        if back {
            let (fresh, start) = rebuild(app);
            *app = fresh;
            effects.extend(start);
            self.next = 0;
        }
        self.clock = index.map_or(0.0, |i| self.lines[i].wall);
        effects.extend(self.catch_up(app));
        effects
    }

    /// Handles a key; `rebuild` makes a fresh app at the recording's start (for going back).
    pub fn key(
        &mut self,
        key: Key,
        app: &mut App,
        rebuild: &dyn Fn(&App) -> (App, Vec<Effect>),
    ) -> Vec<Effect> {
        let Some(action) = replay_action_for(key) else {
            return Vec::new();
        };
        let effects = match action {
            ReplayAction::TogglePause => {
                self.paused = !self.paused;
                Vec::new()
            }
            ReplayAction::Faster => {
                self.pace = (self.pace * 2.0).min(PACE.1);
                Vec::new()
            }
            ReplayAction::Slower => {
                self.pace = (self.pace / 2.0).max(PACE.0);
                Vec::new()
            }
            ReplayAction::NextChapter => match self.chapters.get(self.passed()).copied() {
                Some(i) => self.jump(Some(i), app, rebuild),
                None => Vec::new(),
            },
            ReplayAction::PreviousChapter => {
                // The chapter before the current one (or the start): one chapter per press.
                let passed = self.passed();
                let target = passed
                    .checked_sub(2)
                    .and_then(|c| self.chapters.get(c).copied());
                self.jump(target, app, rebuild)
            }
            ReplayAction::ToggleHelp => app.update(crate::app::Action::ToggleHelp),
            ReplayAction::Redraw => vec![Effect::Redraw],
            ReplayAction::Suspend => vec![Effect::Suspend],
            ReplayAction::Quit => {
                app.update(crate::app::Action::Quit);
                Vec::new()
            }
        };
        app.set_replay(self.info());
        effects
    }
}

/// A replay's clock counted in frames of `1/fps` (no drift from adding `1/fps` again and
/// again), for what plays a recording without a person watching: the cast export draws a
/// frame at each, the browser's fork plays the lecture to its last line. Idle stretches
/// (paused, nothing due) are jumped to the next line on the frame grid.
pub struct FrameClock {
    fps: f64,
    frame: u64,
    shown_until: f64,
}

impl FrameClock {
    /// At the start, `fps` frames a second.
    #[must_use]
    pub fn new(fps: f64) -> Self {
        Self {
            fps,
            frame: 0,
            shown_until: 0.0,
        }
    }

    /// The current frame's time.
    #[must_use]
    pub fn now(&self) -> f64 {
        self.frame as f64 / self.fps
    }

    /// Brings `replay` and `app` to the current frame's time: the effects to run.
    pub fn show(&mut self, replay: &mut Replayer, app: &mut App) -> Vec<Effect> {
        let clock = self.now();
        let effects = replay.advance(clock - self.shown_until, app);
        self.shown_until = clock;
        effects
    }

    /// On to the next frame; while nothing moves until the replay's next line, to the frame
    /// of that line.
    pub fn next(&mut self, replay: &Replayer, app: &App) {
        self.frame += 1;
        if !app.run.playing
            && let Some(l) = replay.lines.get(replay.next)
            && l.wall > self.now()
        {
            self.frame = ((l.wall * self.fps).floor() as u64).max(self.frame);
        }
    }
}

/// A follower's plan book (`follow` and `serve`): the recording's plans so far, its runs
/// bounded one by one (it grows), its later segments awaited from the lecturer unless it ended.
#[must_use]
pub fn follower_book(rec: &crate::record::Recording) -> crate::sim::PlanBook {
    let mut book = crate::record::plan_book(rec);
    book.total = f64::INFINITY;
    book.awaits = !rec
        .lines
        .last()
        .is_some_and(|(_, l)| matches!(l.event, crate::app::journal::Event::End { .. }));
    book
}
