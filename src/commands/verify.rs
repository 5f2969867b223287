//! `replay --verify`: the file checked by its format's rules and re-run headless, and the
//! report of what reproduced (what a cut file reproduced is said of its intact part only).

use crate::commands::cli::ReplayArgs;
use crate::commands::failure::{Failure, Outcome};
use crate::record;

/// `replay --verify`: the report on stdout; `Err` with the exit code when it did not verify.
pub fn replay_verify(args: &ReplayArgs, rec: &record::Recording, path: &str) -> Outcome {
    let key = match args
        .key
        .as_deref()
        .map(record::sign::PublicKey::read)
        .transpose()
    {
        Ok(k) => k,
        Err(e) => {
            return Err(Failure::input(format!("--key: {e}")));
        }
    };
    let mut progress =
        crate::commands::progress::Progress::count("verify", rec.lines.len(), "lines");
    let verified = record::verify_watched(rec, path, key.as_ref(), &mut |n| {
        progress.tick(n as f64);
    });
    progress.finish();
    if args.format == crate::commands::cli::ListFormat::Json {
        let v = crate::commands::outputs::Verification::of(Some(rec), path, verified.as_ref());
        say_raw!("{}", super::json_text(&v));
        return match verified {
            Ok(_) => Ok(()),
            Err(record::VerifyError::Record(_)) => Err(Failure::said(2)),
            Err(_) => Err(Failure::said(1)),
        };
    }
    match verified {
        Ok(r) => print_report(path, &r, None),
        Err(record::VerifyError::Incomplete { through, report }) => {
            print_report(path, &report, Some(through));
            return Err(Failure::said(1));
        }
        Err(record::VerifyError::Diverged(d)) => {
            return Err(Failure::failed(format!(
                "{path}:{}: divergence at t = {}: expected {}, got {}",
                d.line, d.t, d.expected, d.got
            )));
        }
        Err(record::VerifyError::Record(e)) => {
            return Err(Failure::input(e));
        }
    }
    Ok(())
}

/// What `replay --verify` checked; `cut` is the last intact line of a file cut short.
fn print_report(path: &str, r: &record::Report, cut: Option<usize>) {
    // A file cut short fails first, and what it reproduced is said of its intact part only:
    // nothing claims a last frame the cut removed (issue 67).
    if let Some(n) = cut {
        say_err!(
            "rattleback: error: {path}: incomplete: intact up to line {n}, but there is no end line (the recording was cut short, or its tail deleted)"
        );
        say!(
            "{path}: in its intact lines 1-{n}: {} checkpoint(s) reproduced bit for bit, {} screen(s) as recorded; its last frame is not in the file",
            r.checkpoints,
            r.screens
        );
    } else {
        say!(
            "{path}: {} checkpoint(s) reproduced bit for bit, {} screen(s) as recorded",
            r.checkpoints,
            r.screens
        );
    }
    if cut.is_none() && r.final_screen {
        say!("{path}: the last frame, as recorded");
    } else if cut.is_none() {
        say!(
            "{path}: the last frame was not recorded (format {} files ended with q or Ctrl-C have none; format 10 on always does)",
            r.format
        );
    }
    say!("{path}: {}", r.integrity);
    match &r.signature {
        Some(s) => say!("{path}: {s}"),
        None if r.format >= 4 => say!(
            "{path}: not signed (anyone can write a valid chain: only a signature says who made the file)"
        ),
        None => {}
    }
}
