//! The full model at finite `k` (docs/physics.md §1): Euler–Lagrange right-hand side and energy.
//!
//! The state is `(γ, α, γ̇, α̇)` as a `nalgebra` vector; the Hamiltonian form with
//! `pγ = g(α) γ̇`, `pα = iz α̇` is used by the splitting integrators.
use crate::physics::numerics::elementary::Elementary;

use nalgebra::Vector4;

use super::params::{Params, Start};

/// `(gamma, alpha, gamma_dot, alpha_dot)`.
pub type State = Vector4<f64>;

/// Index of `gamma` in a [`State`].
pub const GAMMA: usize = 0;
/// Index of `alpha` in a [`State`].
pub const ALPHA: usize = 1;
/// Index of `gamma_dot` in a [`State`].
pub const GAMMA_DOT: usize = 2;
/// Index of `alpha_dot` in a [`State`].
pub const ALPHA_DOT: usize = 3;

/// The initial values as a state vector.
#[must_use]
pub fn initial_state(start: &Start) -> State {
    State::new(start.gamma, start.alpha, start.gamma_dot, start.alpha_dot)
}

/// Euler–Lagrange right-hand side:
/// `γ̈ = −(g'/g) α̇ γ̇ − (k/g) γ`, `α̈ = g' γ̇² / (2 iz)`.
#[must_use]
#[inline]
pub fn rhs(p: &Params, y: &State) -> State {
    let (gamma, alpha, gamma_dot, alpha_dot) = (y[0], y[1], y[2], y[3]);
    let (s, c) = alpha.e_sin_cos();
    let g = p.ix * c * c + p.iy * s * s;
    let g_prime = 2.0 * (p.iy - p.ix) * s * c;
    let gamma_ddot = -(g_prime * alpha_dot * gamma_dot + p.k * gamma) / g;
    let alpha_ddot = g_prime * gamma_dot * gamma_dot / (2.0 * p.iz);
    State::new(gamma_dot, alpha_dot, gamma_ddot, alpha_ddot)
}

/// Total energy `E = ½ g(α) γ̇² + ½ iz α̇² + ½ k γ²`, conserved exactly by the flow.
#[must_use]
#[inline]
pub fn energy(p: &Params, y: &State) -> f64 {
    p.energy(y[0], y[1], y[2], y[3])
}

/// Energy of the fast oscillation alone, `E⊥ = ½ g(α) γ̇² + ½ k γ²`.
#[must_use]
#[inline]
pub fn transverse_energy(p: &Params, y: &State) -> f64 {
    0.5 * p.g(y[1]) * y[2] * y[2] + 0.5 * p.k * y[0] * y[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_is_constant_along_rhs() {
        // dE/dt = ∇E · f must vanish for any state.
        let p = Params {
            ix: 2.0,
            iy: 1.0,
            iz: 1.5,
            k: 30.0,
        };
        let y = State::new(0.3, 0.7, -1.2, 0.4);
        let f = rhs(&p, &y);
        let h = 1e-6;
        let mut de = 0.0;
        for i in 0..4 {
            let mut yp = y;
            let mut ym = y;
            yp[i] += h;
            ym[i] -= h;
            de += (energy(&p, &yp) - energy(&p, &ym)) / (2.0 * h) * f[i];
        }
        assert!(de.abs() < 1e-7, "dE/dt = {de}");
    }
}
