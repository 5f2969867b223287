//! Round tick marks for a horizontal axis: a step of 1, 2 or 5 times a power of ten, labels
//! centred on their columns, never cut at an edge and never touching each other. The time
//! series, the comparison and the portrait share it, so every axis reads the same way. The
//! drawings' exaggerations are round factors too ([`round_gain`]).
use crate::physics::numerics::elementary::Elementary;

/// Seconds of the recent past a drawing of the body traces (the body's ring, the bob's arc).
pub const TRACE_SECONDS: f64 = 6.0;

/// The exaggeration that draws `biggest` as about `drawn`: 1, 2 or 5 times a power of ten,
/// never below 1 (1 for nothing to draw, or something not a number).
#[must_use]
pub fn round_gain(biggest: f64, drawn: f64) -> f64 {
    if biggest.is_nan() || biggest <= 0.0 || biggest >= drawn {
        return 1.0;
    }
    let want = drawn / biggest;
    let decade = 10f64.e_powf(want.e_log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&g| g <= want)
        .unwrap_or(1.0)
        .max(1.0)
}

/// A canvas's half-extents `(x, y)` over `area` that keep circles round (a cell is about twice
/// as tall as wide) and show at least `reach` on either side of the centre both ways.
#[must_use]
pub fn round_bounds(area: ratatui::layout::Rect, reach: f64) -> (f64, f64) {
    let ratio = f64::from(area.width) / (2.0 * f64::from(area.height));
    (reach * ratio.max(1.0), reach * (1.0 / ratio).max(1.0))
}

/// Round tick values inside `[lo, hi]`: the finest step of 1, 2 or 5 × 10ⁿ that gives at most
/// `most` ticks, and that step.
#[must_use]
pub fn ticks(lo: f64, hi: f64, most: usize) -> (Vec<f64>, f64) {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) || most == 0 {
        return (Vec::new(), 0.0);
    }
    let raw = span / most as f64;
    let mut power = 10f64.e_powf(raw.e_log10().floor());
    let step = loop {
        if let Some(m) = [1.0, 2.0, 5.0]
            .into_iter()
            .find(|m| span / (m * power) <= most as f64)
        {
            break m * power;
        }
        power *= 10.0;
    };
    let first = (lo / step).ceil();
    let last = (hi / step).floor();
    let n = (last - first).max(-1.0) as i64 + 1;
    let values = (0..n.clamp(0, 1000))
        .map(|i| {
            let v = (first + i as f64) * step;
            // -0 and round-off (0.30000000000000004) print as 0 and 0.3.
            if v.abs() < step * 1e-9 { 0.0 } else { v }
        })
        .collect();
    (values, step)
}

/// A tick's label: as many decimals as the step needs, an exponent for very large or small
/// values.
#[must_use]
pub fn label(v: f64, step: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    let a = v.abs();
    if !(1e-3..1e6).contains(&a) {
        let s = format!("{v:.0e}");
        return s;
    }
    let decimals = if step >= 1.0 {
        0
    } else {
        (-step.e_log10().floor()) as usize
    };
    format!("{v:.decimals$}")
}

/// A row of `width` characters: the round ticks of `[lo, hi]` laid over the plot's columns
/// (the plot starts `offset` columns into the row and is `plot` columns wide), each label
/// centred on its column, shifted inside the row where it would be cut, and dropped where it
/// would touch the one before.
#[must_use]
pub fn row(lo: f64, hi: f64, offset: usize, plot: usize, width: usize) -> String {
    let mut cells = vec![' '; width];
    if plot < 2 || width == 0 {
        return String::new();
    }
    // About one label per 10 columns.
    let most = (plot / 10).max(2);
    let (values, step) = ticks(lo, hi, most);
    let mut free_from = 0;
    for v in values {
        let text = label(v, step);
        let len = text.chars().count();
        let f = (v - lo) / (hi - lo);
        let col = offset + (f * (plot - 1) as f64).round() as usize;
        let start = col.saturating_sub(len / 2).min(width.saturating_sub(len));
        if start < free_from || start + len > width {
            continue;
        }
        for (j, ch) in text.chars().enumerate() {
            cells[start + j] = ch;
        }
        free_from = start + len + 1;
    }
    cells.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(ticks(0.0, 30.0, 5).0, [0.0, 10.0, 20.0, 30.0]);
        assert_eq!(ticks(12.374, 21.799, 5).0, [14.0, 16.0, 18.0, 20.0]);
        let (v, step) = ticks(-1.571, 1.571, 5);
        assert!((step - 1.0).abs() < 1e-12);
        assert_eq!(v, [-1.0, 0.0, 1.0]);
        let (v, step) = ticks(0.0, 0.9, 4);
        assert!((step - 0.5).abs() < 1e-12);
        assert_eq!(v, [0.0, 0.5]);
        assert_eq!(label(0.1 + 0.2, 0.1), "0.3");
        assert!(ticks(1.0, 1.0, 4).0.is_empty());
        assert!(ticks(0.0, f64::NAN, 4).0.is_empty());
    }

    #[test]
    fn labels_sit_on_their_columns_and_are_never_cut() {
        let r = row(0.0, 30.0, 8, 40, 48);
        assert_eq!(r.chars().count(), 48);
        assert!(r.trim_end().ends_with("30"), "{r:?}");
        assert!(r[8..].starts_with('0'), "{r:?}");
        // Labels never touch.
        assert!(!r.contains("00 10"), "{r:?}");
        // The celt's following window (issue 54: "12.374 14.731 … 21.799", the last cut).
        let r = row(12.374, 21.799, 8, 40, 48);
        assert_eq!(
            r.split_whitespace().collect::<Vec<_>>(),
            ["15", "20"],
            "{r:?}"
        );
    }
}
