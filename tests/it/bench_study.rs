// Rows are grouped by the exact constants of `bench::KS`.
#![allow(clippy::float_cmp)]
//! `rattleback bench`: the quick study measures every method with finite errors where it runs,
//! writes the CSV with its contract columns and an SVG, and auto meets its tolerance.

use rattleback::bench::{self, Config};

#[test]
fn quick_study_covers_every_method_and_writes_its_files() {
    let mut log = Vec::new();
    let rows = bench::work_precision(Config { quick: true }, &mut |l| log.push(l.to_owned()));
    assert!(log.iter().filter(|l| l.contains("reference")).count() == bench::KS.len());
    for &m in rattleback::physics::ModelKind::Rattleback.methods() {
        let at_1e4: Vec<_> = rows
            .iter()
            .filter(|r| r.k == 1e4 && r.method == m.name())
            .collect();
        assert!(!at_1e4.is_empty(), "{m} missing at k = 1e4");
        assert!(
            at_1e4
                .iter()
                .all(|r| r.error_alpha.is_finite() && r.seconds > 0.0),
            "{m}"
        );
    }
    for r in rows.iter().filter(|r| r.method == "auto") {
        assert!(
            r.error_alpha <= 1e-6 && r.error_alpha_dot <= 1e-6,
            "auto at k = {:e}: {:e}",
            r.k,
            r.error_alpha
        );
    }
    let dir = std::env::temp_dir().join(format!("rattleback-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    bench::write_csv(&rows, &dir.join("work_precision.csv")).unwrap();
    bench::write_svg(&rows, &dir.join("work_precision.svg")).unwrap();
    let csv = std::fs::read_to_string(dir.join("work_precision.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    for column in [
        "method",
        "k",
        "tolerance",
        "error_alpha",
        "seconds",
        "rhs_evaluations",
    ] {
        assert!(header.split(',').any(|c| c == column), "column {column}");
    }
    assert_eq!(csv.lines().count(), rows.len() + 1);
    assert!(
        std::fs::read_to_string(dir.join("work_precision.svg"))
            .unwrap()
            .starts_with("<svg")
    );
    assert!(bench::terminal_diagram(&rows, 1e4, 60, 12).lines().count() > 12);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The celt's part: every configuration counts exactly, every `auto` claim holds against the
/// references (met ⇒ error within the tolerance, and the estimate above the error), and the
/// tables and CSV carry every row.
#[test]
fn the_celt_part_measures_against_the_references_and_auto_keeps_its_claims() {
    let mut log = Vec::new();
    let rows = bench::celt::study(true, &mut |l| log.push(l.to_owned()));
    assert!(log.is_empty(), "{log:?}");
    assert_eq!(
        rows.len(),
        2 * 2 * 3,
        "two presets, two tolerances, three methods"
    );
    for r in &rows {
        assert!(
            r.counts_exact,
            "{} {} {:e}",
            r.preset, r.method, r.tolerance
        );
        assert!(r.seconds > 0.0 && r.error.is_finite());
        if r.met == Some(true) {
            let floor = r.reference_uncertainty;
            assert!(r.error <= r.tolerance + floor, "{r:?}");
            assert!(r.estimate.unwrap() + floor >= r.error, "{r:?}");
        }
    }
    // DOP853 at a loose tolerance is far off on these unstable spins: the study sees it.
    assert!(
        rows.iter()
            .any(|r| r.method == "dop853" && r.tolerance == 1e-6 && r.error > 1e-4)
    );
    let table = bench::celt::table(&rows);
    assert!(table.lines().count() > rows.len() + 2, "{table}");
    let dir = std::env::temp_dir().join(format!("rattleback-celt-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    bench::celt::write_csv(&rows, &dir.join("celt.csv")).unwrap();
    let csv = std::fs::read_to_string(dir.join("celt.csv")).unwrap();
    assert_eq!(csv.lines().count(), rows.len() + 1);
    assert!(csv.starts_with("preset,method,tolerance,"));
    let _ = std::fs::remove_dir_all(&dir);
}
