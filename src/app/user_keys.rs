//! The user's extra key bindings (`[keys]` in `config.toml`): action names, key names, and the
//! checks that keep the keymap unambiguous. They add keys to actions; they never take a key the
//! explorer already uses (the error names the action that has it), so the help, the footer and
//! the README stay true for everyone else's keys.

use super::keys::{Action, KEYMAP, Key};

/// Every action a user may bind, with its name in `[keys]`.
pub const ACTION_NAMES: &[(Action, &str)] = &[
    (Action::Quit, "quit"),
    (Action::SelectPrev, "select_prev"),
    (Action::SelectNext, "select_next"),
    (Action::Decrease, "decrease"),
    (Action::Increase, "increase"),
    (Action::DecreaseCoarse, "decrease_coarse"),
    (Action::IncreaseCoarse, "increase_coarse"),
    (Action::Edit, "edit"),
    (Action::TogglePlay, "toggle_play"),
    (Action::Step, "step"),
    (Action::Reset, "reset"),
    (Action::Faster, "faster"),
    (Action::Slower, "slower"),
    (Action::ToggleEffective, "toggle_effective"),
    (Action::ToggleSeries, "toggle_series"),
    (Action::ToggleSweep, "toggle_sweep"),
    (Action::ToggleWeak, "toggle_weak"),
    (Action::ToggleMap, "toggle_map"),
    (Action::ToggleBody, "toggle_body"),
    (Action::ToggleCompare, "toggle_compare"),
    (Action::WiderWindow, "wider_window"),
    (Action::NarrowerWindow, "narrower_window"),
    (Action::ZoomIn, "zoom_in"),
    (Action::ZoomOut, "zoom_out"),
    (Action::PanLeft, "pan_left"),
    (Action::PanRight, "pan_right"),
    (Action::PanUp, "pan_up"),
    (Action::PanDown, "pan_down"),
    (Action::ToggleWrap, "toggle_wrap"),
    (Action::ResetView, "reset_view"),
    (Action::ClearTrail, "clear_trail"),
    (Action::ToggleHelp, "help"),
    (Action::OpenPicker, "presets"),
    (Action::Save, "save"),
    (Action::Export, "export"),
    (Action::CopyCommand, "copy_command"),
    (Action::CycleTheme, "next_theme"),
    (Action::Note, "note"),
    (Action::Chapter, "chapter"),
    (Action::ToggleRecording, "record"),
    (Action::Redraw, "redraw"),
    (Action::Suspend, "suspend"),
];

/// The name of `action` in `[keys]`.
#[must_use]
pub fn action_name(action: Action) -> &'static str {
    ACTION_NAMES
        .iter()
        .find(|(a, _)| *a == action)
        .map_or("?", |(_, n)| n)
}

/// Parses a key as written in `[keys]`: one character (`"i"`, `"I"`, `"!"`), `space`, `enter`,
/// `esc`, `backspace`, `up`/`down`/`left`/`right`, `shift-` + an arrow, `ctrl-` or `alt-` + a
/// letter.
///
/// # Errors
/// What is allowed.
pub fn parse_key(text: &str) -> Result<Key, String> {
    let lower = text.trim().to_lowercase();
    let one = |s: &str| {
        let mut c = s.chars();
        match (c.next(), c.next()) {
            (Some(ch), None) => Some(ch),
            _ => None,
        }
    };
    let key = match lower.as_str() {
        "space" => Some(Key::Char(' ')),
        "enter" | "return" => Some(Key::Enter),
        "esc" | "escape" => Some(Key::Esc),
        "backspace" => Some(Key::Backspace),
        "up" => Some(Key::Up),
        "down" => Some(Key::Down),
        "left" => Some(Key::Left),
        "right" => Some(Key::Right),
        "shift-up" => Some(Key::ShiftUp),
        "shift-down" => Some(Key::ShiftDown),
        "shift-left" => Some(Key::ShiftLeft),
        "shift-right" => Some(Key::ShiftRight),
        s => {
            if let Some(rest) = s.strip_prefix("ctrl-") {
                one(rest).filter(char::is_ascii_lowercase).map(Key::Ctrl)
            } else if let Some(rest) = s.strip_prefix("alt-") {
                one(rest).filter(|c| !c.is_control()).map(Key::Alt)
            } else {
                // One character, case kept (`I` is shift-i).
                one(text.trim()).filter(|c| !c.is_control()).map(Key::Char)
            }
        }
    };
    key.ok_or_else(|| {
        format!(
            "'{text}' is not a key; allowed: one character, space, enter, esc, backspace, up, down, left, right, shift-ARROW, ctrl-LETTER, alt-KEY"
        )
    })
}

/// How a key is written in help.
#[must_use]
pub fn key_label(key: Key) -> String {
    match key {
        Key::Char(' ') => "space".to_owned(),
        Key::Char(c) => c.to_string(),
        Key::Up => "↑".to_owned(),
        Key::Down => "↓".to_owned(),
        Key::Left => "←".to_owned(),
        Key::Right => "→".to_owned(),
        Key::ShiftUp => "shift-↑".to_owned(),
        Key::ShiftDown => "shift-↓".to_owned(),
        Key::ShiftLeft => "shift-←".to_owned(),
        Key::ShiftRight => "shift-→".to_owned(),
        Key::Enter => "Enter".to_owned(),
        Key::Esc => "Esc".to_owned(),
        Key::Backspace => "Backspace".to_owned(),
        Key::Ctrl(c) => format!("Ctrl-{}", c.to_ascii_uppercase()),
        Key::Alt(c) => format!("Alt-{c}"),
    }
}

/// The user's bindings, checked.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct UserKeys {
    bindings: Vec<(Key, Action)>,
}

impl UserKeys {
    /// Checks `(action name, keys)` entries; an error gives the entry's index and why.
    ///
    /// # Errors
    /// An unknown action, a malformed key, a key the explorer already uses, or a key given twice.
    pub fn parse(entries: &[(String, Vec<String>)]) -> Result<Self, (usize, String)> {
        let mut bindings: Vec<(Key, Action)> = Vec::new();
        for (i, (name, keys)) in entries.iter().enumerate() {
            let Some(action) = ACTION_NAMES
                .iter()
                .find(|(_, n)| n == name)
                .map(|(a, _)| *a)
            else {
                return Err((
                    i,
                    format!(
                        "unknown action `{name}`{}; allowed: {}",
                        crate::scenario::text::did_you_mean(
                            name,
                            ACTION_NAMES.iter().map(|(_, n)| *n)
                        ),
                        ACTION_NAMES
                            .iter()
                            .map(|(_, n)| *n)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            };
            for text in keys {
                let key = parse_key(text).map_err(|e| (i, e))?;
                if key == Key::Ctrl('c') {
                    return Err((i, "Ctrl-C always quits; choose another key".to_owned()));
                }
                if let Some(b) = KEYMAP.iter().find(|b| b.keys.contains(&key)) {
                    if b.action == action {
                        continue;
                    }
                    return Err((
                        i,
                        format!(
                            "'{text}' is already bound to {}; choose a free key",
                            action_name(b.action).replace('_', " ")
                        ),
                    ));
                }
                if let Some((_, other)) = bindings.iter().find(|(k, _)| *k == key) {
                    return Err((
                        i,
                        format!(
                            "'{text}' is given twice (also to `{}`)",
                            action_name(*other)
                        ),
                    ));
                }
                bindings.push((key, action));
            }
        }
        Ok(Self { bindings })
    }

    /// The user's action for `key`, if any.
    #[must_use]
    pub fn action_for(&self, key: Key) -> Option<Action> {
        self.bindings
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, a)| *a)
    }

    /// The user's keys for `action`, as help writes them.
    #[must_use]
    pub fn labels(&self, action: Action) -> Vec<String> {
        self.bindings
            .iter()
            .filter(|(_, a)| *a == action)
            .map(|(k, _)| key_label(*k))
            .collect()
    }

    /// Whether there are any.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bindings.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(action: &str, keys: &[&str]) -> (String, Vec<String>) {
        (
            action.to_owned(),
            keys.iter().map(|k| (*k).to_owned()).collect(),
        )
    }

    #[test]
    fn every_action_has_one_name() {
        let mut names: Vec<&str> = ACTION_NAMES.iter().map(|(_, n)| *n).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), ACTION_NAMES.len());
        // Every bound action of the keymap can be named.
        for b in KEYMAP {
            assert_ne!(action_name(b.action), "?", "{:?}", b.action);
        }
    }

    #[test]
    fn keys_parse_and_conflicts_are_refused_with_the_holder() {
        let keys = UserKeys::parse(&[
            entry("zoom_in", &["i"]),
            entry("toggle_play", &["ctrl-p", "Alt-x"]),
            entry("pan_up", &["I"]),
        ])
        .unwrap();
        assert_eq!(keys.action_for(Key::Char('i')), Some(Action::ZoomIn));
        assert_eq!(keys.action_for(Key::Char('I')), Some(Action::PanUp));
        assert_eq!(keys.action_for(Key::Ctrl('p')), Some(Action::TogglePlay));
        assert_eq!(keys.action_for(Key::Alt('x')), Some(Action::TogglePlay));
        assert_eq!(keys.labels(Action::TogglePlay), ["Ctrl-P", "Alt-x"]);

        let e =
            UserKeys::parse(&[entry("zoom_in", &["i"]), entry("zoom_out", &["q"])]).unwrap_err();
        assert_eq!(e.0, 1);
        assert!(e.1.contains("'q' is already bound to quit"), "{}", e.1);
        let e = UserKeys::parse(&[entry("zom_in", &["i"])]).unwrap_err();
        assert!(e.1.contains("did you mean `zoom_in`?"), "{}", e.1);
        let e = UserKeys::parse(&[entry("zoom_in", &["ctrl-"])]).unwrap_err();
        assert!(e.1.contains("is not a key"), "{}", e.1);
        let e =
            UserKeys::parse(&[entry("zoom_in", &["i"]), entry("zoom_out", &["i"])]).unwrap_err();
        assert!(e.1.contains("given twice"), "{}", e.1);
        let e = UserKeys::parse(&[entry("quit", &["ctrl-c"])]).unwrap_err();
        assert!(e.1.contains("Ctrl-C always quits"), "{}", e.1);
        // A default key bound to its own action again is harmless.
        assert!(UserKeys::parse(&[entry("zoom_in", &["z", "i"])]).is_ok());
    }
}
