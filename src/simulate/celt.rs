//! `simulate` for the celt: JSON with `params` (the body), `initial`, `final` {`t`, `omega`,
//! `gamma`, `quaternion`, `spin`, `G`, `contact`}, `events` {`reversals`, `crossings`: each
//! {`count`, `times`}, `band`}, `energy` {`initial`, `final`, `max_drift`, `rel_drift`},
//! `constraint` {`gamma_norm_error`, `quat_norm_error`, `contact_height_max`}, `auto`, `stats`;
//! CSV (`t,turn,spin,tilt`) and a table too. The celt has no limit, so there is no
//! `effective` section.

use crate::physics::method::Asked;
use std::fmt::Write as _;
use std::time::Instant;

use serde::Serialize;

use super::render::StatsOut;
use super::{Failure, Format, Missed, Resolved, compact, times};
use crate::physics::Method;
use crate::physics::StepError;
use crate::physics::celt::run::{self, RunResult, RunSpec};
use crate::physics::celt::{self, Problem};
use crate::physics::plan::{AutoPolicy, PlanRequest, Shortfall};
use crate::scenario::Preset;

/// Predicted seconds of the run `spec` asks for (the celt's cost model, [`celt::budget`]).
#[must_use]
pub fn predicted_seconds(problem: &Problem, spec: &crate::physics::rattleback::RunSpec) -> f64 {
    celt::budget::cost_seconds(
        problem,
        &Asked::new(spec.method, spec.tolerance, None, spec.t_end),
    )
}

#[derive(Serialize)]
struct Report {
    #[serde(flatten)]
    head: super::Head<celt::Params, celt::Start, AutoOut>,
    t_end: f64,
    /// The chirality of the body: the turn of the principal axes from the long axis (degrees).
    skew_degrees: f64,
    #[serde(rename = "final")]
    final_: FinalOut,
    events: EventsOut,
    energy: EnergyOut,
    constraint: ConstraintOut,
    stats: StatsOut,
}

#[derive(Serialize)]
struct AutoOut {
    choice: Method,
    reason: String,
    /// The local tolerance the chosen run was integrated at.
    tolerance: f64,
    /// The verified error of the spin and the final ω (rad/s).
    error_estimate: f64,
    met: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    shortfall: Option<Shortfall>,
}

impl super::Account for AutoOut {
    fn account(&self) -> (bool, f64, Option<Shortfall>) {
        (self.met, self.error_estimate, self.shortfall)
    }
}

#[derive(Serialize)]
#[allow(non_snake_case)]
struct FinalOut {
    t: f64,
    omega: [f64; 3],
    gamma: [f64; 3],
    quaternion: [f64; 4],
    /// `ω·γ`.
    spin: f64,
    /// The mass centre in space.
    G: [f64; 3],
    /// The contact point in space.
    contact: [f64; 3],
}

#[derive(Serialize)]
struct Times {
    count: usize,
    times: Vec<f64>,
}

#[derive(Serialize)]
struct EventsOut {
    /// The spin at `t = 0`.
    spin_initial: f64,
    /// Reversals: the spin reached the band with the opposite sign (time: the last crossing).
    reversals: Times,
    /// Every sign change of the spin.
    crossings: Times,
    /// The hysteresis band (rad/s).
    band: f64,
}

#[derive(Serialize)]
struct EnergyOut {
    initial: f64,
    #[serde(rename = "final")]
    final_: f64,
    /// Largest `|E − E(0)|` over accepted steps.
    max_drift: f64,
    /// `max_drift / |E(0)|`.
    rel_drift: f64,
}

#[derive(Serialize)]
struct ConstraintOut {
    gamma_norm_error: f64,
    quat_norm_error: f64,
    contact_height_max: f64,
}

impl super::Finite for RunResult {
    fn named_numbers(&self) -> Vec<(&'static str, f64)> {
        let state = self.state.iter().map(|&x| ("the state", x));
        let energy = [self.energy_final, self.max_energy_drift].map(|e| ("the energy", e));
        state.chain(energy).collect()
    }

    fn reached(&self) -> f64 {
        self.t
    }
}

/// The concrete run of `resolved`, with `auto`'s account.
fn plan_of(
    problem: &Problem,
    resolved: &Resolved,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunSpec, Option<AutoOut>), StepError> {
    let spec = resolved.spec;
    let mut run = RunSpec {
        method: spec.method,
        tolerance: spec.tolerance,
        t_end: spec.t_end,
        samples: spec.samples,
    };
    if spec.method != Method::Auto {
        return Ok((run, None));
    }
    let ask = PlanRequest {
        method: Method::Auto,
        tolerance: spec.tolerance,
        t_end: spec.t_end,
        policy: AutoPolicy::Verified,
        budget: resolved.budget,
    };
    let r = celt::plan::resolve(problem, &ask, progress)?;
    run.method = r.plan.method;
    run.tolerance = r.plan.tolerance;
    let estimate = r.estimate.unwrap_or(f64::INFINITY);
    let met = r.shortfall.is_none();
    let reason = if met {
        format!(
            "dop853 at local tolerance {:.1e}, verified against a run 16x looser",
            r.plan.tolerance
        )
    } else {
        format!(
            "dop853 at local tolerance {:.1e}; the tolerance was not reached: {}",
            r.plan.tolerance,
            r.shortfall.map_or("", Shortfall::describe)
        )
    };
    Ok((
        run,
        Some(AutoOut {
            choice: r.plan.method,
            reason,
            tolerance: r.plan.tolerance,
            error_estimate: estimate,
            met,
            shortfall: r.shortfall,
        }),
    ))
}

/// Runs the celt's preset and writes the report.
///
/// # Errors
/// As [`super::simulate_to`].
pub fn simulate_to(
    preset: &Preset,
    problem: &Problem,
    resolved: &Resolved,
    format: Format,
    out: &mut dyn std::io::Write,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Option<Missed>, Failure> {
    let (spec, auto) = plan_of(problem, resolved, progress)?;
    let missed = auto
        .as_ref()
        .and_then(|a| super::Account::missed(a, resolved.spec.tolerance));
    let clock = Instant::now();
    let result = run::run(problem, &spec, progress).and_then(super::Finite::finite)?;
    let wall_seconds = clock.elapsed().as_secs_f64();
    if format == Format::Csv {
        let head = super::csv_head(preset, resolved, spec.method, spec.t_end);
        out.write_all(head.as_bytes())?;
        out.write_all(b"t,turn,spin,tilt\n")?;
        for s in &result.samples {
            writeln!(out, "{},{},{},{}", s.t, s.turn, s.spin, s.tilt)?;
        }
        out.flush()?;
        return Ok(missed);
    }
    let y = result.state;
    let pose = problem.pose(&y);
    let e0 = result.energy_initial;
    let report = Report {
        head: super::Head::new(
            preset,
            (*problem.params(), *problem.start()),
            resolved,
            auto,
            |a| a.choice,
        ),
        t_end: spec.t_end,
        skew_degrees: problem.params().skew().to_degrees(),
        final_: FinalOut {
            t: result.t,
            omega: [y[0], y[1], y[2]],
            gamma: [y[3], y[4], y[5]],
            quaternion: celt::quaternion(&y),
            spin: celt::spin(&y),
            G: pose.g,
            contact: pose.contact,
        },
        events: EventsOut {
            spin_initial: celt::spin(&problem.initial_state()),
            reversals: Times {
                count: result.reversal_count,
                times: result.reversals.clone(),
            },
            crossings: Times {
                count: result.crossing_count,
                times: result.crossings.clone(),
            },
            band: problem.band(),
        },
        energy: EnergyOut {
            initial: e0,
            final_: result.energy_final,
            max_drift: result.max_energy_drift,
            rel_drift: result.max_energy_drift / e0.abs().max(f64::MIN_POSITIVE),
        },
        constraint: ConstraintOut {
            gamma_norm_error: result.gamma_norm_error,
            quat_norm_error: result.quat_norm_error,
            contact_height_max: result.contact_height_max,
        },
        stats: StatsOut::of(&result.stats, wall_seconds),
    };
    let text = super::render::text(format, &report, || table(&report));
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(missed)
}

fn triple(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.9}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn table(r: &Report) -> String {
    let mut o = String::new();
    let p = &r.head.params;
    let s = &r.head.initial;
    let _ = writeln!(
        o,
        "preset        {} (classical rattleback, celt)",
        r.head.preset
    );
    let _ = writeln!(
        o,
        "body          a, b, c = {}, {}, {} cm, offset {} cm, inertia {}, {}, {}, product {} cm^2, g = {}",
        p.a, p.b, p.c, p.offset, p.ix, p.iy, p.iz, p.product, p.gravity
    );
    let _ = writeln!(
        o,
        "              skew of the principal axes {:+.3} deg",
        r.skew_degrees
    );
    let _ = writeln!(
        o,
        "start         roll {}, pitch {}, yaw {} rad; omega = ({}, {}, {}) rad/s",
        s.roll, s.pitch, s.yaw, s.omega[0], s.omega[1], s.omega[2]
    );
    super::render::method_lines(
        &mut o,
        (r.head.method, r.head.tolerance, None),
        &compact(r.t_end),
        r.head.auto.as_ref().map(|a| super::render::Choice {
            method: a.choice,
            reason: &a.reason,
            error_estimate: a.error_estimate,
            met: a.met,
        }),
    );
    let f = &r.final_;
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "spin(T)       {:.9} rad/s (from {:.9})",
        f.spin, r.events.spin_initial
    );
    let _ = writeln!(o, "omega(T)      {}", triple(&f.omega));
    let _ = writeln!(o, "gamma(T)      {}", triple(&f.gamma));
    let _ = writeln!(
        o,
        "reversals     {:>6}    (band {} rad/s) at {}",
        r.events.reversals.count,
        r.events.band,
        times(&r.events.reversals.times)
    );
    let _ = writeln!(
        o,
        "crossings     {:>6}    at {}",
        r.events.crossings.count,
        times(&r.events.crossings.times)
    );
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "energy        {:.12} (drift {:.2e}, relative {:.2e})",
        r.energy.initial, r.energy.max_drift, r.energy.rel_drift
    );
    let c = &r.constraint;
    let _ = writeln!(
        o,
        "constraints   |gamma| - 1 {:.1e}, |q| - 1 {:.1e}, contact height {:.1e} cm",
        c.gamma_norm_error, c.quat_norm_error, c.contact_height_max
    );
    super::render::work_line(&mut o, &r.stats);
    o
}
