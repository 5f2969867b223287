//! The work budget and bounded memory (issue "Never hang, never clobber, never inject", items 1
//! and 6): inputs the tracker reported running for minutes with no output are refused before
//! they start, with the prediction and `--force`; `auto` refuses a refinement over its budget;
//! the explorer refuses to verify `auto` for hours; the CSV is streamed; reversal lists are
//! capped while their counts stay exact.

use crate::common;
use rattleback::physics::method::Asked;

use rattleback::physics::budget::BUDGET_SECONDS;
use rattleback::physics::method::RunSpec;
use rattleback::physics::plan::AutoRules;
use rattleback::physics::rattleback::effective::Effective;
use rattleback::physics::rattleback::plan::{predicted_seconds, resolve};
use rattleback::physics::rattleback::run::MAX_REVERSAL_TIMES;
use rattleback::physics::{Method, StepError};
use rattleback::scenario::shipped::{SHIPPED, resolve as preset};
use rattleback::simulate::{self, Failure, Format, Request};

fn bin(args: &[&str]) -> (i32, String, String) {
    let out = crate::common::rattleback()
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn request(format: Format, force: bool) -> Request {
    Request {
        method: None,
        tolerance: None,
        step: None,
        t_end: None,
        format,
        samples: 1000,
        force,
    }
}

#[test]
fn the_reported_long_runs_are_refused_before_they_start() {
    // Each ran for minutes with no output before (issue 16's list).
    for set in [
        &["--set", "body.ix=1e12"][..],
        &["--set", "body.iz=2e-12"],
        &["--set", "initial.gamma_dot=1e6"],
        &["--set", "run.t_end=1e9", "--set", "spring.k=1e8"],
        &["--set", "run.t_end=1e100", "--method", "effective"],
        &["--set", "run.t_end=1e9", "--method", "dop853"],
        &["--method", "rk4", "--step", "1e-9"],
    ] {
        let mut args = vec!["simulate"];
        args.extend_from_slice(set);
        let clock = std::time::Instant::now();
        let (code, out, err) = bin(&args);
        assert_eq!(code, 2, "{set:?}: {err}");
        assert!(out.is_empty(), "{set:?}: nothing on stdout, got {out}");
        assert!(
            err.contains("predicted to take about") && err.contains("--force"),
            "{set:?}: {err}"
        );
        assert!(err.lines().count() == 1, "{set:?}: one line: {err}");
        // Refused from the cost model, not after computing (generous bound, shared machine).
        assert!(
            clock.elapsed().as_secs() < 20,
            "{set:?} took {:?}",
            clock.elapsed()
        );
    }
}

#[test]
fn every_shipped_preset_runs_within_the_budget_with_every_method() {
    for (name, _) in SHIPPED {
        let p = preset(name, &[]).expect("shipped");
        let tol = p
            .run
            .tolerance
            .unwrap_or(rattleback::physics::DEFAULT_TOLERANCE);
        let Some(problem) = p.problem() else {
            // The pendulum's methods, through simulate's own prediction.
            for &method in p.model.kind().methods() {
                let request = simulate::Request {
                    method: Some(method),
                    ..request(Format::Json, false)
                };
                let resolved = simulate::resolve(&p, &request);
                let s = simulate::predicted_seconds(&p, &resolved, Format::Json);
                assert!(
                    s.is_finite() && s > 0.0 && s < BUDGET_SECONDS / 10.0,
                    "{name} {method}: {s}"
                );
            }
            continue;
        };
        for &method in rattleback::physics::ModelKind::Rattleback.methods() {
            let s = predicted_seconds(problem, &Asked::new(method, tol, None, p.run.t_end));
            assert!(
                s.is_finite() && s > 0.0 && s < BUDGET_SECONDS / 10.0,
                "{name} {method}: {s}"
            );
        }
    }
}

#[test]
fn a_tiny_budget_refuses_and_force_runs() {
    let p = preset("subcritical", &[]).expect("shipped");
    let mut resolved = simulate::resolve(&p, &request(Format::Json, false));
    assert!((resolved.budget - BUDGET_SECONDS).abs() < 1e-9);
    resolved.budget = 1e-6;
    match simulate::simulate(&p, &resolved, Format::Json) {
        Err(Failure::Run(StepError::OverBudget { what, over })) => {
            assert!(what.contains("auto"), "{what}");
            assert!(over.predicted > 1e-6, "{over}");
        }
        other => panic!("refused expected, got {other:?}"),
    }
    let forced = simulate::resolve(&p, &request(Format::Json, true));
    assert!(forced.budget.is_infinite());
    let json = simulate::simulate(&p, &forced, Format::Json).expect("runs");
    assert!(json.contains("\"regime\""));
}

#[test]
fn auto_stops_refining_at_its_budget_and_says_so() {
    // Subcritical to t = 1000 at 1e-12: no refinement can reach it in double precision; the
    // first pair runs (within the 10 s given), the next refinement is not run, and the result
    // says the tolerance was not met instead of computing on.
    let p = preset(
        "subcritical",
        &["run.t_end=1000".parse().expect("override")],
    )
    .expect("ok");
    let r = resolve(
        p.problem().unwrap(),
        Method::Auto,
        1e-12,
        1000.0,
        AutoRules::Verified,
        10.0,
        &mut |_| true,
    )
    .expect("answers");
    assert!(r.shortfall.is_some(), "{r:?}");
    assert!(r.estimate.expect("auto's estimate") > 1e-12, "{r:?}");
}

/// Issue 27: a run whose verification would take hours is verified in segments; the explorer
/// draws its first segment at once and says, at once, where the run stops and what to do (each
/// horizon priced before anything runs); only the horizons before it are verified, and the run
/// fails there. One whose first segment alone is over the budget is refused, as before.
#[test]
fn the_explorer_refuses_to_verify_auto_for_hours_and_says_what_to_do() {
    let p = preset(
        "subcritical",
        &[
            "run.t_end=1e9".parse().expect("override"),
            "spring.k=1e8".parse().expect("override"),
        ],
    )
    .expect("ok");
    let clock = std::time::Instant::now();
    let h = common::Headless::of(&p);
    let status = h.app.status.as_ref().expect("a message");
    assert!(
        status.text.contains("the run stops beyond t = ")
            && status.text.contains("auto needs about")
            && status.text.contains("pick a method in the panel"),
        "{}",
        status.text
    );
    let at = h.app.run.stops.expect("where it stops");
    assert!(
        !h.app.run.segments.is_empty() && h.app.run.verified() <= at && at < 1e9,
        "drawn from its first segment, stops at {at}"
    );
    assert!(clock.elapsed().as_secs() < 20, "{:?}", clock.elapsed());

    // The first segment alone over the budget: refused at once.
    let p = preset(
        "subcritical",
        &[
            "run.t_end=1e300".parse().expect("override"),
            "spring.k=1e8".parse().expect("override"),
        ],
    )
    .expect("ok");
    let h = common::Headless::of(&p);
    let status = h.app.status.as_ref().expect("a message");
    assert!(status.error, "{}", status.text);
    assert!(status.text.contains("auto needs about"), "{}", status.text);
    assert!(h.app.run.segments.is_empty());
}

/// A sink that accepts `limit` bytes and then fails, as a closed pipe does.
struct Closing {
    written: usize,
    limit: usize,
}

impl std::io::Write for Closing {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.written + buf.len() > self.limit {
            return Err(std::io::ErrorKind::BrokenPipe.into());
        }
        self.written += buf.len();
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn the_csv_is_streamed_and_a_closed_output_stops_the_run() {
    let p = preset("subcritical", &[]).expect("shipped");
    let mut req = request(Format::Csv, false);
    req.samples = 10_000_000;
    req.method = Some(Method::Dop853);
    let resolved = simulate::resolve(&p, &req);
    let mut out = Closing {
        written: 0,
        limit: 4096,
    };
    let mut last_t = 0.0;
    let result = simulate::simulate_to(&p, &resolved, Format::Csv, &mut out, &mut |t| {
        last_t = t;
        true
    });
    assert!(matches!(result, Err(Failure::Output(_))), "{result:?}");
    // Rows reached the output while the run was at its very start: it was streamed, and it
    // stopped there instead of integrating (and holding) all ten million samples.
    assert!(out.written > 0);
    assert!(last_t < 1.0, "the run went on to t = {last_t}");
}

#[test]
fn the_streamed_csv_of_auto_is_the_verified_run_bit_for_bit() {
    let p = preset("supercritical", &[]).expect("shipped");
    let mut req = request(Format::Csv, false);
    req.samples = 50;
    let resolved = simulate::resolve(&p, &req);
    let csv = simulate::simulate(&p, &resolved, Format::Csv).expect("runs");
    let verified = rattleback::physics::rattleback::auto::run_auto(
        p.problem().unwrap(),
        1e-9,
        p.run.t_end,
        50,
        true,
    )
    .expect("auto runs");
    // The `# key = value` lines, then the column names, then the rows.
    let rows: Vec<&str> = csv
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .collect();
    assert_eq!(rows.len(), 50);
    for (row, s) in rows.iter().zip(&verified.result.samples) {
        let cols: Vec<f64> = row.split(',').map(|c| c.parse().expect("number")).collect();
        assert_eq!(cols[0].to_bits(), s.t.to_bits(), "{row}");
        for i in 0..4 {
            assert_eq!(cols[i + 1].to_bits(), s.state[i].to_bits(), "{row}");
        }
    }
}

#[test]
fn reversal_lists_are_capped_and_counts_exact_for_any_horizon() {
    let p = preset("subcritical", &[]).expect("shipped");
    let eff = Effective::new(p.problem().unwrap());
    let half = eff.half_period().expect("reverses");
    // 1e300 / half reversals: counted in closed form, not by stepping (which never ended
    // where `half` is below the spacing of floats near t).
    let clock = std::time::Instant::now();
    let count = eff.reversal_count(1e300);
    assert!(count > 1_000_000_000, "{count}");
    assert_eq!(eff.reversal_times(1e300).len(), MAX_REVERSAL_TIMES);
    assert!(clock.elapsed().as_secs() < 20);
    // Where the list is complete, the count is its length and agrees with the closed form.
    let t_end = 1000.0;
    let times = eff.reversal_times(t_end);
    assert_eq!(eff.reversal_count(t_end), times.len());
    assert!(times.len() as f64 >= t_end / half - 2.0);
    assert!(times.iter().all(|&t| t > 0.0 && t <= t_end));
    // And a run's own count matches its list.
    let r = rattleback::physics::rattleback::run(
        p.problem().unwrap(),
        &RunSpec {
            method: Method::Dop853,
            tolerance: 1e-9,
            step: None,
            t_end: 100.0,
            samples: 0,
            monitor_energy: false,
        },
    )
    .expect("runs");
    assert_eq!(r.reversal_count, r.reversals.len());
    assert!(r.reversal_count > 0);
}

#[test]
fn progress_never_reaches_a_pipe() {
    // stderr is a pipe here: a long-enough run prints nothing but the report.
    let (code, _out, err) = bin(&["simulate", "--set", "run.t_end=300", "--method", "dop853"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "{err:?}");
}

/// Prints the cost model's prediction beside the measured seconds of `auto` (resolved, then
/// the chosen run, as `simulate` does) and of one DOP853 run, on the shipped celt presets
/// and the reliability review's hostile cases (issue 56):
/// `cargo test --release --test it celt_cost_model -- --ignored --nocapture`.
#[test]
#[ignore = "a measurement, run by hand"]
fn celt_cost_model_prediction_against_measurement() {
    use rattleback::physics::Method;
    use rattleback::physics::celt::budget::cost_seconds;
    use rattleback::physics::celt::run::run;
    use rattleback::physics::method::Asked;
    use rattleback::physics::method::RunSpec;
    use rattleback::physics::plan::{AutoRules, PlanRequest};
    let mut cases: Vec<(String, rattleback::scenario::Preset)> =
        rattleback::scenario::shipped::SHIPPED
            .iter()
            .filter(|(n, _)| n.starts_with("celt"))
            .map(|(n, _)| {
                (
                    (*n).to_owned(),
                    rattleback::scenario::shipped::resolve(n, &[]).unwrap(),
                )
            })
            .collect();
    for set in [
        &["run.t_end=1e3"][..],
        &["celt.gravity=1e7"],
        &["initial.omega_z=1e4", "run.t_end=10"],
        &["initial.omega_z=1e6", "run.t_end=0.1"],
    ] {
        let o: Vec<rattleback::scenario::preset::Override> =
            set.iter().map(|s| s.parse().unwrap()).collect();
        cases.push((
            set.join(" "),
            rattleback::scenario::shipped::resolve("celt-clockwise", &o).unwrap(),
        ));
    }
    for (name, preset) in cases {
        let Some(p) = preset.model.celt() else {
            continue;
        };
        let tol = preset.run.tolerance.unwrap_or(1e-8);
        let t_end = preset.run.t_end;
        for method in [Method::Dop853, Method::Auto] {
            let predicted = cost_seconds(p, &Asked::new(method, tol, None, t_end));
            let start = std::time::Instant::now();
            let resolution = rattleback::physics::celt::plan::resolve(
                p,
                &PlanRequest {
                    method,
                    tolerance: tol,
                    t_end,
                    policy: AutoRules::Verified,
                    budget: 60.0,
                },
                &mut |_| true,
            )
            .unwrap();
            let spec = RunSpec {
                method: Method::Dop853,
                tolerance: resolution.plan.tolerance,
                t_end,
                samples: 0,
                step: None,
                monitor_energy: true,
            };
            run(p, &spec, &mut |_| true).unwrap();
            let measured = start.elapsed().as_secs_f64();
            println!(
                "{name:40} {:7} predicted {predicted:9.4} s measured {measured:9.4} s ratio {:5.2}",
                method.name(),
                measured / predicted
            );
        }
    }
}
