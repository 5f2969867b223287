//! The command layer's one error: why a command stopped, and so how the process ends.
//!
//! Every command (`main.rs`, `commands/`) returns an [`Outcome`]; `main` makes the one exit
//! decision with [`Failure::exit`]: it prints the lines (`rattleback: error: …`, control
//! characters stripped: the text can come from files) and gives the exit status the manual
//! lists (`manual::EXIT_STATUS`): 0 done, 1 a run, a write or a verification failed, 2 the
//! input is wrong, `128 + n` interrupted by signal `n`. The layers below have their own
//! error types (`PresetError`, `StepError`, `VerifyError`, …); this one only says how they end
//! the process.

use std::fmt::Display;
use std::process::ExitCode;

/// What a command gives `main`.
pub type Outcome = Result<(), Failure>;

/// Why a command stopped.
#[derive(Clone, Debug, PartialEq, Eq)]
#[must_use]
pub struct Failure {
    /// The exit status.
    code: u8,
    /// What is printed on standard error, one `rattleback: error: ` line each.
    lines: Vec<String>,
}

impl Failure {
    /// The input is wrong (a flag, a file, a value): exit 2.
    pub fn input(message: impl Display) -> Self {
        // Several problems in one message (a preset's, issue 68) are several lines, each
        // bounded alone, as `check` says them.
        Self::inputs(message.to_string().lines())
    }

    /// Several things are wrong with the input, each said on its own line: exit 2.
    pub fn inputs<M: Display>(messages: impl IntoIterator<Item = M>) -> Self {
        Self {
            code: 2,
            lines: messages.into_iter().map(|m| m.to_string()).collect(),
        }
    }

    /// A run, a write or a check failed on good input: exit 1.
    pub fn failed(message: impl Display) -> Self {
        Self {
            code: 1,
            lines: vec![message.to_string()],
        }
    }

    /// The command has said what went wrong itself (a report, a JSON object on standard
    /// output): exit with `code`, print nothing more.
    pub fn said(code: u8) -> Self {
        Self {
            code,
            lines: Vec::new(),
        }
    }

    /// Ended by signal `n` (the terminal restored, nothing to add): `128 + n`, as shells
    /// report it.
    pub fn signalled(n: i32) -> Self {
        Self::said(u8::try_from(128 + n).unwrap_or(1))
    }

    /// Interrupted by signal `n`: `128 + n`, saying that nothing was written, or which files
    /// were before the signal ([`crate::interrupt::wrote`]).
    pub fn interrupted(n: i32) -> Self {
        Self::signalled(n).saying(crate::interrupt::what_was_written())
    }

    /// The same end, saying `line` too.
    pub fn saying(mut self, line: impl Display) -> Self {
        self.lines.push(line.to_string());
        self
    }

    /// The exit status.
    #[must_use]
    pub fn code(&self) -> u8 {
        self.code
    }

    /// Says the lines and ends the process now with the status: only for a signal the command
    /// did not answer within the grace of its watchdog (`interrupt`; the temporary files
    /// removed first). Every other end goes through `main`'s [`exit`].
    pub fn end_now(self) -> ! {
        for line in self.shown() {
            crate::scenario::text::warn(&format!("rattleback: error: {line}"));
        }
        std::process::exit(i32::from(self.code))
    }

    /// Prints the lines on standard error and ends with the status: the one exit decision.
    #[must_use]
    pub fn exit(self) -> ExitCode {
        for line in self.shown() {
            crate::scenario::text::warn(&format!("rattleback: error: {line}"));
        }
        ExitCode::from(self.code)
    }

    /// The lines as said: at most a few dozen, each cut to a sane length, and a count of the
    /// rest (`scenario::text::bounded` a config of a hundred thousand bad keys is not a 12 MB error,
    /// issue 56).
    #[must_use]
    pub fn shown(&self) -> Vec<String> {
        crate::scenario::text::bounded(&self.lines)
    }
}

/// The exit status of a command's outcome: the one exit decision. A failed write on standard
/// output decides first (a closed pipe is success: the reader had what it wanted).
#[must_use]
pub fn exit(outcome: Outcome) -> ExitCode {
    stdout_failure()
        .unwrap_or(outcome)
        .map_or_else(Failure::exit, |()| ExitCode::SUCCESS)
}

/// Prints cleaned text on stdout. A reader that went away (`| head`) ends the command quietly
/// with success, as `simulate`'s streamed output does; any other write error ends it with one
/// line and exit 1. The first failed write is kept (later ones are skipped) for `main`'s exit
/// decision ([`exit`] asks [`stdout_failure`]).
pub fn say_raw(text: &str) {
    use std::io::Write as _;
    if STDOUT_FAILED.get().is_some() {
        return;
    }
    let text = crate::scenario::text::shown(text);
    if let Err(e) = std::io::stdout().lock().write_all(text.as_bytes()) {
        let _ = STDOUT_FAILED.set((e.kind(), e.to_string()));
    }
}

/// The first failed write on stdout through [`say_raw`].
static STDOUT_FAILED: std::sync::OnceLock<(std::io::ErrorKind, String)> =
    std::sync::OnceLock::new();

/// How a failed write on stdout ends the command, if one failed: a closed pipe ends it with
/// success and nothing said; any other error with exit 1.
#[must_use]
pub fn stdout_failure() -> Option<Outcome> {
    STDOUT_FAILED.get().map(|(kind, e)| match kind {
        std::io::ErrorKind::BrokenPipe => Ok(()),
        _ => Err(Failure::failed(format!("writing to standard output: {e}"))),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_ends_with_its_status() {
        assert_eq!(Failure::input("x").code(), 2);
        assert_eq!(Failure::inputs(["a", "b"]).lines.len(), 2);
        assert_eq!(Failure::failed("x").code(), 1);
        assert_eq!(Failure::said(1).lines.len(), 0);
        assert_eq!(Failure::interrupted(2).code(), 130);
        assert_eq!(Failure::interrupted(15).code(), 143);
        assert!(Failure::signalled(1).lines.is_empty());
    }
}
