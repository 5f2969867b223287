//! The binary's [`Fork`]: `auto`'s independent computations on a second core (issue 27).
//!
//! [`both`](crate::physics::fork::both) hands over two computations: `here` runs on the calling
//! thread, `there` is offered to rayon's pool. Whichever thread takes `there` first runs it: a
//! pool thread while `here` runs, or the calling thread itself once `here` is done and no pool
//! thread has started it (a busy pool, a map being computed, never makes the caller wait). While
//! a pool thread runs it, the caller's `go_on` still decides: the calling thread asks it every
//! few milliseconds while it waits, and a stop reaches the pool thread through a flag it asks
//! instead. A panic there is caught and resumed on the caller.
//!
//! A pool thread that has gone to sleep takes 17–45 µs to start the offered half (median, over
//! runs; `cargo run --release --example fork_latency`), so the dearer
//! half stays on the caller ([`fork::dearer_here`](crate::physics::fork::dearer_here)). Inside
//! the pool (a sweep's or a map's cells, already one per core) or on one core, the two run one
//! after the other. A fresh `std::thread` per join was tried instead: it starts in about 7 µs,
//! but `fork::both` of two empty jobs then cost the caller 26–35 µs (0.4–1.1 µs through the
//! pool), and `auto` on start A at k = 1e8 took 0.150–0.157 ms against 0.129.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError, mpsc};
use std::time::Duration;

use crate::physics::fork::{Fork, GoOn, Job};

/// How often a caller waiting for the pool's half asks its `go_on`.
const POLL: Duration = Duration::from_millis(5);

/// rayon's global pool as a [`Fork`].
pub struct Pool {
    /// How many `there`s a pool thread ran (the tests' proof that the two ways were compared).
    elsewhere: AtomicU64,
}

static POOL: Pool = Pool {
    elsewhere: AtomicU64::new(0),
};

/// Installs the pool as `auto`'s [`Fork`] (once per process; later calls do nothing).
pub fn install() {
    crate::physics::fork::install(&POOL);
}

/// How many computations a pool thread took so far, in this process.
#[must_use]
pub fn ran_elsewhere() -> u64 {
    POOL.elsewhere.load(Ordering::Relaxed)
}

/// What the caller and the pool thread share.
struct Offer {
    job: Mutex<Option<Job>>,
    stop: AtomicBool,
}

impl Offer {
    fn take(&self) -> Option<Job> {
        self.job
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take()
    }
}

type Ended = std::thread::Result<()>;

impl Fork for Pool {
    fn join(&self, go_on: GoOn<'_>, here: &mut dyn FnMut(GoOn<'_>), there: Job) {
        if rayon::current_thread_index().is_some() || rayon::current_num_threads() < 2 {
            here(&mut *go_on);
            there(go_on);
            return;
        }
        let offer = Arc::new(Offer {
            job: Mutex::new(Some(there)),
            stop: AtomicBool::new(false),
        });
        let (done, finished) = mpsc::channel::<Ended>();
        {
            let offer = Arc::clone(&offer);
            rayon::spawn(move || {
                if let Some(job) = offer.take() {
                    POOL.elsewhere.fetch_add(1, Ordering::Relaxed);
                    let stop = &offer.stop;
                    let ended = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        job(&mut |_| !stop.load(Ordering::Relaxed));
                    }));
                    let _ = done.send(ended);
                }
            });
        }
        let mut last = 0.0;
        here(&mut |t| {
            last = t;
            let go = go_on(t);
            if !go {
                offer.stop.store(true, Ordering::Relaxed);
            }
            go
        });
        if let Some(job) = offer.take() {
            // The other thread has not started it: run it here.
            job(go_on);
            return;
        }
        loop {
            match finished.recv_timeout(POLL) {
                Ok(Ok(())) => return,
                Ok(Err(panic)) => std::panic::resume_unwind(panic),
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    unreachable!("the thread that took the job sends how it ended")
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    if !go_on(last) {
                        offer.stop.store(true, Ordering::Relaxed);
                    }
                }
            }
        }
    }
}
