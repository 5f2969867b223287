//! `study map` and `study merge`: a chart computed, priced and printed, or put back together
//! from its parts (issue 59; provenance, issue 66). The study's helpers (`emit`, the
//! set-up, the files) are `study.rs`'s.

use super::{emit, study_setup, write_files};
use crate::commands::progress::{Progress, counted, tallied};
use crate::commands::{Failure, Outcome, finished, go_on, interrupted, json_text};

pub(super) fn study_map(args: &crate::commands::cli::MapArgs) -> Outcome {
    use crate::study::chart;
    let (preset, model, t_end, tolerance, _folder) = study_setup(&args.common)?;
    let ask = crate::study::ask::StudyAsk {
        grid: args.grid,
        t_end,
        tolerance,
        asked_tolerance: args.common.tolerance,
        ratio_max: args.ratio_max,
        inertia_min: args.inertia_min,
        inertia_max: args.inertia_max,
        k: args.k,
        columns: args.columns,
        rows: args.rows,
        hanging: args
            .position
            .map(|p| p == crate::commands::cli::Position::Hanging),
        asked_t_end: args.common.t_end,
        exhaustive: args.exhaustive,
    };
    let chart = chart::Chart::for_study(&model, &ask).map_err(Failure::input)?;
    if args.shard.is_some() && args.common.out.is_some() {
        return Err(Failure::input(
            "--out draws the whole chart: give the parts to `study merge --out DIR`".to_owned(),
        ));
    }
    if args.shard.is_some() && args.common.format == crate::commands::cli::StudyFormat::Csv {
        return Err(Failure::input(
            "a shard is written as JSON (`study merge --format csv` prints the whole chart as CSV)"
                .to_owned(),
        ));
    }
    let expected = chart.expected_cells(args.exhaustive, args.shard);
    let price = chart.price(args.exhaustive, args.shard);
    chart_priced(&chart, expected, price, args.common.force)?;
    let label = match args.shard {
        Some(s) => format!("study map {}/{}", s.index, s.count),
        None => "study map".to_owned(),
    };
    // Progress by cells computed, of those the cost model expects (more when the refinement
    // finds more to compute); Ctrl-C cancels the cells in flight.
    let started = std::time::Instant::now();
    let progress = Progress::count(&label, expected, "cells computed").priced(price);
    let watch = Watchdog::new(price, args.common.force);
    let mapped = tallied(progress, &|tally| {
        chart.compute(
            args.exhaustive,
            args.shard,
            &|_| go_on() && watch.ok(),
            tally,
        )
    });
    if let Some(over) = watch.tripped() {
        return Err(Failure::input(format!(
            "study map stopped: this {} ran past twice its price ({over}); nothing was written. The cost model misjudged this window: pass --force to run it to the end, or use a smaller --grid",
            chart.title()
        )));
    }
    let computed = finished(mapped, "study map")?;
    let mut out = chart.output(
        crate::commands::outputs::SCHEMA_VERSION,
        &crate::scenario::text::one_line(&preset.name),
        &computed.indices,
        &computed.verdicts,
        args.shard,
        args.exhaustive,
    );
    out.wall_seconds = started.elapsed().as_secs_f64();
    if args.shard.is_some() {
        // A part proves where it came from (issue 66): the chart's whole description, then a
        // digest over everything.
        out.description = Some(crate::study::part::Description::new(preset.to_toml(), &ask));
        return emit(&json_text(&crate::study::part::sealed(out)));
    }
    print_chart(
        &out,
        args.common.format,
        args.common.out.as_deref(),
        args.common.force,
    )
}

/// Prints a chart in `format` and writes `map.csv` and `map.svg` into `out` when asked.
fn print_chart(
    out: &crate::study::chart::ChartOutput,
    format: crate::commands::cli::StudyFormat,
    dir: Option<&std::path::Path>,
    force: bool,
) -> Outcome {
    let csv = out.csv();
    match format {
        crate::commands::cli::StudyFormat::Json => emit(&json_text(out)),
        crate::commands::cli::StudyFormat::Csv => emit(&csv),
        crate::commands::cli::StudyFormat::Table => emit(&out.table()),
    }?;
    let Some(dir) = dir else { return Ok(()) };
    let svg = match crate::study::svg::chart_svg(out) {
        Ok(svg) => svg,
        Err(e) => return Err(Failure::failed(format!("drawing the map: {e}"))),
    };
    write_files(dir, force, &[("map.csv", csv), ("map.svg", svg)])
}

/// `rattleback study merge PART…`: each part read within its slice's size, the chart rebuilt
/// from the parts' description, every header and cell compared with what that chart writes, a
/// random sample of each part's cells recomputed (issue 66).
pub(super) fn study_merge(args: &crate::commands::cli::MergeArgs) -> Outcome {
    use crate::study::part;
    let mut parts = Vec::new();
    if args
        .parts
        .iter()
        .filter(|p| crate::scenario::write::is_stdin(p))
        .count()
        > 1
    {
        return Err(Failure::input(
            "`-` given twice: stdin holds one part".to_owned(),
        ));
    }
    for path in &args.parts {
        let name = crate::scenario::text::one_line(&path.display().to_string());
        let read = if crate::scenario::write::is_stdin(path) {
            part::read(std::io::stdin().lock())
        } else {
            match std::fs::metadata(path) {
                Ok(m) if m.is_dir() => Err("a folder, not a part file".to_owned()),
                Ok(_) => std::fs::File::open(path)
                    .map_err(|e| e.to_string())
                    .and_then(part::read),
                Err(e) => Err(e.to_string()),
            }
        };
        let part = read.map_err(|e| Failure::input(format!("{name}: {e}")))?;
        if part.schema_version != crate::commands::outputs::SCHEMA_VERSION {
            return Err(Failure::input(format!(
                "{name}: schema_version {} (this build writes and reads {})",
                part.schema_version,
                crate::commands::outputs::SCHEMA_VERSION
            )));
        }
        parts.push((name, part));
    }
    let (first_name, first) = &parts[0];
    let Some(description) = &first.description else {
        return Err(Failure::input(format!(
            "{first_name}: not a part (no `description`)"
        )));
    };
    // The chart rebuilt from the description alone, its preset read by the preset validator.
    let rebuilt = || -> Result<crate::study::chart::Chart, Box<dyn std::error::Error>> {
        let ask = description.ask(crate::scenario::preset::TOLERANCE_RANGE)?;
        let preset = crate::scenario::Preset::parse(
            &description.preset,
            "the part's description",
            "part",
            &[],
        )?;
        Ok(crate::study::chart::Chart::for_study(&preset.model, &ask)?)
    };
    let chart = rebuilt().map_err(|e| {
        Failure::input(format!(
            "{first_name}: its description is not a chart this program makes: {}",
            crate::scenario::text::one_line(&e.to_string())
        ))
    })?;
    let merged = part::merge(&chart, crate::commands::outputs::SCHEMA_VERSION, &parts)
        .map_err(|e| Failure::input(crate::scenario::text::one_line(&e.to_string())))?;
    let mut random = || {
        let mut b = [0u8; 8];
        // Without the system's randomness, the clock: a forger still cannot pick the cells.
        if getrandom::fill(&mut b).is_err() {
            let nanos = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.subsec_nanos());
            b = (u64::from(nanos) ^ 0x9e37_79b9_7f4a_7c15).to_le_bytes();
        }
        u64::from_le_bytes(b)
    };
    let chosen = part::choose(&parts, args.check, &mut random);
    let price = chart.predicted_seconds(&part::indices(&parts, &chosen));
    let budget = if args.force {
        f64::INFINITY
    } else {
        crate::physics::budget::BUDGET_SECONDS
    };
    if let Err(over) = crate::physics::budget::check(price, budget) {
        return Err(Failure::input(format!(
            "recomputing {} cells to check the parts is {over}; give a smaller --check, or pass --force",
            chosen.len()
        )));
    }
    let progress = Progress::count("study merge: checking", chosen.len(), "cells").priced(price);
    let checked = counted(progress, &|_| {
        part::sample(&chart, &parts, &chosen, &|_| go_on())
    });
    if let Some(failure) = interrupted() {
        return Err(failure);
    }
    checked.map_err(|e| Failure::input(crate::scenario::text::one_line(&e.to_string())))?;
    if let Some(dir) = &args.out
        && let Err(e) = std::fs::create_dir_all(dir)
    {
        return Err(Failure::input(format!("--out {}: {e}", dir.display())));
    }
    print_chart(&merged, args.format, args.out.as_deref(), args.force)
}

/// The chart's cells when its cost model puts the `cells` it expects to compute within the work
/// budget (or `--force`).
/// A chart stopped once it has run past twice its price (issue 80: a window the cost model
/// misjudges runs no longer than that, unless `--force`): measured in the process's CPU time
/// against the price's CPU (the price is wall time on every thread), with
/// [`WATCHDOG_SLACK_SECONDS`] besides, so that a chart of a fraction of a second is not stopped
/// by its threads' start.
struct Watchdog {
    start: Option<cpu_time::ProcessTime>,
    /// The price in CPU seconds.
    price_cpu: f64,
    /// CPU seconds after which the chart stops.
    limit: f64,
    tripped: std::sync::atomic::AtomicBool,
}

/// CPU seconds a chart may run beyond twice its price's.
const WATCHDOG_SLACK_SECONDS: f64 = 2.0;

impl Watchdog {
    fn new(price: f64, force: bool) -> Self {
        Self::with_slack(price, force, WATCHDOG_SLACK_SECONDS)
    }

    fn with_slack(price: f64, force: bool, slack: f64) -> Self {
        let threads = rayon::current_num_threads().max(1) as f64;
        let price_cpu = price * threads;
        Self {
            start: (!force)
                .then(cpu_time::ProcessTime::try_now)
                .and_then(Result::ok),
            price_cpu,
            limit: 2.0 * price_cpu + slack,
            tripped: std::sync::atomic::AtomicBool::new(false),
        }
    }

    /// Whether the chart may go on (and, when it may not, remembers why).
    fn ok(&self) -> bool {
        let Some(start) = self.start else {
            return true;
        };
        if self.tripped.load(std::sync::atomic::Ordering::Relaxed) {
            return false;
        }
        let spent = start.try_elapsed().map_or(0.0, |d| d.as_secs_f64());
        if spent > self.limit {
            self.tripped
                .store(true, std::sync::atomic::Ordering::Relaxed);
            return false;
        }
        true
    }

    /// What was spent against the price when it stopped the chart.
    fn tripped(&self) -> Option<String> {
        if !self.tripped.load(std::sync::atomic::Ordering::Relaxed) {
            return None;
        }
        Some(format!(
            "priced at {} of CPU, stopped after {}",
            crate::physics::budget::duration(self.price_cpu),
            crate::physics::budget::duration(self.limit)
        ))
    }
}

fn chart_priced(
    chart: &crate::study::chart::Chart,
    cells: usize,
    predicted: f64,
    force: bool,
) -> Outcome {
    let budget = if force {
        f64::INFINITY
    } else {
        crate::physics::budget::BUDGET_SECONDS
    };
    if let Err(over) = crate::physics::budget::check(predicted, budget) {
        let what = chart.title();
        return Err(Failure::input(format!(
            "the chart {what}: {cells} cells to compute, {over}; use a smaller --grid or --shard I/N, or pass --force"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::Watchdog;

    #[test]
    fn the_watchdog_stops_a_chart_past_twice_its_price_unless_forced() {
        let spin = |w: &Watchdog| {
            let start = std::time::Instant::now();
            let mut x = 0u64;
            while w.ok() && start.elapsed().as_secs_f64() < 5.0 {
                x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            }
            std::hint::black_box(x);
        };
        let w = Watchdog::with_slack(0.01, false, 0.05);
        spin(&w);
        assert!(!w.ok());
        let said = w.tripped().unwrap();
        assert!(
            said.contains("priced at") && said.contains("stopped after"),
            "{said}"
        );
        let forced = Watchdog::with_slack(0.0, true, 0.0);
        assert!(forced.ok() && forced.tripped().is_none());
    }
}
