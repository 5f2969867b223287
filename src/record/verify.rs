//! `replay --verify`: re-run a session headless through the worker's own interpreter and check
//! every checkpoint bit for bit.

use super::{RecordError, Recording};
use crate::app::effects::commands;
use crate::app::journal::{Event, state_hash};
use crate::app::{App, Effect, Options};
use crate::physics::plan::AutoPolicy;
use crate::scenario::Preset;
use crate::sim::{Command, Engine, PlanBook, SimEvent, drive};

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

/// Why a session did not verify.
#[derive(Debug, thiserror::Error)]
pub enum VerifyError {
    /// A checkpoint did not reproduce.
    #[error("{}: divergence at t = {}: expected {}, got {}", .0.line, .0.t, .0.expected, .0.got)]
    Diverged(Divergence),
    /// The file itself is bad.
    #[error(transparent)]
    Record(#[from] RecordError),
}

/// How `auto` resolves in a replay of `rec`: the plans it recorded, and for format 1 files
/// (which recorded none) `auto` as it was then.
#[must_use]
pub fn plan_book(rec: &Recording) -> PlanBook {
    PlanBook {
        policy: if rec.header.version < 2 {
            AutoPolicy::Legacy
        } else {
            AutoPolicy::Verified
        },
        recorded: rec
            .lines
            .iter()
            .filter_map(|(_, l)| match &l.event {
                Event::Plan { key, plan } => Some((*key, *plan)),
                _ => None,
            })
            .collect(),
        ..PlanBook::default()
    }
}

/// Rebuilds the explorer state of a recording's start.
///
/// # Errors
/// When the inline preset is not valid.
pub fn start(rec: &Recording, path: &str) -> Result<(App, Vec<Effect>), RecordError> {
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
    Ok(App::new(&preset, Options::at(rec.header.fps)))
}

/// The commands that decide the trajectory: restarts, the overlay and checkpoints. Pacing
/// (`AdvanceTo`) and the computed panes (sweep, weak-*, map) are dropped: trajectories do not
/// depend on them.
fn trajectory(effects: Vec<Effect>) -> Vec<Command> {
    commands(effects)
        .into_iter()
        .filter(|c| {
            !matches!(
                c,
                Command::AdvanceTo { .. }
                    | Command::Sweep { .. }
                    | Command::Weak { .. }
                    | Command::Map { .. }
            )
        })
        .collect()
}

/// Checks the hash chain of a format-2 file: the first line whose chain differs is named (an
/// edited, deleted or inserted line there or just before).
fn check_chain(rec: &Recording) -> Result<(), VerifyError> {
    if rec.header.version < 2 {
        return Ok(());
    }
    let mut previous = rec.header_text.clone();
    for (number, line) in &rec.lines {
        let bare = serde_json::to_string(&super::Line {
            chain: None,
            ..line.clone()
        })
        .unwrap_or_default();
        let expected = super::chain_after(&previous, &bare);
        if line.chain.as_deref() != Some(expected.as_str()) {
            return Err(VerifyError::Diverged(Divergence {
                line: *number,
                t: line.t,
                expected: format!("hash chain {expected}"),
                got: format!(
                    "{} (this line, or the one before it, was edited, deleted or inserted)",
                    line.chain.as_deref().unwrap_or("no chain")
                ),
            }));
        }
        previous = expected;
    }
    Ok(())
}

/// Re-runs `rec` and compares every checkpoint. `Ok(n)`: all `n` checkpoints reproduced.
///
/// # Errors
/// A bad header preset, or the first divergence.
pub fn verify(rec: &Recording, path: &str) -> Result<usize, VerifyError> {
    check_chain(rec)?;
    let (mut app, effects) = start(rec, path)?;
    let mut engine = Engine::new(plan_book(rec));
    drive(&mut engine, trajectory(effects), &mut |_| {});
    let mut checked = 0;
    for (number, line) in &rec.lines {
        if let Event::Checkpoint {
            state,
            reversals,
            hash,
        } = &line.event
        {
            let mut got = None;
            drive(
                &mut engine,
                vec![Command::Checkpoint {
                    generation: app.run.generation,
                    t: line.t,
                }],
                &mut |e| {
                    if let SimEvent::Checkpoint {
                        t,
                        state,
                        reversals,
                        ..
                    } = e
                    {
                        got = Some((t, state, reversals));
                    }
                },
            );
            let (got_t, got_state, got_rev) =
                got.unwrap_or_else(|| (line.t, vec![f64::NAN; state.len()], usize::MAX));
            let got_hash = state_hash(got_t, &got_state, got_rev);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            if got_hash != *hash || bits(&got_state) != bits(state) || got_rev != *reversals {
                return Err(VerifyError::Diverged(Divergence {
                    line: *number,
                    t: line.t,
                    expected: format!("state {state:?}, {reversals} reversals, hash {hash}"),
                    got: format!("state {got_state:?}, {got_rev} reversals, hash {got_hash}"),
                }));
            }
            checked += 1;
        } else {
            let effects = app.apply_event(&line.event);
            drive(&mut engine, trajectory(effects), &mut |_| {});
        }
    }
    Ok(checked)
}
