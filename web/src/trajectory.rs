//! One run as `simulate --format csv` writes it, from a preset's text: what the bit-for-bit
//! check (issue 82) computes natively (`web/examples/trajectories.rs`) and in the module
//! (`rb_trajectory`), and compares character by character. Every number of the CSV is written
//! so that it reads back to the same bits, so equal text is equal trajectories.

use rattleback::scenario::Preset;
use rattleback::simulate::{Format, Request, resolve, simulate};

/// Longest preset text taken (a shipped preset is under 2 kB).
pub const MAX_TOML: usize = 64 * 1024;

/// Most samples asked.
pub const MAX_SAMPLES: u32 = 10_000;

/// The CSV of `toml`'s run (its own method, tolerance and horizon) at `samples` samples, or
/// `error: …` when the preset is refused or the run fails (the same refusal on both sides is
/// the same answer).
#[must_use]
pub fn csv(toml: &str, samples: u32) -> String {
    if toml.len() > MAX_TOML {
        return format!("error: a preset of over {MAX_TOML} bytes");
    }
    let preset = match Preset::parse(toml, "case", "case", &[]) {
        Ok(p) => p,
        Err(e) => return format!("error: {e}"),
    };
    let request = Request {
        method: None,
        tolerance: None,
        step: None,
        t_end: None,
        format: Format::Csv,
        samples: samples.clamp(2, MAX_SAMPLES),
        force: false,
    };
    match simulate(&preset, &resolve(&preset, &request), Format::Csv) {
        Ok(text) => text,
        Err(e) => format!("error: {e}"),
    }
}
