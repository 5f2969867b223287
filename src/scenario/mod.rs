//! Scenarios: presets parsed from TOML (raw serde structs) and validated into domain types.
//!
//! Depends on `physics` only; never on the terminal, threads or the clock. Every error names
//! the file, the line where it can be found, the key, and what is allowed.

pub mod config;
pub mod error;
pub mod lesson;
pub mod preset;
pub mod shipped;
pub mod store;
pub mod text;
pub mod theme;
pub mod write;

pub use error::PresetError;
pub use preset::{Preset, RunConfig};
