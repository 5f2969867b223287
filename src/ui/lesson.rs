//! The lesson pane: the current step's title and text, its question (the choices numbered, the
//! answer given, then the right one after the run), what `n` waits for, and the keys.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget, Wrap};

use super::Look;
use crate::app::lesson::LessonState;
use crate::scenario::lesson::Question;

/// The lesson pane: what it shows, borrowed.
pub struct LessonPane<'a> {
    /// The lesson and where it stands.
    pub lesson: &'a LessonState,
    /// What the step still waits for (`None`: `n` moves on).
    pub missing: Option<String>,
    /// Marker and colours.
    pub look: &'a Look<'a>,
}

impl LessonPane<'_> {
    /// Rows the pane needs at `width` columns (its text wrapped, borders included).
    #[must_use]
    pub fn height(&self, width: u16) -> u16 {
        let inner = usize::from(width.saturating_sub(2)).max(1);
        let rows: usize = self
            .lines()
            .iter()
            .map(|l| {
                let text: String = l.spans.iter().map(|s| s.content.as_ref()).collect();
                super::wrap_words(&text, inner, usize::MAX).len().max(1)
            })
            .sum();
        u16::try_from(rows + 2).unwrap_or(u16::MAX)
    }

    fn lines(&self) -> Vec<Line<'static>> {
        let (state, look) = (self.lesson, self.look);
        let step = state.current();
        let count = state.lesson.steps.len();
        let bold = Style::default().add_modifier(Modifier::BOLD);
        let mut lines = vec![Line::raw(step.text.clone())];
        // The lesson's description opens its first step (dim, above the step's words).
        if state.step == 0 && !state.lesson.description.is_empty() {
            lines.insert(
                0,
                Line::styled(state.lesson.description.clone(), look.dim()),
            );
        }
        if let Some(q) = &step.question {
            lines.push(Line::styled(format!("? {}", q.prompt()), bold));
            match q {
                Question::Choice { choices, .. } => {
                    let row: Vec<Span> = choices
                        .iter()
                        .enumerate()
                        .flat_map(|(i, c)| {
                            let chosen = state.given == Some(crate::app::lesson::Given::Choice(i));
                            let style = if chosen {
                                bold.add_modifier(Modifier::REVERSED)
                            } else {
                                Style::default()
                            };
                            [
                                Span::styled(format!(" {} {c} ", i + 1), style),
                                Span::raw("  "),
                            ]
                        })
                        .collect();
                    lines.push(Line::from(row));
                }
                Question::Number { .. } => {}
            }
            let verdict = match (state.given_text(), state.revealed, state.correct()) {
                (None, _, _) if matches!(q, Question::Number { .. }) => {
                    "a: type your answer, before you play".to_owned()
                }
                (None, _, _) => "answer before you play".to_owned(),
                // The verdict comes after the run (the message line says so).
                (Some(g), false, _) => format!("your answer: {g}"),
                // A choice given is highlighted above: the verdict need not repeat it.
                (Some(_), true, Some(false)) if matches!(q, Question::Choice { .. }) => {
                    format!("wrong; the answer: {}", q.answer_text())
                }
                (Some(_), true, _) => state.verdict_text().unwrap_or_default(),
            };
            lines.push(Line::styled(verdict, look.dim()));
        }
        let next = match (&self.missing, state.finished) {
            (_, true) => "lesson complete".to_owned(),
            (None, _) if state.step + 1 == count => "n: finish the lesson".to_owned(),
            (None, _) => "n: next step".to_owned(),
            (Some(m), _) => format!("n waits for {m}"),
        };
        lines.push(Line::styled(next, bold));
        lines
    }
}

impl Widget for LessonPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let state = self.lesson;
        // The step (its number and title) is what a student needs: the lesson's title gives
        // way first, shortened in its middle.
        let step = format!(
            " │ step {}/{}: {}",
            state.step + 1,
            state.lesson.steps.len(),
            state.current().title
        );
        let room = usize::from(area.width.saturating_sub(4))
            .saturating_sub(step.chars().count() + "lesson: ".len());
        let heading = if room >= 16 {
            format!(
                "lesson: {}{step}",
                super::middle_words(&state.lesson.title, room)
            )
        } else {
            // No room for the lesson's title (`v` and the help show it): the step alone.
            step.trim_start_matches(" │ ").to_owned()
        };
        let block = Block::bordered().title(super::title_middle(&heading, area.width));
        // Too short for everything: the step's text gives way (cut, with `…`), the question,
        // the answer and what `n` waits for stay whole.
        let mut lines = self.lines();
        let inner = usize::from(area.width.saturating_sub(2)).max(1);
        let rows = |l: &Line<'_>| {
            let text: String = l.spans.iter().map(|s| s.content.as_ref()).collect();
            super::wrap_words(&text, inner, usize::MAX).len().max(1)
        };
        let room = usize::from(area.height.saturating_sub(2));
        // The description gives way first (it is in `lessons` and on the exported page too).
        if state.step == 0
            && !state.lesson.description.is_empty()
            && lines.iter().map(rows).sum::<usize>() > room
        {
            lines.remove(0);
        }
        let tail: usize = lines.iter().skip(1).map(rows).sum();
        if rows(&lines[0]) + tail > room {
            let keep = room.saturating_sub(tail).max(1) * inner;
            let text: String = lines[0].spans.iter().map(|s| s.content.as_ref()).collect();
            lines[0] = Line::raw(crate::app::ellipsis(&text, keep.saturating_sub(inner / 4)));
        }
        Paragraph::new(lines)
            .wrap(Wrap { trim: true })
            .block(block)
            .render(area, buf);
    }
}
