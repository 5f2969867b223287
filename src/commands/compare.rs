//! `rattleback compare`: two presets side by side in the explorer.

use super::explore::{Opening, open_explorer};
use super::shared::refuse_stdin;
use crate::commands::failure::{Failure, Outcome};
use crate::scenario::shipped::resolve;

/// `compare A B`: the explorer on `A` with `B` beside it on one time axis.
pub fn run_compare(args: &crate::commands::cli::CompareArgs) -> Outcome {
    if args.a == "-" || args.b == "-" {
        return refuse_stdin("compare -");
    }
    let (preset, partner) = match (resolve(&args.a, &[]), resolve(&args.b, &[])) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            return Err(Failure::input(format!("compare: {e}")));
        }
    };
    let opening = Opening {
        look: &args.look,
        rec: &args.rec,
        mouse: false,
        lesson: None,
        partner: Some(partner),
    };
    open_explorer(Some(Ok(preset)), opening)
}
