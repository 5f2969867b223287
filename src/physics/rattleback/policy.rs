//! How the rattleback's `auto` verifies and plans: the data of the one loop
//! (`physics::verify`), read by `auto` (whose candidate refines a plan by its own rules: a
//! tolerance, a step, or another method) and by the plans; and, below it, `auto`'s tuning: the
//! constants its error and cost models, its probes and its conditioning read, each with what it
//! was measured on (issue 69: they were a room of `auto` of their own, away from the rest of its
//! policy).

use crate::physics::method::Method;
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

// auto's tuning.

/// Error of `blanes-moan4` per unit time: `C_BM · spin^2.5 · c_max⁴ · h⁴ ν² / g_min`, with
/// `spin` the largest spin rate of the limit, `c_max = |iy − ix| / (4 min(ix, iy))`, fitted on
/// the averaging note's starts A, B, D for k = 1e2 … 1e5 and `ν h` ≤ 1.5 (measured 6.9e-3 …
/// 7.3e-3, doubled: docs/benchmarks.md).
pub const C_BM: f64 = 1.5e-2;

/// Error of `blanes-moan4` per unit time at `ν h = 1` that remains where `c_max` or the spin
/// vanish (issue 3's calibration at k = 1e6).
pub const C_FAST: f64 = 3e-12;

/// Largest `ν h` of a `blanes-moan4` run: its companion at `2h` stays where the error still
/// follows `h⁴` (measured up to `ν h = 1.5`; at 2 it jumps by 10²–10³ on trapped starts).
pub const BLANES_MOAN_MAX_NU_H: f64 = 0.75;

/// The series' global error over its local tolerance per fast period of the horizon (at least
/// 20): median 0.27 on the long-double references up to k = 1e6, a tenth of DOP853's
/// (`cargo run --release --example rattleback_taylor growth`, and with `METHOD=dop853`), which
/// is what [`DOP853_GROWTH`] is to DOP853.
pub const TAYLOR_GROWTH: f64 = 0.25;

/// DOP853's global error over its local tolerance per fast period of the horizon (measured
/// 0.6–2.7 on trapped starts, 0.06–0.25 on rotating ones, k = 1e2 … 1e5, T = 30).
pub const DOP853_GROWTH: f64 = 2.5;

/// The averaged model `auto` plans with (probes, plans and refines): `averaged3`, whose
/// O(k⁻³) error reaches into the middle stiffnesses `averaged2` could not serve.
pub const AVERAGED: Method = Method::Averaged3;

/// `averaged2` runs instead of [`AVERAGED`] where its probed model error is at most this share
/// of the tolerance (issue 27): at large `k` its O(k⁻²) error is far below any tolerance, and a
/// run costs half of `averaged3`'s (12 against 34 ns per evaluation), so `auto`'s run and
/// companion do too. Within a tenth, the integration still gets most of the tolerance, as with
/// `averaged3`.
pub const SECOND_ORDER_MODEL_SHARE: f64 = 0.1;

/// The order in `1/k` of [`AVERAGED`]'s model error (the theory's; a probe's slope is clamped
/// to it).
pub const MODEL_ORDER: f64 = 3.0;

/// Safety factor on the probed model error of the averaged model.
pub const PROBE_SAFETY: f64 = 2.0;

/// Samples of `α`, `α̇` compared by a probe.
pub const PROBE_SAMPLES: usize = 33;

/// The method of a probe's full model: the Taylor series (`taylor`). At
/// [`PROBE_FULL_TOLERANCE`] its error in `α(T)`, `α̇(T)` and the reversal times is at most
/// DOP853's on every long-double reference of `averaged.toml` and `rattleback_honesty.toml` up
/// to k = 1e6, and 3–70× below it from k = 1e2 to 1e4, where the probes run (over the samples
/// too, within 3e-11 there: `averaged::the_probes_full_model_is_as_accurate_as_dop853`), at
/// 0.3–0.5 of its time (`cargo run --release --example rattleback_taylor probe`;
/// docs/benchmarks.md, "The middle by a Taylor series").
pub const PROBE_FULL_METHOD: Method = Method::Taylor;

/// Local tolerance of the full model in a probe: its global error at the probe stiffnesses (≤ 100
/// fast periods over T = 30) is at most 1.5e-11 on the references (DOP853's at this tolerance
/// was about 2.5e-10), against the averaged model's gaps of 1e-8 and more there
/// (docs/averaging/third-order.md).
pub const PROBE_FULL_TOLERANCE: f64 = 1e-12;

/// Local tolerance of the averaged model in a probe (its global error ≈ 1e-10, against gaps
/// of 1e-8 and more at the probe stiffnesses).
pub const PROBE_TOLERANCE: f64 = 1e-12;

/// Largest `|α̇| (1 + c_max) / ω_min` at the lower probe stiffness: where the averaging
/// expansion already holds (from k = 1e2, where this is 0.1–0.3 for the note's starts,
/// `averaged3`'s errors already fall like k^-2.7 … k^-3: docs/averaging/third-order.md).
pub const PROBE_VALIDITY: f64 = 0.2;

/// Most rungs of probes ([`probe_averaged`](super::auto::probe_averaged)).
pub const PROBE_RUNGS: u32 = 3;

/// The averaged model is considered from `k ≥ AVERAGED_MIN_RATIO · k_hi` on (where probing
/// is predicted cheaper than resolving): its error is extrapolated from `k_hi` with the
/// measured slope, which a pre-asymptotic start keeps below the theory's 3, so the prediction
/// errs high.
pub const AVERAGED_MIN_RATIO: f64 = 4.0;

/// Predicted seconds (calibration machine) after which `auto` stops refining and reports
/// `met = false` instead of computing on: it answers within about this time, whatever the
/// start and tolerance.
pub const AUTO_SECONDS: f64 = 10.0;

/// Gain of the round-off floor ([`round_off`]): blanes-moan4's reversal times at very small
/// steps, against the long-double references, fit a gain of 1.2–1.5 (T = 30, k = 1e4, and
/// T = 1000, k = 1e2, 10⁵–6·10⁵ steps); 5 keeps a margin for the scatter. What it was fitted
/// to was mostly the time itself, summed `t + h` in double each step; the fixed-step methods now
/// sum it compensated (4.3e-11 → 1.2e-12 on `lib_b1_a015_k1e06`'s reversal times:
/// docs/benchmarks.md, "Issue 29"), so only the adaptive methods keep it, in their predicted
/// errors and their estimates (`phase_round_off`); the splitting's prediction counts one
/// rounding per step ([`conditioned_round_off`](super::auto::conditioned_round_off) at κ = 1).
///
/// [`round_off`]: super::auto::round_off
pub const ROUND_OFF_GAIN: f64 = 5.0;

/// Relative nudge of the rates, and absolute nudge of the angle (radians), by which
/// [`conditioning`] measures how much the start's rounding is amplified by `T` (small enough
/// to stay linear at condition numbers of 1e7, large enough to stand far above the rounding of
/// the runs it compares).
///
/// [`conditioning`]: fn@super::auto::conditioning
pub const NUDGE: f64 = 1e-10;

/// Largest expansion parameter ([`super::averaged::expansion_parameter`]) at which a plan's
/// condition numbers are measured on [`CONDITIONING_MODEL`] instead of the plan's own method:
/// a sensitivity measured with nudges of 1e-10 is the derivative of the slow motion in its start,
/// which the averaged models' errors (`averaged2`'s O(x⁴) relative) move by far less than the
/// factor of two the round-off floor's gain leaves. Raised from 0.1 in issue 27 to take in the
/// rotating start at k = 1e2 (x = 0.21): on the long-double references with 0.1 < x ≤ 0.3 the
/// slow model's κ is within 0.3 % of the full model's away from the separatrix (B, C, D, E at
/// k = 1e2); near it (κ of 1e3 … 1e6) it is off by up to 300× either way but always reads above
/// [`CONDITIONING_RECHECK`], so it is measured again on the plan's own method
/// (`cargo run --release --example conditioning_check`).
pub const CONDITIONING_AVERAGED_LIMIT: f64 = 0.25;

/// The model [`conditioning`] measures on below [`CONDITIONING_AVERAGED_LIMIT`]: `averaged2`,
/// the cheapest slow model with the fast action's back-reaction (12 ns per evaluation against
/// `averaged3`'s 34: its three runs took 0.14 ms instead of 0.31 ms at k = 1e8 on the trapped
/// start). It replaced `averaged3` here in issue 27: on the held-out starts of
/// `rattleback_honesty.toml` (k = 1e2 … 1e12) the condition numbers `auto` measures stay within
/// 0.9–1.7 of the long-double references' (`honesty::auto_measures_the_conditioning_the_references_report`).
///
/// [`conditioning`]: fn@super::auto::conditioning
pub const CONDITIONING_MODEL: Method = Method::Averaged2;

/// Condition number above which a measurement on the averaged model
/// ([`CONDITIONING_AVERAGED_LIMIT`]) is repeated on the plan's own method: below it the
/// conditioned round-off floor (`10 ε √steps κ`) is far under any tolerance `auto` is asked
/// for, so the cheap measurement's accuracy does not matter; above it, it does (the shipped
/// `just-below` start measures κ = 1.4e4 on `averaged3` and 9.1e3 on the full model).
pub const CONDITIONING_RECHECK: f64 = 100.0;

/// Expansion parameter ([`super::averaged::expansion_parameter`]) below which (at a `k` above the
/// start's [`conditioning_stiffness`]) an averaged plan's condition numbers may be bounded by the
/// start's reading at that one stiffness instead of measured at its own `k` (issue 27, stop 51):
/// that reading is kept ([`memo`]) and serves every larger `k` (the explorer's `k` slider, a sweep's
/// rungs), so `auto`'s verification is its companion alone.
///
/// [`conditioning_stiffness`]: super::auto::conditioning_stiffness
/// [`memo`]: super::auto::memo
pub const CONDITIONING_KEPT_X: f64 = 0.01;

/// How much a reading at the conditioning stiffness is widened into a bound on the start's
/// condition numbers at a larger `k`: they move with `k` (the fast ripple's phase in `α̇(T)`, and
/// the reversals crossing where the ripple makes `α̇` steep or shallow by turns), on the reference
/// families up to 16× (rate) and 21× (angle) above that reading, `k` up to 1e12
/// (`cargo run --release --example conditioning_check spread`;
/// `honesty::a_kept_conditioning_bounds_the_start_at_every_larger_k`).
pub const CONDITIONING_KEPT_MARGIN: f64 = 50.0;

/// The bound ([`CONDITIONING_KEPT_MARGIN`]) serves only where the conditioned round-off floor it
/// gives is at most this share of the tolerance: there it can neither cost `met` nor, misread
/// by less than tenfold, hide an error of the tolerance's size. Elsewhere (tight tolerances,
/// ill-conditioned starts) the start is measured at its own `k`, as below
/// [`CONDITIONING_KEPT_X`].
pub const CONDITIONING_KEPT_SHARE: f64 = 0.1;

/// Local tolerance of [`conditioning`]'s runs (at least; the companion's when looser).
///
/// [`conditioning`]: fn@super::auto::conditioning
pub const CONDITIONING_TOLERANCE: f64 = 1e-9;

/// Local tolerance of [`conditioning`]'s first measurement on [`CONDITIONING_MODEL`]: the nudged
/// starts are integrated side by side with the start, on its steps
/// ([`slow_condition_numbers`]), so their truncation errors cancel and a loose run measures the
/// sensitivity as well as a tight one where it is small; where it reads above
/// [`CONDITIONING_RECHECK`] (the floor may matter) the measurement is repeated at
/// [`CONDITIONING_TOLERANCE`], as before. Issue 27: three separate runs at 1e-9 were half of
/// `auto`'s time at k ≥ 1e5 with the probes kept; at 1e-7 side by side the reading costs
/// 0.06 ms (trapped start) and 0.10 ms (rotating), against 0.09 and 0.18 ms for three separate
/// runs at 1e-7 (`cargo run --release --example conditioning_check all`).
///
/// [`conditioning`]: fn@super::auto::conditioning
/// [`slow_condition_numbers`]: super::auto::slow_condition_numbers
pub const CONDITIONING_LOOSE_TOLERANCE: f64 = 1e-7;

/// Gain of the conditioned round-off floor `CONDITIONED_GAIN · ε · √steps · κ`: a step rounds
/// several numbers, so the random walk's step is a few ε. Measured on the held-out starts near
/// the separatrix of `rattleback_honesty.toml` (κ = 1e3 … 2e7): restarting from one to five ulps
/// away spreads `α(T)` by up to 3.3 `ε √steps κ` (`sep_b2_in5_k1e03`, a 1-ulp change moved it
/// by 1e-8); 10 bounds every one of 225 such runs with a margin of two.
pub const CONDITIONED_GAIN: f64 = 10.0;

/// Global-to-local error growth of the averaged slow flow over `T = 30` (measured 6–140 on the
/// note's starts at local tolerance 1e-10; it grows linearly with `T` on rotating starts).
pub const AVERAGED_GROWTH: f64 = 150.0;
