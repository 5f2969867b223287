//! The explorer's one modal state: at most one of typing a value, a prompt, the picker, an
//! error dialog or the help is open, and keys go to it first.

use crate::scenario::shipped::Entry;

/// What has the keyboard.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Mode {
    /// The keymap.
    #[default]
    Normal,
    /// Typing an exact value for the selected parameter.
    Editing(String),
    /// A one-line prompt.
    Prompt(Prompt),
    /// The preset picker.
    Picker(Picker),
    /// An error shown until a key is pressed; the explorer keeps running.
    Dialog(String),
    /// The help: the keys, then the legend.
    Help(HelpPage),
    /// The regime map has the arrows: they move its cursor, Enter loads the cell.
    Map,
}

/// A page of the help.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HelpPage {
    /// The keymap.
    Keys,
    /// What every colour, mark and status field means.
    Legend,
}

/// What a prompt is for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PromptFor {
    /// The name of a user preset to save (`s`).
    SaveName,
    /// Its description, once named.
    SaveDescription {
        /// The name chosen.
        name: String,
    },
    /// A note in the recording (`n`).
    Note,
    /// A chapter marker in the recording (`m`).
    Chapter,
    /// The numeric answer to a lesson's question (`a`).
    Answer,
}

impl PromptFor {
    /// The label shown before the typed text.
    #[must_use]
    pub fn label(&self) -> &'static str {
        match self {
            Self::SaveName => "save as",
            Self::SaveDescription { .. } => "description",
            Self::Note => "note",
            Self::Chapter => "chapter",
            Self::Answer => "answer",
        }
    }
}

/// What Enter must confirm before it acts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Confirm {
    /// Nothing: Enter acts.
    No,
    /// The name is a shipped preset's: saving hides it for every later run.
    Shipped,
    /// A user preset of that name exists: saving replaces it.
    Overwrite,
}

/// A one-line text prompt.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Prompt {
    /// What it is for.
    pub purpose: PromptFor,
    /// The text typed so far.
    pub text: String,
    /// What Enter must confirm first.
    pub confirm: Confirm,
}

impl Prompt {
    /// An empty prompt for `purpose`.
    #[must_use]
    pub fn new(purpose: PromptFor) -> Self {
        Self {
            purpose,
            text: String::new(),
            confirm: Confirm::No,
        }
    }
}

/// One row of the picker.
#[derive(Clone, Debug, PartialEq)]
pub enum PickerRow {
    /// A preset that loads.
    Preset(Entry),
    /// A user file that does not: its name and why.
    Broken {
        /// The file's name.
        name: String,
        /// The problem, as `check` reports it.
        error: String,
    },
}

/// The preset picker (`p`).
#[derive(Clone, Debug, PartialEq)]
pub struct Picker {
    /// Every preset, then every broken user file.
    pub rows: Vec<PickerRow>,
    /// Highlighted row.
    pub selected: usize,
}

impl Picker {
    /// Moves the selection one row down (`true`) or up, wrapping.
    pub fn move_by(&mut self, down: bool) {
        let n = self.rows.len().max(1);
        self.selected = if down {
            (self.selected + 1) % n
        } else {
            (self.selected + n - 1) % n
        };
    }

    /// The first row to draw so that the selection is visible in `height` rows.
    #[must_use]
    pub fn first_visible(&self, height: usize) -> usize {
        let h = height.max(1);
        if self.selected < h {
            0
        } else {
            self.selected + 1 - h
        }
    }
}
