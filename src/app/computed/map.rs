//! The regime-map pane's state (issue 12): the number of spin reversals in `(0, T]` over a grid
//! of `(α̇0²/γ̇0², iy/ix)` for the current body (`ix`, `iz`), `γ̇0` and horizon, with the paper's
//! critical curve; computed by the worker row by row (from the limit by quadrature, or from the
//! full model at the current `k` on request), a cursor over the cells, and Enter loading the
//! cell under it as the current start (`iy = ix · iy/ix`, `γ0 = α0 = 0`, `α̇0 = √ratio · γ̇0`).

use super::{ComputedPane, Cx};
use crate::app::fields::Settings;
use crate::physics::rattleback::{Params, Problem, Start};
use crate::sim::jobs::MapSpec;
use crate::sim::{Command, JobData, JobKind, JobSpec};
use crate::study::map::{Grid, Source};

/// Columns × rows of the map from the limit (two quadratures a cell: instant).
pub const LIMIT_GRID: (usize, usize) = (48, 24);
/// Columns × rows of the map from the full model (a verified `auto` run a cell).
pub const FULL_GRID: (usize, usize) = (24, 12);
/// The pane's inertia-ratio axis: the critical curve lives below `iy/ix = 1`; the strip above
/// it shows that nothing reverses there.
pub const PANE_INERTIA: (f64, f64) = (0.1, 1.25);

/// Loosest tolerance of the full map's runs: a count of reversals needs their times to a
/// fraction of a half period, not the run's own tolerance.
pub const FULL_TOLERANCE: f64 = 1e-6;

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
    /// Reversals of each cell, row by row from the smallest `iy/ix` (`None`: not computed yet).
    pub cells: Vec<Option<usize>>,
    /// The cursor `(column, row)`.
    pub cursor: (usize, usize),
    /// All cells are in.
    pub done: bool,
    /// Why the computation stopped short.
    pub failed: Option<String>,
}

impl MapState {
    /// The spec of the map for `settings` from the chosen source.
    /// `None` when the settings are not the rattleback's (the map is of the rattleback).
    #[must_use]
    pub fn spec_for(&self, settings: &Settings) -> Option<MapSpec> {
        let (cols, rows) = match self.source {
            MapSource::Limit => LIMIT_GRID,
            MapSource::Full => FULL_GRID,
        };
        let problem = settings.rattleback()?;
        let (p, s) = (problem.params(), problem.start());
        let gamma_dot = if s.gamma_dot == 0.0 { 1.0 } else { s.gamma_dot };
        // The ratio axis spans `(0, ix/iz]`: the critical curve crosses the plot from
        // `iy/ix = 1/4` (where it equals `ix/iz`) to `iy/ix = 1` (where it is 0). It depends on
        // `ix` and `iz` only, so loading a cell (which sets `iy`) keeps the axes.
        let grid = Grid {
            ratio_max: p.ix / p.iz,
            inertia: PANE_INERTIA,
            ..Grid::new(cols, rows, p.ix, p.iz, gamma_dot, settings.t_end)
        };
        let source = match self.source {
            MapSource::Limit => Source::Limit,
            MapSource::Full => Source::Full {
                k: p.k,
                tolerance: settings.tolerance.max(FULL_TOLERANCE),
            },
        };
        Some(MapSpec { grid, source })
    }

    /// Asks the worker for the map of `settings`: nothing when the map of the same spec is
    /// complete, the missing cells when it is partial, everything otherwise.
    pub fn start(&mut self, settings: &Settings) -> Option<Command> {
        let spec = self.spec_for(settings)?;
        if self.spec == Some(spec) && self.done && self.failed.is_none() {
            return None;
        }
        if self.spec != Some(spec) {
            let g = spec.grid;
            self.cells = vec![None; g.cols * g.rows];
            self.cursor = match self.spec {
                // A first map: the cursor on the current start.
                None => {
                    let problem = settings.rattleback()?;
                    let (p, s) = (problem.params(), problem.start());
                    let ratio = (s.alpha_dot / g.gamma_dot).powi(2);
                    nearest_cell(&g, ratio, p.iy / p.ix)
                }
                Some(_) => (self.cursor.0.min(g.cols - 1), self.cursor.1.min(g.rows - 1)),
            };
        }
        self.spec = Some(spec);
        self.id += 1;
        self.done = false;
        self.failed = None;
        let from = self
            .cells
            .iter()
            .position(Option::is_none)
            .unwrap_or(self.cells.len());
        Some(Command::start_job(self.id, JobSpec::Map { spec, from }))
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
        if let (Some(old), Some(new)) = (self.spec, self.spec_for(settings)) {
            let new = new.grid;
            let (ratio, inertia) = (
                old.grid.ratio(self.cursor.0),
                old.grid.inertia_ratio(self.cursor.1),
            );
            self.cursor = nearest_cell(&new, ratio, inertia);
        }
        self.start(settings)
    }

    /// Takes cells of computation `id`; whether they were this map's.
    pub fn on_cells(&mut self, id: u64, first: usize, reversals: &[usize]) -> bool {
        if id != self.id {
            return false;
        }
        for (n, r) in reversals.iter().enumerate() {
            if let Some(c) = self.cells.get_mut(first + n) {
                *c = Some(*r);
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

    /// Cells computed so far.
    #[must_use]
    pub fn computed(&self) -> usize {
        self.cells.iter().filter(|c| c.is_some()).count()
    }

    /// The count of cell `(i, j)`, if computed.
    #[must_use]
    pub fn cell(&self, i: usize, j: usize) -> Option<usize> {
        let cols = self.spec?.grid.cols;
        self.cells.get(j * cols + i).copied().flatten()
    }

    /// Moves the cursor by `(di, dj)` cells, stopping at the edges (`dj > 0` is up: larger
    /// `iy/ix`).
    pub fn move_cursor(&mut self, di: isize, dj: isize) {
        let Some(spec) = self.spec else { return };
        let clamp = |v: usize, d: isize, n: usize| v.saturating_add_signed(d).min(n - 1);
        self.cursor = (
            clamp(self.cursor.0, di, spec.grid.cols),
            clamp(self.cursor.1, dj, spec.grid.rows),
        );
    }

    /// `(ratio, iy/ix)` at the cursor.
    #[must_use]
    pub fn at_cursor(&self) -> Option<(f64, f64)> {
        let g = self.spec?.grid;
        Some((g.ratio(self.cursor.0), g.inertia_ratio(self.cursor.1)))
    }

    /// The settings of the cell under the cursor: `settings` with `iy = ix · iy/ix` and the
    /// start `(0, 0, γ̇0, √ratio · γ̇0)`.
    ///
    /// # Errors
    /// When there is no map yet or the cell is not a valid body.
    pub fn load(&self, settings: &Settings) -> Result<Settings, String> {
        let spec = self.spec.ok_or("no map yet")?;
        let (ratio, inertia) = self.at_cursor().ok_or("no map yet")?;
        let g = spec.grid;
        let problem = settings
            .rattleback()
            .ok_or("the map is of the rattleback")?;
        let params = Params {
            iy: g.ix * inertia,
            ..*problem.params()
        };
        let start = Start {
            gamma: 0.0,
            alpha: 0.0,
            gamma_dot: g.gamma_dot,
            alpha_dot: ratio.sqrt() * g.gamma_dot,
        };
        let problem = Problem::new(params, start).map_err(|e| format!("this cell: {e}"))?;
        Ok(Settings {
            model: problem.into(),
            ..*settings
        })
    }
}

/// The cell of `grid` nearest to `(ratio, iy/ix)`.
#[must_use]
pub fn nearest_cell(grid: &Grid, ratio: f64, inertia: f64) -> (usize, usize) {
    let i = (ratio / grid.ratio_max * grid.cols as f64).floor();
    let (lo, hi) = grid.inertia;
    let j = ((inertia / lo).ln() / (hi / lo).ln() * grid.rows as f64).floor();
    let clamp = |v: f64, n: usize| {
        if v.is_finite() {
            (v.max(0.0) as usize).min(n - 1)
        } else {
            0
        }
    };
    (clamp(i, grid.cols), clamp(j, grid.rows))
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
            JobData::MapCells { first, reversals } => self.on_cells(stamp, first, &reversals),
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
            spec: Some(JobSpec::Map { from: 0, .. }),
            ..
        }) = m.start(&s)
        else {
            panic!("a first map starts at cell 0")
        };
        let id = m.id;
        assert!(m.on_cells(id, 0, &[1; 48]));
        assert!(!m.on_cells(id - 1, 48, &[1; 48]), "stale cells are ignored");
        let Some(Command::Job {
            spec: Some(JobSpec::Map { from: 48, .. }),
            ..
        }) = m.start(&s)
        else {
            panic!("a partial map resumes where it stopped")
        };
        assert!(m.on_done(m.id, None));
        assert_eq!(m.start(&s), None);
        let t = crate::app::fields::Field::named(crate::physics::ModelKind::Rattleback, "iz")
            .unwrap()
            .with_value(&s, 3.0)
            .unwrap();
        assert!(matches!(
            m.start(&t),
            Some(Command::Job {
                spec: Some(JobSpec::Map { from: 0, .. }),
                ..
            })
        ));
        assert_eq!(m.computed(), 0, "a new body forgets the old counts");
    }

    #[test]
    fn loading_the_cursor_cell_sets_the_body_and_the_start() {
        let s = settings();
        let mut m = MapState::default();
        m.start(&s);
        m.cursor = (11, 3);
        let g = m.spec.unwrap().grid;
        let loaded = m.load(&s).unwrap();
        let (lp, ls) = (
            loaded.rattleback().unwrap().params(),
            loaded.rattleback().unwrap().start(),
        );
        assert_eq!(lp.iy, g.ix * g.inertia_ratio(3));
        assert_eq!(ls.gamma, 0.0);
        assert_eq!(ls.alpha, 0.0);
        assert_eq!(ls.gamma_dot, 0.5);
        let ratio = (ls.alpha_dot / ls.gamma_dot).powi(2);
        assert!((ratio - g.ratio(11)).abs() < 1e-12);
        assert_eq!(lp.k, 1e4, "k, t_end and the method stay");
    }

    #[test]
    fn the_cursor_stays_on_the_grid_and_on_its_point_when_the_source_changes() {
        let s = settings();
        let mut m = MapState::default();
        m.start(&s);
        let g = m.spec.unwrap().grid;
        let (ratio, inertia) = m.at_cursor().unwrap();
        assert!(
            (ratio - 0.36).abs() <= g.ratio_max / g.cols as f64,
            "on the start: {ratio}"
        );
        assert!((inertia.ln() - 0.5f64.ln()).abs() <= 2.5f64.ln() / g.rows as f64);
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
