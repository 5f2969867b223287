//! The overlays' keys: the help (keys, legend, messages) scrolls, and the log of every message
//! shown, which the message line may have to cut.

use super::keys::{Action, Key};
use super::mode::{Help, HelpPage, Mode};
use super::{App, Effect};

impl App {
    /// A key while the help is open: the arrows, page up and down, Home and End scroll it; `?`
    /// turns to the legend, then closes; Esc and Enter close it; a printable key is typed into
    /// its filter (Backspace takes one back), so the help shows only the lines holding what was
    /// typed; nothing else happens (issue 81: `reset` typed in the help reset the run). Ctrl-C
    /// quits, as everywhere. A view the program opened itself ([`Help::passes_on`]) scrolls by
    /// page only, and passes any other key on but Esc and Enter.
    pub(super) fn on_help_key(&mut self, mut help: Help, key: Key) -> Vec<Effect> {
        const PAGE: i32 = 10;
        if help.passes_on {
            return match key {
                Key::PageDown => {
                    self.mode = Mode::Help(help.scrolled(PAGE));
                    Vec::new()
                }
                Key::PageUp => {
                    self.mode = Mode::Help(help.scrolled(-PAGE));
                    Vec::new()
                }
                Key::Esc | Key::Enter => Vec::new(),
                _ => self.key(key),
            };
        }
        let by = match key {
            Key::Down => Some(1),
            Key::Up => Some(-1),
            Key::PageDown => Some(PAGE),
            Key::PageUp => Some(-PAGE),
            Key::Home => Some(-i32::from(u16::MAX)),
            Key::End => Some(i32::from(u16::MAX)),
            _ => None,
        };
        if let Some(by) = by {
            self.mode = Mode::Help(help.scrolled(by));
            return Vec::new();
        }
        match key {
            Key::Esc | Key::Enter => return Vec::new(),
            Key::Backspace => {
                help.filter.pop();
                self.mode = Mode::Help(help.scrolled(-i32::from(u16::MAX)));
                return Vec::new();
            }
            _ => {}
        }
        if self.options.action_for(key) == Some(Action::ToggleHelp) {
            if help.page == HelpPage::Keys {
                self.mode = Mode::Help(Help::at(HelpPage::Legend));
            }
            return Vec::new();
        }
        if let Key::Char(c) = key
            && !c.is_control()
        {
            help.filter.push(c);
            help.max = u16::MAX;
            self.mode = Mode::Help(help.scrolled(-i32::from(u16::MAX)));
            return Vec::new();
        }
        // Any other key (Tab, a function key): nothing, the help stays.
        self.mode = Mode::Help(help);
        Vec::new()
    }

    /// The help's last scroll position that still fills the overlay, as drawn (the loop calls
    /// this after a frame that showed the help): the scroll never runs past it, so an upward
    /// key always moves.
    pub fn fit_help(&mut self, max: u16) {
        if let Mode::Help(help) = &mut self.mode {
            help.max = max;
            help.scroll = help.scroll.min(max);
        }
    }

    /// Notes the message and caption on screen in the log, when they are new (called after
    /// every key, tick, worker event and outcome).
    pub(super) fn remember(&mut self) {
        self.messages
            .remember(self.status.as_ref(), self.caption.as_ref());
    }
}
