//! The rattleback's report: its JSON sections (a contract), its CSV and its table, on top of
//! the shared head and accounts (`physics::report`), as the other scenes' (`kapitza/report.rs`,
//! `celt/report.rs`).

use std::fmt::Write as _;

use serde::Serialize;

use crate::physics::StepError;
use crate::physics::method::RunSpec;
use crate::physics::method::{Asked, Method};
use crate::physics::rattleback::auto::{Shortfall, run_auto_cancellable};
use crate::physics::rattleback::averaged::Averaged2;
use crate::physics::rattleback::budget::cost_seconds;
use crate::physics::rattleback::effective::{Effective, tapping_acceleration};
use crate::physics::rattleback::model::{ALPHA, ALPHA_DOT, GAMMA, GAMMA_DOT, energy};
use crate::physics::rattleback::run::{RunResult, run_cancellable, run_streaming};
use crate::physics::rattleback::{Problem, plan};
use crate::physics::report::{
    Account, Ask, Failure, Finite, Format, Head, Host, Missed, Resolved, Times, energy_bound, opt,
    render, times, warn_drift,
};

/// Predicted seconds of the run `spec` asks for, and of the limit's run the report compares it
/// with (the streamed CSV of `auto` skips its verification's share).
pub(super) fn predicted_seconds(problem: &Problem, spec: &RunSpec, format: Format) -> f64 {
    let main = plan::predicted_seconds(problem, &spec.asked());
    let extra = match format {
        Format::Csv if spec.method == Method::Auto => main / (1.0 + plan::VERIFY_FRACTION),
        Format::Csv => 0.0,
        Format::Json | Format::Table => cost_seconds(
            problem,
            &Asked::new(Method::Effective, spec.tolerance, None, spec.t_end),
        ),
    };
    main + extra
}

#[derive(Serialize)]
struct Report {
    #[serde(flatten)]
    head: Head<ParamsOut, crate::physics::rattleback::Start, AutoOut>,
    step: Option<f64>,
    t_end: f64,
    #[serde(rename = "final")]
    final_: FinalOut,
    reversals: Times,
    energy: EnergyOut,
    effective: EffectiveOut,
    #[serde(skip_serializing_if = "Option::is_none")]
    averaged: Option<AveragedOut>,
    stats: render::StatsOut,
}

#[derive(Serialize)]
struct AutoOut {
    choice: Method,
    reason: String,
    tolerance: f64,
    step: Option<f64>,
    predicted_error: f64,
    /// Bounds the error of `α(T)`, `α̇(T)` and the reversal times (model error included),
    /// unless `met` is false.
    error_estimate: f64,
    /// Whether `error_estimate` meets the requested tolerance.
    met: bool,
    /// Why not (`floor`, `clamped`, `refinements`, `time`), or null.
    shortfall: Option<Shortfall>,
    /// The averaged model's probed error included in the estimate (0 for a resolved run).
    model_error: f64,
    refinements: u32,
    /// The start's condition numbers (`rate`: per relative change of the spin rate; `angle`:
    /// per radian of the spin angle) that scale the round-off floor in `error_estimate`, times
    /// `margin` (1 where measured at this `k`; 50 where bounded by the start's reading at its
    /// conditioning stiffness, kept across `k`).
    condition: crate::physics::rattleback::auto::Conditioning,
    /// The part of `error_estimate` that rounding alone sets (no refinement lowers it; above
    /// the tolerance, `auto` stops after its first run with `shortfall = floor`).
    round_off_floor: f64,
}

/// The averaged model's own account of the start (method `averaged2` or `averaged3`, or `auto`
/// choosing one): the second-order account, good to O(k⁻²), for either.
#[derive(Serialize)]
struct AveragedOut {
    /// The averaged fast action `Ī`, an exact constant of the averaged motion.
    ibar: f64,
    /// `θ̄ = Ī √k`.
    theta_bar: f64,
    /// The averaged Hamiltonian `K̄` of the start.
    kbar: f64,
    regime: &'static str,
    /// Averaged time between turning points (trapped starts).
    half_period: Option<f64>,
}

impl AveragedOut {
    fn of(problem: &crate::physics::rattleback::Problem) -> Self {
        let (m, y0) = Averaged2::new(problem);
        Self {
            ibar: m.ibar(),
            theta_bar: m.theta_bar(),
            kbar: m.kbar(y0[0], y0[1]),
            regime: m.regime(&y0).name(),
            half_period: m.half_period(&y0),
        }
    }
}

impl Account for AutoOut {
    /// Met exactly when there is no shortfall.
    fn account(&self) -> (bool, f64, Option<Shortfall>) {
        (
            self.shortfall.is_none(),
            self.error_estimate,
            self.shortfall,
        )
    }

    fn choice(&self) -> render::Choice<'_> {
        render::Choice::new(self.choice, &self.reason, self.error_estimate, self.met)
    }

    fn floor(&self) -> Option<f64> {
        Some(self.round_off_floor)
    }
}

#[derive(Serialize)]
struct ParamsOut {
    ix: f64,
    iy: f64,
    iz: f64,
    k: f64,
}

#[derive(Serialize)]
struct FinalOut {
    t: f64,
    gamma: f64,
    alpha: f64,
    gamma_dot: f64,
    alpha_dot: f64,
}

#[derive(Serialize)]
struct EnergyOut {
    initial: f64,
    #[serde(rename = "final")]
    final_: f64,
    max_relative_error: f64,
    /// Whether the energy drifted past what the method's tolerance promises (see
    /// [`energy_bound`]): the run is not to be trusted, and stderr says so.
    exceeds_bound: bool,
}

impl EnergyOut {
    fn of(result: &crate::physics::rattleback::RunResult, tolerance: f64) -> Self {
        Self {
            initial: result.energy_initial,
            final_: result.energy_final,
            max_relative_error: result.max_relative_energy_error,
            exceeds_bound: result.max_relative_energy_error > energy_bound(tolerance),
        }
    }
}

/// Says on stderr that a run's energy drifted past [`energy_bound`].
fn warn_energy(host: &dyn Host, energy: &EnergyOut, tolerance: f64) {
    if energy.exceeds_bound {
        warn_drift(
            host,
            "the energy",
            energy.max_relative_error,
            energy_bound(tolerance),
            tolerance,
        );
    }
}

#[derive(Serialize)]
struct EffectiveOut {
    theta: f64,
    regime: &'static str,
    critical_ratio: Option<f64>,
    start_ratio: Option<f64>,
    energy: f64,
    /// The limit's own `α(T)`; `null` only when its comparison run failed (`comparison_error`).
    alpha: Option<f64>,
    /// The limit's own `α̇(T)`, likewise.
    alpha_dot: Option<f64>,
    /// Why the comparison with the limit could not be made (the requested run succeeded).
    #[serde(skip_serializing_if = "Option::is_none")]
    comparison_error: Option<String>,
    half_period: Option<f64>,
    turning_points: Option<(f64, f64)>,
    tapping_acceleration: f64,
    reversals: Times,
}

/// The rattleback's report (see [`simulate_to`]).
pub(super) fn simulate_to(
    problem: &crate::physics::rattleback::Problem,
    mut ask: Ask<'_>,
) -> Result<Option<Missed>, Failure> {
    let resolved = ask.resolved;
    let spec = resolved.spec;
    let start = ask.host.seconds();
    if ask.format == Format::Csv {
        let (result, shortfall) = csv(ask.host, problem, resolved, ask.out, ask.progress)?;
        result.finite()?;
        ask.out.flush()?;
        return Ok(shortfall);
    }
    let (result, auto) = requested_run(problem, resolved, ask.progress)?;
    let result = result.finite()?;
    let wall_seconds = ask.host.seconds() - start;
    // The limit's own trajectory at t_end, for comparison (cheap: cost independent of k).
    let eff_spec = RunSpec {
        method: Method::Effective,
        tolerance: crate::physics::ModelKind::Rattleback.limit_tolerance(),
        samples: 0,
        monitor_energy: true,
        step: None,
        ..spec
    };
    // A failure of this extra comparison does not discard the requested run: it is reported.
    let eff_run = run_cancellable(problem, &eff_spec, ask.progress).and_then(Finite::finite);
    let eff = Effective::new(problem);
    let p = problem.params();
    let y = result.final_state;
    let ran = auto.as_ref().map_or(spec.method, |a| a.choice);
    let averaged = ran.is_averaged().then(|| AveragedOut::of(problem));
    let shortfall = auto.as_ref().and_then(|a| a.missed(spec.tolerance));
    let step = auto.as_ref().map_or(spec.step, |a| a.step);
    let params = ParamsOut {
        ix: p.ix,
        iy: p.iy,
        iz: p.iz,
        k: p.k,
    };
    let report = Report {
        head: ask.head((params, *problem.start()), auto),
        step,
        t_end: spec.t_end,
        final_: FinalOut {
            t: result.t,
            gamma: y[GAMMA],
            alpha: y[ALPHA],
            gamma_dot: y[GAMMA_DOT],
            alpha_dot: y[ALPHA_DOT],
        },
        reversals: Times::of(&result.reversals, result.reversal_count),
        energy: EnergyOut::of(&result, spec.tolerance),
        effective: EffectiveOut {
            theta: eff.theta(),
            regime: eff.regime().name(),
            critical_ratio: eff.critical_ratio(problem),
            start_ratio: eff.start_ratio(problem),
            energy: eff.energy(),
            alpha: eff_run.as_ref().ok().map(|r| r.final_state[ALPHA]),
            alpha_dot: eff_run.as_ref().ok().map(|r| r.final_state[ALPHA_DOT]),
            comparison_error: eff_run.as_ref().err().map(ToString::to_string),
            half_period: eff.half_period(),
            turning_points: eff.turning_points(),
            tapping_acceleration: tapping_acceleration(problem),
            reversals: Times::of(
                &eff.reversal_times(spec.t_end),
                eff.reversal_count(spec.t_end),
            ),
        },
        averaged,
        stats: render::StatsOut::of(&result.stats, wall_seconds),
    };
    warn_energy(ask.host, &report.energy, spec.tolerance);
    ask.write(&report, table)?;
    Ok(shortfall)
}

/// The requested run, and `auto`'s account of it.
fn requested_run(
    problem: &crate::physics::rattleback::Problem,
    resolved: &Resolved,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunResult, Option<AutoOut>), StepError> {
    let spec = resolved.spec;
    if spec.method != Method::Auto {
        return Ok((run_cancellable(problem, &spec, progress)?, None));
    }
    let v = run_auto_cancellable(problem, &spec, resolved.budget, progress)?;
    let auto = AutoOut {
        choice: v.plan.method,
        reason: v.plan.reason.clone(),
        tolerance: v.plan.tolerance,
        step: v.plan.step,
        predicted_error: v.plan.predicted_error,
        error_estimate: v.error_estimate,
        met: v.met,
        shortfall: v.shortfall,
        model_error: v.model_error,
        refinements: v.refinements,
        condition: v.condition,
        round_off_floor: v.round_off_floor,
    };
    Ok((v.result, Some(auto)))
}

/// Streams the CSV: `auto` is planned and verified first (no samples), then its plan is run
/// again with the samples, which gives the verified run bit for bit.
fn csv(
    host: &dyn Host,
    problem: &crate::physics::rattleback::Problem,
    resolved: &Resolved,
    out: &mut dyn std::io::Write,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<(RunResult, Option<Missed>), Failure> {
    let mut spec = resolved.spec;
    let mut shortfall = None;
    if spec.method == Method::Auto {
        let resolution = plan::resolve(
            problem,
            spec.method,
            spec.tolerance,
            spec.t_end,
            crate::physics::plan::AutoRules::Verified,
            resolved.budget,
            progress,
        )?;
        shortfall = resolution.shortfall.map(|why| Missed {
            estimate: resolution.estimate.unwrap_or(f64::NAN),
            tolerance: spec.tolerance,
            why,
            floor: resolution.floor,
        });
        let plan = resolution.plan;
        spec.method = plan.method;
        spec.tolerance = plan.tolerance;
        spec.step = plan.step;
    }
    let p = problem.params();
    out.write_all(host.csv_head(spec.method, spec.t_end).as_bytes())?;
    out.write_all(b"t,gamma,alpha,gamma_dot,alpha_dot,energy\n")?;
    let mut failure: Option<Failure> = None;
    let result = run_streaming(problem, &spec, progress, &mut |s| {
        let y = s.state;
        let e = energy(p, &y);
        if let Some(i) = y.iter().position(|x| !x.is_finite()) {
            failure = Some(
                StepError::NotFinite {
                    what: STATE_NAMES[i],
                    t: s.t,
                }
                .into(),
            );
            return false;
        }
        match writeln!(
            out,
            "{},{},{},{},{},{}",
            s.t, y[GAMMA], y[ALPHA], y[GAMMA_DOT], y[ALPHA_DOT], e
        ) {
            Ok(()) => true,
            Err(err) => {
                failure = Some(err.into());
                false
            }
        }
    });
    match (result, failure) {
        (_, Some(f)) => Err(f),
        (r, None) => Ok((r?, shortfall)),
    }
}

fn table(r: &Report) -> String {
    let mut o = String::new();
    let e = &r.effective;
    let _ = writeln!(o, "preset        {}", r.head.preset_line);
    let _ = writeln!(
        o,
        "body          ix = {}, iy = {}, iz = {}, k = {:e}",
        r.head.params.ix, r.head.params.iy, r.head.params.iz, r.head.params.k
    );
    let _ = writeln!(
        o,
        "start         gamma = {}, alpha = {}, gamma_dot = {}, alpha_dot = {}",
        r.head.initial.gamma,
        r.head.initial.alpha,
        r.head.initial.gamma_dot,
        r.head.initial.alpha_dot
    );
    r.head.method_lines(&mut o, r.step, &r.t_end.to_string());
    render::compare_rows(
        &mut o,
        "effective (k → ∞)",
        crate::physics::ModelKind::Rattleback.words(),
        (r.final_.alpha, r.final_.alpha_dot),
        (e.alpha, e.alpha_dot),
        e.comparison_error.as_deref(),
    );
    let _ = writeln!(
        o,
        "reversals     {:>16}    {:>16}",
        r.reversals.count, e.reversals.count
    );
    let _ = writeln!(o, "  full at      {}", times(&r.reversals.times));
    let _ = writeln!(o, "  limit at     {}", times(&e.reversals.times));
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "regime        {} (ratio {} vs critical {})",
        e.regime,
        opt(e.start_ratio),
        opt(e.critical_ratio)
    );
    let _ = writeln!(o, "theta         {:.12}", e.theta);
    let _ = writeln!(o, "half period   {}", opt(e.half_period));
    // `+ 0.0` prints a negative zero as 0.
    let _ = writeln!(o, "tapping acc.  {:.9}", e.tapping_acceleration + 0.0);
    let _ = writeln!(
        o,
        "energy        {:.12} (max relative error {:.2e})",
        r.energy.initial, r.energy.max_relative_error
    );
    render::work_line(&mut o, &r.stats);
    o
}

const STATE_NAMES: [&str; 4] = ["gamma", "alpha", "gamma_dot", "alpha_dot"];

impl Finite for RunResult {
    fn named_numbers(&self) -> (f64, Vec<(&'static str, f64)>) {
        let state = STATE_NAMES
            .into_iter()
            .zip(self.final_state.iter().copied());
        let energy = [self.energy_final, self.max_relative_energy_error].map(|e| ("the energy", e));
        let reversals = self.reversals.iter().map(|&t| ("a reversal time", t));
        (self.t, state.chain(energy).chain(reversals).collect())
    }
}

impl crate::physics::report::Report for Problem {
    fn predicted_seconds(&self, spec: &RunSpec, format: Format) -> f64 {
        predicted_seconds(self, spec, format)
    }

    fn simulate_to(&self, ask: Ask<'_>) -> Result<Option<Missed>, Failure> {
        simulate_to(self, ask)
    }
}
