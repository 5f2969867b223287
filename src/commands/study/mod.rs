//! `rattleback study`: the set-up every study shares, its outputs, and `study sweep`
//! (`study map` and `study merge` are in `study/charts.rs`, which takes these helpers from here).

mod charts;

use std::fmt::Write as _;

use crate::commands::failure::{Failure, Outcome};
use crate::commands::progress::{Progress, counted};

use super::{finished, go_on, json_text};

/// `rattleback study sweep|map`.
pub fn study(command: &crate::commands::cli::StudyCommand) -> Outcome {
    use crate::commands::cli::StudyCommand;
    // Ctrl-C (or any ending signal: `main` installs them) cancels the runs in flight and ends
    // with 128 + the signal, the progress bar erased and no file written.
    match command {
        StudyCommand::Sweep(args) => study_sweep(args),
        StudyCommand::Map(args) => charts::study_map(args),
        StudyCommand::Merge(args) => charts::study_merge(args),
    }
}

/// The preset, horizon and tolerance of a study, or the exit of a bad input.
pub(crate) fn study_setup(
    common: &crate::commands::cli::StudyCommon,
) -> Result<
    (
        crate::scenario::Preset,
        crate::physics::Model,
        f64,
        f64,
        Option<crate::fault::MadeFolder>,
    ),
    Failure,
> {
    let preset =
        crate::scenario::shipped::resolve(&common.preset, &common.set).map_err(Failure::input)?;
    let model = preset.model;
    let t_end = common.t_end.unwrap_or(preset.run.t_end);
    let tolerance = common
        .tolerance
        .or(preset.run.tolerance)
        .unwrap_or(crate::physics::DEFAULT_TOLERANCE);
    // Made now, so that a bad --out is refused before the work; removed again if the run ends
    // without writing into it.
    let folder = match &common.out {
        Some(dir) => Some(
            crate::fault::made_folder(dir)
                .map_err(|e| Failure::input(format!("--out {}: {e}", dir.display())))?,
        ),
        None => None,
    };
    Ok((preset, model, t_end, tolerance, folder))
}

/// Writes `files` (name, contents) into `--out`, refusing to replace without `--force`.
pub(crate) fn write_outputs(
    common: &crate::commands::cli::StudyCommon,
    files: &[(&str, String)],
) -> Outcome {
    match &common.out {
        Some(dir) => write_files(dir, common.force, files),
        None => Ok(()),
    }
}

/// Why `path` was not written: a file there (`--force` replaces it), something else there that
/// is never replaced (both input, exit 2), or what the system said (exit 1).
pub(crate) fn not_written(path: &std::path::Path, e: &std::io::Error) -> Failure {
    match e.kind() {
        std::io::ErrorKind::AlreadyExists => Failure::input(format!("{e}; --force replaces it")),
        std::io::ErrorKind::InvalidInput => Failure::input(e),
        _ => Failure::failed(format!("{}: {e}", path.display())),
    }
}

/// Writes `files` (name, contents) into `dir`, refusing to replace without `force`.
pub(crate) fn write_files(dir: &std::path::Path, force: bool, files: &[(&str, String)]) -> Outcome {
    for (name, text) in files {
        let path = dir.join(name);
        if let Err(e) = crate::scenario::write::write_atomic(&path, text.as_bytes(), force) {
            return Err(not_written(&path, &e));
        }
    }
    say_err!(
        "wrote {}",
        files
            .iter()
            .map(|(n, _)| dir.join(n).display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

/// Writes `text` to stdout; a closed pipe (`| head`) ends the output quietly (exit 0, the
/// `--out` files are still written), another failure is exit 1.
pub(crate) fn emit(text: &str) -> Outcome {
    use std::io::Write as _;
    let text = crate::scenario::text::shown(text);
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(Failure::failed(format!("writing the output: {e}"))),
    }
}

/// The sweep's cost, asked before it runs: every rung validated, the total within the budget
/// (`--force` lifts the budget).
pub(crate) fn sweep_budget(
    model: &crate::physics::Model,
    ladder: &[f64],
    t_end: f64,
    tolerance: f64,
    force: bool,
) -> Outcome {
    match crate::study::sweep::predicted_seconds(model, ladder, t_end, tolerance) {
        Err(e) => Err(Failure::input(format!("--ladder: {e}"))),
        Ok(predicted) if predicted > crate::physics::budget::BUDGET_SECONDS && !force => {
            Err(Failure::input(format!(
                "this sweep is predicted to take about {} (budget {}); use fewer rungs, a shorter --t-end or a looser --tolerance, or pass --force",
                crate::physics::budget::duration(predicted),
                crate::physics::budget::duration(crate::physics::budget::BUDGET_SECONDS)
            )))
        }
        Ok(_) => Ok(()),
    }
}

pub(crate) fn study_sweep(args: &crate::commands::cli::SweepArgs) -> Outcome {
    use crate::study::sweep::{ladder, sweep};
    let (preset, model, t_end, tolerance, _folder) = study_setup(&args.common)?;
    let kind = model.kind();
    let Some(small) = kind.small() else {
        return Err(Failure::input(format!(
            "the {} has no small parameter to sweep",
            kind.title()
        )));
    };
    let ladder = if args.ladder.is_empty() {
        ladder(kind).to_vec()
    } else {
        args.ladder.clone()
    };
    // Every rung is the model's own parameter: its range is the preset's.
    if let Some(spec) = kind.params().iter().find(|p| p.key == small.key)
        && let Some(bad) = ladder.iter().find(|x| !spec.allowed.contains(**x))
    {
        return Err(Failure::input(format!(
            "--ladder: {} = {bad} is out of range for the {} model; allowed: {}",
            small.key,
            kind.name(),
            spec.allowed.text()
        )));
    }
    sweep_budget(&model, &ladder, t_end, tolerance, args.common.force)?;
    // Progress by runs (the limit is one); Ctrl-C cancels the runs in flight.
    let runs = Progress::count("study sweep", ladder.len() + 1, "runs");
    let swept = counted(runs, &|done| {
        sweep(&model, &ladder, t_end, tolerance, &|_| go_on(), done)
    });
    let s = finished(swept, "study sweep")?;
    // The rattleback's column and field are `stiffness` (a contract); the pendulum's `epsilon`.
    let column = small.column;
    let mut csv = format!("{column},sup_error,method,estimate\n");
    for r in &s.rungs {
        let _ = writeln!(
            csv,
            "{:e},{:e},{},{:e}",
            r.parameter, r.sup_error, r.method, r.estimate
        );
    }
    let printed = match args.common.format {
        crate::commands::cli::StudyFormat::Json => {
            let ladder = s.stiffness();
            emit(&json_text(&crate::commands::outputs::Sweep {
                schema_version: crate::commands::outputs::SCHEMA_VERSION,
                model: model.kind(),
                preset: preset.name.clone(),
                t_end,
                tolerance,
                stiffness: (column == "stiffness").then(|| ladder.clone()),
                epsilon: (column != "stiffness").then_some(ladder),
                sup_error: s.sup_error(),
                slope: s.slope,
                methods: s.rungs.iter().map(|r| r.method.name()).collect(),
                estimates: s.rungs.iter().map(|r| r.estimate).collect(),
            }))
        }
        crate::commands::cli::StudyFormat::Csv => emit(&crate::scenario::text::clean(&csv)),
        crate::commands::cli::StudyFormat::Table => emit(&crate::scenario::text::clean(
            &sweep_table(&preset.name, t_end, tolerance, &s),
        )),
    };
    printed?;
    // The files only when asked for (a scene never computes what it does not need).
    if args.common.out.is_none() {
        return Ok(());
    }
    let curves = sweep_curves(&s);
    let svg = match crate::study::svg::sweep_svg(&s) {
        Ok(svg) => svg,
        Err(e) => {
            return Err(Failure::failed(format!("drawing the sweep: {e}")));
        }
    };
    write_outputs(
        &args.common,
        &[
            ("sweep.csv", csv),
            ("sweep_curves.csv", curves),
            ("sweep.svg", svg),
        ],
    )
}

pub(crate) fn sweep_table(
    name: &str,
    t_end: f64,
    tolerance: f64,
    s: &crate::study::sweep::Sweep,
) -> String {
    let mut o = format!(
        "preset        {} (T = {t_end}, tolerance {tolerance:e})\n",
        crate::scenario::text::one_line(name)
    );
    let small = s.small();
    let (parameter, sup) = (small.key, small.sup_short);
    let _ = writeln!(
        o,
        "{:>10}  {:>14}  {:<19} {:>9}",
        parameter, sup, "auto chose", "estimate"
    );
    for r in &s.rungs {
        let _ = writeln!(
            o,
            "{:>10.0e}  {:>14.3e}  {:<19} {:>9.1e}",
            r.parameter,
            r.sup_error,
            r.method.name(),
            r.estimate
        );
    }
    let _ = writeln!(
        o,
        "slope of log sup against log {parameter}: {}",
        s.slope
            .map_or_else(|| "n/a".to_owned(), |x| format!("{x:.3}"))
    );
    o
}

/// `sweep_curves.csv`: `t, limit, alpha_k<k>…`, one row per sample.
pub(crate) fn sweep_curves(s: &crate::study::sweep::Sweep) -> String {
    let mut curves = String::from("t,limit");
    let (q, tag) = (s.model.words().q_name, s.small().tag);
    for r in &s.rungs {
        let _ = write!(curves, ",{q}_{tag}{:e}", r.parameter);
    }
    curves.push('\n');
    for (i, t) in s.t.iter().enumerate() {
        let _ = write!(curves, "{t},{}", s.limit[i]);
        for r in &s.rungs {
            let _ = write!(curves, ",{}", r.alpha[i]);
        }
        curves.push('\n');
    }
    curves
}
