//! How the pendulum's resolved run is verified (data for the one loop, `physics::verify`).

use crate::physics::verify::Policy;

/// The Taylor series against a companion 8× looser: the series' error falls faster than its
/// tolerance (a slope of 1–1.5 in log-log), so their difference is 1.1–30× the run's error on
/// the references where rounding does not set it (16× looser, as for DOP853 before, read up to
/// 100×; 4× looser read 0.6× the error of the held-out `returns_eps1e-2`, both runs at its
/// rounding floor). Refined at least 4× a round (16× when the estimate is infinite), down to
/// 1e-14, four refinements at most; one stall stops it (the pendulum's rule since issue 29).
pub const POLICY: Policy = Policy {
    companion_looser: 8.0,
    companion_cap: 1e-3,
    refine: 0.25,
    blind_refine: 1.0 / 16.0,
    tightest: 1e-14,
    max_refinements: 4,
    stalls: 1,
};
