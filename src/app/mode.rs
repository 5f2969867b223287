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
    /// The address `--serve` serves the recording at, with its QR code for a hall to scan,
    /// until a key is pressed (as a dialog).
    Address(String),
    /// The help: the keys, then the legend; it scrolls where it is taller than the screen.
    Help(Help),
    /// The regime map has the arrows: they move its cursor, Enter loads the cell.
    Map,
}

/// The help overlay: its page, how far it is scrolled, and what was typed to filter it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Help {
    /// The page shown.
    pub page: HelpPage,
    /// The first line shown.
    pub scroll: u16,
    /// The last first line that still fills the overlay, as the last frame drew it (the loop
    /// tells the app with [`crate::app::App::fit_help`]; until then, unbounded).
    pub max: u16,
    /// Opened by the program, not asked for (`y` shows the copied command whole): a key other
    /// than Esc, Enter and the page keys closes it and does what it does (issue 67: the key
    /// after `y` was lost).
    pub passes_on: bool,
    /// What was typed: only the lines holding it are shown (issue 81, lazygit's menus: typing
    /// in the help filtered nothing, closed it, and the letters acted).
    pub filter: String,
}

impl Help {
    /// The top of `page`.
    #[must_use]
    pub fn at(page: HelpPage) -> Self {
        Self {
            page,
            scroll: 0,
            max: u16::MAX,
            passes_on: false,
            filter: String::new(),
        }
    }

    /// The same view, passing on the key that closes it ([`Self::passes_on`]).
    #[must_use]
    pub fn passing_on(self) -> Self {
        Self {
            passes_on: true,
            ..self
        }
    }

    /// Whether `line` is shown under the filter (every line when nothing was typed; case is
    /// ignored).
    #[must_use]
    pub fn shows(&self, line: &str) -> bool {
        self.filter.is_empty() || line.to_lowercase().contains(&self.filter.to_lowercase())
    }

    /// Scrolled by `by` lines (negative: up), within `[0, max]`.
    #[must_use]
    pub fn scrolled(self, by: i32) -> Self {
        let scroll = (i32::from(self.scroll) + by).clamp(0, i32::from(self.max));
        Self {
            scroll: u16::try_from(scroll).unwrap_or(0),
            ..self
        }
    }
}

/// A page of the help.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HelpPage {
    /// The keymap.
    Keys,
    /// What every colour, mark and status field means.
    Legend,
    /// Every message shown, in full (`v`).
    Messages,
}

/// What a prompt is for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PromptFor {
    /// The name of a user preset to save (`s`).
    SaveName,
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
    /// Opened while the map had the arrows: it gets them back when the prompt closes.
    pub from_map: bool,
}

impl Prompt {
    /// An empty prompt for `purpose`.
    #[must_use]
    pub fn new(purpose: PromptFor) -> Self {
        Self {
            purpose,
            text: String::new(),
            confirm: Confirm::No,
            from_map: false,
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

/// The preset picker (`p`): typing filters the rows (by name, scene or title, ignoring case),
/// the arrows, Home, End and the page keys move among the rows left.
#[derive(Clone, Debug, PartialEq)]
pub struct Picker {
    /// Every preset, then every broken user file.
    pub rows: Vec<PickerRow>,
    /// Highlighted row (an index into `rows`, always among the rows the filter keeps).
    pub selected: usize,
    /// What has been typed.
    pub filter: String,
}

impl PickerRow {
    /// Whether the row matches `filter` (lower case).
    fn matches(&self, filter: &str) -> bool {
        if filter.is_empty() {
            return true;
        }
        let text = match self {
            Self::Preset(e) => format!("{} {} {}", e.name, e.model.name(), e.title),
            Self::Broken { name, .. } => name.clone(),
        };
        text.to_lowercase().contains(filter)
    }
}

impl Picker {
    /// A picker over `rows` with `selected` highlighted.
    #[must_use]
    pub fn new(rows: Vec<PickerRow>, selected: usize) -> Self {
        Self {
            rows,
            selected,
            filter: String::new(),
        }
    }

    /// The rows the filter keeps, as indices into `rows`.
    #[must_use]
    pub fn visible(&self) -> Vec<usize> {
        let filter = self.filter.to_lowercase();
        (0..self.rows.len())
            .filter(|&i| self.rows[i].matches(&filter))
            .collect()
    }

    /// The selected row's place among the visible ones.
    fn place(&self, visible: &[usize]) -> usize {
        visible
            .iter()
            .position(|&i| i == self.selected)
            .unwrap_or(0)
    }

    /// Moves the selection by `by` visible rows (clamped at both ends).
    pub fn move_by(&mut self, by: isize) {
        let visible = self.visible();
        if visible.is_empty() {
            return;
        }
        let place = self.place(&visible).cast_signed().saturating_add(by);
        let last = visible.len().cast_signed() - 1;
        self.selected = visible[place.clamp(0, last).cast_unsigned()];
    }

    /// Types `c` into the filter (or, with `None`, deletes its last character); the selection
    /// stays where it can, else moves to the first row left.
    pub fn type_char(&mut self, c: Option<char>) {
        match c {
            Some(c) => self.filter.push(c),
            None => {
                self.filter.pop();
            }
        }
        let visible = self.visible();
        if !visible.contains(&self.selected) {
            self.selected = visible.first().copied().unwrap_or(self.selected);
        }
    }

    /// The first visible row to draw so that the selection is visible in `height` rows.
    #[must_use]
    pub fn first_visible(&self, height: usize) -> usize {
        let h = height.max(1);
        let place = self.place(&self.visible());
        if place < h { 0 } else { place + 1 - h }
    }
}
