//! Entry point: parse arguments, dispatch, and turn errors into messages and exit codes
//! (2 for bad input, 1 for a failed run).

use std::io::Write as _;
use std::process::ExitCode;

use clap::Parser;
use rattleback::cli::{Cli, Command, Format, SimulateArgs};
use rattleback::scenario::shipped::resolve;
use rattleback::simulate::{resolve as resolve_run, simulate};

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Some(Command::Simulate(args)) => run_simulate(&args),
        // Until the interactive explorer exists, the default action is a summary of the preset.
        None => run_simulate(&SimulateArgs {
            preset: cli.preset,
            set: Vec::new(),
            method: None,
            tolerance: None,
            step: None,
            t_end: None,
            format: Format::Table,
            samples: 2,
        }),
    }
}

fn run_simulate(args: &SimulateArgs) -> ExitCode {
    let preset = match resolve(&args.preset, &args.set) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("rattleback: error: {e}");
            return ExitCode::from(2);
        }
    };
    let resolved = resolve_run(&preset, args);
    match simulate(&preset, &resolved, args.format) {
        Ok(text) => {
            let mut out = std::io::stdout().lock();
            // A closed pipe (e.g. `| head`) is not an error worth a panic.
            let _ = out.write_all(text.as_bytes());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("rattleback: integration failed: {e}");
            ExitCode::from(1)
        }
    }
}
