//! `simulate` for the celt: JSON with `params` (the body), `initial`, `final` {`t`, `omega`,
//! `gamma`, `quaternion`, `spin`, `G`, `contact`}, `events` {`reversals`, `crossings`: each
//! {`count`, `times`}, `band`}, `energy` {`initial`, `final`, `max_drift`, `rel_drift`},
//! `constraint` {`gamma_norm_error`, `quat_norm_error`, `contact_height_max`}, `auto`, `stats`;
//! CSV (`t,turn,spin,tilt`) and a table too. The celt has no limit, so there is no
//! `effective` section.

use crate::physics::method::Asked;
use std::fmt::Write as _;

use serde::Serialize;

use crate::physics::celt::run::{self, RunResult};
use crate::physics::celt::{self, Problem};
use crate::physics::method::RunSpec;
use crate::physics::plan::Shortfall;
use crate::physics::report::{
    Ask, Failure, Finite, Format, Head, Missed, PlannedOut, Resolved, Times, compact, energy_bound,
    render, times, warn_drift,
};

/// Predicted seconds of the run `spec` asks for (the celt's cost model, [`celt::budget`]).
#[must_use]
pub fn predicted_seconds(problem: &Problem, spec: &crate::physics::method::RunSpec) -> f64 {
    celt::budget::cost_seconds(
        problem,
        &Asked::new(spec.method, spec.tolerance, None, spec.t_end),
    )
}

#[derive(Serialize)]
struct Report {
    #[serde(flatten)]
    head: Head<celt::Params, celt::Start, AutoOut>,
    t_end: f64,
    /// The chirality of the body: the turn of the principal axes from the long axis (degrees).
    skew_degrees: f64,
    #[serde(rename = "final")]
    final_: FinalOut,
    events: EventsOut,
    energy: EnergyOut,
    constraint: ConstraintOut,
    stats: render::StatsOut,
}

/// `auto`'s account: the celt adds nothing of its own (`error_estimate` is the verified error of
/// the spin and the final ω, rad/s).
type AutoOut = PlannedOut<NoExtra>;

#[derive(Serialize)]
struct NoExtra {}

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

/// The energy: `max_drift` the largest `|E − E(0)|` over accepted steps, `rel_drift` that over
/// `|E(0)|`.
type EnergyOut = render::DriftOut;

#[derive(Serialize)]
struct ConstraintOut {
    gamma_norm_error: f64,
    quat_norm_error: f64,
    contact_height_max: f64,
}

impl Finite for RunResult {
    fn named_numbers(&self) -> (f64, Vec<(&'static str, f64)>) {
        let state = self.state.iter().map(|&x| ("the state", x));
        let energy = [self.energy_final, self.max_energy_drift].map(|e| ("the energy", e));
        (self.t, state.chain(energy).collect())
    }
}

/// Resolves `auto` into `run`, and gives its account.
fn plan_auto(
    problem: &Problem,
    resolved: &Resolved,
    run: &mut RunSpec,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<AutoOut, crate::physics::StepError> {
    let r = celt::plan::resolve(problem, &resolved.auto_request(), progress)?;
    let local = r.plan.tolerance;
    let reason = |met: bool| {
        if met {
            format!("dop853 at local tolerance {local:.1e}, verified against a run 16x looser")
        } else {
            format!(
                "dop853 at local tolerance {local:.1e}; the tolerance was not reached: {}",
                r.shortfall.map_or("", Shortfall::describe)
            )
        }
    };
    Ok(AutoOut::of(&r, run, reason, NoExtra {}))
}

/// Runs the celt's preset and writes the report.
///
/// # Errors
/// The celt's report (`simulate`).
pub(super) fn simulate_to(problem: &Problem, mut ask: Ask<'_>) -> Result<Option<Missed>, Failure> {
    let ran = ask.plan_and_run(
        (
            problem,
            RunSpec {
                step: None,
                ..ask.resolved.spec
            },
        ),
        plan_auto,
        run::run,
    )?;
    let (spec, result) = (ran.spec, ran.result);
    // Nothing dissipates: the energy is conserved, and its drift says what the rattleback's
    // says (issue 56).
    let drift = result.max_energy_drift / result.energy_initial.abs().max(f64::MIN_POSITIVE);
    let bound = energy_bound(spec.tolerance);
    if drift.is_nan() || drift > bound {
        warn_drift(ask.host, "the energy", drift, bound, spec.tolerance);
    }
    if ask.format == Format::Csv {
        let head = ask.csv_head(spec.method, spec.t_end);
        ask.out.write_all(head.as_bytes())?;
        ask.out.write_all(b"t,turn,spin,tilt\n")?;
        for s in &result.samples {
            writeln!(ask.out, "{},{},{},{}", s.t, s.turn, s.spin, s.tilt)?;
        }
        ask.out.flush()?;
        return Ok(ran.missed);
    }
    let y = result.state;
    let pose = problem.pose(&y);
    let e0 = result.energy_initial;
    let report = Report {
        head: ask.head((*problem.params(), *problem.start()), ran.auto),
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
            reversals: Times::of(&result.reversals, result.reversal_count),
            crossings: Times::of(&result.crossings, result.crossing_count),
            band: problem.band(),
        },
        energy: EnergyOut {
            initial: e0,
            final_: result.energy_final,
            max_drift: result.max_energy_drift,
            rel_drift: Some(result.max_energy_drift / e0.abs().max(f64::MIN_POSITIVE)),
        },
        constraint: ConstraintOut {
            gamma_norm_error: result.gamma_norm_error,
            quat_norm_error: result.quat_norm_error,
            contact_height_max: result.contact_height_max,
        },
        stats: render::StatsOut::of(&result.stats, ran.wall_seconds),
    };
    ask.write(&report, table)?;
    Ok(ran.missed)
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
        r.head.preset_line
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
    r.head.method_lines(&mut o, None, &compact(r.t_end));
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
        r.energy.initial,
        r.energy.max_drift,
        r.energy.rel_drift.unwrap_or(f64::NAN)
    );
    let c = &r.constraint;
    let _ = writeln!(
        o,
        "constraints   |gamma| - 1 {:.1e}, |q| - 1 {:.1e}, contact height {:.1e} cm",
        c.gamma_norm_error, c.quat_norm_error, c.contact_height_max
    );
    render::work_line(&mut o, &r.stats);
    o
}

impl crate::physics::report::Report for Problem {
    fn predicted_seconds(&self, spec: &RunSpec, _format: Format) -> f64 {
        predicted_seconds(self, spec)
    }

    fn simulate_to(&self, ask: Ask<'_>) -> Result<Option<Missed>, Failure> {
        simulate_to(self, ask)
    }
}
