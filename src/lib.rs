//! The holonomic rattleback explorer: physics core, scenarios and the headless commands.
//!
//! Layers (each module's doc says what it may import): `physics` ← `scenario` ← `cli`.

pub mod cli;
pub mod physics;
pub mod scenario;
pub mod simulate;
