//! Every scene's `auto` keeps its claims (issue 29, item 4): against held-out references that
//! share no code with the crate, `simulate --format json` at several tolerances, on starts of
//! every shape the issue names. `met` means the reported state is within the tolerance, and the
//! estimate is at least the true error, both up to the reference's own accuracy (an error is
//! counted only by how much it exceeds that). Each test prints its row of the table of claims
//! held / claims made / runs declined, with how many of the declined were in fact within the
//! tolerance (`cargo test --test it honesty:: -- --nocapture`).
//!
//! - the rattleback: `tests/fixtures/reference/rattleback_honesty.toml`
//!   (`scripts/rattleback_honesty.py`: the full model in long double, or the note's averaged
//!   model beyond k = 1e8) near the finite-k separatrix on both sides (condition numbers up to
//!   1e7) and small librations at k = 1e6 … 1e12, T up to 300;
//! - the pendulum: `tests/fixtures/reference/kapitza_honesty.toml` (an order-28 Taylor
//!   integrator in long double, `scripts/kapitza_honesty.py`): starts returning near the
//!   unstable upright over long horizons, coarse and fine ε;
//! - the celt: `tests/fixtures/celt/references.json` (scipy DOP853 at 1e-13 on the note's
//!   independent script, two derivations; each case states its uncertainty).

use crate::common::{self, simulate_json};

/// Claims held, claims made, runs declined, and every estimate found below the error.
#[derive(Default)]
struct Tally {
    held: usize,
    made: usize,
    declined: usize,
    /// Declined runs whose error was in fact within the tolerance (too cautious, not wrong).
    cautious: usize,
    /// Declined runs whose error was under a tenth of the tolerance.
    needless: usize,
    /// Declined runs whose error was within a third of the tolerance (issue 80: shy).
    shy: usize,
    broken: Vec<String>,
    low: Vec<String>,
}

impl Tally {
    /// Counts one run: `err` the true error, `accuracy` the reference's.
    fn count(&mut self, what: &str, tol: f64, report: &serde_json::Value, err: f64, accuracy: f64) {
        let auto = &report["auto"];
        let estimate = auto["error_estimate"].as_f64().unwrap_or(f64::INFINITY);
        let excess = (err - accuracy).max(0.0);
        if auto["met"].as_bool().expect("auto.met") {
            self.made += 1;
            if excess <= tol {
                self.held += 1;
            } else {
                self.broken
                    .push(format!("{what} at {tol:e}: met, but {err:.1e} off"));
            }
        } else {
            self.declined += 1;
            if err + accuracy <= tol {
                self.cautious += 1;
            }
            if err + accuracy <= 0.1 * tol {
                self.needless += 1;
            }
            if err + accuracy <= tol / 3.0 {
                self.shy += 1;
            }
            assert!(
                auto["shortfall"].is_string(),
                "{what} at {tol:e}: a miss must say why"
            );
        }
        if estimate < excess {
            self.low.push(format!(
                "{what} at {tol:e}: estimate {estimate:.1e}, error {err:.1e}"
            ));
        }
    }

    fn assert_honest(&self, scene: &str, tol: &str) {
        eprintln!(
            "| {scene} | {tol} | {} | {} | {} ({} of them within it) |",
            self.held, self.made, self.declined, self.cautious
        );
        assert!(self.broken.is_empty(), "{scene}: {:#?}", self.broken);
        assert!(self.low.is_empty(), "{scene}: {:#?}", self.low);
    }
}

/// Every tolerance of `tolerances`: the scene's `run` honest, and something claimed.
fn audit(scene: &str, tolerances: &[f64], run: fn(f64) -> Tally) {
    for &tol in tolerances {
        let tally = run(tol);
        tally.assert_honest(scene, &format!("{tol:e}"));
        assert!(
            tally.made > 0,
            "{scene}: auto never claimed anything at {tol:e}"
        );
    }
}

fn with_sets(preset: &str, sets: &[String]) -> serde_json::Value {
    let mut args = vec!["--preset", preset];
    for s in sets {
        args.extend(["--set", s.as_str()]);
    }
    simulate_json(&args)
}

/// `simulate` on a held-out rattleback case at `tol`, its spin rate replaced by `alpha_dot`:
/// the report and its true error (`α(T)`, `α̇(T)`, reversal times; infinite when the counts
/// differ).
fn run_case(case: &common::AveragedCase, alpha_dot: f64, tol: f64) -> (serde_json::Value, f64) {
    let p = case.problem.params();
    let s = case.problem.start();
    let sets = [
        format!("body.ix={}", p.ix),
        format!("body.iy={}", p.iy),
        format!("body.iz={}", p.iz),
        format!("spring.k={}", p.k),
        format!("initial.gamma={}", s.gamma),
        format!("initial.alpha={}", s.alpha),
        format!("initial.gamma_dot={}", s.gamma_dot),
        format!("initial.alpha_dot={alpha_dot}"),
        format!("run.t_end={}", case.t_end),
        format!("run.tolerance={tol}"),
    ];
    let r = with_sets("subcritical", &sets);
    let f = &r["final"];
    let times = r["reversals"]["times"].as_array().expect("reversal times");
    let mut err = (f["alpha"].as_f64().unwrap() - case.end.0)
        .abs()
        .max((f["alpha_dot"].as_f64().unwrap() - case.end.1).abs());
    if times.len() == case.reversals.len() {
        for (a, b) in times.iter().zip(&case.reversals) {
            err = err.max((a.as_f64().unwrap() - b).abs());
        }
    } else {
        err = f64::INFINITY;
    }
    (r, err)
}

fn rattleback(tol: f64) -> Tally {
    let mut tally = Tally::default();
    let mut cases = common::cases_from("rattleback_honesty.toml");
    cases.extend(common::cases_from("rattleback_unequal.toml"));
    for case in cases {
        let started = std::time::Instant::now();
        let (r, err) = run_case(&case, case.problem.start().alpha_dot, tol);
        eprintln!(
            "{} at {tol:e}: {} est {:.1e} err {err:.1e} met {} cond {:.0e} ({:.1} s)",
            case.name,
            r["auto"]["choice"],
            r["auto"]["error_estimate"].as_f64().unwrap_or(f64::NAN),
            r["auto"]["met"],
            case.condition.unwrap_or(f64::NAN),
            started.elapsed().as_secs_f64()
        );
        tally.count(&case.name, tol, &r, err, case.uncertainty);
    }
    tally
}

#[test]
fn the_rattleback_keeps_its_claims_near_the_separatrix_and_at_very_large_k() {
    audit("rattleback", &[1e-6, 1e-8, 1e-10], rattleback);
}

/// Issue 58, item 7: on a very unequal body near `α = π/2` (`scripts/rattleback_unequal.py`),
/// a request `auto` cannot meet is declined without a long run (it used to integrate 6.3e7
/// splitting steps, 20 s, at 1e-10, and end with a larger estimate than at 1e-8), and the
/// tighter request never ends with the larger estimate.
#[test]
fn a_request_below_the_floor_is_declined_without_a_long_run() {
    for case in common::cases_from("rattleback_unequal.toml") {
        let alpha_dot = case.problem.start().alpha_dot;
        let (loose, _) = run_case(&case, alpha_dot, 1e-8);
        let (tight, err) = run_case(&case, alpha_dot, 1e-10);
        let steps = tight["stats"]["steps"].as_f64().expect("steps");
        let estimate = |r: &serde_json::Value| r["auto"]["error_estimate"].as_f64().unwrap();
        assert!(steps < 1e6, "{}: {steps} steps", case.name);
        assert!(
            estimate(&tight) <= estimate(&loose),
            "{}: {:.1e} at 1e-10 against {:.1e} at 1e-8",
            case.name,
            estimate(&tight),
            estimate(&loose)
        );
        assert!(
            estimate(&tight) >= err - case.uncertainty,
            "{}: {err:.1e}",
            case.name
        );
    }
}

fn pendulum(tol: f64) -> Tally {
    pendulum_cases(
        include_str!("../fixtures/reference/kapitza_honesty.toml"),
        tol,
    )
}

/// `simulate` on every case of a pendulum reference file at `tol`, tallied.
fn pendulum_cases(fixture: &str, tol: f64) -> Tally {
    let cases: toml::Table = fixture.parse().expect("fixture");
    let mut tally = Tally::default();
    for (name, c) in cases["case"].as_table().unwrap() {
        let c = c.as_table().unwrap();
        let num = |k: &str| c[k].as_float().unwrap();
        let last = |k: &str| c[k].as_array().unwrap().last().unwrap().as_float().unwrap();
        let sets = [
            format!("pendulum.a={}", num("a")),
            format!("pendulum.b={}", num("b")),
            format!("pendulum.epsilon={}", num("epsilon")),
            format!("initial.theta={}", num("theta0")),
            format!("initial.theta_dot={}", num("theta_dot0")),
            format!("run.t_end={}", num("t_end")),
            format!("run.tolerance={tol}"),
        ];
        let r = with_sets("kapitza-falls", &sets);
        let f = &r["final"];
        let err = (f["theta"].as_f64().unwrap() - last("theta"))
            .abs()
            .max((f["theta_dot"].as_f64().unwrap() - last("theta_dot")).abs());
        tally.count(name, tol, &r, err, num("accuracy"));
    }
    tally
}

#[test]
fn the_pendulum_keeps_its_claims_on_the_held_out_starts() {
    audit("pendulum", &[1e-6, 1e-8, 1e-9], pendulum);
}

/// Issue 66: 41 random pendulums and starts (`scripts/kapitza_random.py`, seeded; the audit's own
/// case first, whose estimate at 1e-10 was 9.9e-11 for an error of 1.58e-10), against the
/// long-double Taylor reference: at 1e-10, 1e-9 and 1e-8 no estimate is below its error, and
/// at most 6 runs in 100 decline with an error under a tenth of their tolerance. (3 in 100
/// before issue 82: the portable sine and cosine, the browser's too, round within 1 ulp where
/// glibc's round to nearest, and the shifted twin that witnesses the rounding sees up to 10×
/// more of it on a few starts: 6 of 123 runs decline needlessly, 5 of them at 1e-10.)
#[test]
fn the_pendulums_estimates_count_their_rounding_on_random_starts() {
    let fixture = include_str!("../fixtures/reference/kapitza_random.toml");
    let (mut runs, mut needless) = (0, 0);
    for tol in [1e-10, 1e-9, 1e-8] {
        let tally = pendulum_cases(fixture, tol);
        tally.assert_honest("pendulum (random starts)", &format!("{tol:e}"));
        runs += tally.made + tally.declined;
        needless += tally.needless;
    }
    assert!(
        100 * needless <= 6 * runs,
        "{needless} of {runs} runs declined with an error under a tenth of the tolerance"
    );
}

fn celt(tol: f64) -> Tally {
    let refs: serde_json::Value =
        serde_json::from_str(include_str!("../fixtures/celt/references.json")).expect("fixture");
    let mut tally = Tally::default();
    for case in refs["cases"].as_array().unwrap() {
        let preset = case["preset"].as_str().unwrap();
        let reference = &case["reference"];
        let r = with_sets(
            preset,
            &[
                format!("run.t_end={}", case["t_end"]),
                format!("run.tolerance={tol}"),
            ],
        );
        let f = &r["final"];
        let mut err = (f["spin"].as_f64().unwrap() - reference["spin"].as_f64().unwrap()).abs();
        for i in 0..3 {
            err = err.max(
                (f["omega"][i].as_f64().unwrap() - reference["omega"][i].as_f64().unwrap()).abs(),
            );
        }
        let counts = |v: &serde_json::Value, key: &str| v[key]["count"].as_u64();
        if counts(&r["events"], "reversals") != reference["reversals"].as_u64()
            || counts(&r["events"], "crossings") != reference["crossings"].as_u64()
        {
            err = f64::INFINITY;
        }
        tally.count(
            preset,
            tol,
            &r,
            err,
            case["omega_uncertainty"].as_f64().unwrap(),
        );
    }
    tally
}

#[test]
fn the_celt_keeps_its_claims_on_every_preset() {
    audit("celt", &[1e-6, 1e-8, 1e-10], celt);
}

#[test]
fn the_celt_meets_a_looser_tolerance_wherever_it_meets_a_tighter_one() {
    // Stop 52: one refinement that did not halve the estimate was read as a floor, and
    // `celt-pitching` ended `met = false` at 1e-4 (estimate 1.1e-4, far above its round-off)
    // while it met 5e-5 and every tighter tolerance. Every shipped celt preset at every decade
    // from 1e-4 to 1e-10: honest, and met at every tolerance looser than one it meets.
    audit("celt", &[1e-4, 1e-5, 1e-7, 1e-9], celt);
    let tolerances = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
    let presets: Vec<String> = std::fs::read_dir(concat!(root!(), "/presets"))
        .expect("the presets")
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            let stem = name.strip_suffix(".toml")?;
            stem.starts_with("celt-").then(|| stem.to_owned())
        })
        .collect();
    assert!(presets.len() >= 7, "{presets:?}");
    for preset in &presets {
        let met: Vec<bool> = tolerances
            .iter()
            .map(|t| {
                with_sets(preset, &[format!("run.tolerance={t}")])["auto"]["met"]
                    .as_bool()
                    .expect("auto.met")
            })
            .collect();
        for (i, &tight) in met.iter().enumerate() {
            for (j, &loose) in met[..i].iter().enumerate() {
                assert!(
                    !tight || loose,
                    "{preset}: met at {:e}, missed at the looser {:e}",
                    tolerances[i],
                    tolerances[j]
                );
            }
        }
    }
}

#[test]
fn auto_measures_the_conditioning_the_references_report() {
    // The condition number `auto` folds into its estimate, against the references' own (the
    // long-double model nudged the same way): near the separatrix 1e3 … 2e7, on small
    // librations below 1. The measurement runs coarse (measured: 0.93–1.6 times the
    // reference's), so it may be up to 3× above, which only makes the floor more cautious,
    // and at most 1.5× below.
    use rattleback::physics::rattleback::auto::{conditioning, plan};
    for case in common::cases_from("rattleback_honesty.toml") {
        let reference = case
            .condition
            .expect("every held-out case states its condition");
        if case.t_end > 60.0 {
            continue; // the long horizons: measured by the same rule, slower to plan
        }
        let p = plan(&case.problem, 1e-8, case.t_end);
        let kappa = conditioning(&case.problem, case.t_end, &p, &mut |_| true)
            .unwrap()
            .rate;
        eprintln!("{}: κ {kappa:.2e}, reference {reference:.2e}", case.name);
        assert!(
            kappa <= 3.0 * reference.max(1.0) && kappa >= reference / 1.5,
            "{}: measured κ {kappa:e}, the reference says {reference:e}",
            case.name
        );
    }
}

#[test]
fn the_slow_models_first_reading_of_the_conditioning_sends_every_ill_conditioned_start_back() {
    // Issue 27: `auto` first measures a start's condition number on `averaged2` at a loose
    // tolerance wherever the expansion parameter is at most 0.25, and measures again on the
    // plan's own method where that reads above 100. Away from the separatrix the reading must be
    // the full model's (here within 1.5×); near it, where the slow model may be off by 300×,
    // it must read above 100, so that the accurate measurement follows. The full model's κ is
    // the Taylor series' at 1e-11 (within 5 % of the references' own where they state it).
    use rattleback::physics::method::RunSpec;
    use rattleback::physics::rattleback::auto::{
        CONDITIONING_AVERAGED_LIMIT, CONDITIONING_LOOSE_TOLERANCE, CONDITIONING_MODEL,
        CONDITIONING_RECHECK, NUDGE, difference, slow_condition_numbers,
    };
    use rattleback::physics::rattleback::averaged::expansion_parameter;
    use rattleback::physics::rattleback::run::run;
    let mut cases = common::averaged_cases();
    cases.extend(common::cases_from("rattleback_honesty.toml"));
    let mut checked = (0, 0);
    for case in cases
        .iter()
        .filter(|c| c.source == "rk8-long-double" && c.t_end <= 100.0)
    {
        if expansion_parameter(&case.problem) > CONDITIONING_AVERAGED_LIMIT {
            continue;
        }
        let kappa = |method, tolerance| {
            let spec = RunSpec {
                method,
                tolerance,
                step: None,
                t_end: case.t_end,
                samples: 0,
                monitor_energy: false,
            };
            let base = run(&case.problem, &spec).unwrap();
            let mut start = *case.problem.start();
            start.alpha_dot *= 1.0 + NUDGE;
            let nudged =
                rattleback::physics::rattleback::Problem::new(*case.problem.params(), start)
                    .unwrap();
            difference(&base, &run(&nudged, &spec).unwrap()) / NUDGE
        };
        // `auto`'s own first reading (the start and its nudged copies side by side).
        let slow = slow_condition_numbers(
            &case.problem,
            CONDITIONING_MODEL,
            CONDITIONING_LOOSE_TOLERANCE,
            case.t_end,
            &mut |_| true,
        )
        .unwrap()
        .rate;
        let full = kappa(rattleback::physics::Method::Taylor, 1e-11);
        if let Some(reference) = case.condition {
            // Within 5 %, or 0.05 where κ is below 1: the nudged runs' own rounding is an
            // absolute noise in κ (about 1e-12 over a nudge of 1e-10 where the series takes a
            // million steps, k = 1e8).
            assert!(
                (full - reference).abs() < 0.05 * reference.max(1.0),
                "{}: {full:e}, the reference's {reference:e}",
                case.name
            );
        }
        if full > CONDITIONING_RECHECK {
            checked.0 += 1;
            assert!(
                slow > CONDITIONING_RECHECK,
                "{}: the slow model reads κ = {slow:e}, the full model's is {full:e}",
                case.name
            );
        } else {
            checked.1 += 1;
            assert!(
                slow <= 1.5 * full.max(1.0) && slow >= full / 1.5,
                "{}: the slow model reads κ = {slow:e}, the full model's is {full:e}",
                case.name
            );
        }
    }
    assert!(checked.0 >= 10 && checked.1 >= 20, "{checked:?}");
}

#[test]
fn a_fixed_step_run_keeps_its_reversal_times_over_many_steps() {
    // 72 000 steps of blanes-moan4 on a small libration at k = 1e6: summed plainly, the time
    // drifted the last reversal by 4.3e-11 while the state was good to 5e-12; the compensated
    // sum keeps every reversal time within 3e-12 of the long-double reference.
    let case = common::cases_from("rattleback_honesty.toml")
        .into_iter()
        .find(|c| c.name == "lib_b1_a015_k1e06")
        .expect("the case");
    let r = with_sets(
        "subcritical",
        &[
            "spring.k=1000000".to_owned(),
            format!("initial.alpha_dot={}", case.problem.start().alpha_dot),
            "run.method=blanes-moan4".to_owned(),
            "run.step=0.0004150370852266856".to_owned(),
        ],
    );
    let times = r["reversals"]["times"].as_array().unwrap();
    assert_eq!(times.len(), case.reversals.len());
    let worst = times
        .iter()
        .zip(&case.reversals)
        .map(|(a, b)| (a.as_f64().unwrap() - b).abs())
        .fold(0.0, f64::max);
    assert!(worst < 3e-12, "a reversal time is {worst:e} off");
}

#[test]
fn near_the_separatrix_the_estimate_bounds_every_rounding_of_the_start() {
    // Rounding near the separatrix is a random walk, and one run is one sample of it: the same
    // start moved by one to three ulps of α̇0 (which moves the reference by at most κ·3 ulps,
    // added to its uncertainty) gives other samples. Every estimate must bound its error on
    // all of them, and no claim may fail.
    let mut tally = Tally::default();
    for case in common::cases_from("rattleback_honesty.toml")
        .into_iter()
        .filter(|c| c.name.starts_with("sep_"))
    {
        let s = case.problem.start();
        for ulps in 1..=3_u64 {
            let alpha_dot = f64::from_bits(s.alpha_dot.to_bits() + ulps);
            let moved = case.condition.expect("stated") * (ulps as f64) * 2.0 * f64::EPSILON;
            for tol in [1e-8, 1e-10] {
                let (r, err) = run_case(&case, alpha_dot, tol);
                let what = format!("{} +{ulps} ulp", case.name);
                tally.count(&what, tol, &r, err, case.uncertainty + moved);
            }
        }
    }
    tally.assert_honest("rattleback, starts 1–3 ulps apart", "1e-8, 1e-10");
}

/// Issue 27, stop 51: far in (an averaged plan at or above the start's conditioning stiffness,
/// where its expansion parameter is 0.01), `auto` may bound the start's condition numbers by its
/// reading at that one stiffness, kept across k, times `CONDITIONING_KEPT_MARGIN`. The bound must
/// hold at every larger k: for every family of reference starts (the start at every k), from
/// that stiffness to 1e12 in steps of √10, the reading `auto` takes at k is within the bound, in
/// rate and in angle, and so is every reference's own κ at or above it (measured: up to 16× and
/// 21× the reading at the stiffness; the margin is 50).
#[test]
fn a_kept_conditioning_bounds_the_start_at_every_larger_k() {
    use rattleback::physics::rattleback::Problem;
    use rattleback::physics::rattleback::auto::{
        CONDITIONING_KEPT_MARGIN, CONDITIONING_LOOSE_TOLERANCE, CONDITIONING_MODEL,
        conditioning_stiffness, probe_problem, slow_condition_numbers,
    };
    let read = |p: &Problem, t_end: f64| {
        let c = slow_condition_numbers(
            p,
            CONDITIONING_MODEL,
            CONDITIONING_LOOSE_TOLERANCE,
            t_end,
            &mut |_| true,
        )
        .unwrap();
        [c.rate, c.angle]
    };
    let mut all = common::cases_from("averaged.toml");
    all.extend(common::cases_from("rattleback_honesty.toml"));
    let (mut families, mut readings, mut most) = (std::collections::BTreeSet::new(), 0, 0.0f64);
    for case in &all {
        let Some(k_c) = conditioning_stiffness(&case.problem) else {
            continue;
        };
        let kept = read(&probe_problem(&case.problem, k_c), case.t_end);
        let bound = kept.map(|x| CONDITIONING_KEPT_MARGIN * x);
        if let Some(reference) = case.condition
            && case.problem.params().k >= k_c
        {
            assert!(
                reference <= bound[0],
                "{}: the reference's κ {reference:e} above the bound {:e}",
                case.name,
                bound[0]
            );
        }
        let family = format!("{} T {}", case.name.split("_k").next().unwrap(), case.t_end);
        if !families.insert(family.clone()) {
            continue;
        }
        let mut k = k_c;
        while k <= 1e12 {
            let here = read(&probe_problem(&case.problem, k), case.t_end);
            for i in 0..2 {
                most = most.max(here[i] / kept[i]);
                assert!(
                    here[i] <= bound[i],
                    "{family} at k = {k:e}: {here:?} above the bound {bound:?}"
                );
            }
            readings += 1;
            k *= 10f64.sqrt();
        }
    }
    eprintln!(
        "{} families, {readings} readings: at most {most:.1}× the kept reading",
        families.len()
    );
    assert!(families.len() >= 15 && readings >= 150, "{readings}");
    assert!(most * 2.0 <= CONDITIONING_KEPT_MARGIN, "{most}");
}

/// Issue 80: 60 random pendulums over long horizons (T 60–1000, `scripts/kapitza_long.py`,
/// seeded), where `auto` declined 1e-10 while its error was 8–150× below its estimate: at the
/// tightest tolerance no estimate is below its error, and at most one decline in eight has an
/// error within a third of the tolerance (measured: 6 of 55 with the portable elementary
/// functions of issue 82, whose rounding the shifted twin sees more of; 4 of 54 with glibc's, when
/// the bound was one in ten); at 1e-9 no estimate is below its error.
#[test]
fn the_pendulums_declines_over_long_horizons_are_not_shy() {
    let fixture = include_str!("../fixtures/reference/kapitza_long.toml");
    let tight = pendulum_cases(fixture, 1e-10);
    tight.assert_honest("pendulum (long horizons)", "1e-10");
    let fix: toml::Table = fixture.parse().unwrap();
    assert!(fix["case"].as_table().unwrap().len() >= 60);
    assert!(
        8 * tight.shy <= tight.declined,
        "{} of {} declines had an error within a third of the tolerance",
        tight.shy,
        tight.declined
    );
    pendulum_cases(fixture, 1e-9).assert_honest("pendulum (long horizons)", "1e-9");
}
