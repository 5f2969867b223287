//! Widgets that draw the app's state into ratatui buffers: they draw, never decide. Nothing
//! imports `ui` but `main` (and the explorer loop).

mod dialogs;
mod help;
mod params;
mod portrait;
mod series;
mod status;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};

use crate::app::App;
use crate::app::keys::{FOOTER, REPLAY_FOOTER};
use crate::scenario::theme::{Colour, ThemeSpec};

/// Smallest terminal the explorer draws into.
pub const MIN_SIZE: (u16, u16) = (80, 24);

/// Colours of the interface (a 16-colour default that reads well over plain SSH).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Theme {
    /// Background energy levels.
    pub contour: Color,
    /// The separatrix.
    pub separatrix: Color,
    /// The start's own level.
    pub start_level: Color,
    /// The full trajectory.
    pub trail: Color,
    /// The effective trajectory.
    pub effective: Color,
    /// The current point.
    pub current: Color,
    /// Reversal ticks.
    pub reversal: Color,
    /// Error messages.
    pub error: Color,
    /// Axis labels and secondary text.
    pub dim: Color,
}

impl Default for Theme {
    fn default() -> Self {
        Self {
            contour: Color::DarkGray,
            separatrix: Color::Yellow,
            start_level: Color::Cyan,
            trail: Color::Green,
            effective: Color::Magenta,
            current: Color::Red,
            reversal: Color::Yellow,
            error: Color::Red,
            dim: Color::Gray,
        }
    }
}

/// How to draw.
#[derive(Clone, Debug)]
pub struct UiOptions {
    /// Canvas marker (`--marker`).
    pub marker: Marker,
    /// The themes `T` cycles through, the starting one first.
    pub themes: Vec<Theme>,
}

impl Default for UiOptions {
    fn default() -> Self {
        Self {
            marker: Marker::Braille,
            themes: vec![Theme::default()],
        }
    }
}

impl UiOptions {
    /// Options starting from `first`, then every other available theme; `no_color` (the
    /// `NO_COLOR` convention) drops every colour, leaving the bold and reverse-video cues that
    /// do not depend on it.
    #[must_use]
    pub fn new(marker: Marker, first: &ThemeSpec, no_color: bool) -> Self {
        let mut themes = vec![Theme::from_spec(first, no_color)];
        for (_, spec) in crate::scenario::theme::themes().0 {
            let t = Theme::from_spec(&spec, no_color);
            if !themes.contains(&t) {
                themes.push(t);
            }
        }
        Self { marker, themes }
    }

    fn look(&self, theme: usize) -> Look {
        Look {
            marker: self.marker,
            theme: self.themes[theme % self.themes.len().max(1)],
        }
    }
}

/// The marker and the theme in use for one frame.
#[derive(Clone, Copy, Debug)]
pub struct Look {
    /// Canvas marker.
    pub marker: Marker,
    /// Colours.
    pub theme: Theme,
}

fn colour(c: Colour, no_color: bool) -> Color {
    if no_color {
        return Color::Reset;
    }
    match c {
        Colour::Default => Color::Reset,
        Colour::Rgb(r, g, b) => Color::Rgb(r, g, b),
        Colour::Ansi(i) => match i {
            0 => Color::Black,
            1 => Color::Red,
            2 => Color::Green,
            3 => Color::Yellow,
            4 => Color::Blue,
            5 => Color::Magenta,
            6 => Color::Cyan,
            7 => Color::Gray,
            8 => Color::DarkGray,
            9 => Color::LightRed,
            10 => Color::LightGreen,
            11 => Color::LightYellow,
            12 => Color::LightBlue,
            13 => Color::LightMagenta,
            14 => Color::LightCyan,
            _ => Color::White,
        },
    }
}

impl Theme {
    /// The colours of a validated theme (all `Reset` under `NO_COLOR`).
    #[must_use]
    pub fn from_spec(spec: &ThemeSpec, no_color: bool) -> Self {
        let c = |role: &str| colour(spec.colour(role), no_color);
        Self {
            contour: c("contour"),
            separatrix: c("separatrix"),
            start_level: c("start_level"),
            trail: c("trail"),
            effective: c("effective"),
            current: c("current"),
            reversal: c("reversal"),
            error: c("error"),
            dim: c("dim"),
        }
    }
}

/// Draws the whole screen.
pub fn draw(frame: &mut Frame<'_>, app: &mut App, options: &UiOptions) {
    let look = options.look(app.theme);
    let options = &look;
    let area = frame.area();
    if area.width < MIN_SIZE.0 || area.height < MIN_SIZE.1 {
        let text = format!(
            "terminal too small: {}x{} needed, this one is {}x{}",
            MIN_SIZE.0, MIN_SIZE.1, area.width, area.height
        );
        frame.render_widget(Paragraph::new(text).wrap(Wrap { trim: true }), area);
        return;
    }
    let [main, status_area, footer] = Layout::vertical([
        Constraint::Min(0),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    let [left, right] =
        Layout::horizontal([Constraint::Length(30), Constraint::Min(0)]).areas(main);
    params::draw(frame, left, app, options);
    if app.show_series {
        let [top, bottom] =
            Layout::vertical([Constraint::Percentage(65), Constraint::Percentage(35)]).areas(right);
        portrait::draw(frame, top, app, options);
        series::draw(frame, bottom, app, options);
    } else {
        portrait::draw(frame, right, app, options);
    }
    status::draw(frame, status_area, app, options);
    draw_footer(
        frame,
        footer,
        if app.replaying { REPLAY_FOOTER } else { FOOTER },
        options,
    );
    if app.show_help {
        help::draw(frame, area, options);
    }
    if app.picker.is_some() {
        dialogs::picker(frame, area, app, options);
    }
    if let Some(text) = &app.dialog {
        dialogs::error(frame, area, text, options);
    }
}

fn draw_footer(frame: &mut Frame<'_>, area: Rect, hints: &[(&str, &str)], options: &Look) {
    let mut spans = Vec::new();
    for (i, (key, what)) in hints.iter().enumerate() {
        if i > 0 {
            spans.push(Span::styled(" · ", Style::default().fg(options.theme.dim)));
        }
        spans.push(Span::styled(
            *key,
            Style::default().add_modifier(Modifier::BOLD),
        ));
        spans.push(Span::raw(format!(" {what}")));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}
