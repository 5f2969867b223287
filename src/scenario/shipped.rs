//! Presets shipped inside the binary, so an installed program has them, and the resolution of
//! `--preset NAME|PATH`.

use std::path::Path;

use super::error::PresetError;
use super::preset::{Override, Preset};

/// `(name, TOML text)` of every shipped preset; the name is the file stem under `presets/`.
pub const SHIPPED: &[(&str, &str)] = &[
    (
        "subcritical",
        include_str!("../../presets/subcritical.toml"),
    ),
    (
        "supercritical",
        include_str!("../../presets/supercritical.toml"),
    ),
    (
        "soft-spring",
        include_str!("../../presets/soft-spring.toml"),
    ),
];

/// The preset `cargo run --release` opens.
pub const DEFAULT_PRESET: &str = "subcritical";

/// Names of the shipped presets, comma-separated.
#[must_use]
pub fn shipped_names() -> String {
    SHIPPED
        .iter()
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Loads `name_or_path`: an existing file path, else a shipped preset of that name.
///
/// # Errors
/// No such file or preset, or an invalid preset.
pub fn resolve(name_or_path: &str, overrides: &[Override]) -> Result<Preset, PresetError> {
    let path = Path::new(name_or_path);
    if path.is_file() {
        return Preset::load(path, overrides);
    }
    if let Some((name, src)) = SHIPPED.iter().find(|(n, _)| *n == name_or_path) {
        let label = format!("presets/{name}.toml (shipped)");
        return Preset::parse(src, &label, name, overrides);
    }
    if path.extension().is_some() || name_or_path.contains(std::path::MAIN_SEPARATOR) {
        // Looks like a path: say so, with the system's reason.
        return Preset::load(path, overrides);
    }
    Err(PresetError::NotFound {
        name: name_or_path.to_owned(),
        available: shipped_names(),
    })
}
