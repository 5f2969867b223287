//! The peer: the `differential-equations` crate's DOP853 and Verner 9(8) (`rkv988e`) on the
//! same right-hand side (feature `peer`). Only the final state and the evaluation count are
//! compared; reversal times are not located by the peer.

use differential_equations::prelude::*;
use nalgebra::SVector;

use crate::physics::rattleback::model::{initial_state, rhs};
use crate::physics::rattleback::{Params, Problem};

struct Full(Params);

impl ODE<f64, SVector<f64, 4>> for Full {
    fn diff(&self, _t: f64, y: &SVector<f64, 4>, dydt: &mut SVector<f64, 4>) {
        *dydt = rhs(&self.0, y);
    }
}

/// Which peer method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Peer {
    /// Its DOP853.
    Dop853,
    /// Its Verner 9(8).
    Vern9,
}

impl Peer {
    /// The row name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Dop853 => "peer-dop853",
            Self::Vern9 => "peer-vern9",
        }
    }
}

/// The final state and the number of evaluations.
///
/// # Errors
/// What the peer reported, or a non-finite result.
pub fn run(
    problem: &Problem,
    peer: Peer,
    tol: f64,
    t_end: f64,
) -> Result<(SVector<f64, 4>, u64), String> {
    let ode = Full(*problem.params());
    let y0 = initial_state(problem.start());
    let ivp = IVP::ode(&ode, 0.0, t_end, y0).even(t_end);
    let solution = match peer {
        Peer::Dop853 => ivp
            .method(
                ExplicitRungeKutta::dop853()
                    .rtol(tol)
                    .atol(tol)
                    .max_steps(usize::MAX),
            )
            .solve(),
        Peer::Vern9 => ivp
            .method(
                ExplicitRungeKutta::rkv988e()
                    .rtol(tol)
                    .atol(tol)
                    .max_steps(usize::MAX),
            )
            .solve(),
    }
    .map_err(|e| format!("{e:?}").chars().take(120).collect::<String>())?;
    let (_, y) = solution.last().map_err(|e| format!("{e:?}"))?;
    if !y.iter().all(|v| v.is_finite()) {
        return Err(format!(
            "non-finite result after {} evaluations",
            solution.evals.function
        ));
    }
    Ok((*y, solution.evals.function as u64))
}
