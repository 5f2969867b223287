//! `replay --verify`: re-run a session headless through the worker's own interpreter and check
//! every checkpoint bit for bit.

use super::sign::PublicKey;
use super::{RecordError, Recording};
use crate::app::effects::commands;
use crate::app::journal::{Event, state_hash};
use crate::app::{App, Effect, Options};
use crate::physics::method::Arithmetic;
use crate::physics::plan::AutoRules;
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
    /// A checkpoint or a screen did not reproduce, or a line fails the file's integrity check.
    #[error("{}: divergence at t = {}: expected {}, got {}", .0.line, .0.t, .0.expected, .0.got)]
    Diverged(Divergence),
    /// Everything there is checks, but the file has no end line: it was cut short (a crash, a
    /// lost connection, or a deleted tail).
    #[error("incomplete: intact up to line {through}, but it has no end line (cut short)")]
    Incomplete {
        /// The last line checked.
        through: usize,
        /// What was checked.
        report: Report,
    },
    /// The file itself is bad.
    #[error(transparent)]
    Record(#[from] RecordError),
}

/// What `replay --verify` checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The format version the header claims (and the rules it was checked by).
    pub format: u32,
    /// Checkpoints reproduced bit for bit.
    pub checkpoints: usize,
    /// Screens (status-bar values) reproduced.
    pub screens: usize,
    /// The last frame before the end line was recorded, and so checked (always from format 10
    /// on; a format 9 file ended with `q` has none).
    pub final_screen: bool,
    /// What the file's integrity check covers, in words.
    pub integrity: String,
    /// "signed by NAME (key FINGERPRINT)", with whether it was checked against a given key.
    pub signature: Option<String>,
}

/// How `auto` resolves in a replay of `rec`: the plans it recorded for `auto`, and for format 1
/// files (which recorded none) `auto` as it was then.
///
/// A plan line does not say which method was asked. From format 4 on, `auto`'s lines carry its
/// estimate and a method asked by name has none, so only lines with an estimate are kept: a
/// lecture that picked `dop853` in the panel, then went back to `auto`, replays `auto`'s plan for
/// `auto` (formats 2 and 3 keep every line, as before).
#[must_use]
pub fn plan_book(rec: &Recording) -> PlanBook {
    let auto_only = rec.header.version >= 4;
    PlanBook {
        policy: if rec.header.version < 2 {
            AutoRules::Legacy
        } else {
            AutoRules::Verified
        },
        recorded: rec
            .lines
            .iter()
            .filter_map(|(_, l)| match &l.event {
                Event::Plan {
                    key,
                    plan,
                    estimate,
                    ..
                } if estimate.is_some() || !auto_only => Some((*key, *plan)),
                _ => None,
            })
            .collect(),
        estimates: rec
            .lines
            .iter()
            .filter_map(|(_, l)| match &l.event {
                Event::Plan {
                    key,
                    estimate: Some(e),
                    ..
                } => Some((*key, *e)),
                _ => None,
            })
            .collect(),
        // All the runs of a replay together (each priced whole, though a replay computes only
        // what was shown): a budget, and ten times the recording's own length.
        total: crate::physics::budget::BUDGET_SECONDS
            + 10.0 * rec.lines.last().map_or(0.0, |(_, l)| l.wall),
        // The rules the file was recorded with (format 5 and older: the plain sum of the time;
        // 7 and older: the rounded fast phase).
        arithmetic: Arithmetic::of_format(rec.header.version),
        // Runs shown in segments from format 9 on; older files showed them in one piece.
        segmented: rec.header.version >= 9,
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
    let (mut app, effects) = App::new(&preset, Options::at(rec.header.fps));
    if let Some(lesson) = rec
        .header
        .lesson
        .as_ref()
        .and_then(crate::scenario::lesson::RecordedLesson::lesson)
    {
        app.replay_lesson(lesson);
    }
    Ok((app, effects))
}

fn tampered(
    line: usize,
    t: f64,
    expected: impl Into<String>,
    got: impl Into<String>,
) -> VerifyError {
    VerifyError::Diverged(Divergence {
        line,
        t,
        expected: expected.into(),
        got: got.into(),
    })
}

/// The replayed state `got` against the recorded one at `t`.
fn same_state(
    number: usize,
    t: f64,
    (state, reversals, hash): (&[f64], usize, &str),
    got: Option<(f64, Vec<f64>, usize)>,
    failed: Option<&str>,
) -> Result<(), VerifyError> {
    // No state: the replayed run stopped before this time (refused by the budget, failed).
    // Said as such, not as a state of NaNs (issue 56).
    let Some((got_t, got_state, got_rev)) = got else {
        let why = failed.map_or_else(
            || "it stopped before this time".to_owned(),
            crate::scenario::text::one_line,
        );
        return Err(tampered(
            number,
            t,
            format!("state {state:?}, {reversals} reversals, hash {hash}"),
            format!("no state: the replayed run did not reach t = {t}: {why}"),
        ));
    };
    let got_hash = state_hash(got_t, &got_state, got_rev);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    if got_hash != hash || bits(&got_state) != bits(state) || got_rev != reversals {
        return Err(tampered(
            number,
            t,
            format!("state {state:?}, {reversals} reversals, hash {hash}"),
            format!("state {got_state:?}, {got_rev} reversals, hash {got_hash}"),
        ));
    }
    Ok(())
}

/// Whether `line` comes in order after the line before it (`before`: the replayed app's run
/// stamp after it, its own stamp, time and wall clock), the replayed app's stamp being `now`:
/// the wall clock and the run stamps never go down, and the displayed time runs backwards only
/// where a new run starts (issue 80, N11).
fn ordered(
    number: usize,
    line: &super::Line,
    (generation, stamp, t, wall): (u64, u64, f64, f64),
    now: u64,
) -> Result<(), VerifyError> {
    if line.generation < stamp {
        return Err(tampered(
            number,
            line.t,
            format!("a run stamp (generation) of {stamp} or more"),
            format!("{} (it went down)", line.generation),
        ));
    }
    if line.wall < wall {
        return Err(tampered(
            number,
            line.t,
            format!("a wall clock at or after {wall}"),
            format!("{} (it ran backwards)", line.wall),
        ));
    }
    if line.t < t && line.generation == stamp && now == generation {
        return Err(tampered(
            number,
            line.t,
            format!("a time at or after t = {t} within the run"),
            format!("t = {} (it ran backwards)", line.t),
        ));
    }
    Ok(())
}

/// A field a file of format `version` cannot have: the line's kind, if it is one.
fn newer_than(version: u32, line: &super::Line) -> Option<&'static str> {
    let fnv = |c: &str| c.len() == 16;
    match &line.event {
        Event::Clock | Event::Screen(_) | Event::Select { .. } if version < 4 => {
            Some("a clock, screen or select line (format 4)")
        }
        Event::End {
            lines,
            signer,
            public_key,
            signature,
        } if version < 4
            && (lines.is_some()
                || signer.is_some()
                || public_key.is_some()
                || signature.is_some()) =>
        {
            Some("a counted or signed end line (format 4)")
        }
        Event::Plan { .. } if version < 2 => Some("a plan line (format 2)"),
        Event::Plan { model: Some(_), .. } if version < 11 => {
            Some("a plan line naming its model (format 11)")
        }
        Event::Window { .. } if version < 7 => Some("a window line (format 7)"),
        Event::MapCursor { .. } if version < 12 => Some("a map cursor line (format 12)"),
        Event::Terminal { .. } if version < 14 => Some("a terminal line (format 14)"),
        Event::Given { .. } | Event::LessonDone if version < 10 => {
            Some("a given or lesson-done line (format 10)")
        }
        Event::Layout { .. } | Event::Partner { .. } if version < 5 => {
            Some("a layout or partner line (format 5)")
        }
        Event::Screen(s) if version < 5 && (s.crossings.is_some() || s.compare.is_some()) => {
            Some("a screen with crossings or a compared partner (format 5)")
        }
        Event::Plan {
            estimate: Some(_), ..
        } if version < 4 => Some("a plan line with an estimate (format 4)"),
        _ => match line.chain.as_deref() {
            Some(_) if version < 2 => Some("a hash chain (format 2)"),
            Some(c) if version < 4 && !fnv(c) => Some("a SHA-256 chain (format 4)"),
            _ => None,
        },
    }
}

/// Checks the file by the rules of the format its header claims: no field of a newer format
/// (a downgraded header fails), the chain (FNV-1a in formats 2 and 3, SHA-256 over every byte
/// in format 4), the end line's count and signature. Returns what was checked and the signer;
/// `Err(Incomplete)` is decided by the caller once the rest has verified.
fn check_integrity(
    rec: &Recording,
    key: Option<&PublicKey>,
) -> Result<(String, Option<String>, bool), VerifyError> {
    let version = rec.header.version;
    for (number, line) in &rec.lines {
        if let Some(what) = newer_than(version, line) {
            return Err(tampered(
                *number,
                line.t,
                format!("a format-{version} file, as its header says"),
                format!("{what}: the header's version was changed, or the line was added"),
            ));
        }
        if version >= 11 && matches!(line.event, Event::Plan { model: None, .. }) {
            return Err(tampered(
                *number,
                line.t,
                "a plan line naming its model, as format 11 writes it",
                "a plan line without its model (the line was edited)",
            ));
        }
    }
    if version < 2 {
        if key.is_some() {
            return Err(tampered(
                1,
                0.0,
                "a signed session",
                "format 1 has no signatures",
            ));
        }
        return Ok((
            "format 1: no hash chain; only the checkpoints are checked (an edit elsewhere is not detected)".to_owned(),
            None,
            true,
        ));
    }
    if version < 4 {
        check_fnv(rec)?;
        if key.is_some() {
            return Err(tampered(
                1,
                0.0,
                "a signed session",
                format!("format {version} has no signatures"),
            ));
        }
        return Ok((
            format!(
                "format {version}: FNV-1a chain over each line as read (finds accidental edits, not deliberate ones; a cut tail is not detected)"
            ),
            None,
            true,
        ));
    }
    let (signature, ended) = check_sha256(rec, key)?;
    Ok((
        format!(
            "format {version}: SHA-256 chain over every byte of every line, end line with the line count"
        ),
        signature,
        ended,
    ))
}

/// Formats 2 and 3: the FNV-1a chain over each line as serialized again.
fn check_fnv(rec: &Recording) -> Result<(), VerifyError> {
    let mut previous = rec.header_text.clone();
    for (number, line) in &rec.lines {
        let bare = serde_json::to_string(&super::Line {
            chain: None,
            ..line.clone()
        })
        .unwrap_or_default();
        let expected = super::chain_after(&previous, &bare);
        if line.chain.as_deref() != Some(expected.as_str()) {
            return Err(tampered(
                *number,
                line.t,
                format!("hash chain {expected}"),
                format!(
                    "{} (this line, or the one before it, was edited, deleted or inserted)",
                    line.chain.as_deref().unwrap_or("no chain")
                ),
            ));
        }
        previous = expected;
    }
    Ok(())
}

/// Format 4: every line is its exact bytes and then its chain (`,"chain":"<64 hex>"}`), the
/// bytes are the canonical form of what they say (no unknown, repeated or reordered field),
/// the end line is last, counts the lines before it and, when signed, its signature holds.
/// Returns the signature's description and whether the file has its end line.
fn check_sha256(
    rec: &Recording,
    key: Option<&PublicKey>,
) -> Result<(Option<String>, bool), VerifyError> {
    const TAIL: usize = r#","chain":""#.len() + 64 + r#""}"#.len();
    let mut previous = rec.header_text.clone();
    let mut signature = None;
    let mut ended = false;
    for ((number, line), raw) in rec.lines.iter().zip(&rec.raw) {
        let (number, t) = (*number, line.t);
        if ended {
            return Err(tampered(
                number,
                t,
                "nothing after the end line",
                "another line",
            ));
        }
        let split = raw
            .len()
            .checked_sub(TAIL)
            .filter(|&i| raw.is_char_boundary(i));
        let Some((body, tail)) = split.map(|i| raw.split_at(i)) else {
            return Err(tampered(
                number,
                t,
                "a line ending in its chain",
                "a line without one",
            ));
        };
        let chain = tail
            .strip_prefix(r#","chain":""#)
            .and_then(|c| c.strip_suffix(r#""}"#))
            .filter(|c| c.bytes().all(|b| b.is_ascii_hexdigit()));
        let Some(chain) = chain else {
            return Err(tampered(
                number,
                t,
                "a line ending in its chain",
                "a line without one",
            ));
        };
        let bare = format!("{body}}}");
        let canonical = serde_json::to_string(&super::Line {
            chain: None,
            ..line.clone()
        })
        .unwrap_or_default();
        if bare != canonical {
            return Err(tampered(
                number,
                t,
                "the line as this format writes it",
                "an unknown, repeated or reordered field (the line was edited)",
            ));
        }
        let expected = super::chain_sha256(&previous, &bare);
        if chain != expected {
            return Err(tampered(
                number,
                t,
                format!("chain {expected}"),
                format!("{chain} (this line, or one before it, was edited, deleted or inserted)"),
            ));
        }
        if let Event::End {
            lines,
            signer,
            public_key,
            signature: sig,
        } = &line.event
        {
            ended = true;
            if *lines != Some(number - 1) {
                return Err(tampered(
                    number,
                    t,
                    format!("an end line counting {} lines before it", number - 1),
                    lines.map_or_else(
                        || "an end line without a count".to_owned(),
                        |n| format!("one counting {n}"),
                    ),
                ));
            }
            signature = check_signature(number, t, &previous, (signer, public_key, sig), key)?;
        }
        previous = expected;
    }
    if key.is_some() && signature.is_none() && ended {
        let (last, t) = rec.lines.last().map_or((1, 0.0), |(n, l)| (*n, l.t));
        return Err(tampered(
            last,
            t,
            "a session signed with the given key",
            "an unsigned session",
        ));
    }
    Ok((signature, ended))
}

type SignatureFields<'a> = (&'a Option<String>, &'a Option<String>, &'a Option<String>);

/// The end line's signature: none, or valid (and made by `key` when one is given).
fn check_signature(
    number: usize,
    t: f64,
    chain: &str,
    (signer, public_key, signature): SignatureFields<'_>,
    key: Option<&PublicKey>,
) -> Result<Option<String>, VerifyError> {
    let (Some(signer), Some(public), Some(signature)) = (signer, public_key, signature) else {
        if signer.is_some() || public_key.is_some() || signature.is_some() {
            return Err(tampered(
                number,
                t,
                "a whole signature (signer, key, signature)",
                "part of one",
            ));
        }
        return Ok(None);
    };
    let message = super::sign::message(chain, number - 1, signer, public);
    if !super::sign::check(public, &message, signature) {
        return Err(tampered(
            number,
            t,
            "a valid signature",
            "a signature that does not match the file",
        ));
    }
    let fingerprint = super::sign::fingerprint(public);
    let signer = crate::scenario::text::clean(signer);
    match key {
        Some(k) if k.hex() != *public => Err(tampered(
            number,
            t,
            format!("signed by {} (key {})", k.name, k.fingerprint()),
            format!("signed by another key: '{signer}' (key {fingerprint})"),
        )),
        Some(k) => Ok(Some(format!(
            "signed by {} (key {fingerprint}, checked against {})",
            k.name, k.name
        ))),
        None => Ok(Some(format!(
            "signed by '{signer}' (key {fingerprint}; not checked against a key you trust: pass --key FILE.pub)"
        ))),
    }
}

/// Runs `effects` on the engine, the app taking every event (as the explorer's loop does);
/// the computed panes whose numbers a recorded screen does not hold are dropped. A checkpoint's state is kept.
fn run(
    engine: &mut Engine,
    app: &mut App,
    effects: Vec<Effect>,
    got: &mut Option<(f64, Vec<f64>, usize)>,
) {
    let commands = commands(effects)
        .into_iter()
        .filter(|c| !matches!(c, Command::Job { kind, .. } if !kind.shown_in_record()))
        .collect();
    drive(engine, commands, &mut |e| {
        if let SimEvent::Checkpoint {
            t,
            ref state,
            reversals,
            ..
        } = e
        {
            *got = Some((t, state.clone(), reversals));
        }
        app.on_sim(e);
    });
}

/// Re-runs `rec` as a replay does (each line at its recorded displayed time) and compares every
/// checkpoint bit for bit and every screen's values; checks the file's integrity first by the
/// rules of its format (and the signature against `key` when given).
///
/// # Errors
/// A bad header preset, the first line that fails, or a file cut short.
pub fn verify(rec: &Recording, path: &str, key: Option<&PublicKey>) -> Result<Report, VerifyError> {
    verify_watched(rec, path, key, &mut |_| {})
}

/// As [`verify`], telling `seen` how many of the file's lines have been re-run (for progress).
///
/// # Errors
/// As [`verify`].
pub fn verify_watched(
    rec: &Recording,
    path: &str,
    key: Option<&PublicKey>,
    seen: &mut dyn FnMut(usize),
) -> Result<Report, VerifyError> {
    let (integrity, signature, ended) = check_integrity(rec, key)?;
    let (mut app, effects) = start(rec, path)?;
    // A signal stops it natively; in the browser nothing does.
    #[cfg(not(target_arch = "wasm32"))]
    let mut engine = Engine::new(plan_book(rec)).stopping_on(crate::interrupt::not_requested);
    #[cfg(target_arch = "wasm32")]
    let mut engine = Engine::new(plan_book(rec));
    let mut got = None;
    run(&mut engine, &mut app, effects, &mut got);
    let mut report = Report {
        format: rec.header.version,
        checkpoints: 0,
        screens: 0,
        final_screen: false,
        integrity,
        signature,
    };
    // The displayed time runs backwards only where a new run starts (the line's run stamp rose,
    // or the replayed app's moved), the run stamps and the wall clock never (issue 80, N11: a
    // clock line moved a second ahead of the next passed a re-chained file).
    let mut before: Option<(u64, u64, f64, f64)> = None;
    for (i, (number, line)) in rec.lines.iter().enumerate() {
        seen(i);
        if rec.header.version >= 4
            && let Some(before) = before
        {
            ordered(*number, line, before, app.run.generation)?;
        }
        // The last frame: a screen line after which only checkpoints, clock lines and the end
        // come.
        match &line.event {
            Event::Screen(_) => report.final_screen = true,
            Event::Checkpoint { .. } | Event::Clock | Event::End { .. } => {}
            _ => report.final_screen = false,
        }
        let mut effects = app.seek(line.t);
        match &line.event {
            Event::Checkpoint {
                state,
                reversals,
                hash,
            } => {
                effects.push(Effect::Sim(Command::Checkpoint {
                    generation: app.run.generation,
                    t: line.t,
                }));
                got = None;
                run(&mut engine, &mut app, effects, &mut got);
                let failed = app.run.failed.as_deref();
                same_state(
                    *number,
                    line.t,
                    (state, *reversals, hash),
                    got.take(),
                    failed,
                )?;
                report.checkpoints += 1;
            }
            Event::Screen(recorded) => {
                run(&mut engine, &mut app, effects, &mut got);
                let replayed = app.shown();
                if let Some(d) = recorded.difference(&replayed) {
                    return Err(tampered(
                        *number,
                        line.t,
                        "the lecturer's screen",
                        format!("a different screen: {d}"),
                    ));
                }
                report.screens += 1;
            }
            event => {
                let rose = i
                    .checked_sub(1)
                    .is_some_and(|j| line.generation > rec.lines[j].1.generation);
                effects.extend(app.apply_event(event, rose));
                run(&mut engine, &mut app, effects, &mut got);
            }
        }
        before = Some((app.run.generation, line.generation, line.t, line.wall));
    }
    if !ended {
        let through = rec.lines.last().map_or(1, |(n, _)| *n);
        return Err(VerifyError::Incomplete { through, report });
    }
    if !report.final_screen
        && rec.header.version >= 10
        && let Some((number, last)) = rec.lines.last()
    {
        // From format 10 on, whatever ended the recording wrote its last frame.
        return Err(tampered(
            *number,
            last.t,
            "the last frame (a screen line before the end)",
            "none: the file ends without its last frame",
        ));
    }
    Ok(report)
}
