//! Saving user presets: checked names, never overwriting without consent, atomic writes (a
//! temporary file in the same folder, then a rename), so a crash never leaves half a file.

use std::path::{Path, PathBuf};

/// Why a preset could not be saved.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SaveError {
    /// The name cannot be a file name.
    #[error("'{0}' is not allowed as a preset name; use letters, digits, '-' and '_'")]
    BadName(String),
    /// A file of that name exists and overwriting was not confirmed.
    #[error("{0} exists")]
    Exists(PathBuf),
    /// No config folder (no home directory and no `RATTLEBACK_CONFIG_DIR`).
    #[error("no folder for user presets: set RATTLEBACK_CONFIG_DIR")]
    NoFolder,
    /// The system refused.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
}

/// Whether `name` is a safe preset name.
#[must_use]
pub fn valid_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= 64
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
}

/// Writes `text` to `dir/name.toml` atomically; refuses to replace an existing file unless
/// `overwrite`.
///
/// # Errors
/// A bad name, an existing file, or an I/O failure (nothing is left half-written).
pub fn save(
    dir: Option<&Path>,
    name: &str,
    text: &str,
    overwrite: bool,
) -> Result<PathBuf, SaveError> {
    if !valid_name(name) {
        return Err(SaveError::BadName(name.to_owned()));
    }
    let dir = dir.ok_or(SaveError::NoFolder)?;
    let path = dir.join(format!("{name}.toml"));
    if !overwrite && std::fs::symlink_metadata(&path).is_ok() {
        return Err(SaveError::Exists(path));
    }
    let io = |source| SaveError::Io {
        path: path.clone(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(io)?;
    super::write::write_atomic(&path, text.as_bytes(), overwrite).map_err(|e| {
        if e.kind() == std::io::ErrorKind::AlreadyExists {
            SaveError::Exists(path.clone())
        } else {
            io(e)
        }
    })?;
    Ok(path)
}
