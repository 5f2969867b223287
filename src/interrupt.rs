//! Ctrl-C, SIGTERM and SIGHUP for the headless commands that write a file: instead of dying
//! with a half-written temporary file beside the output, they stop at the next frame or step,
//! the temporary file is removed, and the process exits `128 + n`. Installed by the command
//! (`install`), asked by the long loops (`requested`).

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

static SIGNAL: std::sync::OnceLock<Arc<AtomicUsize>> = std::sync::OnceLock::new();

/// The signals that interrupt a headless command.
pub const SIGNALS: [i32; 3] = [
    signal_hook::consts::SIGINT,
    signal_hook::consts::SIGTERM,
    signal_hook::consts::SIGHUP,
];

/// Catches [`SIGNALS`] from now on (their default action would leave temporary files).
///
/// # Errors
/// When a handler cannot be registered.
pub fn install() -> std::io::Result<()> {
    let flag = SIGNAL.get_or_init(|| Arc::new(AtomicUsize::new(0)));
    for n in SIGNALS {
        signal_hook::flag::register_usize(n, Arc::clone(flag), n as usize)?;
    }
    Ok(())
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

/// An error for a loop that stopped because a signal arrived.
#[must_use]
pub fn error() -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::Interrupted, "interrupted by a signal")
}
