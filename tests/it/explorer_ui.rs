//! Whole screens rendered through ratatui's `TestBackend`, snapshotted with insta at 80×24 and
//! 160×48, with the colours and styles of key cells asserted separately.

use crate::common;
use crate::explorer_screens::replay_at_4_of_7;

use common::Headless;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};

use rattleback::app::{App, Key, PlanState};
use rattleback::physics::Method;
use rattleback::scenario::shipped::{SHIPPED, resolve};
use rattleback::ui::{self, Cache, UiOptions};

/// The default preset, played through the worker's interpreter until the display shows `t`.
fn app_at(t: f64) -> App {
    preset_at("subcritical", t)
}

fn preset_at(name: &str, t: f64) -> App {
    let mut h = Headless::new(name);
    if t > 0.0 {
        h.play_until(t, 4.0);
        h.key(Key::Char(' '));
    }
    h.app
}

fn render_with(app: &App, width: u16, height: u16, options: &UiOptions) -> Buffer {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| ui::draw(f, app, options, &mut Cache::default()))
        .unwrap();
    terminal.backend().buffer().clone()
}

pub fn render(app: &App, width: u16, height: u16) -> Buffer {
    render_with(app, width, height, &UiOptions::default())
}

/// The screen of `app` at `width × height`, as text.
pub fn screen_text(app: &App, width: u16, height: u16) -> String {
    text(&render(app, width, height))
}

pub fn text(buffer: &Buffer) -> String {
    let area = buffer.area;
    let mut out = String::new();
    for y in 0..area.height {
        for x in 0..area.width {
            out.push_str(buffer[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

pub fn find(buffer: &Buffer, needle: &str) -> Option<(u16, u16)> {
    let area = buffer.area;
    for y in 0..area.height {
        let row: String = (0..area.width)
            .map(|x| buffer[(x, y)].symbol().to_owned())
            .collect();
        if let Some(i) = row.find(needle) {
            let col = row[..i].chars().count() as u16;
            return Some((col, y));
        }
    }
    None
}

#[test]
fn screen_80x24_after_ten_seconds() {
    let app = app_at(10.0);
    let buffer = render(&app, 80, 24);
    insta::assert_snapshot!("screen_80x24", text(&buffer));
}

#[test]
fn screen_160x48_with_series_pane() {
    let mut app = app_at(10.0);
    app.on_key(Key::Char('t'));
    let buffer = render(&app, 160, 48);
    insta::assert_snapshot!("screen_160x48_series", text(&buffer));
}

#[test]
fn help_overlay_lists_the_bindings() {
    let mut app = app_at(0.0);
    app.on_key(Key::Char('?'));
    let buffer = render(&app, 80, 24);
    insta::assert_snapshot!("help_80x24", text(&buffer));
    // The help scrolls at 80×24, and says so; End shows its last row (`q` quits).
    assert!(
        text(&buffer).contains("↓ lines 1-22 of"),
        "{}",
        text(&buffer)
    );
    let options = rattleback::ui::UiOptions::default();
    let area = ratatui::layout::Rect::new(0, 0, 80, 24);
    app.fit_help(rattleback::ui::help::max_scroll(&app, area, &options));
    app.on_key(Key::End);
    let end = text(&render(&app, 80, 24));
    assert!(end.contains("q/Ctrl-C") && end.contains("↑ lines"), "{end}");
    app.on_key(Key::Home);
    app.on_key(Key::Char('?'));
    // Every page of the legend, scrolled through.
    let mut legend = String::new();
    for _ in 0..10 {
        legend.push_str(&text(&render(&app, 80, 24)));
        app.fit_help(rattleback::ui::help::max_scroll(&app, area, &options));
        app.on_key(Key::PageDown);
    }
    for what in ["separatrix", "limit", "ΔE/E", "vs critical", "REC"] {
        assert!(legend.contains(what), "legend lacks {what}:\n{legend}");
    }
}

#[test]
fn key_cells_have_their_styles_and_colours() {
    let app = app_at(10.0);
    let buffer = render(&app, 80, 24);
    // The selected row is reverse video: visible without colour.
    let (x, y) = find(&buffer, "› ix").expect("selected row");
    assert!(buffer[(x + 2, y)].modifier.contains(Modifier::REVERSED));
    // The status bar is reverse video too.
    let (x, y) = find(&buffer, "reversals").expect("status bar");
    assert!(buffer[(x, y)].modifier.contains(Modifier::REVERSED));
    // The current point is red; the separatrix and the start's level have their colours.
    let (x, y) = find(&buffer, "●").expect("current point");
    assert_eq!(buffer[(x, y)].fg, Color::Red);
    let colours: Vec<Color> = buffer.content().iter().map(|c| c.fg).collect();
    for (colour, what) in [(Color::Yellow, "separatrix"), (Color::Green, "trail")] {
        assert!(colours.contains(&colour), "no {what} cell ({colour:?})");
    }
    // At k = 1e4 the limit's trail lies under the full one; with a soft spring they part.
    let soft = render(&preset_at("soft-spring", 20.0), 80, 24);
    assert!(
        soft.content().iter().any(|c| c.fg == Color::Magenta),
        "no effective-overlay cell"
    );
    // The trail runs along the start's own level and covers it; before it, the level shows.
    let fresh = render(&app_at(0.0), 80, 24);
    assert!(
        fresh.content().iter().any(|c| c.fg == Color::Cyan),
        "no start-level cell"
    );
}

#[test]
fn status_counts_reversals_and_names_the_chosen_method() {
    let app = app_at(10.0);
    let buffer = render(&app, 160, 48);
    let screen = text(&buffer);
    // Reversals of the limit before t = 10: 2.217 and 6.651.
    assert!(screen.contains("reversals 2 limit 2"), "{screen}");
    let PlanState::Running { plan, .. } = app.run.plan else {
        panic!("worker said nothing")
    };
    let chosen = plan.method;
    assert_ne!(chosen, Method::Auto);
    assert!(screen.contains(&format!("auto→{chosen}")), "{screen}");
}

#[test]
fn tiny_terminals_get_a_message_not_a_panic() {
    for (w, h) in [(20, 5), (79, 24), (80, 23), (1, 1)] {
        let app = app_at(0.0);
        let buffer = render(&app, w, h);
        if w >= 20 {
            assert!(text(&buffer).contains("too small"), "{w}x{h}");
        }
    }
}

#[test]
fn marker_option_changes_the_canvas() {
    let app = app_at(5.0);
    let options = UiOptions {
        marker: ratatui::symbols::Marker::Dot,
        ..UiOptions::default()
    };
    let screen = text(&render_with(&app, 80, 24, &options));
    assert!(
        !screen
            .chars()
            .any(|c| ('\u{2801}'..='\u{28FF}').contains(&c)),
        "Braille with --marker dot"
    );
    assert!(screen.contains('•'), "dots expected");
}

/// Item 5: at 80 and 100 columns the footer keeps `? help` and `q quit`; the status bar drops
/// whole fields and never cuts a number; any method name fits the panel.
#[test]
fn narrow_screens_drop_whole_fields_never_parts() {
    let mut app = preset_at("subcritical", 3.0);
    for width in [80, 100, 160] {
        let screen = text(&render(&app, width, 24));
        let rows: Vec<&str> = screen.lines().collect();
        let footer = rows[rows.len() - 1];
        assert!(
            footer.contains("? help") && footer.contains("q quit"),
            "{width}: {footer}"
        );
        let status = rows[rows.len() - 2];
        // Every number of the status bar is whole: ΔE/E, when shown, has its exponent.
        if let Some(i) = status.find("ΔE/E") {
            let field: String = status[i..].split('│').next().unwrap().trim().to_owned();
            assert!(
                field.contains('e'),
                "{width}: cut field '{field}' in '{status}'"
            );
        }
        assert!(status.contains("reversals"), "{width}: {status}");
    }
    // The longest method name fits the panel.
    for _ in 0..9 {
        app.on_key(Key::Down);
    }
    assert_eq!(app.field().label(), "method");
    app.on_key(Key::Enter);
    for c in "effective-corrected".chars() {
        app.on_key(Key::Char(c));
    }
    app.on_key(Key::Enter);
    let screen = text(&render(&app, 80, 24));
    assert!(screen.contains("method effective-corrected"), "{screen}");
    assert!(
        screen.contains("tolerance"),
        "the next row survives:\n{screen}"
    );
}

/// Item 5: under `NO_COLOR` the curves differ by shape: the limit's marks, the dotted levels,
/// the solid separatrix; bold for the current point.
#[test]
fn curves_are_told_apart_without_colour() {
    let spec = rattleback::scenario::theme::theme("default").unwrap();
    let options = UiOptions::new(ratatui::symbols::Marker::Braille, &spec, &[], true);
    let app = preset_at("soft-spring", 20.0);
    let buffer = render_with(&app, 80, 24, &options);
    assert!(buffer.content().iter().all(|c| c.fg == Color::Reset));
    let screen = text(&buffer);
    assert!(screen.contains('∘'), "limit marks:\n{screen}");
    let (x, y) = find(&buffer, "●").expect("current point");
    assert!(buffer[(x, y)].modifier.contains(Modifier::BOLD));
}

/// Item 5: a theme sets the background; `T` names the theme it switched to.
#[test]
fn themes_set_their_background_and_t_names_them() {
    let (all, _) = rattleback::scenario::theme::themes();
    let all: Vec<_> = all.into_iter().map(|(_, t)| t).collect();
    let first = rattleback::scenario::theme::theme("default").unwrap();
    let options = UiOptions::new(ratatui::symbols::Marker::Braille, &first, &all, false);
    let mut h = Headless::new("subcritical");
    let (app, _) = App::new(
        &resolve("subcritical", &[]).unwrap(),
        rattleback::app::Options {
            theme_names: options.theme_names(),
            ..rattleback::app::Options::at(30.0)
        },
    );
    h.app = app;
    h.key(Key::Char('T'));
    let screen = text(&render_with(&h.app, 80, 24, &options));
    assert!(screen.contains("Dark"), "{screen}");
    let buffer = render_with(&h.app, 80, 24, &options);
    assert_eq!(buffer[(40, 10)].bg, Color::Rgb(0x1e, 0x21, 0x27));
}

/// Item 5: the regime is the limit's, and the side of the threshold a signed distance.
#[test]
fn the_regime_is_labelled_as_the_limits() {
    for name in ["just-above", "just-below"] {
        let screen = text(&render(&app_at_preset(name), 80, 24));
        assert!(screen.contains("limit regime"), "{screen}");
        let sign = if name == "just-above" { "+" } else { "-" };
        let row = screen
            .lines()
            .find(|l| l.contains("vs critical"))
            .expect("distance row");
        assert!(row.contains(sign) && row.contains('%'), "{name}: {row}");
    }
}

fn app_at_preset(name: &str) -> App {
    preset_at(name, 0.0)
}

/// Item 8: the picker scrolls at 80×24: the selection stays on screen.
#[test]
fn the_picker_keeps_the_selection_on_screen() {
    let mut app = app_at(0.0);
    let (entries, _) = rattleback::scenario::shipped::catalogue();
    let many: Vec<_> = (0..3)
        .flat_map(|i| {
            entries.iter().cloned().map(move |mut e| {
                e.name = format!("p{i}-{}", e.name);
                e
            })
        })
        .collect();
    let last = many.last().unwrap().name.clone();
    let n = many.len();
    app.on_outcome(rattleback::app::Outcome::Catalogue(many, Vec::new()));
    for _ in 1..n {
        app.on_key(Key::Down);
    }
    let screen = text(&render(&app, 80, 24));
    assert!(screen.contains(&last), "{screen}");
    assert!(screen.contains(&format!("{n}/{n}")), "{screen}");
}

/// Every shipped preset draws at 80×24 at ×1 and at top speed with its numbers whole.
#[test]
fn every_shipped_preset_draws_at_80x24() {
    for (name, _) in SHIPPED {
        for speed in [1.0, 1024.0] {
            let mut h = Headless::new(name);
            h.play_until(2.0, speed);
            let screen = text(&render(&h.app, 80, 24));
            let status = screen.lines().nth(22).unwrap();
            assert!(
                status.contains(&format!("t {:.2}", h.app.run.shown)),
                "{name}: {status}"
            );
            let kind = h.app.scenario.settings.model.kind();
            assert!(
                status.contains(&format!(
                    "{} {}",
                    kind.words().events,
                    h.app.run.reversals_shown()
                )),
                "{name}: {status}"
            );
            if let (Some(n), Some(second)) = (h.app.run.second_shown(), kind.words().second_events)
            {
                assert!(
                    status.contains(&format!("{} {n}", second.name)),
                    "{name}: {status}"
                );
            }
        }
    }
}

#[test]
fn a_missed_tolerance_is_shown_in_the_status_bar_at_80x24() {
    // just-below at 1e-10: auto cannot verify it (its JSON says met = false); the explorer
    // must say so where it cannot be missed, not only in the help.
    let preset = resolve("just-below", &["run.tolerance=1e-10".parse().unwrap()]).unwrap();
    let mut h = Headless::of(&preset);
    h.play_until(5.0, 4.0);
    h.key(Key::Char(' '));
    let PlanState::Running {
        estimate: Some(e), ..
    } = h.app.run.plan
    else {
        panic!("auto verified")
    };
    assert!(e > 1e-10);
    let screen = text(&render(&h.app, 80, 24));
    assert!(screen.contains("✗ tol missed"), "{screen}");
}

#[test]
fn sweep_pane_at_80x24_and_160x48() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('K'));
    let small = text(&render(&h.app, 80, 24));
    assert!(small.contains("k-sweep: slope -1.01"), "{small}");
    assert!(small.contains('●'));
    insta::assert_snapshot!("sweep_80x24", small);
    h.key(Key::Char('t'));
    insta::assert_snapshot!("sweep_160x48_with_series", text(&render(&h.app, 160, 48)));
}

#[test]
fn weak_star_pane_at_80x24_and_160x48() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('W'));
    let screen = text(&render(&h.app, 80, 24));
    assert!(
        screen.contains("weak-*: average over w = 1 within"),
        "{screen}"
    );
    insta::assert_snapshot!("weak_80x24", screen);
    h.key(Key::Char('>'));
    let large = text(&render(&h.app, 160, 48));
    assert!(large.contains("average over w = 2 within"), "{large}");
    insta::assert_snapshot!("weak_160x48_window_2", large);
}

#[test]
fn regime_map_pane_at_80x24_and_160x48() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('M'));
    let buf = render(&h.app, 80, 24);
    let small = text(&buf);
    assert!(small.contains("map (limit) 1152 cells"), "{small}");
    assert!(small.contains('┃'), "the critical curve is drawn: {small}");
    assert!(
        small.contains("←→↑↓ cell"),
        "the footer lists the map's keys: {small}"
    );
    insta::assert_snapshot!("map_80x24", small);
    // The cursor is in reverse video while the map has the arrows; the critical curve in the
    // separatrix colour.
    let cells: Vec<_> = buf.content().iter().collect();
    let cursor = cells
        .iter()
        .find(|c| c.symbol() == "+" && c.modifier.contains(Modifier::REVERSED));
    assert!(cursor.is_some(), "a reversed cursor: {small}");
    let curve = cells.iter().find(|c| c.symbol() == "┃").unwrap();
    assert_eq!(curve.fg, Color::Yellow);
    // Larger, with the cursor moved and the arrows given back.
    for _ in 0..6 {
        h.key(Key::Right);
    }
    h.key(Key::Esc);
    let large = text(&render(&h.app, 160, 48));
    assert!(large.contains("│ M "), "{large}");
    assert!(
        large.contains("+ ratio 0.521 iy/ix 0.511: 6 rev"),
        "{large}"
    );
    insta::assert_snapshot!("map_160x48", large);
}

#[test]
fn the_map_reads_without_colour_the_counts_are_glyph_densities() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('M'));
    let spec = rattleback::scenario::theme::theme("default").unwrap();
    let options = UiOptions::new(ratatui::symbols::Marker::Braille, &spec, &[], true);
    let buffer = render_with(&h.app, 120, 40, &options);
    assert!(buffer.content().iter().all(|c| c.fg == Color::Reset));
    let screen = text(&buffer);
    // Counts are told apart by density (blank none … █ eight or more), the curve and the
    // cursor by their shapes.
    let densities = ['░', '▒', '▓', '█']
        .iter()
        .filter(|g| screen.contains(**g))
        .count();
    assert!(densities >= 3, "{screen}");
    for glyph in ['┃', '+'] {
        assert!(screen.contains(glyph), "{glyph} missing:\n{screen}");
    }
}

/// Issue 14, item 1: the body from above, at two sizes, in Braille, half blocks and without
/// colour.
#[test]
fn body_pane_at_80x24_and_160x48() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('B'));
    h.play_until(11.5, 4.0);
    h.key(Key::Char(' '));
    let small = text(&render(&h.app, 80, 24));
    assert!(small.contains("body from above (B): spin"), "{small}");
    // A reversal happened in the trace's window: both senses are on the ring.
    assert!(small.contains('+') && small.contains('-'), "{small}");
    assert!(small.contains('●'));
    insta::assert_snapshot!("body_80x24", small);
    insta::assert_snapshot!("body_160x48", text(&render(&h.app, 160, 48)));
    // Half blocks and no colour: the same shapes and signs.
    let spec = rattleback::scenario::theme::theme("default").unwrap();
    let options = UiOptions::new(ratatui::symbols::Marker::HalfBlock, &spec, &[], true);
    let buffer = render_with(&h.app, 80, 24, &options);
    assert!(buffer.content().iter().all(|c| c.fg == Color::Reset));
    let plain = text(&buffer);
    assert!(
        plain.contains('+') && plain.contains('-') && plain.contains('●'),
        "{plain}"
    );
    assert!(
        plain.contains('▀') || plain.contains('▄') || plain.contains('█'),
        "{plain}"
    );
}

#[test]
fn the_body_turns_with_alpha_and_the_bar_shows_the_rocking() {
    use rattleback::ui::body_envelope;
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('B'));
    h.play_until(2.0, 4.0);
    let rock = body_envelope(&h.app.run);
    let peak = h
        .app
        .run
        .trail_shown()
        .iter()
        .map(|p| p.fast.abs())
        .fold(0.0, f64::max);
    assert!(rock > 0.0 && rock <= peak, "{rock} {peak}");
    // The rocking of this start is small: the tilt of a stiff spring (k = 1e4).
    assert!(peak < 0.05, "{peak}");
    let before = text(&render(&h.app, 80, 24));
    h.play_until(3.0, 4.0);
    let after = text(&render(&h.app, 80, 24));
    assert_ne!(before, after, "the body turns as alpha changes");
}

#[test]
fn lesson_pane_at_80x24() {
    let lesson = rattleback::scenario::lesson::resolve("first-reversal").unwrap();
    let mut h = Headless::new("supercritical");
    let effects = h.app.start_lesson(lesson);
    h.exec(effects);
    h.key(Key::Char('1'));
    let screen = text(&render(&h.app, 80, 24));
    // The step's number and title, whole; the lesson's title where there is room (issue 68).
    assert!(
        screen.contains("step 1/5: A body that turns back"),
        "{screen}"
    );
    assert!(screen.contains("1 yes"), "{screen}");
    assert!(
        screen.contains("your answer: yes") && !screen.contains("your answer: yes, right"),
        "{screen}"
    );
    insta::assert_snapshot!("lesson_80x24", screen);
    // The step is about the time series: it is open, with at least 8 rows beside the lesson.
    assert!(rows_of(&screen, "(t): full") >= 8, "{screen}");
}

/// Rows of the bordered pane whose title holds `title`: from its top border to its bottom one.
fn rows_of(screen: &str, title: &str) -> usize {
    let lines: Vec<Vec<char>> = screen.lines().map(|l| l.chars().collect()).collect();
    let needle: Vec<char> = title.chars().collect();
    let (top, at) = lines
        .iter()
        .enumerate()
        .find_map(|(y, l)| {
            l.windows(needle.len())
                .position(|w| w == needle.as_slice())
                .map(|x| (y, x))
        })
        .unwrap_or_else(|| panic!("no pane titled {title}"));
    let corner = lines[top][..at]
        .iter()
        .rposition(|c| *c == '┌')
        .expect("a bordered pane");
    let bottom = (top + 1..lines.len())
        .find(|&y| lines[y].get(corner) == Some(&'└'))
        .expect("its bottom border");
    bottom - top + 1
}

/// Every shipped lesson step that names a pane gets it, with at least 8 rows, at 80×24, in both
/// scenes.
#[test]
fn a_lesson_steps_pane_gets_room_at_80x24() {
    for (name, _) in rattleback::scenario::lesson::SHIPPED_LESSONS {
        let lesson = rattleback::scenario::lesson::resolve(name).unwrap();
        for (i, step) in lesson.steps.iter().enumerate() {
            let Some(pane) = step.pane.as_deref() else {
                continue;
            };
            // The step alone, as a lesson: it begins as it would in its place.
            let alone = rattleback::scenario::lesson::Lesson {
                steps: vec![step.clone()],
                ..lesson.clone()
            };
            let mut h = Headless::new("subcritical");
            let effects = h.app.start_lesson(alone);
            h.exec(effects);
            let screen = text(&render(&h.app, 80, 24));
            let title = match pane {
                "portrait" => "phase portrait",
                "series" => "(t): full",
                "sweep" => "-sweep:",
                "compare" => "compare: spin(t)",
                "map" => " cells │",
                "body" => "(B)",
                other => panic!("a shipped step asks for {other}: add its title here"),
            };
            assert!(
                rows_of(&screen, title) >= 8,
                "{name} step {}: the {pane} pane is too small\n{screen}",
                i + 1
            );
        }
    }
}

/// At 80 columns the status bar has room for one of the verified estimate, the energy monitor
/// and the method beside the time, the state, the speed and the events: the estimate, which
/// says how accurate the numbers on screen are, is kept first, recording or not.
#[test]
fn at_80_columns_the_verified_estimate_stays_recorded_replayed_and_followed() {
    let mut app = app_at(10.0);
    let bar_at = |app: &App, width: u16| {
        let buffer = render(app, width, 24);
        (0..width)
            .map(|x| buffer[(x, 22)].symbol().to_owned())
            .collect::<String>()
    };
    let bar = |app: &App| bar_at(app, 80);
    let PlanState::Running {
        estimate: Some(e), ..
    } = app.run.plan
    else {
        panic!("auto has verified the run: {:?}", app.run.plan);
    };
    let est = format!("est {e:.0e} ✓");
    let row = bar(&app);
    assert!(row.contains(&est) && row.contains("ΔE/E"), "{row}");
    app.journal.state = rattleback::app::RecState::On;
    let row = bar(&app);
    assert!(
        row.contains("● REC") && row.contains(&est) && row.contains("reversals"),
        "{row}"
    );
    // Replayed (playing), the same estimate, beside the replay's own fields (a session without
    // chapters counts none); followed, beside the fork's hint, the state shortened at 80
    // columns and whole from 100.
    app.journal.state = rattleback::app::RecState::Off;
    app.run.playing = true;
    let mut replay = replay_at_4_of_7();
    app.replay = Some(replay);
    let row = bar(&app);
    assert!(
        row.contains(&est) && row.contains("replay ×1") && !row.contains("chapter"),
        "{row}"
    );
    replay.chapters = 2;
    app.replay = Some(replay);
    let row = bar(&app);
    assert!(row.contains(&est) && row.contains("chapter 0/2"), "{row}");
    replay.live = Some(false);
    app.replay = Some(replay);
    // Playing, the whole state fits; the lecturer paused (`paused` is five columns longer than
    // `▶`), it is shortened rather than the estimate dropped.
    for (playing, state) in [
        (true, "▶ │ ● following live │"),
        (false, "paused │ ● live │"),
    ] {
        app.run.playing = playing;
        let row = bar(&app);
        assert!(
            [state, "f forks", "reversals", &est]
                .iter()
                .all(|s| row.contains(s)),
            "{row}"
        );
    }
    let wide = bar_at(&app, 100);
    assert!(
        wide.contains("● following live") && wide.contains("f forks") && wide.contains(&est),
        "{wide}"
    );
    // The follower paused itself: shortened at 80 columns too, whole at 100.
    replay.paused = true;
    app.replay = Some(replay);
    let row = bar(&app);
    assert!(
        ["paused │ you paused │", "f forks", "reversals", &est]
            .iter()
            .all(|s| row.contains(s)),
        "{row}"
    );
    let wide = bar_at(&app, 100);
    assert!(
        wide.contains("following, paused") && wide.contains(&est),
        "{wide}"
    );
}

/// Issue 54, 80×24: `t K W M` no longer stacks five panes into 19 rows. The most recent pane and
/// the portrait get readable rows (at least 8 inside each box), the others are listed on one
/// line, and Tab brings the next to the front.
#[test]
fn four_panes_at_80x24_are_cycled_not_squeezed() {
    let mut h = Headless::new("subcritical");
    h.play_until(10.0, 4.0);
    h.key(Key::Char(' '));
    for k in ['t', 'K', 'W', 'M'] {
        h.key(Key::Char(k));
    }
    h.key(Key::Esc);
    let right = ui::screen(&h.app, ratatui::layout::Rect::new(0, 0, 80, 24)).right;
    let check = |h: &Headless| {
        let layout = ui::column_layout(&h.app, right);
        assert!(layout.panes.len() >= 2, "{:?}", layout.panes);
        for (p, area) in &layout.panes {
            assert!(area.height >= 10, "{p:?} squeezed to {} rows", area.height);
        }
        let (_, hidden) = layout.hidden.as_ref().expect("the others are listed");
        assert!(!hidden.is_empty());
        layout
    };
    let first = check(&h);
    insta::assert_snapshot!("four_panes_80x24", screen_text(&h.app, 80, 24));
    h.key(Key::Tab);
    let second = check(&h);
    assert_ne!(
        first.panes, second.panes,
        "Tab brings another pane to the front"
    );
    insta::assert_snapshot!("four_panes_80x24_tab", screen_text(&h.app, 80, 24));
}

/// Issue 54: `y` shows the copied command whole (it was cut with `…`), and `v` shows every
/// message in full.
#[test]
fn the_copied_command_and_every_message_are_shown_whole() {
    let mut h = Headless::new("just-below");
    h.key(Key::Char('y'));
    let copied = match h.effects.last() {
        Some(rattleback::app::Effect::Copy(text)) => text.clone(),
        other => panic!("no copy: {other:?}"),
    };
    // As the explorer's shell answers outside tmux: the command saved beside the sessions.
    h.app.on_outcome(rattleback::app::Outcome::Copied {
        text: copied.clone(),
        tmux: false,
        file: Some(Ok(
            "/home/me/.local/share/rattleback/sessions/last-command.sh".into(),
        )),
    });
    let screen = screen_text(&h.app, 80, 24);
    insta::assert_snapshot!("copied_command_80x24", screen);
    assert!(screen.contains("last-command.sh"), "{screen}");
    // Every word of the command is on the screen (wrapped, never cut).
    let flat: String = screen.split_whitespace().collect::<Vec<_>>().join(" ");
    for word in copied.split_whitespace() {
        assert!(flat.contains(word), "{word} is not on the screen");
    }
    h.key(Key::Esc);
    h.key(Key::Char('v'));
    let log = screen_text(&h.app, 80, 24);
    assert!(log.contains("messages, in full"), "{log}");
    assert!(
        log.contains("last-command.sh") && log.contains("rattleback simulate"),
        "{log}"
    );
}
