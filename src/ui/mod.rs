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

mod axis;
mod body;
mod compare;
mod dialogs;
mod figure;
pub mod glyphs;
pub mod help;
pub mod legend;
mod lesson;
mod map;
pub mod marks;
mod options;
pub mod params;
mod pendulum;
mod portrait;
pub mod qr;
mod series;
pub mod status;
mod sweep;
mod weak;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use crate::app::keys::{self, Hint, KEYMAP};
use crate::app::lesson::LessonState;
use crate::app::panes::Pane;
use crate::app::{App, Mode};
use crate::scenario::theme::{Colour, ThemeSpec};

pub use body::envelope as body_envelope;
pub use options::UiOptions;
pub use params::HIDDEN;
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

/// Rows a pane needs to be read, its borders included: 8 inside the box for a plot and its axis
/// (the portrait, the series' trace, energy strip and time axis), more for the body's views
/// and the comparison's two lanes.
#[must_use]
pub fn min_rows(pane: Pane) -> u16 {
    match pane {
        Pane::Portrait | Pane::Series | Pane::Sweep | Pane::Weak | Pane::Map => 10,
        Pane::Body => 13,
        Pane::Compare => 12,
        Pane::Lesson | Pane::Params => 0,
    }
}

/// Where the right-hand column puts its panes: the panes shown, each with its area, in layout
/// order; and where the open panes that did not fit are named (on the last pane's bottom
/// border; Tab brings the next).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ColumnLayout {
    /// The panes drawn.
    pub panes: Vec<(Pane, Rect)>,
    /// The border row naming the panes open but not drawn, and those panes.
    pub hidden: Option<(Rect, Vec<Pane>)>,
}

/// The right-hand column's layout. A lesson takes what its text needs (up to 60 % of the
/// column), the pane its step asks about first; then the most recently opened pane, the
/// portrait and the other open panes, most recent first, each while there is room for it to be
/// read ([`min_rows`]); what does not fit is listed on a line of its own, never squeezed. Every
/// pane drawn gets its rows, and what is left is shared by weight.
#[must_use]
pub fn column_layout(app: &App, right: Rect) -> ColumnLayout {
    let panes = app.view.panes;
    let visible: Vec<Pane> = panes.column().into_iter().map(|(p, _)| p).collect();
    let asked = app
        .lesson
        .as_ref()
        .and_then(|s| s.current().pane.as_deref())
        .and_then(Pane::named)
        .filter(|p| visible.contains(p));
    let lesson_rows = app.lesson.as_ref().map_or(0, |state| {
        let look = UiOptions::default();
        let look = look.look(0);
        let need = lesson::LessonPane {
            lesson: state,
            missing: app.lesson_missing(),
            look: &look,
        }
        .height(right.width);
        // The pane the step asks about (else the portrait) keeps its rows.
        let first = asked.or(visible.contains(&Pane::Portrait).then_some(Pane::Portrait));
        need.min(right.height * 3 / 5)
            .min(right.height.saturating_sub(first.map_or(0, min_rows)))
            .max(3)
    });
    // In order of claim: the asked pane, the front pane, the portrait, the others by recency.
    let mut optional: Vec<Pane> = visible
        .iter()
        .copied()
        .filter(|p| !matches!(p, Pane::Portrait | Pane::Lesson) && Some(*p) != asked)
        .collect();
    optional.sort_by_key(|p| std::cmp::Reverse(panes.recency(*p)));
    let mut claims: Vec<Pane> = asked.into_iter().collect();
    let mut rest = optional.into_iter();
    let front = if asked.is_none() { rest.next() } else { None };
    let portrait = visible.contains(&Pane::Portrait).then_some(Pane::Portrait);
    // The portrait claims before the front pane once Tab has brought it forward.
    if front.is_some_and(|f| panes.recency(Pane::Portrait) > panes.recency(f)) {
        claims.extend(portrait);
        claims.extend(front);
    } else {
        claims.extend(front);
        claims.extend(portrait);
    }
    claims.extend(rest);
    let height = right.height.saturating_sub(lesson_rows);
    let all: u16 = claims.iter().map(|p| min_rows(*p)).sum();
    let mut kept = Vec::new();
    let mut hidden = Vec::new();
    if all <= height {
        kept = claims;
    } else {
        // One line lists what does not fit.
        // In order of claim, until one does not fit: the rest wait their turn (Tab).
        let mut room = height;
        for p in claims {
            if hidden.is_empty() && (min_rows(p) <= room || kept.is_empty()) {
                room = room.saturating_sub(min_rows(p));
                kept.push(p);
            } else {
                hidden.push(p);
            }
        }
    }
    let area = right;
    let mut out = ColumnLayout::default();
    // Layout order; the lesson first with its rows; each pane its rows, the rest by weight.
    let order: Vec<Pane> = visible
        .into_iter()
        .filter(|p| *p == Pane::Lesson && lesson_rows > 0 || kept.contains(p))
        .collect();
    out.panes = stack(&order, lesson_rows, area);
    // The panes that wait are named on the last pane's bottom border: no row is taken.
    if !hidden.is_empty()
        && let Some((_, last)) = out.panes.last()
        && last.height > 0
    {
        let line = Rect {
            x: last.x + 1,
            y: last.y + last.height - 1,
            width: last.width.saturating_sub(2),
            height: 1,
        };
        out.hidden = Some((line, hidden));
    }
    out
}

/// `order`'s panes stacked over `area`: each its rows ([`min_rows`], the lesson
/// `lesson_rows`), what is left shared by weight.
fn stack(order: &[Pane], lesson_rows: u16, area: Rect) -> Vec<(Pane, Rect)> {
    let rows = |p: Pane| {
        if p == Pane::Lesson {
            lesson_rows
        } else {
            min_rows(p)
        }
    };
    let spare = area
        .height
        .saturating_sub(order.iter().map(|p| rows(*p)).sum::<u16>());
    let weights: u32 = order
        .iter()
        .filter(|p| **p != Pane::Lesson)
        .map(|p| u32::from(p.weight()))
        .sum::<u32>()
        .max(1);
    let mut given = 0;
    let mut y = area.y;
    let last = order.iter().rposition(|p| *p != Pane::Lesson);
    let mut out = Vec::new();
    for (i, p) in order.iter().enumerate() {
        let extra = if *p == Pane::Lesson {
            0
        } else if Some(i) == last {
            spare - given
        } else {
            let e = (u32::from(spare) * u32::from(p.weight()) / weights) as u16;
            given += e;
            e
        };
        let h = (rows(*p) + extra).min(area.y + area.height - y);
        out.push((
            *p,
            Rect {
                y,
                height: h,
                ..area
            },
        ));
        y += h;
    }
    out
}

/// The right-hand column: the panes that fit, and a line naming the others.
fn draw_column(frame: &mut Frame<'_>, app: &App, right: Rect, look: &Look<'_>, cache: &mut Cache) {
    let layout = column_layout(app, right);
    for (pane, area) in &layout.panes {
        draw_pane(frame, app, *pane, *area, look, cache);
    }
    if let Some((line, hidden)) = layout.hidden {
        let names: Vec<String> = hidden
            .iter()
            .map(|p| match crate::app::keys::pane_binding(*p) {
                Some(b) => format!("{} {}", p.key(), key_of(&b)),
                None => p.key(),
            })
            .collect();
        // Tab brings the next pane to the front, the portrait included (issue 68).
        let text = format!(" more: {} · Tab cycles ", names.join(" · "));
        let text = crate::app::ellipsis(&text, line.width as usize);
        let width = text.chars().count() as u16;
        let at = Rect {
            x: line.x + line.width.saturating_sub(width),
            width: width.min(line.width),
            ..line
        };
        frame.render_widget(
            Paragraph::new(Line::styled(
                text,
                look.dim().add_modifier(Modifier::REVERSED),
            )),
            at,
        );
    }
}

/// The key a binding's row shows it with.
fn key_of(b: &crate::app::keys::Binding<crate::app::Action>) -> String {
    b.keys
        .first()
        .map(|k| crate::app::user_keys::key_label(*k))
        .unwrap_or_default()
}

/// What a pane draws, for the legend (each widget's own `legend`, beside its `draw_pane` arm).
#[must_use]
pub fn pane_legend(
    pane: Pane,
    facts: &marks::Facts<'_>,
    look: &Look<'_>,
) -> Option<marks::Section> {
    Some(match pane {
        Pane::Series => series::legend(facts, look),
        Pane::Sweep => sweep::legend(facts, look),
        Pane::Weak => weak::legend(facts, look),
        Pane::Map => map::legend(facts, look),
        Pane::Body => body::legend(facts, look),
        Pane::Compare => compare::legend(facts, look),
        Pane::Portrait => portrait::legend(facts, look),
        Pane::Params | Pane::Lesson => return None,
    })
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
                focused: app.mode == Mode::Map || app.computed.map.replayed_focus,
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
                drawing: app.scenario.settings.model.drawing(),
                words: app.scenario.settings.model.kind().words(),
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

/// The areas of the screen: the panel, the column, the caption, the message, the status bar and
/// the footer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Screen {
    /// The parameter panel.
    pub left: Rect,
    /// The column of panes ([`column_layout`]).
    pub right: Rect,
    /// The note or chapter line.
    pub caption: Rect,
    /// The message's lines.
    pub message: Rect,
    /// The status bar.
    pub status: Rect,
    /// The key hints.
    pub footer: Rect,
}

/// The message's lines (at most [`MESSAGE_LINES`]; a message cut short says `v` shows it
/// whole) and whether it is an error.
fn message_lines(app: &App, width: u16) -> Option<(Vec<String>, bool)> {
    app.status.as_ref().map(|m| {
        let width = width.saturating_sub(2) as usize;
        let mut lines = wrap_words(&fit_long_words(&m.text, width), width, MESSAGE_LINES);
        if let Some(last) = lines.last_mut()
            && last.ends_with('…')
        {
            // While a value or a prompt is typed `v` is text: no key is offered then (issue 81).
            let hint = if matches!(app.mode, Mode::Editing(_) | Mode::Prompt(_)) {
                ""
            } else {
                " (v: whole)"
            };
            let keep: String = last
                .trim_end_matches('…')
                .chars()
                .take(width.saturating_sub(hint.chars().count() + 1))
                .collect();
            *last = format!("{keep}…{hint}");
        }
        (lines, m.error)
    })
}

/// Where everything goes on a screen of `area` (at least [`MIN_SIZE`]).
#[must_use]
pub fn screen(app: &App, area: Rect) -> Screen {
    let caption = u16::from(app.caption.is_some());
    // The message line is always there, blank when there is no message: a message never moves
    // the panes (a recording's frames are the same for the lecturer, who sees "recording to
    // …", and for the follower and the cast, who do not: issue 55).
    let [main, caption, message, status, footer] = Layout::vertical([
        Constraint::Min(0),
        Constraint::Length(caption),
        Constraint::Length(MESSAGE_LINES as u16),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    let [left, right] =
        Layout::horizontal([Constraint::Length(PARAMS_WIDTH), Constraint::Min(0)]).areas(main);
    Screen {
        left,
        right,
        caption,
        message,
        status,
        footer,
    }
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
    let message = message_lines(app, area.width);
    let Screen {
        left,
        right,
        caption: caption_area,
        message: message_area,
        status: status_area,
        footer,
    } = screen(app, area);
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
            hide_predictions: app.lesson.as_ref().is_some_and(LessonState::answer_hidden),
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
            recording: app.journal.state != crate::app::RecState::Off || options.recorded,
            overlay: app.view.overlay,
        },
        status_area,
    );
    let owned = |h: Vec<Hint>| -> Vec<FooterHint> {
        h.into_iter()
            .map(|(k, w, r)| (k.to_owned(), w, r))
            .collect()
    };
    let hints = if let Some(replay) = app.replay {
        owned(keys::replay_footer(replay))
    } else if app.mode == Mode::Map {
        let kind = app.scenario.settings.model.kind();
        owned(keys::map_footer(crate::study::chart::words(kind).sources))
    } else if matches!(app.mode, Mode::Editing(_) | Mode::Prompt(_)) {
        // Typing: the keys are text; the footer says what ends it (issue 81, D-3).
        owned(keys::PROMPT_FOOTER.to_vec())
    } else {
        // The user's keys where an action lost its defaults; the words say what a key does
        // now (`space pause` while playing).
        let mut hints = app.options.keys.footer(&KEYMAP);
        for hint in &mut hints {
            if hint.1 == "play" && app.run.playing {
                hint.1 = "pause";
            }
        }
        hints
    };
    if options.footer {
        draw_footer(frame, footer, &hints, &look);
    }
    match &app.mode {
        Mode::Help(h) => help::draw(frame, area, app, h, &look),
        Mode::Picker(p) => dialogs::picker(frame, area, p, &look),
        Mode::Dialog(text) => dialogs::error(frame, area, text, &look),
        Mode::Address(url) => dialogs::address(frame, area, url, &look),
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

/// `text` with its longest word (a path, a command) shortened in the middle so that the whole
/// fits in `width` columns: `recording to /home/…/subcritical-2026-11-28-101500.jsonl`, not
/// `recording to…`. Text that fits, or whose other words alone do not, is left as it is.
#[must_use]
pub fn fit_long_words(text: &str, width: usize) -> String {
    let n = text.chars().count();
    if n <= width {
        return text.to_owned();
    }
    // Two long words (`x`'s "wrote ….svg and ….csv") share the cut, each keeping its name's
    // end, when each keeps 16 characters at least (issue 81, D-4).
    let words: Vec<&str> = text.split(' ').collect();
    let long: Vec<usize> = (0..words.len())
        .filter(|&i| words[i].chars().count() >= 24)
        .collect();
    if long.len() > 1 {
        let share = (n - width).div_ceil(long.len());
        if long.iter().all(|&i| words[i].chars().count() >= share + 16) {
            return words
                .iter()
                .enumerate()
                .map(|(i, w)| {
                    if long.contains(&i) {
                        crate::scenario::text::middle(w, w.chars().count() - share)
                    } else {
                        (*w).to_owned()
                    }
                })
                .collect::<Vec<_>>()
                .join(" ");
        }
    }
    let Some(longest) = words.iter().copied().max_by_key(|w| w.chars().count()) else {
        return text.to_owned();
    };
    let len = longest.chars().count();
    if len < 24 {
        return text.to_owned();
    }
    // Room to show everything; else room for the word on the first line, before the `…
    // (v: whole)` that ends a message cut short.
    let whole = len.saturating_sub(n - width);
    let before = text[..text.find(longest).unwrap_or(0)].chars().count();
    let on_line = width.saturating_sub(before + 14);
    let room = if whole >= 16 { whole } else { on_line };
    if room < 16 || room >= len {
        return text.to_owned();
    }
    text.replacen(longest, &crate::scenario::text::middle(longest, room), 1)
}

/// Rows a message takes above the status bar (a longer one is cut, and `v` shows it whole).
const MESSAGE_LINES: usize = 1;

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

/// A block title cut to fit `width` columns, ending in `…` when cut: a pane's title says its
/// numbers first (`weak-*: average over w = 1 within 1.34 %`).
fn title(text: &str, width: u16) -> String {
    format!(
        " {} ",
        crate::app::ellipsis(text, (width as usize).saturating_sub(4))
    )
}

/// A block title whose two ends both matter (a preset's name, the picker's keys, the time
/// series' two plots, a lesson's step) shortened to fit `width` columns: whole words taken out
/// of its middle and a `…` in their place (issue 68).
fn title_middle(text: &str, width: u16) -> String {
    format!(
        " {} ",
        middle_words(text, (width as usize).saturating_sub(4))
    )
}

/// [`framed`] with a [`title_middle`].
fn framed_middle(text: &str, area: Rect, buf: &mut ratatui::buffer::Buffer) -> Rect {
    let block = Block::bordered().title(title_middle(text, area.width));
    let inner = block.inner(area);
    ratatui::widgets::Widget::render(block, area, buf);
    inner
}

/// `text` in at most `max` characters, words taken out of its middle (then characters, for a
/// text of one or two long words).
#[must_use]
pub fn middle_words(text: &str, max: usize) -> String {
    // Its length once joined, with `… ` in it when words were taken out.
    let len = |w: &[&str], cut: bool| {
        w.iter().map(|w| w.chars().count()).sum::<usize>()
            + w.len().saturating_sub(1)
            + if cut { 2 } else { 0 }
    };
    let mut words: Vec<&str> = text.split(' ').collect();
    if text.chars().count() <= max {
        return text.to_owned();
    }
    let mut cut = false;
    while words.len() > 2 && len(&words, cut) > max {
        words.remove(words.len() / 2);
        cut = true;
    }
    if cut {
        let at = words.len().div_ceil(2);
        words.insert(at, "…");
    }
    let joined = words.join(" ");
    if joined.chars().count() <= max {
        joined
    } else {
        crate::app::ellipsis(&crate::scenario::text::middle(text, max), max)
    }
}
