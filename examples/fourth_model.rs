//! A fourth model through the public seam (issue 57), not shipped: a driven harmonic oscillator
//! `x'' + ω² x = F cos(Ω t)`, whose exact solution is known, with a verified `auto` from the
//! one loop, `physics::verify`. What a model brings is its [`Policy`] (data) and its candidate
//! (one method at a local tolerance, `AtTolerance`: a run, two runs' difference, its rounding
//! floor, the cost of a run); the loop is the library's. `cargo run --example fourth_model` prints each start's choice, estimate and true
//! error, and fails when a claim is false; `cargo test --example fourth_model` checks the same.
//! It touches no file of `src/` (docs/architecture.md, "Adding a model").

use nalgebra::SVector;
use rattleback::physics::fork::GoOn;
use rattleback::physics::method::StepError;
use rattleback::physics::numerics::dop853::Dop853;
use rattleback::physics::verify::{AtTolerance, Policy, Rounds, verify};

type State = SVector<f64, 3>;

/// The problem: `ω`, `F`, `Ω` and the start `(x0, v0)`.
#[derive(Clone, Copy, Debug)]
struct Oscillator {
    omega: f64,
    force: f64,
    drive: f64,
    x0: f64,
    v0: f64,
}

/// Samples of `(x, v)` compared between a run and its companion.
const SAMPLES: usize = 33;

impl Oscillator {
    /// The exact `(x, v)` at `t` (`Ω ≠ ω`).
    fn exact(&self, t: f64) -> (f64, f64) {
        let c = self.force / (self.omega * self.omega - self.drive * self.drive);
        let (a, b) = (self.x0 - c, self.v0 / self.omega);
        let (s, co) = (self.omega * t).sin_cos();
        let (sd, cd) = (self.drive * t).sin_cos();
        (
            a * co + b * s + c * cd,
            self.omega * (b * co - a * s) - c * self.drive * sd,
        )
    }

    /// DOP853 at local tolerance `tol` to `t_end`: `(x, v)` at `SAMPLES + 1` even times, and
    /// the steps taken. The drive's phase is a state (`φ' = Ω`): the field is autonomous.
    fn run(&self, tol: f64, t_end: f64) -> Result<(Vec<(f64, f64)>, u64), StepError> {
        let p = *self;
        let field = move |y: &State| {
            State::new(
                y[1],
                -p.omega * p.omega * y[0] + p.force * y[2].cos(),
                p.drive,
            )
        };
        let mut d = Dop853::new(field, 0.0, State::new(self.x0, self.v0, 0.0), tol);
        let mut out = vec![(self.x0, self.v0)];
        while out.len() <= SAMPLES {
            let at = t_end * out.len() as f64 / SAMPLES as f64;
            while d.time() < at {
                d.step(t_end)?;
            }
            let y = d.interpolate(at);
            out.push((y[0], y[1]));
        }
        Ok((out, d.stats().steps))
    }
}

/// The oscillator's `auto`: DOP853 against a companion 16× looser, as the celt's.
const POLICY: Policy = Policy {
    companion_looser: 16.0,
    companion_cap: 1e-2,
    companion_error: 14.0,
    refine: 0.25,
    blind_refine: 1.0 / 16.0,
    tightest: 1e-14,
    step_safety: 1.25,
    max_refinements: 4,
    stalls: 2,
    floor_stops: true,
};

#[derive(Clone)]
struct Auto {
    problem: Oscillator,
    t_end: f64,
}

impl AtTolerance for Auto {
    type Result = (Vec<(f64, f64)>, u64);
    fn policy(&self) -> &'static Policy {
        &POLICY
    }
    fn run(&self, local: f64, _: GoOn<'_>) -> Result<Self::Result, StepError> {
        self.problem.run(local, self.t_end)
    }
    fn difference(&self, fine: &Self::Result, coarse: &Self::Result) -> f64 {
        fine.0.iter().zip(&coarse.0).fold(0.0_f64, |d, (a, b)| {
            d.max((a.0 - b.0).abs()).max((a.1 - b.1).abs())
        })
    }
    fn floor(&self, fine: &Self::Result) -> f64 {
        let steps = fine.1 as f64;
        f64::EPSILON * steps * (1.0 + self.problem.omega)
    }
    fn run_cost(&self, local: f64) -> f64 {
        // About 3 evaluations a radian at tolerance 1, `tol^{-1/8}`, 50 ns each.
        3.0 * self.problem.omega.max(self.problem.drive) * self.t_end * local.powf(-0.125) * 5e-8
    }
}

/// `auto` at `tolerance`: the local tolerance chosen, its estimate and whether it met.
fn auto(problem: Oscillator, tolerance: f64, t_end: f64) -> Result<(f64, f64, bool), StepError> {
    let mut candidate = Auto { problem, t_end };
    let first = (tolerance * 0.1).clamp(POLICY.tightest, 1e-3);
    let ask = Rounds {
        first,
        tolerance,
        budget: 60.0,
    };
    let v = verify(&mut candidate, ask, &mut |_| true)?;
    Ok((v.last.plan, v.last.estimate, v.shortfall.is_none()))
}

/// Every start at every tolerance: `(what, claimed met, estimate, true error)`.
fn audit() -> Vec<(String, bool, f64, f64)> {
    let starts = [
        (1.0, 0.5, 0.3, 1.0, 0.0, 30.0),
        (10.0, 2.0, 3.0, 0.1, 1.0, 20.0),
        (50.0, 100.0, 7.0, 0.0, 0.0, 5.0),
        (2.0, 0.0, 1.0, 1.0, -1.0, 100.0),
    ];
    let mut out = Vec::new();
    for (omega, force, drive, x0, v0, t_end) in starts {
        let p = Oscillator {
            omega,
            force,
            drive,
            x0,
            v0,
        };
        for tolerance in [1e-6, 1e-8, 1e-10] {
            let (local, estimate, met) = auto(p, tolerance, t_end).expect("a finite run");
            let (x, v) = p.run(local, t_end).expect("the chosen run").0[SAMPLES];
            let (xe, ve) = p.exact(t_end);
            let error = (x - xe).abs().max((v - ve).abs());
            let what = format!("ω {omega} F {force} Ω {drive} T {t_end} at {tolerance:e}");
            out.push((what, met && estimate <= tolerance, estimate, error));
        }
    }
    out
}

/// A claim is false when an estimate is under its run's error (the exact solution's own
/// rounding, 1e-13, aside); a run said met then has an error within its tolerance.
fn false_claims(audit: &[(String, bool, f64, f64)]) -> Vec<String> {
    audit
        .iter()
        .filter(|(_, _, estimate, error)| *error > estimate.max(1e-13))
        .map(|(what, _, estimate, error)| {
            format!("{what}: estimate {estimate:.1e}, error {error:.1e}")
        })
        .collect()
}

fn main() {
    let audit = audit();
    for (what, met, estimate, error) in &audit {
        println!("{what:40} met {met:5}  estimate {estimate:8.1e}  error {error:8.1e}");
    }
    let wrong = false_claims(&audit);
    assert!(wrong.is_empty(), "false claims:\n{}", wrong.join("\n"));
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_fourth_models_auto_keeps_its_claims() {
        let audit = super::audit();
        assert!(
            audit.iter().filter(|a| a.1).count() >= audit.len() / 2,
            "{audit:?}"
        );
        let wrong = super::false_claims(&audit);
        assert!(wrong.is_empty(), "{wrong:?}");
    }
}
