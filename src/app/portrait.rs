//! Geometry of the phase portrait: the view's bounds (automatic range, zoom, pan, wrap), the
//! level sets of the effective energy, and trail decimation to the canvas resolution. Pure
//! data, no drawing.

use crate::physics::LimitView;
use crate::sim::Point;

/// Zoom, pan and wrap chosen by the user.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// > 1 zooms in.
    pub zoom: f64,
    /// Pan as a fraction of the visible width.
    pub pan_x: f64,
    /// Pan as a fraction of the visible height.
    pub pan_y: f64,
    /// Show the slow coordinate modulo one period of `V` (π for the rattleback, 2π for the
    /// pendulum).
    pub wrap: bool,
    /// Fixed `alpha` range from the preset (else automatic).
    pub slow_range: Option<[f64; 2]>,
    /// Fixed `alpha_dot` range from the preset (else automatic).
    pub rate_range: Option<[f64; 2]>,
    /// Background energy levels drawn.
    pub levels: usize,
}

impl Default for View {
    fn default() -> Self {
        Self {
            zoom: 1.0,
            pan_x: 0.0,
            pan_y: 0.0,
            wrap: false,
            slow_range: None,
            rate_range: None,
            levels: LEVELS,
        }
    }
}

/// Axis bounds of the portrait.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// `alpha` range.
    pub x: [f64; 2],
    /// `alpha_dot` range.
    pub y: [f64; 2],
}

/// One energy level: polylines in `(alpha, alpha_dot)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// The energy.
    pub energy: f64,
    /// What it is.
    pub kind: LevelKind,
    /// Its curves.
    pub lines: Vec<Vec<(f64, f64)>>,
}

/// How a level is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LevelKind {
    /// A background level.
    Plain,
    /// The separatrix through the potential maximum.
    Separatrix,
    /// The start's own level.
    Start,
}

/// Number of background levels drawn.
pub const LEVELS: usize = 6;

/// Centre of the period shown when wrapped: the rattleback's potential minimum, the
/// pendulum's upright.
#[must_use]
pub fn wrap_centre(limit: &LimitView) -> f64 {
    limit.wrap_centre()
}

/// The slow coordinate as displayed: unchanged, or folded into one `period` around `centre`.
#[must_use]
pub fn display_alpha(alpha: f64, centre: f64, wrap: bool, period: f64) -> f64 {
    if wrap {
        centre + (alpha - centre + period / 2.0).rem_euclid(period) - period / 2.0
    } else {
        alpha
    }
}

/// Periods of `V` beyond which an unwrapped view follows the motion instead of showing all of
/// it (a long rotating run would otherwise crush the portrait to vertical lines).
pub const FOLLOW_PERIODS: f64 = 3.0;

/// The automatic bounds (before zoom and pan): the separatrix's height, the start with a
/// margin whatever the inertia order, and the trail; an unwrapped trail wider than
/// [`FOLLOW_PERIODS`] periods is followed by a window of that width ending at its last point.
#[must_use]
pub fn auto_bounds(
    limit: &LimitView,
    alpha0: f64,
    alpha_dot0: f64,
    trail: &[Point],
    wrap: bool,
) -> Bounds {
    let period = limit.period();
    let centre = limit.wrap_centre();
    let sep = (2.0 * (limit.potential_max() - limit.potential_min()) / limit.mass())
        .max(0.0)
        .sqrt();
    let mut y_max = sep.max(alpha_dot0.abs()).max(1e-3);
    let margin = 0.08 * period;
    let (mut x_lo, mut x_hi) = if wrap {
        (
            centre - period / 2.0 - margin,
            centre + period / 2.0 + margin,
        )
    } else {
        let c = centre + period * ((alpha0 - centre) / period).round();
        (
            (c - period / 2.0).min(alpha0 - period / 4.0),
            (c + period / 2.0).max(alpha0 + period / 4.0),
        )
    };
    for p in trail {
        y_max = y_max.max(p.rate.abs());
        if !wrap {
            x_lo = x_lo.min(p.slow);
            x_hi = x_hi.max(p.slow);
        }
    }
    if !wrap
        && x_hi - x_lo > FOLLOW_PERIODS * period
        && let Some(last) = trail.last()
    {
        let width = FOLLOW_PERIODS * period;
        // The window trails the motion: the current point sits a sixth from its leading edge.
        let ahead = width / 6.0;
        (x_lo, x_hi) = if last.rate >= 0.0 {
            (last.slow + ahead - width, last.slow + ahead)
        } else {
            (last.slow - ahead, last.slow - ahead + width)
        };
    }
    Bounds {
        x: [x_lo, x_hi],
        y: [-1.15 * y_max, 1.15 * y_max],
    }
}

/// Whether the unwrapped view is following a long run (see [`auto_bounds`]).
#[must_use]
pub fn following(trail: &[Point], wrap: bool, period: f64) -> bool {
    if wrap {
        return false;
    }
    let (lo, hi) = trail
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.slow), hi.max(p.slow))
        });
    hi - lo > FOLLOW_PERIODS * period
}

/// Spacing of the sample grid: fine enough that consecutive samples of the limit's motion are
/// less than a cell apart on a large screen (about 64 samples per unit of the fastest slow
/// rate), whatever the playback speed. A model with a fast period it does not resolve at that
/// spacing (the pendulum at small ε) gets either a spacing resolving it (24 samples per fast
/// period when that costs at most the slow spacing's count ×24), or, when the fast period is
/// shorter than the slow spacing, a spacing of whole fast periods plus a golden-ratio fraction
/// of one: successive samples then visit every phase of the ripple, so the trail fills the
/// ripple band instead of tracing one phase of it (a stroboscope would).
#[must_use]
pub fn sample_spacing(limit: &LimitView) -> f64 {
    let rate = limit.rate_scale().max(1e-3);
    let dt = (1.0 / (64.0 * rate)).min(0.05);
    match limit.fast_period() {
        Some(p) if dt > p / 24.0 && dt < p => p / 24.0,
        Some(p) if dt >= p => p * ((dt / p).floor() + 0.381_966_011_250_105),
        _ => dt,
    }
}

/// Applies fixed ranges, zoom and pan to automatic bounds.
#[must_use]
pub fn apply_view(b: Bounds, view: &View) -> Bounds {
    let b = Bounds {
        x: view.slow_range.unwrap_or(b.x),
        y: view.rate_range.unwrap_or(b.y),
    };
    let scale = |[lo, hi]: [f64; 2], pan: f64| {
        let half = 0.5 * (hi - lo) / view.zoom;
        let mid = 0.5 * (hi + lo) + pan * 2.0 * half;
        [mid - half, mid + half]
    };
    Bounds {
        x: scale(b.x, view.pan_x),
        y: scale(b.y, view.pan_y),
    }
}

/// Level sets of `E_eff = ½ iz α̇² + V(α)` over the bounds, on `samples` points across: the
/// background levels, the separatrix and the start's level.
#[must_use]
pub fn levels(
    eff: &LimitView,
    bounds: &Bounds,
    start_energy: f64,
    count: usize,
    samples: usize,
) -> Vec<Level> {
    let iz = eff.mass();
    let (vmin, vmax) = (eff.potential_min(), eff.potential_max());
    let top = vmax.max(vmin + 0.5 * iz * bounds.y[1].max(-bounds.y[0]).powi(2));
    let mut out = Vec::new();
    // A flat potential (a scene without a limit: the free rotor) has horizontal levels that say
    // nothing the start's own level does not.
    let count = if vmax > vmin { count } else { 0 };
    for i in 1..=count {
        let e = vmin + (top - vmin) * i as f64 / (count + 1) as f64;
        out.push(level(eff, bounds, e, LevelKind::Plain, samples));
    }
    for sep in eff.separatrices() {
        out.push(level(eff, bounds, sep, LevelKind::Separatrix, samples));
    }
    out.push(level(eff, bounds, start_energy, LevelKind::Start, samples));
    out
}

fn level(eff: &LimitView, bounds: &Bounds, energy: f64, kind: LevelKind, samples: usize) -> Level {
    let iz = eff.mass();
    let n = samples.max(8);
    let [x0, x1] = bounds.x;
    let speed = |a: f64| {
        let d = energy - eff.potential(a);
        (d >= 0.0).then(|| (2.0 * d / iz).sqrt())
    };
    // Runs of consecutive α where the level exists.
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut run: Vec<(f64, f64)> = Vec::new();
    for i in 0..=n {
        let a = x0 + (x1 - x0) * i as f64 / n as f64;
        match speed(a) {
            Some(v) => run.push((a, v)),
            None => {
                if !run.is_empty() {
                    runs.push(std::mem::take(&mut run));
                }
            }
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    let mut lines = Vec::new();
    for run in runs {
        let open = run.first().is_some_and(|p| p.0 <= x0) || run.last().is_some_and(|p| p.0 >= x1);
        let upper: Vec<(f64, f64)> = run.clone();
        let lower: Vec<(f64, f64)> = run.iter().rev().map(|&(a, v)| (a, -v)).collect();
        if open {
            // Reaches the edge of the view: two separate branches.
            lines.push(upper);
            lines.push(lower);
        } else {
            // A closed orbit around a well.
            let mut closed = upper;
            closed.extend(lower);
            if let Some(&first) = closed.first() {
                closed.push(first);
            }
            lines.push(closed);
        }
    }
    Level {
        energy,
        kind,
        lines,
    }
}

/// Keeps the points of `trail` that land in a new canvas cell (`cols × rows` cells over the
/// bounds), plus the last one: the trail costs no more to draw than the canvas can show.
#[must_use]
pub fn decimate(
    trail: impl IntoIterator<Item = (f64, f64)>,
    bounds: &Bounds,
    cols: usize,
    rows: usize,
) -> Vec<(f64, f64)> {
    let cell = |(x, y): (f64, f64)| {
        let cx = ((x - bounds.x[0]) / (bounds.x[1] - bounds.x[0]) * cols as f64).floor();
        let cy = ((y - bounds.y[0]) / (bounds.y[1] - bounds.y[0]) * rows as f64).floor();
        (cx as i64, cy as i64)
    };
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut last_cell = None;
    let mut end = None;
    for p in trail {
        let c = cell(p);
        if Some(c) != last_cell {
            out.push(p);
            last_cell = Some(c);
        }
        end = Some(p);
    }
    if let Some(end) = end
        && out.last() != Some(&end)
    {
        out.push(end);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    use std::f64::consts::PI;

    fn eff() -> LimitView {
        crate::physics::Model::from(crate::physics::rattleback::paper_body(
            1e4,
            [0.0, 0.0, 1.0, 0.5],
        ))
        .limit_view()
    }

    #[test]
    fn level_points_lie_on_their_energy() {
        let e = eff();
        let b = auto_bounds(&e, 0.0, 0.5, &[], false);
        for level in levels(&e, &b, e.energy(), LEVELS, 200) {
            for line in &level.lines {
                for &(a, v) in line {
                    let got = e.energy_of(a, v);
                    assert!(
                        (got - level.energy).abs() < 1e-9 * level.energy.max(1.0),
                        "{got} vs {}",
                        level.energy
                    );
                }
            }
        }
    }

    #[test]
    fn trapped_start_level_is_a_closed_orbit_and_separatrix_exists() {
        let e = eff();
        let b = auto_bounds(&e, 0.0, 0.5, &[], false);
        let all = levels(&e, &b, e.energy(), LEVELS, 200);
        let start = all.iter().find(|l| l.kind == LevelKind::Start).unwrap();
        assert_eq!(start.lines.len(), 1);
        assert_eq!(start.lines[0].first(), start.lines[0].last());
        assert!(all.iter().any(|l| l.kind == LevelKind::Separatrix));
    }

    #[test]
    fn decimation_keeps_one_point_per_cell() {
        let b = Bounds {
            x: [0.0, 1.0],
            y: [0.0, 1.0],
        };
        let trail: Vec<(f64, f64)> = (0..10_000)
            .map(|i| (f64::from(i) / 10_000.0, 0.5))
            .collect();
        let d = decimate(trail.iter().copied(), &b, 100, 10);
        assert!(d.len() <= 101, "{}", d.len());
        assert_eq!(d.last(), trail.last());
    }

    #[test]
    fn wrapping_folds_into_one_period() {
        let a = display_alpha(3.0 * PI + 0.1, 0.0, true, PI);
        assert!((a - 0.1).abs() < 1e-12);
        assert!((display_alpha(5.0, 0.0, false, PI) - 5.0).abs() < 1e-15);
        let a = display_alpha(3.0 * PI + 0.1, 0.0, true, 2.0 * PI);
        assert!((a - (0.1 - PI)).abs() < 1e-12);
    }
}
