//! `rattleback simulate`: one headless trajectory, reported as JSON, CSV or a table.
//!
//! The report's field names are a contract (scripts read them): add freely, rename nothing.
//! Each scene's report is its folder's (`physics/NAME/report.rs`, issue 83), made of what
//! every report shares (`physics::report`) and reached through the preset's
//! [`crate::physics::Model`]; this layer resolves the run from the preset and the command
//! line, prices it against the budget, and hosts the report (the preset's words, the clock,
//! warnings, the text cleaned).

use crate::physics::StepError;
use crate::physics::budget::{self, BUDGET_SECONDS};
use crate::physics::method::Method;
use crate::physics::method::RunSpec;
use crate::physics::report::{Ask, Host, Report, compact};
pub use crate::physics::report::{Failure, Format, Missed, Resolved, SCHEMA_VERSION};
use crate::scenario::Preset;

/// Tolerance when neither the command line nor the preset gives one.
pub const DEFAULT_TOLERANCE: f64 = crate::physics::DEFAULT_TOLERANCE;
/// Method when neither the command line nor the preset names one.
pub const DEFAULT_METHOD: Method = Method::Auto;

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
    /// Run even when the work is predicted over [`BUDGET_SECONDS`].
    pub force: bool,
}

/// The wall clock of a report's `wall_seconds`: none in the browser's module
/// (`wasm32-unknown-unknown` has no clock; its reports say 0).
struct Stopwatch(#[cfg(not(target_arch = "wasm32"))] std::time::Instant);

impl Stopwatch {
    fn start() -> Self {
        Self(
            #[cfg(not(target_arch = "wasm32"))]
            std::time::Instant::now(),
        )
    }

    fn seconds(&self) -> f64 {
        #[cfg(not(target_arch = "wasm32"))]
        return self.0.elapsed().as_secs_f64();
        #[cfg(target_arch = "wasm32")]
        0.0
    }
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
                .unwrap_or_else(|| preset.model.default_step(method, tolerance, t_end)),
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
        budget: if args.force {
            f64::INFINITY
        } else {
            BUDGET_SECONDS
        },
    }
}

/// Predicted seconds of everything `simulate` would run for `resolved` in `format`: the run
/// (for `auto`, planned and verified), then the limit's comparison run (JSON, table) or the
/// streamed rerun of `auto`'s plan (CSV).
#[must_use]
pub fn predicted_seconds(preset: &Preset, resolved: &Resolved, format: Format) -> f64 {
    report_of(&preset.model).predicted_seconds(&resolved.spec, format)
}

/// The report of a scene's problem: the one dispatch over the scenes in this layer, generated
/// from the registry (`physics::models::with_scenes`).
macro_rules! report_dispatch {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $name:ident: $folder:ident, $chart:ident;
    )*) => {
        /// The report of `model`'s scene.
        fn report_of(model: &crate::physics::Model) -> &dyn Report {
            match model {
                $( $(#[cfg($cfg)])? crate::physics::Model::$name(p) => p, )*
            }
        }
    };
}
crate::physics::models::with_scenes!(report_dispatch);

/// Runs `preset` as `resolved` says and renders the report in `format` (CSV included: this
/// holds it all in memory; the command streams it with [`simulate_to`]).
///
/// # Errors
/// As [`simulate_to`].
pub fn simulate(preset: &Preset, resolved: &Resolved, format: Format) -> Result<String, Failure> {
    let mut out = Vec::new();
    simulate_to(preset, resolved, format, &mut out, &mut |_| true)?;
    Ok(String::from_utf8_lossy(&out).into_owned())
}

/// Runs `preset` as `resolved` says and writes the report in `format` to `out`; the CSV is
/// written sample by sample as the integration goes, so memory does not grow with
/// `--samples`. `progress(t)` is called every few hundred steps with the time reached (it
/// restarts from 0 for each of `auto`'s runs) and may cancel by returning `false`.
///
/// Nothing starts when the work is predicted over `resolved.budget`
/// ([`StepError::OverBudget`]); `auto` also checks each of its verification runs.
///
/// Returns `auto`'s shortfall when it could not meet the tolerance (the output is complete and
/// says so too: `auto.met = false`); `None` when it met it or another method ran.
///
/// # Errors
/// The integration failed or was refused, a result is not a finite number (an error naming
/// it, never a NaN in the output), or `out` failed.
///
/// # Panics
/// Never in practice: the report holds only finite numbers and strings, which serialize.
pub fn simulate_to(
    preset: &Preset,
    resolved: &Resolved,
    format: Format,
    out: &mut dyn std::io::Write,
    progress: &mut dyn FnMut(f64) -> bool,
) -> Result<Option<Missed>, Failure> {
    within_budget(preset, resolved, format)?;
    let host = Hosted {
        preset,
        resolved,
        clock: Stopwatch::start(),
    };
    let ask = Ask {
        host: &host,
        resolved,
        format,
        out,
        progress,
    };
    report_of(&preset.model).simulate_to(ask)
}

/// What `simulate` does for a scene's report: the preset's words, the clock, warnings on
/// standard error, and text from files cleaned before any terminal or file.
struct Hosted<'a> {
    preset: &'a Preset,
    resolved: &'a Resolved,
    clock: Stopwatch,
}

impl Host for Hosted<'_> {
    fn model(&self) -> &'static str {
        self.preset.model.kind().name()
    }

    fn preset(&self) -> &str {
        &self.preset.name
    }

    fn preset_line(&self) -> String {
        crate::scenario::text::one_line(&self.preset.name)
    }

    fn json_safe(&self, json: &str) -> String {
        crate::scenario::text::json_safe(json)
    }

    fn csv_head(&self, ran: Method, t_end: f64) -> String {
        csv_metadata_of(
            &self.preset.name,
            &self.preset.model,
            self.resolved.spec.method,
            Some(ran),
            self.resolved.spec.tolerance,
            t_end,
        )
    }

    fn seconds(&self) -> f64 {
        self.clock.seconds()
    }

    fn warn(&self, text: &str) {
        crate::scenario::text::warn(text);
    }
}

/// Refuses, before anything runs, work predicted over the budget.
pub(crate) fn within_budget(
    preset: &Preset,
    resolved: &Resolved,
    format: Format,
) -> Result<(), StepError> {
    let spec = resolved.spec;
    budget::check(predicted_seconds(preset, resolved, format), resolved.budget).map_err(|over| {
        StepError::OverBudget {
            what: format!(
                "this run ({}, t_end = {})",
                spec.method,
                compact(spec.t_end)
            ),
            over,
        }
    })
}

/// What a CSV of a run starts with: `# key = value` lines (the program, the model unless it is
/// the default, the preset's name, the method asked and the one that ran, the tolerance, the
/// horizon, then every parameter of the model's table, every number as text that parses back
/// to the same bits), so the file says what made it. `simulate --format csv` and the
/// explorer's export (`x`) write the same lines.
#[must_use]
pub fn csv_metadata_of(
    preset: &str,
    model: &crate::physics::Model,
    method: Method,
    ran: Option<Method>,
    tolerance: f64,
    t_end: f64,
) -> String {
    let kind = model.kind();
    let mut numbers = vec![("tolerance", tolerance), ("t_end", t_end)];
    numbers.extend(kind.params().iter().map(|p| p.key).zip(model.values()));
    metadata_lines(
        preset,
        // Every scene's CSV names its model, the rattleback's too (issue 68).
        Some(kind.name()),
        method,
        ran,
        &numbers,
    )
}

/// The `# key = value` lines every model's CSV starts with: the program, the model, the preset's name cleaned to one line, the method asked and the
/// one that ran, then `numbers` as text that parses back to the same bits.
pub(crate) fn metadata_lines(
    preset: &str,
    model: Option<&str>,
    method: Method,
    ran: Option<Method>,
    numbers: &[(&str, f64)],
) -> String {
    use std::fmt::Write as _;
    let name = crate::scenario::text::one_line(&crate::scenario::text::shown(preset));
    let mut out = format!("# program = rattleback {}\n", env!("CARGO_PKG_VERSION"));
    if let Some(m) = model {
        let _ = writeln!(out, "# model = {m}");
    }
    let _ = writeln!(out, "# preset = {name}\n# method = {}", method.name());
    if let Some(m) = ran {
        let _ = writeln!(out, "# integrated = {}", m.name());
    }
    for (key, value) in numbers {
        let _ = writeln!(out, "# {key} = {value:?}");
    }
    out
}
