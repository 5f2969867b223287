//! `auto`'s estimate never lies (issue 13): against the independent references of
//! `tests/fixtures/reference/averaged.toml` (full model by long-double RK8), whenever `auto`
//! says `met`, its true error in α(T), α̇(T) and the reversal times is within the tolerance,
//! and its estimate bounds that error; where it cannot reach the tolerance it says so.

// Horizons and stiffnesses are compared with the fixture's exact values.
#![allow(clippy::float_cmp)]

use crate::common;

use common::{AveragedCase, averaged_cases};
use rattleback::physics::Method;
use rattleback::physics::rattleback::auto::{Shortfall, Verified, run_auto};
use rattleback::physics::rattleback::run::RunResult;

/// The true error of a verified run against a reference case.
fn true_error(v: &Verified, case: &AveragedCase) -> f64 {
    result_error(&v.result, case)
}

/// The true error of a run against a reference case.
fn result_error(r: &RunResult, case: &AveragedCase) -> f64 {
    let y = r.final_state;
    if r.reversal_count != case.reversals.len() {
        return f64::INFINITY;
    }
    let mut e = (y[1] - case.end.0).abs().max((y[3] - case.end.1).abs());
    for (a, b) in r.reversals.iter().zip(&case.reversals) {
        e = e.max((a - b).abs());
    }
    e
}

/// The references are good to about 1e-12 up to k = 1e7 (step halving, note §5); at k = 1e8
/// (14 million long-double steps) to about 3e-11: below that an error is theirs as much as ours.
fn reference_floor(case: &AveragedCase) -> f64 {
    if case.k >= 1e8 && case.source == "rk8-long-double" {
        3e-11
    } else {
        2e-12
    }
}

fn check(case: &AveragedCase, tolerance: f64) -> Verified {
    let v = run_auto(&case.problem, tolerance, case.t_end, 0, false).unwrap();
    let err = true_error(&v, case);
    eprintln!(
        "{} tol {tolerance:e}: {} err {err:.1e} est {:.1e} met {} ({:?})",
        case.name, v.plan.method, v.error_estimate, v.met, v.shortfall
    );
    assert!(
        err <= v.error_estimate.max(reference_floor(case)),
        "{} at {tolerance:e}: {} errs by {err:e}, its estimate says {:e}",
        case.name,
        v.plan.method,
        v.error_estimate
    );
    if v.met {
        assert!(v.error_estimate <= tolerance);
        assert!(v.shortfall.is_none());
    } else {
        assert!(v.shortfall.is_some(), "a miss must say why");
    }
    v
}

#[test]
fn met_means_met_on_every_reference_start_and_stiffness() {
    for case in averaged_cases()
        .iter()
        .filter(|c| c.source == "rk8-long-double" && c.t_end == 30.0)
    {
        for tol in [1e-6, 1e-8] {
            let v = check(case, tol);
            assert!(
                v.met,
                "{}: auto should reach {tol:e} on a well-conditioned start",
                case.name
            );
        }
    }
}

#[test]
fn met_means_met_at_a_tight_tolerance() {
    // 1e-10 where the references are 100× better; k ≤ 1e4 (resolving is cheap there) and the
    // averaged model's range.
    for case in averaged_cases()
        .iter()
        .filter(|c| c.source == "rk8-long-double" && c.t_end == 30.0 && (c.k <= 1e4 || c.k >= 1e7))
    {
        check(case, 1e-10);
    }
}

#[test]
fn auto_chooses_the_averaged_model_at_large_k_and_it_agrees_with_the_notes_code() {
    // k = 1e10, 1e12: the note's own (scipy) implementation of the averaged model, whose model
    // error there is below 1e-18, is the reference. There `averaged2`'s probed error is far
    // below a tenth of the tolerance and it costs half of `averaged3`: `auto` runs it.
    for case in averaged_cases()
        .iter()
        .filter(|c| c.source == "note-averaged-model")
    {
        let v = check(case, 1e-8);
        assert_eq!(v.plan.method, Method::Averaged2, "{}", case.name);
        assert!(v.met);
        assert!(true_error(&v, case) < 1e-9, "{}", case.name);
    }
}

#[test]
fn long_horizons_are_estimated_honestly() {
    // The audit's finding (i): at T = 1000 DOP853's tolerance clamped for both runs gave an
    // estimate of exactly 0 for errors 160× the tolerance. The companion is now never
    // identical to the run.
    for case in averaged_cases().iter().filter(|c| c.t_end == 1000.0) {
        for tol in [1e-8, 1e-10] {
            let v = check(case, tol);
            assert!(v.error_estimate > 0.0, "{}", case.name);
        }
    }
}

#[test]
fn near_the_separatrix_auto_is_honest_at_any_tolerance() {
    // The audit's finding (ii): ill-conditioned starts, where refinement meets round-off. Met
    // or not, the estimate bounds the true error; a miss says why.
    for case in averaged_cases()
        .iter()
        .filter(|c| c.start == "N" || c.start == "M")
    {
        for tol in [1e-6, 1e-8, 1e-10, 1e-12] {
            check(case, tol);
        }
    }
}

#[test]
fn a_chaotic_start_is_reported_as_missed() {
    // The audit: k = 1, T = 1000, estimate 0, answer wrong by ~120 rad. At k = 1 the fast and
    // slow motions mix; two runs 256× apart in tolerance end far apart, refinement cannot close
    // the gap, and auto must say so rather than report a small estimate.
    let problem = common::problem(2.0, 1.0, 1.0, 1.0, [0.0, 0.0, 1.0, 0.5]);
    let v = run_auto(&problem, 1e-8, 1000.0, 0, false).unwrap();
    eprintln!(
        "chaotic: {} est {:e} met {} {:?} refinements {}",
        v.plan.method, v.error_estimate, v.met, v.shortfall, v.refinements
    );
    assert!(!v.met);
    assert!(v.error_estimate > 1e-8);
    assert!(matches!(
        v.shortfall,
        Some(Shortfall::Floor | Shortfall::Time | Shortfall::Refinements | Shortfall::Clamped)
    ));
}

#[test]
fn the_companion_is_never_the_run() {
    // Clamped at 1e-14, the old companion (16× tighter, clamped too) was the run itself.
    let case = &averaged_cases()[0];
    let v = run_auto(&case.problem, 1e-16, case.t_end, 0, false).unwrap();
    let c = v.plan.companion();
    assert_ne!(c, v.run_settings);
    assert!(!v.met, "1e-16 cannot be met in double precision");
    assert!(v.error_estimate > 0.0);
}

#[test]
fn a_miss_is_in_the_json_warned_on_stderr_and_fatal_with_strict() {
    // Near the separatrix over T = 60, 1e-10 cannot be verified (see the preset's comment).
    let args = [
        "simulate",
        "--preset",
        "just-below",
        "--tolerance",
        "1e-10",
        "--format",
        "json",
    ];
    let (code, out, err) = common::bin(&args);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    assert_eq!(v["auto"]["met"], false, "{out}");
    assert!(v["auto"]["shortfall"].is_string(), "{out}");
    assert!(
        err.contains("warning: auto could not meet the tolerance 1e-10"),
        "{err}"
    );
    let mut strict = args.to_vec();
    strict.push("--strict");
    let (code, out, err) = common::bin(&strict);
    assert_eq!(code, 1, "{err}");
    assert!(
        out.contains("\"met\": false"),
        "the report is still written"
    );
    // Met: no warning, and --strict changes nothing.
    let (code, out, err) = common::bin(&["simulate", "--format", "json", "--strict"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("\"met\": true"), "{out}");
    assert!(!err.contains("warning"), "{err}");
}

#[test]
fn a_floor_above_the_tolerance_is_said_after_the_first_run_with_its_size() {
    // Issue 27, item 5: `just-below` at 1e-10 measures κ ≈ 1.4e4; over its 1e5 steps rounding
    // alone sets about 1e-8, a hundred times the tolerance. No refinement can lower that (it
    // only adds steps), so `auto` stops after its first run and says how much is rounding, in
    // the JSON, the table's warning and the CSV's.
    let base = ["simulate", "--preset", "just-below", "--tolerance", "1e-10"];
    let (code, out, err) = common::bin(&[&base[..], &["--format", "json"]].concat());
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let auto = &v["auto"];
    let floor = auto["round_off_floor"]
        .as_f64()
        .expect("the floor is reported");
    let estimate = auto["error_estimate"].as_f64().unwrap();
    assert!(floor > 1e-10 && floor <= estimate, "{auto}");
    assert_eq!(auto["shortfall"], "floor", "{auto}");
    assert_eq!(
        auto["refinements"], 0,
        "stopped after its first run: {auto}"
    );
    let said = format!("rounding alone accounts for {floor:.1e} of it");
    assert!(err.contains(&said), "{err}");
    for format in ["table", "csv"] {
        let (code, _, err) = common::bin(&[&base[..], &["--format", format]].concat());
        assert_eq!(code, 0, "{err}");
        assert!(err.contains(&said), "{format}: {err}");
    }
    // Where the floor is far below the tolerance, it is reported and `auto` meets it.
    let (_, out, _) = common::bin(&["simulate", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let tolerance = v["tolerance"].as_f64().unwrap();
    assert!(
        v["auto"]["round_off_floor"].as_f64().unwrap() < 0.01 * tolerance,
        "{out}"
    );
    assert_eq!(v["auto"]["met"], true);
}

#[test]
fn the_limits_values_are_accurate_whatever_the_tolerance() {
    // The audit: effective.alpha/alpha_dot came from the limit integrated at the user's
    // tolerance (errors 2e-6 at 1e-8). Now they are good to about 1e-12 at any tolerance:
    // at the limit's 7th reversal time (from its quadrature, an independent computation),
    // its α̇ must vanish.
    use rattleback::physics::rattleback::effective::Effective;
    let preset = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
    let eff = Effective::new(preset.problem().unwrap());
    let t7 = eff.reversal_times(30.0)[6];
    for tolerance in [1e-4, 1e-8] {
        let (code, out, err) = common::bin(&[
            "simulate",
            "--format",
            "json",
            "--method",
            "dop853",
            "--tolerance",
            &tolerance.to_string(),
            "--t-end",
            &format!("{t7:.17e}"),
        ]);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let alpha_dot = v["effective"]["alpha_dot"].as_f64().unwrap();
        assert!(
            alpha_dot.abs() < 1e-11,
            "tolerance {tolerance:e}: the limit's α̇ at its own reversal is {alpha_dot:e}"
        );
    }
}

#[test]
fn averaged_runs_report_the_averaged_model() {
    let (code, out, err) =
        common::bin(&["simulate", "--preset", "stiff-spring", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["auto"]["choice"], "averaged2", "{out}");
    let a = &v["averaged"];
    assert_eq!(a["regime"], "trapped");
    let theta = v["effective"]["theta"].as_f64().unwrap();
    let theta_bar = a["theta_bar"].as_f64().unwrap();
    // θ̄ = θ (1 + O(1/k)) at k = 1e10.
    assert!(
        (theta_bar / theta - 1.0).abs() < 1e-8,
        "{theta_bar} vs {theta}"
    );
    let kbar = a["kbar"].as_f64().unwrap();
    assert!(
        (v["energy"]["initial"].as_f64().unwrap() - kbar).abs() < 1e-12 * kbar,
        "the energy diagnostic of the averaged model is K̄"
    );
    let h = a["half_period"].as_f64().unwrap();
    let h_eff = v["effective"]["half_period"].as_f64().unwrap();
    assert!((h - h_eff).abs() < 1e-6 * h_eff, "{h} vs {h_eff}");
}

/// Issue 27: the probes of one body and start are measured once per process and read at every
/// other `k` (the explorer's slider, a sweep's rungs), and what is read is what would be
/// computed: `auto` at a `k` with the probes kept gives the same bits as with none kept. So is
/// (stop 51) the start's conditioning far in, read at its conditioning stiffness: `auto`'s
/// verification is then its companion alone, the start's condition numbers bounded by that
/// reading times `CONDITIONING_KEPT_MARGIN`, except where the bound would weigh on the estimate
/// (a tight tolerance), where they are measured at `k`.
#[test]
fn probes_are_measured_once_and_reading_them_changes_nothing() {
    use rattleback::physics::rattleback::auto::{
        CONDITIONING_KEPT_MARGIN, conditioning_stiffness, memo, probe_problem, probe_stiffnesses,
    };
    // A body no other test uses, so that its probes are this test's alone.
    let at = |k| common::problem(0.8123, 1.27, 1.0, k, [0.0, 0.0, 1.0, 0.35]);
    let t_end = 10.0;
    let first = run_auto(&at(1e7), 1e-8, t_end, 0, false).unwrap();
    assert!(first.plan.method.is_averaged(), "{}", first.plan.reason);
    let keys = probe_stiffnesses(&at(1e7)).map(|k| memo::key(&probe_problem(&at(1e7), k), t_end));
    let before = keys.map(|k| memo::reads(&k).expect("the probes were kept"));
    // Another k of the same body and start asks for the same probes, and the same reading of its
    // conditioning.
    assert_eq!(probe_stiffnesses(&at(1e9)), probe_stiffnesses(&at(1e7)));
    let k_c = conditioning_stiffness(&at(1e7)).expect("far in");
    assert!(
        k_c <= 1e7 && conditioning_stiffness(&at(1e9)) == Some(k_c),
        "{k_c}"
    );
    let reading = memo::conditioning_key(&probe_problem(&at(1e7), k_c), t_end);
    let read_before = memo::reads(&reading).expect("the reading was kept");
    let warm = run_auto(&at(1e9), 1e-8, t_end, 0, false).unwrap();
    let after = keys.map(|k| memo::reads(&k).unwrap_or(0));
    assert!(
        after[0] > before[0] && after[1] > before[1],
        "the probes were run again: reads {before:?} then {after:?}"
    );
    assert!(
        memo::reads(&reading).unwrap_or(0) > read_before,
        "the conditioning was read again"
    );
    assert!(
        first.condition.margin == CONDITIONING_KEPT_MARGIN
            && warm.condition.margin == CONDITIONING_KEPT_MARGIN,
        "the kept bound served: {:?}, {:?}",
        first.condition,
        warm.condition
    );
    memo::clear();
    let cold = run_auto(&at(1e9), 1e-8, t_end, 0, false).unwrap();
    assert_eq!(
        warm, cold,
        "a kept probe or reading changed what auto returns"
    );
    // Where the bound would weigh on the estimate, the start is measured at its own k.
    let tight = run_auto(&at(1e9), 1e-12, t_end, 0, false).unwrap();
    assert!(tight.condition.margin == 1.0, "{:?}", tight.condition);
}

/// Issue 27: where the averaged model is the exact motion (`ix = iy`: `c ≡ 0`, uniform spin and
/// a harmonic tilt), `auto` runs it with no probe, and it agrees with a tight resolved run.
#[test]
fn an_exact_averaged_model_needs_no_probe() {
    use rattleback::physics::method::RunSpec;
    use rattleback::physics::rattleback::auto::{averaged_is_exact, plan_cancellable, probes_cost};
    use rattleback::physics::rattleback::run;
    let p = common::problem(1.5, 1.5, 1.0, 1e4, [0.01, 0.2, 1.0, 0.5]);
    assert!(averaged_is_exact(&p));
    assert!(probes_cost(&p, 30.0) == 0.0);
    let d = plan_cancellable(&p, 1e-9, 30.0, &mut |_| true).unwrap();
    assert!(d.probe.is_none(), "{}", d.plan.reason);
    assert_eq!(d.plan.method, Method::Averaged3, "{}", d.plan.reason);
    let v = run_auto(&p, 1e-9, 30.0, 0, false).unwrap();
    assert!(v.met);
    let reference = run(
        &p,
        &RunSpec {
            method: Method::Dop853,
            tolerance: 1e-13,
            step: None,
            t_end: 30.0,
            samples: 0,
            monitor_energy: false,
        },
    )
    .unwrap();
    let off = (v.result.final_state[1] - reference.final_state[1])
        .abs()
        .max((v.result.final_state[3] - reference.final_state[3]).abs());
    assert!(off < 1e-9, "off by {off:e}");
    // A body that is not symmetric is probed.
    assert!(
        probes_cost(
            &common::problem(1.5, 1.4, 1.0, 1e4, [0.01, 0.2, 1.0, 0.5]),
            30.0
        ) > 0.0
    );
}

/// Issue 27: `auto` resolves the middle stiffnesses with the Taylor series, whose error is a
/// random walk that a slightly looser companion can under-read (docs/benchmarks.md). Its
/// companion is therefore 1024× looser than the run it verifies, and on every long-double
/// reference up to k = 1e6, at companion tolerances 1e-8 … 1e-12, their difference plus the
/// round-off floors stays at least twice the run's true error (measured 27× at the least:
/// `cargo run --release --example rattleback_taylor tighter`; a companion 64× looser fails here,
/// at 0.53×). Each run is compared where its error stands ten times above the reference's own.
#[test]
fn the_series_companion_bounds_its_run_on_every_reference() {
    use rattleback::physics::rattleback::auto::{conditioned_round_off, difference, round_off};
    const TAYLOR_COMPANION_LOOSER: f64 =
        rattleback::physics::rattleback::policy::TAYLOR.companion_looser;
    use rattleback::physics::method::RunSpec;
    use rattleback::physics::rattleback::run::run;

    let mut cases = averaged_cases();
    cases.extend(common::cases_from("rattleback_honesty.toml"));
    let mut measured = 0;
    for case in cases
        .iter()
        .filter(|c| c.source == "rk8-long-double" && c.k <= 1e6)
    {
        let floor = case.uncertainty.max(2e-12);
        for i in 0..5 {
            let loose = 1e-8 * 10f64.powi(-i);
            let spec = |tolerance| RunSpec {
                method: Method::Taylor,
                tolerance,
                step: None,
                t_end: case.t_end,
                samples: 0,
                monitor_energy: false,
            };
            let r = run(
                &case.problem,
                &spec((loose / TAYLOR_COMPANION_LOOSER).max(1e-14)),
            )
            .unwrap();
            let c = run(&case.problem, &spec(loose)).unwrap();
            let v = result_error(&r, case);
            if v < 10.0 * floor {
                continue;
            }
            let steps = r.stats.steps as f64;
            let estimate = difference(&r, &c)
                + round_off(&case.problem, steps, case.t_end)
                + conditioned_round_off(steps, case.condition.unwrap_or(1.0));
            measured += 1;
            assert!(
                estimate >= 2.0 * v,
                "{} at {loose:e}: estimate {estimate:e}, error {v:e}",
                case.name
            );
        }
    }
    assert!(measured >= 50, "only {measured} runs measurable");
}

#[test]
fn a_looser_tolerance_is_never_missed_where_a_tighter_one_is_met() {
    // Stop 52: on the ill-conditioned starts `M` and `N` at T = 100 (κ ≈ 2 300) the series'
    // companion errs erratically, and one refinement that did not halve the estimate was read
    // as a floor: `M` at k = 1e3 ended `met = false` at 1e-5 and 1e-7 (estimates 2.9e-5 and
    // 1.9e-7, its floor 4e-10) while it met 1e-6 and 1e-8. A user loosening the tolerance must
    // not see it missed.
    let tolerances = [1e-5, 1e-6, 1e-7, 1e-8];
    let mut checked = 0;
    for case in averaged_cases()
        .iter()
        .filter(|c| c.source == "rk8-long-double" && c.t_end == 100.0 && c.k <= 1e3)
    {
        let met: Vec<bool> = tolerances.iter().map(|&t| check(case, t).met).collect();
        for (i, &tight) in met.iter().enumerate() {
            for (j, &loose) in met[..i].iter().enumerate() {
                assert!(
                    !tight || loose,
                    "{}: met at {:e}, missed at the looser {:e}",
                    case.name,
                    tolerances[i],
                    tolerances[j]
                );
            }
        }
        checked += 1;
    }
    assert!(checked >= 4, "{checked}");
}

/// One problem resolved twice in one process gives one answer (issue 80): a start far in
/// (`k` 1.8e7, an averaged plan) whose conditioning bound was kept after its first resolution
/// was measured at its own `k` on its second, and its estimate moved (6.2e-12 against 7.7e-12):
/// a recording of both runs failed its own `--verify`. Found by `generated.rs`'s recordings.
#[test]
fn a_problem_resolved_twice_in_a_process_gives_one_answer() {
    use rattleback::physics::rattleback::{Params, Problem, Start};
    let problem = Problem::new(
        Params {
            ix: 2.0,
            iy: 0.640_813_394_795_905_6,
            iz: 1.0,
            k: 17_855_206.206_385_393,
        },
        Start {
            gamma: -0.001,
            alpha: 0.0,
            gamma_dot: 1.0,
            alpha_dot: 0.724_399_588_002_379_6,
        },
    )
    .unwrap();
    let (tolerance, t_end) = (2.750_326_003_451_969_5e-11, 8.310_232_320_323_543);
    let first = run_auto(&problem, tolerance, t_end, 0, false).unwrap();
    let second = run_auto(&problem, tolerance, t_end, 0, false).unwrap();
    assert_eq!(first.plan, second.plan);
    assert_eq!(
        first.error_estimate.to_bits(),
        second.error_estimate.to_bits(),
        "{} then {}",
        first.error_estimate,
        second.error_estimate
    );
}
