//! Keys while a value is typed, a prompt or the picker is open: saving a preset (name, then
//! description, with the confirmations a shipped or existing name needs), notes and chapters.

use super::mode::{Confirm, Picker, PickerRow, Prompt, PromptFor};
use super::{App, Caption, Effect, Key, Message, Mode, RecState};
use crate::app::journal::Event;
use crate::scenario::text::clean;

impl App {
    pub(super) fn on_edit_key(&mut self, mut text: String, key: Key) -> Vec<Effect> {
        match key {
            Key::Char(c) => text.push(c),
            Key::Backspace => {
                text.pop();
            }
            Key::Esc => {
                self.status = None;
                return Vec::new();
            }
            Key::Enter => {
                return self.apply(self.field().with_text(&self.scenario.settings, &text));
            }
            _ => {}
        }
        self.mode = Mode::Editing(text);
        Vec::new()
    }

    pub(super) fn on_prompt_key(&mut self, mut prompt: Prompt, key: Key) -> Vec<Effect> {
        match key {
            Key::Char(c) if !c.is_control() => {
                prompt.text.push(c);
                prompt.confirm = Confirm::No;
            }
            Key::Backspace => {
                prompt.text.pop();
                prompt.confirm = Confirm::No;
            }
            Key::Esc => {
                self.status = Message::info("cancelled");
                self.back_to_map(prompt.from_map);
                return Vec::new();
            }
            Key::Enter => {
                let from_map = prompt.from_map;
                let effects = self.submit(prompt);
                self.back_to_map(from_map);
                return effects;
            }
            _ => {}
        }
        self.mode = Mode::Prompt(prompt);
        Vec::new()
    }

    /// A prompt opened from the map closed: the map (still shown) takes the arrows back, unless
    /// what the prompt did opened a mode of its own.
    fn back_to_map(&mut self, from_map: bool) {
        if from_map && self.mode == Mode::Normal && self.view.panes.shows(super::panes::Pane::Map) {
            self.mode = Mode::Map;
        }
    }

    /// Enter in a prompt.
    pub(super) fn submit(&mut self, prompt: Prompt) -> Vec<Effect> {
        let text = clean(prompt.text.trim());
        match prompt.purpose {
            PromptFor::Note | PromptFor::Chapter => {
                let chapter = prompt.purpose == PromptFor::Chapter;
                self.log(if chapter {
                    Event::Chapter {
                        title: text.clone(),
                    }
                } else {
                    Event::Note { text: text.clone() }
                });
                // The prompt's hint is over: say what was done.
                self.status = Message::info(format!(
                    "{} marked at t {:.2}",
                    if chapter { "chapter" } else { "note" },
                    self.run.shown
                ));
                self.caption = Some(Caption {
                    chapter,
                    text,
                    t: self.run.shown,
                });
                Vec::new()
            }
            PromptFor::Answer => {
                match text.parse::<f64>() {
                    Ok(x) if x.is_finite() => self.answer(super::lesson::Given::Number(x)),
                    _ => {
                        self.status = Message::error(format!(
                            "'{text}' is not a number; type one, Esc cancels"
                        ));
                        self.mode = Mode::Prompt(prompt);
                    }
                }
                Vec::new()
            }
            PromptFor::SaveName => {
                // `name` or `name: description`, one prompt: a second one took the keys a user
                // typed next (issue 68).
                let (name, description) = match text.split_once(':') {
                    Some((name, words)) => (name.trim().to_owned(), words.trim().to_owned()),
                    None => (text.clone(), String::new()),
                };
                if !crate::scenario::store::valid_name(&name) {
                    self.status = Message::error(format!(
                        "'{name}' cannot be a preset name: letters, digits, - and _ (then `: words` to describe it)"
                    ));
                    self.mode = Mode::Prompt(prompt);
                    return Vec::new();
                }
                if prompt.confirm == Confirm::No && crate::scenario::shipped::is_shipped(&name) {
                    self.status = Message::error(format!(
                        "'{name}' is a shipped preset: your copy would replace it in every later run. Enter: save anyway, Esc: cancel"
                    ));
                    self.mode = Mode::Prompt(Prompt {
                        confirm: Confirm::Shipped,
                        ..prompt
                    });
                    return Vec::new();
                }
                let description = if description.is_empty() {
                    format!(
                        "Saved from the explorer as {name}, from \"{}\": {}",
                        self.scenario.name, self.scenario.description
                    )
                } else {
                    description
                };
                let mut preset = self.to_preset(&name);
                preset.description = description;
                let overwrite = prompt.confirm == Confirm::Overwrite;
                let effect = Effect::SavePreset {
                    name,
                    text: preset.to_toml(),
                    overwrite,
                };
                self.mode = Mode::Prompt(prompt);
                vec![effect]
            }
        }
    }

    pub(super) fn on_picker_key(&mut self, mut picker: Picker, key: Key) -> Vec<Effect> {
        const PAGE: isize = 10;
        match key {
            Key::Up => picker.move_by(-1),
            Key::Down => picker.move_by(1),
            Key::PageUp => picker.move_by(-PAGE),
            Key::PageDown => picker.move_by(PAGE),
            Key::Home => picker.move_by(-isize::MAX / 2),
            Key::End => picker.move_by(isize::MAX / 2),
            // Esc clears what was typed, then closes.
            Key::Esc if !picker.filter.is_empty() => picker.filter.clear(),
            Key::Esc => return Vec::new(),
            Key::Backspace => picker.type_char(None),
            Key::Char(c) => picker.type_char(Some(c)),
            Key::Enter if picker.visible().is_empty() => {}
            Key::Enter => match picker.rows.get(picker.selected) {
                Some(PickerRow::Preset(entry)) => {
                    let source = if entry.source == crate::scenario::shipped::Source::User {
                        entry.path.clone()
                    } else {
                        entry.name.clone()
                    };
                    return vec![Effect::LoadPreset(source)];
                }
                Some(PickerRow::Broken { error, .. }) => {
                    self.mode =
                        Mode::Dialog(format!("{error}\n\nFix the file, then open p again."));
                    return Vec::new();
                }
                None => {}
            },
            _ => {}
        }
        self.mode = Mode::Picker(picker);
        Vec::new()
    }

    /// Opens a prompt (notes and chapters need a recording).
    pub(super) fn open_prompt(&mut self, purpose: PromptFor) {
        if matches!(purpose, PromptFor::Note | PromptFor::Chapter)
            && self.journal.state == RecState::Off
        {
            self.status =
                Message::error("notes and chapters go into a recording: start one with R");
            return;
        }
        self.status = Message::info(match purpose {
            PromptFor::SaveName => {
                "name it (letters, digits, - and _), then `: words` to describe it if you like"
            }
            _ => "type it, Enter marks, Esc cancels",
        });
        self.mode = Mode::Prompt(Prompt::new(purpose));
    }
}
