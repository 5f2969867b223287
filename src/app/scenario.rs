//! What is simulated: the preset's name and description, the editable settings and what is
//! derived from them (the limit, the critical ratio, the sample grid).

use super::fields::Settings;
use super::portrait::{self, View};
use crate::physics::DEFAULT_TOLERANCE;
use crate::physics::effective::Effective;
use crate::physics::integrators::Method;
use crate::scenario::Preset;
use crate::scenario::preset::{RunConfig, ViewConfig};
use crate::scenario::text::clean;
use crate::sim::SessionSpec;

/// Derived values shown read-only under the parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Derived {
    /// The effective model of the start.
    pub effective: Effective,
    /// `alpha_dot² / gamma_dot²`.
    pub ratio: Option<f64>,
    /// The critical ratio.
    pub critical: Option<f64>,
    /// Spacing of the sample grid, from the limit's dynamics (never from the playback speed).
    pub sample_dt: f64,
}

impl Derived {
    fn of(s: &Settings) -> Self {
        let problem = s.problem();
        let effective = Effective::new(&problem);
        Self {
            ratio: effective.start_ratio(&problem),
            critical: effective.critical_ratio(&problem),
            sample_dt: portrait::sample_spacing(&effective, s.start.alpha_dot),
            effective,
        }
    }

    /// The start's side of the reversal threshold, as `(ratio − critical) / critical`:
    /// negative below (reversals), positive above.
    #[must_use]
    pub fn threshold_distance(&self) -> Option<f64> {
        match (self.ratio, self.critical) {
            (Some(r), Some(c)) if c != 0.0 => Some((r - c) / c),
            _ => None,
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
}

impl Scenario {
    /// The scenario of `preset`.
    #[must_use]
    pub fn of(preset: &Preset) -> Self {
        let settings = Settings {
            params: *preset.problem.params(),
            start: *preset.problem.start(),
            t_end: preset.run.t_end,
            method: preset.run.method.unwrap_or(Method::Auto),
            tolerance: preset.run.tolerance.unwrap_or(DEFAULT_TOLERANCE),
        };
        Self {
            name: clean(&preset.name),
            description: clean(&preset.description),
            derived: Derived::of(&settings),
            settings,
            selected: 0,
        }
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
            problem: s.problem(),
            method: s.method,
            tolerance: s.tolerance,
            t_end: s.t_end,
            effective: overlay,
            sample_dt: self.derived.sample_dt,
        }
    }

    /// These settings as a preset named `name`.
    #[must_use]
    pub fn to_preset(&self, name: &str, view: &View, overlay: bool, series: bool) -> Preset {
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
                alpha_range: view.alpha_range,
                alpha_dot_range: view.alpha_dot_range,
                contours: Some(view.levels),
                effective_overlay: Some(overlay),
                series: Some(series),
                wrap: Some(view.wrap),
            },
        }
    }
}
