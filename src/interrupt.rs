//! Signals for the headless commands (every command but the explorer, which restores its
//! terminal first: `explorer::run`). Every signal whose default action ends the process and that
//! can be caught ([`ending`]) sets a flag the long loops ask ([`requested`]): they stop at the
//! next step, frame or cell, the temporary file is removed, and the process exits `128 + n`
//! saying nothing was written. A watchdog makes that hold whatever the command is doing: when
//! the process is still there [`GRACE`] after the signal, it removes the temporary files being
//! written ([`crate::fault::pending`]), says so, and exits `128 + n` itself (issue 56: an export
//! busy in one frame's run answered SIGTERM 9–19 s late, and USR1, USR2, ALRM or XCPU left its
//! temporary file). The faults are [`crate::fault`]'s.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

static SIGNAL: std::sync::OnceLock<Arc<AtomicUsize>> = std::sync::OnceLock::new();

/// The files this command has written whole so far (`bench` writes each part's as it ends):
/// an interruption names them instead of saying nothing was written (issue 81).
static WRITTEN: std::sync::Mutex<Vec<String>> = std::sync::Mutex::new(Vec::new());

/// Notes that `path` was written whole.
pub fn wrote(path: &std::path::Path) {
    if let Ok(mut w) = WRITTEN.lock() {
        w.push(path.display().to_string());
    }
}

/// What an interruption says: nothing was written, or which files were before it.
#[must_use]
pub fn what_was_written() -> String {
    let written = WRITTEN.lock().map(|w| w.clone()).unwrap_or_default();
    if written.is_empty() {
        "interrupted: nothing was written".to_owned()
    } else {
        format!(
            "interrupted: wrote {} before; nothing more was written",
            written.join(", ")
        )
    }
}

/// The command is ending on its own (its exit is being said): the watchdog leaves it be.
static ENDING: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// How long the watchdog leaves the command to stop on its own before it ends the process.
pub const GRACE: Duration = Duration::from_millis(60);

/// Every signal whose default action ends the process and that a handler can take safely
/// (`signal-hook`'s): the faults are [`crate::fault`]'s, SIGPIPE is ignored (a closed pipe is an
/// error where it is written: `rattleback presets | head` ends quietly) and SIGABRT is a
/// program's own `abort()`; the realtime signals (SIGRTMIN to SIGRTMAX) too.
#[must_use]
pub fn ending() -> Vec<i32> {
    use signal_hook::consts::signal as s;
    let mut all = vec![
        s::SIGINT,
        s::SIGTERM,
        s::SIGHUP,
        s::SIGQUIT,
        s::SIGUSR1,
        s::SIGUSR2,
        s::SIGALRM,
        s::SIGVTALRM,
        s::SIGPROF,
        s::SIGXCPU,
        s::SIGXFSZ,
        s::SIGIO,
        libc::SIGPWR,
        libc::SIGSTKFLT,
    ];
    all.extend(libc::SIGRTMIN()..=libc::SIGRTMAX());
    all
}

/// Sets `flag` to a signal's number when it arrives, for each of `signals` the process may
/// catch, and returns those. A signal the system or a supervisor keeps for itself (`sigaction`
/// says EINVAL: under `valgrind`, the last realtime one) keeps its default action: before, every
/// command stopped there with "Invalid argument (os error 22)".
///
/// # Errors
/// When a handler cannot be registered for another reason.
pub fn register(
    signals: impl IntoIterator<Item = i32>,
    flag: &Arc<AtomicUsize>,
) -> std::io::Result<Vec<i32>> {
    let mut caught = Vec::new();
    for n in signals {
        match signal_hook::flag::register_usize(n, Arc::clone(flag), n as usize) {
            Ok(_) => caught.push(n),
            Err(e) if e.raw_os_error() == Some(libc::EINVAL) => {}
            Err(e) => return Err(e),
        }
    }
    Ok(caught)
}

/// Catches [`ending`] signals from now on, with the watchdog (once per process), which calls
/// `end` (the process's end: `Failure::end_now`) when the command has not stopped in time.
///
/// # Errors
/// When a handler cannot be registered.
pub fn install(end: fn(i32) -> !) -> std::io::Result<()> {
    static WATCHDOG: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    let flag = SIGNAL.get_or_init(|| Arc::new(AtomicUsize::new(0)));
    if WATCHDOG.get().is_some() {
        return Ok(());
    }
    let signals = register(ending(), flag)?;
    let mut arrivals = signal_hook::iterator::Signals::new(&signals)?;
    std::thread::Builder::new()
        .name("rattleback-signals".to_owned())
        .spawn(move || {
            if let Some(n) = arrivals.forever().next() {
                std::thread::sleep(GRACE);
                if ENDING.load(Ordering::SeqCst) {
                    return;
                }
                // Still here: the work did not stop in time. Nothing half-written stays.
                crate::fault::remove_pending();
                if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
                    // A progress bar's line, erased.
                    let _ = std::io::Write::write_all(&mut std::io::stderr(), b"\r\x1b[2K");
                }
                end(n);
            }
        })?;
    let _ = WATCHDOG.set(());
    Ok(())
}

/// The command is ending on its own and says so: the watchdog does not end it meanwhile.
pub fn ending_now() {
    ENDING.store(true, Ordering::SeqCst);
}

/// The signal that arrived, if one did.
#[must_use]
pub fn requested() -> Option<i32> {
    SIGNAL
        .get()
        .map(|f| f.load(Ordering::Relaxed))
        .filter(|&n| n != 0)
        .map(|n| i32::try_from(n).unwrap_or(signal_hook::consts::SIGTERM))
}

/// Whether no signal has come (an engine's [`stopping_on`](crate::sim::Engine::stopping_on)).
#[must_use]
pub fn not_requested() -> bool {
    requested().is_none()
}

/// An error for a loop that stopped because a signal arrived.
#[must_use]
pub fn error() -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::Interrupted, "interrupted by a signal")
}

#[cfg(test)]
mod tests {
    /// A signal the system refuses (here a number past the last one, which `sigaction` refuses
    /// with EINVAL as it refuses one a supervisor keeps) is left out, and the others are
    /// caught: before, the first refusal stopped every command.
    #[test]
    fn a_signal_the_system_keeps_is_left_out_not_fatal() {
        let flag = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let past_the_last = libc::SIGRTMAX() + 1;
        let caught = super::register([past_the_last, libc::SIGUSR2], &flag).unwrap();
        assert_eq!(caught, vec![libc::SIGUSR2]);
    }

    /// Issue 81: an interruption after a part was written names it (bench said "nothing was
    /// written" after writing its first CSV).
    #[test]
    fn an_interruption_names_what_was_written() {
        assert_eq!(
            super::what_was_written(),
            "interrupted: nothing was written"
        );
        super::wrote(std::path::Path::new("out/work_precision.csv"));
        assert_eq!(
            super::what_was_written(),
            "interrupted: wrote out/work_precision.csv before; nothing more was written"
        );
    }
}
