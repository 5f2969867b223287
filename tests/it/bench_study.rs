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
