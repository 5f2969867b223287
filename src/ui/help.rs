//! The help overlay: the keys (generated from the keymap table in use) and, on its second page,
//! the legend of every colour, mark and status field.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

use super::Look;
use crate::app::keys::{Binding, KEYMAP, REPLAY_KEYMAP};
use crate::app::mode::HelpPage;
use crate::app::user_keys::{UserKeys, key_label};

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

fn legend(look: &Look) -> Vec<Line<'static>> {
    let t = look.theme;
    let swatch = |mark: &'static str, colour, what: &'static str| {
        Line::from(vec![
            Span::styled(format!(" {mark:<4}"), Style::default().fg(colour)),
            Span::raw(what),
        ])
    };
    vec![
        swatch("⣀⣀", t.trail, "full motion at this k (dense dots)"),
        swatch("∘", t.effective, "the limit k → ∞ (marks), e toggles"),
        swatch("●", t.current, "the displayed point"),
        swatch("───", t.separatrix, "separatrix of the limit (solid)"),
        swatch("- -", t.start_level, "the start's level of E_eff (dashed)"),
        swatch("· ·", t.contour, "other levels of E_eff (dotted)"),
        swatch("╷", t.reversal, "reversal ticks (time series)"),
        swatch(
            "░▒▓█",
            t.trail,
            "map: reversals 1, 2–3, 4–7, ≥ 8; blank none",
        ),
        swatch(
            "┃ +",
            t.separatrix,
            "map: critical ratio (paper) · the cursor",
        ),
        Line::raw(""),
        Line::styled(
            " status bar:",
            Style::default().add_modifier(Modifier::BOLD),
        ),
        Line::raw(" t shown/end · ▶ paused done verifying · ×speed"),
        Line::raw(" reversals (full) and limit (k → ∞), up to t shown"),
        Line::raw(" ΔE/E: relative energy error of the full motion"),
        Line::raw(" method (auto→choice), est: auto's verified error"),
        Line::raw(" ✓ within the tolerance · steps/s · ● REC recording"),
        Line::raw(" panel: limit regime; vs critical = (ratio−crit)/crit"),
        Line::raw(" map (M): ←→↑↓ cell · Enter load · f limit/full · Esc"),
    ]
}

pub fn draw(
    frame: &mut Frame<'_>,
    area: Rect,
    (page, replay): (HelpPage, bool),
    keys: &UserKeys,
    look: &Look,
) {
    let (rows, heading) = match page {
        HelpPage::Keys if replay => (
            key_rows(REPLAY_KEYMAP, &|_| Vec::new(), &|_| false),
            " replay keys: ? legend · Esc closes ",
        ),
        HelpPage::Keys => (
            key_rows(&KEYMAP, &|a| keys.labels(a), &|a| keys.is_replaced(a)),
            " keys: ? legend · Esc closes ",
        ),
        HelpPage::Legend => (legend(look), " legend: ? or Esc closes "),
    };
    let height = (rows.len() as u16 + 2).min(area.height);
    let width = 66.min(area.width);
    let popup = Rect {
        x: area.x + (area.width - width) / 2,
        y: area.y + (area.height - height) / 2,
        width,
        height,
    };
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(rows)
            .wrap(Wrap { trim: false })
            .block(Block::bordered().title(heading)),
        popup,
    );
}
