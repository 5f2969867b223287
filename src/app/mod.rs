//! Application state and actions: decides, never draws. No ratatui types here, no clock and no
//! file I/O: `tick` is handed the elapsed wall time, and what touches files, the recorder, the
//! worker or the terminal is returned as an [`Effect`] that the loop executes and answers with
//! an [`Outcome`]. Every decision is testable.
//!
//! State is split by concern: the scenario (what is simulated), the run (what the worker sent
//! and what is displayed), the view (zoom, panes, theme), one [`Mode`] for whatever has the
//! keyboard, the status line, the caption (notes and chapters), and the journal of a recording.

pub mod computed;
pub mod effects;
pub mod fields;
pub mod journal;
pub mod key;
pub mod keys;
pub mod lesson;
pub mod mode;
mod outcomes;
mod overlays;
pub mod panes;
pub mod portrait;
mod prompts;
mod replayed;
pub mod run;
mod scenario;
mod state;
pub mod user_keys;

pub use effects::{Effect, Outcome, ShellError};
pub use keys::{Action, Key};
pub use mode::Mode;
pub use run::{Events, PlanState, RunState, TRAIL_CAP};
pub use scenario::{Derived, Scenario};
pub use state::{
    Caption, Journal, Message, MessageLog, Options, RecState, ReplayInfo, ViewState, ellipsis, slug,
};

use crate::scenario::Preset;
use crate::scenario::text::clean;
use fields::Field;
use journal::Event;
use mode::{Help, HelpPage, PromptFor};
use panes::{Pane, Panes};
use portrait::{Bounds, View};

/// Speed limits (simulated seconds per wall second).
pub const SPEED_RANGE: (f64, f64) = (1.0 / 64.0, 1024.0);

/// The whole explorer state.
pub struct App {
    /// What is simulated.
    pub scenario: Scenario,
    /// The run and the display clock.
    pub run: RunState,
    /// Zoom, panes, overlay, theme.
    pub view: ViewState,
    /// What the panes the worker computes for show (sweep, weak-*, map, compare).
    pub computed: computed::Computed,
    /// The lesson, when one is open.
    pub lesson: Option<lesson::LessonState>,
    /// What has the keyboard.
    pub mode: Mode,
    /// The last message.
    pub status: Option<Message>,
    /// Every message and caption shown, in full (`v` shows them).
    pub messages: MessageLog,
    /// The current note or chapter.
    pub caption: Option<Caption>,
    /// Set while a session is replayed.
    pub replay: Option<ReplayInfo>,
    /// The lecturer's terminal size at the replayed time, from its last `terminal` line
    /// (format 14; `None` before one: the header's): the exports draw at it.
    pub lecturer_terminal: Option<(u16, u16)>,
    /// The recording's journal.
    pub journal: Journal,
    /// Start-up options.
    pub options: Options,
    /// Quit requested.
    pub quit: bool,
}

impl App {
    /// A paused explorer on `preset`; returns the effects that start its run.
    #[must_use]
    pub fn new(preset: &Preset, options: Options) -> (Self, Vec<Effect>) {
        let scenario = Scenario::of(preset);
        let mut app = Self {
            run: RunState::new(scenario.settings.t_end),
            scenario,
            view: ViewState {
                view: View::default(),
                home: View::default(),
                panes: Panes::default(),
                overlay: true,
                theme: 0,
            },
            computed: computed::Computed::default(),
            lesson: None,
            mode: Mode::Normal,
            status: None,
            messages: MessageLog::default(),
            caption: None,
            replay: None,
            lecturer_terminal: None,
            journal: Journal::default(),
            options,
            quit: false,
        };
        app.apply_view(preset);
        let effects = app.restart();
        (app, effects)
    }

    /// A fresh explorer on `preset` whose runs are numbered after `old`'s, so no event of the
    /// old runs can pass for one of the new (replay's jump back to a chapter).
    #[must_use]
    pub fn new_after(preset: &Preset, options: Options, old: &Self) -> (Self, Vec<Effect>) {
        let (mut app, _) = Self::new(preset, options);
        app.run.generation = old.run.generation;
        app.run.epoch = old.run.epoch + 1;
        app.messages.written.clone_from(&old.messages.written);
        let mut effects = vec![Effect::Sim(app.run.set_overlay(app.view.overlay))];
        effects.extend(app.restart());
        (app, effects)
    }

    /// Shows an error dialog (start-up problems); the explorer keeps running.
    pub fn show_dialog(&mut self, text: &str) {
        self.mode = Mode::Dialog(clean(text));
    }

    /// Shows the address the recording is served at (`--serve`), with its QR code.
    pub fn show_address(&mut self, url: &str) {
        self.mode = Mode::Address(clean(url));
    }

    /// The replay's state, for the status bar.
    pub fn set_replay(&mut self, info: ReplayInfo) {
        self.replay = Some(info);
    }

    /// A message from the loop (the followed file's news).
    pub fn notice(&mut self, text: &str) {
        self.status = Message::info(text);
    }

    /// A follower forks: the replay's hold ends, the state and parameters stay, and the
    /// explorer is the user's own from here.
    pub fn fork(&mut self) {
        self.replay = None;
        self.caption = None;
        // Paused, the display holds where it is shown: a replayed step's goal past the
        // lecture's ceiling is not the user's (issue 82: a fork after the lecturer's `.` jumped
        // one step further as the ceiling went).
        if !self.run.playing {
            self.run.goal = self.run.shown;
        }
        // The lecture's ceiling goes: the display is the user's own from here (issue 55: `.`
        // and space did nothing until a restart).
        self.run.set_ceiling(None);
        // The lecturer's map had the arrows (its title said so): the user's map takes them.
        if std::mem::take(&mut self.computed.map.replayed_focus)
            && self.view.panes.shows(panes::Pane::Map)
        {
            self.mode = Mode::Map;
        }
        self.status = Message::info(format!(
            "forked at t {:.2}: exploring on your own (the lecturer's file is not touched)",
            self.run.shown
        ));
    }

    fn apply_view(&mut self, preset: &Preset) {
        let v = &preset.view;
        let view = View {
            wrap: v.wrap.unwrap_or(false),
            slow_range: v.slow_range,
            rate_range: v.rate_range,
            levels: v.contours.unwrap_or(portrait::LEVELS),
            ..View::default()
        };
        self.view.view = view;
        self.view.home = view;
        self.view.overlay = v.effective_overlay.unwrap_or(true);
        self.view.panes.set(Pane::Series, v.series.unwrap_or(false));
    }

    /// Replaces the scenario with `preset` and restarts.
    pub fn load(&mut self, preset: &Preset) -> Vec<Effect> {
        self.log(Event::Preset {
            toml: preset.to_toml(),
        });
        self.scenario = Scenario::of(preset);
        self.apply_view(preset);
        self.status = Message::info(format!("loaded {}", self.scenario.name));
        let overlay = self.run.set_overlay(self.view.overlay);
        let mut effects = vec![Effect::Sim(overlay)];
        // The panes the new scene does not offer close (their computations stop).
        effects.extend(self.close_foreign_panes());
        effects.extend(self.restart());
        effects
    }

    /// The current state as a preset named `name` (what `s` saves).
    #[must_use]
    pub fn to_preset(&self, name: &str) -> Preset {
        self.scenario
            .to_preset(name, &self.view.view, self.view.overlay, self.series())
    }

    /// Whether the time-series pane is shown.
    #[must_use]
    pub fn series(&self) -> bool {
        self.view.panes.shows(Pane::Series)
    }

    /// The selected field.
    #[must_use]
    pub fn field(&self) -> Field {
        let rows = Field::rows(self.scenario.settings.model.kind());
        rows[self.scenario.selected.min(rows.len() - 1)]
    }

    fn restart(&mut self) -> Vec<Effect> {
        let spec = self.scenario.spec(self.view.overlay);
        let mut effects: Vec<Effect> = self
            .run
            .restart(spec)
            .into_iter()
            .map(Effect::Sim)
            .collect();
        effects.extend(self.start_shown_jobs());
        effects
    }

    /// Handles a key: the open mode first, else the keymap.
    pub fn on_key(&mut self, key: Key) -> Vec<Effect> {
        let effects = self.key(key);
        self.journal_map_cursor();
        self.remember();
        effects
    }

    /// While recording with the map shown: its cursor and whether it has the arrows, when
    /// either changed since last journaled (a key moved it, a step or a load placed it).
    fn journal_map_cursor(&mut self) {
        let shown = self.view.panes.shows(panes::Pane::Map);
        let now = (self.computed.map.cursor, self.mode == Mode::Map);
        if let Some(event) = self.journal.map_cursor_changed(shown, now) {
            self.log(event);
        }
    }

    fn key(&mut self, key: Key) -> Vec<Effect> {
        if key == Key::Ctrl('c') {
            self.quit = true;
            return Vec::new();
        }
        match std::mem::take(&mut self.mode) {
            // Esc closes the innermost thing open and never quits (q and Ctrl-C do).
            Mode::Normal if key == Key::Esc && self.options.action_for(key).is_none() => {
                self.status = if self.status.is_some() {
                    None
                } else {
                    Message::info("nothing to close (q quits)")
                };
                Vec::new()
            }
            Mode::Normal => match self.on_lesson_key(key) {
                Some(effects) => effects,
                None => self
                    .options
                    .action_for(key)
                    .map_or_else(Vec::new, |a| self.update(a)),
            },
            // The address closes on any key, which does nothing else (issue 81: `q` on it
            // ended a hall's lecture; Ctrl-C still quits).
            Mode::Address(_) => Vec::new(),
            // An error's dialog: Esc and Enter close it; any other key closes it and does what
            // it does (issue 66: the key after `R` that could not record was lost, so `q` did
            // not quit; its title says so).
            Mode::Dialog(_) if matches!(key, Key::Esc | Key::Enter) => Vec::new(),
            Mode::Dialog(_) => self.key(key),
            Mode::Help(help) => self.on_help_key(help, key),
            Mode::Editing(text) => self.on_edit_key(text, key),
            Mode::Prompt(prompt) => self.on_prompt_key(prompt, key),
            Mode::Picker(picker) => self.on_picker_key(picker, key),
            Mode::Map => self.on_map_key(key),
        }
    }

    fn log(&mut self, event: Event) {
        self.journal
            .push(self.run.shown, self.run.generation, event);
    }

    /// The terminal now shows `width × height` cells: journaled while recording (format 14), so
    /// the exports draw each moment at the size the lecturer saw.
    pub fn on_resize(&mut self, width: u16, height: u16) {
        self.log(Event::Terminal { width, height });
    }

    /// Takes the journaled events not yet written.
    pub fn take_journal(&mut self) -> Vec<(f64, u64, Event)> {
        std::mem::take(&mut self.journal.entries)
    }

    fn apply(&mut self, result: Result<fields::Settings, fields::EditError>) -> Vec<Effect> {
        match result {
            Ok(s) => {
                self.status = None;
                if s == self.scenario.settings {
                    return Vec::new();
                }
                let field = self.field();
                self.scenario.set(s);
                let value = field.exact(&self.scenario.settings);
                self.log(Event::Set {
                    field: field.label().to_owned(),
                    value,
                });
                self.restart()
            }
            Err(reason) => {
                self.status = Message::error(reason.to_string());
                Vec::new()
            }
        }
    }

    /// Carries out an action; returns the effects. While recording, the actions that change
    /// what is shown are journaled.
    pub fn update(&mut self, action: Action) -> Vec<Effect> {
        // Play at the end starts the run again: journaled as a reset before the play, so a
        // replay (which seeks each line's time before applying it) starts again too.
        let again = action == Action::TogglePlay && self.run.done();
        let effects = self.carry_out(action);
        if again {
            self.log(Event::Reset);
        }
        let event = match action {
            Action::TogglePlay if self.run.playing => Some(Event::Play),
            Action::TogglePlay => Some(Event::Pause),
            Action::Step => Some(Event::Step),
            Action::Reset => Some(Event::Reset),
            Action::Faster | Action::Slower => Some(Event::Speed {
                value: self.run.speed,
            }),
            Action::ZoomIn
            | Action::ZoomOut
            | Action::PanLeft
            | Action::PanRight
            | Action::PanUp
            | Action::PanDown
            | Action::ToggleWrap
            | Action::ResetView => Some(Event::View {
                zoom: self.view.view.zoom,
                pan_x: self.view.view.pan_x,
                pan_y: self.view.view.pan_y,
                wrap: self.view.view.wrap,
            }),
            Action::ToggleEffective | Action::Toggle(_) | Action::CyclePanes => Some(self.layout()),
            Action::ClearTrail => Some(Event::ClearTrail),
            Action::WiderWindow | Action::NarrowerWindow => Some(Event::Window {
                value: self.computed.weak.window,
            }),
            Action::SelectPrev | Action::SelectNext => Some(Event::Select {
                field: self.field().label().to_owned(),
            }),
            // Journaled where they take effect (a set, a preset, a note), or invisible to a
            // replay: listed so that a new action must say which. Not recorded yet: the weak-*
            // window (a new event, so a new session format).
            Action::Quit
            | Action::Decrease
            | Action::Increase
            | Action::DecreaseCoarse
            | Action::IncreaseCoarse
            | Action::Edit
            | Action::ToggleHelp
            | Action::ShowAddress
            | Action::ShowMessages
            | Action::OpenPicker
            | Action::Save
            | Action::Export
            | Action::CopyCommand
            | Action::CycleTheme
            | Action::Note
            | Action::Chapter
            | Action::ToggleRecording
            | Action::Redraw
            | Action::Suspend => None,
        };
        if let Some(e) = event {
            self.log(e);
        }
        effects
    }

    fn carry_out(&mut self, action: Action) -> Vec<Effect> {
        let field = self.field();
        let n = Field::rows(self.scenario.settings.model.kind()).len();
        let settings = self.scenario.settings;
        let v = &mut self.view.view;
        match action {
            Action::Quit => self.quit = true,
            Action::SelectPrev | Action::SelectNext => {
                let d = if action == Action::SelectPrev {
                    n - 1
                } else {
                    1
                };
                self.scenario.selected = (self.scenario.selected + d) % n;
                self.status = None;
            }
            Action::Decrease => return self.apply(field.nudge(&settings, -1.0, false)),
            Action::Increase => return self.apply(field.nudge(&settings, 1.0, false)),
            Action::DecreaseCoarse => return self.apply(field.nudge(&settings, -1.0, true)),
            Action::IncreaseCoarse => return self.apply(field.nudge(&settings, 1.0, true)),
            Action::Edit => {
                self.mode = Mode::Editing(String::new());
                self.status = Message::info(format!(
                    "type {} and press Enter (Esc cancels)",
                    field.label()
                ));
            }
            Action::TogglePlay if self.run.done() => {
                let mut effects = self.restart();
                self.run.playing = true;
                effects.push(Effect::Sim(self.run.advance_command()));
                return effects;
            }
            Action::TogglePlay if self.run.playing => return vec![Effect::Sim(self.run.pause())],
            Action::TogglePlay => {
                self.run.playing = true;
                return vec![Effect::Sim(self.run.advance_command())];
            }
            Action::Step => {
                let dt = self.run.speed / self.options.fps;
                return vec![Effect::Sim(self.run.step(dt))];
            }
            Action::Reset => return self.restart(),
            Action::Faster => self.run.speed = (self.run.speed * 2.0).min(SPEED_RANGE.1),
            Action::Slower => self.run.speed = (self.run.speed / 2.0).max(SPEED_RANGE.0),
            Action::ToggleEffective => return self.toggle_overlay(),
            Action::Toggle(pane) => return self.toggle_pane(pane),
            Action::WiderWindow => self.computed.weak.scale_window(2.0),
            Action::NarrowerWindow => self.computed.weak.scale_window(0.5),
            Action::ZoomIn => v.zoom = (v.zoom * 1.5).min(1e6),
            Action::ZoomOut => v.zoom = (v.zoom / 1.5).max(0.1),
            Action::PanLeft => v.pan_x -= 0.1,
            Action::PanRight => v.pan_x += 0.1,
            Action::PanUp => v.pan_y += 0.1,
            Action::PanDown => v.pan_y -= 0.1,
            Action::ToggleWrap => v.wrap = !v.wrap,
            Action::ResetView => {
                *v = View {
                    wrap: v.wrap,
                    ..self.view.home
                };
                self.status = Message::info("view reset");
            }
            Action::ClearTrail => self.run.clear_trails(),
            Action::ToggleHelp => self.mode = Mode::Help(Help::at(HelpPage::Keys)),
            Action::ShowAddress => match self.options.served.clone() {
                Some(url) => self.show_address(&url),
                None => {
                    self.status =
                        Message::info("not served: --record FILE --serve shows an address here");
                }
            },
            Action::OpenPicker => return vec![Effect::ReadCatalogue],
            Action::Save => self.open_prompt(PromptFor::SaveName),
            Action::Note => self.open_prompt(PromptFor::Note),
            Action::Chapter => self.open_prompt(PromptFor::Chapter),
            Action::ToggleRecording => return self.toggle_recording(),
            Action::CycleTheme => {
                let names = &self.options.theme_names;
                self.view.theme = (self.view.theme + 1) % names.len().max(1);
                let name = names.get(self.view.theme).map_or("default", String::as_str);
                self.status = Message::info(format!(
                    "theme {}/{}: {name}",
                    self.view.theme + 1,
                    names.len().max(1)
                ));
            }
            Action::Export | Action::CopyCommand => return self.export(action),
            Action::Redraw => return vec![Effect::Redraw],
            Action::Suspend => return vec![Effect::Suspend],
            Action::CyclePanes => {
                if !self.view.panes.cycle() {
                    self.status =
                        Message::info("no pane open beside the portrait: nothing to cycle");
                }
            }
            Action::ShowMessages => {
                self.mode = Mode::Help(Help::at(HelpPage::Messages).scrolled(i32::from(u16::MAX)));
            }
        }
        Vec::new()
    }

    /// `x` (files) or `y` (the command line to the clipboard).
    fn export(&mut self, action: Action) -> Vec<Effect> {
        if action == Action::Export {
            self.status = Message::info("exporting…");
            return vec![Effect::Export {
                stem: slug(&self.scenario.name),
            }];
        }
        let text = self.scenario.simulate_command();
        // Said whole, with where it went, once the shell has put it there (`Outcome::Copied`);
        // the messages view shows it whole.
        self.mode = Mode::Help(
            Help::at(HelpPage::Messages)
                .scrolled(i32::from(u16::MAX))
                .passing_on(),
        );
        vec![Effect::Copy(text)]
    }

    /// Advances the displayed clock by `wall_seconds × speed` while playing.
    pub fn tick(&mut self, wall_seconds: f64) -> Vec<Effect> {
        self.journal_map_cursor();
        let effects = self.advance(wall_seconds);
        self.remember();
        effects
    }

    fn advance(&mut self, wall_seconds: f64) -> Vec<Effect> {
        let mut effects: Vec<Effect> = self
            .run
            .tick(wall_seconds)
            .into_iter()
            .map(Effect::Sim)
            .collect();
        self.check_lesson();
        effects.extend(self.journal_tick(wall_seconds));
        effects
    }

    /// The portrait's bounds now.
    #[must_use]
    pub fn bounds(&self) -> Bounds {
        let s = &self.scenario.settings;
        let (q0, q_dot0) = s.model.slow_start();
        let auto = portrait::auto_bounds(
            &self.scenario.derived.limit,
            q0,
            q_dot0,
            self.run.trail_shown(),
            self.view.view.wrap,
        );
        portrait::apply_view(auto, &self.view.view)
    }
}
