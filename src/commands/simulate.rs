//! `rattleback simulate`: one run, reported as a table, CSV or JSON.

use std::io::Write as _;

use crate::commands::cli::SimulateArgs;
use crate::commands::failure::{Failure, Outcome};
use crate::physics::StepError;
use crate::scenario::shipped::resolve;
use crate::simulate::{Failure as Stopped, resolve as resolve_run, simulate_to};

pub fn run_simulate(args: &SimulateArgs) -> Outcome {
    let preset = match resolve(&args.preset, &args.set) {
        Ok(p) => p,
        Err(e) => {
            return Err(Failure::input(e));
        }
    };
    let request = args.request();
    let resolved = resolve_run(&preset, &request);
    let kind = preset.model.kind();
    if !kind.offers(resolved.spec.method) {
        return Err(Failure::input(format!(
            "--method {}: not offered for the {} model ({}); allowed: {}",
            resolved.spec.method,
            kind.name(),
            args.preset,
            kind.method_names()
        )));
    }
    if let Some(h) = resolved.spec.step
        && let Err(e) = crate::physics::method::check_step(h, resolved.spec.t_end)
    {
        return Err(Failure::input(format!("--step: {e}")));
    }
    let format = request.format;
    let mut progress = crate::commands::progress::Progress::stderr("simulate", resolved.spec.t_end);
    let outcome = if format == crate::simulate::Format::Table {
        // The table holds the preset's own text: cleaned of control characters first.
        simulate_to_text(&preset, &resolved, &mut progress)
    } else {
        // JSON escapes control characters itself; the CSV holds numbers only. Streamed.
        let mut out = std::io::BufWriter::new(std::io::stdout().lock());
        simulate_to(&preset, &resolved, format, &mut out, &mut |t| {
            progress.tick(t)
        })
    };
    progress.finish();
    match outcome {
        Ok(None) => Ok(()),
        Ok(Some(missed)) => {
            say_err!("rattleback: warning: {missed}");
            if args.strict {
                Err(Failure::said(1))
            } else {
                Ok(())
            }
        }
        // A closed pipe (e.g. `| head`) ends the output early; not an error worth a message.
        Err(Stopped::Output(e)) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(Stopped::Output(e)) => Err(Failure::failed(format!("writing the output: {e}"))),
        Err(Stopped::Run(e @ StepError::OverBudget { .. })) => Err(Failure::input(format!(
            "{e}; shorten --t-end, loosen --tolerance or choose another --method (`rattleback simulate --help`), or pass --force to run it anyway"
        ))),
        Err(Stopped::Run(e @ StepError::OutsideModel { .. })) => Err(Failure::input(format!(
            "--method {}: {e}",
            resolved.spec.method
        ))),
        Err(Stopped::Run(e)) => Err(Failure::failed(format!("integration failed: {e}"))),
    }
}

pub(crate) fn simulate_to_text(
    preset: &crate::scenario::Preset,
    resolved: &crate::simulate::Resolved,
    progress: &mut crate::commands::progress::Progress,
) -> Result<Option<crate::simulate::Missed>, Stopped> {
    let mut text = Vec::new();
    let missed = simulate_to(
        preset,
        resolved,
        crate::simulate::Format::Table,
        &mut text,
        &mut |t| progress.tick(t),
    )?;
    progress.finish();
    let text = crate::commands::wrap::for_stdout(&crate::scenario::text::shown(
        &String::from_utf8_lossy(&text),
    ));
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(missed)
}
