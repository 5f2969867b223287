//! How the pendulum's resolved run is verified (data for the one loop, `physics::verify`).

use crate::physics::verify::Policy;

/// The Taylor series against a companion 8× looser: the series' error falls faster than its
/// tolerance (a slope of 1–1.5 in log-log), so their difference is 1.1–30× the run's error on
/// the references where rounding does not set it (16× looser, as for DOP853 before, read up to
/// 100×; 4× looser read 0.6× the error of the held-out `returns_eps1e-2`, both runs at its
/// rounding floor). Refined at least 4× a round (16× when the estimate is infinite), down to
/// 1e-14, four refinements at most; one stall stops it (the pendulum's rule since issue 29).
///
/// One stall, not the celt's and the series' two, decided by measurement (issue 57): on the 6
/// held-out starts of `kapitza_honesty.toml` at 1e-8, 1e-9 and 1e-10 (18 runs) and on every
/// shipped preset, two stalls give the same method, claim, estimate and error on every run and
/// the same time within 3 ms (best of 3, one `simulate` per process); 7 of the 18 decline, none
/// by a stall the second would have undone. The extra round buys nothing here, so the cheaper
/// rule stays.
pub const POLICY: Policy = Policy {
    companion_looser: 8.0,
    companion_cap: 1e-3,
    // The difference read 1.1–30× the run's error on the references, so the companion errs
    // 2.1–31× the run: the least is kept (no plan of the pendulum's reads it).
    companion_error: 2.1,
    refine: 0.25,
    blind_refine: 1.0 / 16.0,
    tightest: 1e-14,
    step_safety: 1.25,
    max_refinements: 4,
    stalls: 1,
    floor_stops: false,
};

/// The slow models' check (`plan::averaged_checked`, on the one loop since issue 69): each run
/// against a companion 4× looser, whose difference is 1.3–3× the run's integration error
/// (`4^q − 1`, `q` 0.65–1 measured between 1e-10 and 1e-13 on the references), which keeps the
/// estimates within about 10× of the errors. Its rounds climb a ladder instead of refining one
/// tolerance: the limit with its ripple, `averaged2`, `averaged3`, then the best once more at
/// the tightest tolerance where the integration misses (three refinements at most); no stall
/// stops it (each round is a model of its own), no floor either (the estimate says it).
pub const SLOW: Policy = Policy {
    companion_looser: 4.0,
    // `4^q` with `q` 0.65–1: the least.
    companion_error: 2.5,
    max_refinements: 3,
    ..POLICY
};
