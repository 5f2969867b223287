//! The celt scene against the repository's own references (tests/fixtures/celt/references.json,
//! made by `scripts/celt_references.py` with scipy's DOP853 on an independent implementation that
//! shares no code with the crate), and its symmetries as property tests.

use proptest::prelude::*;
use serde_json::Value;

use rattleback::physics::Method;
use rattleback::physics::celt::run::run;
use rattleback::physics::celt::{Params, Problem, Start};
use rattleback::physics::method::RunSpec;
use rattleback::scenario::shipped::{SHIPPED, resolve as preset};
use rattleback::simulate::{self, Format, Request};

fn references() -> Value {
    serde_json::from_str(include_str!("../fixtures/celt/references.json")).expect("fixture")
}

fn report(name: &str, method: Option<Method>, tolerance: f64) -> Value {
    let p = preset(name, &[]).expect("shipped");
    let req = Request {
        method,
        tolerance: Some(tolerance),
        step: None,
        t_end: None,
        format: Format::Json,
        samples: 0,
        force: false,
    };
    let resolved = simulate::resolve(&p, &req);
    serde_json::from_str(&simulate::simulate(&p, &resolved, Format::Json).expect("runs"))
        .expect("json")
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn every_shipped_celt_preset_is_in_the_references() {
    let refs = references();
    let names: Vec<&str> = refs["cases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["preset"].as_str().unwrap())
        .collect();
    let shipped: Vec<&str> = SHIPPED
        .iter()
        .map(|(n, _)| *n)
        .filter(|n| n.starts_with("celt-"))
        .collect();
    assert!(shipped.len() >= 5, "{shipped:?}");
    for n in &shipped {
        assert!(
            names.contains(n),
            "{n} has no reference: run scripts/celt_references.py"
        );
    }
}

/// The bar: at tolerance 1e-10 (`auto`, the default), the final ω within 1e-6 rad/s,
/// the crossing and reversal counts exact, the energy within 1e-8 relative, crossing times
/// within 1e-6 s.
#[test]
fn simulate_matches_the_references_on_every_shipped_preset() {
    for case in references()["cases"].as_array().unwrap() {
        let name = case["preset"].as_str().unwrap();
        let r = report(name, None, 1e-10);
        let want = &case["reference"];
        let err = max_diff(&floats(&r["final"]["omega"]), &floats(&want["omega"]));
        assert!(err <= 1e-6, "{name}: final omega off by {err:e}");
        assert!(
            max_diff(&floats(&r["final"]["gamma"]), &floats(&want["gamma"])) <= 1e-7,
            "{name}: gamma"
        );
        assert_eq!(
            r["events"]["crossings"]["count"], want["crossings"],
            "{name}: crossings"
        );
        assert_eq!(
            r["events"]["reversals"]["count"], want["reversals"],
            "{name}: reversals"
        );
        let dt = max_diff(
            &floats(&r["events"]["crossings"]["times"]),
            &floats(&want["crossing_times"]),
        );
        assert!(dt <= 1e-6, "{name}: crossing times off by {dt:e}");
        let e_ref = want["energy_initial"].as_f64().unwrap();
        for key in ["initial", "final"] {
            let e = r["energy"][key].as_f64().unwrap();
            assert!(
                ((e - e_ref) / e_ref).abs() <= 1e-8,
                "{name}: energy {key} {e} against {e_ref}"
            );
        }
        assert!(r["constraint"]["contact_height_max"].as_f64().unwrap() < 1e-8);
        // `auto`'s claim holds: a met estimate bounds the error it claims.
        let auto = &r["auto"];
        assert!(
            auto["error_estimate"].as_f64().unwrap() >= err,
            "{name}: estimate below the error {err:e}"
        );
    }
}

/// DOP853 and its projected variant converge to the reference as the tolerance shrinks, with
/// errors of the size the reference's own DOP853 (scipy) makes at the same tolerance.
#[test]
fn both_methods_converge_like_the_references_own_dop853() {
    for case in references()["cases"].as_array().unwrap() {
        let name = case["preset"].as_str().unwrap();
        let want = floats(&case["reference"]["omega"]);
        let spread = case["omega_uncertainty"].as_f64().unwrap();
        for method in [Method::Dop853, Method::Dop853Projected] {
            let mut last = f64::INFINITY;
            for (tol, key) in [(1e-8, "1e-08"), (1e-10, "1e-10")] {
                let r = report(name, Some(method), tol);
                let err = max_diff(&floats(&r["final"]["omega"]), &want);
                let scipy = case["at_tolerance"][key]["omega_error"].as_f64().unwrap();
                assert!(
                    err <= 10.0 * scipy.max(spread),
                    "{name} {method} at {tol:e}: {err:e} against scipy's {scipy:e}"
                );
                assert!(err < last, "{name} {method}: no convergence at {tol:e}");
                last = err;
            }
        }
    }
}

#[test]
fn the_projected_method_keeps_the_constraints_to_rounding() {
    for name in ["celt-clockwise", "celt-fast-spin"] {
        let plain = report(name, Some(Method::Dop853), 1e-8);
        let projected = report(name, Some(Method::Dop853Projected), 1e-8);
        let c = |r: &Value, k: &str| r["constraint"][k].as_f64().unwrap();
        assert!(c(&projected, "gamma_norm_error") < 1e-14, "{name}");
        assert!(c(&projected, "contact_height_max") < 1e-13, "{name}");
        assert!(
            c(&plain, "gamma_norm_error") > 100.0 * c(&projected, "gamma_norm_error"),
            "{name}: the plain method drifts off |γ| = 1 at 1e-8"
        );
    }
}

fn kl(product: f64, roll: f64, pitch: f64, omega: [f64; 3]) -> Problem {
    Problem::new(
        Params {
            product,
            ..Params::KANE_LEVINSON
        },
        Start {
            roll,
            pitch,
            yaw: 0.0,
            omega,
        },
        0.5,
    )
    .expect("valid")
}

fn final_state(p: &Problem, t_end: f64) -> Vec<f64> {
    let spec = RunSpec {
        method: Method::Dop853,
        tolerance: 1e-13,
        t_end,
        samples: 0,
        step: None,
        monitor_energy: true,
    };
    run(p, &spec, &mut |_| true)
        .expect("runs")
        .state
        .iter()
        .copied()
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Reflection y → −y (model.md §6): the body with −D, started with −roll and
    /// ω0 → (−ωx, ωy, −ωz), gives ω → (−ωx, ωy, −ωz) and γ → (γx, −γy, γz).
    #[test]
    fn the_mirror_body_moves_as_the_mirror_image(
        d in -0.5f64..0.5,
        roll in -0.05f64..0.05,
        pitch in -0.05f64..0.05,
        w in prop::array::uniform3(-6.0f64..6.0),
    ) {
        let a = final_state(&kl(d, roll, pitch, w), 1.5);
        let b = final_state(&kl(-d, -roll, pitch, [-w[0], w[1], -w[2]]), 1.5);
        let mirrored = [-a[0], a[1], -a[2], a[3], -a[4], a[5]];
        for i in 0..6 {
            prop_assert!((b[i] - mirrored[i]).abs() < 1e-8, "component {i}: {} vs {}", b[i], mirrored[i]);
        }
    }

    /// Time reversal (model.md §6): from (ω, γ) at T, flip ω and integrate T again; the body
    /// comes back to (−ω0, γ0).
    #[test]
    fn flipping_omega_runs_the_motion_backwards(
        roll in -0.05f64..0.05,
        pitch in -0.05f64..0.05,
        rock in prop::array::uniform2(-3.0f64..3.0),
        spin in -6.0f64..6.0,
    ) {
        let w = [rock[0], rock[1], spin];
        let p = kl(-0.2, roll, pitch, w);
        let y = final_state(&p, 1.0);
        // The state at T as a new start: its attitude in angles (yaw, roll, pitch) from γ and q.
        let g = [y[3], y[4], y[5]];
        let roll_t = g[1].asin();
        let pitch_t = (-g[0]).atan2(g[2]);
        // A start that tumbled past the range a start may have is not a test of reversal.
        prop_assume!(roll_t.abs() < 1.4 && pitch_t.abs() < 1.4);
        let back = Problem::new(
            Params::KANE_LEVINSON,
            Start { roll: roll_t, pitch: pitch_t, yaw: 0.0, omega: [-y[0], -y[1], -y[2]] },
            0.5,
        ).expect("valid");
        let z = final_state(&back, 1.0);
        for i in 0..3 {
            prop_assert!((z[i] + w[i]).abs() < 1e-6, "omega {i}: {} vs {}", z[i], -w[i]);
        }
        let g0 = [-pitch.sin() * roll.cos(), roll.sin(), pitch.cos() * roll.cos()];
        for i in 0..3 {
            prop_assert!((z[3 + i] - g0[i]).abs() < 1e-7, "gamma {i}");
        }
    }
}

fn celt_presets() -> Vec<&'static str> {
    SHIPPED
        .iter()
        .map(|(n, _)| *n)
        .filter(|n| preset(n, &[]).unwrap().model.kind() == rattleback::physics::ModelKind::Celt)
        .collect()
}

/// What the explorer shows at `t_end`, through the worker's interpreter at ×1 and ×1024, is
/// `simulate`'s run bit for bit (the same verified plan), with the same reversals and
/// crossings; the status bar at 80×24 says both counts.
#[test]
fn every_celt_preset_ends_in_the_explorer_where_simulate_ends() {
    use rattleback::app::PlanState;
    use rattleback::physics::Model;
    for name in celt_presets() {
        for speed in [1024.0, 1.0] {
            let mut h = crate::common::Headless::new(name);
            // At ×1 the first two seconds (the clockwise reversal is near 3 s: enough to check
            // the counts shown before it), at ×1024 the whole run.
            let until = if speed > 1.0 { f64::INFINITY } else { 2.0 };
            h.play_until(until, speed);
            let app = &h.app;
            let s = app.scenario.settings;
            let Model::Celt(problem) = s.model else {
                panic!("{name}: not the celt")
            };
            let shown = *app.run.current().expect("a point");
            let PlanState::Running { plan, estimate } = app.run.plan else {
                panic!("{name}: no plan")
            };
            if s.method == Method::Auto {
                assert!(estimate.is_some(), "{name}: auto is verified");
            }
            let simulated = run(
                &problem,
                &RunSpec {
                    method: plan.method,
                    tolerance: plan.tolerance,
                    t_end: shown.t,
                    samples: 0,
                    step: None,
                    monitor_energy: true,
                },
                &mut |_| true,
            )
            .unwrap();
            if speed > 1.0 {
                assert!(app.run.done(), "{name}: not done");
                assert_eq!(shown.t.to_bits(), s.t_end.to_bits(), "{name}");
                let y = simulated.state;
                assert_eq!(
                    [shown.slow.to_bits(), shown.rate.to_bits()],
                    [
                        y[12].to_bits(),
                        rattleback::physics::celt::spin(&y).to_bits()
                    ],
                    "{name}: the screen and simulate differ"
                );
            }
            assert_eq!(
                app.run.reversals_shown(),
                simulated.reversal_count,
                "{name} ×{speed}: reversals"
            );
            assert_eq!(
                app.run.crossings_shown(),
                Some(simulated.crossing_count),
                "{name} ×{speed}: crossings"
            );
            let screen = crate::explorer_ui::screen_text(&h.app, 80, 24);
            let status = screen.lines().nth(22).unwrap();
            assert!(
                status.contains(&format!("reversals {}", simulated.reversal_count))
                    && status.contains(&format!("crossings {}", simulated.crossing_count)),
                "{name} ×{speed}: {status}"
            );
            assert!(
                !status.contains("limit"),
                "{name}: no limit to count: {status}"
            );
        }
    }
}

/// A celt session recorded through the app's update function replays bit for bit: paused
/// before the reversal, played past it at ×1024, then with a changed spin that restarts the
/// run; the status values recorded at each pause (reversals and crossings) replay the same.
#[test]
fn a_recorded_celt_session_verifies() {
    use rattleback::app::journal::Event;
    use rattleback::app::{Key, Outcome};
    use rattleback::record;
    let mut h = crate::common::Headless::new("celt-clockwise");
    let app = &h.app;
    let header = crate::common::header_of(app);
    h.app.on_key(Key::Char('R'));
    h.app
        .on_outcome(Outcome::Recording(Ok("recorded.jsonl".to_owned())));
    h.key(Key::Char(' '));
    h.tick(1.7);
    h.key(Key::Char(' '));
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    for _ in 0..10 {
        h.key(Key::Char('+'));
    }
    h.key(Key::Char(' '));
    h.tick(0.002);
    h.key(Key::Char(' '));
    assert!(
        h.app.run.shown > 3.1,
        "past the reversal: {}",
        h.app.run.shown
    );
    assert_eq!(h.app.run.reversals_shown(), 1);
    assert_eq!(h.app.run.crossings_shown(), Some(3));
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    // omega_z, the 15th row, one coarse step up: restarts.
    for _ in 0..14 {
        h.key(Key::Char('j'));
    }
    h.key(Key::Char('L'));
    assert_eq!(h.app.scenario.settings.model.value("omega_z"), Some(-4.0));
    h.key(Key::Char(' '));
    h.tick(0.005);
    h.key(Key::Char(' '));
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    let journal = h.app.take_journal();
    let pauses: Vec<Option<usize>> = journal
        .iter()
        .filter_map(|(_, _, e)| match e {
            Event::Screen(shown) => Some(shown.crossings),
            _ => None,
        })
        .collect();
    assert!(pauses.contains(&Some(3)), "{pauses:?}");
    let path = std::env::temp_dir().join(format!("celt-{}.jsonl", std::process::id()));
    let mut journal = journal;
    h.stop_recording();
    journal.extend(h.app.take_journal());
    let back = crate::common::write_session(&path, &header, journal, 0.5);
    assert!(back.header.preset.contains("model = \"celt\""));
    assert!(record::verify(&back, "celt", None).unwrap().checkpoints >= 3);
    let _ = std::fs::remove_file(&path);
}

/// The celt from above: its long axis (semi-axis a) turns with the angle turned, the bar
/// shows its tilt, and the ring changes sign where the spin reversed; at 80×24 and 160×48.
#[test]
fn the_celt_body_pane_at_80x24_and_160x48() {
    use rattleback::app::Key;
    let mut h = crate::common::Headless::new("celt-clockwise");
    h.key(Key::Char('B'));
    h.play_until(5.0, 4.0);
    h.key(Key::Char(' '));
    let small = crate::explorer_ui::screen_text(&h.app, 80, 24);
    assert!(small.contains("body from above, side, end (B)"), "{small}");
    assert!(
        small.contains("side, pitch") && small.contains("end, roll"),
        "{small}"
    );
    // The reversal near 3 s is inside the trace's window: both senses are on the ring.
    assert!(small.contains('+') && small.contains('-'), "{small}");
    insta::assert_snapshot!("celt_body_80x24", small);
    let large = crate::explorer_ui::screen_text(&h.app, 160, 48);
    assert!(large.contains("rocking |tilt|"), "{large}");
    insta::assert_snapshot!("celt_body_160x48", large);
}

/// The side and end views read the lean of the state on display: at the end of the run, the
/// pitch and roll they print are those of the independent reference's final `γ`
/// (`asin γ_x`, `asin γ_y`), to the three decimals printed, at x1024.
#[test]
fn the_side_and_end_views_show_the_reference_lean_at_the_end() {
    use rattleback::app::Key;
    for case in references()["cases"].as_array().unwrap() {
        let name = case["preset"].as_str().unwrap();
        if !["celt-clockwise", "celt-fast-spin", "celt-anticlockwise"].contains(&name) {
            continue;
        }
        let t_end = case["t_end"].as_f64().unwrap();
        let gamma = floats(&case["reference"]["gamma"]);
        let mut h = crate::common::Headless::new(name);
        h.key(Key::Char('B'));
        h.play_until(t_end, 1024.0);
        assert_eq!(h.app.run.current().map(|p| p.t), Some(t_end), "{name}");
        let screen = crate::explorer_ui::screen_text(&h.app, 160, 48);
        let read = |label: &str| -> f64 {
            let at = screen
                .find(label)
                .unwrap_or_else(|| panic!("{label}: {screen}"));
            screen[at + label.len()..]
                .split_whitespace()
                .next()
                .and_then(|w| w.parse().ok())
                .unwrap_or_else(|| panic!("{label}: {screen}"))
        };
        let (pitch, roll) = (read("side, pitch "), read("end, roll "));
        assert!(
            (pitch - gamma[0].asin()).abs() <= 6e-4,
            "{name}: pitch {pitch}"
        );
        assert!(
            (roll - gamma[1].asin()).abs() <= 6e-4,
            "{name}: roll {roll}"
        );
    }
}

/// Issue 68: at 80×24 the celt's panel is taller than its pane; the border says how many rows
/// are out of sight, and selecting the last parameter (↑ from the first) scrolls them in.
#[test]
fn the_celt_panel_scrolls_its_hidden_rows_into_sight_at_80x24() {
    use rattleback::app::Key;
    let mut h = crate::common::Headless::new("celt-clockwise");
    let top = crate::explorer_ui::screen_text(&h.app, 80, 24);
    let hidden = top
        .lines()
        .find_map(|l| l.split("↓ ").nth(1).and_then(|r| r.split(" more").next()))
        .unwrap_or_else(|| panic!("no marker of hidden rows: {top}"));
    let hidden: usize = hidden.trim().parse().unwrap();
    assert!(hidden > 0, "{top}");
    h.key(Key::Up);
    let bottom = crate::explorer_ui::screen_text(&h.app, 80, 24);
    assert!(bottom.contains(&format!(" ↑{hidden} ")), "{bottom}");
    assert!(!bottom.contains(" more ┘"), "{bottom}");
    let panel = |screen: &str| -> Vec<String> {
        screen
            .lines()
            .map(|l| l.chars().take(30).collect::<String>())
            .collect()
    };
    // Rows that were out of sight are on the screen now.
    let before = panel(&top);
    let after = panel(&bottom);
    assert!(after.iter().any(|l| !before.contains(l)), "{bottom}");
}
