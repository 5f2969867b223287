//! Convergence orders measured by step halving on a smooth, low-k case (physics.md §6):
//! the error against a much finer run of the same method falls by `2^p` per halving.

use crate::common;

use rattleback::physics::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::rattleback::run;

fn alpha_at(method: Method, h: f64) -> (f64, f64) {
    // k = 3: fast and slow time scales comparable, every quantity smooth.
    let problem = common::problem(2.0, 1.0, 1.5, 3.0, [0.1, 0.2, 1.0, 0.4]);
    let spec = RunSpec {
        method,
        tolerance: 1e-8,
        step: Some(h),
        t_end: 4.0,
        samples: 0,
        monitor_energy: true,
    };
    let r = run(&problem, &spec).expect("integrates");
    (r.final_state[1], r.final_state[3])
}

/// Observed order from the errors at `h` and `h/2` against a run at `h/64`.
fn observed_order(method: Method, h: f64) -> f64 {
    let reference = alpha_at(method, h / 64.0);
    let e1 =
        (alpha_at(method, h).0 - reference.0).abs() + (alpha_at(method, h).1 - reference.1).abs();
    let e2 = (alpha_at(method, h / 2.0).0 - reference.0).abs()
        + (alpha_at(method, h / 2.0).1 - reference.1).abs();
    (e1 / e2).log2()
}

#[test]
fn each_method_shows_its_order() {
    for (method, h) in [
        (Method::Rk4, 0.1),
        (Method::Strang, 0.05),
        (Method::Yoshida4, 0.1),
        (Method::BlanesMoan4, 0.2),
        (Method::Yoshida6, 0.2),
        (Method::Suzuki8, 0.25),
    ] {
        let p = observed_order(method, h);
        let want = f64::from(method.order());
        eprintln!("{method}: observed order {p:.2} at h = {h}");
        assert!(
            (p - want).abs() < 0.5,
            "{method}: observed order {p:.2}, expected {want}"
        );
    }
}
