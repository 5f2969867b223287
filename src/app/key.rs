//! A key press, independent of the terminal library, and a row of a keymap: what every keymap
//! (`keys`) and every pane's own row (`panes`) are written in.

/// A key press, independent of the terminal library.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    /// A printable character (shifted letters arrive upper-case).
    Char(char),
    /// Arrow up.
    Up,
    /// Arrow down.
    Down,
    /// Arrow left.
    Left,
    /// Arrow right.
    Right,
    /// Shift + arrow up.
    ShiftUp,
    /// Shift + arrow down.
    ShiftDown,
    /// Shift + arrow left.
    ShiftLeft,
    /// Shift + arrow right.
    ShiftRight,
    /// Enter.
    Enter,
    /// Escape.
    Esc,
    /// Backspace.
    Backspace,
    /// Page up.
    PageUp,
    /// Page down.
    PageDown,
    /// Home.
    Home,
    /// End.
    End,
    /// Tab.
    Tab,
    /// A letter with Ctrl (lower case): Ctrl-C, Ctrl-L, Ctrl-Z…
    Ctrl(char),
    /// A character with Alt (Meta).
    Alt(char),
}

/// One row of a keymap.
#[derive(Clone, Copy, Debug)]
pub struct Binding<A: 'static> {
    /// Keys that trigger it.
    pub keys: &'static [Key],
    /// How the keys are written in help.
    pub label: &'static str,
    /// The action.
    pub action: A,
    /// What it does.
    pub help: &'static str,
    /// In the footer: `(keys, word, rank)`; lower ranks are dropped last when it is narrow.
    pub footer: Option<(&'static str, &'static str, u8)>,
}
