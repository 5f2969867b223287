//! Verification in segments: the explorer draws as soon as `auto` has verified the start of a
//! long run, and keeps verifying ahead of the display.
//!
//! A run of horizon `T` longer than [`FIRST_SEGMENT`] is verified over the nested horizons
//! `T/2^m, …, T/2, T` ([`horizons`]), the first at most `FIRST_SEGMENT`. Each is `auto`'s
//! plan for that horizon, verified over all of `[0, T_j]` exactly as `simulate --set
//! run.t_end=T_j` verifies it, and shown on `(T_{j−1}, T_j]`: what is on screen is always
//! covered by a verified plan, and the last segment is `simulate`'s own run, so the end of the
//! run is the state `simulate` reports, bit for bit. The first plan is verified before anything
//! is drawn; the others on a thread of their own ([`Ahead`]), each integrated from `t = 0` to
//! its start there too, so the display never waits for a catch-up. Nested horizons cost about
//! twice one verification of `T` (1.5–2.2× measured, `rattleback bench --only segments`), on the
//! second core.
//!
//! The horizons are a function of `T` alone, so a replay or a follower finds the same ones. A
//! session file of format 9 on is verified in segments; older files replay as they were shown,
//! in one piece ([`super::PlanBook::segmented`]).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, Sender, TryRecvError};

use super::session::Segment;
use super::{PlanBook, PlanKey, SessionSpec};
use crate::physics::method::StepError;
use crate::physics::plan::Resolved;
/// The longest first segment: a run at most this long is verified in one piece (every shipped
/// preset is).
pub const FIRST_SEGMENT: f64 = 64.0;

/// Longest wait, in wall seconds, of a follower's verification ahead for the lecturer's plan of
/// one segment ([`PlanBook::awaits`]) before it verifies the segment itself: the lecturer
/// verifies it at the same moment, so the plan normally comes within its verification time
/// and the file's polling; a lecturer gone without an end line costs this much once (the
/// follower then verifies the rest itself).
pub const AWAIT_SECONDS: f64 = 5.0;

/// What a follower's worker passes on to its verification ahead.
#[derive(Clone, Copy, Debug)]
pub enum Forward {
    /// The lecturer's plan of a key.
    Plan(PlanKey, Resolved, Option<f64>),
    /// Stop waiting: verify what is not in the book.
    Release,
}

/// The most segments of a run (a horizon of `FIRST_SEGMENT · 2^39` and more is cut to this).
const MOST_SEGMENTS: usize = 40;

/// The nested horizons of a run of horizon `t_end`: `t_end / 2^m, …, t_end / 2, t_end`, the
/// first at most [`FIRST_SEGMENT`] (exact: halving is exact in binary). One horizon for a run
/// at most `FIRST_SEGMENT` long.
#[must_use]
pub fn horizons(t_end: f64) -> Vec<f64> {
    let mut out = vec![t_end];
    let mut t = t_end;
    while t > FIRST_SEGMENT && out.len() < MOST_SEGMENTS {
        t /= 2.0;
        out.push(t);
    }
    out.reverse();
    out
}

/// What the verifying thread reports, in order.
pub enum Report {
    /// How far the verification of horizon `until` has come (as [`super::SimEvent::PlanProgress`]).
    Progress {
        /// The horizon being verified.
        until: f64,
        /// Which of `auto`'s integrations, from 1.
        run: u32,
        /// Its progress, in whole percent of the horizon.
        percent: u8,
    },
    /// `auto` resolved and verified the plan of the horizon `until`, shown after `from`.
    Verified {
        /// Where its segment starts.
        from: f64,
        /// Its horizon.
        until: f64,
        /// The plan.
        plan: Resolved,
        /// `auto`'s error estimate over `[0, until]`.
        estimate: Option<f64>,
    },
    /// That plan, integrated to its start, ready to take over.
    Ready(Box<Segment>),
    /// The verification beyond `from` failed (the run stops there).
    Failed {
        /// Where the segment that failed starts.
        from: f64,
        /// Why.
        error: StepError,
    },
}

/// What [`Ahead::try_next`] found.
pub enum Next {
    /// A report.
    Report(Report),
    /// Nothing yet.
    Nothing,
    /// The thread has ended and everything it sent was taken.
    Ended,
}

/// The verifying thread of one run; dropping it cancels it (it stops at its next look, within
/// a few hundred steps).
pub struct Ahead {
    reports: Receiver<Report>,
    cancel: Arc<AtomicBool>,
    /// Plans resolved elsewhere, passed on to the thread ([`Ahead::forward`]).
    forwarded: Sender<Forward>,
}

impl Ahead {
    /// Starts verifying the segments of `spec` after the first (`horizons[0]`, already
    /// verified), in order, with `book`'s recorded plans, policy and arithmetic; the horizons
    /// are those within the budget ([`super::PlanBook::check_auto`]).
    ///
    /// # Panics
    /// When the OS cannot spawn a thread (the browser's module spawns none: it verifies them
    /// here, before returning).
    #[must_use]
    pub fn spawn(book: PlanBook, spec: SessionSpec, horizons: &[f64]) -> Self {
        let (tx, reports) = mpsc::channel();
        let (forwarded, plans) = mpsc::channel();
        let cancel = Arc::new(AtomicBool::new(false));
        let stop = Arc::clone(&cancel);
        let pairs: Vec<(f64, f64)> = horizons.windows(2).map(|w| (w[0], w[1])).collect();
        let verify = move || {
            let mut book = book;
            // The browser's module starts no thread: it verifies them here, at once, on its
            // own (a fork has released its book; nothing is awaited from a lecturer).
            if cfg!(target_arch = "wasm32") {
                book.awaits = false;
            }
            let functions = book.arithmetic.functions;
            crate::physics::numerics::elementary::following(functions, || {
                check_segments(&mut book, &plans, &spec, &pairs, &stop, &mut |r| {
                    tx.send(r).is_ok()
                });
            });
        };
        #[cfg(not(target_arch = "wasm32"))]
        std::thread::Builder::new()
            .name("rattleback-verify".to_owned())
            .spawn(verify)
            .expect("spawn the verifying thread");
        #[cfg(target_arch = "wasm32")]
        verify();
        Self {
            reports,
            cancel,
            forwarded,
        }
    }

    /// Passes on a plan resolved elsewhere, or the end of the wait for them.
    pub fn forward(&self, what: Forward) {
        let _ = self.forwarded.send(what);
    }

    /// The next report if one is waiting.
    #[must_use]
    pub fn try_next(&self) -> Next {
        match self.reports.try_recv() {
            Ok(r) => Next::Report(r),
            Err(TryRecvError::Empty) => Next::Nothing,
            Err(TryRecvError::Disconnected) => Next::Ended,
        }
    }

    /// The next report, waiting for it (`None` when the thread has ended).
    #[must_use]
    pub fn next(&self) -> Option<Report> {
        self.reports.recv().ok()
    }

    /// The next report, waiting for it at most `limit`.
    #[must_use]
    pub fn next_within(&self, limit: std::time::Duration) -> Next {
        match self.reports.recv_timeout(limit) {
            Ok(r) => Next::Report(r),
            Err(mpsc::RecvTimeoutError::Timeout) => Next::Nothing,
            Err(mpsc::RecvTimeoutError::Disconnected) => Next::Ended,
        }
    }
}

impl Drop for Ahead {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

/// Verifies the segments `pairs` (`(from, until)`) of `spec` in order, sending what it finds;
/// stops when cancelled, when `send` fails, or at the first failure.
fn check_segments(
    book: &mut PlanBook,
    plans: &Receiver<Forward>,
    spec: &SessionSpec,
    pairs: &[(f64, f64)],
    cancel: &AtomicBool,
    send: &mut dyn FnMut(Report) -> bool,
) {
    let take = |book: &mut PlanBook, what: Forward| match what {
        Forward::Plan(key, plan, estimate) => book.add(key, plan, estimate),
        Forward::Release => book.awaits = false,
    };
    for &(from, until) in pairs {
        let mut asked = *spec;
        asked.t_end = until;
        // A follower waits for the lecturer's plan of this segment (bounded).
        let waited = std::time::Instant::now();
        loop {
            for what in plans.try_iter() {
                take(book, what);
            }
            if cancel.load(Ordering::Relaxed) {
                return;
            }
            if !book.awaits || book.lookup(&asked).is_some() {
                break;
            }
            if waited.elapsed().as_secs_f64() >= AWAIT_SECONDS {
                // The lecturer is gone or far behind: verify from here on.
                book.awaits = false;
                break;
            }
            match plans.recv_timeout(std::time::Duration::from_millis(20)) {
                Ok(what) => take(book, what),
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                // The worker is gone: nothing more will come.
                Err(mpsc::RecvTimeoutError::Disconnected) => book.awaits = false,
            }
        }
        let mut progress = Progress::new(until);
        let mut go_on = |t: f64| {
            if let Some((run, percent)) = progress.at(t) {
                // A closed channel is seen at the next send.
                send(Report::Progress {
                    until,
                    run,
                    percent,
                });
            }
            !cancel.load(Ordering::Relaxed)
        };
        // Every horizon here was priced within the budget before the thread started.
        let resolved = match book.lookup(&asked) {
            Some(plan) => Ok((plan, book.estimate(&asked))),
            None => spec
                .model
                .resolve(&book.request(&asked), &mut go_on)
                .map(|r| (r.plan, r.estimate)),
        };
        let (plan, estimate) = match resolved {
            Ok(r) => r,
            Err(StepError::Cancelled { .. }) => return,
            Err(error) => {
                send(Report::Failed { from, error });
                return;
            }
        };
        if !send(Report::Verified {
            from,
            until,
            plan,
            estimate,
        }) {
            return;
        }
        let mut go_on = |_t: f64| !cancel.load(Ordering::Relaxed);
        match Segment::prepare(spec, plan, from, until, book.arithmetic, &mut go_on) {
            Ok(segment) => {
                if !send(Report::Ready(Box::new(segment))) {
                    return;
                }
            }
            Err(StepError::Cancelled { .. }) => return,
            Err(error) => {
                send(Report::Failed { from, error });
                return;
            }
        }
    }
}

/// Whole percents of `auto`'s integrations over a horizon: a time below the last one starts
/// the next integration (each runs from 0).
pub(super) struct Progress {
    until: f64,
    last_t: f64,
    run: u32,
    percent: Option<u8>,
}

impl Progress {
    pub(super) fn new(until: f64) -> Self {
        Self {
            until,
            last_t: f64::INFINITY,
            run: 0,
            percent: None,
        }
    }

    /// The integration and percent to report for time `t`, when either changed.
    pub(super) fn at(&mut self, t: f64) -> Option<(u32, u8)> {
        if t < self.last_t {
            self.run += 1;
            self.percent = None;
        }
        self.last_t = t;
        let percent = (100.0 * t / self.until).clamp(0.0, 100.0) as u8;
        (self.percent != Some(percent)).then(|| {
            self.percent = Some(percent);
            (self.run, percent)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn horizons_halve_down_to_the_first_segment() {
        assert_eq!(horizons(30.0), vec![30.0]);
        assert_eq!(horizons(64.0), vec![64.0]);
        assert_eq!(horizons(100.0), vec![50.0, 100.0]);
        assert_eq!(horizons(1000.0), vec![62.5, 125.0, 250.0, 500.0, 1000.0]);
        let long = horizons(1e300);
        assert_eq!(long.len(), MOST_SEGMENTS);
        assert_eq!(long.last().map(|t| t.to_bits()), Some(1e300_f64.to_bits()));
    }
}
