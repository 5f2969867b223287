//! The body pane (toggle `B`): the rattleback seen from above, so the reversal is seen and not
//! only plotted. An elongated body whose long axis turns with `alpha`; its rocking `gamma`, far
//! too fast to draw at large `k`, shown by the cross bar whose length is the rocking envelope
//! (the largest `|gamma|` over the last stretch of samples, exaggerated to the body's size); the
//! trace of the long axis's tip over the last seconds, `+` while the spin is counter-clockwise
//! (`alpha_dot > 0`) and `-` while clockwise, so a reversal is a change of sign on the ring. It
//! reads the same in Braille, half blocks and under `NO_COLOR` (shapes and signs, not colours).
use crate::physics::numerics::elementary::Elementary;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::Line as TextLine;
use ratatui::widgets::Widget;
use ratatui::widgets::canvas::{Line, Points};

use super::marks::{Facts, Section, curve, printed};
use super::{Look, framed};
use crate::app::RunState;
use crate::physics::scene::{Drawing, SideView};

/// The tip's trace while the spin is counter-clockwise, and clockwise.
const COUNTER: char = '+';
const CLOCKWISE: char = '-';
/// The long axis's tip.
const TIP: char = '●';
/// Where the side view's profile touches the ground.
const CONTACT: char = '^';
/// The side view's ground, with one point per cell.
const GROUND: char = '─';

/// What the pane draws, for the legend (the same marks as the pane).
pub fn legend(f: &Facts<'_>, look: &Look<'_>) -> Section {
    match f.drawing {
        Drawing::Pendulum(_) => return super::pendulum::legend(f, look),
        Drawing::Figure(figure) => return super::figure::legend(&figure, look),
        Drawing::Body { .. } => {}
    }
    let t = look.theme;
    let words = f.kind.words();
    let mut s = Section::new("body (B), seen from above")
        .mark(
            curve(look, '•', "⠢⠤⠔", "▄▄▀"),
            t.trail,
            "the outline; its long axis turns with the spin angle",
        )
        .mark(
            curve(look, '•', "⠒⠒⠒", "▀▀▀"),
            t.effective,
            format!(
                "the cross bar: the rocking envelope |{}| (exaggerated)",
                words.fast
            ),
        )
        .mark(
            printed(look, COUNTER),
            t.trail,
            "the tip's trace while spinning counter-clockwise",
        )
        .mark(
            printed(look, CLOCKWISE),
            t.reversal,
            format!(
                "the tip's trace while spinning clockwise (a {} turns + into -)",
                words.event
            ),
        )
        .mark(printed(look, TIP), t.current, "the tip of the long axis");
    if f.drawing.has_sides() {
        s = s
            .mark(
                curve(look, GROUND, "⠤⠤⠤", "▄▄▄"),
                t.dim,
                "side and end views: the ground",
            )
            .mark(
                printed(look, CONTACT),
                t.reversal,
                "where the body touches the ground (tilt drawn exaggerated)",
            );
    }
    s
}

/// Seconds of trace drawn around the body (the pendulum's pane draws as many).
pub const TRACE_SECONDS: f64 = super::axis::TRACE_SECONDS;
/// Samples the rocking envelope is taken over.
pub const ENVELOPE_SAMPLES: usize = 96;

/// The body pane: what it shows, borrowed.
pub struct BodyPane<'a> {
    /// The run (its displayed samples).
    pub run: &'a RunState,
    /// What the scene draws: a body (from above, and from the side when it has a profile),
    /// the pendulum on its pivot ([`super::pendulum`]) or the scene's own figure
    /// ([`super::figure`]).
    pub drawing: Drawing,
    /// The scene's words (the fast coordinate's name `gamma`, `tilt`; the event counted).
    pub words: crate::physics::Words,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

/// The rocking envelope: the largest `|gamma|` over the last samples shown.
#[must_use]
pub fn envelope(run: &RunState) -> f64 {
    let shown = run.trail_shown();
    shown[shown.len().saturating_sub(ENVELOPE_SAMPLES)..]
        .iter()
        .map(|p| p.fast.abs())
        .fold(0.0, f64::max)
}

/// The pane's title: the sense of the spin, the reversals, the rocking envelope.
fn heading(run: &RunState, alpha_dot: f64, rock: f64, fast: &str, sides: bool) -> String {
    let turning = match alpha_dot.partial_cmp(&0.0) {
        Some(std::cmp::Ordering::Greater) => "↺ counter-clockwise",
        Some(std::cmp::Ordering::Less) => "↻ clockwise",
        _ => "at rest",
    };
    format!(
        "body {} (B): spin {turning}, reversals {} │ rocking |{fast}| {rock:.1e}",
        if sides {
            "from above, side, end"
        } else {
            "from above"
        },
        run.reversals_shown()
    )
}

/// The long axis's tip over the last [`TRACE_SECONDS`]: `(x, y, counter-clockwise)`, on a ring
/// just outside the body (`along_x`: the long axis is the body's x axis).
fn trace(run: &RunState, along_x: bool) -> Vec<(f64, f64, bool)> {
    let t_now = run.current().map_or(0.0, |p| p.t);
    let (x, y) = if along_x { (1.18, 0.0) } else { (0.0, 1.18) };
    run.trail_shown()
        .iter()
        .rev()
        .take_while(|p| t_now - p.t <= TRACE_SECONDS)
        .step_by(2)
        .map(|p| {
            let (c, s) = (p.slow.e_cos(), p.slow.e_sin());
            (x * c - y * s, x * s + y * c, p.rate >= 0.0)
        })
        .collect()
}

impl Widget for BodyPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        match self.drawing {
            Drawing::Pendulum(pivot) => super::pendulum::PendulumPane {
                run: self.run,
                pivot,
                events: self.words.events,
                look: self.look,
            }
            .render(area, buf),
            Drawing::Body { plan, side } => self.body(plan, side, area, buf),
            Drawing::Figure(figure) => super::figure::FigurePane {
                run: self.run,
                figure,
                events: self.words.events,
                look: self.look,
            }
            .render(area, buf),
        }
    }
}

impl BodyPane<'_> {
    /// A body from above (half-extents `plan`), with its side and end views when it has a
    /// profile.
    fn body(&self, plan: [f64; 2], side: Option<SideView>, area: Rect, buf: &mut Buffer) {
        let (run, look) = (self.run, self.look);
        // The body's extent along y over x: the body is drawn longer along x when it is at
        // most 1.
        let aspect = plan[1] / plan[0];
        let now = run.current().copied();
        let (alpha, alpha_dot) = now.map_or((0.0, 0.0), |p| (p.slow, p.rate));
        let rock = envelope(run);
        let mut inner = framed(
            &heading(run, alpha_dot, rock, self.words.fast_name, side.is_some()),
            area,
            buf,
        );
        if inner.width < 4 || inner.height < 3 {
            return;
        }
        // The side and end views take the bottom third, when there is room for them.
        if let Some(side) = side
            && inner.height >= 10
            && inner.width >= 30
        {
            let rows = (inner.height / 3).clamp(4, 8);
            inner.height -= rows;
            let below = Rect {
                y: inner.y + inner.height,
                height: rows,
                ..inner
            };
            let lean = now.and_then(|p| p.lean).unwrap_or([0.0, 0.0]);
            sides(side, lean, exaggeration(run), look, below, buf);
        }
        // Cells are about twice as tall as wide: keep circles round.
        let (sx, sy) = super::axis::round_bounds(inner, 1.35);
        // The long axis is the body's x axis when ix > iy (the rattleback's keel).
        let (a, b) = if aspect <= 1.0 {
            (1.0, 0.42)
        } else {
            (0.42, 1.0)
        };
        let (c, s) = (alpha.e_cos(), alpha.e_sin());
        let rot = |x: f64, y: f64| (x * c - y * s, x * s + y * c);
        let outline: Vec<(f64, f64)> = (0..=96)
            .map(|i| {
                let u = f64::from(i) / 96.0 * std::f64::consts::TAU;
                rot(a * u.e_cos(), b * u.e_sin())
            })
            .collect();
        // The cross bar: its half-length is the envelope, scaled so the largest rocking of the
        // run fills the body's width (exaggerated: the real tilt is tiny at large k).
        let biggest = run
            .trail_shown()
            .iter()
            .map(|p| p.fast.abs())
            .fold(0.0, f64::max);
        let bar = if biggest > 0.0 {
            0.15 + 0.85 * rock / biggest
        } else {
            0.15
        };
        let cross = if a >= b {
            (0.0, b * bar)
        } else {
            (a * bar, 0.0)
        };
        let long = if a >= b { (a, 0.0) } else { (0.0, b) };
        let trace = trace(run, a >= b);
        let theme = look.theme;
        super::glyphs::canvas(look, [-sx, sx], [-sy, sy], |ctx| {
            for w in outline.windows(2) {
                ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, theme.trail));
            }
            let (x0, y0) = rot(-long.0, -long.1);
            let (x1, y1) = rot(long.0, long.1);
            ctx.draw(&Line::new(x0, y0, x1, y1, theme.separatrix));
            let (u0, v0) = rot(-cross.0, -cross.1);
            let (u1, v1) = rot(cross.0, cross.1);
            ctx.draw(&Line::new(u0, v0, u1, v1, theme.effective));
            ctx.draw(&Points {
                coords: &[(0.0, 0.0)],
                color: theme.current,
            });
            ctx.layer();
            super::marks::print_signed(ctx, &trace, (COUNTER, CLOCKWISE), theme);
            // The tip of the long axis, bold, where the trace starts.
            ctx.print(
                x1,
                y1,
                TextLine::styled(
                    TIP.to_string(),
                    Style::default()
                        .fg(theme.current)
                        .add_modifier(Modifier::BOLD),
                ),
            );
        })
        .render(inner, buf);
    }
}

/// The side view (pitch, three fifths of `area`) and the end view (roll) side by side.
fn sides(side: SideView, lean: [f64; 2], gain: f64, look: &Look, area: Rect, buf: &mut Buffer) {
    let left = area.width * 3 / 5;
    let profile = |half_width, angle, label| Profile {
        half_width,
        depth: side.height,
        offset: side.offset,
        angle,
        gain,
        label,
        look,
    };
    profile(side.long, lean[0], "side, pitch").render(
        Rect {
            width: left,
            ..area
        },
        buf,
    );
    profile(side.cross, lean[1], "end, roll").render(
        Rect {
            x: area.x + left + 1,
            width: area.width - left - 1,
            ..area
        },
        buf,
    );
}

/// How much the side and end views exaggerate the lean: the largest lean shown so far is drawn
/// as about 0.3 rad (17°), never less than its true angle; a power of ten times 1, 2 or 5, so
/// the label reads simply.
#[must_use]
pub fn exaggeration(run: &RunState) -> f64 {
    let biggest = run
        .trail_shown()
        .iter()
        .filter_map(|p| p.lean)
        .map(|[x, y]| x.abs().max(y.abs()))
        .fold(0.0, f64::max);
    super::axis::round_gain(biggest, 0.3)
}

/// One profile of the body on the ground, seen from the side (`long`, pitch) or from an end
/// (`cross`, roll): the half-ellipse of its bottom and its flat top, tipped by the lean times
/// the gain, resting on the ground at its lowest point, its mass centre and the contact marked.
struct Profile<'a> {
    half_width: f64,
    depth: f64,
    offset: f64,
    angle: f64,
    gain: f64,
    label: &'a str,
    look: &'a Look<'a>,
}

impl Profile<'_> {
    /// The outline, the mass centre and the contact's x, in the ground's frame (the body
    /// tipped by `theta`, its lowest point at height 0).
    fn shape(&self, theta: f64) -> (Vec<(f64, f64)>, (f64, f64), f64) {
        let (a, c) = (self.half_width, self.depth);
        let (ct, st) = (theta.e_cos(), theta.e_sin());
        let lift = (a * a * st * st + c * c * ct * ct).sqrt();
        let place = |x: f64, z: f64| (x * ct - z * st, x * st + z * ct + lift);
        let mut outline: Vec<(f64, f64)> = (0..=48)
            .map(|i| {
                let u = std::f64::consts::PI * (1.0 + f64::from(i) / 48.0);
                place(a * u.e_cos(), c * u.e_sin())
            })
            .collect();
        outline.push(outline[0]);
        let centre = place(0.0, -self.offset);
        let contact = -(a * a - c * c) * st * ct / lift;
        (outline, centre, contact)
    }
}

impl Widget for Profile<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        if area.width < 8 || area.height < 2 {
            return;
        }
        let theme = self.look.theme;
        let (outline, centre, contact) = self.shape(self.angle * self.gain);
        // Equal scales on both axes (a cell is about twice as tall as wide); zoom out until the
        // tipped body fits under the label row.
        let top = outline.iter().map(|p| p.1).fold(0.0, f64::max);
        let (cols, rows) = (f64::from(area.width), f64::from(area.height));
        let mut half = self.half_width * 1.15;
        let span = |half: f64| rows * 4.0 * half / cols;
        let room = (rows - 1.0) / rows;
        if top * 1.1 > room * span(half) * 0.9 {
            half *= top * 1.1 / (room * span(half) * 0.9);
        }
        let floor = -0.08 * span(half);
        let gain = if self.gain > 1.0 {
            format!(" drawn ×{}", self.gain)
        } else {
            String::new()
        };
        let text = format!("{} {:+.3}{gain}", self.label, self.angle);
        super::glyphs::canvas(
            self.look,
            [-half, half],
            [floor, floor + span(half)],
            |ctx| {
                if self.look.marker == ratatui::symbols::Marker::Dot {
                    ctx.marker(ratatui::symbols::Marker::Custom(GROUND));
                }
                ctx.draw(&Line::new(-half, 0.0, half, 0.0, theme.dim));
                ctx.layer();
                if self.look.marker == ratatui::symbols::Marker::Dot {
                    ctx.marker(ratatui::symbols::Marker::Dot);
                }
                for w in outline.windows(2) {
                    ctx.draw(&Line::new(w[0].0, w[0].1, w[1].0, w[1].1, theme.trail));
                }
                ctx.draw(&Points {
                    coords: &[centre],
                    color: theme.current,
                });
                ctx.layer();
                ctx.print(
                    contact,
                    0.0,
                    TextLine::styled(CONTACT.to_string(), Style::default().fg(theme.reversal)),
                );
                ctx.print(
                    -half,
                    floor + span(half),
                    TextLine::styled(text.clone(), Style::default().fg(theme.dim)),
                );
            },
        )
        .render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The profile rests on the ground at its lowest point, which is where the contact mark
    /// goes, whatever the lean; the mass centre lies below the centre along the tipped axis.
    #[test]
    fn the_profile_rests_on_its_contact() {
        let theme = crate::ui::Theme::default();
        let look = Look {
            theme: &theme,
            marker: ratatui::symbols::Marker::Braille,
            no_color: false,
            charset: crate::ui::glyphs::Charset::Unicode,
        };
        for theta in [-0.6, -0.2, -0.01, 0.0, 0.05, 0.3, 0.7] {
            let p = Profile {
                half_width: 20.0,
                depth: 2.0,
                offset: 1.0,
                angle: theta,
                gain: 1.0,
                label: "",
                look: &look,
            };
            let (outline, centre, contact) = p.shape(theta);
            let lowest = outline
                .iter()
                .copied()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            assert!(lowest.1 < 1e-2 && lowest.1 > -1e-12, "{theta}: {lowest:?}");
            // The outline is sampled every 3.75°: the contact lies within a sample of it.
            assert!(
                (lowest.0 - contact).abs() < 20.0 * 0.07,
                "{theta}: {contact}"
            );
            // G is 1 below the centre (height `lift`), along the body's tipped z axis.
            let lift = (400.0 * theta.e_sin().powi(2) + 4.0 * theta.e_cos().powi(2)).sqrt();
            assert!((centre.0 - theta.e_sin()).abs() < 1e-12, "{theta}");
            assert!((centre.1 - (lift - theta.e_cos())).abs() < 1e-12, "{theta}");
        }
    }

    #[test]
    fn the_exaggeration_is_a_round_factor_that_never_shrinks() {
        let gain = |x| super::super::axis::round_gain(x, 0.3);
        assert!((gain(0.005) - 50.0).abs() < 1e-9);
        assert!((gain(0.02) - 10.0).abs() < 1e-9);
        assert!((gain(0.1) - 2.0).abs() < 1e-9);
        assert!((gain(0.2) - 1.0).abs() < 1e-9);
        assert!((gain(0.5) - 1.0).abs() < 1e-9);
        assert!((gain(0.0) - 1.0).abs() < 1e-9);
        assert!((gain(f64::NAN) - 1.0).abs() < 1e-9);
        assert!((gain(1e-300) - 1.0).abs() >= 1.0, "finite and large");
        assert!(gain(1e-300).is_finite());
    }
}
