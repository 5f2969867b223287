//! Application state and actions: decides, never draws. No ratatui types here; no clock
//! either (`tick` is handed the elapsed wall time), so every decision is testable.
//!
//! The flow: a key becomes an [`Action`] through the keymap table; [`App::update`] changes
//! state and returns the [`Command`]s for the worker; [`App::on_sim`] takes the worker's
//! events; [`App::tick`] advances the simulated clock while playing.

pub mod fields;
pub mod journal;
pub mod keys;
pub mod portrait;

use crate::physics::effective::Effective;
use crate::scenario::preset::{RunConfig, ViewConfig};
use crate::scenario::shipped::{Entry, catalogue_in, resolve, user_preset_dir};
use crate::scenario::{Preset, store};
use crate::sim::{self, Command, Point, SimEvent};
use fields::{Field, Settings};
use journal::Event;
pub use keys::{Action, Key};
use portrait::{Bounds, Level, View};

/// Most trail points kept (the oldest half is dropped beyond).
pub const TRAIL_CAP: usize = 40_000;
/// Samples per frame asked from the worker.
const SAMPLES_PER_FRAME: f64 = 8.0;
/// Speed limits (simulated seconds per wall second).
pub const SPEED_RANGE: (f64, f64) = (1.0 / 64.0, 1024.0);

/// Options fixed at start-up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Frame-rate cap.
    pub fps: f64,
}

/// The preset picker (`p`).
#[derive(Clone, Debug, PartialEq)]
pub struct Picker {
    /// Every preset.
    pub entries: Vec<Entry>,
    /// Highlighted row.
    pub selected: usize,
    /// Problems found in the user's folder.
    pub problems: Vec<String>,
}

/// What a text prompt is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PromptFor {
    /// Saving a user preset (`s`).
    Save,
    /// A note in the recording (`n`).
    Note,
    /// A chapter marker in the recording (`m`).
    Chapter,
}

/// A one-line text prompt.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SavePrompt {
    /// What it is for.
    pub purpose: PromptFor,
    /// The text typed so far.
    pub name: String,
    /// The file exists and Enter again will overwrite it (saving only).
    pub confirm: bool,
}

/// Derived values shown read-only under the parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Derived {
    /// The effective model of the start.
    pub effective: Effective,
    /// `alpha_dot² / gamma_dot²`.
    pub ratio: Option<f64>,
    /// The critical ratio.
    pub critical: Option<f64>,
}

/// The whole explorer state.
// Independent toggles of the interface, each a plain yes/no.
#[allow(clippy::struct_excessive_bools)]
pub struct App {
    /// Preset name.
    pub name: String,
    /// What the preset says to look for.
    pub description: String,
    /// Editable parameters.
    pub settings: Settings,
    /// Derived from the settings.
    pub derived: Derived,
    /// Selected row of the panel.
    pub selected: usize,
    /// Text being typed (Enter), if any.
    pub editing: Option<String>,
    /// A message for the user, and whether it is an error.
    pub message: Option<(String, bool)>,
    /// Playing or paused.
    pub playing: bool,
    /// Simulated seconds per wall second.
    pub speed: f64,
    /// Simulated time asked of the worker.
    pub target: f64,
    /// Time reached by the samples received.
    pub reached: f64,
    /// Stamp of the current run.
    pub generation: u64,
    /// Samples of the full motion.
    pub trail: Vec<Point>,
    /// Samples of the effective motion.
    pub effective_trail: Vec<Point>,
    /// Reversal times of the full motion.
    pub reversals: Vec<f64>,
    /// Reversal times of the effective motion.
    pub effective_reversals: Vec<f64>,
    /// Zoom, pan, wrap.
    pub view: View,
    /// Effective overlay shown.
    pub show_effective: bool,
    /// Time-series pane shown.
    pub show_series: bool,
    /// Help overlay shown.
    pub show_help: bool,
    /// The run reached `t_end`.
    pub finished: bool,
    /// The run failed.
    pub failed: Option<String>,
    /// Steps taken by the worker in this run.
    pub steps: u64,
    /// The method integrating this run (what `auto` chose), once the worker says.
    pub method_in_use: Option<crate::physics::Method>,
    /// Steps per wall second, smoothed.
    pub rate: f64,
    /// Quit requested.
    pub quit: bool,
    /// Start-up options.
    pub options: Options,
    /// Index of the colour theme (the UI holds the list).
    pub theme: usize,
    /// The preset picker, when open.
    pub picker: Option<Picker>,
    /// The save prompt, when open.
    pub saving: Option<SavePrompt>,
    /// An error shown in a dialog until a key is pressed; the explorer keeps running.
    pub dialog: Option<String>,
    /// The user's preset folder (from `RATTLEBACK_CONFIG_DIR` or the platform's).
    pub user_dir: Option<std::path::PathBuf>,
    /// Semantic events are journaled (a recording is on).
    pub recording: bool,
    /// Journaled events not yet written: `(simulated time, generation, event)`.
    pub journal: Vec<(f64, u64, Event)>,
    /// The user pressed the record key; the explorer starts or stops the recording.
    pub recording_requested: bool,
    /// A session is being replayed: keys drive the replay, and the footer says so.
    pub replaying: bool,
    steps_at_tick: u64,
    contour_cache: Option<(ContourKey, Vec<Level>)>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct ContourKey {
    settings: Settings,
    bounds: Bounds,
    levels: usize,
    samples: usize,
}

impl App {
    /// A paused explorer on `preset`; returns the commands that start its run.
    #[must_use]
    pub fn new(preset: &Preset, options: Options) -> (Self, Vec<Command>) {
        let settings = settings_of(preset);
        let mut app = Self {
            name: preset.name.clone(),
            description: preset.description.clone(),
            derived: derive(&settings),
            settings,
            selected: 0,
            editing: None,
            message: None,
            playing: false,
            speed: 1.0,
            target: 0.0,
            reached: 0.0,
            generation: 0,
            trail: Vec::new(),
            effective_trail: Vec::new(),
            reversals: Vec::new(),
            effective_reversals: Vec::new(),
            view: View::default(),
            show_effective: true,
            show_series: false,
            show_help: false,
            finished: false,
            failed: None,
            steps: 0,
            method_in_use: None,
            rate: 0.0,
            quit: false,
            options,
            theme: 0,
            picker: None,
            saving: None,
            dialog: None,
            user_dir: user_preset_dir(),
            recording: false,
            journal: Vec::new(),
            recording_requested: false,
            replaying: false,
            steps_at_tick: 0,
            contour_cache: None,
        };
        app.apply_view(preset);
        let commands = app.restart();
        (app, commands)
    }

    fn apply_view(&mut self, preset: &Preset) {
        let v = &preset.view;
        self.view = View {
            wrap: v.wrap.unwrap_or(false),
            alpha_range: v.alpha_range,
            alpha_dot_range: v.alpha_dot_range,
            levels: v.contours.unwrap_or(portrait::LEVELS),
            ..View::default()
        };
        self.show_effective = v.effective_overlay.unwrap_or(true);
        self.show_series = v.series.unwrap_or(false);
    }

    /// Replaces the scenario with `preset` and restarts.
    pub fn load(&mut self, preset: &Preset) -> Vec<Command> {
        self.log(Event::Preset {
            toml: preset.to_toml(),
        });
        self.name.clone_from(&preset.name);
        self.description.clone_from(&preset.description);
        self.settings = settings_of(preset);
        self.apply_view(preset);
        self.message = Some((format!("loaded {}", preset.name), false));
        let mut commands = self.restart();
        commands.push(Command::SetEffective(self.show_effective));
        commands
    }

    /// The current state as a preset named `name` (what `s` saves).
    #[must_use]
    pub fn to_preset(&self, name: &str) -> Preset {
        Preset {
            name: name.to_owned(),
            description: self.description.clone(),
            problem: self.settings.problem(),
            run: RunConfig {
                t_end: self.settings.t_end,
                method: Some(self.settings.method),
                tolerance: Some(self.settings.tolerance),
                step: None,
            },
            view: ViewConfig {
                alpha_range: self.view.alpha_range,
                alpha_dot_range: self.view.alpha_dot_range,
                contours: Some(self.view.levels),
                effective_overlay: Some(self.show_effective),
                series: Some(self.show_series),
                wrap: Some(self.view.wrap),
            },
        }
    }

    fn on_dialog_key(&mut self, key: Key) -> Vec<Command> {
        if key == Key::CtrlC {
            self.quit = true;
        }
        self.dialog = None;
        Vec::new()
    }

    fn on_save_key(&mut self, key: Key) -> Vec<Command> {
        let Some(prompt) = self.saving.as_mut() else {
            return Vec::new();
        };
        match key {
            Key::Char(c) => {
                prompt.name.push(c);
                prompt.confirm = false;
            }
            Key::Backspace => {
                prompt.name.pop();
                prompt.confirm = false;
            }
            Key::Esc => self.saving = None,
            Key::CtrlC => self.quit = true,
            Key::Enter if prompt.purpose != PromptFor::Save => {
                let text = prompt.name.clone();
                let event = if prompt.purpose == PromptFor::Note {
                    Event::Note { text: text.clone() }
                } else {
                    Event::Chapter {
                        title: text.clone(),
                    }
                };
                self.saving = None;
                self.message = Some((format!("marked: {text}"), false));
                self.log(event);
            }
            Key::Enter => {
                let (name, confirm) = (prompt.name.clone(), prompt.confirm);
                let text = self.to_preset(&name).to_toml();
                match store::save(self.user_dir.as_deref(), &name, &text, confirm) {
                    Ok(path) => {
                        self.saving = None;
                        self.message = Some((format!("saved {}", path.display()), false));
                    }
                    Err(store::SaveError::Exists(path)) => {
                        if let Some(p) = self.saving.as_mut() {
                            p.confirm = true;
                        }
                        self.message = Some((
                            format!("{} exists: Enter overwrites, Esc cancels", path.display()),
                            true,
                        ));
                    }
                    Err(e) => {
                        self.saving = None;
                        self.dialog = Some(e.to_string());
                    }
                }
            }
            _ => {}
        }
        Vec::new()
    }

    fn on_picker_key(&mut self, key: Key) -> Vec<Command> {
        let Some(picker) = self.picker.as_mut() else {
            return Vec::new();
        };
        let n = picker.entries.len().max(1);
        match key {
            Key::Up | Key::Char('k') => picker.selected = (picker.selected + n - 1) % n,
            Key::Down | Key::Char('j') => picker.selected = (picker.selected + 1) % n,
            Key::Esc | Key::Char('p' | 'q') => self.picker = None,
            Key::CtrlC => self.quit = true,
            Key::Enter => {
                let Some(entry) = picker.entries.get(picker.selected).cloned() else {
                    return Vec::new();
                };
                self.picker = None;
                let source = if entry.source == crate::scenario::shipped::Source::User {
                    entry.path
                } else {
                    entry.name
                };
                return match resolve(&source, &[]) {
                    Ok(preset) => self.load(&preset),
                    Err(e) => {
                        self.dialog =
                            Some(format!("{e}\n\nThe explorer keeps the current scenario."));
                        Vec::new()
                    }
                };
            }
            _ => {}
        }
        Vec::new()
    }

    /// The selected field.
    #[must_use]
    pub fn field(&self) -> Field {
        Field::ALL[self.selected]
    }

    fn restart(&mut self) -> Vec<Command> {
        self.generation += 1;
        self.derived = derive(&self.settings);
        self.target = 0.0;
        self.reached = 0.0;
        self.trail.clear();
        self.effective_trail.clear();
        self.reversals.clear();
        self.effective_reversals.clear();
        self.finished = false;
        self.failed = None;
        self.steps = 0;
        self.steps_at_tick = 0;
        self.method_in_use = None;
        vec![
            Command::Restart {
                generation: self.generation,
                spec: sim::spec(
                    self.settings.problem(),
                    self.settings.method,
                    self.settings.tolerance,
                    self.settings.t_end,
                    self.show_effective,
                ),
            },
            self.advance_command(),
        ]
    }

    fn sample_dt(&self) -> f64 {
        self.speed / (self.options.fps * SAMPLES_PER_FRAME)
    }

    fn advance_command(&self) -> Command {
        Command::AdvanceTo {
            generation: self.generation,
            t: self.target,
            sample_dt: self.sample_dt(),
        }
    }

    /// Handles a key: the dialog, the save prompt, the picker or text entry when open, else
    /// the keymap.
    pub fn on_key(&mut self, key: Key) -> Vec<Command> {
        if self.dialog.is_some() {
            return self.on_dialog_key(key);
        }
        if self.saving.is_some() {
            return self.on_save_key(key);
        }
        if self.picker.is_some() {
            return self.on_picker_key(key);
        }
        if let Some(buffer) = self.editing.as_mut() {
            match key {
                Key::Char(c) => buffer.push(c),
                Key::Backspace => {
                    buffer.pop();
                }
                Key::Esc => {
                    self.editing = None;
                    self.message = None;
                }
                Key::CtrlC => self.quit = true,
                Key::Enter => {
                    let text = self.editing.take().unwrap_or_default();
                    return self.apply(self.field().with_text(&self.settings, &text));
                }
                _ => {}
            }
            return Vec::new();
        }
        if self.show_help && matches!(key, Key::Esc) {
            self.show_help = false;
            return Vec::new();
        }
        keys::action_for(key).map_or_else(Vec::new, |a| self.update(a))
    }

    fn log(&mut self, event: Event) {
        if self.recording {
            self.journal.push((self.target, self.generation, event));
        }
    }

    fn apply(&mut self, result: Result<Settings, String>) -> Vec<Command> {
        match result {
            Ok(s) => {
                self.message = None;
                if s == self.settings {
                    return Vec::new();
                }
                let field = self.field();
                self.settings = s;
                let value = field.exact(&self.settings);
                self.log(Event::Set {
                    field: field.label().to_owned(),
                    value,
                });
                self.restart()
            }
            Err(reason) => {
                self.message = Some((reason, true));
                Vec::new()
            }
        }
    }

    /// Carries out an action; returns the commands for the worker. While recording, the
    /// actions that change what is shown are journaled.
    pub fn update(&mut self, action: Action) -> Vec<Command> {
        let commands = self.carry_out(action);
        let event = match action {
            Action::TogglePlay if self.playing => Some(Event::Play),
            Action::TogglePlay => Some(Event::Pause),
            Action::Step => Some(Event::Step),
            Action::Reset => Some(Event::Reset),
            Action::Faster | Action::Slower => Some(Event::Speed { value: self.speed }),
            Action::ZoomIn
            | Action::ZoomOut
            | Action::PanLeft
            | Action::PanRight
            | Action::PanUp
            | Action::PanDown
            | Action::ToggleWrap => Some(Event::View {
                zoom: self.view.zoom,
                pan_x: self.view.pan_x,
                pan_y: self.view.pan_y,
                wrap: self.view.wrap,
            }),
            Action::ToggleEffective | Action::ToggleSeries => Some(Event::Panes {
                effective: self.show_effective,
                series: self.show_series,
            }),
            Action::ClearTrail => Some(Event::ClearTrail),
            _ => None,
        };
        if let Some(e) = event {
            self.log(e);
        }
        commands
    }

    /// Replays one recorded event (used by `replay` and `replay --verify`).
    pub fn apply_event(&mut self, event: &Event) -> Vec<Command> {
        match event {
            Event::Set { field, value } => {
                let Some(f) = Field::named(field) else {
                    self.message =
                        Some((format!("unknown field '{field}' in the recording"), true));
                    return Vec::new();
                };
                self.selected = Field::ALL.iter().position(|x| *x == f).unwrap_or(0);
                self.apply(f.with_text(&self.settings, value))
            }
            Event::Play => {
                if self.playing {
                    Vec::new()
                } else {
                    self.carry_out(Action::TogglePlay)
                }
            }
            Event::Pause => {
                self.playing = false;
                Vec::new()
            }
            Event::Step => self.carry_out(Action::Step),
            Event::Reset => self.carry_out(Action::Reset),
            Event::Speed { value } => {
                self.speed = value.clamp(SPEED_RANGE.0, SPEED_RANGE.1);
                Vec::new()
            }
            Event::View {
                zoom,
                pan_x,
                pan_y,
                wrap,
            } => {
                self.view.zoom = *zoom;
                self.view.pan_x = *pan_x;
                self.view.pan_y = *pan_y;
                self.view.wrap = *wrap;
                Vec::new()
            }
            Event::Panes { effective, series } => {
                self.show_series = *series;
                if *effective == self.show_effective {
                    Vec::new()
                } else {
                    self.carry_out(Action::ToggleEffective)
                }
            }
            Event::ClearTrail => self.carry_out(Action::ClearTrail),
            Event::Preset { toml } => match Preset::parse(toml, "recorded preset", "recorded", &[])
            {
                Ok(p) => self.load(&p),
                Err(e) => {
                    self.dialog = Some(e.to_string());
                    Vec::new()
                }
            },
            Event::Note { text } => {
                self.message = Some((format!("note: {text}"), false));
                Vec::new()
            }
            Event::Chapter { title } => {
                self.message = Some((format!("chapter: {title}"), false));
                Vec::new()
            }
            Event::Checkpoint { .. } => Vec::new(),
        }
    }

    /// Asks the worker for the exact state at the current target (journaled on arrival).
    #[must_use]
    pub fn checkpoint(&self) -> Command {
        Command::Checkpoint {
            generation: self.generation,
            t: self.target,
        }
    }

    /// Opens the picker or a prompt.
    fn open_dialog(&mut self, action: Action) {
        match action {
            Action::OpenPicker => {
                let (entries, problems) = catalogue_in(self.user_dir.as_deref());
                let selected = entries
                    .iter()
                    .position(|e| e.title == self.name)
                    .unwrap_or(0);
                self.picker = Some(Picker {
                    entries,
                    selected,
                    problems: problems.iter().map(ToString::to_string).collect(),
                });
            }
            Action::Note | Action::Chapter => {
                if !self.recording {
                    self.message = Some((
                        "notes and chapters go into a recording: start one with R".to_owned(),
                        true,
                    ));
                    return;
                }
                let purpose = if action == Action::Note {
                    PromptFor::Note
                } else {
                    PromptFor::Chapter
                };
                self.saving = Some(SavePrompt {
                    purpose,
                    name: String::new(),
                    confirm: false,
                });
                self.message = Some(("type it, Enter marks, Esc cancels".to_owned(), false));
            }
            Action::Save => {
                self.saving = Some(SavePrompt {
                    purpose: PromptFor::Save,
                    name: String::new(),
                    confirm: false,
                });
                self.message = Some((
                    "name the preset (letters, digits, - and _), Enter saves, Esc cancels"
                        .to_owned(),
                    false,
                ));
            }
            _ => {}
        }
    }

    fn carry_out(&mut self, action: Action) -> Vec<Command> {
        let field = self.field();
        match action {
            Action::Quit => self.quit = true,
            Action::SelectPrev => {
                self.selected = (self.selected + Field::ALL.len() - 1) % Field::ALL.len();
                self.message = None;
            }
            Action::SelectNext => {
                self.selected = (self.selected + 1) % Field::ALL.len();
                self.message = None;
            }
            Action::Decrease => return self.apply(field.nudge(&self.settings, -1.0, false)),
            Action::Increase => return self.apply(field.nudge(&self.settings, 1.0, false)),
            Action::DecreaseCoarse => return self.apply(field.nudge(&self.settings, -1.0, true)),
            Action::IncreaseCoarse => return self.apply(field.nudge(&self.settings, 1.0, true)),
            Action::Edit => {
                self.editing = Some(String::new());
                self.message = Some((
                    format!("type {} and press Enter (Esc cancels)", field.label()),
                    false,
                ));
            }
            Action::TogglePlay => {
                if self.finished {
                    let mut c = self.restart();
                    self.playing = true;
                    c.push(self.advance_command());
                    return c;
                }
                self.playing = !self.playing;
            }
            Action::Step => {
                self.playing = false;
                self.target =
                    (self.target + self.speed / self.options.fps).min(self.settings.t_end);
                return vec![self.advance_command()];
            }
            Action::Reset => return self.restart(),
            Action::Faster => self.speed = (self.speed * 2.0).min(SPEED_RANGE.1),
            Action::Slower => self.speed = (self.speed / 2.0).max(SPEED_RANGE.0),
            Action::ToggleEffective => {
                self.show_effective = !self.show_effective;
                if !self.show_effective {
                    self.effective_trail.clear();
                    self.effective_reversals.clear();
                }
                return vec![Command::SetEffective(self.show_effective)];
            }
            Action::ToggleSeries => self.show_series = !self.show_series,
            Action::ZoomIn => self.view.zoom = (self.view.zoom * 1.5).min(1e6),
            Action::ZoomOut => self.view.zoom = (self.view.zoom / 1.5).max(0.1),
            Action::PanLeft => self.view.pan_x -= 0.1,
            Action::PanRight => self.view.pan_x += 0.1,
            Action::PanUp => self.view.pan_y += 0.1,
            Action::PanDown => self.view.pan_y -= 0.1,
            Action::ToggleWrap => self.view.wrap = !self.view.wrap,
            Action::ClearTrail => {
                self.trail.clear();
                self.effective_trail.clear();
            }
            Action::ToggleHelp => self.show_help = !self.show_help,
            Action::OpenPicker | Action::Note | Action::Chapter | Action::Save => {
                self.open_dialog(action);
            }
            Action::ToggleRecording => self.recording_requested = true,
            Action::CycleTheme => self.theme = self.theme.wrapping_add(1),
        }
        Vec::new()
    }

    /// Advances the simulated clock by `wall_seconds × speed` while playing.
    pub fn tick(&mut self, wall_seconds: f64) -> Vec<Command> {
        let done = self.steps.saturating_sub(self.steps_at_tick) as f64;
        self.steps_at_tick = self.steps;
        if wall_seconds > 0.0 {
            let now = done / wall_seconds;
            self.rate = if self.rate == 0.0 {
                now
            } else {
                0.8 * self.rate + 0.2 * now
            };
        }
        if !self.playing || self.finished || self.failed.is_some() {
            return Vec::new();
        }
        self.target = (self.target + wall_seconds * self.speed).min(self.settings.t_end);
        vec![self.advance_command()]
    }

    /// Takes an event from the worker (stale runs are ignored). Returns whether anything
    /// visible changed.
    pub fn on_sim(&mut self, event: SimEvent) -> bool {
        match event {
            SimEvent::Started { generation, method } if generation == self.generation => {
                self.method_in_use = Some(method);
                true
            }
            SimEvent::Samples {
                generation,
                full,
                effective,
                t,
                steps,
            } if generation == self.generation => {
                let changed = !full.is_empty() || !effective.is_empty();
                push_capped(&mut self.trail, full);
                push_capped(&mut self.effective_trail, effective);
                self.reached = self.reached.max(t);
                self.steps = steps;
                changed
            }
            SimEvent::Reversal {
                generation,
                t,
                effective,
            } if generation == self.generation => {
                if effective {
                    self.effective_reversals.push(t);
                } else {
                    self.reversals.push(t);
                }
                true
            }
            SimEvent::Checkpoint {
                generation,
                t,
                state,
                reversals,
            } if generation == self.generation => {
                if self.recording {
                    let hash = journal::state_hash(t, &state, reversals);
                    self.journal.push((
                        t,
                        generation,
                        Event::Checkpoint {
                            state,
                            reversals,
                            hash,
                        },
                    ));
                }
                false
            }
            SimEvent::Finished { generation } if generation == self.generation => {
                self.finished = true;
                self.playing = false;
                true
            }
            SimEvent::Failed {
                generation,
                message,
            } if generation == self.generation => {
                self.failed = Some(message.clone());
                self.message = Some((format!("integration failed: {message}"), true));
                self.playing = false;
                true
            }
            _ => false,
        }
    }

    /// The portrait's bounds now.
    #[must_use]
    pub fn bounds(&self) -> Bounds {
        let s = &self.settings;
        let auto = portrait::auto_bounds(
            &self.derived.effective,
            s.start.alpha,
            s.start.alpha_dot,
            &self.trail,
            self.view.wrap,
        );
        portrait::apply_view(auto, &self.view)
    }

    /// Recomputes the level sets if the settings, bounds or sampling changed since last time;
    /// read them with [`App::levels`].
    pub fn refresh_contours(&mut self, samples: usize) {
        let key = ContourKey {
            settings: self.settings,
            bounds: self.bounds(),
            levels: self.view.levels,
            samples,
        };
        if self.contour_cache.as_ref().is_none_or(|(k, _)| *k != key) {
            let eff = &self.derived.effective;
            let levels =
                portrait::levels(eff, &key.bounds, eff.energy(), self.view.levels, samples);
            self.contour_cache = Some((key, levels));
        }
    }

    /// The level sets of the last [`App::refresh_contours`] (none before the first).
    #[must_use]
    pub fn levels(&self) -> &[Level] {
        self.contour_cache
            .as_ref()
            .map_or(&[], |(_, l)| l.as_slice())
    }

    /// The latest sample of the full motion.
    #[must_use]
    pub fn current(&self) -> Option<&Point> {
        self.trail.last()
    }
}

fn push_capped(trail: &mut Vec<Point>, new: Vec<Point>) {
    trail.extend(new);
    if trail.len() > TRAIL_CAP {
        trail.drain(..trail.len() - TRAIL_CAP / 2);
    }
}

fn settings_of(preset: &Preset) -> Settings {
    Settings {
        params: *preset.problem.params(),
        start: *preset.problem.start(),
        t_end: preset.run.t_end,
        method: preset.run.method.unwrap_or(crate::physics::Method::Auto),
        tolerance: preset.run.tolerance.unwrap_or(1e-8),
    }
}

fn derive(s: &Settings) -> Derived {
    let problem = s.problem();
    let effective = Effective::new(&problem);
    Derived {
        ratio: effective.start_ratio(&problem),
        critical: effective.critical_ratio(&problem),
        effective,
    }
}
