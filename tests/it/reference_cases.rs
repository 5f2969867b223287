//! Every case of the reference cases (carried in `tests/fixtures/reference/cases.toml` from
//! `../shared/reference/cases.toml`), an independent 8th-order integration at
//! relative tolerance 1e-13: final `alpha` and `alpha_dot` to 1e-7, reversal counts exact,
//! reversal times to 1e-6, for the full model (several methods) and the effective limit.

use crate::common;

use common::{case_problem, num, reference_cases, reference_path, shared_reference_path};
use rattleback::physics::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::effective::Effective;
use rattleback::physics::rattleback::run;

fn times(t: &toml::Table) -> Vec<f64> {
    t.get("reversal_times")
        .and_then(|v| v.as_array())
        .map(|a| a.iter().map(|x| x.as_float().expect("float")).collect())
        .unwrap_or_default()
}

#[track_caller]
fn check(label: &str, got_alpha: f64, got_alpha_dot: f64, got_times: &[f64], want: &toml::Table) {
    let (a, ad) = (num(want, "alpha"), num(want, "alpha_dot"));
    assert!(
        (got_alpha - a).abs() < 1e-7,
        "{label}: alpha {got_alpha} vs {a}"
    );
    assert!(
        (got_alpha_dot - ad).abs() < 1e-7,
        "{label}: alpha_dot {got_alpha_dot} vs {ad}"
    );
    let n = num(want, "reversals");
    let count = got_times.len() as f64;
    assert!(
        (count - n).abs() < 0.5,
        "{label}: {} reversals, want {n}",
        got_times.len()
    );
    for (g, w) in got_times.iter().zip(times(want)) {
        assert!((g - w).abs() < 1e-6, "{label}: reversal at {g}, want {w}");
    }
}

fn cases() -> Vec<(String, toml::Table)> {
    let all = reference_cases();
    let cases = all["case"].as_table().expect("[case] table").clone();
    assert!(cases.len() >= 3, "expected the public cases");
    cases
        .into_iter()
        .map(|(name, v)| (name, v.as_table().expect("case table").clone()))
        .collect()
}

#[test]
fn full_model_matches_reference_with_every_resolved_method() {
    for (name, case) in cases() {
        let problem = case_problem(&case);
        let full = case["full"].as_table().expect("full");
        for method in [Method::Dop853, Method::Yoshida6, Method::Suzuki8] {
            let spec = RunSpec {
                method,
                tolerance: 1e-10,
                step: None,
                t_end: num(&case, "t_end"),
                samples: 0,
                monitor_energy: true,
            };
            let r = run(&problem, &spec).expect("integrates");
            check(
                &format!("{name}/{method}"),
                r.final_state[1],
                r.final_state[3],
                &r.reversals,
                full,
            );
        }
    }
}

#[test]
fn effective_model_matches_reference_by_ode_and_by_quadrature() {
    for (name, case) in cases() {
        let Some(want) = case.get("effective").and_then(|v| v.as_table()) else {
            continue;
        };
        let problem = case_problem(&case);
        let eff = Effective::new(&problem);
        assert!(
            (eff.theta() - num(want, "theta")).abs() < 1e-12,
            "{name}: theta"
        );
        let t_end = num(&case, "t_end");
        let spec = RunSpec {
            method: Method::Effective,
            tolerance: 1e-10,
            step: None,
            t_end,
            samples: 0,
            monitor_energy: true,
        };
        let r = run(&problem, &spec).expect("integrates");
        check(
            &format!("{name}/effective-ode"),
            r.final_state[1],
            r.final_state[3],
            &r.reversals,
            want,
        );
        let by_quadrature = eff.reversal_times(t_end);
        check(
            &format!("{name}/quadrature"),
            num(want, "alpha"),
            num(want, "alpha_dot"),
            &by_quadrature,
            want,
        );
    }
}

/// The carried copy is the shared file's content, unchanged (checked where `../shared` exists).
#[test]
fn the_carried_reference_equals_the_shared_one() {
    let carried = std::fs::read_to_string(reference_path()).unwrap();
    assert!(
        carried.contains("[case.subcritical]"),
        "carried fixture present"
    );
    if let Some(shared) = shared_reference_path() {
        let shared = std::fs::read_to_string(shared).unwrap();
        let start = carried
            .find("# Public reference cases")
            .expect("the shared file's first line");
        let body = &carried[start..];
        assert_eq!(
            body, shared,
            "tests/fixtures/reference/cases.toml drifted from ../shared"
        );
    }
}
