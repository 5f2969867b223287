//! The integration tests, as modules of one test binary: the library is linked once, not once
//! per file (issue 25; the first `cargo test` before and after is in docs/benchmarks.md). Run one
//! group with `cargo test --test it GROUP::` (for example `cargo test --test it bounded::`).
//!
//! They are the package `rattleback-it` (`tests/it/Cargo.toml`), beside the program's in one
//! workspace, so that their dependencies are none of the program's (issue 68); they run the
//! program's binary from the same target folder (`common::bin`).

/// The repository's root, where the presets, docs, fixtures and `src/` are: this package
/// lives in `tests/it` (issue 68). A macro, so that `concat!` and `include_str!` take it.
macro_rules! root {
    () => {
        concat!(env!("CARGO_MANIFEST_DIR"), "/../..")
    };
}

mod common;

mod auto_honest;
mod averaged;
mod bad_presets;
mod bench_study;
mod bounded;
mod budget;
mod celt;
mod charsets;
mod charts;
mod cli_conventions;
mod compare;
mod completions;
mod convergence_order;
mod docs_commands;
mod ecosystem;
mod effective_limit;
mod energy;
mod explorer_app;
mod explorer_panes;
mod explorer_screens;
mod explorer_ui;
mod follow;
mod fork;
mod generated;
mod honesty;
mod hostile;
mod hostile6;
mod hostile_props;
mod hygiene;
mod kapitza;
mod kapitza_cli;
mod kapitza_explorer;
mod layering;
mod lecture;
mod lecture_lessons;
mod lecture_trust;
mod legend;
mod lesson_review;
mod lessons;
mod page;
mod presets_themes;
mod prices;
mod program;
mod readme;
mod record_replay;
mod reference_cases;
mod refined;
mod scenes;
mod schema_walk;
mod schemas;
mod segments;
mod serve;
mod session_format;
mod signals;
mod special_solutions;
mod stiff;
mod stress;
mod studies;
mod trust;
mod user_folder;
mod widgets;
