//! `replay --verify`: re-run a session headless and check every checkpoint bit for bit.

use super::{RecordError, Recording};
use crate::app::journal::{Event, state_hash};
use crate::app::{App, Options};
use crate::scenario::Preset;
use crate::sim::{Command, Session};

/// The first checkpoint that did not reproduce.
#[derive(Clone, Debug, PartialEq)]
pub struct Divergence {
    /// 1-based line of the checkpoint in the file.
    pub line: usize,
    /// Its simulated time.
    pub t: f64,
    /// What the file says.
    pub expected: String,
    /// What this build computes.
    pub got: String,
}

/// Rebuilds the explorer state of a recording's start.
///
/// # Errors
/// When the inline preset is not valid.
pub fn start(rec: &Recording, path: &str) -> Result<(App, Vec<Command>), RecordError> {
    let preset = Preset::parse(
        &rec.header.preset,
        &format!("{path} (header preset)"),
        "recorded",
        &[],
    )
    .map_err(|e| RecordError::Corrupt {
        path: path.to_owned(),
        line: 1,
        message: e.to_string(),
    })?;
    Ok(App::new(
        &preset,
        Options {
            fps: rec.header.fps,
        },
    ))
}

/// Re-runs `rec` and compares every checkpoint. `Ok(n)`: all `n` checkpoints reproduced.
///
/// # Errors
/// A bad header preset (`Err(Err)`), or the first divergence (`Err(Ok)`).
pub fn verify(rec: &Recording, path: &str) -> Result<usize, Result<Divergence, RecordError>> {
    let (mut app, commands) = start(rec, path).map_err(Err)?;
    let mut session = None;
    let feed = |commands: Vec<Command>, session: &mut Option<Session>| {
        for c in commands {
            if let Command::Restart { generation, spec } = c {
                *session = Some(Session::new(generation, spec));
            }
        }
    };
    feed(commands, &mut session);
    let mut checked = 0;
    for (number, line) in &rec.lines {
        if let Event::Checkpoint {
            state,
            reversals,
            hash,
        } = &line.event
        {
            let Some(s) = session.as_mut() else { continue };
            s.advance(line.t, 1.0, usize::MAX);
            let got = s.checkpoint(line.t);
            let (got_state, got_rev) = got.unwrap_or(([f64::NAN; 4], usize::MAX));
            let got_hash = state_hash(line.t, &got_state, got_rev);
            if got_hash != *hash
                || got_state.map(f64::to_bits) != state.map(f64::to_bits)
                || got_rev != *reversals
            {
                return Err(Ok(Divergence {
                    line: *number,
                    t: line.t,
                    expected: format!("state {state:?}, {reversals} reversals, hash {hash}"),
                    got: format!("state {got_state:?}, {got_rev} reversals, hash {got_hash}"),
                }));
            }
            checked += 1;
        } else {
            let commands = app.apply_event(&line.event);
            feed(commands, &mut session);
        }
    }
    Ok(checked)
}
