//! Helpers shared by the integration tests.
#![allow(dead_code)]

use rattleback::physics::{Params, Problem, Start};

/// Path of the shared reference cases (`../shared/reference/cases.toml` beside the checkout),
/// overridable with `RATTLEBACK_REFERENCE`.
pub fn reference_path() -> std::path::PathBuf {
    std::env::var_os("RATTLEBACK_REFERENCE").map_or_else(
        || std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/reference/cases.toml"),
        Into::into,
    )
}

/// The parsed reference file; a missing file is a failure, not a skip.
#[track_caller]
pub fn reference_cases() -> toml::Table {
    let path = reference_path();
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read reference cases {}: {e}", path.display()));
    text.parse::<toml::Table>()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[track_caller]
pub fn num(t: &toml::Table, key: &str) -> f64 {
    match t.get(key) {
        Some(toml::Value::Float(f)) => *f,
        #[allow(clippy::cast_precision_loss)]
        Some(toml::Value::Integer(i)) => *i as f64,
        other => panic!("reference key {key}: expected a number, got {other:?}"),
    }
}

/// A problem built from raw numbers.
#[track_caller]
pub fn problem(ix: f64, iy: f64, iz: f64, k: f64, start: [f64; 4]) -> Problem {
    Problem::new(
        Params { ix, iy, iz, k },
        Start {
            gamma: start[0],
            alpha: start[1],
            gamma_dot: start[2],
            alpha_dot: start[3],
        },
    )
    .expect("valid test problem")
}

/// The problem of one reference case.
#[track_caller]
pub fn case_problem(case: &toml::Table) -> Problem {
    problem(
        num(case, "ix"),
        num(case, "iy"),
        num(case, "iz"),
        num(case, "k"),
        [
            num(case, "gamma"),
            num(case, "alpha"),
            num(case, "gamma_dot"),
            num(case, "alpha_dot"),
        ],
    )
}
