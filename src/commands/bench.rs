//! `rattleback bench` (split from `commands/mod.rs`): every part's tables on stdout, its CSV
//! and SVG files in `--out`, the files of an earlier run refused without `--force`, and what
//! was written said, even when a signal stops it.

use super::failure::{Failure, Outcome};

/// Refused before minutes of work: files of an earlier run are replaced only with `--force`.
fn bench_refuses_old_files(args: &crate::commands::cli::BenchArgs) -> Outcome {
    let part = |p: crate::commands::cli::BenchPart| args.only.is_none_or(|o| o == p);
    let files: &[(crate::commands::cli::BenchPart, &[&str])] = &[
        (
            crate::commands::cli::BenchPart::WorkPrecision,
            &["work_precision.csv", "work_precision.svg"],
        ),
        (crate::commands::cli::BenchPart::Auto, &["auto_profile.csv"]),
        (crate::commands::cli::BenchPart::Kapitza, &["kapitza.csv"]),
        (crate::commands::cli::BenchPart::Celt, &["celt.csv"]),
        (
            crate::commands::cli::BenchPart::Stability,
            &["stability.csv"],
        ),
        (crate::commands::cli::BenchPart::Segments, &["segments.csv"]),
    ];
    if !args.force
        && let Some(existing) = files
            .iter()
            .filter(|(p, _)| part(*p))
            .flat_map(|(_, names)| names.iter().map(|n| args.out.join(n)))
            .find(|p| std::fs::symlink_metadata(p).is_ok())
    {
        return Err(Failure::input(format!(
            "{}: exists (from an earlier run); choose another --out or add --force to replace it",
            existing.display()
        )));
    }
    Ok(())
}

/// Files written whole, kept for the summary and noted for an interruption's message.
fn kept(wrote: &mut Vec<std::path::PathBuf>, paths: impl IntoIterator<Item = std::path::PathBuf>) {
    for p in paths {
        crate::interrupt::wrote(&p);
        wrote.push(p);
    }
}

/// `rattleback bench`.
pub fn bench(args: &crate::commands::cli::BenchArgs) -> Outcome {
    use crate::bench;
    let config = bench::Config { quick: args.quick };
    // Removed again if the run ends (a signal, a failure) with nothing written into it.
    let _folder = crate::fault::made_folder(&args.out)
        .map_err(|e| Failure::input(format!("{}: {e}", args.out.display())))?;
    let part = |p: crate::commands::cli::BenchPart| args.only.is_none_or(|o| o == p);
    bench_refuses_old_files(args)?;
    let mut wrote = Vec::new();
    let fail = |path: &std::path::Path, e: std::io::Error| {
        Failure::failed(format!("{}: {e}", path.display()))
    };
    if part(crate::commands::cli::BenchPart::WorkPrecision) {
        let rows = bench::work_precision(config, &mut |line| say_err!("{line}"));
        say_raw!("{}", bench::table(&rows));
        say!("");
        if rows.iter().any(|r| r.method.starts_with("peer-")) {
            say!("{}", bench::peer_summary(&rows, 1e-8));
        }
        for k in [1e4, 1e8] {
            say_raw!("{}", bench::terminal_diagram(&rows, k, 72, 16));
        }
        let csv = args.out.join("work_precision.csv");
        let svg = args.out.join("work_precision.svg");
        bench::write_csv(&rows, &csv).map_err(|e| fail(&csv, e))?;
        bench::write_svg(&rows, &svg)
            .map_err(|e| Failure::failed(format!("{}: {e}", svg.display())))?;
        kept(&mut wrote, [csv, svg]);
    }
    if part(crate::commands::cli::BenchPart::Auto) {
        say!(
            "\nauto at every stiffness (T = 30, tolerance 1e-8; errors against tests/fixtures/reference/averaged.toml)"
        );
        let profile = bench::profile(config.quick, &mut |line| say_err!("{line}"));
        say_raw!("{}", bench::profile_table(&profile));
        let profile_csv = args.out.join("auto_profile.csv");
        bench::write_profile_csv(&profile, &profile_csv).map_err(|e| fail(&profile_csv, e))?;
        let profile_svg = args.out.join("auto_profile.svg");
        bench::auto_profile::write_profile_svg(&profile, &profile_svg)
            .map_err(|e| Failure::failed(format!("{}: {e}", profile_svg.display())))?;
        kept(&mut wrote, [profile_csv, profile_svg]);
    }
    // A scene's part: its heading, its table, its CSV (its curves go to `curves`).
    let mut curves = Vec::new();
    let mut scene = |heading: &str,
                     table: String,
                     name: &str,
                     write: &dyn Fn(&std::path::Path) -> std::io::Result<()>| {
        say!("\n{heading}");
        say_raw!("{table}");
        let path = args.out.join(name);
        write(&path).map_err(|e| fail(&path, e))?;
        kept(&mut wrote, [path]);
        Ok::<(), Failure>(())
    };
    if part(crate::commands::cli::BenchPart::Kapitza) {
        let rows = bench::kapitza::study(config.quick, &mut |line| say_err!("{line}"));
        let heading = "Kapitza's pendulum: cost against epsilon (T = 5; errors against tests/fixtures/reference/kapitza.toml)";
        scene(heading, bench::kapitza::table(&rows), "kapitza.csv", &|p| {
            bench::kapitza::write_csv(&rows, p)
        })?;
        let svg = args.out.join("kapitza.svg");
        bench::kapitza::write_svg(&rows, &svg)
            .map_err(|e| Failure::failed(format!("{}: {e}", svg.display())))?;
        crate::interrupt::wrote(&svg);
        curves.push(svg);
    }
    if part(crate::commands::cli::BenchPart::Celt) {
        let rows = bench::celt::study(config.quick, &mut |line| say_err!("{line}"));
        let heading = "The celt: run time against error (final omega against tests/fixtures/celt/references.json)";
        scene(heading, bench::celt::table(&rows), "celt.csv", &|p| {
            bench::celt::write_csv(&rows, p)
        })?;
    }
    if part(crate::commands::cli::BenchPart::Segments) {
        let rows = bench::segments::study(config.quick, &mut |line| say_err!("{line}"));
        let heading = "Long runs verified in segments: the wait before the first frame (first) against the run verified in one piece (whole), and all the horizons together (nested, on the second core)";
        scene(
            heading,
            bench::segments::table(&rows),
            "segments.csv",
            &|p| bench::segments::write_csv(&rows, p),
        )?;
    }
    wrote.extend(curves);
    if part(crate::commands::cli::BenchPart::Stability) {
        let stability = bench::stability(config);
        say!("\nStability\n{}", bench::stability_table(&stability));
        let path = args.out.join("stability.csv");
        bench::write_stability_csv(&stability, &path).map_err(|e| fail(&path, e))?;
        kept(&mut wrote, [path]);
    }
    say!(
        "wrote {}",
        wrote
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}
