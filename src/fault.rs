//! The faults: SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGTRAP and SIGSYS, whether the program caused
//! them or `kill` sent them. Their handler puts the terminal back (when the explorer has it in
//! raw mode on the alternate screen), removes the temporary files being written, lets Rust's
//! own handler say "stack overflow" where it has one to say, then ends the process by the same
//! signal with its default action (so the shell sees `128 + n`, and a core is dumped where the
//! system dumps them). Before (issue 56) SIGSEGV and SIGBUS sent by `kill` were swallowed by
//! Rust's handler and the explorer ran on; the others left the terminal raw.
//!
//! This is the one module with `unsafe` code (`Cargo.toml` denies it elsewhere, a test checks
//! that no other file has any): `signal-hook` refuses SIGSEGV, SIGILL and SIGFPE, and no safe
//! interface installs a handler for them. Everything the handler does is async-signal-safe:
//! atomic loads, `write(2)`, `tcsetattr(3)`, `unlink(2)`, `signal(2)`, `raise(3)`, and a call to
//! the handler it replaced.
#![allow(unsafe_code)]

use std::ffi::CString;
use std::path::Path;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicPtr, AtomicUsize, Ordering};

/// The fault signals.
pub const FAULTS: [i32; 6] = [
    libc::SIGSEGV,
    libc::SIGBUS,
    libc::SIGILL,
    libc::SIGFPE,
    libc::SIGTRAP,
    libc::SIGSYS,
];

/// What puts a terminal back from any state the explorer leaves it in: the end of a
/// synchronized update, mouse reports off, the main screen, the cursor shown, colours reset.
const RESTORE: &[u8] =
    b"\x1b[?2026l\x1b[?1000l\x1b[?1002l\x1b[?1003l\x1b[?1006l\x1b[0m\x1b[?1049l\x1b[?25h\r\n";

/// How many temporary files can be pending at once (a command writes one or two).
const SLOTS: usize = 16;

/// The temporary files being written, as C strings leaked on purpose: the handler may read a
/// pointer after a slot is cleared, so what it points to is never freed.
static PENDING: [AtomicPtr<libc::c_char>; SLOTS] =
    [const { AtomicPtr::new(std::ptr::null_mut()) }; SLOTS];

/// Whether the explorer has the terminal (raw mode, the alternate screen).
static ARMED: AtomicBool = AtomicBool::new(false);

/// The terminal's settings before raw mode, and its descriptor.
static COOKED: OnceLock<(i32, libc::termios)> = OnceLock::new();

/// The handlers the faults had before (Rust's, for SIGSEGV and SIGBUS: its stack-overflow
/// message), by index in [`FAULTS`]; 0 when there was none to call.
static PREVIOUS: [AtomicUsize; 6] = [const { AtomicUsize::new(0) }; 6];
/// Whether the previous handler takes `siginfo` (`SA_SIGINFO`), by index in [`FAULTS`].
static PREVIOUS_INFO: [AtomicBool; 6] = [const { AtomicBool::new(false) }; 6];

/// Installs the handler for every fault (once; later calls do nothing). Failures are ignored:
/// the faults then keep their default action.
pub fn install() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        for (i, &signal) in FAULTS.iter().enumerate() {
            // SAFETY: `sigaction` with a zeroed struct (a valid `sigaction`: no handler, empty
            // mask, no flags) to read the old one, then our handler, which only does
            // async-signal-safe work (see the module's documentation). SA_ONSTACK: a stack
            // overflow is handled on the alternate stack Rust gives each thread.
            unsafe {
                let mut old: libc::sigaction = std::mem::zeroed();
                let mut new: libc::sigaction = std::mem::zeroed();
                new.sa_sigaction = on_fault as *const () as usize;
                new.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK;
                libc::sigemptyset(&raw mut new.sa_mask);
                if libc::sigaction(signal, &raw const new, &raw mut old) != 0 {
                    continue;
                }
                if old.sa_sigaction != libc::SIG_DFL && old.sa_sigaction != libc::SIG_IGN {
                    PREVIOUS[i].store(old.sa_sigaction, Ordering::SeqCst);
                    PREVIOUS_INFO[i].store(old.sa_flags & libc::SA_SIGINFO != 0, Ordering::SeqCst);
                }
            }
        }
    });
}

/// The explorer takes the terminal (before raw mode): a fault puts back the settings read now
/// from standard input's terminal.
pub fn arm() {
    if COOKED.get().is_none() {
        // SAFETY: `tcgetattr` fills a zeroed `termios` (plain data) for descriptor 0; on
        // failure nothing is kept.
        let mut t: libc::termios = unsafe { std::mem::zeroed() };
        if unsafe { libc::tcgetattr(0, &raw mut t) } == 0 {
            let _ = COOKED.set((0, t));
        }
    }
    ARMED.store(true, Ordering::SeqCst);
}

/// The explorer has put the terminal back.
pub fn disarm() {
    ARMED.store(false, Ordering::SeqCst);
}

/// A temporary file being written: a fault removes it. Dropping the mark forgets it.
#[derive(Debug)]
pub struct Pending(Option<usize>);

/// Marks `path` as a temporary file being written (unmarked when the mark drops: once the file
/// is moved into place, or removed). `None` when every slot is taken (the file is still
/// removed on every other path; only a fault would leave it).
#[must_use]
pub fn pending(path: &Path) -> Pending {
    use std::os::unix::ffi::OsStrExt as _;
    let Ok(c) = CString::new(path.as_os_str().as_bytes()) else {
        return Pending(None);
    };
    let raw = c.into_raw();
    for (i, slot) in PENDING.iter().enumerate() {
        if slot
            .compare_exchange(
                std::ptr::null_mut(),
                raw,
                Ordering::SeqCst,
                Ordering::SeqCst,
            )
            .is_ok()
        {
            return Pending(Some(i));
        }
    }
    // SAFETY: `raw` came from `CString::into_raw` just above and was stored nowhere.
    drop(unsafe { CString::from_raw(raw) });
    Pending(None)
}

impl Drop for Pending {
    fn drop(&mut self) {
        // The string is leaked: a handler may still be reading it.
        if let Some(i) = self.0 {
            PENDING[i].store(std::ptr::null_mut(), Ordering::SeqCst);
        }
    }
}

/// Removes the temporary files being written (a signal's watchdog, before it ends the process),
/// then the folders this run made for them when they are left empty ([`made_folder`]; `rmdir`
/// removes only an empty one).
pub fn remove_pending() {
    for slot in &PENDING {
        let p = slot.load(Ordering::SeqCst);
        if !p.is_null() {
            // SAFETY: a pointer stored by `pending`, from a C string never freed. A folder is
            // not unlinked (EISDIR).
            unsafe {
                libc::unlink(p);
            }
        }
    }
    for slot in &PENDING {
        let p = slot.swap(std::ptr::null_mut(), Ordering::SeqCst);
        if !p.is_null() {
            // SAFETY: as above; a file already unlinked fails here harmlessly.
            unsafe {
                libc::rmdir(p);
            }
        }
    }
}

/// A folder this run made for its output (`bench`'s, a study's `--out`): removed when the run
/// ends, however it ends, if it is still empty (issue 81, D-12: an interrupted `bench` said
/// nothing was written and left an empty folder). A folder that was there before is left alone.
#[derive(Debug)]
pub struct MadeFolder {
    path: Option<std::path::PathBuf>,
    _mark: Option<Pending>,
}

/// Makes `path` and its parents (as `create_dir_all`), marked as [`MadeFolder`] when it was not
/// there.
///
/// # Errors
/// What `create_dir_all` says.
pub fn made_folder(path: &Path) -> std::io::Result<MadeFolder> {
    if path.exists() {
        std::fs::create_dir_all(path)?;
        return Ok(MadeFolder {
            path: None,
            _mark: None,
        });
    }
    std::fs::create_dir_all(path)?;
    Ok(MadeFolder {
        path: Some(path.to_path_buf()),
        _mark: Some(pending(path)),
    })
}

impl Drop for MadeFolder {
    fn drop(&mut self) {
        if let Some(p) = &self.path {
            // Only an empty folder goes.
            let _ = std::fs::remove_dir(p);
        }
    }
}

/// The handler: the terminal back, the temporary files removed, Rust's handler asked, then the
/// process ends by the signal.
extern "C" fn on_fault(
    signal: libc::c_int,
    info: *mut libc::siginfo_t,
    context: *mut libc::c_void,
) {
    // SAFETY: async-signal-safe calls only, on data that is valid for the whole process (see
    // the statics above); the previous handler is called as it was installed to be called.
    unsafe {
        if ARMED.swap(false, Ordering::SeqCst) {
            libc::write(1, RESTORE.as_ptr().cast(), RESTORE.len());
            if let Some((fd, cooked)) = COOKED.get() {
                libc::tcsetattr(*fd, libc::TCSANOW, cooked);
            }
        }
        remove_pending();
        if let Some(i) = FAULTS.iter().position(|&f| f == signal) {
            let previous = PREVIOUS[i].load(Ordering::SeqCst);
            if previous != 0 {
                if PREVIOUS_INFO[i].load(Ordering::SeqCst) {
                    let f: extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) =
                        std::mem::transmute(previous);
                    f(signal, info, context);
                } else {
                    let f: extern "C" fn(libc::c_int) = std::mem::transmute(previous);
                    f(signal);
                }
            }
        }
        // Ends by the signal: blocked while this handler runs, it is delivered with its
        // default action when the handler returns (a real fault would also recur).
        libc::signal(signal, libc::SIG_DFL);
        libc::raise(signal);
    }
}
