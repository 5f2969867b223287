//! The explorer honours every key of the preset schema that `simulate` honours: a table walks
//! each model's schema, and for each key that decides the computation, a preset that sets it to a
//! value other than the base preset's ends on screen (through the worker's interpreter at ×1024)
//! exactly where `simulate --format json` ends, bit for bit; the limit drawn and counted is
//! `simulate`'s limit, bit for bit too. A key added to a schema fails here until it is walked.

use crate::common;

use common::Headless;
use rattleback::physics::ModelKind;
use rattleback::scenario::preset::schema;

/// `(base preset, section.key = value, more settings it needs)` for every computing key.
const RATTLEBACK: &[(&str, &[&str])] = &[
    ("body.ix=2.5", &[]),
    ("body.iy=1.2", &[]),
    ("body.iz=1.5", &[]),
    ("spring.k=3000", &[]),
    ("initial.gamma=0.05", &[]),
    ("initial.alpha=0.1", &[]),
    ("initial.gamma_dot=1.1", &[]),
    ("initial.alpha_dot=0.4", &[]),
    ("run.t_end=12", &[]),
    ("run.method=\"dop853\"", &[]),
    ("run.tolerance=1e-7", &[]),
    ("run.step=0.005", &["run.method=\"rk4\"", "run.t_end=6"]),
];

const KAPITZA: &[(&str, &[&str])] = &[
    ("pendulum.a=0.8", &[]),
    ("pendulum.b=1.8", &[]),
    ("pendulum.epsilon=0.01", &[]),
    ("initial.theta=0.2", &[]),
    ("initial.theta_dot=0.1", &[]),
    ("run.t_end=8", &[]),
    ("run.method=\"dop853\"", &[]),
    ("run.tolerance=1e-7", &[]),
    ("run.step=0.0005", &["run.method=\"rk4\"", "run.t_end=3"]),
];

/// The keys that only say how things look (or name the preset): the walk leaves them out.
fn computes(section: &str) -> bool {
    !matches!(section, "preset" | "view")
}

use crate::common::simulate_json;

fn simulate(preset: &str, sets: &[&str]) -> serde_json::Value {
    let mut args = vec!["--preset", preset];
    for s in sets {
        args.push("--set");
        args.push(s);
    }
    simulate_json(&args)
}

fn bits(v: &serde_json::Value) -> u64 {
    v.as_f64()
        .unwrap_or_else(|| panic!("not a number: {v}"))
        .to_bits()
}

fn walk(base: &str, table: &[(&str, &[&str])], schema: &[rattleback::scenario::preset::KeySpec]) {
    // The table covers the schema: every computing key is walked.
    for k in schema.iter().filter(|k| computes(k.section)) {
        let key = format!("{}.{}=", k.section, k.key);
        assert!(
            table.iter().any(|(set, _)| set.starts_with(&key)),
            "{base}: the key {}.{} is not walked",
            k.section,
            k.key
        );
    }
    let (q, q_dot) = if base.starts_with("kapitza") {
        ("theta", "theta_dot")
    } else {
        ("alpha", "alpha_dot")
    };
    for (set, more) in table {
        let mut sets: Vec<&str> = more.to_vec();
        sets.push(set);
        let preset = rattleback::scenario::shipped::resolve(
            base,
            &sets.iter().map(|s| s.parse().unwrap()).collect::<Vec<_>>(),
        )
        .unwrap();
        let mut h = Headless::of(&preset);
        h.play_until(f64::INFINITY, 1024.0);
        assert!(h.app.run.done(), "{base} {set}: not done");
        let shown = *h.app.run.current().unwrap();
        let json = simulate(base, &sets);
        assert_eq!(
            shown.t.to_bits(),
            bits(&json["final"]["t"]),
            "{base} {set}: t"
        );
        assert_eq!(
            [shown.slow.to_bits(), shown.rate.to_bits()],
            [bits(&json["final"][q]), bits(&json["final"][q_dot])],
            "{base} {set}: the screen at t_end is not simulate's ({} {}) vs ({} {})",
            shown.slow,
            shown.rate,
            json["final"][q],
            json["final"][q_dot]
        );
        // The command `y` copies runs the screen again: same final state, bit for bit.
        let copied = h.app.scenario.simulate_command();
        let words: Vec<&str> = copied.split_whitespace().skip(2).collect();
        let again = simulate_json(&words);
        assert_eq!(
            [bits(&again["final"][q]), bits(&again["final"][q_dot])],
            [shown.slow.to_bits(), shown.rate.to_bits()],
            "{base} {set}: the copied command `{copied}` does not reproduce the screen"
        );
        // The limit: the overlay's last sample is simulate's `effective`.
        let limit = *h
            .app
            .run
            .effective_trail
            .last()
            .expect("the limit is drawn");
        assert_eq!(limit.t.to_bits(), shown.t.to_bits());
        assert_eq!(
            [limit.slow.to_bits(), limit.rate.to_bits()],
            [bits(&json["effective"][q]), bits(&json["effective"][q_dot])],
            "{base} {set}: the limit drawn is not simulate's"
        );
    }
}

#[test]
fn every_rattleback_key_ends_where_simulate_ends() {
    walk("subcritical", RATTLEBACK, &schema(ModelKind::Rattleback));
}

#[test]
fn every_pendulum_key_ends_where_simulate_ends() {
    walk("kapitza-upright", KAPITZA, &schema(ModelKind::Kapitza));
}

/// Issue 55: the command `y` copies names the preset that is loaded (`just-below` was copied as
/// `--preset subcritical --set …`: the numbers reproduced, the story did not), or the file it
/// came from; run, it reports that preset and ends on the screen's final state, bit for bit.
#[test]
fn the_copied_command_names_the_loaded_preset() {
    let dir = std::env::temp_dir().join(format!("rattleback-copied-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("my start.toml");
    std::fs::write(
        &file,
        include_str!("../../presets/just-below.toml").replace("t_end = 60.0", "t_end = 7.0"),
    )
    .unwrap();
    let mut names: Vec<String> = ["just-below", "kapitza-falls", "celt-stubby", "soft-spring"]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
    names.push(file.display().to_string());
    for name in names {
        let preset = rattleback::scenario::shipped::resolve(&name, &[]).unwrap();
        let mut h = Headless::of(&preset);
        h.play_until(f64::INFINITY, 1024.0);
        let shown = *h.app.run.current().unwrap();
        let copied = h.app.scenario.simulate_command();
        let words = shell_words(&copied);
        assert_eq!(
            words[..3],
            ["rattleback", "simulate", "--preset"],
            "{copied}"
        );
        let named = std::fs::canonicalize(&words[3])
            .map_or_else(|_| words[3].clone(), |p| p.display().to_string());
        let want = std::fs::canonicalize(&name).map_or(name.clone(), |p| p.display().to_string());
        assert_eq!(named, want, "{copied}");
        let args: Vec<&str> = words[2..].iter().map(String::as_str).collect();
        let json = simulate_json(&args);
        assert_eq!(json["preset"], preset.name.as_str(), "{copied}");
        // The same end as the preset run by its own name (which the screen matches, above).
        let plain = simulate_json(&["--preset", &name]);
        assert_eq!(json["final"], plain["final"], "{name}: `{copied}`");
        assert_eq!(bits(&json["final"]["t"]), shown.t.to_bits(), "{copied}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The words of a command line as a POSIX shell splits them (single quotes only, as the
/// copied command writes them).
fn shell_words(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word = String::new();
    let mut quoted = false;
    let mut any = false;
    for c in line.chars() {
        match c {
            '\'' => {
                quoted = !quoted;
                any = true;
            }
            ' ' if !quoted => {
                if any || !word.is_empty() {
                    out.push(std::mem::take(&mut word));
                }
                any = false;
            }
            c => word.push(c),
        }
    }
    if any || !word.is_empty() {
        out.push(word);
    }
    out
}
