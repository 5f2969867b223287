//! The panes the worker computes for (the sweep, the weak-* view, the regime map, the
//! comparison): each pane's state implements [`ComputedPane`] (start its job, stop it, take its
//! answers), and [`Computed::pane_mut`] is the one place that says which panes have one. Their
//! jobs start with the pane and the run and stop when the pane is hidden; their answers come
//! back as [`SimEvent::Job`](crate::sim::SimEvent::Job) and go to the pane whose job's kind
//! they carry. The map's cursor keys are here too.
//!
//! A new computed pane is its state in a file here (with its `ComputedPane`), its field and
//! its arm in `pane_mut`, and its job in `sim/jobs.rs`: nothing else in the app changes.

pub mod compare;
pub mod map;
pub mod sweep;
pub mod weak;

use super::fields::Settings;
use super::journal::Event;
use super::keys::{Action, Key};
use super::panes::Pane;
use super::{App, Effect, Message, Mode};
use crate::sim::{Command, JobData, JobKind};

/// What the panes the worker computes for show.
#[derive(Clone, Debug, Default)]
pub struct Computed {
    /// The sweep pane's data.
    pub sweep: sweep::SweepState,
    /// The weak-* pane's data.
    pub weak: weak::WeakState,
    /// The regime map's data and cursor.
    pub map: map::MapState,
    /// The comparison's partner and its run.
    pub compare: compare::CompareState,
}

/// What the status line says while the map has the arrows.
const MAP_HINT: &str = "map: arrows move, Enter loads the cell, Esc gives the arrows back";

impl Computed {
    /// The state of `pane` when the worker computes for it; none for a pane drawn from what
    /// the run already has. Exhaustive, so a new pane must say which it is.
    pub fn pane_mut(&mut self, pane: Pane) -> Option<&mut dyn ComputedPane> {
        match pane {
            Pane::Sweep => Some(&mut self.sweep),
            Pane::Weak => Some(&mut self.weak),
            Pane::Map => Some(&mut self.map),
            Pane::Compare => Some(&mut self.compare),
            Pane::Params | Pane::Portrait | Pane::Series | Pane::Lesson | Pane::Body => None,
        }
    }
}

/// What a computed pane sees of the app when it starts or takes an answer, and what it asks
/// of it in return (journal lines, a status message).
pub struct Cx<'a> {
    /// The current settings.
    pub settings: &'a Settings,
    /// The current run's stamp.
    pub generation: u64,
    /// Lines to journal, in order.
    pub log: Vec<Event>,
    /// A message for the status line.
    pub status: Option<Message>,
}

/// The state of a pane the worker computes for.
pub trait ComputedPane {
    /// Its job's kind: its answers come back under it.
    fn kind(&self) -> JobKind;
    /// Asks for its job on the current run (the pane was shown, or the run restarted), unless
    /// what it has still stands.
    fn start(&mut self, cx: &mut Cx) -> Option<Command>;
    /// Stops its job (the pane was hidden).
    fn stop(&mut self) -> Command;
    /// Takes an answer of its job stamped `stamp`; whether anything it shows changed (an
    /// answer to an older order changes nothing).
    fn take(&mut self, stamp: u64, data: JobData, cx: &mut Cx) -> bool;
}

impl App {
    /// Runs `f` on `pane`'s state with the app's context, then journals and says what it
    /// asked; none when the pane has no job.
    fn with_computed<R>(
        &mut self,
        pane: Pane,
        f: impl FnOnce(&mut dyn ComputedPane, &mut Cx) -> R,
    ) -> Option<R> {
        let state = self.computed.pane_mut(pane)?;
        let mut cx = Cx {
            settings: &self.scenario.settings,
            generation: self.run.generation,
            log: Vec::new(),
            status: None,
        };
        let out = f(state, &mut cx);
        let (log, status) = (cx.log, cx.status);
        for event in log {
            self.log(event);
        }
        if status.is_some() {
            self.status = status;
        }
        Some(out)
    }

    /// Starts `pane`'s job, when it has one.
    pub(in crate::app) fn start_job(&mut self, pane: Pane) -> Option<Command> {
        self.with_computed(pane, |state, cx| state.start(cx))
            .flatten()
    }

    /// Stops `pane`'s job, when it has one.
    pub(in crate::app) fn stop_job(&mut self, pane: Pane) -> Option<Command> {
        self.with_computed(pane, |state, _| state.stop())
    }

    /// Starts the jobs of the shown panes (the run restarted).
    pub(in crate::app) fn start_shown_jobs(&mut self) -> Vec<Effect> {
        let shown: Vec<Pane> = Pane::ALL
            .into_iter()
            .filter(|p| self.view.panes.shows(*p))
            .collect();
        shown
            .into_iter()
            .filter_map(|p| self.start_job(p))
            .map(Effect::Sim)
            .collect()
    }

    /// Takes a job's answer: it goes to the pane whose job is of its kind.
    pub(in crate::app) fn on_job(&mut self, stamp: u64, data: JobData) -> bool {
        let kind = data.kind();
        let Some(pane) = Pane::ALL.into_iter().find(|p| {
            self.computed
                .pane_mut(*p)
                .is_some_and(|state| state.kind() == kind)
        }) else {
            return false;
        };
        self.with_computed(pane, |state, cx| state.take(stamp, data, cx))
            .unwrap_or(false)
    }

    /// Shows or hides a pane (one the scene offers, when it shows it): a pane the worker
    /// computes for (sweep, weak-*, map, compare), shown, starts its job; hidden, stops it. The
    /// map, shown, takes the arrows.
    pub(in crate::app) fn toggle_pane(&mut self, pane: Pane) -> Vec<Effect> {
        if !self.view.panes.shows(pane) && !self.scene_has(pane) {
            return Vec::new();
        }
        self.view.panes.toggle(pane);
        let on = self.view.panes.shows(pane);
        if pane == Pane::Map {
            if on {
                self.mode = Mode::Map;
                self.status = Message::info(MAP_HINT);
            } else {
                self.mode = Mode::Normal;
                // Its hint said the arrows move the map's cursor: no longer true.
                if self.status == Message::info(MAP_HINT) {
                    self.status = Message::info("map hidden: arrows back on the parameters");
                }
            }
        }
        let command = if on {
            self.start_job(pane)
        } else {
            self.stop_job(pane)
        };
        command.map(Effect::Sim).into_iter().collect()
    }

    /// A key while the map has the arrows: they move the cursor, Enter loads the cell, `f`
    /// changes the source, Esc gives the arrows back; other keys go to an open lesson, then
    /// to the keymap.
    pub(in crate::app) fn on_map_key(&mut self, key: Key) -> Vec<Effect> {
        self.mode = Mode::Map;
        let step = |k| match k {
            Key::Left | Key::Char('h') => Some((-1, 0)),
            Key::Right | Key::Char('l') => Some((1, 0)),
            Key::Up | Key::Char('k') => Some((0, 1)),
            Key::Down | Key::Char('j') => Some((0, -1)),
            Key::ShiftLeft | Key::Char('H') => Some((-4, 0)),
            Key::ShiftRight | Key::Char('L') => Some((4, 0)),
            Key::ShiftUp | Key::Char('K') => Some((0, 4)),
            Key::ShiftDown | Key::Char('J') => Some((0, -4)),
            _ => None,
        };
        if let Some((di, dj)) = step(key) {
            self.computed.map.move_cursor(di, dj);
            return Vec::new();
        }
        match key {
            Key::Esc => {
                self.mode = Mode::Normal;
                self.status = Message::info("arrows back on the parameters (M hides the map)");
                Vec::new()
            }
            Key::Enter => match self.computed.map.load(&self.scenario.settings) {
                Ok(s) => {
                    let what = self.computed.map.cursor_words();
                    let mut scenario = self.scenario.clone();
                    scenario.set(s);
                    let name = self.scenario.name.clone();
                    let preset = scenario.to_preset(
                        &name,
                        &self.view.view,
                        self.view.overlay,
                        self.series(),
                    );
                    let effects = self.load(&preset);
                    self.mode = Mode::Map;
                    self.status = Message::info(format!("loaded the cell {what}"));
                    effects
                }
                Err(why) => {
                    self.status = Message::error(why.to_string());
                    Vec::new()
                }
            },
            Key::Char('f') if self.scenario.settings.rattleback().is_none() => {
                self.status = Message::info(
                    "f switches the rattleback's map between the limit and the full model; this chart has one source",
                );
                Vec::new()
            }
            Key::Char('f') => self
                .computed
                .map
                .toggle_source(&self.scenario.settings)
                .map(Effect::Sim)
                .into_iter()
                .collect(),
            key => {
                // A lesson's keys first, as in the normal mode: its answers, `n`, and the guard
                // on play (a step that opens the map gives the map the arrows, not the lesson).
                if let Some(effects) = self.on_lesson_key(key) {
                    self.prompt_from_map();
                    return effects;
                }
                let Some(action) = self.options.action_for(key) else {
                    return Vec::new();
                };
                let effects = self.update(action);
                self.prompt_from_map();
                // `M` hid the map; an action that opened its own mode (help, picker…) keeps it.
                if action == Action::Toggle(Pane::Map) && self.mode == Mode::Map {
                    self.mode = Mode::Normal;
                }
                effects
            }
        }
    }

    /// A prompt a key opened from the map (an answer, a note) gives the map its arrows back.
    fn prompt_from_map(&mut self) {
        if let Mode::Prompt(p) = &mut self.mode {
            p.from_map = true;
        }
    }

    /// Whether the scene offers `pane` (its scene's studies); says so in the status line when
    /// not.
    pub(in crate::app) fn scene_has(&mut self, pane: Pane) -> bool {
        let kind = self.scenario.settings.model.kind();
        if !pane.offered_by(kind) {
            let owners: Vec<&str> = crate::physics::ModelKind::ALL
                .into_iter()
                .filter(|m| pane.offered_by(*m))
                .map(crate::physics::ModelKind::name)
                .collect();
            self.status = Message::error(format!(
                "the {} pane is of the {}; this scene is {}",
                pane.name(),
                owners.join(" and the "),
                kind.title()
            ));
            return false;
        }
        true
    }

    /// Closes the panes a newly loaded scene does not offer (their computations stop).
    pub(in crate::app) fn close_foreign_panes(&mut self) -> Vec<Effect> {
        let kind = self.scenario.settings.model.kind();
        let mut effects = Vec::new();
        for pane in Pane::ALL {
            if self.view.panes.shows(pane) && !pane.offered_by(kind) {
                // Shown, so this hides it (and stops its job).
                effects.extend(self.toggle_pane(pane));
            }
        }
        if self.mode == Mode::Map && !Pane::Map.offered_by(kind) {
            self.mode = Mode::Normal;
        }
        effects
    }
}
