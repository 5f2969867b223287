//! What the app asks the loop to do, and what the loop reports back. The app decides; the loop
//! executes (files, the recorder, the worker, the terminal) and never writes the app's fields.

use std::path::PathBuf;

use crate::scenario::Preset;
use crate::scenario::shipped::Entry;
use crate::sim::Command;

/// A side effect for the loop.
#[derive(Clone, Debug, PartialEq)]
pub enum Effect {
    /// A command for the worker.
    Sim(Command),
    /// Open a recording (answered by [`Outcome::Recording`]).
    StartRecording,
    /// Close the recording once its final checkpoint is written.
    StopRecording,
    /// Write a user preset (answered by [`Outcome::Saved`]).
    SavePreset {
        /// File stem.
        name: String,
        /// TOML text.
        text: String,
        /// Replace an existing file.
        overwrite: bool,
    },
    /// Read the preset catalogue (answered by [`Outcome::Catalogue`]).
    ReadCatalogue,
    /// Load a preset by shipped name or path (answered by [`Outcome::Loaded`]).
    LoadPreset(String),
    /// Write the portrait (SVG) and the trajectory (CSV) into the exports folder, named after
    /// `stem` (answered by [`Outcome::Exported`]).
    Export {
        /// A readable file stem (the preset's name, slugged).
        stem: String,
    },
    /// Put `text` on the clipboard of the terminal (OSC 52: works over SSH and in tmux).
    Copy(String),
    /// Redraw the whole screen.
    Redraw,
    /// Suspend the process (terminal restored, then re-entered on resume).
    Suspend,
}

/// Why an effect the shell carried out failed (issue 83: typed; each says itself on the status
/// line or in a dialog).
#[derive(Debug, thiserror::Error)]
pub enum ShellError {
    /// A file or folder the system refused.
    #[error("{}: {source}", .path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// No folder to write into, and where one comes from.
    #[error("{0}")]
    NoFolder(&'static str),
    /// The recording could not start: its signing key, its file (the recorder's own errors,
    /// which live above the explorer's state).
    #[error(transparent)]
    Recording(Box<dyn std::error::Error + Send + Sync>),
    /// A preset that does not load.
    #[error(transparent)]
    Preset(#[from] crate::scenario::PresetError),
    /// The portrait's drawing.
    #[error("drawing the portrait: {0}")]
    Drawing(String),
    /// What this build (the browser's) does not do yet.
    #[error("{0}")]
    NotInThisBuild(String),
}

/// What came of an effect.
#[derive(Debug)]
pub enum Outcome {
    /// The recording started (its path) or could not.
    Recording(Result<String, ShellError>),
    /// The recording was closed (its path).
    RecordingSaved(String),
    /// Writing the recording failed; it stopped.
    RecordingFailed(String),
    /// The preset was written, or why not (`Exists` asks for confirmation).
    Saved(Result<PathBuf, crate::scenario::store::SaveError>),
    /// The catalogue: presets and the problems of broken user files (`(name, error)`).
    Catalogue(Vec<Entry>, Vec<(String, String)>),
    /// A preset to load, or why it did not load.
    Loaded(Box<Result<Preset, ShellError>>),
    /// The files written by an export, or why not.
    Exported(Result<Vec<PathBuf>, ShellError>),
    /// Where `y` put the command: `text` was sent as OSC 52 (no terminal answers it); `tmux`
    /// when tmux's buffer took it too; else the file it was saved to, or why not.
    Copied {
        /// The command.
        text: String,
        /// tmux's `load-buffer` took it.
        tmux: bool,
        /// The file beside the sessions, when tmux did not take it.
        file: Option<Result<PathBuf, ShellError>>,
    },
}

/// The worker commands among `effects` (what headless drivers execute).
#[must_use]
pub fn commands(effects: Vec<Effect>) -> Vec<Command> {
    effects
        .into_iter()
        .filter_map(|e| match e {
            Effect::Sim(c) => Some(c),
            _ => None,
        })
        .collect()
}
