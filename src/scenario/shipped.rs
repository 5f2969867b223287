//! Where presets and themes come from: a path; else the user's folder
//! (`~/.config/rattleback/{presets,themes}` on Linux via `directories`, or
//! `$RATTLEBACK_CONFIG_DIR/{presets,themes}`); else the ones shipped inside the binary, so an
//! installed program has them. A user file with a shipped name shadows the shipped one.

use std::path::{Path, PathBuf};

use serde::Serialize;

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
    ("just-below", include_str!("../../presets/just-below.toml")),
    ("just-above", include_str!("../../presets/just-above.toml")),
    ("symmetric", include_str!("../../presets/symmetric.toml")),
    ("iy-greater", include_str!("../../presets/iy-greater.toml")),
    ("tapping", include_str!("../../presets/tapping.toml")),
    (
        "stiff-spring",
        include_str!("../../presets/stiff-spring.toml"),
    ),
    (
        "soft-spring",
        include_str!("../../presets/soft-spring.toml"),
    ),
    (
        "tilted-start",
        include_str!("../../presets/tilted-start.toml"),
    ),
    (
        "kapitza-upright",
        include_str!("../../presets/kapitza-upright.toml"),
    ),
    (
        "kapitza-falls",
        include_str!("../../presets/kapitza-falls.toml"),
    ),
    (
        "kapitza-just-above",
        include_str!("../../presets/kapitza-just-above.toml"),
    ),
    (
        "kapitza-just-below",
        include_str!("../../presets/kapitza-just-below.toml"),
    ),
    (
        "kapitza-coarse",
        include_str!("../../presets/kapitza-coarse.toml"),
    ),
    (
        "kapitza-stiff",
        include_str!("../../presets/kapitza-stiff.toml"),
    ),
    (
        "celt-clockwise",
        include_str!("../../presets/celt-clockwise.toml"),
    ),
    (
        "celt-anticlockwise",
        include_str!("../../presets/celt-anticlockwise.toml"),
    ),
    (
        "celt-pitching",
        include_str!("../../presets/celt-pitching.toml"),
    ),
    (
        "celt-rolling",
        include_str!("../../presets/celt-rolling.toml"),
    ),
    (
        "celt-fast-spin",
        include_str!("../../presets/celt-fast-spin.toml"),
    ),
    (
        "celt-mirrored",
        include_str!("../../presets/celt-mirrored.toml"),
    ),
    (
        "celt-stubby",
        include_str!("../../presets/celt-stubby.toml"),
    ),
];

/// The preset `cargo run --release` opens.
pub const DEFAULT_PRESET: &str = "subcritical";

/// The shipped preset a command line of `kind` starts from: the first of its scene in
/// [`SHIPPED`] (every value is then set explicitly, so the command runs the same on any
/// machine).
#[must_use]
pub fn base_preset(kind: crate::physics::ModelKind) -> &'static str {
    SHIPPED
        .iter()
        .find(|(name, text)| {
            Preset::parse(text, name, name, &[]).is_ok_and(|p| p.model.kind() == kind)
        })
        .map_or(DEFAULT_PRESET, |(name, _)| name)
}

/// The environment variable that replaces the config folder.
pub const CONFIG_ENV: &str = "RATTLEBACK_CONFIG_DIR";

/// The user's config folder: `$RATTLEBACK_CONFIG_DIR`, else the platform's
/// (`~/.config/rattleback` on Linux). `None` when neither exists (no home directory).
#[must_use]
pub fn config_dir() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os(CONFIG_ENV).filter(|d| !d.is_empty()) {
        return Some(PathBuf::from(dir));
    }
    directories::ProjectDirs::from("", "", "rattleback").map(|d| d.config_dir().to_path_buf())
}

/// The user's preset folder.
#[must_use]
pub fn user_preset_dir() -> Option<PathBuf> {
    config_dir().map(|d| d.join("presets"))
}

/// Whether `name` is a shipped preset's (saving a user preset under it would hide it).
#[must_use]
pub fn is_shipped(name: &str) -> bool {
    SHIPPED.iter().any(|(n, _)| *n == name)
}

/// Names of the shipped presets, comma-separated.
#[must_use]
pub fn shipped_names() -> String {
    SHIPPED
        .iter()
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Where a preset comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Source {
    /// Inside the binary.
    Shipped,
    /// The user's preset folder.
    User,
}

/// One entry of the catalogue.
#[derive(Clone, Debug, PartialEq, Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Entry {
    /// What `--preset` takes (the file stem).
    pub name: String,
    /// The preset's own `preset.name`.
    pub title: String,
    /// Which scene (model) it loads.
    pub model: crate::physics::ModelKind,
    /// Shipped or user.
    pub source: Source,
    /// The file (`presets/NAME.toml` inside the binary for shipped ones).
    pub path: String,
    /// What to look for.
    pub description: String,
}

/// The text of the preset `resolve` would load for `name_or_path` (checked first: an invalid or
/// unknown preset is an error), to print and copy.
///
/// # Errors
/// As [`resolve`].
pub fn source_text(name_or_path: &str) -> Result<String, PresetError> {
    resolve(name_or_path, &[])?;
    let path = Path::new(name_or_path);
    if path.is_file() || super::write::is_stdin(path) {
        return PresetError::read(path);
    }
    if let Some(user) = user_preset_dir().map(|d| d.join(format!("{name_or_path}.toml")))
        && user.is_file()
    {
        return PresetError::read(&user);
    }
    Ok(SHIPPED
        .iter()
        .find(|(n, _)| *n == name_or_path)
        .map(|(_, src)| (*src).to_owned())
        .unwrap_or_default())
}

/// Every preset: shipped ones, then the user's (a user preset with a shipped name replaces
/// it). Invalid user files and two presets sharing a `preset.name` are reported, not hidden.
#[must_use]
pub fn catalogue() -> (Vec<Entry>, Vec<PresetError>) {
    catalogue_in(user_preset_dir().as_deref())
}

/// [`catalogue`] with the user presets taken from `user_dir`.
#[must_use]
pub fn catalogue_in(user_dir: Option<&Path>) -> (Vec<Entry>, Vec<PresetError>) {
    let mut entries = Vec::new();
    let mut problems = Vec::new();
    for (name, src) in SHIPPED {
        match Preset::parse(src, &format!("presets/{name}.toml (shipped)"), name, &[]) {
            Ok(p) => entries.push(Entry {
                name: (*name).to_owned(),
                title: p.name,
                model: p.model.kind(),
                source: Source::Shipped,
                path: format!("presets/{name}.toml"),
                description: p.description,
            }),
            Err(e) => problems.push(e),
        }
    }
    if let Some(dir) = user_dir {
        let (files, mut odd) = toml_files_and_unnameable(dir);
        problems.append(&mut odd);
        for path in files {
            let name = stem(&path);
            match Preset::load(&path, &[]) {
                Ok(p) => {
                    entries.retain(|e| e.name != name);
                    entries.push(Entry {
                        name,
                        title: p.name,
                        model: p.model.kind(),
                        source: Source::User,
                        path: path.display().to_string(),
                        description: p.description,
                    });
                }
                Err(e) => problems.push(e),
            }
        }
    }
    for (i, a) in entries.iter().enumerate() {
        if let Some(b) = entries[i + 1..].iter().find(|b| b.title == a.title) {
            problems.push(PresetError::Invalid {
                path: b.path.clone(),
                line: None,
                key: Some("preset.name".to_owned()),
                message: format!(
                    "two presets are named \"{}\" ({} and {}); rename one",
                    a.title, a.path, b.path
                ),
            });
        }
    }
    (entries, problems)
}

/// The `.toml` files of a folder, sorted (none if it does not exist).
#[must_use]
pub fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let (files, _) = toml_files_and_unnameable(dir);
    files
}

/// The `.toml` files of `dir` whose names can be typed, and a problem for each of the others
/// (a name with a control, bidirectional or separator character: listed, completed or
/// printed raw it would act on the terminal or split in two; issue 56).
#[must_use]
pub fn toml_files_and_unnameable(dir: &Path) -> (Vec<PathBuf>, Vec<PresetError>) {
    let Ok(read) = std::fs::read_dir(dir) else {
        return (Vec::new(), Vec::new());
    };
    let mut files: Vec<PathBuf> = read
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    let (plain, odd): (Vec<PathBuf>, Vec<PathBuf>) = files
        .into_iter()
        .partition(|p| super::text::is_plain(&p.to_string_lossy()));
    let problems = odd
        .iter()
        .map(|p| PresetError::Invalid {
            path: super::text::visible(&p.display().to_string()),
            line: None,
            key: None,
            message: "the file's name has control or invisible characters, so it cannot be shown or typed; rename it".to_owned(),
        })
        .collect();
    (plain, problems)
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Loads `name_or_path`: an existing file path; else a user preset of that name; else a
/// shipped one.
///
/// # Errors
/// No such file or preset, or an invalid preset.
pub fn resolve(name_or_path: &str, overrides: &[Override]) -> Result<Preset, PresetError> {
    let path = Path::new(name_or_path);
    let named = |mut p: Preset, origin: String| {
        p.origin = Some(origin);
        p
    };
    if super::write::is_stdin(path) {
        return Preset::load(path, overrides);
    }
    if path.is_file() {
        // Named again by its full path, from wherever the command is run.
        let full = std::fs::canonicalize(path)
            .map_or_else(|_| name_or_path.to_owned(), |p| p.display().to_string());
        return Preset::load(path, overrides).map(|p| named(p, full));
    }
    if let Some(user) = user_preset_dir().map(|d| d.join(format!("{name_or_path}.toml")))
        && user.is_file()
    {
        return Preset::load(&user, overrides).map(|p| named(p, name_or_path.to_owned()));
    }
    if let Some((name, src)) = SHIPPED.iter().find(|(n, _)| *n == name_or_path) {
        let label = format!("presets/{name}.toml (shipped)");
        return Preset::parse(src, &label, name, overrides).map(|p| named(p, (*name).to_owned()));
    }
    if path.extension().is_some() || name_or_path.contains(std::path::MAIN_SEPARATOR) {
        // Looks like a path: say so, with the system's reason.
        return Preset::load(path, overrides);
    }
    let mut available: Vec<String> = SHIPPED.iter().map(|(n, _)| (*n).to_owned()).collect();
    if let Some(dir) = user_preset_dir() {
        available.extend(toml_files(&dir).iter().map(|p| stem(p)));
    }
    Err(PresetError::NotFound {
        noun: "preset",
        name: name_or_path.to_owned(),
        available: available.join(", "),
    })
}
