//! `auto`: the cheapest method that meets a tolerance on the slow observables (`α(T)`,
//! `α̇(T)` and the reversal times), with an error estimate that never claims more than it
//! knows.
//!
//! **Candidates** (costs predicted by [`super::budget`], calibrated on this machine):
//! - `taylor`, resolving the fast motion by its Taylor series, at a local tolerance `L / 1024`
//!   where its companion at `L` should still meet the tolerance: the companion's global error
//!   is about `G L` with `G = 0.25 · max(20, fast periods)` ([`TAYLOR_GROWTH`]). The series'
//!   error is a random walk that a slightly looser companion can under-read; one
//!   `TAYLOR.companion_looser` = 1024 times looser did not on any reference, and the series'
//!   cost grows so slowly with its tolerance (`tol^-0.05`) that the tight run costs 1.4× the
//!   companion. The cheapest resolving candidate at tolerances down to about 1e-9;
//! - `dop853`, resolving the fast motion, at a local tolerance `L` such that its companion at
//!   `16 L` should still meet the tolerance: the global error is about `G L` with
//!   `G = 2.5 · max(20, fast periods)` (measured, [`DOP853_GROWTH`]); a plan whose `L` would
//!   fall below the 1e-14 clamp cannot be verified and counts as missing the tolerance;
//! - `blanes-moan4`, resolving, at a step `h` such that its companion at `2h` should meet the
//!   tolerance: error ≈ `(C_BM spin^2.5 c_max⁴ ν²/g_min + C_FAST ν⁴) h⁴ T` ([`C_BM`]);
//!   `ν h ≤ 0.75`, so that the companion at `2h` stays where the error follows `h⁴`;
//! - `averaged3`, the O(k⁻³) averaged model ([`AVERAGED`]), once `k` is far enough above the
//!   stiffnesses at which its model error can be *measured* cheaply. Two probes at `k_lo` and
//!   `k_hi = 4 k_lo` (the smallest `k` where the averaging expansion is valid for this start:
//!   `|α̇|/ω ≤ 0.2`) compare it with the resolved full model (`taylor` at 1e-12) over `[0, T]`
//!   (33 samples of `α`, `α̇`, and the reversal times); the model error at `k` is predicted as
//!   `2 · gap(k_hi) · (k_hi/k)^p`, with `p` the measured slope between the probes clamped to
//!   `[0.5, 3]` (3 is the theory's; a pre-asymptotic start decays slower and is extrapolated
//!   with its own, smaller slope). Where the model is exact (`ix = iy`, or no fast action) no
//!   probe runs. The slow flow then runs at a local tolerance such that its companion at `16 L`
//!   meets the rest of the tolerance;
//! - `averaged2`, the O(k⁻²) model, measured by the same probes against the same full runs and
//!   extrapolated the same way (slope clamped to `[0.5, 2]`), where its predicted model error is
//!   at most [`SECOND_ORDER_MODEL_SHARE`] of the tolerance and it is predicted cheaper (a run
//!   costs half of `averaged3`'s): the large stiffnesses.
//!
//! **Verification.** Every plan runs twice: the run that is returned, and a *coarser*
//! companion (step `2h`, or tolerance `16 L`; `1024 L` for the series) that costs 0.5–0.7× as
//! much and is never identical to it. The estimate is their difference in `α(T)`, `α̇(T)` and
//! the reversal times (infinite when the reversal counts differ), plus the probed model error for
//! the averaged model, plus the round-off floors (the phase's, and the start's rounding scaled by
//! its measured condition numbers, [`conditioning`], first read on the slow model at a loose
//! tolerance and measured again accurately where they pass [`CONDITIONING_RECHECK`]). The
//! difference bounds
//! the returned run's error whenever the companion's error is at least twice the run's, which
//! holds with a wide margin where the method converges (the companion's is 16× for a 4th-order
//! step, ~14× for a 16× looser tolerance) and fails only at the round-off floor, which the
//! refinement rule detects.
//!
//! **Refinement**, by the one loop (`physics::verify`, as `POLICY` and `TAYLOR` say; the
//! candidate here is `Auto`), until the estimate meets the tolerance: the step or tolerance
//! shrinks by the factor the estimate asks for; an averaged model whose error is too large gives way to the
//! best resolving method. It stops, and says so with `met = false`, when the estimate stops
//! falling (less than halved by a refinement: the round-off floor or an ill-conditioned start;
//! the estimate reached is reported as the floor), at once when the round-off floors alone pass
//! the tolerance (a refinement only adds steps to them), when an adaptive tolerance reaches its
//! 1e-14 clamp, after `POLICY.max_refinements`, or before a refinement predicted to take the total
//! past [`AUTO_SECONDS`] (or the caller's smaller budget).
//!
//! **Far in** (an averaged plan at `k` above the start's conditioning stiffness, where its
//! expansion parameter is [`CONDITIONING_KEPT_X`], stop 51), the start's condition numbers are
//! bounded instead of measured: by its reading at that one stiffness, kept across `k` ([`memo`]),
//! times [`CONDITIONING_KEPT_MARGIN`] (they move with `k`, by up to 21× on the references),
//! wherever that reading is at most [`CONDITIONING_RECHECK`] and the floor the bound gives at
//! most [`CONDITIONING_KEPT_SHARE`] of the tolerance; elsewhere they are measured at `k`. With
//! the reading kept, the verification is the companion alone.
//!
//! **Two cores.** The run, its companion and the condition numbers do not depend on one another,
//! nor do the two probes: [`fork::both`] runs them side by side where the program installed a
//! second core (the binary does: `crate::parallel`), the dearer half on the calling thread. The
//! answer is the same either way, bit for bit; only the wall time differs (issue 27: with the
//! probes and the conditioning's reading kept, 0.8–1.5× the cheapest single run at `auto`'s
//! error, against 1.4–2.5× on one core).
//!
//! The first planner is kept, frozen, in [`legacy`] for the replay of old session files.
//! Pure: no clock; a caller's `go_on` decides about cancellation.
//!
//! [`conditioning`]: fn@conditioning
//! [`fork::both`]: crate::physics::fork::both

pub mod legacy;
pub mod memo;

mod choice;
mod conditioning;
mod measure;
mod probe;
mod resolved;
mod verified;

pub use super::policy::{
    AUTO_SECONDS, AVERAGED, AVERAGED_GROWTH, AVERAGED_MIN_RATIO, BLANES_MOAN_MAX_NU_H, C_BM,
    C_FAST, CONDITIONED_GAIN, CONDITIONING_AVERAGED_LIMIT, CONDITIONING_KEPT_MARGIN,
    CONDITIONING_KEPT_SHARE, CONDITIONING_KEPT_X, CONDITIONING_LOOSE_TOLERANCE, CONDITIONING_MODEL,
    CONDITIONING_RECHECK, CONDITIONING_TOLERANCE, DOP853_GROWTH, MODEL_ORDER, NUDGE,
    PROBE_FULL_METHOD, PROBE_FULL_TOLERANCE, PROBE_RUNGS, PROBE_SAFETY, PROBE_SAMPLES,
    PROBE_TOLERANCE, PROBE_VALIDITY, ROUND_OFF_GAIN, SECOND_ORDER_MODEL_SHARE, TAYLOR_GROWTH,
};
pub use crate::physics::plan::Shortfall;
pub use choice::{Decision, plan, plan_cancellable};
pub use conditioning::{
    Conditioning, conditioning, conditioning_stiffness, slow_condition_numbers,
};
pub use measure::{Plan, conditioned_round_off, difference, round_off};
pub use probe::{
    ModelProbe, averaged_is_exact, considers_averaged, probe_averaged, probe_problem,
    probe_stiffnesses, probes_cost,
};
pub use resolved::best_resolved;
pub use verified::{Verified, run_auto, run_auto_cancellable};
