//! The body pane of Kapitza's pendulum (issue 59): the rod and its bob on the shaken pivot,
//! beside the averaged rod the slow motion follows.
//!
//! The pivot's travel (`±b ε` rod lengths) and the ripple `θ − Θ` are O(ε): invisible at the
//! rod's scale. Both are drawn with one exaggeration `×G`, a round factor that makes the pivot's
//! travel about [`DRAWN_STROKE`] of the rod (never less than its true size), printed in the pane:
//! the true rod hangs from the pivot where it is, at `Θ + G (θ − Θ)`; the averaged rod from the
//! pivot's mean position at `Θ`. The bob's trace over the last seconds is `+` while the averaged
//! angle grows and `-` while it shrinks, so a swing (a turning point of the slow motion) turns
//! one into the other, as a reversal does on the rattleback's ring. Shapes, not colours: it
//! reads the same under `NO_COLOR`, in Braille, half blocks and one point per cell.
use crate::physics::numerics::elementary::Elementary;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::Line as TextLine;
use ratatui::widgets::Widget;
use ratatui::widgets::canvas::{Context, Line, Points};

use super::marks::{Facts, Section, curve, printed};
use super::{Look, framed};
use crate::app::RunState;
use crate::physics::scene::Pivot;
use crate::sim::Point;

/// The true bob.
pub const BOB: char = '●';
/// The averaged rod's bob.
pub const AVERAGED_BOB: char = '○';
/// The pivot (a hinge on its rail).
pub const PIVOT: char = '▲';
/// The rod, the averaged rod's dots and the pivot's rail, with one point per cell.
const ROD: char = '•';
const DOT: char = '·';
const RAIL: char = '│';
/// The bob's trace while the averaged angle grows, and while it shrinks.
const GROWING: char = '+';
const SHRINKING: char = '-';
/// The pivot's travel as drawn, in rod lengths, when its true travel is smaller.
pub const DRAWN_STROKE: f64 = 0.15;
/// Seconds of the bob's trace.
use super::axis::TRACE_SECONDS;
/// Dots along the averaged rod.
const AVERAGED_DOTS: u32 = 7;

/// What the pane draws, for the legend (the same marks as the pane).
pub fn legend(f: &Facts<'_>, look: &Look<'_>) -> Section {
    let t = look.theme;
    let words = f.kind.words();
    // The scene's pendulum: Kapitza's is averaged on a shaken pivot; another draws what it has.
    let (averaged, shaken) = match f.drawing {
        crate::physics::scene::Drawing::Pendulum(p) => (p.averaged, p.stroke != 0.0),
        crate::physics::scene::Drawing::Body { .. } | crate::physics::scene::Drawing::Figure(_) => {
            (false, false)
        }
    };
    let mut s = Section::new(if shaken {
        "pendulum (B), on its shaken pivot"
    } else {
        "pendulum (B)"
    });
    if averaged {
        s = s
            .mark(
                format!("{}{}", curve(look, ROD, "⠒⠒⠒", "▀▀▀"), printed(look, BOB)),
                t.trail,
                format!(
                    "the rod and its bob, at {} with the ripple {} exaggerated ×G",
                    words.q, words.fast
                ),
            )
            .mark(
                format!(
                    "{}{}",
                    curve(look, DOT, "⠂ ⠂", "▀ ▀"),
                    printed(look, AVERAGED_BOB)
                ),
                t.effective,
                "the averaged rod Θ = θ − ripple, hung from the pivot's mean position",
            );
    } else {
        s = s.mark(
            format!("{}{}", curve(look, ROD, "⠒⠒⠒", "▀▀▀"), printed(look, BOB)),
            t.trail,
            format!("the rod and its bob, at {}", words.q),
        );
    }
    if shaken {
        s = s.mark(
            format!("{}{}", curve(look, RAIL, "⡇", "█"), printed(look, PIVOT)),
            t.current,
            "the pivot on its travel ±b ε (drawn ×G: the pane prints G)",
        );
    }
    s.mark(
        printed(look, GROWING),
        t.trail,
        if averaged {
            "the bob's trace while the averaged angle grows"
        } else {
            "the bob's trace while the angle grows"
        },
    )
    .mark(
        printed(look, SHRINKING),
        t.reversal,
        format!(
            "the bob's trace while it shrinks (a {} turns + into -)",
            words.event
        ),
    )
}

/// The exaggeration of the pivot's travel and the ripple: a round factor (1, 2 or 5 times a
/// power of ten) that draws a travel of `stroke` as about [`DRAWN_STROKE`], never below 1.
#[must_use]
pub fn exaggeration(stroke: f64) -> f64 {
    super::axis::round_gain(stroke, DRAWN_STROKE)
}

/// The pendulum's pane: what it shows, borrowed.
pub struct PendulumPane<'a> {
    /// The run (its displayed samples).
    pub run: &'a RunState,
    /// The shaken pivot.
    pub pivot: Pivot,
    /// The slow motion's event, counted in the heading (`swings`).
    pub events: &'a str,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

/// Where the drawing puts a sample: the pivot's height, the averaged angle `Θ` and the angle
/// the true rod is drawn at (`Θ + G (θ − Θ)`), with `θ` measured from the upright.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The pivot's drawn height above its mean position.
    pub pivot: f64,
    /// The averaged angle.
    pub averaged: f64,
    /// The true rod's drawn angle.
    pub drawn: f64,
}

/// The pose of `p` drawn with exaggeration `gain`.
#[must_use]
pub fn pose(pivot: &Pivot, gain: f64, p: &Point) -> Pose {
    // Without a ripple (a pendulum that is not averaged), the rod is at θ itself.
    let fast = if pivot.averaged { p.fast } else { 0.0 };
    let averaged = p.slow - fast;
    Pose {
        pivot: gain * pivot.height(p.t),
        averaged,
        drawn: averaged + gain * fast,
    }
}

impl Pose {
    /// Where the true bob is drawn: the rod's end from the pivot where it is.
    #[must_use]
    pub fn bob(&self) -> (f64, f64) {
        tip(self.drawn, self.pivot)
    }

    /// Where the averaged bob is drawn: the rod's end from the pivot's mean position.
    #[must_use]
    pub fn averaged_bob(&self) -> (f64, f64) {
        tip(self.averaged, 0.0)
    }
}

/// The end of a rod of unit length at angle `theta` from the upright, hung at height `y0`.
fn tip(theta: f64, y0: f64) -> (f64, f64) {
    (theta.e_sin(), y0 + theta.e_cos())
}

/// The bob's trace over the last [`TRACE_SECONDS`] (from the mean pivot, at the averaged
/// angle): `(x, y, growing)`.
fn trace(run: &RunState) -> Vec<(f64, f64, bool)> {
    let shown = run.trail_shown();
    let t_now = run.current().map_or(0.0, |p| p.t);
    let recent: Vec<&Point> = shown
        .iter()
        .rev()
        .take_while(|p| t_now - p.t <= TRACE_SECONDS)
        .collect();
    recent
        .windows(2)
        .step_by(2)
        .map(|w| {
            let (now, before) = (w[0].slow - w[0].fast, w[1].slow - w[1].fast);
            let (x, y) = tip(now, 0.0);
            (x, y, now >= before)
        })
        .collect()
}

impl Widget for PendulumPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (run, look, pivot) = (self.run, self.look, self.pivot);
        let gain = exaggeration(pivot.stroke);
        let now = run.current().copied();
        let at = now.map(|p| pose(&pivot, gain, &p));
        let angles = now.map_or_else(String::new, |p| {
            if pivot.averaged {
                format!(": θ {:+.3}, Θ {:+.3}", p.slow, p.slow - p.fast)
            } else {
                format!(": θ {:+.3}", p.slow)
            }
        });
        let heading = format!(
            "pendulum (B){angles} │ {} {}",
            self.events,
            run.reversals_shown()
        );
        // Spelled for the set in use (the heading's θ and Θ would both fold to `t`).
        let inner = framed(&look.charset.spell(&heading), area, buf);
        if inner.width < 4 || inner.height < 3 {
            return;
        }
        // Equal scales (a cell is about twice as tall as wide): the rod and the pivot's travel
        // fit whatever the angle.
        let travel = gain * pivot.stroke;
        let (sx, sy) = super::axis::round_bounds(inner, 1.0 + travel + 0.12);
        let theme = look.theme;
        let label = if pivot.stroke == 0.0 {
            "pivot fixed".to_owned()
        } else if gain > 1.0 {
            format!("pivot ±{:.1e} drawn ×{gain}", pivot.stroke)
        } else {
            format!("pivot ±{:.2} to scale", pivot.stroke)
        };
        let label = look.charset.spell(&label);
        let trace = trace(run);
        super::glyphs::canvas(look, [-sx, sx], [-sy, sy], |ctx| {
            // One point per cell (the console, ASCII): each part its own character, as
            // the legend shows it; else the marker's dots.
            let one_per_cell = look.marker == Marker::Dot;
            let part = |ctx: &mut Context<'_>, c: char| {
                if one_per_cell {
                    ctx.marker(Marker::Custom(c));
                }
            };
            // The pivot's travel, a short rail.
            if travel > 0.0 {
                part(ctx, RAIL);
                ctx.draw(&Line::new(0.0, -travel, 0.0, travel, theme.current));
            }
            ctx.layer();
            if let Some(at) = at.filter(|_| pivot.averaged) {
                // The averaged rod: dots from the pivot's mean position.
                let (xa, ya) = at.averaged_bob();
                let dots: Vec<(f64, f64)> = (1..=AVERAGED_DOTS)
                    .map(|i| {
                        let s = f64::from(i) / f64::from(AVERAGED_DOTS + 1);
                        (s * xa, s * ya)
                    })
                    .collect();
                part(ctx, DOT);
                ctx.draw(&Points {
                    coords: &dots,
                    color: theme.effective,
                });
            }
            ctx.layer();
            if let Some(at) = at {
                // The true rod, from the pivot where it is.
                let (x1, y1) = at.bob();
                part(ctx, ROD);
                ctx.draw(&Line::new(0.0, at.pivot, x1, y1, theme.trail));
            }
            ctx.layer();
            super::marks::print_signed(ctx, &trace, (GROWING, SHRINKING), theme);
            if let Some(at) = at {
                if pivot.averaged {
                    let (xa, ya) = at.averaged_bob();
                    ctx.print(xa, ya, styled(AVERAGED_BOB, theme.effective, false));
                }
                let (x1, y1) = at.bob();
                ctx.print(x1, y1, styled(BOB, theme.current, true));
                ctx.print(0.0, at.pivot, styled(PIVOT, theme.current, true));
            }
            ctx.print(
                -sx,
                -sy,
                TextLine::styled(label.clone(), Style::default().fg(theme.dim)),
            );
        })
        .render(inner, buf);
    }
}

fn styled(c: char, colour: ratatui::style::Color, bold: bool) -> TextLine<'static> {
    let style = Style::default().fg(colour);
    TextLine::styled(
        c.to_string(),
        if bold {
            style.add_modifier(Modifier::BOLD)
        } else {
            style
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::scene::Drawing;

    fn point(t: f64, slow: f64, fast: f64) -> Point {
        Point {
            t,
            slow,
            rate: 0.0,
            energy_error: 0.0,
            fast,
            lean: None,
        }
    }

    /// The pivot moves as the model's forcing says: its acceleration, by central differences
    /// of the height, is `(b/ε) cos(t/ε)` when the travel is `b ε`.
    #[test]
    fn the_pivot_accelerates_as_the_forcing_says() {
        let (b, eps) = (2.0, 0.05);
        let pivot = Pivot {
            stroke: b * eps,
            epsilon: eps,
            averaged: true,
        };
        for t in [0.0, 0.3, 1.7, 4.2] {
            let h = 1e-4;
            let acc = (pivot.height(t + h) - 2.0 * pivot.height(t) + pivot.height(t - h)) / (h * h);
            let want = b / eps * (t / eps).e_cos();
            assert!(
                (acc - want).abs() < 1e-3 * want.abs().max(1.0),
                "{t}: {acc} {want}"
            );
        }
    }

    /// The averaged rod is at `θ − ripple`; the true one at the averaged angle plus the ripple
    /// times the stated gain, from the pivot's drawn height; with a gain of 1, at `θ` itself.
    #[test]
    fn the_rods_are_where_the_sample_and_the_gain_say() {
        let pivot = Pivot {
            stroke: 2e-3,
            epsilon: 1e-3,
            averaged: true,
        };
        let gain = exaggeration(pivot.stroke);
        assert!((gain - 50.0).abs() < 1e-12, "{gain}");
        let p = point(0.0, 0.3, 1e-3);
        let at = pose(&pivot, gain, &p);
        assert!((at.averaged - 0.299).abs() < 1e-12);
        assert!((at.drawn - (0.299 + 0.05)).abs() < 1e-12);
        assert!((at.pivot + 0.1).abs() < 1e-12, "{at:?}");
        let coarse = Pivot {
            stroke: 0.3,
            epsilon: 0.15,
            averaged: true,
        };
        assert!((exaggeration(coarse.stroke) - 1.0).abs() < 1e-12);
        let at = pose(&coarse, 1.0, &p);
        assert!((at.drawn - 0.3).abs() < 1e-12);
    }

    /// Issue 83: a pendulum that is neither shaken nor averaged (a scene's own, such as a
    /// damped driven pendulum) has no pivot travel, no averaged rod and no `Θ`: its rod is at
    /// `θ`, and the legend speaks of what it draws.
    #[test]
    fn a_fixed_pendulum_draws_its_rod_alone() {
        let fixed = Pivot {
            stroke: 0.0,
            epsilon: 1.0,
            averaged: false,
        };
        let p = point(2.0, 0.4, 0.05);
        let at = pose(&fixed, 1.0, &p);
        assert!((at.drawn - 0.4).abs() < 1e-15 && (at.averaged - 0.4).abs() < 1e-15);
        assert!(at.pivot.abs() < f64::MIN_POSITIVE, "{at:?}");
        let theme = crate::ui::Theme::default();
        let look = Look {
            theme: &theme,
            marker: Marker::Braille,
            no_color: false,
            charset: crate::ui::glyphs::Charset::Unicode,
        };
        let model = crate::physics::Model::from(crate::physics::rattleback::paper_body(
            1e4,
            [0.0, 0.0, 1.0, 0.5],
        ));
        let limit = model.limit_view();
        let legend = |drawing| {
            let f = Facts {
                kind: crate::physics::ModelKind::Kapitza,
                limit: &limit,
                drawing,
                summary: &[],
            };
            let s = legend(&f, &look);
            let marks: Vec<String> = s.marks.iter().map(|m| m.what.clone()).collect();
            (s.title, marks.join("\n"))
        };
        let (title, marks) = legend(Drawing::Pendulum(fixed));
        assert_eq!(title, "pendulum (B)");
        assert!(!marks.contains('Θ') && !marks.contains("pivot"), "{marks}");
        let shaken = Pivot {
            stroke: 0.1,
            epsilon: 0.05,
            averaged: true,
        };
        let (title, marks) = legend(Drawing::Pendulum(shaken));
        assert_eq!(title, "pendulum (B), on its shaken pivot");
        assert!(marks.contains("averaged rod Θ") && marks.contains("pivot on its travel"));
    }
}
