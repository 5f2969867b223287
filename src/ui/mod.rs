//! Widgets that draw the app's state into ratatui buffers: they draw, never decide. Each panel
//! is a widget struct that borrows only what it draws (`ParamsPanel`, `PortraitPane`,
//! `SeriesPane`, `StatusBar`); `draw` builds them from `&App`. Nothing imports `ui` but the explorer loop (and the cast export above
//! both). The only state of its own is the [`Cache`] of level sets, keyed by what they depend
//! on.
//!
//! ```text
//! ┌ name ──────────┐┌ phase portrait ─────────────────────────┐
//! │ parameters     ││ level sets, separatrix, trail, limit    │
//! │ derived values ││                                          │
//! │ message        │├ time series (t) ─────────────────────────┤
//! │                ││ alpha_dot, limit, reversals, energy error│
//! │                │├ k-sweep (K) ──────────────────────────────┤
//! │                ││ sup |α_k − α_eff| against k, log–log      │
//! │                │├ weak-* (W), regime map (M) ───────────────┤
//! └────────────────┘└──────────────────────────────────────────┘
//!  ▌ chapter / note (when there is one)
//!  status: time, state, speed, reversals, energy error, method…   (fields dropped by priority)
//!  footer: key hints from the keymap table (? help and q quit always kept)
//! ```

mod body;
mod compare;
mod dialogs;
pub mod glyphs;
mod help;
mod lesson;
mod map;
mod params;
mod portrait;
mod series;
mod status;
mod sweep;
mod weak;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use crate::app::keys::{self, Hint, KEYMAP, REPLAY_KEYMAP};
use crate::app::panes::Pane;
use crate::app::{App, Mode};
use crate::scenario::theme::{Colour, ThemeSpec};

pub use body::envelope as body_envelope;
pub use portrait::Cache;

/// A plot's areas inside a pane: the y labels (8 columns), the plot, the x labels (one row).
fn plot_areas(inner: Rect) -> (Rect, Rect, Rect) {
    let [y_axis, rest] =
        Layout::horizontal([Constraint::Length(8), Constraint::Min(0)]).areas(inner);
    let [plot, x_axis] = Layout::vertical([Constraint::Min(1), Constraint::Length(1)]).areas(rest);
    (y_axis, plot, x_axis)
}

/// Rows a lesson step's own pane gets at least.
pub const ASKED_ROWS: u16 = 8;

/// The lesson's rows: what its text needs, up to 60 % of the column. The pane the step is about
/// gets at least [`ASKED_ROWS`]: on a short column the other panes give way (they leave
/// `column`), then the lesson's text (it keeps its title and a few rows).
fn lesson_rows(app: &App, column: &mut Vec<(Pane, u16)>, need: u16, height: u16) -> u16 {
    let rows = need.min(height * 3 / 5);
    let asked = app
        .lesson
        .as_ref()
        .and_then(|s| s.current().pane.as_deref())
        .and_then(Pane::named)
        .filter(|p| column.iter().any(|(q, _)| q == p));
    let Some(a) = asked else {
        return rows;
    };
    let others: u32 = column
        .iter()
        .filter(|(p, _)| *p != Pane::Lesson)
        .map(|(_, w)| u32::from(*w))
        .sum();
    let room = u32::from(height.saturating_sub(rows));
    if room * u32::from(a.weight()) < u32::from(ASKED_ROWS) * others.max(1) {
        column.retain(|(p, _)| *p == Pane::Lesson || *p == a);
    }
    rows.min(height.saturating_sub(ASKED_ROWS).max(3))
}

/// The right-hand column: the visible panes, stacked by weight.
fn draw_column(frame: &mut Frame<'_>, app: &App, right: Rect, look: &Look<'_>, cache: &mut Cache) {
    let mut column = app.view.panes.column();
    // On a short terminal the body or the comparison takes the portrait's place (B or C brings
    // the portrait back).
    if right.height < 30
        && (app.view.panes.shows(Pane::Body) || app.view.panes.shows(Pane::Compare))
    {
        column.retain(|(p, _)| *p != Pane::Portrait);
    }
    let look_ref = look;
    let lesson_pane = app.lesson.as_ref().map(|state| lesson::LessonPane {
        lesson: state,
        missing: app.lesson_missing(),
        look: look_ref,
    });
    let lesson_rows = lesson_pane.as_ref().map_or(0, |p| {
        lesson_rows(app, &mut column, p.height(right.width), right.height)
    });
    let areas = Layout::vertical(column.iter().map(|(p, w)| match p {
        Pane::Lesson if lesson_pane.is_some() => Constraint::Length(lesson_rows),
        _ => Constraint::Fill(*w),
    }))
    .split(right);
    for ((pane, _), area) in column.iter().zip(areas.iter()) {
        draw_pane(frame, app, *pane, *area, look, cache);
    }
}

/// One pane of the column.
fn draw_pane(
    frame: &mut Frame<'_>,
    app: &App,
    pane: Pane,
    area: Rect,
    look: &Look<'_>,
    cache: &mut Cache,
) {
    match pane {
        Pane::Portrait => frame.render_stateful_widget(
            portrait::PortraitPane {
                scenario: &app.scenario,
                run: &app.run,
                view: &app.view,
                bounds: app.bounds(),
                look,
            },
            area,
            cache,
        ),
        Pane::Series => frame.render_widget(
            series::SeriesPane {
                run: &app.run,
                overlay: app.view.overlay,
                model: app.scenario.settings.model.kind(),
                look,
            },
            area,
        ),
        Pane::Sweep => frame.render_widget(
            sweep::SweepPane {
                model: app.scenario.settings.model.kind(),
                sweep: &app.computed.sweep,
                look,
            },
            area,
        ),
        Pane::Weak => frame.render_widget(
            weak::WeakPane {
                weak: &app.computed.weak,
                look,
            },
            area,
        ),
        Pane::Map => frame.render_widget(
            map::MapPane {
                map: &app.computed.map,
                focused: app.mode == Mode::Map,
                look,
            },
            area,
        ),
        Pane::Lesson => {
            if let Some(state) = &app.lesson {
                frame.render_widget(
                    lesson::LessonPane {
                        lesson: state,
                        missing: app.lesson_missing(),
                        look,
                    },
                    area,
                );
            }
        }
        Pane::Body => frame.render_widget(
            body::BodyPane {
                run: &app.run,
                aspect: app
                    .scenario
                    .settings
                    .model
                    .plan_view()
                    .map_or(1.0, |[x, y]| y / x),
                fast: app.scenario.settings.model.kind().words().fast_name,
                side: app.scenario.settings.model.side_view(),
                look,
            },
            area,
        ),
        Pane::Compare => frame.render_widget(
            compare::ComparePane {
                run: &app.run,
                scenario: &app.scenario,
                compare: &app.computed.compare,
                look,
            },
            area,
        ),
        Pane::Params => {}
    }
}

/// Smallest terminal the explorer draws into.
pub const MIN_SIZE: (u16, u16) = (80, 24);
/// Width of the parameter column.
pub const PARAMS_WIDTH: u16 = 30;

/// Colours of the interface (a 16-colour default that reads well over plain SSH).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Theme {
    /// Its name (what `T` announces).
    pub name: String,
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
    /// Background of the whole screen (`Reset`: the terminal's).
    pub background: Color,
    /// Plain text (`Reset`: the terminal's).
    pub text: Color,
}

impl Default for Theme {
    fn default() -> Self {
        Self {
            name: "Default (16 colours)".to_owned(),
            contour: Color::DarkGray,
            separatrix: Color::Yellow,
            start_level: Color::Cyan,
            trail: Color::Green,
            effective: Color::Magenta,
            current: Color::Red,
            reversal: Color::Yellow,
            error: Color::Red,
            dim: Color::Gray,
            background: Color::Reset,
            text: Color::Reset,
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
    /// `NO_COLOR`: every colour is off; shapes, density and bold tell the curves apart.
    pub no_color: bool,
    /// What the terminal can show ([`glyphs::Charset::detect`]); other than Unicode, every
    /// canvas draws one point per cell and every cell is folded into the set.
    pub charset: glyphs::Charset,
    /// The key hints on the last row (off in an exported cast or page: nobody can press them).
    pub footer: bool,
}

impl Default for UiOptions {
    fn default() -> Self {
        Self {
            marker: Marker::Braille,
            themes: vec![Theme::default()],
            no_color: false,
            charset: glyphs::Charset::Unicode,
            footer: true,
        }
    }
}

impl UiOptions {
    /// Options starting from `first`, then every other theme of `all`; `no_color` (the
    /// `NO_COLOR` convention) drops every colour, leaving the shapes, bold and reverse-video
    /// cues that do not depend on it.
    #[must_use]
    pub fn new(marker: Marker, first: &ThemeSpec, all: &[ThemeSpec], no_color: bool) -> Self {
        let mut themes = vec![Theme::from_spec(first, no_color)];
        for spec in all {
            let t = Theme::from_spec(spec, no_color);
            if !themes.iter().any(|x| x.name == t.name) {
                themes.push(t);
            }
        }
        Self {
            marker,
            themes,
            no_color,
            charset: glyphs::Charset::Unicode,
            footer: true,
        }
    }

    /// The same options without the key hints (an exported cast or page).
    #[must_use]
    pub fn without_footer(self) -> Self {
        Self {
            footer: false,
            ..self
        }
    }

    /// The same options for a terminal that shows `charset`.
    #[must_use]
    pub fn with_charset(self, charset: glyphs::Charset) -> Self {
        Self { charset, ..self }
    }

    /// The theme names, in `T` order.
    #[must_use]
    pub fn theme_names(&self) -> Vec<String> {
        self.themes.iter().map(|t| t.name.clone()).collect()
    }

    fn look(&self, theme: usize) -> Look<'_> {
        Look {
            // Braille and half blocks need glyphs only the Unicode set has.
            marker: if self.charset == glyphs::Charset::Unicode {
                self.marker
            } else {
                Marker::Dot
            },
            theme: &self.themes[theme % self.themes.len().max(1)],
            no_color: self.no_color,
            charset: self.charset,
        }
    }
}

/// The marker and the theme in use for one frame.
#[derive(Clone, Copy, Debug)]
pub struct Look<'a> {
    /// Canvas marker.
    pub marker: Marker,
    /// Colours.
    pub theme: &'a Theme,
    /// No colours at all.
    pub no_color: bool,
    /// What the terminal shows.
    pub charset: glyphs::Charset,
}

impl Look<'_> {
    /// Secondary text.
    fn dim(&self) -> Style {
        Style::default().fg(self.theme.dim)
    }
}

fn colour(c: Colour, no_color: bool) -> Color {
    if no_color {
        return Color::Reset;
    }
    match c {
        Colour::Default => Color::Reset,
        Colour::Rgb(r, g, b) => Color::Rgb(r, g, b),
        Colour::Indexed(i) => Color::Indexed(i),
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
            name: crate::scenario::text::clean(&spec.name),
            contour: c("contour"),
            separatrix: c("separatrix"),
            start_level: c("start_level"),
            trail: c("trail"),
            effective: c("effective"),
            current: c("current"),
            reversal: c("reversal"),
            error: c("error"),
            dim: c("dim"),
            background: c("background"),
            text: c("text"),
        }
    }
}

/// The portrait point `(alpha, alpha_dot)` under the terminal cell `(column, row)`, if the last
/// frame drew the portrait there.
#[must_use]
pub fn portrait_point(cache: &Cache, column: u16, row: u16) -> Option<(f64, f64)> {
    let (plot, b) = cache.plot?;
    let inside = (plot.x..plot.x + plot.width).contains(&column)
        && (plot.y..plot.y + plot.height).contains(&row);
    if !inside {
        return None;
    }
    let fx = (f64::from(column - plot.x) + 0.5) / f64::from(plot.width);
    let fy = (f64::from(row - plot.y) + 0.5) / f64::from(plot.height);
    Some((
        b.x[0] + fx * (b.x[1] - b.x[0]),
        b.y[1] - fy * (b.y[1] - b.y[0]),
    ))
}

/// Draws the whole screen from `app`; `cache` keeps the level sets between frames.
pub fn draw(frame: &mut Frame<'_>, app: &App, options: &UiOptions, cache: &mut Cache) {
    draw_screen(frame, app, options, cache);
    glyphs::fold_buffer(frame.buffer_mut(), options.charset);
}

fn draw_screen(frame: &mut Frame<'_>, app: &App, options: &UiOptions, cache: &mut Cache) {
    let look = options.look(app.view.theme);
    let area = frame.area();
    frame.render_widget(
        Block::new().style(
            Style::default()
                .bg(look.theme.background)
                .fg(look.theme.text),
        ),
        area,
    );
    if area.width < MIN_SIZE.0 || area.height < MIN_SIZE.1 {
        let text = format!(
            "terminal too small: {}x{} needed, this one is {}x{} (q quits)",
            MIN_SIZE.0, MIN_SIZE.1, area.width, area.height
        );
        frame.render_widget(Paragraph::new(text).wrap(Wrap { trim: true }), area);
        return;
    }
    let caption = u16::from(app.caption.is_some());
    let message = app.status.as_ref().map(|m| {
        (
            wrap_words(
                &m.text,
                area.width.saturating_sub(2) as usize,
                MESSAGE_LINES,
            ),
            m.error,
        )
    });
    let message_height = message.as_ref().map_or(0, |(lines, _)| lines.len() as u16);
    let [main, caption_area, message_area, status_area, footer] = Layout::vertical([
        Constraint::Min(0),
        Constraint::Length(caption),
        Constraint::Length(message_height),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    let [left, right] =
        Layout::horizontal([Constraint::Length(PARAMS_WIDTH), Constraint::Min(0)]).areas(main);
    let (editing, prompt) = match &app.mode {
        Mode::Editing(text) => (Some(text.as_str()), None),
        Mode::Prompt(p) => (None, Some(p)),
        _ => (None, None),
    };
    frame.render_widget(
        params::ParamsPanel {
            scenario: &app.scenario,
            editing,
            prompt,
            look: &look,
        },
        left,
    );
    draw_column(frame, app, right, &look, cache);
    if let Some(c) = &app.caption {
        draw_caption(frame, caption_area, c, &look);
    }
    if let Some((lines, error)) = message {
        draw_message(frame, message_area, lines, error, &look);
    }
    frame.render_widget(
        status::StatusBar {
            run: &app.run,
            settings: &app.scenario.settings,
            replay: app.replay,
            recording: app.journal.state != crate::app::RecState::Off,
            overlay: app.view.overlay,
        },
        status_area,
    );
    let owned = |h: Vec<Hint>| -> Vec<FooterHint> {
        h.into_iter()
            .map(|(k, w, r)| (k.to_owned(), w, r))
            .collect()
    };
    let hints = if app.replay.is_some() {
        owned(keys::footer(REPLAY_KEYMAP))
    } else if app.mode == Mode::Map {
        owned(keys::MAP_FOOTER.to_vec())
    } else {
        // The user's keys where an action lost its defaults.
        app.options.keys.footer(&KEYMAP)
    };
    if options.footer {
        draw_footer(frame, footer, &hints, &look);
    }
    match &app.mode {
        Mode::Help(page) => help::draw(
            frame,
            area,
            (*page, app.replay.is_some()),
            &app.options.keys,
            &look,
        ),
        Mode::Picker(p) => dialogs::picker(frame, area, p, &look),
        Mode::Dialog(text) => dialogs::error(frame, area, text, &look),
        _ => {}
    }
}

fn draw_caption(frame: &mut Frame<'_>, area: Rect, c: &crate::app::Caption, look: &Look) {
    let kind = if c.chapter { "chapter" } else { "note" };
    let text = c.text.replace(['\n', '\t'], " ");
    let head = format!(" ▌ {kind} (t {:.2}): ", c.t);
    let room = (area.width as usize).saturating_sub(head.chars().count());
    frame.render_widget(
        Paragraph::new(Line::from(vec![
            Span::styled(head, look.dim()),
            Span::styled(
                crate::app::ellipsis(&text, room),
                Style::default().add_modifier(Modifier::BOLD),
            ),
        ])),
        area,
    );
}

/// The message line(s) above the status bar, in the error colour for an error.
fn draw_message(frame: &mut Frame<'_>, area: Rect, lines: Vec<String>, error: bool, look: &Look) {
    let style = if error {
        Style::default()
            .fg(look.theme.error)
            .add_modifier(Modifier::BOLD)
    } else {
        Style::default()
    };
    let text: Vec<Line> = lines
        .into_iter()
        .map(|l| Line::styled(format!(" {l}"), style))
        .collect();
    frame.render_widget(Paragraph::new(text), area);
}

/// Most rows a message takes above the status bar.
const MESSAGE_LINES: usize = 3;

/// `text` wrapped at spaces into at most `most` lines of `width` characters: a word is cut only
/// when it is longer than a whole line (a long path), and the last line ends in `…` when the text
/// does not fit.
#[must_use]
pub fn wrap_words(text: &str, width: usize, most: usize) -> Vec<String> {
    let width = width.max(8);
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let mut word: Vec<char> = word.chars().collect();
        loop {
            let used = line.chars().count();
            let room = if used == 0 {
                width
            } else {
                width.saturating_sub(used + 1)
            };
            if word.len() <= room {
                if used > 0 {
                    line.push(' ');
                }
                line.extend(word.iter());
                break;
            }
            if used == 0 {
                // Longer than a line: cut it.
                line.extend(word.drain(..width));
            }
            lines.push(std::mem::take(&mut line));
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    if lines.len() > most {
        lines.truncate(most);
        let last = &mut lines[most - 1];
        let keep: String = last.chars().take(width.saturating_sub(1)).collect();
        *last = format!("{keep}…");
    }
    lines
}

/// A footer hint as drawn: the keys (the user's, where they replace the defaults), the word,
/// the rank.
pub type FooterHint = (String, &'static str, u8);

/// The hints that fit in `width`, dropping the highest ranks first; rank 0 always stays.
#[must_use]
pub fn fit_hints<K: AsRef<str> + Clone>(
    hints: &[(K, &'static str, u8)],
    width: usize,
) -> Vec<(K, &'static str, u8)> {
    let len = |h: &[(K, &'static str, u8)]| -> usize {
        h.iter()
            .map(|(k, w, _)| k.as_ref().chars().count() + 1 + w.chars().count())
            .sum::<usize>()
            + 3 * h.len().saturating_sub(1)
    };
    let mut kept = hints.to_vec();
    while len(&kept) > width {
        let Some(worst) = kept
            .iter()
            .enumerate()
            .filter(|(_, h)| h.2 > 0)
            .max_by_key(|(i, h)| (h.2, *i))
            .map(|(i, _)| i)
        else {
            break;
        };
        kept.remove(worst);
    }
    kept
}

fn draw_footer(frame: &mut Frame<'_>, area: Rect, hints: &[FooterHint], look: &Look) {
    let mut spans = Vec::new();
    for (i, (key, what, _)) in fit_hints(hints, area.width as usize)
        .into_iter()
        .enumerate()
    {
        if i > 0 {
            // ASCII would fold `·` into `.`, which the keys use.
            let sep = if look.charset == glyphs::Charset::Ascii {
                " | "
            } else {
                " · "
            };
            spans.push(Span::styled(sep, look.dim()));
        }
        spans.push(Span::styled(
            key,
            Style::default().add_modifier(Modifier::BOLD),
        ));
        spans.push(Span::raw(format!(" {what}")));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

/// Draws a bordered pane titled `text` (cut to fit) over `area`; returns its inside.
fn framed(text: &str, area: Rect, buf: &mut ratatui::buffer::Buffer) -> Rect {
    let block = Block::bordered().title(title(text, area.width));
    let inner = block.inner(area);
    ratatui::widgets::Widget::render(block, area, buf);
    inner
}

/// A block title cut to fit `width` columns, ending in `…` when cut.
fn title(text: &str, width: u16) -> String {
    format!(
        " {} ",
        crate::app::ellipsis(text, (width as usize).saturating_sub(4))
    )
}
