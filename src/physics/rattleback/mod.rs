//! The holonomic rattleback (docs/physics.md §1–4): a rigid body on a stiff spring of Hooke constant
//! `k`, its effective limit `k → ∞`, the second-order averaged model, their integrators,
//! spin-reversal location, `auto` and the cost model. The state vector is
//! `(γ, α, γ̇, α̇)` ([`model::State`], named indices [`model::ALPHA`] …); the slow coordinate is
//! `α`, the event function `α̇`. Reached from outside through [`super::Model::Rattleback`].

pub mod auto;
pub mod averaged;
pub mod averaged3;
#[rustfmt::skip]
mod averaged3_terms;
pub mod budget;
pub mod chart;
#[cfg(test)]
pub mod contract;
pub mod effective;
pub mod integrators;
pub mod map;
pub mod model;
pub mod params;
pub mod plan;
pub mod policy;
pub mod report;
pub mod run;
pub mod scene;
pub mod weak;

pub use model::State;
#[cfg(test)]
pub(crate) use params::paper_body;
pub use params::{Params, Problem, Start};
pub use run::{RunResult, run};
