//! `rattleback simulate`: one headless trajectory, reported as JSON, CSV or a table.
//!
//! The report's field names are a contract (scripts read them): add freely, rename nothing.

use std::fmt::Write as _;
use std::time::Instant;

use serde::Serialize;

use crate::physics::auto::run_auto;
use crate::physics::effective::{Effective, tapping_acceleration};
use crate::physics::integrators::{Method, default_step};
use crate::physics::model::energy;
use crate::physics::run::RunResult;
use crate::physics::{RunSpec, StepError, run};
use crate::scenario::Preset;

/// Tolerance when neither the command line nor the preset gives one.
pub const DEFAULT_TOLERANCE: f64 = crate::physics::DEFAULT_TOLERANCE;
/// Method when neither the command line nor the preset names one.
pub const DEFAULT_METHOD: Method = Method::Auto;

/// Output format of `simulate`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// One JSON object.
    Json,
    /// The sampled trajectory as CSV.
    Csv,
    /// A summary for people.
    Table,
}

/// What the command line asks of one run (each absent value falls back to the preset).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Request {
    /// Method.
    pub method: Option<Method>,
    /// Tolerance.
    pub tolerance: Option<f64>,
    /// Fixed step.
    pub step: Option<f64>,
    /// Final time.
    pub t_end: Option<f64>,
    /// Output format.
    pub format: Format,
    /// Samples of the CSV output.
    pub samples: u32,
}

/// The resolved settings of one run.
#[derive(Clone, Copy, Debug)]
pub struct Resolved {
    /// Run settings.
    pub spec: RunSpec,
}

/// Combines the preset's `[run]` section with command-line flags (flags win).
#[must_use]
pub fn resolve(preset: &Preset, args: &Request) -> Resolved {
    let method = args.method.or(preset.run.method).unwrap_or(DEFAULT_METHOD);
    let tolerance = args
        .tolerance
        .or(preset.run.tolerance)
        .unwrap_or(DEFAULT_TOLERANCE);
    let t_end = args.t_end.unwrap_or(preset.run.t_end);
    let step = if method.is_fixed_step() {
        Some(
            args.step
                .or(preset.run.step)
                .unwrap_or_else(|| default_step(method, &preset.problem, tolerance, t_end)),
        )
    } else {
        None
    };
    let samples = if args.format == Format::Csv {
        args.samples as usize
    } else {
        0
    };
    Resolved {
        spec: RunSpec {
            method,
            tolerance,
            step,
            t_end,
            samples,
            monitor_energy: true,
        },
    }
}

#[derive(Serialize)]
struct Report {
    preset: String,
    params: ParamsOut,
    initial: crate::physics::Start,
    method: Method,
    /// With `method = auto`: the method it chose (also in `auto.choice`).
    #[serde(skip_serializing_if = "Option::is_none")]
    auto_choice: Option<Method>,
    #[serde(skip_serializing_if = "Option::is_none")]
    auto: Option<AutoOut>,
    tolerance: f64,
    step: Option<f64>,
    t_end: f64,
    #[serde(rename = "final")]
    final_: FinalOut,
    reversals: Reversals,
    energy: EnergyOut,
    effective: EffectiveOut,
    stats: StatsOut,
}

#[derive(Serialize)]
struct AutoOut {
    choice: Method,
    reason: String,
    tolerance: f64,
    step: Option<f64>,
    predicted_error: f64,
    error_estimate: f64,
    refinements: u32,
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
struct Reversals {
    count: usize,
    times: Vec<f64>,
}

impl Reversals {
    fn of(times: Vec<f64>) -> Self {
        Self {
            count: times.len(),
            times,
        }
    }
}

#[derive(Serialize)]
struct EnergyOut {
    initial: f64,
    #[serde(rename = "final")]
    final_: f64,
    max_relative_error: f64,
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
    reversals: Reversals,
}

#[derive(Serialize)]
struct StatsOut {
    steps: u64,
    rejected: u64,
    rhs_evaluations: u64,
    wall_seconds: f64,
}

/// Runs `preset` as `resolved` says and renders the report in `format`.
///
/// # Errors
/// When the integration fails (non-finite state, step underflow).
///
/// # Panics
/// Never in practice: the report holds only finite numbers and strings, which serialize.
pub fn simulate(preset: &Preset, resolved: &Resolved, format: Format) -> Result<String, StepError> {
    let problem = &preset.problem;
    let spec = resolved.spec;
    let clock = Instant::now();
    let (result, auto) = if spec.method == Method::Auto {
        let v = run_auto(problem, spec.tolerance, spec.t_end, spec.samples, true)?;
        let auto = AutoOut {
            choice: v.plan.method,
            reason: v.plan.reason.clone(),
            tolerance: v.plan.tolerance,
            step: v.plan.step,
            predicted_error: v.plan.predicted_error,
            error_estimate: v.error_estimate,
            refinements: v.refinements,
        };
        (v.result, Some(auto))
    } else {
        (run(problem, &spec)?, None)
    };
    if let Some(what) = non_finite(&result) {
        return Err(StepError::NotFinite { what, t: result.t });
    }
    let wall_seconds = clock.elapsed().as_secs_f64();
    if format == Format::Csv {
        return Ok(csv(preset, &result));
    }
    // The limit's own trajectory at t_end, for comparison (cheap: cost independent of k).
    let eff_spec = RunSpec {
        method: Method::Effective,
        samples: 0,
        monitor_energy: true,
        step: None,
        ..spec
    };
    // A failure of this extra comparison does not discard the requested run: it is reported.
    let eff_run = run(problem, &eff_spec).and_then(|r| match non_finite(&r) {
        Some(what) => Err(StepError::NotFinite { what, t: r.t }),
        None => Ok(r),
    });
    let eff = Effective::new(problem);
    let p = problem.params();
    let y = result.final_state;
    let report = Report {
        preset: preset.name.clone(),
        params: ParamsOut {
            ix: p.ix,
            iy: p.iy,
            iz: p.iz,
            k: p.k,
        },
        initial: *problem.start(),
        method: spec.method,
        auto_choice: auto.as_ref().map(|a| a.choice),
        step: auto.as_ref().map_or(spec.step, |a| a.step),
        auto,
        tolerance: spec.tolerance,
        t_end: spec.t_end,
        final_: FinalOut {
            t: result.t,
            gamma: y[0],
            alpha: y[1],
            gamma_dot: y[2],
            alpha_dot: y[3],
        },
        reversals: Reversals::of(result.reversals.clone()),
        energy: EnergyOut {
            initial: result.energy_initial,
            final_: result.energy_final,
            max_relative_error: result.max_relative_energy_error,
        },
        effective: EffectiveOut {
            theta: eff.theta(),
            regime: eff.regime().name(),
            critical_ratio: eff.critical_ratio(problem),
            start_ratio: eff.start_ratio(problem),
            energy: eff.energy(),
            alpha: eff_run.as_ref().ok().map(|r| r.final_state[1]),
            alpha_dot: eff_run.as_ref().ok().map(|r| r.final_state[3]),
            comparison_error: eff_run.as_ref().err().map(ToString::to_string),
            half_period: eff.half_period(),
            turning_points: eff.turning_points(),
            tapping_acceleration: tapping_acceleration(problem),
            reversals: Reversals::of(eff.reversal_times(spec.t_end)),
        },
        stats: StatsOut {
            steps: result.stats.steps,
            rejected: result.stats.rejected,
            rhs_evaluations: result.stats.rhs_evaluations,
            wall_seconds,
        },
    };
    Ok(match format {
        Format::Json => {
            let mut s = serde_json::to_string_pretty(&report).expect("report serializes");
            s.push('\n');
            s
        }
        Format::Table | Format::Csv => table(&report),
    })
}

fn csv(preset: &Preset, result: &RunResult) -> String {
    let p = preset.problem.params();
    let mut out = String::from("t,gamma,alpha,gamma_dot,alpha_dot,energy\n");
    for s in &result.samples {
        let y = s.state;
        let _ = writeln!(
            out,
            "{},{},{},{},{},{}",
            s.t,
            y[0],
            y[1],
            y[2],
            y[3],
            energy(p, &y)
        );
    }
    out
}

fn opt(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_owned(), |x| format!("{x:.9}"))
}

fn times(t: &[f64]) -> String {
    const SHOWN: usize = 8;
    let mut s: Vec<String> = t.iter().take(SHOWN).map(|x| format!("{x:.6}")).collect();
    if t.len() > SHOWN {
        s.push(format!("… ({} more)", t.len() - SHOWN));
    }
    s.join(", ")
}

fn table(r: &Report) -> String {
    let mut o = String::new();
    let e = &r.effective;
    let _ = writeln!(o, "preset        {}", r.preset);
    let _ = writeln!(
        o,
        "body          ix = {}, iy = {}, iz = {}, k = {:e}",
        r.params.ix, r.params.iy, r.params.iz, r.params.k
    );
    let _ = writeln!(
        o,
        "start         gamma = {}, alpha = {}, gamma_dot = {}, alpha_dot = {}",
        r.initial.gamma, r.initial.alpha, r.initial.gamma_dot, r.initial.alpha_dot
    );
    let step = r
        .step
        .map(|h| format!(", step {h:.3e}"))
        .unwrap_or_default();
    let _ = writeln!(
        o,
        "method        {} (tolerance {:e}{step}), t_end = {}",
        r.method, r.tolerance, r.t_end
    );
    if let Some(a) = &r.auto {
        let _ = writeln!(
            o,
            "auto chose    {}: {} (estimated error {:.1e})",
            a.choice, a.reason, a.error_estimate
        );
    }
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "                   full model          effective (k → ∞)"
    );
    let limit = |v: Option<f64>| v.map_or_else(|| "n/a".to_owned(), |x| format!("{x:.9}"));
    let _ = writeln!(
        o,
        "alpha(T)      {:>16.9}    {:>16}",
        r.final_.alpha,
        limit(e.alpha)
    );
    let _ = writeln!(
        o,
        "alpha_dot(T)  {:>16.9}    {:>16}",
        r.final_.alpha_dot,
        limit(e.alpha_dot)
    );
    if let Some(why) = &e.comparison_error {
        let _ = writeln!(o, "  (no comparison with the limit: {why})");
    }
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
    let _ = writeln!(
        o,
        "work          {} steps ({} rejected), {} rhs evaluations, {:.4} s",
        r.stats.steps, r.stats.rejected, r.stats.rhs_evaluations, r.stats.wall_seconds
    );
    o
}

/// The first part of a result that is not a finite number, named for the error message.
fn non_finite(r: &RunResult) -> Option<&'static str> {
    const NAMES: [&str; 4] = ["gamma", "alpha", "gamma_dot", "alpha_dot"];
    if let Some(i) = r.final_state.iter().position(|x| !x.is_finite()) {
        return Some(NAMES[i]);
    }
    if !r.energy_final.is_finite() || !r.max_relative_energy_error.is_finite() {
        return Some("the energy");
    }
    r.reversals
        .iter()
        .any(|t| !t.is_finite())
        .then_some("a reversal time")
}
