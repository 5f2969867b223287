//! The overlays' keys: the help (keys, legend, messages) scrolls, and the log of every message
//! shown, which the message line may have to cut.

use super::keys::{Action, Key};
use super::mode::{Help, HelpPage, Mode};
use super::{App, Effect};

impl App {
    /// A key while the help is open: the arrows, `j` `k`, page up and down, Home and End scroll it; `?`
    /// turns to the legend, then closes; `q` and Ctrl-C quit; any other key only closes it (a
    /// key that closes the help does nothing else). A view the program opened itself
    /// ([`Help::passes_on`]) scrolls by page only, and passes any other key on but Esc and Enter.
    pub(super) fn on_help_key(&mut self, help: Help, key: Key) -> Vec<Effect> {
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
            Key::Down | Key::Char('j') => Some(1),
            Key::Up | Key::Char('k') => Some(-1),
            Key::PageDown | Key::Char(' ') => Some(PAGE),
            Key::PageUp => Some(-PAGE),
            Key::Home => Some(-i32::from(u16::MAX)),
            Key::End => Some(i32::from(u16::MAX)),
            _ => None,
        };
        if let Some(by) = by {
            self.mode = Mode::Help(help.scrolled(by));
            return Vec::new();
        }
        match self.options.action_for(key) {
            Some(Action::ToggleHelp) if help.page == HelpPage::Keys => {
                self.mode = Mode::Help(Help::at(HelpPage::Legend));
            }
            Some(Action::Quit) if key != Key::Esc => self.quit = true,
            // Anything else closes the help and does nothing more.
            _ => {}
        }
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
