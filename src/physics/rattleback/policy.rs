//! How the rattleback's `auto` verifies: data for the one loop, `physics::verify`, read by
//! `auto` (whose candidate refines a plan by its own rules: a tolerance, a step, or another
//! method) and by the plans.

use crate::physics::verify::Policy;

/// The adaptive methods (DOP853 and the averaged models): a companion 16× looser, tightened by
/// twice the excess of the estimate over the tolerance (at least 4×, 32× when the estimate is
/// infinite), down to 1e-14, six refinements at most, one stall a floor.
///
/// How much looser the companion of an adaptive run is (its error is then ≈ 14× the run's:
/// DOP853's global error goes like `tol^0.95` here, docs/benchmarks.md).
///
/// `companion_error`:
/// The companion's error over the run's, for an adaptive method (`16^0.95`).
///
/// `max_refinements`:
/// Most refinements before `auto` reports what it has.
pub const POLICY: Policy = Policy {
    companion_looser: 16.0,
    companion_cap: 1e-3,
    companion_error: 14.0,
    refine: 0.25,
    blind_refine: 1.0 / 32.0,
    tightest: 1e-14,
    step_safety: 1.25,
    max_refinements: 6,
    stalls: 1,
    floor_stops: true,
};

/// The Taylor series (`taylor`): its own companion, refinement and stall rule.
///
/// `companion_looser`:
/// How much looser the companion of a `taylor` run is. The series' error does not fall
/// smoothly with its tolerance (a random walk of local errors that take the sign of a ripple's
/// phase: docs/benchmarks.md, "The middle by a Taylor series"), so a companion a little looser
/// can land on an error as small as the run's; one 1024× looser cannot, in practice: on every
/// long-double reference up to k = 1e6, companions at 1e-8 … 1e-12, their difference plus the
/// round-off floors was at least 27× the run's true error (185 runs measurable above the
/// references' own error; 5.6× at 256×, 0.53× at 64×, 0.11× at 16×:
/// `cargo run --release --example rattleback_taylor tighter`). The series' cost grows like
/// `tol^-0.05`, so the run 1024× tighter than its companion costs only 1.4× as much.
///
/// `stalls`:
/// How many refinements of the series in a row may fail to halve its estimate before `auto`
/// reads a stall (a floor) and stops; one for the other methods. The series' companion, 1024×
/// looser, errs erratically on an ill-conditioned start: on `M` at k = 1e3, T = 100 (κ ≈ 2 300)
/// its error moves by up to 4× between local tolerances a factor 2 apart, up as often as down
/// (`cargo run --release --example rattleback_taylor stall`). With one, that start ended
/// `met = false` "at its floor" at tolerances 1e-5 and 1e-7 (estimates 2.9e-5, 1.9e-7) while its
/// floor was 4e-10 and it met 1e-6 and 1e-8 (stop 52).
///
/// `refine` (its inverse is the least factor):
/// The least factor by which a refinement tightens the series' local tolerance: its cost grows
/// like `tol^-0.06` (16× tighter costs about 1.2× as much: `… rattleback_taylor cost`), while
/// its companion's error, on an ill-conditioned start, moves by up to 4× either way between
/// tolerances a factor 2 apart (`TAYLOR.stalls`), so a small step may land on a worse one.
pub const TAYLOR: Policy = Policy {
    companion_looser: 1024.0,
    refine: 1.0 / 16.0,
    stalls: 2,
    ..POLICY
};

/// The policy a run of `method` follows: [`TAYLOR`] for the series, [`POLICY`] for the others.
#[must_use]
pub fn of(method: crate::physics::method::Method) -> &'static Policy {
    if method == crate::physics::method::Method::Taylor {
        &TAYLOR
    } else {
        &POLICY
    }
}
