//! Progress of long headless runs on stderr, only when stderr is a terminal: one line,
//! rewritten at most five times a second once a run has taken more than a second, and erased
//! at the end (so pipes, logs and quick runs see nothing).

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// How long a run goes before progress shows.
const QUIET_FOR: Duration = Duration::from_secs(1);
/// Shortest interval between two updates.
const EVERY: Duration = Duration::from_millis(200);

/// One progress line.
#[derive(Debug)]
pub struct Progress {
    label: String,
    t_end: f64,
    started: Instant,
    last: Option<Instant>,
    run: u32,
    last_t: f64,
    enabled: bool,
}

impl Progress {
    /// Progress of `label` towards `t_end`, on stderr if it is a terminal.
    #[must_use]
    pub fn stderr(label: &str, t_end: f64) -> Self {
        Self::new(label, t_end, std::io::stderr().is_terminal())
    }

    /// As [`Progress::stderr`], shown or not as `enabled` says (tests).
    #[must_use]
    pub fn new(label: &str, t_end: f64, enabled: bool) -> Self {
        Self {
            label: crate::scenario::text::clean(label),
            t_end,
            started: Instant::now(),
            last: None,
            run: 1,
            last_t: 0.0,
            enabled,
        }
    }

    /// The line for time `t` (a run that restarts from an earlier time is the next run, as
    /// `auto`'s verification does), or `None` when it is not yet time to show one.
    pub fn line(&mut self, t: f64, now: Instant) -> Option<String> {
        if t < self.last_t {
            self.run += 1;
        }
        self.last_t = t;
        if now.duration_since(self.started) < QUIET_FOR
            || self.last.is_some_and(|l| now.duration_since(l) < EVERY)
        {
            return None;
        }
        self.last = Some(now);
        let percent = if self.t_end > 0.0 {
            (100.0 * t / self.t_end).clamp(0.0, 100.0)
        } else {
            100.0
        };
        let run = if self.run > 1 {
            format!(", run {}", self.run)
        } else {
            String::new()
        };
        Some(format!(
            "{}: t = {t:.6e} of {:e} ({percent:.0} %){run}, {:.0} s",
            self.label,
            self.t_end,
            now.duration_since(self.started).as_secs_f64()
        ))
    }

    /// Reports `t`; always `true` (a run is cancelled by Ctrl-C, which ends the process).
    pub fn tick(&mut self, t: f64) -> bool {
        if self.enabled
            && let Some(line) = self.line(t, Instant::now())
        {
            let mut err = std::io::stderr().lock();
            let _ = write!(err, "\r\x1b[K{line}");
            let _ = err.flush();
        }
        true
    }

    /// Erases the line if one was shown.
    pub fn finish(&mut self) {
        if self.enabled && self.last.is_some() {
            let mut err = std::io::stderr().lock();
            let _ = write!(err, "\r\x1b[K");
            let _ = err.flush();
            self.last = None;
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quiet_at_first_then_throttled_and_counting_runs() {
        let mut p = Progress::new("simulate", 30.0, false);
        let t0 = p.started;
        assert_eq!(p.line(1.0, t0 + Duration::from_millis(500)), None);
        let first = p
            .line(15.0, t0 + Duration::from_millis(1500))
            .expect("shown");
        assert!(first.starts_with("simulate: t = 1.5"), "{first}");
        assert!(first.contains("(50 %)"), "{first}");
        assert_eq!(p.line(16.0, t0 + Duration::from_millis(1600)), None);
        let again = p
            .line(2.0, t0 + Duration::from_millis(1800))
            .expect("shown");
        assert!(again.contains("run 2"), "{again}");
    }

    #[test]
    fn control_characters_in_the_label_are_removed() {
        let mut p = Progress::new("a\x1b]0;x\x07b", 1.0, false);
        let line = p
            .line(0.5, p.started + Duration::from_secs(2))
            .expect("shown");
        assert!(!line.chars().any(char::is_control), "{line:?}");
    }
}
