//! `rattleback man`: the manual page.

use crate::commands::failure::{Failure, Outcome};

use super::write_stdout;

/// `rattleback man`.
pub fn man() -> Outcome {
    let cmd = crate::commands::cli::command();
    let mut out = Vec::new();
    if let Err(e) = crate::commands::manual::render(cmd, &mut out) {
        return Err(Failure::failed(format!("rendering the manual: {e}")));
    }
    write_stdout(&out)
}
