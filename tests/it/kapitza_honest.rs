//! The pendulum's `auto` keeps its claims (issue 29): against held-out references made by an
//! order-28 Taylor integrator in long double (`scripts/kapitza_honesty.py`,
//! `tests/fixtures/reference/kapitza_honesty.toml`), for starts that return near the unstable
//! upright over long horizons and long runs of the other shapes, `simulate`'s `auto` at 1e-6,
//! 1e-8 and 1e-9: `met` means the final state is within the tolerance, and the estimate is at
//! least the true error (both up to the reference's own accuracy).

use crate::common::simulate_json;

fn cases() -> toml::Table {
    include_str!("../fixtures/reference/kapitza_honesty.toml")
        .parse()
        .expect("fixture")
}

/// `(claims held, claims made, runs declined, estimates below the error)` over every case.
fn audit(tolerances: &[f64]) -> (usize, usize, usize, Vec<String>) {
    let cases = cases();
    let (mut held, mut made, mut declined, mut low) = (0, 0, 0, Vec::new());
    for (name, c) in cases["case"].as_table().unwrap() {
        let c = c.as_table().unwrap();
        let num = |k: &str| c[k].as_float().unwrap();
        let last = |k: &str| c[k].as_array().unwrap().last().unwrap().as_float().unwrap();
        let accuracy = num("accuracy");
        for &tol in tolerances {
            let sets = [
                format!("pendulum.a={}", num("a")),
                format!("pendulum.b={}", num("b")),
                format!("pendulum.epsilon={}", num("epsilon")),
                format!("initial.theta={}", num("theta0")),
                format!("initial.theta_dot={}", num("theta_dot0")),
                format!("run.t_end={}", num("t_end")),
                format!("run.tolerance={tol}"),
            ];
            let mut args = vec!["--preset", "kapitza-falls"];
            for s in &sets {
                args.extend(["--set", s.as_str()]);
            }
            let r = simulate_json(&args);
            let f = &r["final"];
            let err = (f["theta"].as_f64().unwrap() - last("theta"))
                .abs()
                .max((f["theta_dot"].as_f64().unwrap() - last("theta_dot")).abs());
            let estimate = r["auto"]["error_estimate"].as_f64().unwrap();
            if r["auto"]["met"].as_bool().unwrap() {
                made += 1;
                if err <= tol + accuracy {
                    held += 1;
                }
            } else {
                declined += 1;
            }
            if estimate + accuracy < err {
                low.push(format!(
                    "{name} at {tol:e}: estimate {estimate:.1e}, error {err:.1e}"
                ));
            }
        }
    }
    (held, made, declined, low)
}

#[test]
fn met_means_met_and_the_estimate_bounds_the_error_on_the_held_out_starts() {
    let (held, made, declined, low) = audit(&[1e-6, 1e-8, 1e-9]);
    eprintln!("pendulum auto: {held} claims held of {made} made, {declined} declined");
    assert_eq!(held, made, "a claim was broken");
    assert!(low.is_empty(), "{low:#?}");
    assert!(made > 0, "auto never claimed anything");
}
