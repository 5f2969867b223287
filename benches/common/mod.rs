//! Shared by the benches: the problem every benchmark integrates.

use rattleback::physics::{Method, Params, Problem, RunSpec, Start};

/// `ix = 2, iy = 1, iz = 1`, start `(0, 0, 1, alpha_dot)` at stiffness `k`.
pub fn problem(k: f64, alpha_dot: f64) -> Problem {
    Problem::new(
        Params {
            ix: 2.0,
            iy: 1.0,
            iz: 1.0,
            k,
        },
        Start {
            gamma: 0.0,
            alpha: 0.0,
            gamma_dot: 1.0,
            alpha_dot,
        },
    )
    .expect("valid")
}

/// A run to `t_end` with no samples and no energy monitoring (the integrator alone).
pub fn spec(method: Method, tolerance: f64, step: Option<f64>, t_end: f64) -> RunSpec {
    RunSpec {
        method,
        tolerance,
        step,
        t_end,
        samples: 0,
        monitor_energy: false,
    }
}
