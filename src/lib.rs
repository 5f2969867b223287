//! The holonomic rattleback explorer: physics core, scenarios and the headless commands.
//!
//! Layers (each module's doc says what it may import):
//! `physics` ← `scenario` ← `sim`, `app` ← `ui` ← `explorer`, `terminal` ← `main`; `study`
//! (the limit's studies, threaded) sits beside `sim`, above `physics`.

pub mod app;
#[cfg(not(target_arch = "wasm32"))]
pub mod bench;
#[cfg(not(target_arch = "wasm32"))]
pub mod cast;
#[cfg(not(target_arch = "wasm32"))]
pub mod commands;
#[cfg(not(target_arch = "wasm32"))]
pub mod explorer;
#[cfg(not(target_arch = "wasm32"))]
pub mod export;
#[cfg(not(target_arch = "wasm32"))]
pub mod fault;
#[cfg(not(target_arch = "wasm32"))]
pub mod interrupt;
pub mod parallel;
pub mod physics;
pub mod record;
pub mod scenario;
pub mod sim;
pub mod simulate;
pub mod study;
#[cfg(not(target_arch = "wasm32"))]
pub mod terminal;
pub mod ui;

#[cfg(test)]
mod scene_contract;
