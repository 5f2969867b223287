//! Progress of long headless work on stderr, only when stderr is a terminal: an indicatif bar,
//! shown once the work has taken more than a second, redrawn at most five times a second, and
//! erased at the end (so pipes, logs and quick runs see nothing). Time-based for `simulate`
//! (`t` of `t_end`, a restart from an earlier `t` counted as the next run, as `auto`'s
//! verification does); count-based for the studies, `replay --verify` and `--export-cast`.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long work goes before progress shows.
const QUIET_FOR: Duration = Duration::from_secs(1);
/// Shortest interval between two updates.
const EVERY: Duration = Duration::from_millis(200);
/// The bar's resolution.
const STEPS: u64 = 1000;

/// One progress bar.
#[derive(Debug)]
pub struct Progress {
    label: String,
    t_end: f64,
    started: Instant,
    last: Option<Instant>,
    run: u32,
    last_t: f64,
    enabled: bool,
    /// The bar, made when first shown.
    bar: Option<ProgressBar>,
    /// `Some(what)` for count-based progress (`cells`, `lines`, `frames`).
    unit: Option<&'static str>,
}

impl Progress {
    /// Progress of `label` towards `t_end`, on stderr if it is a terminal.
    #[must_use]
    pub fn stderr(label: &str, t_end: f64) -> Self {
        Self::new(label, t_end, std::io::stderr().is_terminal())
    }

    /// Progress of `label` through `total` `unit`s (`cells`, `lines`…), on stderr if it is a
    /// terminal.
    #[must_use]
    pub fn count(label: &str, total: usize, unit: &'static str) -> Self {
        let mut p = Self::new(label, total as f64, std::io::stderr().is_terminal());
        p.unit = Some(unit);
        p
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
            bar: None,
            unit: None,
        }
    }

    /// The message for `t` (a time, or a count) and the fraction done, or `None` when it is
    /// not yet time to show one.
    pub fn line(&mut self, t: f64, now: Instant) -> Option<(String, f64)> {
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
        let fraction = if self.t_end > 0.0 {
            (t / self.t_end).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let text = if let Some(unit) = self.unit {
            format!("{}: {t:.0} of {:.0} {unit}", self.label, self.t_end)
        } else {
            let run = if self.run > 1 {
                format!(", run {}", self.run)
            } else {
                String::new()
            };
            format!("{}: t = {t:.6e} of {:e}{run}", self.label, self.t_end)
        };
        Some((text, fraction))
    }

    /// Reports `t` (or the count done); always `true` (work is cancelled by Ctrl-C, which
    /// ends it through the interrupt flag).
    pub fn tick(&mut self, t: f64) -> bool {
        if self.enabled
            && let Some((text, fraction)) = self.line(t, Instant::now())
        {
            let bar = self.bar.get_or_insert_with(|| {
                let bar = ProgressBar::with_draw_target(Some(STEPS), ProgressDrawTarget::stderr());
                // ASCII only: right under any locale and font.
                bar.set_style(
                    ProgressStyle::with_template("{msg} [{bar:24}] {percent:>3}% {elapsed}")
                        .unwrap_or_else(|_| ProgressStyle::default_bar())
                        .progress_chars("=> "),
                );
                bar
            });
            bar.set_message(text);
            bar.set_position((fraction * STEPS as f64) as u64);
        }
        true
    }

    /// Erases the bar if one was shown.
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
        self.last = None;
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
        let (first, fraction) = p
            .line(15.0, t0 + Duration::from_millis(1500))
            .expect("shown");
        assert!(first.starts_with("simulate: t = 1.5"), "{first}");
        assert!((fraction - 0.5).abs() < 1e-12, "{fraction}");
        assert_eq!(p.line(16.0, t0 + Duration::from_millis(1600)), None);
        let (again, _) = p
            .line(2.0, t0 + Duration::from_millis(1800))
            .expect("shown");
        assert!(again.contains("run 2"), "{again}");
    }

    #[test]
    fn control_characters_in_the_label_are_removed() {
        let mut p = Progress::new("a\x1b]0;x\x07b", 1.0, false);
        let (line, _) = p
            .line(0.5, p.started + Duration::from_secs(2))
            .expect("shown");
        assert!(!line.chars().any(char::is_control), "{line:?}");
    }

    #[test]
    fn counts_say_how_many_of_how_many() {
        let mut p = Progress::new("study map", 200.0, false);
        p.unit = Some("cells");
        let (line, fraction) = p
            .line(50.0, p.started + Duration::from_secs(2))
            .expect("shown");
        assert_eq!(line, "study map: 50 of 200 cells");
        assert!((fraction - 0.25).abs() < 1e-12);
    }
}
