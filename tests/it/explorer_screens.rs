//! Whole screens that must read whole at 80×24 (split from `explorer_ui.rs`, issue 69: no
//! source file over 1,000 lines): the picker, every lesson step, the portrait beside the body,
//! the footers, file names and titles.

use crate::common;
use crate::explorer_ui::{render, screen_text, text};

use common::Headless;
use rattleback::app::{App, Key};
use rattleback::scenario::shipped::resolve;
use rattleback::ui;

/// Issue 54: the picker filters as you type, Home and End jump, Backspace and Esc clear.
#[test]
fn the_picker_filters_as_you_type() {
    use rattleback::app::Mode;
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('p'));
    let catalogue = rattleback::app::Outcome::Catalogue(
        rattleback::scenario::shipped::catalogue().0,
        Vec::new(),
    );
    let effects = h.app.on_outcome(catalogue);
    h.exec(effects);
    for c in "kap".chars() {
        h.key(Key::Char(c));
    }
    let Mode::Picker(p) = &h.app.mode else {
        panic!("the picker is open")
    };
    let names: Vec<String> = p
        .visible()
        .into_iter()
        .map(|i| match &p.rows[i] {
            rattleback::app::mode::PickerRow::Preset(e) => e.name.clone(),
            rattleback::app::mode::PickerRow::Broken { name, .. } => name.clone(),
        })
        .collect();
    assert!(
        !names.is_empty() && names.iter().all(|n| n.starts_with("kapitza")),
        "{names:?}"
    );
    let screen = screen_text(&h.app, 80, 24);
    assert!(screen.contains("filter: kap"), "{screen}");
    h.key(Key::End);
    let Mode::Picker(p) = &h.app.mode else {
        panic!()
    };
    let last = *p.visible().last().unwrap();
    assert_eq!(p.selected, last, "End: the last match");
    h.key(Key::Home);
    let Mode::Picker(p) = &h.app.mode else {
        panic!()
    };
    assert_eq!(p.selected, p.visible()[0], "Home: the first match");
    h.key(Key::Backspace);
    h.key(Key::Esc);
    let Mode::Picker(p) = &h.app.mode else {
        panic!("the first Esc clears the filter")
    };
    assert!(p.filter.is_empty());
    h.key(Key::Esc);
    assert_eq!(h.app.mode, Mode::Normal, "the second closes");
}

/// Issue 55: every step of every shipped lesson is readable at 80×24, walked in its place (the
/// step's start, its answer given, its condition met): the lesson's pane shows all its lines
/// (nothing cut), the pane the step asks about has at least 8 rows inside its box, every phrase
/// the text quotes ('vs critical', 'est') is on the screen, the text never tells the student to
/// open a pane it opens itself, and a number question's answer is not in its own text.
#[test]
#[allow(clippy::too_many_lines)] // every lesson, walked step by step
fn every_lesson_step_reads_whole_at_80x24() {
    use rattleback::scenario::lesson::Question;
    for (name, _) in rattleback::scenario::lesson::SHIPPED_LESSONS {
        let lesson = rattleback::scenario::lesson::resolve(name).unwrap();
        let mut h = Headless::new("subcritical");
        let effects = h.app.start_lesson(lesson.clone());
        h.exec(effects);
        for (i, step) in lesson.steps.iter().enumerate() {
            let what = format!("{name} step {}", i + 1);
            let check = |h: &Headless, when: &str| {
                let screen = screen_text(&h.app, 80, 24);
                let right = ui::screen(&h.app, ratatui::layout::Rect::new(0, 0, 80, 24)).right;
                let layout = ui::column_layout(&h.app, right);
                let (_, lesson_area) = layout
                    .panes
                    .iter()
                    .find(|(p, _)| *p == rattleback::app::panes::Pane::Lesson)
                    .unwrap_or_else(|| panic!("{what} {when}: no lesson pane\n{screen}"));
                // Everything the pane has to say fits (the last line is what n waits for).
                let last = if h.app.lesson_missing().is_some() {
                    "n waits for"
                } else {
                    "n:"
                };
                assert!(
                    screen.contains(last) || screen.contains("lesson complete"),
                    "{what} {when}: the condition line is cut\n{screen}"
                );
                // Below its title, nothing in the lesson's pane is cut.
                let pane_text: String = screen
                    .lines()
                    .skip(lesson_area.y as usize + 1)
                    .take(lesson_area.height as usize - 1)
                    .map(|l| {
                        l.chars()
                            .skip(lesson_area.x as usize)
                            .take(lesson_area.width as usize)
                            .collect::<String>()
                    })
                    .collect();
                assert!(
                    !pane_text.contains('…'),
                    "{what} {when}: the text is cut\n{screen}"
                );
                if let Some(asked) = step
                    .pane
                    .as_deref()
                    .and_then(rattleback::app::panes::Pane::named)
                {
                    let area = layout
                        .panes
                        .iter()
                        .find(|(p, _)| *p == asked)
                        .unwrap_or_else(|| panic!("{what} {when}: {asked:?} not drawn\n{screen}"))
                        .1;
                    assert!(
                        area.height >= 10,
                        "{what} {when}: {asked:?} has {} rows\n{screen}",
                        area.height
                    );
                }
                // Words the text quotes ('vs critical') are on screen, spaces as the panel
                // lays them out (a label and its value apart).
                let flat = screen.split_whitespace().collect::<Vec<_>>().join(" ");
                for quoted in quoted(&step.text) {
                    assert!(
                        flat.contains(&quoted),
                        "{what} {when}: '{quoted}' is not on screen\n{screen}"
                    );
                }
                screen
            };
            check(&h, "at its start");
            // Never tells to open what it opened.
            if let Some(pane) = step
                .pane
                .as_deref()
                .and_then(rattleback::app::panes::Pane::named)
                && let Some(b) = rattleback::app::keys::pane_binding(pane)
            {
                let key = format!("({})", rattleback::app::user_keys::key_label(b.keys[0]));
                assert!(
                    !step.text.contains(&key),
                    "{what}: says {key} for a pane it opens"
                );
            }
            match &step.question {
                Some(Question::Choice { .. }) => h.key(Key::Char('1')),
                Some(Question::Number { answer, .. }) => {
                    let written = format!("{answer}");
                    assert!(
                        !step.text.contains(&format!(" {written} "))
                            && !step.text.contains(&format!(" {written}.")),
                        "{what}: states its answer {written}"
                    );
                    h.key(Key::Char('a'));
                    for c in written.chars() {
                        h.key(Key::Char(c));
                    }
                    h.key(Key::Enter);
                }
                None => {}
            }
            check(&h, "answered");
            if let Some(p) = &step.until.parameter {
                let label = p.key.rsplit('.').next().unwrap();
                // The step's map has the arrows: Esc gives them back, as its text says.
                if h.app.mode == rattleback::app::Mode::Map {
                    h.key(Key::Esc);
                }
                let mut presses = 0;
                while h.app.field().label() != label {
                    h.key(Key::Down);
                    presses += 1;
                    assert!(presses < 100, "{what}: no field {label} under the arrows");
                }
                h.key(Key::Enter);
                for c in format!("{}", p.at_least.or(p.at_most).unwrap()).chars() {
                    h.key(Key::Char(c));
                }
                h.key(Key::Enter);
            }
            if let Some(t) = step.until.time {
                h.play_until(t, 64.0);
                if h.app.run.playing {
                    h.key(Key::Char(' '));
                }
            }
            for _ in 0..3 {
                h.tick(1.0 / 30.0);
            }
            check(&h, "ready");
            h.key(Key::Char('n'));
        }
    }
}

/// The phrases a text quotes in single quotes (an apostrophe inside a word is not a quote).
fn quoted(text: &str) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let opens = chars[i] == '\'' && (i == 0 || matches!(chars[i - 1], ' ' | '('));
        if opens && let Some(len) = chars[i + 1..].iter().position(|c| *c == '\'') {
            out.push(chars[i + 1..i + 1 + len].iter().collect());
            i += len + 2;
            continue;
        }
        i += 1;
    }
    out
}

/// Issue 68: at 80×24 the body pane (B) takes the portrait's place, and Tab gives the
/// portrait back (then the body again); the line naming what waits says Tab cycles.
#[test]
fn tab_brings_the_portrait_back_beside_the_body_at_80x24() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('B'));
    let with_body = text(&render(&h.app, 80, 24));
    assert!(with_body.contains("body from above (B)"), "{with_body}");
    assert!(!with_body.contains("phase portrait"), "{with_body}");
    assert!(
        with_body.contains("more: portrait · Tab cycles"),
        "{with_body}"
    );
    h.key(Key::Tab);
    let portrait = text(&render(&h.app, 80, 24));
    assert!(portrait.contains("phase portrait"), "{portrait}");
    assert!(!portrait.contains("body from above (B)"), "{portrait}");
    assert!(portrait.contains("Tab cycles"), "{portrait}");
    h.key(Key::Tab);
    let again = text(&render(&h.app, 80, 24));
    assert!(again.contains("body from above (B)"), "{again}");
    // At 160×48 both fit: Tab changes nothing that is shown.
    let big = text(&render(&h.app, 160, 48));
    assert!(big.contains("phase portrait") && big.contains("body from above (B)"));
}

/// Issue 68: the footer says what `space` does now: `play` when paused, `pause` when playing.
#[test]
fn the_footer_follows_the_state() {
    let mut h = Headless::new("subcritical");
    let paused = text(&render(&h.app, 80, 24));
    let footer = paused.lines().last().unwrap().to_owned();
    assert!(footer.contains("space play"), "{footer}");
    h.key(Key::Char(' '));
    let playing = text(&render(&h.app, 80, 24));
    let footer = playing.lines().last().unwrap().to_owned();
    assert!(footer.contains("space pause"), "{footer}");
    assert!(!footer.contains("space play"), "{footer}");
}

/// Issue 68: a replay's footer says what `space` does too: `pause` while it plays, `resume`
/// when paused, nothing once the recording has ended.
#[test]
fn the_replays_footer_follows_the_replay() {
    let mut h = Headless::new("subcritical");
    let mut replay = replay_at_4_of_7();
    let mut footer = |replay| {
        h.app.replay = Some(replay);
        let screen = text(&render(&h.app, 80, 24));
        screen.lines().last().unwrap().to_owned()
    };
    let playing = footer(replay);
    assert!(playing.contains("space pause"), "{playing}");
    replay.paused = true;
    let paused = footer(replay);
    assert!(
        paused.contains("space resume") && !paused.contains("pause"),
        "{paused}"
    );
    replay.ended = true;
    let ended = footer(replay);
    assert!(!ended.contains("space"), "{ended}");
    assert!(ended.contains("+/- pace"), "{ended}");
}

/// Issue 68: a message that names a file shows the file's name whole at 80 columns (its
/// folders shortened in the middle), never `recording to… (v: whole)`.
#[test]
fn a_recordings_file_name_is_shown_whole_at_80_columns() {
    let (mut app, _) = App::new(
        &resolve("subcritical", &[]).unwrap(),
        rattleback::app::Options::at(30.0),
    );
    let path = "/home/a-lecturer/.local/share/rattleback/sessions/subcritical-start-2026-11-27-193208.jsonl";
    app.on_outcome(rattleback::app::Outcome::Recording(Ok(path.to_owned())));
    let screen = text(&render(&app, 80, 24));
    let line = screen
        .lines()
        .find(|l| l.contains("recording to"))
        .unwrap_or_else(|| panic!("{screen}"));
    assert!(
        line.contains("subcritical-start-2026-11-27-193208.jsonl"),
        "{line}"
    );
    assert!(line.contains('…') && !line.contains("v: whole"), "{line}");
    assert!(
        line.trim_start().starts_with("recording to /home/"),
        "{line}"
    );
    // `v` shows it whole: the path in pieces, none of them wrapped again (a lone character on
    // a line of its own, before).
    app.on_key(Key::Char('v'));
    let log = text(&render(&app, 80, 24));
    // The popup is 66 columns wide, centred: its inside is columns 8 to 71.
    let pieces: Vec<String> = log
        .lines()
        .map(|l| l.chars().collect::<Vec<char>>())
        .filter(|c| c.len() >= 73 && c[7] == '│' && c[72] == '│')
        .map(|c| c[8..72].iter().collect::<String>().trim().to_owned())
        .filter(|l| !l.is_empty())
        .collect();
    let joined: String = pieces.concat();
    assert!(joined.contains(path), "{log}");
    assert!(pieces.iter().all(|p| p.chars().count() > 3), "{log}");
}

/// Issue 68: titles too long for their pane lose words from the middle, so both ends stay
/// (the picker's `Esc closes`).
#[test]
fn long_titles_are_shortened_in_the_middle() {
    assert_eq!(
        ui::middle_words(
            "presets 1/23: type to filter, ↑↓ Home End choose, Enter loads, Esc closes",
            60
        ),
        "presets 1/23: type to filter, … Enter loads, Esc closes"
    );
    assert_eq!(ui::middle_words("short", 60), "short");
    let cut = ui::middle_words("Kapitza: upright and stable", 24);
    assert!(
        cut.chars().count() <= 24 && cut.starts_with("Kapitza:") && cut.ends_with("stable"),
        "{cut}"
    );
    let (mut app, _) = App::new(
        &resolve("subcritical", &[]).unwrap(),
        rattleback::app::Options::at(30.0),
    );
    let catalogue =
        rattleback::explorer::file_outcome(&rattleback::app::Effect::ReadCatalogue, None).unwrap();
    app.on_outcome(catalogue);
    let screen = text(&render(&app, 80, 24));
    assert!(
        screen.contains("presets 1/") && screen.contains("Esc closes"),
        "{screen}"
    );
}

/// A replay playing at ×1, 4 s into a 7 s recording without chapters.
pub(crate) fn replay_at_4_of_7() -> rattleback::app::ReplayInfo {
    rattleback::app::ReplayInfo {
        pace: 1.0,
        paused: false,
        chapter: 0,
        chapters: 0,
        ended: false,
        at: 4.0,
        length: 7.0,
        live: None,
    }
}
