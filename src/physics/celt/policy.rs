//! How the celt's `auto` verifies (data for the one loop, `physics::verify`), read by `plan`
//! and by the cost model (`budget`), which prices the rounds the loop runs.

use crate::physics::verify::Policy;

/// The first local tolerance, over the tolerance asked.
pub const FIRST: f64 = 0.1;

/// DOP853 at a local tolerance `L` against a companion at `16 L` (the rattleback's rule),
/// refined at least 4× a round, 16× when the two runs count different events, down to 1e-14,
/// four refinements at most. Two stalls in a row stop it: one was read as a floor on
/// `celt-pitching` at tolerance 1e-4 (its estimate went 1.6e-2, 1.9e-4, 1.1e-4 at local
/// tolerances 1e-5, 3.2e-8, 8.0e-9, far above its round-off, while 5e-5 and every tighter
/// tolerance were met: DOP853's error falls unevenly before it settles); a chaotic run, whose
/// states differ between any two tolerances, still stops, one refinement later (stop 52).
pub const POLICY: Policy = Policy {
    companion_looser: 16.0,
    companion_cap: 1e-2,
    // About 14× for a 16× looser tolerance where DOP853 converges (plan.rs).
    companion_error: 14.0,
    refine: 0.25,
    blind_refine: 0.25 * 0.25,
    tightest: 1e-14,
    step_safety: 1.25,
    max_refinements: 4,
    stalls: 2,
    floor_stops: true,
};
