//! Charts computed where their answer changes (issue 70): every cell's answer (its count of
//! reversals, its stability verdict, or undecided) equal to `--exhaustive`'s, cell for cell,
//! on several charts of each scene (default axes and held-out ones, islands and thin tongues
//! among them); each cell marked `computed` or `inferred`; the computed ones bit for bit the
//! exhaustive run's. Issue 80: on generated windows too (a seeded generator, its seed printed),
//! and on the reviews' windows where an uncertified refinement lost a tongue.

use crate::common::{Seeded, bin};

/// A cell's answer: `("count", n)`, `("stable", 0/1)`, or undecided (`None`).
fn answer(cell: &serde_json::Value) -> Option<(&'static str, u64)> {
    if cell.get("error").is_some() || cell["decided"] == false {
        return None;
    }
    match cell.get("stable") {
        Some(s) => Some(("stable", u64::from(s.as_bool().unwrap()))),
        None => Some(("count", cell["reversals"].as_u64().unwrap())),
    }
}

/// The chart `args` refined and exhaustive: the same answers cell for cell, every computed
/// cell the exhaustive one bit for bit; how many cells were inferred.
fn equal_to_exhaustive(args: &[&str]) -> usize {
    equal_to_exhaustive_tagged(args, "")
}

/// [`equal_to_exhaustive`], each failure's message ending with `tag` (a generated case's seed).
fn equal_to_exhaustive_tagged(args: &[&str], tag: &str) -> usize {
    let mut refined_args = vec!["study", "map", "--format", "json", "--force"];
    refined_args.extend_from_slice(args);
    let run = |a: &[&str]| {
        let (code, out, err) = bin(a);
        assert_eq!(code, 0, "{a:?}: {err} {tag}");
        serde_json::from_str::<serde_json::Value>(&out).unwrap()
    };
    let refined = run(&refined_args);
    refined_args.push("--exhaustive");
    let every = run(&refined_args);
    let (r, e) = (
        refined["cells"].as_array().unwrap(),
        every["cells"].as_array().unwrap(),
    );
    assert_eq!(r.len(), e.len(), "{args:?}");
    let mut inferred = 0;
    for (r, e) in r.iter().zip(e) {
        assert_eq!(r["index"], e["index"]);
        assert_eq!(
            e["mark"], "computed",
            "{args:?}: an exhaustive chart computes every cell"
        );
        assert_eq!(
            answer(r),
            answer(e),
            "{args:?}: cell {} refined {r} exhaustive {e} {tag}",
            r["index"]
        );
        match r["mark"].as_str() {
            Some("computed") => assert_eq!(r, e, "{args:?}: a computed cell is the same"),
            Some("inferred") => {
                inferred += 1;
                for field in [
                    "first_reversal",
                    "growth_rate",
                    "trace",
                    "trace_error",
                    "error",
                ] {
                    assert!(r.get(field).is_none(), "{args:?}: an inferred {field}: {r}");
                }
            }
            other => panic!("{args:?}: mark {other:?}"),
        }
    }
    inferred
}

#[test]
fn the_rattlebacks_limit_charts_compute_every_cell() {
    // Two quadratures a cell are cheaper than any certificate (issue 80): nothing inferred.
    for args in [
        &["--preset", "subcritical"][..],
        &["--preset", "supercritical"],
        // Held out: other axes, another window and body.
        &[
            "--preset",
            "just-below",
            "--ratio-max",
            "6",
            "--inertia-min",
            "0.02",
            "--inertia-max",
            "2",
            "--grid",
            "160x90",
        ],
        &[
            "--preset",
            "iy-greater",
            "--t-end",
            "90",
            "--grid",
            "120x80",
        ],
    ] {
        assert_eq!(equal_to_exhaustive(args), 0, "{args:?}");
    }
}

#[test]
fn the_rattlebacks_full_model_charts_equal_the_exhaustive_ones() {
    for args in [
        &["--preset", "subcritical", "--k", "1e4", "--grid", "40x20"][..],
        &[
            "--preset",
            "soft-spring",
            "--k",
            "400",
            "--grid",
            "36x18",
            "--t-end",
            "20",
            "--inertia-min",
            "0.3",
        ],
    ] {
        let inferred = equal_to_exhaustive(args);
        assert!(inferred > 50, "{args:?}: {inferred} inferred");
    }
}

#[test]
fn the_pendulums_charts_equal_the_exhaustive_ones_tongues_and_all() {
    for args in [
        &["--preset", "kapitza-upright"][..],
        // The hanging pendulum's thin tongues of parametric resonance.
        &["--preset", "kapitza-upright", "--position", "hanging"],
        // Held out: the upper instability's tongue at other ranges, another epsilon.
        &[
            "--preset",
            "kapitza-falls",
            "--columns",
            "-3,3",
            "--rows",
            "0.05,30",
            "--grid",
            "180x90",
        ],
        &[
            "--preset",
            "kapitza-stiff",
            "--position",
            "hanging",
            "--columns",
            "-1,8",
            "--rows",
            "0.01,12",
            "--grid",
            "150x120",
        ],
    ] {
        let inferred = equal_to_exhaustive(args);
        assert!(inferred > 5000, "{args:?}: {inferred} inferred");
    }
}

#[test]
fn the_celts_charts_compute_every_cell_and_equal_the_exhaustive_ones() {
    // The celt infers no region (lone chaotic cells: `CeltChart::infers`).
    for args in [
        &[
            "--preset",
            "celt-fast-spin",
            "--grid",
            "24x12",
            "--t-end",
            "5",
        ][..],
        &[
            "--preset",
            "celt-pitching",
            "--grid",
            "20x10",
            "--t-end",
            "4",
            "--columns",
            "-30,30",
        ],
    ] {
        assert_eq!(equal_to_exhaustive(args), 0, "{args:?}");
    }
}

#[test]
fn a_refined_charts_csv_says_which_cells_were_computed() {
    let (code, csv, err) = bin(&[
        "study",
        "map",
        "--preset",
        "kapitza-upright",
        "--grid",
        "60x30",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let mut lines = csv.lines();
    assert!(lines.next().unwrap().ends_with(",decided,mark"), "{csv}");
    let marks: Vec<&str> = lines.map(|l| l.rsplit(',').next().unwrap()).collect();
    assert_eq!(marks.len(), 1800);
    assert!(marks.iter().all(|m| *m == "computed" || *m == "inferred"));
    assert!(marks.contains(&"inferred") && marks.contains(&"computed"));
    // An inferred cell's row has the answer and no trace.
    let row = csv.lines().find(|l| l.ends_with(",inferred")).unwrap();
    let fields: Vec<&str> = row.split(',').collect();
    assert_eq!(fields[4], "", "no trace: {row}");
    assert_eq!(fields[6], "true", "decided: {row}");
}

#[test]
fn the_reviews_windows_keep_every_tongue() {
    // shared/docs/reviews/reliability.md N3 and issue 80: an uncertified refinement inferred
    // these tongues and bands away.
    for args in [
        &[
            "--preset",
            "kapitza-upright",
            "--grid",
            "96x64",
            "--set",
            "pendulum.epsilon=0.3",
            "--columns",
            "-10,10",
            "--rows",
            "0.01,30",
        ][..],
        &[
            "--preset",
            "kapitza-upright",
            "--grid",
            "96x64",
            "--set",
            "pendulum.epsilon=0.3",
            "--columns",
            "0,50",
            "--rows",
            "0.1,100",
        ],
        &[
            "--preset",
            "kapitza-upright",
            "--grid",
            "96x64",
            "--position",
            "hanging",
            "--set",
            "pendulum.epsilon=0.3",
            "--columns",
            "-5,30",
            "--rows",
            "0.01,10",
        ],
        &[
            "--preset",
            "kapitza-upright",
            "--grid",
            "200x100",
            "--position",
            "hanging",
            "--set",
            "pendulum.epsilon=0.3",
            "--columns",
            "0,50",
            "--rows",
            "0.001,10",
        ],
    ] {
        equal_to_exhaustive(args);
    }
}

/// A random window of the pendulum's chart: ε from 1e-2 to 0.5, either position, wide or
/// narrow, `a` across (linear) and `b` up (log), a small grid.
fn pendulum_window(g: &mut Seeded) -> Vec<String> {
    let eps = g.log_uniform(1e-2, 0.5);
    let hanging = g.next_u64().is_multiple_of(2);
    // The tongues' roots are at |a| = n²/(4ε²): windows around them, or anywhere.
    let scale = 1.0 / (4.0 * eps * eps);
    let centre = g.uniform(-2.0, 12.0) * scale;
    let width = g.log_uniform(0.05, 20.0) * scale;
    let (b_lo, b_hi) = {
        let lo = g.log_uniform(1e-3, 1.0 / eps);
        (lo, lo * g.log_uniform(2.0, 1e4))
    };
    let (cols, rows) = (g.int(8, 48), g.int(6, 32));
    let mut args = vec![
        "--preset".to_owned(),
        "kapitza-upright".to_owned(),
        "--set".to_owned(),
        format!("pendulum.epsilon={eps}"),
        "--columns".to_owned(),
        format!("{},{}", centre - width / 2.0, centre + width / 2.0),
        "--rows".to_owned(),
        format!("{b_lo},{b_hi}"),
        "--grid".to_owned(),
        format!("{cols}x{rows}"),
    ];
    if hanging {
        args.extend(["--position".to_owned(), "hanging".to_owned()]);
    }
    args
}

#[test]
fn generated_pendulum_windows_equal_the_exhaustive_ones() {
    let mut g = Seeded::new("generated pendulum windows");
    for _ in 0..40 {
        let args = pendulum_window(&mut g);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        equal_to_exhaustive_tagged(&args, &g.tag());
    }
}

#[test]
fn generated_full_model_windows_equal_the_exhaustive_ones() {
    let mut g = Seeded::new("generated full-model windows");
    for _ in 0..3 {
        let k = g.log_uniform(1e2, 1e5);
        let lo = g.log_uniform(0.05, 2.0);
        let args = [
            "--preset".to_owned(),
            g.pick(&["subcritical", "soft-spring", "just-above"])
                .to_string(),
            "--k".to_owned(),
            format!("{k}"),
            "--ratio-max".to_owned(),
            format!("{}", g.log_uniform(0.2, 4.0)),
            "--inertia-min".to_owned(),
            format!("{lo}"),
            "--inertia-max".to_owned(),
            format!("{}", lo * g.log_uniform(1.5, 20.0)),
            "--t-end".to_owned(),
            format!("{}", g.uniform(5.0, 20.0)),
            "--grid".to_owned(),
            format!("{}x{}", g.int(10, 20), g.int(6, 12)),
        ];
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        equal_to_exhaustive_tagged(&args, &g.tag());
    }
}
