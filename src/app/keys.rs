//! Keys, actions and the keymap tables (the explorer's and the replay's). The help overlay and
//! the footers are generated from the tables, so they always list the actual bindings.

pub use super::key::{Binding, Key};
use super::panes::Pane;

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
    /// Show or hide a pane (one a key toggles: `Pane::toggle_name`); the regime map, shown,
    /// takes the arrows; a computed pane's job starts and stops with it.
    Toggle(super::panes::Pane),
    /// Double the weak-* averaging window.
    WiderWindow,
    /// Halve it.
    NarrowerWindow,
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
    /// Show the address `--serve` serves the recording at, with its QR code, again.
    ShowAddress,
    /// Open the preset picker.
    OpenPicker,
    /// Save the current parameters as a user preset.
    Save,
    /// Write the portrait as SVG and the trajectory as CSV.
    Export,
    /// Copy the current parameters as a `simulate` command line (OSC 52).
    CopyCommand,
    /// Next colour theme.
    CycleTheme,
    /// Type a note into the recording.
    Note,
    /// Type a chapter marker into the recording.
    Chapter,
    /// Start or stop recording.
    ToggleRecording,
    /// Redraw the whole screen (Ctrl-L).
    Redraw,
    /// Suspend to the shell (Ctrl-Z); `fg` resumes.
    Suspend,
    /// Back to the preset's view: zoom 1, no pan.
    ResetView,
    /// Bring the next open pane to the front (when the column cannot show them all).
    CyclePanes,
    /// Show every message so far, in full.
    ShowMessages,
}

/// A pane's row in the keymap ([`Pane::binding`]), its action the pane's toggle.
#[must_use]
pub fn pane_binding(pane: Pane) -> Option<Binding<Action>> {
    pane.binding().map(|b| Binding {
        keys: b.keys,
        label: b.label,
        action: Action::Toggle(b.action),
        help: b.help,
        footer: b.footer,
    })
}

/// The keymap, in the order help lists it: the panes' toggles (each pane's row is in
/// [`pane_binding`]) between the rows before and after them.
pub static KEYMAP: std::sync::LazyLock<Vec<Binding<Action>>> = std::sync::LazyLock::new(|| {
    let mut rows = BEFORE_PANES.to_vec();
    rows.extend(Pane::KEYED.into_iter().filter_map(pane_binding));
    rows.extend_from_slice(AFTER_PANES);
    rows
});

/// The keymap's rows before the panes' toggles.
const BEFORE_PANES: &[Binding<Action>] = &[
    Binding {
        keys: &[Key::Up, Key::Char('k')],
        label: "↑↓ / k j",
        action: Action::SelectPrev,
        help: "select the previous / next parameter",
        footer: Some(("↑↓", "select", 5)),
    },
    Binding {
        keys: &[Key::Down, Key::Char('j')],
        label: "",
        action: Action::SelectNext,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Left, Key::Char('h')],
        label: "←→ / h l",
        action: Action::Decrease,
        help: "decrease / increase (fine; k on a log scale)",
        footer: Some(("←→", "change", 5)),
    },
    Binding {
        keys: &[Key::Right, Key::Char('l')],
        label: "",
        action: Action::Increase,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('H')],
        label: "H / L",
        action: Action::DecreaseCoarse,
        help: "decrease / increase (coarse)",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('L')],
        label: "",
        action: Action::IncreaseCoarse,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Enter],
        label: "Enter",
        action: Action::Edit,
        help: "type an exact value",
        footer: Some(("Enter", "edit", 6)),
    },
    Binding {
        keys: &[Key::Char(' ')],
        label: "space",
        action: Action::TogglePlay,
        help: "play / pause",
        footer: Some(("space", "play", 1)),
    },
    Binding {
        keys: &[Key::Char('.')],
        label: ".",
        action: Action::Step,
        help: "single step (paused)",
        footer: Some((".", "step", 3)),
    },
    Binding {
        keys: &[Key::Char('r')],
        label: "r",
        action: Action::Reset,
        help: "reset to t = 0",
        footer: Some(("r", "reset", 4)),
    },
    Binding {
        keys: &[Key::Char('+'), Key::Char('=')],
        label: "+/-",
        action: Action::Faster,
        help: "faster / slower",
        footer: Some(("+/-", "speed", 2)),
    },
    Binding {
        keys: &[Key::Char('-'), Key::Char('_')],
        label: "",
        action: Action::Slower,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('e')],
        label: "e / t",
        action: Action::ToggleEffective,
        help: "effective overlay / time-series pane",
        footer: Some(("e", "limit", 7)),
    },
];

/// The keymap's rows after the panes' toggles.
const AFTER_PANES: &[Binding<Action>] = &[
    Binding {
        keys: &[Key::Char('<')],
        label: "",
        action: Action::NarrowerWindow,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('>')],
        label: "",
        action: Action::WiderWindow,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('z')],
        label: "z/Z",
        action: Action::ZoomIn,
        help: "zoom in / out",
        footer: Some(("z/Z", "zoom", 8)),
    },
    Binding {
        keys: &[Key::Char('Z')],
        label: "",
        action: Action::ZoomOut,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::ShiftLeft],
        label: "shift+arrows",
        action: Action::PanLeft,
        help: "pan",
        footer: None,
    },
    Binding {
        keys: &[Key::ShiftRight],
        label: "",
        action: Action::PanRight,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::ShiftUp],
        label: "",
        action: Action::PanUp,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::ShiftDown],
        label: "",
        action: Action::PanDown,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('w')],
        label: "w / 0",
        action: Action::ToggleWrap,
        help: "wrap alpha to one period / reset the view",
        footer: Some(("w", "wrap", 9)),
    },
    Binding {
        keys: &[Key::Char('0')],
        label: "",
        action: Action::ResetView,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Tab],
        label: "Tab",
        action: Action::CyclePanes,
        help: "next open pane to the front (when not all fit)",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('c')],
        label: "c",
        action: Action::ClearTrail,
        help: "clear the trail",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('p')],
        label: "p",
        action: Action::OpenPicker,
        help: "pick a preset",
        footer: Some(("p", "presets", 6)),
    },
    Binding {
        keys: &[Key::Char('s')],
        label: "s / x / y",
        action: Action::Save,
        help: "save preset / export SVG+CSV / copy command line",
        footer: Some(("s", "save", 9)),
    },
    Binding {
        keys: &[Key::Char('x')],
        label: "",
        action: Action::Export,
        help: "",
        footer: Some(("x", "export", 11)),
    },
    Binding {
        keys: &[Key::Char('y')],
        label: "",
        action: Action::CopyCommand,
        help: "",
        footer: Some(("y", "copy", 11)),
    },
    Binding {
        keys: &[Key::Char('v')],
        label: "v",
        action: Action::ShowMessages,
        help: "every message so far, in full (a long one is cut)",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('T')],
        label: "T",
        action: Action::CycleTheme,
        help: "next colour theme",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('R')],
        label: "R",
        action: Action::ToggleRecording,
        help: "start / stop recording a session",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('n')],
        label: "n/m",
        action: Action::Note,
        help: "note / chapter marker (recording)",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('m')],
        label: "",
        action: Action::Chapter,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('U')],
        label: "U",
        action: Action::ShowAddress,
        help: "the address --serve serves at, with its QR code",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('?')],
        label: "?",
        action: Action::ToggleHelp,
        help: "this help; ? again: the legend",
        footer: Some(("?", "help", 0)),
    },
    Binding {
        keys: &[Key::Ctrl('l')],
        label: "Ctrl-L / Z",
        action: Action::Redraw,
        help: "redraw the screen / suspend (fg resumes)",
        footer: None,
    },
    Binding {
        keys: &[Key::Ctrl('z')],
        label: "",
        action: Action::Suspend,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('q'), Key::Ctrl('c')],
        label: "q/Ctrl-C",
        action: Action::Quit,
        help: "quit",
        footer: Some(("q", "quit", 0)),
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

/// What a key does while a session is replayed (the recording drives the explorer).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReplayAction {
    /// Pause or resume the replay.
    TogglePause,
    /// Replay faster.
    Faster,
    /// Replay slower.
    Slower,
    /// Jump to the next chapter.
    NextChapter,
    /// Jump back to the previous chapter.
    PreviousChapter,
    /// Show or hide the help.
    ToggleHelp,
    /// Redraw the screen.
    Redraw,
    /// Suspend to the shell.
    Suspend,
    /// Leave.
    Quit,
}

/// The replay's keymap, in the order help lists it.
pub const REPLAY_KEYMAP: &[Binding<ReplayAction>] = &[
    Binding {
        keys: &[Key::Char(' ')],
        label: "space",
        action: ReplayAction::TogglePause,
        help: "pause / resume the replay",
        footer: Some(("space", "pause", 1)),
    },
    Binding {
        keys: &[Key::Char('+'), Key::Char('=')],
        label: "+/-",
        action: ReplayAction::Faster,
        help: "replay faster / slower",
        footer: Some(("+/-", "pace", 2)),
    },
    Binding {
        keys: &[Key::Char('-'), Key::Char('_')],
        label: "",
        action: ReplayAction::Slower,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char(']')],
        label: "] / [",
        action: ReplayAction::NextChapter,
        help: "next / previous chapter",
        footer: Some(("[ ]", "chapters", 1)),
    },
    Binding {
        keys: &[Key::Char('[')],
        label: "",
        action: ReplayAction::PreviousChapter,
        help: "",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('?')],
        label: "?",
        action: ReplayAction::ToggleHelp,
        help: "this help",
        footer: Some(("?", "help", 0)),
    },
    Binding {
        keys: &[Key::Ctrl('l')],
        label: "Ctrl-L",
        action: ReplayAction::Redraw,
        help: "redraw the screen",
        footer: None,
    },
    Binding {
        keys: &[Key::Ctrl('z')],
        label: "Ctrl-Z",
        action: ReplayAction::Suspend,
        help: "suspend to the shell (fg resumes)",
        footer: None,
    },
    Binding {
        keys: &[Key::Char('q'), Key::Ctrl('c')],
        label: "q/Ctrl-C",
        action: ReplayAction::Quit,
        help: "quit",
        footer: Some(("q", "quit", 0)),
    },
];

/// The replay action bound to `key`, if any.
#[must_use]
pub fn replay_action_for(key: Key) -> Option<ReplayAction> {
    REPLAY_KEYMAP
        .iter()
        .find(|b| b.keys.contains(&key))
        .map(|b| b.action)
}

/// The keys of the regime map while it has the arrows (`M`); every other key goes to the
/// keymap.
pub const MAP_KEYS: &[(&str, &str)] = &[
    (
        "←→↑↓ / hjkl",
        "move the cursor over the cells (shift: 4 cells)",
    ),
    ("Enter", "load the cell as the start (iy, α̇0; γ0 = α0 = 0)"),
    ("f", "count from the limit or the full model at this k"),
    (
        "Esc",
        "give the arrows back to the parameters (the map stays)",
    ),
    ("M", "hide the map"),
];

/// The map's keys as a Markdown table (docs/guide.md's, checked by a test).
#[must_use]
pub fn map_markdown() -> String {
    use std::fmt::Write as _;
    let mut out = String::from("| key (map has the arrows) | action |\n|---|---|\n");
    for (k, what) in MAP_KEYS {
        let _ = writeln!(out, "| `{k}` | {what} |");
    }
    out
}

/// The footer while the regime map has the arrows.
pub const MAP_FOOTER: &[Hint] = &[
    ("←→↑↓", "cell", 1),
    ("Enter", "load", 1),
    ("f", "limit/full", 2),
    ("Esc", "keys back", 1),
    ("?", "help", 0),
    ("q", "quit", 0),
];

/// The footer while a value or a prompt is typed: the keys are text then.
pub const PROMPT_FOOTER: &[Hint] = &[
    ("type", "text", 1),
    ("Backspace", "delete", 2),
    ("Enter", "done", 0),
    ("Esc", "cancel", 0),
];

/// The footer while the map has the arrows, for a chart with (`sources`: the rattleback's limit
/// or full model, switched by `f`) or without a choice of source.
#[must_use]
pub fn map_footer(sources: bool) -> Vec<Hint> {
    MAP_FOOTER
        .iter()
        .copied()
        .filter(|(key, _, _)| sources || *key != "f")
        .collect()
}

/// A keymap as a Markdown table (docs/guide.md's key tables are this, checked by a test).
#[must_use]
pub fn markdown<A>(map: &[Binding<A>]) -> String {
    use std::fmt::Write as _;
    let mut out = String::from("| key | action |\n|---|---|\n");
    for b in map.iter().filter(|b| !b.label.is_empty()) {
        let _ = writeln!(out, "| `{}` | {} |", b.label, b.help);
    }
    out
}

/// A footer hint: the keys, the word, and its rank (0 is never dropped).
pub type Hint = (&'static str, &'static str, u8);

/// The footer hints of a keymap, in table order.
#[must_use]
pub fn footer<A>(map: &[Binding<A>]) -> Vec<Hint> {
    map.iter().filter_map(|b| b.footer).collect()
}

/// The replay's footer as `space` acts now: `pause` while it plays, `resume` when paused, and
/// no `space` once the recording has ended. A follower's (`rattleback follow`) offers `f fork`
/// too, and `space` until the lecture has ended and been shown to its end (issue 81: caught up
/// with a live lecture, its footer left out both).
#[must_use]
pub fn replay_footer(info: crate::app::ReplayInfo) -> Vec<Hint> {
    let mut hints = footer(REPLAY_KEYMAP);
    let ended = match info.live {
        Some(lecture_ended) => lecture_ended && info.ended,
        None => info.ended,
    };
    let paused = info.paused;
    if info.live.is_some() {
        let at = hints.len().saturating_sub(2);
        hints.insert(at, ("f", "fork", 1));
    }
    if ended {
        hints.retain(|hint| hint.1 != "pause");
    } else if paused {
        for hint in &mut hints {
            if hint.1 == "pause" {
                hint.1 = "resume";
            }
        }
    }
    hints
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unique<A>(map: &[Binding<A>]) {
        let mut seen = std::collections::HashSet::new();
        for b in map {
            for k in b.keys {
                assert!(seen.insert(*k), "{k:?} bound twice");
            }
        }
    }

    #[test]
    fn every_key_maps_to_one_action() {
        unique(&KEYMAP);
        unique(REPLAY_KEYMAP);
        assert_eq!(action_for(Key::Char('q')), Some(Action::Quit));
        assert_eq!(action_for(Key::Ctrl('c')), Some(Action::Quit));
        assert_eq!(action_for(Key::Ctrl('l')), Some(Action::Redraw));
        assert_eq!(action_for(Key::Ctrl('p')), None, "Ctrl-P is not p");
        assert_eq!(action_for(Key::Alt('q')), None, "Alt-q is not q");
        assert_eq!(action_for(Key::Char('x')), Some(Action::Export));
        assert_eq!(action_for(Key::Char('g')), None);
        assert_eq!(
            replay_action_for(Key::Char('?')),
            Some(ReplayAction::ToggleHelp)
        );
    }

    #[test]
    fn footers_come_from_the_tables_and_keep_help_and_quit() {
        for hints in [footer(&KEYMAP), footer(REPLAY_KEYMAP)] {
            let never: Vec<&str> = hints.iter().filter(|h| h.2 == 0).map(|h| h.1).collect();
            assert_eq!(never, ["help", "quit"]);
        }
    }
}
