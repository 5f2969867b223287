//! Two independent computations, side by side where the program allows it.
//!
//! `auto` verifies a run with computations that do not depend on it (its coarser companion, the
//! start's condition numbers, the averaged model's two probes). One core runs them one after
//! the other; a second core can run them while the run itself goes on, so that a verified
//! answer takes about the wall time of its longest part (issue 27).
//!
//! This layer has no threads (docs/architecture.md): it only says which computations are
//! independent, through [`both`]. How they run is the program's choice, installed once with
//! [`install`] (the binary installs a thread pool: `crate::parallel`); without one, and on a
//! thread that asked for [`sequentially`], they run one after the other on the calling thread.
//! Either way each computation is the same pure function of its inputs, so the results are the
//! same, bit for bit: only the time differs.

use std::cell::Cell;
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

pub use super::flow::GoOn;

/// The computation [`Fork::join`] may hand to another thread: it owns what it needs.
pub type Job = Box<dyn FnOnce(GoOn<'_>) + Send + 'static>;

/// How two independent computations are run: `here` on the calling thread, `there` wherever
/// the implementation likes, both done on return. `go_on` is the caller's: while either runs,
/// the caller's answer must reach both (a cancellation stops both). A panic in either reaches
/// the caller.
pub trait Fork: Sync {
    /// Runs `here` and `there`, each exactly once.
    fn join(&self, go_on: GoOn<'_>, here: &mut dyn FnMut(GoOn<'_>), there: Job);
}

static INSTALLED: OnceLock<&'static dyn Fork> = OnceLock::new();

thread_local! {
    static ONE_AFTER_THE_OTHER: Cell<bool> = const { Cell::new(false) };
}

/// Installs how [`both`] runs its computations, for the life of the process (the first
/// installation stays; later ones are ignored and return `false`).
pub fn install(fork: &'static dyn Fork) -> bool {
    INSTALLED.set(fork).is_ok()
}

/// Whether a [`Fork`] is installed.
#[must_use]
pub fn installed() -> bool {
    INSTALLED.get().is_some()
}

/// Runs `work` with every [`both`] it reaches on this thread one after the other (what one
/// core costs: the benchmark's `one core` column, and the tests that compare the two ways).
pub fn sequentially<R>(work: impl FnOnce() -> R) -> R {
    let _restore = Restore(ONE_AFTER_THE_OTHER.with(|c| c.replace(true)));
    work()
}

/// [`sequentially`]'s setting as it was, restored on return and on unwinding alike.
struct Restore(bool);

impl Drop for Restore {
    fn drop(&mut self) {
        ONE_AFTER_THE_OTHER.with(|c| c.set(self.0));
    }
}

/// Runs the independent computations `here` and `there` (on two cores where a [`Fork`] is
/// installed and this thread did not ask for [`sequentially`]; else `here`, then `there`) and
/// returns both results. `there` owns what it needs: it may run on another thread.
pub fn both<A, B: Send + 'static>(
    go_on: GoOn<'_>,
    here: impl FnOnce(GoOn<'_>) -> A,
    there: impl FnOnce(GoOn<'_>) -> B + Send + 'static,
) -> (A, B) {
    let fork = INSTALLED
        .get()
        .filter(|_| !ONE_AFTER_THE_OTHER.with(Cell::get));
    let Some(fork) = fork else {
        let a = here(&mut *go_on);
        let b = there(go_on);
        return (a, b);
    };
    let mut a = None;
    let mut here = Some(here);
    let b = Arc::new(Mutex::new(None));
    let slot = Arc::clone(&b);
    fork.join(
        go_on,
        &mut |g| {
            if let Some(f) = here.take() {
                a = Some(f(g));
            }
        },
        Box::new(move |g| {
            let value = there(g);
            *slot.lock().unwrap_or_else(PoisonError::into_inner) = Some(value);
        }),
    );
    let b = b.lock().unwrap_or_else(PoisonError::into_inner).take();
    match (a, b) {
        (Some(a), Some(b)) => (a, b),
        _ => unreachable!("a Fork runs both computations"),
    }
}

/// [`both`] for two computations of predicted costs `a_cost` and `b_cost`: the dearer one runs
/// on the calling thread and the cheaper one is offered, since an offered computation starts
/// late (a sleeping pool thread wakes in tens of microseconds, as long as a short run takes).
/// The results come back in the order given.
pub fn dearer_here<A: Send + 'static, B: Send + 'static>(
    go_on: GoOn<'_>,
    (a, a_cost): (impl FnOnce(GoOn<'_>) -> A + Send + 'static, f64),
    (b, b_cost): (impl FnOnce(GoOn<'_>) -> B + Send + 'static, f64),
) -> (A, B) {
    if a_cost >= b_cost {
        both(go_on, a, b)
    } else {
        let (b, a) = both(go_on, b, a);
        (a, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_a_fork_both_run_in_order_with_the_callers_go_on() {
        let order = Arc::new(Mutex::new(Vec::new()));
        let mut asked = 0;
        let (a, b) = both(
            &mut |_| {
                asked += 1;
                false
            },
            |go_on| {
                order.lock().unwrap().push("here");
                go_on(0.0)
            },
            {
                let order = Arc::clone(&order);
                move |go_on: GoOn<'_>| {
                    order.lock().unwrap().push("there");
                    go_on(1.0)
                }
            },
        );
        assert_eq!((a, b), (false, false));
        assert_eq!(asked, 2);
        assert_eq!(*order.lock().unwrap(), ["here", "there"]);
    }

    #[test]
    fn sequentially_restores_the_setting_after_a_panic() {
        let caught = std::panic::catch_unwind(|| sequentially(|| panic!("inside")));
        assert!(caught.is_err());
        assert!(!ONE_AFTER_THE_OTHER.with(Cell::get));
        sequentially(|| assert!(ONE_AFTER_THE_OTHER.with(Cell::get)));
    }
}
