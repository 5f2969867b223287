//! The demonstration that an implicit stiff method converges to the wrong motion: backward
//! Euler (L-stable, like Radau and BDF) damps the fast oscillation when `ω h ≫ 1`, so the
//! adiabatic constant `θ` drains away, the effective potential flattens, and the spin stops
//! reversing. Order 1; each step solves `y' = y + h f(y')` by Newton's method with a
//! finite-difference Jacobian.

use crate::physics::rattleback::model::ALPHA_DOT;
use nalgebra::Matrix4;

use crate::physics::rattleback::model::{initial_state, rhs, transverse_energy};
use crate::physics::rattleback::{Problem, State};

/// What backward Euler did.
#[derive(Clone, Copy, Debug)]
pub struct EulerRun {
    /// Final state.
    pub state: State,
    /// Sign changes of `alpha_dot` at step ends.
    pub reversals: usize,
    /// Fast energy at the end over fast energy at the start.
    pub fast_energy_ratio: f64,
}

/// Backward Euler with step `h` to `t_end`.
#[must_use]
pub fn backward_euler(problem: &Problem, h: f64, t_end: f64) -> EulerRun {
    let p = problem.params();
    let mut y = initial_state(problem.start());
    let e0 = transverse_energy(p, &y);
    let mut last_sign = y[ALPHA_DOT].signum();
    let mut reversals = 0;
    let steps = (t_end / h).round() as usize;
    for _ in 0..steps {
        let prev = y;
        let mut z = y;
        for _ in 0..8 {
            let g = z - prev - rhs(p, &z) * h;
            let mut jac = Matrix4::<f64>::identity();
            for j in 0..4 {
                let eps = 1e-7 * z[j].abs().max(1.0);
                let mut zp = z;
                zp[j] += eps;
                let col = (rhs(p, &zp) - rhs(p, &z)) * (-h / eps);
                for i in 0..4 {
                    jac[(i, j)] += col[i];
                }
            }
            let Some(dz) = jac.lu().solve(&g) else { break };
            z -= dz;
            if dz.norm() <= 1e-14 * z.norm().max(1.0) {
                break;
            }
        }
        y = z;
        let s = y[ALPHA_DOT].signum();
        // Signs are exactly -1 or 1.
        #[allow(clippy::float_cmp)]
        if y[ALPHA_DOT] != 0.0 && s != last_sign && last_sign != 0.0 {
            reversals += 1;
        }
        if y[ALPHA_DOT] != 0.0 {
            last_sign = s;
        }
    }
    EulerRun {
        state: y,
        reversals,
        fast_energy_ratio: transverse_energy(p, &y) / e0,
    }
}
