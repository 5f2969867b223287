//! Trust at the new doors (issue 66): every reproduction of the fifth reliability review
//! (`tests/fixtures/hostile5/`, copied from the review) refused or answered right, through the
//! real binary. The shard script's own hostile names are run by CI (`.ci/run`, which has GNU
//! parallel); the parts' provenance is tested in `study::part`'s unit tests as well.

use crate::common::bin;
use rattleback::app::journal::Event;
use rattleback::record::{Line, Recorder};

fn fixture(name: &str) -> String {
    format!("{}/tests/fixtures/hostile5/{name}", root!())
}

#[track_caller]
fn refused(args: &[&str], needles: &[&str]) -> String {
    let (code, out, err) = bin(args);
    assert_eq!(code, 2, "{args:?}: exit {code}, stdout {out}, stderr {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: lacks `{n}`: {err}");
    }
    err
}

/// H2/R15: a celt body whose squared moments overflow is no body; R8's residue: what `check`
/// passes, `simulate` runs, and both refuse the same three files with the same words.
#[test]
fn check_and_simulate_refuse_the_same_impossible_presets() {
    for (file, words) in [
        ("celt-ix-1e155.toml", "principal moments"),
        ("check-ok-simulate-fails-iy.toml", "within a factor 1e12"),
        (
            "check-ok-simulate-fails-alpha.toml",
            "an angle of magnitude at most 1e6",
        ),
        (
            "check-ok-simulate-fails-theta.toml",
            "an angle of magnitude at most 1e6",
        ),
    ] {
        let path = fixture(file);
        let by_check = refused(&["check", &path], &[words]);
        let by_simulate = refused(&["simulate", "--preset", &path], &[words]);
        assert_eq!(
            by_check, by_simulate,
            "{file}: check and simulate say the same"
        );
        // A 300-digit decimal is no message (R20).
        assert!(!by_check.contains("0000000000"), "{by_check}");
    }
    // The chart that ran for minutes is refused at once.
    refused(
        &[
            "study",
            "map",
            "--preset",
            "celt-clockwise",
            "--set",
            "celt.ix=1e300",
            "--grid",
            "1x1",
        ],
        &["celt.ix", "principal moments"],
    );
}

/// H6, H9: a session line the program never writes is refused by the one validator that
/// replay, follow and `--verify` share.
#[test]
fn impossible_sessions_do_not_verify() {
    refused(
        &["replay", "--verify", &fixture("mc-out-of-range.jsonl")],
        &[
            "mc-out-of-range.jsonl:4",
            "map cursor at column 18446744073709551615",
            "48 columns",
        ],
    );
    refused(
        &[
            "replay",
            "--verify",
            &fixture("impossible-header-and-set.jsonl"),
        ],
        &[
            "impossible-header-and-set.jsonl:1",
            "method",
            "not one of the",
        ],
    );
    // A `set` of a field the scene has not (a pendulum session setting the rattleback's
    // `gamma_dot`), re-chained as a forger would: refused by verify, replay's reader and follow.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("set.jsonl");
    let h = crate::common::Headless::new("kapitza-upright");
    let header = crate::common::header_of(&h.app);
    let mut rec = Recorder::create(&path, &header, None).unwrap();
    for (i, event) in [
        Event::Set {
            field: "gamma_dot".into(),
            value: "1e16".into(),
        },
        Event::end(),
    ]
    .into_iter()
    .enumerate()
    {
        rec.write(&Line {
            wall: i as f64,
            t: 0.0,
            generation: 1,
            chain: None,
            event,
        })
        .unwrap();
    }
    drop(rec);
    let p = path.display().to_string();
    refused(
        &["replay", "--verify", &p],
        &["set.jsonl:2", "gamma_dot", "pendulum"],
    );
    assert!(rattleback::record::read(&path).is_err());
    assert!(rattleback::record::tail::Tail::open(&path).is_err());
    // The same file with a field the pendulum has verifies that far (the validator is not a
    // blanket refusal).
    let good = dir.path().join("good.jsonl");
    let mut rec = Recorder::create(&good, &header, None).unwrap();
    rec.write(&Line {
        wall: 0.0,
        t: 0.0,
        generation: 1,
        chain: None,
        event: Event::Set {
            field: "b".into(),
            value: "2.5".into(),
        },
    })
    .unwrap();
    drop(rec);
    assert!(rattleback::record::read(&good).is_ok());
}

/// H5: parts that no run could write are refused, by their provenance.
#[test]
fn merge_refuses_forged_and_foreign_parts() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    let part = |i: usize| {
        let (code, out, err) = bin(&[
            "study",
            "map",
            "--preset",
            "kapitza-upright",
            "--grid",
            "4x3",
            "--shard",
            &format!("{i}/3"),
        ]);
        assert_eq!(code, 0, "{err}");
        out
    };
    let parts: Vec<String> = (1..=3).map(part).collect();
    let files: Vec<String> = parts
        .iter()
        .enumerate()
        .map(|(i, t)| write(&format!("p{}.json", i + 1), t))
        .collect();
    // Every part carries its description and digest; the three merge, with every cell checked.
    assert!(parts[0].contains("\"description\"") && parts[0].contains("\"digest\""));
    let (code, _, err) = bin(&[
        "study", "merge", &files[0], &files[1], &files[2], "--check", "100",
    ]);
    assert_eq!(code, 0, "{err}");
    // The review's forged files (written before parts had a description) say what they are.
    refused(
        &[
            "study",
            "merge",
            &fixture("merge-forged/part-1-coords-edited.json"),
            &fixture("merge-forged/part-2.json"),
            &fixture("merge-forged/part-3.json"),
        ],
        &["part-1-coords-edited.json", "older build", "edited"],
    );
    // An edited value without a new digest.
    let edited = parts[1].replacen("\"stable\": true", "\"stable\": false", 1);
    assert_ne!(edited, parts[1]);
    let e = write("edited.json", &edited);
    refused(
        &["study", "merge", &files[0], &e, &files[2]],
        &["edited.json", "digest does not match"],
    );
    // Another chart's description.
    let (_, other, _) = bin(&[
        "study",
        "map",
        "--preset",
        "kapitza-upright",
        "--grid",
        "4x3",
        "--set",
        "pendulum.epsilon=0.01",
        "--shard",
        "2/3",
    ]);
    let o = write("other.json", &other);
    refused(
        &["study", "merge", &files[0], &o, &files[2]],
        &["other.json", "another chart"],
    );
    // H4: whitespace without end on stdin, and a part far larger than its slice, are refused
    // at their cap, in bounded memory.
    let huge = parts[2].replacen(
        "\"cells\": [",
        &format!("\"cells\": [{}", " ".repeat(4 << 20)),
        1,
    );
    let h = write("huge.json", &huge);
    refused(
        &["study", "merge", &files[0], &files[1], &h],
        &["huge.json", "larger than a part of this chart can be"],
    );
    refused(&["study", "merge", "-", "-"], &["`-` given twice"]);
}

/// H8: a cell whose integration fails is marked in the chart, not the end of the chart.
#[test]
fn a_failing_cell_is_marked_and_the_chart_goes_on() {
    let (code, out, err) = bin(&[
        "study",
        "map",
        "--preset",
        "kapitza-upright",
        "--grid",
        "4x3",
        "--columns",
        "-1e12,1e12",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let chart: serde_json::Value = serde_json::from_str(&out).unwrap();
    let cells = chart["cells"].as_array().unwrap();
    let failed: Vec<_> = cells.iter().filter(|c| c["error"].is_string()).collect();
    assert!(!failed.is_empty(), "the wide axis has failing cells");
    for c in &failed {
        assert_eq!(c["decided"], false, "{c}");
        assert!(c["stable"].is_null(), "a failed cell has no verdict: {c}");
    }
    assert!(cells.len() > failed.len(), "the others are computed");
    // The table draws them undecided.
    let (_, table, _) = bin(&[
        "study",
        "map",
        "--preset",
        "kapitza-upright",
        "--grid",
        "4x3",
        "--columns",
        "-1e12,1e12",
    ]);
    assert!(table.contains('?'), "{table}");
    // And `study map`'s JSON says what it predicted and what it took.
    assert!(chart["predicted_seconds"].as_f64().unwrap() > 0.0);
    assert!(chart["wall_seconds"].as_f64().unwrap() >= 0.0);
}

/// Residue N15: a lesson whose condition no value can meet is refused.
#[test]
fn contradictory_lesson_conditions_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("never.toml");
    std::fs::write(
        &path,
        "[lesson]\ntitle = \"never\"\n\n[[step]]\ntitle = \"one\"\npreset = \"subcritical\"\ntext = \"t\"\nuntil = { parameter = \"initial.alpha_dot\", at_least = 10, at_most = 1 }\n",
    )
    .unwrap();
    refused(
        &["check", &path.display().to_string()],
        &["at_least", "above `at_most`", "never end"],
    );
}

/// H7: `R` that cannot record says why, and the key after it is not lost.
#[test]
fn a_recording_that_cannot_start_says_why_and_keeps_the_next_key() {
    use rattleback::app::{Key, Mode, Outcome};
    let mut h = crate::common::Headless::new("subcritical");
    let effects = h
        .app
        .on_outcome(Outcome::Recording(Err(rattleback::app::ShellError::Io {
            path: "/dev/null".into(),
            source: std::io::Error::from_raw_os_error(17),
        })));
    h.exec(effects);
    let Mode::Dialog(text) = &h.app.mode else {
        panic!("a dialog says why: {:?}", h.app.mode)
    };
    assert!(
        text.contains("cannot record") && text.contains("sessions"),
        "{text}"
    );
    h.key(Key::Char('q'));
    assert!(
        h.app.quit,
        "q after the dialog quits (it closed the dialog and acted)"
    );
    // Esc only closes it.
    let mut h = crate::common::Headless::new("subcritical");
    let effects = h.app.on_outcome(Outcome::Recording(Err(
        rattleback::app::ShellError::NoFolder("no"),
    )));
    h.exec(effects);
    h.key(Key::Esc);
    assert_eq!(h.app.mode, Mode::Normal);
    assert!(!h.app.quit);
}
