//! Shared by the benches: the problem every benchmark integrates, from the `bench` module.

pub use rattleback::bench::spec;

/// `ix = 2, iy = 1, iz = 1`, start `(0, 0, 1, alpha_dot)` at stiffness `k`.
pub fn problem(k: f64, alpha_dot: f64) -> rattleback::physics::rattleback::Problem {
    rattleback::bench::case(2.0, 1.0, k, alpha_dot)
}
