//! The help overlay: the keys (generated from the keymap table in use) and, on its second page,
//! the legend of every colour, mark and status field.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

use super::Look;
use super::legend;
use super::marks::Facts;
use crate::app::keys::{Binding, KEYMAP, REPLAY_KEYMAP};
use crate::app::mode::{Help, HelpPage};
use crate::app::user_keys::key_label;
use crate::app::{App, Mode};

/// The rows of a keymap; `extra` gives the user's keys of a row's bindings (a labelled binding
/// and the unlabelled ones after it), added to its label; `replaced` says which actions lost
/// their default keys (`"none"` in `[keys]`): a row with one is labelled with the keys in
/// effect (`none` where an action has none).
fn key_rows<A: Copy>(
    map: &[Binding<A>],
    extra: &dyn Fn(A) -> Vec<String>,
    replaced: &dyn Fn(A) -> bool,
) -> Vec<Line<'static>> {
    let mut groups: Vec<Vec<&Binding<A>>> = Vec::new();
    for b in map {
        match groups.last_mut() {
            Some(g) if b.label.is_empty() => g.push(b),
            _ => groups.push(vec![b]),
        }
    }
    let mut rows: Vec<(String, &'static str)> = Vec::new();
    for group in groups.iter().filter(|g| !g[0].label.is_empty()) {
        let label = if group.iter().any(|b| replaced(b.action)) {
            let per_action: Vec<String> = group
                .iter()
                .map(|b| {
                    let mut keys = if replaced(b.action) {
                        Vec::new()
                    } else {
                        b.keys.iter().map(|k| key_label(*k)).collect()
                    };
                    keys.extend(extra(b.action));
                    if keys.is_empty() {
                        "none".to_owned()
                    } else {
                        keys.join(",")
                    }
                })
                .collect();
            per_action.join(" / ")
        } else {
            let added: Vec<String> = group.iter().flat_map(|b| extra(b.action)).collect();
            if added.is_empty() {
                group[0].label.to_owned()
            } else {
                format!("{} +{}", group[0].label, added.join(","))
            }
        };
        rows.push((label, group[0].help));
    }
    let width = rows
        .iter()
        .map(|(l, _)| l.chars().count() + 1)
        .max()
        .unwrap_or(0)
        .max(13);
    rows.into_iter()
        .map(|(label, help)| {
            Line::from(vec![
                Span::styled(
                    format!(" {label:<width$}"),
                    Style::default().add_modifier(Modifier::BOLD),
                ),
                Span::raw(help),
            ])
        })
        .collect()
}

/// The lines of the help's page, only those its filter shows, and its heading.
fn content(app: &App, help: &Help, look: &Look<'_>) -> (Vec<Line<'static>>, String) {
    let (lines, heading) = page(app, help, look);
    if help.filter.is_empty() {
        let heading = if help.page == HelpPage::Messages || help.passes_on {
            heading.to_owned()
        } else {
            heading.replacen(": ", ": type to filter · ", 1)
        };
        return (lines, heading);
    }
    let text = |l: &Line<'_>| {
        l.spans
            .iter()
            .map(|s| s.content.as_ref())
            .collect::<String>()
    };
    let mut kept: Vec<Line<'static>> = lines.into_iter().filter(|l| help.shows(&text(l))).collect();
    if kept.is_empty() {
        kept.push(Line::raw(format!(
            " nothing holds '{}' (Backspace takes a letter back)",
            help.filter
        )));
    }
    let name = heading.split(':').next().unwrap_or("").trim();
    (
        kept,
        format!(" {name} holding '{}': Backspace · Esc closes ", help.filter),
    )
}

/// The lines of the help's page, and its heading.
fn page(app: &App, help: &Help, look: &Look<'_>) -> (Vec<Line<'static>>, &'static str) {
    let keys = &app.options.keys;
    match help.page {
        HelpPage::Keys if app.replay.is_some() => (
            key_rows(REPLAY_KEYMAP, &|_| Vec::new(), &|_| false),
            " replay keys: ? legend · Esc closes ",
        ),
        HelpPage::Keys => (
            key_rows(&KEYMAP, &|a| keys.labels(a), &|a| keys.is_replaced(a)),
            " keys: ? legend · Esc closes ",
        ),
        HelpPage::Messages => (messages(app, look), " messages, in full: Esc closes "),
        HelpPage::Legend => {
            let model = &app.scenario.settings.model;
            let facts = Facts {
                kind: model.kind(),
                limit: &app.scenario.derived.limit,
                drawing: model.drawing(),
                summary: &app.scenario.derived.summary,
            };
            (legend::lines(&facts, look), " legend: ? or Esc closes ")
        }
    }
}

/// Every message and caption shown, in full, wrapped, the newest last.
fn messages(app: &App, look: &Look<'_>) -> Vec<Line<'static>> {
    let entries = &app.messages.entries;
    if entries.is_empty() {
        return vec![Line::raw(" no message yet")];
    }
    let mut out = Vec::new();
    for m in entries {
        let style = if m.error {
            Style::default().fg(look.theme.error)
        } else {
            Style::default()
        };
        // 60 columns, so a continuation line with its indent still fits the popup (a long
        // path was wrapped again with a lone character, issue 68).
        for (i, part) in super::wrap_words(&m.text, 60, usize::MAX)
            .into_iter()
            .enumerate()
        {
            let lead = if i == 0 { " " } else { "   " };
            out.push(Line::styled(format!("{lead}{part}"), style));
        }
    }
    out
}

/// The scene's legend as plain text lines, as the legend page shows them (spelled and folded
/// for `options.charset`): what the tests read.
#[must_use]
pub fn legend_text(app: &App, options: &super::UiOptions) -> Vec<String> {
    let look = options.look(app.view.theme);
    let (lines, _) = content(app, &Help::at(HelpPage::Legend), &look);
    lines
        .iter()
        .map(|l| {
            let text: String = l.spans.iter().map(|s| s.content.as_ref()).collect();
            text.chars().map(|c| options.charset.mark(c)).collect()
        })
        .collect()
}

/// Where the overlay goes for `lines` lines of text on `area`, and how many it shows.
fn popup(area: Rect, lines: usize) -> (Rect, u16) {
    let height = (lines as u16).saturating_add(2).min(area.height);
    let width = 66.min(area.width);
    let rect = Rect {
        x: area.x + (area.width - width) / 2,
        y: area.y + (area.height - height) / 2,
        width,
        height,
    };
    (rect, height.saturating_sub(2))
}

/// The last first line that still fills the overlay: what [`App::fit_help`] is told after a
/// frame (0 when the page fits).
#[must_use]
pub fn max_scroll(app: &App, area: Rect, options: &super::UiOptions) -> u16 {
    let Mode::Help(help) = &app.mode else {
        return 0;
    };
    let look = options.look(app.view.theme);
    let (lines, _) = content(app, help, &look);
    let (_, shown) = popup(area, lines.len());
    (lines.len() as u16).saturating_sub(shown)
}

pub fn draw(frame: &mut Frame<'_>, area: Rect, app: &App, help: &Help, look: &Look) {
    let (lines, heading) = content(app, help, look);
    let total = lines.len();
    let (rect, shown) = popup(area, total);
    let max = (total as u16).saturating_sub(shown);
    let scroll = help.scroll.min(max);
    let mut block = Block::bordered().title(heading);
    if max > 0 {
        // It scrolls, and says so: where it is and how to move.
        let last = (usize::from(scroll) + usize::from(shown)).min(total);
        let more = match (scroll > 0, scroll < max) {
            (true, true) => "↑↓",
            (false, true) => "↓",
            _ => "↑",
        };
        block = block.title_bottom(
            Line::from(format!(
                " {more} lines {}-{last} of {total} · ↑↓ PgUp PgDn ",
                scroll + 1
            ))
            .right_aligned(),
        );
    }
    frame.render_widget(Clear, rect);
    frame.render_widget(
        Paragraph::new(lines)
            .wrap(Wrap { trim: false })
            .scroll((scroll, 0))
            .block(block),
        rect,
    );
}
