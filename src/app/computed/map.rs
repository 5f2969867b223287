//! The map pane's state (issues 12 and 59): the scene's chart (`study::chart`), computed by the
//! worker row by row or a few cells at a time, a cursor over the cells, and Enter loading the
//! cell under it as the current settings.
//!
//! - the rattleback: the reversals in `(0, T]` over `(α̇0²/γ̇0², iy/ix)` for the current body
//!   (`ix`, `iz`), `γ̇0` and horizon, with the paper's critical curve, from the limit by
//!   quadrature or (`f`) the full model at the current `k`; a cell loads as `iy = ix · iy/ix`,
//!   `γ0 = α0 = 0`, `α̇0 = √ratio · γ̇0`;
//! - the pendulum: the upright's stability over `(a, b)` at the current `ε` (Floquet), with
//!   Kapitza's `b² = 2a`; a cell loads its `a` and `b`;
//! - the celt: the reversals in `[0, T]` over the initial `ω_z` (both senses) and the product of
//!   inertia, with the linear theory's curve; a cell loads its `ω_z` and `D`.

use super::{ComputedPane, Cx};
use crate::app::fields::EditError;
use crate::app::fields::Settings;
use crate::sim::jobs::MapSpec;
use crate::sim::{Command, JobData, JobKind, JobSpec};
use crate::study::chart::{Chart, Mark, Verdict};

pub use crate::study::chart::pane::{
    CELT_GRID, FULL_GRID, FULL_TOLERANCE, LIMIT_GRID, PANE_INERTIA, PENDULUM_GRID,
};

/// Where the map's counts come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MapSource {
    /// The limit `k → ∞` (the theorem's statement).
    #[default]
    Limit,
    /// The full model at the current `k`.
    Full,
}

/// What the pane shows.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MapState {
    /// Stamp of the computation the cells belong to.
    pub id: u64,
    /// What is (being) computed.
    pub spec: Option<MapSpec>,
    /// Which source the user chose.
    pub source: MapSource,
    /// The verdict of each cell, row by row from the bottom (`None`: not computed yet).
    pub cells: Vec<Option<Verdict>>,
    /// The theory's curve of the chart computed, in its axes' values.
    pub curve: Vec<(f64, f64)>,
    /// The cursor `(column, row)`.
    pub cursor: (usize, usize),
    /// All cells are in.
    pub done: bool,
    /// After a loaded cell of the pendulum or the celt: the point the axes were drawn from and
    /// the point loaded (the axes stay while the settings sit on the loaded point).
    pub anchor: Option<((f64, f64), (f64, f64))>,
    /// Why the computation stopped short.
    pub failed: Option<String>,
    /// In a replay: whether the lecturer's map had the arrows (a replay's keys are its own, so
    /// its map never takes them; its title shows the lecturer's keys from this).
    pub replayed_focus: bool,
}

impl MapState {
    /// The spec of the map for `settings` (the rattleback's from the chosen source).
    #[must_use]
    pub fn spec_for(&self, settings: &Settings) -> Option<MapSpec> {
        let here = crate::study::chart::point_of(&settings.model);
        let chart = Chart::for_pane(
            &settings.model,
            crate::study::chart::PaneAsk {
                t_end: settings.t_end,
                tolerance: settings.tolerance,
                full: self.source == MapSource::Full,
                axes_from: self.axes_point(here),
            },
        );
        Some(MapSpec { chart })
    }

    /// Asks the worker for the map of `settings`: nothing when the map of the same spec is
    /// complete, the missing cells when it is partial, everything otherwise.
    pub fn start(&mut self, settings: &Settings) -> Option<Command> {
        let spec = self.spec_for(settings)?;
        if self.spec == Some(spec) && self.done && self.failed.is_none() {
            return None;
        }
        if self.spec != Some(spec) {
            let chart = spec.chart;
            let (x, y) = chart.axes();
            self.cells = vec![None; chart.len()];
            self.curve = chart.curve();
            // The rattleback's map keeps its cell when `k` or the start changes (its axes are
            // the plane of starts and bodies); the pendulum's and the celt's charts are drawn
            // around the problem, so their cursor goes to its cell: the cell of the problem on
            // screen (a lesson's next step, a typed value, a loaded cell).
            let keep = chart.words().sources
                && self
                    .spec
                    .is_some_and(|old| old.chart.model() == chart.model());
            self.cursor = if keep {
                (
                    self.cursor.0.min(x.cells - 1),
                    self.cursor.1.min(y.cells - 1),
                )
            } else {
                nearest(&chart, chart.preset_point())
            };
        }
        self.spec = Some(spec);
        self.id += 1;
        self.done = false;
        self.failed = None;
        // The cells computed so far: the refinement goes on from them and infers again.
        let known = self
            .cells
            .iter()
            .map(|c| c.clone().filter(|v| v.mark() == Mark::Computed))
            .collect();
        Some(Command::start_job(
            self.id,
            JobSpec::Map {
                spec: Box::new(spec),
                known,
            },
        ))
    }

    /// Stops the worker's computation (the cells so far are kept).
    pub fn stop(&mut self) -> Command {
        self.id += 1;
        Command::stop_job(JobKind::Map, self.id)
    }

    /// Switches between the limit and the full model; the new map starts from scratch.
    pub fn toggle_source(&mut self, settings: &Settings) -> Option<Command> {
        self.source = match self.source {
            MapSource::Limit => MapSource::Full,
            MapSource::Full => MapSource::Limit,
        };
        // The grids differ: keep the cursor on the same point of the plane.
        if let (Some(point), Some(new)) = (self.at_cursor(), self.spec_for(settings)) {
            self.cursor = nearest(&new.chart, point);
        }
        self.start(settings)
    }

    /// Takes cells of computation `id` (each cell's index and verdict, computed or
    /// inferred); whether they were this map's.
    pub fn on_cells(&mut self, id: u64, cells: Vec<(usize, Verdict)>) -> bool {
        if id != self.id {
            return false;
        }
        for (n, v) in cells {
            if let Some(c) = self.cells.get_mut(n) {
                *c = Some(v);
            }
        }
        true
    }

    /// The worker finished (or gave up on) computation `id`.
    pub fn on_done(&mut self, id: u64, failed: Option<String>) -> bool {
        if id != self.id {
            return false;
        }
        self.done = failed.is_none();
        self.failed = failed;
        true
    }

    /// Cells settled so far (computed or inferred).
    #[must_use]
    pub fn computed(&self) -> usize {
        self.cells.iter().filter(|c| c.is_some()).count()
    }

    /// What the cost model prices the cells still to compute at (s): the cells the
    /// refinement is expected to compute, less those computed.
    #[must_use]
    pub fn seconds_left(&self) -> Option<f64> {
        let chart = self.spec?.chart;
        let computed = self
            .cells
            .iter()
            .flatten()
            .filter(|v| v.mark() == Mark::Computed)
            .count();
        Some(chart.price_left(computed))
    }

    /// The verdict of cell `(i, j)`, if computed.
    #[must_use]
    pub fn cell(&self, i: usize, j: usize) -> Option<&Verdict> {
        let cols = self.spec?.chart.axes().0.cells;
        self.cells.get(j * cols + i)?.as_ref()
    }

    /// The point the axes are drawn from: the anchor's while the settings sit on the cell
    /// loaded last, `here` otherwise.
    fn axes_point(&self, here: (f64, f64)) -> (f64, f64) {
        match self.anchor {
            Some((from, loaded)) if loaded == here => from,
            _ => here,
        }
    }

    /// Moves the cursor by `(di, dj)` cells, stopping at the edges (`dj > 0` is up: larger
    /// `iy/ix`).
    pub fn move_cursor(&mut self, di: isize, dj: isize) {
        let Some(spec) = self.spec else { return };
        let (x, y) = spec.chart.axes();
        let clamp = |v: usize, d: isize, n: usize| v.saturating_add_signed(d).min(n - 1);
        self.cursor = (
            clamp(self.cursor.0, di, x.cells),
            clamp(self.cursor.1, dj, y.cells),
        );
    }

    /// A recorded cursor and focus (a replay's): the cursor kept inside the chart.
    pub fn replay_cursor(&mut self, (column, row): (usize, usize), focused: bool) {
        self.replayed_focus = focused;
        self.cursor = match self.spec {
            Some(spec) => {
                let (x, y) = spec.chart.axes();
                (column.min(x.cells - 1), row.min(y.cells - 1))
            }
            None => (column, row),
        };
    }

    /// The axes' values at the cursor (the rattleback's `(ratio, iy/ix)`, the pendulum's
    /// `(a, b)`, the celt's `(ω_z, D)`).
    #[must_use]
    pub fn at_cursor(&self) -> Option<(f64, f64)> {
        let (x, y) = self.spec?.chart.axes();
        Some((x.at(self.cursor.0), y.at(self.cursor.1)))
    }

    /// The cursor's cell in words, by its axes (the status line's "loaded the cell …").
    #[must_use]
    pub fn cursor_words(&self) -> String {
        let (Some(spec), Some((x, y))) = (self.spec, self.at_cursor()) else {
            return String::new();
        };
        let (nx, ny) = spec.chart.words().axes;
        format!("{nx} {x:.4}, {ny} {y:.4}")
    }

    /// The settings of the cell under the cursor (`Chart::load`). The axes of the pendulum's
    /// and the celt's charts stay where they are (the anchor).
    ///
    /// # Errors
    /// When there is no map yet or the cell is not a valid problem.
    pub fn load(&mut self, settings: &Settings) -> Result<Settings, EditError> {
        let spec = self.spec.ok_or(EditError::NoMap)?;
        let point = self.at_cursor().ok_or(EditError::NoMap)?;
        let model = spec.chart.load(&settings.model, point)?;
        if !spec.chart.words().sources {
            let from = self.axes_point(crate::study::chart::point_of(&settings.model));
            self.anchor = Some((from, point));
        }
        Ok(Settings { model, ..*settings })
    }
}

/// The cell of `chart` nearest to a point of its axes.
#[must_use]
pub fn nearest(chart: &Chart, (px, py): (f64, f64)) -> (usize, usize) {
    let (x, y) = chart.axes();
    let clamp = |f: f64, n: usize| {
        if f.is_finite() {
            let v = (f * n as f64).floor();
            (v.max(0.0) as usize).min(n - 1)
        } else {
            0
        }
    };
    (
        clamp(x.fraction(px), x.cells),
        clamp(y.fraction(py), y.cells),
    )
}

impl ComputedPane for MapState {
    fn kind(&self) -> JobKind {
        JobKind::Map
    }

    fn start(&mut self, cx: &mut Cx) -> Option<Command> {
        MapState::start(self, cx.settings)
    }

    fn stop(&mut self) -> Command {
        MapState::stop(self)
    }

    /// Cells, or the end of the map (or why it stopped short).
    fn take(&mut self, stamp: u64, data: JobData, _: &mut Cx) -> bool {
        match data {
            JobData::MapCells { cells } => self.on_cells(stamp, cells),
            JobData::MapDone { failed } => self.on_done(stamp, failed),
            _ => false,
        }
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are copied, not computed
mod tests {
    use super::*;
    use crate::physics::method::Method;
    use crate::physics::rattleback::{Params, Problem, Start};
    fn settings() -> Settings {
        let params = Params {
            ix: 1.0,
            iy: 0.5,
            iz: 2.0,
            k: 1e4,
        };
        let start = Start {
            gamma: 0.1,
            alpha: 0.2,
            gamma_dot: 0.5,
            alpha_dot: 0.3,
        };
        Settings {
            model: Problem::new(params, start).unwrap().into(),
            t_end: 30.0,
            method: Method::Auto,
            tolerance: 1e-8,
            step: None,
        }
    }

    #[test]
    fn a_complete_map_of_the_same_spec_is_not_asked_again_and_a_partial_one_resumes() {
        let s = settings();
        let mut m = MapState::default();
        let Some(Command::Job {
            spec: Some(JobSpec::Map { known, .. }),
            ..
        }) = m.start(&s)
        else {
            panic!("a first map starts")
        };
        assert!(known.iter().all(Option::is_none), "from nothing");
        let id = m.id;
        let one = Verdict::counted(1);
        let first: Vec<_> = (0..48).map(|n| (n, one.clone())).collect();
        let inferred = (48, Verdict::Inferred(crate::study::chart::Answer::Count(1)));
        assert!(m.on_cells(id, [first, vec![inferred]].concat()));
        assert!(
            !m.on_cells(id - 1, (49..96).map(|n| (n, one.clone())).collect()),
            "stale cells are ignored"
        );
        let Some(Command::Job {
            spec: Some(JobSpec::Map { known, .. }),
            ..
        }) = m.start(&s)
        else {
            panic!("a partial map resumes")
        };
        assert_eq!(
            known.iter().flatten().count(),
            48,
            "from the cells it computed (an inferred one is inferred again)"
        );
        assert!(m.on_done(m.id, None));
        assert_eq!(m.start(&s), None);
        let t = crate::app::fields::Field::named(s.model.kind(), "iz")
            .unwrap()
            .with_value(&s, 3.0)
            .unwrap();
        let Some(Command::Job {
            spec: Some(JobSpec::Map { known, .. }),
            ..
        }) = m.start(&t)
        else {
            panic!("a new body starts a new map")
        };
        assert!(known.iter().all(Option::is_none));
        assert_eq!(m.computed(), 0, "a new body forgets the old counts");
    }

    #[test]
    fn loading_the_cursor_cell_sets_the_body_and_the_start() {
        let s = settings();
        let mut m = MapState::default();
        m.start(&s);
        m.cursor = (11, 3);
        let (x, y) = m.spec.unwrap().chart.axes();
        let ix = s.model.rattleback().unwrap().params().ix;
        let loaded = m.load(&s).unwrap();
        let (lp, ls) = (
            loaded.rattleback().unwrap().params(),
            loaded.rattleback().unwrap().start(),
        );
        assert_eq!(lp.iy, ix * y.at(3));
        assert_eq!(ls.gamma, 0.0);
        assert_eq!(ls.alpha, 0.0);
        assert_eq!(ls.gamma_dot, 0.5);
        let ratio = (ls.alpha_dot / ls.gamma_dot).powi(2);
        assert!((ratio - x.at(11)).abs() < 1e-12);
        assert_eq!(lp.k, 1e4, "k, t_end and the method stay");
    }

    #[test]
    fn the_cursor_stays_on_the_grid_and_on_its_point_when_the_source_changes() {
        let s = settings();
        let mut m = MapState::default();
        m.start(&s);
        let (x, y) = m.spec.unwrap().chart.axes();
        let (ratio, inertia) = m.at_cursor().unwrap();
        assert!(
            (ratio - 0.36).abs() <= x.max / x.cells as f64,
            "on the start: {ratio}"
        );
        assert!((inertia.ln() - 0.5f64.ln()).abs() <= 2.5f64.ln() / y.cells as f64);
        m.move_cursor(-100, -100);
        assert_eq!(m.cursor, (0, 0));
        m.move_cursor(100, 100);
        assert_eq!(m.cursor, (LIMIT_GRID.0 - 1, LIMIT_GRID.1 - 1));
        m.cursor = (24, 12);
        let (r, i) = m.at_cursor().unwrap();
        m.toggle_source(&s);
        assert_eq!(m.source, MapSource::Full);
        let (r2, i2) = m.at_cursor().unwrap();
        assert!((r2 - r).abs() <= 2.0 / 24.0 && (i2.ln() - i.ln()).abs() <= 100f64.ln() / 12.0);
    }
}
