//! The holonomic rattleback explorer: physics core, scenarios and the headless commands.
//!
//! Layers (each module's doc says what it may import):
//! `physics` ← `scenario` ← `sim`, `app` ← `ui` ← `explorer`, `terminal` ← `main`; `study`
//! (the limit's studies, threaded) sits beside `sim`, above `physics`.

pub mod app;
pub mod bench;
pub mod cast;
pub mod commands;
pub mod explorer;
pub mod export;
pub mod fault;
pub mod interrupt;
pub mod parallel;
pub mod physics;
pub mod record;
pub mod scenario;
pub mod sim;
pub mod simulate;
pub mod study;
pub mod terminal;
pub mod ui;

#[cfg(test)]
mod scene_contract;
