//! The panes the worker computes for (the stiffness sweep, the weak-* view, the regime map):
//! starting and stopping their computations with the pane and the run; the map's cursor keys.

use super::keys::{Action, Key};
use super::panes::Pane;
use super::{App, Effect, Message, Mode};

impl App {
    /// Shows or hides a pane (one the scene offers, when it shows it): a pane the worker
    /// computes for (sweep, weak-*, map, compare), shown, starts its job; hidden, stops it. The
    /// map, shown, takes the arrows.
    pub(super) fn toggle_pane(&mut self, pane: Pane) -> Vec<Effect> {
        if !self.view.panes.shows(pane) && !self.scene_has(pane) {
            return Vec::new();
        }
        self.view.panes.toggle(pane);
        let on = self.view.panes.shows(pane);
        let command = match (pane, on) {
            (Pane::Sweep, true) => Some(self.start_sweep()),
            (Pane::Sweep, false) => Some(self.sweep.stop()),
            (Pane::Map, true) => {
                self.mode = Mode::Map;
                self.status = Message::info("map: arrows move, Enter loads the cell, Esc");
                self.map.start(&self.scenario.settings)
            }
            (Pane::Map, false) => Some(self.map.stop()),
            (Pane::Weak, true) => Some(self.start_weak()),
            (Pane::Weak, false) => Some(self.weak.stop()),
            (Pane::Compare, true) => self.start_compare(),
            (Pane::Compare, false) => Some(self.stop_compare()),
            // Drawn from what the run already has: no job to start or stop. Listed, so that
            // a new computed pane cannot fall silently into another pane's job.
            (Pane::Params | Pane::Portrait | Pane::Series | Pane::Lesson | Pane::Body, _) => None,
        };
        command.map(Effect::Sim).into_iter().collect()
    }

    /// A key while the map has the arrows: they move the cursor, Enter loads the cell, `f`
    /// changes the source, Esc gives the arrows back; other keys go to the keymap.
    pub(super) fn on_map_key(&mut self, key: Key) -> Vec<Effect> {
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
            self.map.move_cursor(di, dj);
            return Vec::new();
        }
        match key {
            Key::Esc => {
                self.mode = Mode::Normal;
                self.status = Message::info("arrows back on the parameters (M hides the map)");
                Vec::new()
            }
            Key::Enter => match self.map.load(&self.scenario.settings) {
                Ok(s) => {
                    let (ratio, inertia) = self.map.at_cursor().unwrap_or_default();
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
                    self.status = Message::info(format!(
                        "loaded the cell alpha_dot0^2/gamma_dot0^2 {ratio:.3}, iy/ix {inertia:.3}"
                    ));
                    effects
                }
                Err(why) => {
                    self.status = Message::error(why);
                    Vec::new()
                }
            },
            Key::Char('f') => self
                .map
                .toggle_source(&self.scenario.settings)
                .map(Effect::Sim)
                .into_iter()
                .collect(),
            key => {
                let Some(action) = self.options.action_for(key) else {
                    return Vec::new();
                };
                let effects = self.update(action);
                // `M` hid the map; an action that opened its own mode (help, picker…) keeps it.
                if action == Action::Toggle(Pane::Map) && self.mode == Mode::Map {
                    self.mode = Mode::Normal;
                }
                effects
            }
        }
    }

    /// Turns the limit's overlay on or off; a scene without a limit (the celt) says so instead.
    pub(super) fn toggle_overlay(&mut self) -> Vec<Effect> {
        let kind = self.scenario.settings.model.kind();
        if kind.small().is_none() {
            self.status = Message::error(format!("the {} has no limit to draw", kind.title()));
            return Vec::new();
        }
        self.view.overlay = !self.view.overlay;
        vec![Effect::Sim(self.run.set_overlay(self.view.overlay))]
    }

    /// Whether the scene offers `pane` (its scene's studies); says so in the status line when
    /// not.
    pub(super) fn scene_has(&mut self, pane: Pane) -> bool {
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
    pub(super) fn close_foreign_panes(&mut self) -> Vec<Effect> {
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

    /// Asks the worker for the weak-* view of the current settings.
    pub(super) fn start_weak(&mut self) -> crate::sim::Command {
        let s = &self.scenario.settings;
        let spec = crate::sim::WeakSpec {
            model: s.model,
            t_end: s.t_end,
        };
        self.weak.start(self.run.generation, spec)
    }
    /// Asks the worker for the sweep of the current settings (`k`, or the pendulum's `ε`).
    pub(super) fn start_sweep(&mut self) -> crate::sim::Command {
        let s = &self.scenario.settings;
        let spec = crate::sim::SweepSpec {
            model: s.model,
            t_end: s.t_end,
            tolerance: s.tolerance,
        };
        self.sweep.start(self.run.generation, spec)
    }
}

impl App {
    /// Sets the start's slow coordinate and rate (a click in the portrait: the rattleback's
    /// `(alpha, alpha_dot)`, keeping `gamma` and `gamma_dot`; the pendulum's `(theta,
    /// theta_dot)`), and restarts; journaled as two `set` events.
    pub fn set_start_point(&mut self, alpha: f64, alpha_dot: f64) -> Vec<Effect> {
        use super::fields::Field;
        use super::journal::Event;
        let s = self.scenario.settings;
        let (kind, words) = (s.model.kind(), s.model.kind().words());
        let named = |name| {
            Field::named(kind, name).ok_or_else(|| format!("the {} has no `{name}`", kind.title()))
        };
        let set = named(words.q_name).and_then(|q| {
            let q_dot = named(words.q_dot_name)?;
            let s = q.with_value(&s, alpha)?;
            Ok(([q, q_dot], q_dot.with_value(&s, alpha_dot)?))
        });
        let (fields, s) = match set {
            Ok(set) => set,
            Err(e) => {
                self.status = Message::error(format!("{e}; start kept"));
                return Vec::new();
            }
        };
        self.scenario.set(s);
        for f in fields {
            let value = f.exact(&self.scenario.settings);
            self.log(Event::Set {
                field: f.label().to_owned(),
                value,
            });
        }
        self.status = Message::info(format!(
            "start {} {}, {} {}",
            words.q_name,
            super::fields::format_number(alpha),
            words.q_dot_name,
            super::fields::format_number(alpha_dot)
        ));
        self.restart()
    }
}
