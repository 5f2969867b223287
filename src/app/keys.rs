//! Keys, actions and the keymap table. The help overlay is generated from the table, so it
//! always lists the actual bindings; the footer is a short chosen subset (checked against the
//! table by a test).

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
    /// Ctrl-C.
    CtrlC,
}

/// What a key asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// Leave the explorer.
    Quit,
    /// Select the previous parameter.
    SelectPrev,
    /// Select the next parameter.
    SelectNext,
    /// Decrease the selected parameter a little.
    Decrease,
    /// Increase it a little.
    Increase,
    /// Decrease it a lot.
    DecreaseCoarse,
    /// Increase it a lot.
    IncreaseCoarse,
    /// Type an exact value.
    Edit,
    /// Play or pause.
    TogglePlay,
    /// Advance one frame while paused.
    Step,
    /// Restart from t = 0.
    Reset,
    /// Double the speed.
    Faster,
    /// Halve the speed.
    Slower,
    /// Show or hide the effective motion.
    ToggleEffective,
    /// Show or hide the time-series pane.
    ToggleSeries,
    /// Zoom in.
    ZoomIn,
    /// Zoom out.
    ZoomOut,
    /// Pan left.
    PanLeft,
    /// Pan right.
    PanRight,
    /// Pan up.
    PanUp,
    /// Pan down.
    PanDown,
    /// Wrap `alpha` to one period, or unwrap it.
    ToggleWrap,
    /// Forget the drawn trail.
    ClearTrail,
    /// Show or hide the help.
    ToggleHelp,
    /// Open the preset picker.
    OpenPicker,
    /// Save the current parameters as a user preset.
    Save,
    /// Next colour theme.
    CycleTheme,
    /// Type a note into the recording.
    Note,
    /// Type a chapter marker into the recording.
    Chapter,
    /// Start or stop recording.
    ToggleRecording,
}

/// One row of the keymap.
#[derive(Clone, Copy, Debug)]
pub struct Binding {
    /// Keys that trigger it.
    pub keys: &'static [Key],
    /// How the keys are written in help.
    pub label: &'static str,
    /// The action.
    pub action: Action,
    /// What it does.
    pub help: &'static str,
}

/// The keymap, in the order help lists it.
pub const KEYMAP: &[Binding] = &[
    Binding {
        keys: &[Key::Up, Key::Char('k')],
        label: "↑↓ / k j",
        action: Action::SelectPrev,
        help: "select the previous / next parameter",
    },
    Binding {
        keys: &[Key::Down, Key::Char('j')],
        label: "",
        action: Action::SelectNext,
        help: "",
    },
    Binding {
        keys: &[Key::Left, Key::Char('h')],
        label: "←→ / h l",
        action: Action::Decrease,
        help: "decrease / increase (fine; k on a log scale)",
    },
    Binding {
        keys: &[Key::Right, Key::Char('l')],
        label: "",
        action: Action::Increase,
        help: "",
    },
    Binding {
        keys: &[Key::Char('H')],
        label: "H / L",
        action: Action::DecreaseCoarse,
        help: "decrease / increase (coarse)",
    },
    Binding {
        keys: &[Key::Char('L')],
        label: "",
        action: Action::IncreaseCoarse,
        help: "",
    },
    Binding {
        keys: &[Key::Enter],
        label: "Enter",
        action: Action::Edit,
        help: "type an exact value",
    },
    Binding {
        keys: &[Key::Char(' ')],
        label: "space",
        action: Action::TogglePlay,
        help: "play / pause",
    },
    Binding {
        keys: &[Key::Char('.')],
        label: ".",
        action: Action::Step,
        help: "single step (paused)",
    },
    Binding {
        keys: &[Key::Char('r')],
        label: "r",
        action: Action::Reset,
        help: "reset to t = 0",
    },
    Binding {
        keys: &[Key::Char('+'), Key::Char('=')],
        label: "+/-",
        action: Action::Faster,
        help: "faster / slower",
    },
    Binding {
        keys: &[Key::Char('-'), Key::Char('_')],
        label: "",
        action: Action::Slower,
        help: "",
    },
    Binding {
        keys: &[Key::Char('e')],
        label: "e / t",
        action: Action::ToggleEffective,
        help: "effective overlay / time-series pane",
    },
    Binding {
        keys: &[Key::Char('t')],
        label: "",
        action: Action::ToggleSeries,
        help: "",
    },
    Binding {
        keys: &[Key::Char('z')],
        label: "z/Z",
        action: Action::ZoomIn,
        help: "zoom in / out",
    },
    Binding {
        keys: &[Key::Char('Z')],
        label: "",
        action: Action::ZoomOut,
        help: "",
    },
    Binding {
        keys: &[Key::ShiftLeft],
        label: "shift+arrows",
        action: Action::PanLeft,
        help: "pan",
    },
    Binding {
        keys: &[Key::ShiftRight],
        label: "",
        action: Action::PanRight,
        help: "",
    },
    Binding {
        keys: &[Key::ShiftUp],
        label: "",
        action: Action::PanUp,
        help: "",
    },
    Binding {
        keys: &[Key::ShiftDown],
        label: "",
        action: Action::PanDown,
        help: "",
    },
    Binding {
        keys: &[Key::Char('w')],
        label: "w",
        action: Action::ToggleWrap,
        help: "wrap alpha to one period",
    },
    Binding {
        keys: &[Key::Char('c')],
        label: "c",
        action: Action::ClearTrail,
        help: "clear the trail",
    },
    Binding {
        keys: &[Key::Char('p')],
        label: "p",
        action: Action::OpenPicker,
        help: "pick a preset",
    },
    Binding {
        keys: &[Key::Char('s')],
        label: "s",
        action: Action::Save,
        help: "save as a user preset",
    },
    Binding {
        keys: &[Key::Char('T')],
        label: "T",
        action: Action::CycleTheme,
        help: "next colour theme",
    },
    Binding {
        keys: &[Key::Char('R')],
        label: "R",
        action: Action::ToggleRecording,
        help: "start / stop recording a session",
    },
    Binding {
        keys: &[Key::Char('n')],
        label: "n/m",
        action: Action::Note,
        help: "note / chapter marker (recording)",
    },
    Binding {
        keys: &[Key::Char('m')],
        label: "",
        action: Action::Chapter,
        help: "",
    },
    Binding {
        keys: &[Key::Char('?')],
        label: "?",
        action: Action::ToggleHelp,
        help: "this help",
    },
    Binding {
        keys: &[Key::Char('q'), Key::Esc, Key::CtrlC],
        label: "q/Esc/Ctrl-C",
        action: Action::Quit,
        help: "quit",
    },
];

/// The action bound to `key`, if any.
#[must_use]
pub fn action_for(key: Key) -> Option<Action> {
    KEYMAP
        .iter()
        .find(|b| b.keys.contains(&key))
        .map(|b| b.action)
}

/// Short hints for the footer, from the table.
pub const FOOTER: &[(&str, &str)] = &[
    ("space", "play"),
    (".", "step"),
    ("r", "reset"),
    ("+/-", "speed"),
    ("↑↓", "select"),
    ("←→", "change"),
    ("Enter", "edit"),
    ("e", "limit"),
    ("t", "series"),
    ("z/Z", "zoom"),
    ("w", "wrap"),
    ("p", "presets"),
    ("s", "save"),
    ("?", "help"),
    ("q", "quit"),
];

/// Footer hints while replaying a session (keys drive the replay, not the explorer).
pub const REPLAY_FOOTER: &[(&str, &str)] = &[
    ("space", "pause"),
    ("+/-", "pace"),
    ("]", "next chapter"),
    ("[", "previous chapter"),
    ("q", "quit"),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_maps_to_one_action_and_footer_keys_exist() {
        let mut seen = std::collections::HashSet::new();
        for b in KEYMAP {
            for k in b.keys {
                assert!(seen.insert(*k), "{k:?} bound twice");
            }
        }
        assert_eq!(action_for(Key::Char('q')), Some(Action::Quit));
        assert_eq!(action_for(Key::CtrlC), Some(Action::Quit));
        assert_eq!(action_for(Key::Char('x')), None);
    }
}
