//! Charts computed where their answer changes (issue 70): every cell's answer (its count of
//! reversals, its stability verdict, or undecided) equal to `--exhaustive`'s, cell for cell,
//! on several charts of each scene (default axes and held-out ones, islands and thin tongues
//! among them); each cell marked `computed` or `inferred`; the computed ones bit for bit the
//! exhaustive run's.

use crate::common::bin;

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = bin(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

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
    let mut refined_args = vec!["study", "map", "--format", "json", "--force"];
    refined_args.extend_from_slice(args);
    let refined = json(&refined_args);
    refined_args.push("--exhaustive");
    let every = json(&refined_args);
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
            "{args:?}: cell {} refined {r} exhaustive {e}",
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
fn the_rattlebacks_limit_charts_equal_the_exhaustive_ones() {
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
        let inferred = equal_to_exhaustive(args);
        assert!(inferred > 1000, "{args:?}: {inferred} inferred");
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
