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
    /// What the cost model predicted the whole work takes (s): the line says the time left.
    priced: Option<f64>,
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
            priced: None,
        }
    }

    /// The same line, saying the time left: from `predicted_seconds` (the cost model's price of
    /// the whole work) at first, from the pace measured as the work goes.
    #[must_use]
    pub fn priced(mut self, predicted_seconds: f64) -> Self {
        self.priced = Some(predicted_seconds).filter(|s| s.is_finite() && *s >= 0.0);
        self
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
            let left = self.priced.map_or_else(String::new, |predicted| {
                let elapsed = now.duration_since(self.started).as_secs_f64();
                format!(
                    ", {} left",
                    duration(time_left(predicted, elapsed, fraction))
                )
            });
            format!("{}: {t:.0} of {:.0} {unit}{left}", self.label, self.t_end)
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

    /// The whole is now `total` (a count that grows as the work finds more to do).
    pub fn expect(&mut self, total: f64) {
        if total > self.t_end {
            if let Some(predicted) = &mut self.priced
                && self.t_end > 0.0
            {
                *predicted *= total / self.t_end;
            }
            self.t_end = total;
        }
    }

    /// Reports `t` (or the count done); always `true` (work is cancelled by Ctrl-C, which
    /// ends it through the interrupt flag).
    pub fn tick(&mut self, t: f64) -> bool {
        if self.enabled
            && let Some((text, fraction)) = self.line(t, Instant::now())
        {
            let priced = self.priced.is_some();
            let bar = self.bar.get_or_insert_with(|| {
                let bar = ProgressBar::with_draw_target(Some(STEPS), ProgressDrawTarget::stderr());
                // ASCII only: right under any locale and font. With the time left in the
                // message, a shorter bar and no elapsed time, so the line fits 80 columns.
                let template = if priced {
                    "{wide_msg} [{bar:16}] {percent:>3}%"
                } else {
                    "{msg} [{bar:24}] {percent:>3}% {elapsed}"
                };
                bar.set_style(
                    ProgressStyle::with_template(template)
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

/// Runs `work` with `progress` (a count, on stderr: a terminal only), counting each call of
/// the counter `work` is given (from any thread); the bar is erased at the end.
pub(super) fn counted<R>(progress: Progress, work: &dyn Fn(&(dyn Fn() + Sync)) -> R) -> R {
    tallied(progress, &|tally| work(tally.done))
}

/// [`counted`] for work whose length grows as it goes (a refined chart's passes): `tally`
/// hears each cell done and the cells now expected.
pub(super) fn tallied<R>(
    progress: Progress,
    work: &dyn Fn(&crate::study::chart::Tally<'_>) -> R,
) -> R {
    let progress = std::sync::Mutex::new(progress);
    let count = std::sync::atomic::AtomicUsize::new(0);
    let done = || {
        let n = count.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        if let Ok(mut p) = progress.lock() {
            p.tick(n as f64);
        }
    };
    let expect = |total: usize| {
        if let Ok(mut p) = progress.lock() {
            p.expect(total as f64);
        }
    };
    let out = work(&crate::study::chart::Tally {
        done: &done,
        expect: &expect,
    });
    if let Ok(mut p) = progress.lock() {
        p.finish();
    }
    out
}

/// Seconds left of work the cost model priced at `predicted` (s), a `fraction` done in
/// `elapsed` (s): the model's remainder at first, the measured pace's as the work goes (each
/// weighted by how much is done).
#[must_use]
pub fn time_left(predicted: f64, elapsed: f64, fraction: f64) -> f64 {
    let f = fraction.clamp(0.0, 1.0);
    if f <= 0.0 {
        return predicted;
    }
    let modelled = predicted * (1.0 - f);
    let measured = elapsed * (1.0 - f) / f;
    ((1.0 - f) * modelled + f * measured).max(0.0)
}

/// `12 s`, `3 min 05 s`, `2 h 10 min`: a time left, short.
#[must_use]
pub fn duration(seconds: f64) -> String {
    let s = seconds.max(0.0).ceil().min(1e9) as u64;
    if s < 60 {
        format!("{s} s")
    } else if s < 3600 {
        format!("{} min {:02} s", s / 60, s % 60)
    } else {
        format!("{} h {:02} min", s / 3600, (s % 3600) / 60)
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

    #[test]
    fn a_priced_count_says_the_time_left() {
        let mut p = Progress::new("study map", 200.0, false).priced(40.0);
        p.unit = Some("cells");
        // A quarter done in 2 s against a price of 40 s: the model says 30 s left, the pace
        // 6 s; three quarters of the weight is the model's.
        let (line, _) = p
            .line(50.0, p.started + Duration::from_secs(2))
            .expect("shown");
        assert_eq!(line, "study map: 50 of 200 cells, 24 s left");
        // Nearly done: the pace decides.
        let (line, _) = p
            .line(190.0, p.started + Duration::from_secs(10))
            .expect("shown");
        assert_eq!(line, "study map: 190 of 200 cells, 1 s left");
    }

    #[test]
    fn the_time_left_runs_from_the_price_to_the_pace() {
        assert!((time_left(40.0, 0.0, 0.0) - 40.0).abs() < 1e-12);
        assert!(time_left(40.0, 9.0, 1.0).abs() < 1e-12);
        // A model 10 times pessimistic matters less and less.
        let early = time_left(100.0, 1.0, 0.1);
        let late = time_left(100.0, 9.0, 0.9);
        assert!(early > 70.0 && late < 2.0, "{early} {late}");
        assert_eq!(duration(0.2), "1 s");
        assert_eq!(duration(185.0), "3 min 05 s");
        assert_eq!(duration(7800.0), "2 h 10 min");
        assert_eq!(duration(f64::INFINITY), duration(1e9));
    }
}
