//! The user's extra key bindings (`[keys]` in `config.toml`): action names, key names, and the
//! checks that keep the keymap unambiguous. They add keys to actions; they never take a key the
//! explorer already uses (the error names the action that has it), so the help, the footer and
//! the README stay true for everyone else's keys.

use super::keys::{Action, KEYMAP, Key};
use super::panes::Pane;

/// Every action a user may bind, with its name in `[keys]`: the panes' toggles (their names
/// from [`Pane::toggle_name`]) after `toggle_effective`, in the order help lists them.
pub static ACTION_NAMES: std::sync::LazyLock<Vec<(Action, &'static str)>> =
    std::sync::LazyLock::new(|| {
        let panes = Pane::ALL
            .into_iter()
            .filter_map(|p| Some((Action::Toggle(p), p.toggle_name()?)));
        let mut names: Vec<_> = BEFORE_PANES.to_vec();
        names.extend(panes);
        names.extend_from_slice(AFTER_PANES);
        names
    });

/// The actions before the panes' toggles.
const BEFORE_PANES: &[(Action, &str)] = &[
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
];

/// The actions after them.
const AFTER_PANES: &[(Action, &str)] = &[
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
    (Action::CyclePanes, "next_pane"),
    (Action::ClearTrail, "clear_trail"),
    (Action::ToggleHelp, "help"),
    (Action::ShowAddress, "address"),
    (Action::OpenPicker, "presets"),
    (Action::Save, "save"),
    (Action::Export, "export"),
    (Action::CopyCommand, "copy_command"),
    (Action::ShowMessages, "messages"),
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
pub fn parse_key(text: &str) -> Result<Key, KeyBindError> {
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
        "pageup" | "pgup" => Some(Key::PageUp),
        "pagedown" | "pgdn" => Some(Key::PageDown),
        "home" => Some(Key::Home),
        "end" => Some(Key::End),
        "tab" => Some(Key::Tab),
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
    key.ok_or_else(|| KeyBindError::NotAKey(text.to_owned()))
}

/// Why a key of `[keys]` was refused (issue 83: typed; each says itself).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum KeyBindError {
    /// Not a key's name.
    #[error(
        "'{0}' is not a key; allowed: one character, space, enter, esc, backspace, tab, pgup, pgdn, home, end, up, down, left, right, shift-ARROW, ctrl-LETTER, alt-KEY"
    )]
    NotAKey(String),
    /// Ctrl-C.
    #[error("Ctrl-C always quits; choose another key")]
    CtrlC,
    /// Held by another action that keeps its defaults.
    #[error(
        "'{text}' is already bound to {}; choose a free key, or free it with {holder} = \"none\" (or {holder} = [\"none\", \"OTHER KEY\"])",
        .holder.replace('_', " ")
    )]
    Held {
        /// As written.
        text: String,
        /// The action holding it, as named in `[keys]`.
        holder: &'static str,
    },
    /// Given to two actions.
    #[error("'{text}' is given twice (also to `{other}`)")]
    Twice {
        /// As written.
        text: String,
        /// The other action, as named in `[keys]`.
        other: &'static str,
    },
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
        Key::PageUp => "PgUp".to_owned(),
        Key::PageDown => "PgDn".to_owned(),
        Key::Home => "Home".to_owned(),
        Key::End => "End".to_owned(),
        Key::Tab => "Tab".to_owned(),
        Key::Ctrl(c) => format!("Ctrl-{}", c.to_ascii_uppercase()),
        Key::Alt(c) => format!("Alt-{c}"),
    }
}

/// The user's bindings, checked.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct UserKeys {
    bindings: Vec<(Key, Action)>,
    /// Actions whose default keys are gone (`"none"` first in their entry).
    replaced: Vec<Action>,
}

/// What `[keys]` writes to take an action's default keys away.
pub const NONE: &str = "none";

impl UserKeys {
    /// Checks `(action name, keys)` entries. Keys are added to the action's defaults; `"none"`
    /// first takes the defaults away (`presets = "none"`; `toggle_play = ["none", "p"]`
    /// moves it), which frees them for other actions. Every problem is returned, each with its
    /// entry's index.
    ///
    /// # Errors
    /// An unknown action, a malformed key, `"none"` after a key, a key another action holds (and
    /// keeps), or a key given twice.
    pub fn parse(entries: &[(String, Vec<String>)]) -> Result<Self, Vec<(usize, String)>> {
        let mut errors = Vec::new();
        let mut actions = Vec::new();
        for (i, (name, _)) in entries.iter().enumerate() {
            let found = ACTION_NAMES
                .iter()
                .find(|(_, n)| n == name)
                .map(|(a, _)| *a);
            if found.is_none() {
                errors.push((i, unknown_action(name)));
            }
            actions.push(found);
        }
        let replaced: Vec<Action> = entries
            .iter()
            .zip(&actions)
            .filter(|((_, keys), _)| keys.first().is_some_and(|k| k.eq_ignore_ascii_case(NONE)))
            .filter_map(|(_, a)| *a)
            .collect();
        let mut bindings: Vec<(Key, Action)> = Vec::new();
        for (i, ((_, keys), action)) in entries.iter().zip(&actions).enumerate() {
            let Some(action) = *action else { continue };
            for (j, text) in keys.iter().enumerate() {
                if text.eq_ignore_ascii_case(NONE) {
                    if j > 0 {
                        errors.push((i, "\"none\" goes first: it takes the action's default keys away, then the keys after it are its own".to_owned()));
                    }
                    continue;
                }
                match bind(text, action, &replaced, &bindings) {
                    Ok(Some(key)) => bindings.push((key, action)),
                    Ok(None) => {}
                    Err(e) => errors.push((i, e.to_string())),
                }
            }
        }
        if errors.is_empty() {
            Ok(Self { bindings, replaced })
        } else {
            Err(errors)
        }
    }

    /// The action of `key`: the user's binding, else the default one unless its action was
    /// given `"none"`.
    #[must_use]
    pub fn resolve(&self, key: Key) -> Option<Action> {
        self.action_for(key)
            .or_else(|| super::keys::action_for(key).filter(|a| !self.replaced.contains(a)))
    }

    /// Whether `action` lost its default keys.
    #[must_use]
    pub fn is_replaced(&self, action: Action) -> bool {
        self.replaced.contains(&action)
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

    /// The footer of `map` (the explorer's keymap): an action that lost its default keys shows
    /// the user's first key instead, or nothing when it has none.
    #[must_use]
    pub fn footer(&self, map: &[super::keys::Binding<Action>]) -> Vec<(String, &'static str, u8)> {
        map.iter()
            .filter_map(|b| {
                let (keys, word, rank) = b.footer?;
                if self.is_replaced(b.action) {
                    let mine = self.labels(b.action).into_iter().next()?;
                    Some((mine, word, rank))
                } else {
                    Some((keys.to_owned(), word, rank))
                }
            })
            .collect()
    }

    /// Whether there are any.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bindings.is_empty() && self.replaced.is_empty()
    }
}

fn unknown_action(name: &str) -> String {
    format!(
        "unknown action `{name}`{}; allowed: {}",
        crate::scenario::text::did_you_mean(name, ACTION_NAMES.iter().map(|(_, n)| *n)),
        ACTION_NAMES
            .iter()
            .map(|(_, n)| *n)
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// One key of `action`'s entry: `Ok(None)` when it is already the action's default (kept);
/// `Err` when it is not a key, is Ctrl-C, is held by another action that keeps its defaults, or
/// was given already.
fn bind(
    text: &str,
    action: Action,
    replaced: &[Action],
    bindings: &[(Key, Action)],
) -> Result<Option<Key>, KeyBindError> {
    let key = parse_key(text)?;
    if key == Key::Ctrl('c') {
        return Err(KeyBindError::CtrlC);
    }
    if let Some(b) = KEYMAP.iter().find(|b| b.keys.contains(&key)) {
        let free = replaced.contains(&b.action);
        if b.action == action && !free {
            return Ok(None);
        }
        if b.action != action && !free {
            return Err(KeyBindError::Held {
                text: text.to_owned(),
                holder: action_name(b.action),
            });
        }
    }
    if let Some((_, other)) = bindings.iter().find(|(k, _)| *k == key) {
        return Err(KeyBindError::Twice {
            text: text.to_owned(),
            other: action_name(*other),
        });
    }
    Ok(Some(key))
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
        for b in KEYMAP.iter() {
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

        let one = |entries: &[(String, Vec<String>)]| {
            let mut e = UserKeys::parse(entries).unwrap_err();
            assert_eq!(e.len(), 1, "{e:?}");
            e.remove(0)
        };
        let e = one(&[entry("zoom_in", &["i"]), entry("zoom_out", &["q"])]);
        assert_eq!(e.0, 1);
        assert!(e.1.contains("'q' is already bound to quit"), "{}", e.1);
        let e = one(&[entry("zom_in", &["i"])]);
        assert!(e.1.contains("did you mean `zoom_in`?"), "{}", e.1);
        let e = one(&[entry("zoom_in", &["ctrl-"])]);
        assert!(e.1.contains("is not a key"), "{}", e.1);
        let e = one(&[entry("zoom_in", &["i"]), entry("zoom_out", &["i"])]);
        assert!(e.1.contains("given twice"), "{}", e.1);
        let e = one(&[entry("quit", &["ctrl-c"])]);
        assert!(e.1.contains("Ctrl-C always quits"), "{}", e.1);
        // Every problem at once, each with its entry.
        let all = UserKeys::parse(&[
            entry("zom_in", &["i"]),
            entry("zoom_out", &["q"]),
            entry("pan_up", &["ctrl-"]),
        ])
        .unwrap_err();
        assert_eq!(all.iter().map(|e| e.0).collect::<Vec<_>>(), [0, 1, 2]);
        // A default key bound to its own action again is harmless.
        assert!(UserKeys::parse(&[entry("zoom_in", &["z", "i"])]).is_ok());
    }

    #[test]
    fn none_unbinds_and_frees_the_keys_for_another_action() {
        // `p` moves from the picker to play/pause; the picker gets `P`; space plays no more.
        let keys = UserKeys::parse(&[
            entry("presets", &["none", "P"]),
            entry("toggle_play", &["none", "p"]),
        ])
        .unwrap();
        assert_eq!(keys.resolve(Key::Char('p')), Some(Action::TogglePlay));
        assert_eq!(keys.resolve(Key::Char('P')), Some(Action::OpenPicker));
        assert_eq!(keys.resolve(Key::Char(' ')), None);
        assert_eq!(keys.resolve(Key::Char('q')), Some(Action::Quit));
        // Unbound alone: the key does nothing.
        let keys = UserKeys::parse(&[entry("clear_trail", &["none"])]).unwrap();
        assert_eq!(keys.resolve(Key::Char('c')), None);
        assert!(keys.is_replaced(Action::ClearTrail));
        // Without freeing it, the key is still refused, with the way to free it.
        let e = UserKeys::parse(&[entry("toggle_play", &["p"])]).unwrap_err();
        assert!(e[0].1.contains("presets = \"none\""), "{}", e[0].1);
        // "none" after a key is a mistake.
        let e = UserKeys::parse(&[entry("zoom_in", &["i", "none"])]).unwrap_err();
        assert!(e[0].1.contains("goes first"), "{}", e[0].1);
    }
}
