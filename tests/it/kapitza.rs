//! Kapitza's pendulum against independent references (`tests/fixtures/reference/kapitza.toml`:
//! a Taylor-series integrator of order 28 in long double, `scripts/kapitza_taylor.c`), for
//! ε from 1e-1 to 1e-6: the resolved methods to their tolerance, the limit to its model error
//! (O(ε) from the raw start, O(ε²) with the ripple), and `auto` to the tolerance it was given.

use rattleback::physics::Method;
use rattleback::physics::kapitza::run::run;
use rattleback::physics::kapitza::{Params, Problem, Start, plan};
use rattleback::physics::method::RunSpec;

struct Case {
    name: String,
    problem: Problem,
    t_end: f64,
    theta: Vec<f64>,
    theta_dot: Vec<f64>,
    /// The reference's own accuracy (its run against a refined one).
    accuracy: f64,
}

fn cases() -> Vec<Case> {
    cases_in("kapitza.toml")
}

/// The cases of `tests/fixtures/reference/FILE`.
fn cases_in(file: &str) -> Vec<Case> {
    let path = format!("{}/tests/fixtures/reference/{file}", root!());
    let table: toml::Table = std::fs::read_to_string(path).unwrap().parse().unwrap();
    let num = |t: &toml::Table, k: &str| t[k].as_float().unwrap();
    let list = |t: &toml::Table, k: &str| -> Vec<f64> {
        t[k].as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_float().unwrap())
            .collect()
    };
    table["case"]
        .as_table()
        .unwrap()
        .iter()
        .map(|(name, c)| {
            let c = c.as_table().unwrap();
            let params = Params {
                a: num(c, "a"),
                b: num(c, "b"),
                epsilon: num(c, "epsilon"),
            };
            let start = Start {
                theta: num(c, "theta0"),
                theta_dot: num(c, "theta_dot0"),
            };
            // Rounding over the 1e7 steps at ε = 1e-6 leaves up to 2.2e-11.
            assert!(num(c, "accuracy") < 3e-11, "{name}: reference not accurate");
            Case {
                name: name.clone(),
                problem: Problem::new(params, start).unwrap(),
                t_end: num(c, "t_end"),
                theta: list(c, "theta"),
                theta_dot: list(c, "theta_dot"),
                accuracy: num(c, "accuracy"),
            }
        })
        .collect()
}

/// Largest error in θ and in θ̇ over the reference's samples.
fn errors(case: &Case, method: Method, tolerance: f64) -> (f64, f64) {
    let spec = RunSpec {
        method,
        tolerance,
        step: None,
        t_end: case.t_end,
        samples: case.theta.len(),
        monitor_energy: true,
    };
    let r = run(&case.problem, &spec, &mut |_| true).unwrap();
    let mut e = (0.0f64, 0.0f64);
    for (i, s) in r.samples.iter().enumerate() {
        e.0 = e.0.max((s.theta - case.theta[i]).abs());
        e.1 = e.1.max((s.theta_dot - case.theta_dot[i]).abs());
    }
    e
}

#[test]
fn the_references_cover_every_decade_of_epsilon() {
    let cases = cases();
    for eps in [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6] {
        assert_eq!(
            cases
                .iter()
                .filter(|c| (c.problem.params().epsilon - eps).abs() < 1e-3 * eps)
                .count(),
            3,
            "{eps}"
        );
    }
}

#[test]
fn resolved_methods_match_the_references() {
    for case in cases()
        .iter()
        .filter(|c| c.problem.params().epsilon >= 1e-4)
    {
        // DOP853's tolerance is per step: its global error grows with the fast periods.
        let (et, ev) = errors(case, Method::Dop853, 1e-12);
        assert!(
            et < 1e-8 && ev < 1e-8,
            "{}: dop853 {et:e} {ev:e}",
            case.name
        );
        if case.problem.params().epsilon >= 1e-2 {
            for m in [
                Method::Suzuki8,
                Method::Yoshida6,
                Method::Rk4,
                Method::BlanesMoan4,
            ] {
                let (et, ev) = errors(case, m, 1e-10);
                assert!(et < 1e-7 && ev < 1e-6, "{}: {m} {et:e} {ev:e}", case.name);
            }
        }
    }
}

#[test]
fn the_limit_converges_at_first_order_and_with_its_ripple_at_second() {
    for case in cases()
        .iter()
        .filter(|c| c.problem.params().epsilon <= 1e-2)
    {
        let eps = case.problem.params().epsilon;
        let (raw, _) = errors(case, Method::Effective, 1e-13);
        let (corr_t, corr_v) = errors(case, Method::EffectiveCorrected, 1e-13);
        let predicted = plan::model_error(&case.problem, case.t_end);
        println!(
            "{:>18} eps {eps:.0e}: raw {raw:.2e}  corrected θ {corr_t:.2e} θ̇ {corr_v:.2e}  predicted {predicted:.2e}",
            case.name
        );
        // O(ε) without the ripple (the start alone is off by ε b sin θ0).
        assert!(
            raw < 20.0 * eps && raw > 0.01 * eps,
            "{}: raw {raw:e}",
            case.name
        );
        // O(ε²) with it, in θ and in θ̇, and within what auto predicts (above the reference's
        // own accuracy: 2.2e-11 at ε = 1e-6 on the falling start).
        let floor = 1e-12 + 2.0 * case.accuracy;
        assert!(
            corr_t < 0.3 * predicted + floor,
            "{}: {corr_t:e} vs {predicted:e}",
            case.name
        );
        assert!(
            corr_v < 0.3 * predicted + floor,
            "{}: {corr_v:e} vs {predicted:e}",
            case.name
        );
    }
}

/// Issue 27: the second-order averaged model (`averaged2`) is within O(ε⁴) of the references,
/// below what `auto` predicts for it ([`plan::model_error2`]), and far below the limit with its
/// first ripple (O(ε²)).
#[test]
fn the_second_order_averaged_model_is_fourth_order() {
    for case in cases()
        .iter()
        .filter(|c| c.problem.params().epsilon <= 1e-2)
    {
        let eps = case.problem.params().epsilon;
        let (t2, v2) = errors(case, Method::Averaged2, 1e-13);
        let (t1, v1) = errors(case, Method::EffectiveCorrected, 1e-13);
        let predicted = plan::model_error2(&case.problem, case.t_end);
        let (second, first) = (t2.max(v2), t1.max(v1));
        println!(
            "{:>18} eps {eps:.0e}: averaged2 {second:.2e} (predicted {predicted:.2e}), effective-corrected {first:.2e}",
            case.name
        );
        // The references and the integration at 1e-13 leave about 1e-12; the rounding of the
        // fast phase t/ε moves the ripple by up to b ε_mach t/ε (both in auto's estimate).
        let floor = 2e-12 + plan::phase_rounding(&case.problem, case.t_end);
        assert!(
            second < 0.5 * predicted + floor,
            "{}: {second:e} vs predicted {predicted:e}",
            case.name
        );
        // Two orders of ε better than the first ripple, where that is measurable.
        if first > 1e3 * floor {
            assert!(
                second < 30.0 * eps * eps * first + floor,
                "{}: {second:e} against {first:e}",
                case.name
            );
        }
    }
}

/// Issue 27: the third-order averaged model (`averaged3`) is within O(ε⁶) of the references:
/// where `averaged2`'s error is measurable, `averaged3`'s is at least `(ε s)²`-times smaller
/// (`s = b² + |a| + 1`, the expansion's scale), and at ε = 1e-2 below 1e-9 on every start.
/// Also the ratio of the error to what `auto`'s check measures (`|averaged3 − averaged2|
/// (ε s)²`) where it considers `averaged3`: below [`plan::THIRD_ORDER_MARGIN`].
/// Stop 51: the rounding floor a resolved run's estimate counts, `24 ε_mach n^1.5` (20 before issue 82) over `n` fast
/// periods (`plan::ROUNDING_GAIN`), bounds what the Taylor series leaves where truncation no
/// longer sets its error (local tolerance 1e-14, and 1e-13 where 1e-14 is no more than 3×
/// closer), on every reference start from ε = 1e-1
/// to 1e-4 (8 … 8 000 periods) but those that keep returning near the unstable upright
/// (`returns_*`, held out: they amplify their rounding beyond any such law, and their estimates
/// rest on the companion's difference, `honesty::`). The gain measured is at most 10.4 (5.8 with glibc's functions); the old
/// floor, `1e-12 n`, was 25–300× above these errors up to 800 periods.
#[test]
fn the_rounding_floor_bounds_the_series_at_its_tightest() {
    let mut all = cases();
    all.extend(cases_in("kapitza_honesty.toml"));
    let (mut gain, mut measured) = (0.0f64, 0);
    for case in &all {
        let p = case.problem.params();
        if p.epsilon < 1e-4 || case.name.starts_with("returns") {
            continue;
        }
        let n = case.t_end / (2.0 * std::f64::consts::PI * p.epsilon);
        let floor = plan::rounding_floor(&case.problem, case.t_end);
        let error = |tol| {
            let (et, ev) = errors(case, Method::Taylor, tol);
            et.max(ev) - case.accuracy
        };
        let (e13, e14) = (error(1e-13), error(1e-14));
        // The run at 1e-14, and the one at 1e-13 where a tighter tolerance no longer lowers the
        // error by more than 3× (rounding, not truncation, sets it).
        let floored = if e14 * 3.0 >= e13 {
            vec![e13, e14]
        } else {
            vec![e14]
        };
        for e in floored {
            gain = gain.max(e / (f64::EPSILON * n.powf(1.5)));
            measured += 1;
            assert!(
                e <= floor,
                "{}: {e:e} above the floor {floor:e} ({n:.0} periods)",
                case.name
            );
        }
    }
    println!("largest error / (ε_mach n^1.5): {gain:.2} over {measured} runs");
    assert!(measured >= 12, "{measured}");
    assert!(
        gain * 2.0 <= plan::ROUNDING_GAIN,
        "the floor's margin over the measured gain {gain} is under 2"
    );
}

#[test]
fn the_third_order_averaged_model_is_sixth_order() {
    let (mut worst_ratio, mut measured) = (0.0f64, 0);
    for case in cases()
        .iter()
        .filter(|c| c.problem.params().epsilon <= 1e-1)
    {
        let p = case.problem.params();
        let eps = p.epsilon;
        let (t3, v3) = errors(case, Method::Averaged3, 1e-13);
        let (t2, v2) = errors(case, Method::Averaged2, 1e-13);
        let (third, second) = (t3.max(v3), t2.max(v2));
        let floor = 2e-12 + plan::phase_rounding(&case.problem, case.t_end);
        let es2 = (eps * (p.b * p.b + p.a.abs() + 1.0)).powi(2);
        let check = plan::averaged3_gap(&case.problem, case.t_end).unwrap() * es2;
        if third > 10.0 * floor && es2.sqrt() <= plan::THIRD_ORDER_MAX_EPS_S {
            worst_ratio = worst_ratio.max(third / check);
            measured += 1;
        }
        println!(
            "{:>18} eps {eps:.0e}: averaged3 {third:.2e}, averaged2 {second:.2e}, check {check:.2e}",
            case.name
        );
        if second > 1e3 * floor {
            assert!(
                third < 10.0 * es2 * second + floor,
                "{}: {third:e} against {second:e}",
                case.name
            );
        }
        if (eps - 1e-2).abs() < 1e-6 {
            assert!(third < 1e-8, "{}: {third:e}", case.name);
        }
    }
    println!("largest error / check: {worst_ratio:.2} over {measured} cases");
    assert!(
        measured >= 3,
        "the margin is measured on the three starts at ε = 1e-2"
    );
    assert!(
        worst_ratio <= plan::THIRD_ORDER_MARGIN,
        "{worst_ratio} > {}",
        plan::THIRD_ORDER_MARGIN
    );
}

/// Issue 27: below ε = 1e-6, where the full model cannot be resolved, `auto` as `simulate` runs
/// it (planned and verified) stays within its estimate against the 30-digit references
/// (`kapitza_small_eps.toml`), and says `met` only where its error is within the tolerance.
/// The lifts carry the fast phase exactly (`FastPhase::Exact`), so it meets 1e-8 there, with
/// a measured estimate (`estimates_lie_within_ten_times_the_errors`);
/// the phase as the lifts rounded it before (`b ε_mach t/ε`, 2.2e-8 … 2.2e-6 here) no longer
/// sets a floor.
#[test]
fn auto_is_honest_where_the_full_model_cannot_be_resolved() {
    let cases = cases_in("kapitza_small_eps.toml");
    assert_eq!(cases.len(), 9);
    for case in &cases {
        for tol in [1e-6, 1e-8] {
            let c = plan::verified(&case.problem, tol, case.t_end, 10.0, &mut |_| true).unwrap();
            let (et, ev) = errors(case, c.method, c.settings.tolerance);
            let error = et.max(ev);
            println!(
                "{:>18} tol {tol:.0e}: {} error {error:.1e} estimate {:.1e} met {}",
                case.name, c.method, c.estimate, c.met
            );
            assert!(error <= c.estimate, "{} at {tol:e}", case.name);
            assert!(!c.met || error <= tol, "{} at {tol:e}", case.name);
            assert_eq!(c.met, c.estimate <= tol, "{}", case.name);
            assert!(c.met, "{} at {tol:e}: {:e}", case.name, c.estimate);
            let rounded_phase = plan::phase_rounding(&case.problem, case.t_end);
            assert!(
                c.estimate < rounded_phase,
                "{}: the estimate {:e} is not below the old floor {rounded_phase:e}",
                case.name,
                c.estimate
            );
        }
    }
}

#[test]
fn auto_meets_its_tolerance_at_every_epsilon() {
    for case in cases() {
        for tol in [1e-6, 1e-9] {
            let choice = plan::resolve(&case.problem, tol, case.t_end);
            if choice.method == Method::Dop853 && case.problem.params().epsilon < 1e-4 {
                // A resolved run at ε = 1e-5 takes seconds: the benchmark covers it.
                continue;
            }
            let (et, ev) = errors(&case, choice.method, choice.settings.tolerance);
            // Honest: within the estimate it states (the tolerance when it says it met it).
            assert!(choice.met == (choice.estimate <= tol), "{}", case.name);
            println!(
                "{:>18} tol {tol:.0e}: {} error {:.1e} estimate {:.1e} met {}",
                case.name,
                choice.method,
                et.max(ev),
                choice.estimate,
                choice.met
            );
            assert!(
                et <= choice.estimate && ev <= choice.estimate,
                "{} at {tol:e}: {} gives {et:e} {ev:e}, estimate {:e}",
                case.name,
                choice.method,
                choice.estimate
            );
        }
    }
}

/// Issue 27: `auto` as `simulate` and the explorer run it (verified) takes the second-order
/// averaged model where its a-posteriori estimate meets the tolerance, and the estimate holds
/// against the references; it takes it at every reference start from ε = 1e-3 down at 1e-8,
/// where a resolved run took milliseconds to seconds.
#[test]
fn verified_auto_takes_the_averaged_model_honestly() {
    let mut taken = 0;
    for case in cases() {
        for tol in [1e-6, 1e-8, 1e-9] {
            let c = plan::verified(&case.problem, tol, case.t_end, 60.0, &mut |_| true).unwrap();
            if c.method == Method::Dop853 && case.problem.params().epsilon < 1e-4 {
                continue;
            }
            let (et, ev) = errors(&case, c.method, c.settings.tolerance);
            println!(
                "{:>18} tol {tol:.0e}: {} error {:.1e} estimate {:.1e} met {}",
                case.name,
                c.method,
                et.max(ev),
                c.estimate,
                c.met
            );
            assert!(
                et.max(ev) <= c.estimate,
                "{} at {tol:e}: {} gives {:e}, estimate {:e}",
                case.name,
                c.method,
                et.max(ev),
                c.estimate
            );
            let eps = case.problem.params().epsilon;
            if c.method == Method::Averaged2 {
                taken += 1;
            } else if (tol - 1e-8).abs() < 1e-20 && (1e-4..=1e-3).contains(&eps) {
                panic!("{} at 1e-8: {} instead of averaged2", case.name, c.method);
            }
        }
    }
    assert!(taken > 0);
}

/// Issue 27: the cost `auto` is refused by is the cost of what it will run: where `averaged2`
/// is expected, a long horizon at a small ε is not refused as if it were resolved. Where the
/// averaged models then miss the tolerance, the resolved run that would take minutes is not
/// started: the averaged model's shortfall is the answer (before the fast phase was exact, and
/// the averaged check tightened, that was a refusal at T = 2000).
#[test]
fn autos_budget_follows_the_averaged_model() {
    use rattleback::physics::kapitza::plan::predicted_seconds as cost_seconds;
    use rattleback::physics::method::Asked;
    let at = |t_end: f64| {
        let p = Problem::new(
            Params {
                a: 1.0,
                b: 2.0,
                epsilon: 1e-4,
            },
            Start {
                theta: 0.3,
                theta_dot: 0.0,
            },
        )
        .unwrap();
        (p, t_end)
    };
    let (p, t) = at(200.0);
    let predicted = cost_seconds(&p, &Asked::new(Method::Auto, 1e-8, None, t));
    let resolved = cost_seconds(&p, &Asked::new(Method::Dop853, 1e-12, None, t));
    assert!(predicted < 1e-2 * resolved, "{predicted} {resolved}");
    let c = plan::verified(&p, 1e-8, t, 60.0, &mut |_| true).unwrap();
    assert_eq!(c.method, Method::Averaged2);
    // At T = 2000 the averaged model meets 1e-8 once its slow run is tightened.
    let (p, t) = at(2000.0);
    let c = plan::verified(&p, 1e-8, t, 60.0, &mut |_| true).unwrap();
    assert!(c.met && c.estimate <= 1e-8, "{c:?}");
    // At T = 20 000 it cannot: its shortfall comes back at once (the resolved run, predicted at
    // many minutes, would hang this test if it ran).
    let (p, t) = at(20_000.0);
    let c = plan::verified(&p, 1e-8, t, 60.0, &mut |_| true).unwrap();
    assert!(c.method.is_averaged() && !c.met, "{c:?}");
    assert_eq!(
        c.shortfall,
        Some(rattleback::physics::plan::Shortfall::Clamped),
        "{c:?}"
    );
}

/// Issue 27: where neither the averaged models nor a resolved run can meet the tolerance,
/// `auto` returns the one that came closer, as the module says, and the averaged model at once
/// where a resolved run's rounding floor alone is above its estimate. At 1e-13 on the
/// references at ε ≤ 1e-3 (T = 5): `averaged3` or `averaged2`, `met = false` unless its error is
/// within the tolerance, its estimate below the resolved run's floor and above its true error
/// (measured against the references, whose own accuracy is added).
#[test]
fn the_closer_shortfall_is_returned_and_the_averaged_one_at_once() {
    let mut seen = 0;
    for case in cases()
        .iter()
        .filter(|c| c.problem.params().epsilon <= 1e-3)
    {
        let tol = 1e-13;
        let c = plan::verified(&case.problem, tol, case.t_end, 10.0, &mut |_| true).unwrap();
        let (et, ev) = errors(case, c.method, c.settings.tolerance);
        let error = et.max(ev);
        println!(
            "{:>18} tol {tol:.0e}: {} error {error:.1e} estimate {:.1e} met {} {:?}",
            case.name, c.method, c.estimate, c.met, c.shortfall
        );
        assert!(c.method.is_averaged(), "{}: {}", case.name, c.method);
        assert!(error <= c.estimate + 2.0 * case.accuracy, "{}", case.name);
        assert!(
            !c.met || error <= tol + 2.0 * case.accuracy,
            "{}",
            case.name
        );
        assert!(
            c.met || c.estimate < plan::rounding_floor(&case.problem, case.t_end),
            "{}: a resolved run could have come closer",
            case.name
        );
        seen += 1;
    }
    assert_eq!(seen, 12, "the references at ε = 1e-3 … 1e-6");
}

/// Issue 27, item 3: `auto`'s estimates lie close above the true errors. Over every reference
/// start, ε = 1e-1 … 1e-9, at tolerances 1e-6, 1e-8 and 1e-9, where the error stands clear of
/// the reference's own accuracy (73 of 81 runs): every error is within its estimate; the
/// estimates are a median 4× the errors (17× when the limit's was its a-priori allowance), at
/// least three quarters of them within 10×. The slow models are within 18× (their companions
/// are 4× looser); resolved runs (the Taylor series, its companion 8× looser) within 30× where
/// the rounding floor is not half of the estimate (the floor, `24 ε_mach n^1.5` since issue 82, 20 from stop 51,
/// no longer is anywhere here; `1e-12 n` before, it made estimates at 1e-9 up to 306× the
/// errors); `averaged3` up to 66× (its model error is
/// its gap to `averaged2` times `(ε s)²`, with a margin of 8 over a measured spread of
/// 0.12–3.3).
#[test]
fn estimates_lie_within_ten_times_the_errors() {
    let mut all = cases();
    all.extend(cases_in("kapitza_small_eps.toml"));
    // Every run is checked and the summary printed before any assertion, so that the same
    // command measures another version of `auto` (docs/benchmarks.md's "before" column).
    let mut ratios = Vec::new();
    let mut ranges = std::collections::BTreeMap::<String, (f64, f64)>::new();
    let mut broken = Vec::new();
    for case in &all {
        for tol in [1e-6, 1e-8, 1e-9] {
            let c = plan::verified(&case.problem, tol, case.t_end, 10.0, &mut |_| true).unwrap();
            let (et, ev) = errors(case, c.method, c.settings.tolerance);
            let error = et.max(ev);
            let ratio = c.estimate / error;
            println!(
                "{:>22} tol {tol:.0e}: {:>19} error {error:.1e} estimate {:.1e} ratio {ratio:5.1}",
                case.name,
                c.method.to_string(),
                c.estimate
            );
            if error > c.estimate || !c.met {
                broken.push(format!("{} at {tol:e}: met {}, {ratio}", case.name, c.met));
            }
            if error < 10.0 * case.accuracy {
                continue;
            }
            // The resolved runs' ratios are their companions' (8× looser: 1.1–29×).
            let most = match c.method {
                Method::Averaged3 => 70.0,
                Method::Dop853 | Method::Taylor => 30.0,
                _ => 18.0,
            };
            // A resolved run's estimate carries the rounding floor; where that floor is half of
            // it, the ratio is the floor's, not the check's (with the floor of `1e-12 n` before
            // stop 51, the Taylor series at ε = 1e-2, tolerance 1e-9: up to 306×).
            let floored = matches!(c.method, Method::Dop853 | Method::Taylor)
                && 2.0 * plan::rounding_floor(&case.problem, case.t_end) >= c.estimate;
            if ratio > most && !floored {
                broken.push(format!("{} at {tol:e}: {} {ratio}", case.name, c.method));
            }
            let range = ranges
                .entry(c.method.to_string())
                .or_insert((f64::INFINITY, 0.0));
            *range = (range.0.min(ratio), range.1.max(ratio));
            ratios.push(ratio);
        }
    }
    ratios.sort_by(f64::total_cmp);
    let n = ratios.len();
    let within = ratios.iter().filter(|&&r| r <= 10.0).count();
    println!(
        "{n} runs: median {:.1}, {within} within 10x, largest {:.1}",
        ratios[n / 2],
        ratios[n - 1]
    );
    for (method, (lo, hi)) in &ranges {
        println!("{method}: {lo:.1}-{hi:.1}x");
    }
    assert!(broken.is_empty(), "{broken:#?}");
    assert!(n >= 70, "{n}");
    assert!(ratios[n / 2] <= 6.0, "median {}", ratios[n / 2]);
    assert!(within * 4 >= 3 * n, "{within} of {n}");
}

#[test]
fn estimates_bound_the_errors_at_every_tolerance() {
    // `auto`'s estimate is at least the error of what it returns, over every sample, at every
    // decade of tolerance from 1e-4 to 1e-10, on the references and the held-out starts (the
    // honesty audit checks the final state at 1e-6, 1e-8 and 1e-9). The two-run difference it
    // rests on does read below the error at some local tolerances (7 of 98 runs of the series
    // at fixed tolerances, `cargo run --release --example kapitza_companions`): the tolerance
    // `auto` asks first and the widening of a run whose refinement barely moved it keep its
    // own runs above.
    let mut all = cases();
    all.extend(cases_in("kapitza_small_eps.toml"));
    all.extend(cases_in("kapitza_honesty.toml"));
    let mut low = Vec::new();
    let mut n = 0;
    for case in &all {
        for tol in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10] {
            let c = plan::verified(&case.problem, tol, case.t_end, 10.0, &mut |_| true).unwrap();
            let (et, ev) = errors(case, c.method, c.settings.tolerance);
            let excess = et.max(ev) - case.accuracy;
            n += 1;
            if excess > c.estimate {
                low.push(format!(
                    "{} at {tol:e}: {} at {:e}, error {excess:.1e}, estimate {:.1e}",
                    case.name, c.method, c.settings.tolerance, c.estimate
                ));
            }
        }
    }
    assert!(n >= 200, "{n}");
    assert!(low.is_empty(), "{low:#?}");
}
