//! What is simulated: the preset's name and description, the editable settings and what is
//! derived from them (the limit, the critical ratio, the sample grid).

use super::fields::Settings;
use super::portrait::{self, View};
use super::{App, Effect, Message};
use crate::physics::Method;
use crate::physics::scene::SummaryLine;
use crate::physics::{DEFAULT_TOLERANCE, LimitView};
use crate::scenario::Preset;
use crate::scenario::preset::{RunConfig, ViewConfig};
use crate::scenario::text::clean;
use crate::sim::SessionSpec;

/// Derived values shown read-only under the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Derived {
    /// The limit of the start, as the portrait draws it.
    pub limit: LimitView,
    /// What the model derives from its parameters, as the panel shows it (the rattleback's
    /// ratio against the critical one, the pendulum's threshold…).
    pub summary: Vec<SummaryLine>,
    /// Spacing of the sample grid, from the limit's dynamics (never from the playback speed).
    pub sample_dt: f64,
}

impl Derived {
    fn of(s: &Settings) -> Self {
        let limit = s.model.limit_view();
        Self {
            summary: s.model.summary(),
            sample_dt: portrait::sample_spacing(&limit),
            limit,
        }
    }
}

/// The scenario being explored.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Preset name (control characters stripped).
    pub name: String,
    /// What the preset says to look for.
    pub description: String,
    /// Editable parameters.
    pub settings: Settings,
    /// Derived from the settings.
    pub derived: Derived,
    /// Selected row of the panel.
    pub selected: usize,
    /// How the preset is named on a command line, when it was loaded by name or path (`y`
    /// copies it).
    pub origin: Option<String>,
}

impl Scenario {
    /// The scenario of `preset`.
    #[must_use]
    pub fn of(preset: &Preset) -> Self {
        let settings = Settings {
            model: preset.model,
            t_end: preset.run.t_end,
            method: preset.run.method.unwrap_or(Method::Auto),
            tolerance: preset.run.tolerance.unwrap_or(DEFAULT_TOLERANCE),
            step: preset.run.step,
        };
        Self {
            name: clean(&preset.name),
            description: clean(&preset.description),
            derived: Derived::of(&settings),
            settings,
            selected: 0,
            origin: preset.origin.as_ref().map(|o| clean(o)),
        }
    }

    /// The `simulate` command that reproduces what is shown: the loaded preset by the name (or
    /// path) it was loaded by, else the scene's base preset, then every parameter and run
    /// setting as shown.
    #[must_use]
    pub fn simulate_command(&self) -> String {
        self.settings.simulate_command(self.origin.as_deref())
    }

    /// Replaces the settings (already validated).
    pub fn set(&mut self, settings: Settings) {
        self.settings = settings;
        self.derived = Derived::of(&settings);
    }

    /// The worker's spec of a run of these settings.
    #[must_use]
    pub fn spec(&self, overlay: bool) -> SessionSpec {
        let s = &self.settings;
        SessionSpec {
            model: s.model,
            method: s.method,
            tolerance: s.tolerance,
            t_end: s.t_end,
            effective: overlay,
            sample_dt: crate::sim::grid_spacing(self.derived.sample_dt, s.t_end),
            step: s.step,
        }
    }

    /// These settings as a preset named `name`.
    #[must_use]
    pub fn to_preset(&self, name: &str, view: &View, overlay: bool, series: bool) -> Preset {
        Preset {
            name: name.to_owned(),
            description: self.description.clone(),
            model: self.settings.model,
            run: RunConfig {
                t_end: self.settings.t_end,
                method: Some(self.settings.method),
                tolerance: Some(self.settings.tolerance),
                step: self.settings.step,
            },
            origin: self.origin.clone(),
            view: ViewConfig {
                slow_range: view.slow_range,
                rate_range: view.rate_range,
                contours: Some(view.levels),
                effective_overlay: Some(overlay),
                series: Some(series),
                wrap: Some(view.wrap),
            },
        }
    }
}

impl App {
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

    /// Sets the start's slow coordinate and rate (a click in the portrait: the rattleback's
    /// `(alpha, alpha_dot)`, keeping `gamma` and `gamma_dot`; the pendulum's `(theta,
    /// theta_dot)`), and restarts; journaled as two `set` events.
    pub fn set_start_point(&mut self, alpha: f64, alpha_dot: f64) -> Vec<Effect> {
        use super::fields::Field;
        use super::journal::Event;
        let s = self.scenario.settings;
        let (kind, words) = (s.model.kind(), s.model.kind().words());
        let named = |name| {
            Field::named(kind, name).ok_or_else(|| super::fields::EditError::NotHere {
                label: name.to_owned(),
                model: kind.name(),
            })
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
