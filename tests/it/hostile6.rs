//! The sixth reviews' reproductions (shared/docs/reviews/reliability.md N1–N11, lecturer.md L1,
//! copied into tests/fixtures/hostile6/), each failing on the build they were found in (issue
//! 80): a session whose clock runs backwards, writers onto what is not a regular file, a lesson's
//! walk that is priced, logins that are ssh options, and `serve` against FIFOs, links and
//! greedy clients (those in `serve.rs`).

use crate::common::bin;

fn fixture(name: &str) -> String {
    format!("{}/tests/fixtures/hostile6/{name}", root!())
}

#[test]
fn a_session_whose_clock_runs_backwards_is_refused() {
    // N11: one clock line's t moved a second ahead of the next, the chain recomputed.
    let (code, out, err) = bin(&[
        "replay",
        &fixture("clock-backwards-rechained.jsonl"),
        "--verify",
    ]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        err.contains(":9:") && err.contains("ran backwards"),
        "{err}"
    );
}
