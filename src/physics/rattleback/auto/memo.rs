//! The probes' answers, and the start's condition numbers read at its conditioning stiffness,
//! kept for the life of the process.
//!
//! A probe's gaps (the resolved full model against `averaged3` and `averaged2` over `[0, T]`) depend
//! only on the probe problem (the body at the probe stiffness and the start of the averaging's
//! family, [`super::probe_problem`]) and on `T`: not on the `k` that asked for it. Where the
//! start's tilt is zero (every shipped preset) or scales with the family, the probes of one body
//! and start are the same problems at every `k`, so `auto` at another `k` (the explorer's `k`
//! slider, a sweep's rungs, a stiffness table) reads them here instead of running them again.
//!
//! The start's condition numbers are kept likewise: above [`super::conditioning_stiffness`],
//! `auto` may bound them by their reading at that one stiffness (the start of the same family,
//! [`super::probe_problem`]), whatever the `k` that asked, kept under [`conditioning_key`].
//!
//! The answer read is the answer that would be computed, bit for bit, so nothing `auto` returns
//! depends on what was kept: its budget counts the probes' predicted cost either way. A
//! cancelled probe is not kept. At most [`CAPACITY`] answers are kept, the oldest forgotten
//! first.

use std::sync::Mutex;

use super::super::params::Problem;

/// How many answers (probes and condition numbers) are kept.
pub const CAPACITY: usize = 256;

/// What is kept (a probe's gaps, or condition numbers), the problem and the horizon, as the bits
/// of their numbers.
type Key = [u64; 10];

/// A probe's gaps: the full model against `averaged3`, and against `averaged2`; or a start's
/// condition numbers, rate and angle.
pub type Gaps = [f64; 2];

/// What a key's answer is.
#[derive(Clone, Copy)]
enum Kind {
    /// A probe's gaps.
    Probe = 1,
    /// A start's condition numbers on the slow model.
    Conditioning = 2,
}

struct Entry {
    key: Key,
    gaps: Gaps,
    reads: u64,
}

static KEPT: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// The key of the probe problem `probe` over `[0, t_end]`.
#[must_use]
pub fn key(probe: &Problem, t_end: f64) -> Key {
    key_of(Kind::Probe, probe, t_end)
}

/// The key of the condition numbers of `problem` (a start at its conditioning stiffness) over
/// `[0, t_end]`.
#[must_use]
pub fn conditioning_key(problem: &Problem, t_end: f64) -> Key {
    key_of(Kind::Conditioning, problem, t_end)
}

fn key_of(kind: Kind, problem: &Problem, t_end: f64) -> Key {
    let (p, s) = (problem.params(), problem.start());
    let numbers = [
        p.ix,
        p.iy,
        p.iz,
        p.k,
        s.gamma,
        s.alpha,
        s.gamma_dot,
        s.alpha_dot,
        t_end,
    ];
    let mut key = [kind as u64; 10];
    for (slot, x) in key[1..].iter_mut().zip(numbers) {
        *slot = x.to_bits();
    }
    key
}

fn kept() -> std::sync::MutexGuard<'static, Vec<Entry>> {
    // A panic elsewhere while holding the lock leaves whole entries: the list stays usable.
    KEPT.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// The kept answer of `key`, if any (counting the read).
#[must_use]
pub fn read(key: &Key) -> Option<Gaps> {
    let mut list = kept();
    let entry = list.iter_mut().find(|e| e.key == *key)?;
    entry.reads += 1;
    Some(entry.gaps)
}

/// Keeps `gaps` (or condition numbers) as the answer of `key`.
pub fn keep(key: Key, gaps: Gaps) {
    let mut list = kept();
    if list.iter().any(|e| e.key == key) {
        return;
    }
    if list.len() == CAPACITY {
        list.remove(0);
    }
    list.push(Entry {
        key,
        gaps,
        reads: 0,
    });
}

/// How many times the answer of `key` was read instead of computed (`None`: not kept).
#[must_use]
pub fn reads(key: &Key) -> Option<u64> {
    kept().iter().find(|e| e.key == *key).map(|e| e.reads)
}

/// Forgets every answer (the benchmark's cold runs; results never depend on it).
pub fn clear() {
    kept().clear();
}
