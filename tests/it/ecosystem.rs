//! Issue 15, items 2 and 3: exports from the explorer, the copied command line, the
//! configuration file, the user's keys and the mouse.
#![allow(clippy::float_cmp)] // values copied, not computed, are compared exactly

use crate::common;

use common::{Headless, bin_in};
use rattleback::app::user_keys::UserKeys;
use rattleback::app::{Action, Effect, Key, Options};

fn temp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("rattleback-eco-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn the_export_writes_a_portrait_and_a_csv_that_says_what_made_it() {
    let mut h = Headless::new("subcritical");
    h.play_until(10.0, 4.0);
    let effects = h.app.on_key(Key::Char('x'));
    assert_eq!(
        effects,
        vec![Effect::Export {
            stem: "subcritical-start".to_owned()
        }]
    );
    let dir = temp("export");
    let paths = rattleback::export::export(&h.app, &dir, "subcritical-start").unwrap();
    assert_eq!(paths.len(), 2);
    let name = paths[0].file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        name.starts_with("subcritical-start-20")
            && std::path::Path::new(&name)
                .extension()
                .is_some_and(|e| e == "svg"),
        "{name}"
    );
    let svg = std::fs::read_to_string(&paths[0]).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..80]);
    assert!(svg.contains("alpha_dot") && svg.contains("separatrix"));
    // Axis labels are short: no `9.999999999999999e-5`.
    let labels: Vec<&str> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| {
            t.split_once('>')
                .and_then(|(_, rest)| rest.split_once("</text>"))
        })
        .map(|(label, _)| label)
        .collect();
    assert!(labels.len() > 8, "{labels:?}");
    for l in &labels {
        assert!(
            l.split(|c: char| !(c.is_ascii_digit() || c == '.'))
                .all(|w| w.len() <= 6),
            "a long number in a label: {l}"
        );
    }
    let csv = std::fs::read_to_string(&paths[1]).unwrap();
    let meta: std::collections::BTreeMap<&str, &str> = csv
        .lines()
        .take_while(|l| l.starts_with("# "))
        .filter_map(|l| l[2..].split_once(" = "))
        .collect();
    assert_eq!(meta["preset"], "Subcritical start");
    assert_eq!(meta["method"], "auto");
    assert_eq!(meta["tolerance"].parse::<f64>().unwrap(), 1e-9);
    assert!(meta["program"].starts_with("rattleback "));
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(
        rows[0],
        "t,alpha,alpha_dot,energy_error,limit_alpha,limit_alpha_dot"
    );
    assert_eq!(rows.len() - 1, h.app.run.trail_shown().len());
    let last: Vec<f64> = rows[rows.len() - 1]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let shown = h.app.run.trail_shown().last().unwrap();
    assert_eq!(last[1].to_bits(), shown.slow.to_bits());
    assert!(last[4].is_finite(), "the limit's columns are filled");
    // A second export never replaces the first.
    let again = rattleback::export::export(&h.app, &dir, "subcritical-start").unwrap();
    assert_ne!(again[0], paths[0]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The `(x, y)` pixel pairs of one `<polyline` element's text.
fn polyline_points_of(element: &str) -> Vec<(f64, f64)> {
    element
        .split_once("points=\"")
        .and_then(|(_, rest)| rest.split_once('"'))
        .map(|(pts, _)| {
            pts.split_whitespace()
                .filter_map(|xy| {
                    let (x, y) = xy.split_once(',')?;
                    Some((x.parse().ok()?, y.parse().ok()?))
                })
                .collect()
        })
        .unwrap_or_default()
}

/// The `(x, y)` pixel pairs of every polyline in an SVG.
fn polyline_points(svg: &str) -> Vec<(f64, f64)> {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|p| p.split_once("points=\"").map(|(_, rest)| rest))
        .filter_map(|p| p.split_once('"').map(|(pts, _)| pts))
        .flat_map(|pts| {
            pts.split_whitespace().filter_map(|xy| {
                let (x, y) = xy.split_once(',')?;
                Some((x.parse().ok()?, y.parse().ok()?))
            })
        })
        .collect()
}

/// Issue 28, item 5: the export is the screen. The SVG's axes span the screen's range (the
/// review's `subcritical` exported α ±0.8 against the screen's ±1.571); the level sets, the
/// start's level and the separatrix are drawn; curves leave the frame instead of running along
/// it; tick labels are round (no `-1.1e-16`); the legend sits right of the plot, over no data.
#[test]
fn the_exported_portrait_is_the_screens_view() {
    let mut h = Headless::new("subcritical");
    h.play_until(12.0, 4.0);
    let b = h.app.bounds();
    let svg = rattleback::export::portrait_svg(&h.app).unwrap();
    let labels: Vec<String> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
        .map(|(l, _)| l.trim().replace("&apos;", "'"))
        .collect();
    assert!(!labels.iter().any(|l| l.contains("e-1")), "{labels:?}");
    let numbers: Vec<f64> = labels.iter().filter_map(|l| l.parse().ok()).collect();
    // Some tick labels reach past 80 % of each half-range of alpha: the screen's range.
    let reach = numbers.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(
        reach >= 0.8 * b.x[1].abs().max(b.x[0].abs()) * 0.9,
        "{numbers:?} vs {b:?}"
    );
    for word in [
        "energy levels",
        "start's level",
        "separatrix",
        "full motion",
        "now",
    ] {
        assert!(
            labels.iter().any(|l| l.contains(word)),
            "legend lacks {word}"
        );
    }
    // Many level-set pieces (dotted lines are many short polylines).
    assert!(svg.matches("<polyline").count() > 100, "level sets missing");
    // Every curve is inside the plot's column (x ≤ 740) or is a legend sample right of it;
    // none crosses into the legend, whose text is right of the plot.
    let pts = polyline_points(&svg);
    let data = pts.iter().filter(|p| p.0 <= 740.0).count();
    let legend = pts.len() - data;
    assert!(data > 1000 && legend > 0 && legend < 20, "{data} {legend}");
    let legend_x: Vec<f64> = svg
        .split("<text")
        .skip(1)
        .filter(|t| t.contains("full motion"))
        .filter_map(|t| t.split_once("x=\"").and_then(|(_, r)| r.split_once('"')))
        .filter_map(|(x, _)| x.parse().ok())
        .collect();
    assert!(legend_x.iter().all(|&x| x >= 740.0), "{legend_x:?}");
    // Zoomed in, the curves leave the frame: clipped, not clamped onto it (no segment runs
    // along an edge of the plot).
    for _ in 0..2 {
        h.key(Key::Char('z'));
    }
    let svg = rattleback::export::portrait_svg(&h.app).unwrap();
    let lines: Vec<Vec<(f64, f64)>> = svg
        .split("<polyline")
        .skip(1)
        .map(polyline_points_of)
        .filter(|l| l.iter().all(|p| p.0 <= 740.0))
        .collect();
    let all: Vec<(f64, f64)> = lines.iter().flatten().copied().collect();
    assert!(all.len() > 200, "{} points", all.len());
    let (x0, x1, y0, y1) = all.iter().fold(
        (f64::MAX, f64::MIN, f64::MAX, f64::MIN),
        |(a, b, c, d), p| (a.min(p.0), b.max(p.0), c.min(p.1), d.max(p.1)),
    );
    let edge = |u: f64, v: f64| (u - v).abs() < 0.01;
    let along = lines
        .iter()
        .flat_map(|l| l.windows(2))
        .filter(|w| {
            (edge(w[0].1, y0) && edge(w[1].1, y0))
                || (edge(w[0].1, y1) && edge(w[1].1, y1))
                || (edge(w[0].0, x0) && edge(w[1].0, x0))
                || (edge(w[0].0, x1) && edge(w[1].0, x1))
        })
        .count();
    assert_eq!(along, 0, "segments along the frame");
}

#[test]
fn the_copied_command_line_runs_exactly_the_explorers_settings() {
    let mut h = Headless::new("just-below");
    for k in [Key::Down, Key::Right, Key::Right] {
        h.key(k); // iy nudged twice
    }
    let effects = h.app.on_key(Key::Char('y'));
    let [Effect::Copy(text)] = effects.as_slice() else {
        panic!("{effects:?}")
    };
    // Said whole once the shell says where it went (issue 68).
    h.app.on_outcome(rattleback::app::Outcome::Copied {
        text: text.clone(),
        tmux: true,
        file: None,
    });
    assert!(h.app.status.as_ref().unwrap().text.contains(text.as_str()));
    let args: Vec<&str> = text.split_whitespace().collect();
    let cli = <rattleback::commands::cli::Cli as clap::Parser>::try_parse_from(&args).unwrap();
    let Some(rattleback::commands::cli::Command::Simulate(sim)) = cli.command else {
        panic!("not simulate: {text}")
    };
    let preset = rattleback::scenario::shipped::resolve(&sim.preset, &sim.set).unwrap();
    let s = h.app.scenario.settings;
    assert_eq!(preset.model, s.model);
    assert_eq!(sim.method, Some(s.method));
    assert_eq!(sim.tolerance, Some(s.tolerance));
    assert_eq!(sim.t_end, Some(s.t_end));
}

#[test]
fn user_keys_work_and_help_shows_them() {
    let keys = UserKeys::parse(&[
        ("zoom_in".to_owned(), vec!["i".to_owned()]),
        ("toggle_map".to_owned(), vec!["ctrl-g".to_owned()]),
    ])
    .unwrap();
    let options = Options {
        keys,
        ..Options::at(30.0)
    };
    assert_eq!(options.action_for(Key::Char('i')), Some(Action::ZoomIn));
    assert_eq!(options.action_for(Key::Char('z')), Some(Action::ZoomIn));
    let preset = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
    let (mut app, _) = rattleback::app::App::new(&preset, options);
    let zoom = app.view.view.zoom;
    app.on_key(Key::Char('i'));
    assert!(app.view.view.zoom > zoom, "the user's key zooms");
    app.on_key(Key::Char('?'));
    let backend = ratatui::backend::TestBackend::new(100, 40);
    let mut terminal = ratatui::Terminal::new(backend).unwrap();
    let mut cache = rattleback::ui::Cache::default();
    terminal
        .draw(|f| rattleback::ui::draw(f, &app, &rattleback::ui::UiOptions::default(), &mut cache))
        .unwrap();
    let screen: String = terminal
        .backend()
        .buffer()
        .content()
        .iter()
        .map(ratatui::buffer::Cell::symbol)
        .collect();
    assert!(screen.contains("z/Z +i"), "help shows the user's key");
    assert!(screen.contains("+Ctrl-G"), "help shows the user's key");
}

#[test]
fn a_click_in_the_portrait_sets_the_start_there() {
    let mut h = Headless::new("subcritical");
    let backend = ratatui::backend::TestBackend::new(120, 40);
    let mut terminal = ratatui::Terminal::new(backend).unwrap();
    let mut cache = rattleback::ui::Cache::default();
    terminal
        .draw(|f| {
            rattleback::ui::draw(f, &h.app, &rattleback::ui::UiOptions::default(), &mut cache);
        })
        .unwrap();
    let (plot, b) = cache.plot.expect("the portrait was drawn");
    assert_eq!(
        rattleback::ui::portrait_point(&cache, 0, 0),
        None,
        "outside"
    );
    let (col, row) = (plot.x + plot.width / 4, plot.y + plot.height / 4);
    let (alpha, alpha_dot) = rattleback::ui::portrait_point(&cache, col, row).unwrap();
    assert!(b.x[0] < alpha && alpha < f64::midpoint(b.x[0], b.x[1]));
    assert!(f64::midpoint(b.y[0], b.y[1]) < alpha_dot && alpha_dot < b.y[1]);
    h.app.on_key(Key::Char('R'));
    h.app.on_outcome(rattleback::app::Outcome::Recording(
        Ok("click.jsonl".into()),
    ));
    let generation = h.app.run.generation;
    let effects = h.app.set_start_point(alpha, alpha_dot);
    h.exec(effects);
    assert!(h.app.run.generation > generation, "restarted");
    let s = *h.app.scenario.settings.rattleback().unwrap().start();
    assert_eq!((s.alpha, s.alpha_dot), (alpha, alpha_dot));
    assert_eq!(s.gamma_dot, 1.0, "the tilt rate stays");
    let sets: Vec<String> = h
        .app
        .take_journal()
        .into_iter()
        .filter_map(|(_, _, e)| match e {
            rattleback::app::journal::Event::Set { field, .. } => Some(field),
            _ => None,
        })
        .collect();
    assert_eq!(sets, ["alpha", "alpha_dot"]);
}

#[test]
fn the_guides_config_example_is_accepted_as_written() {
    // docs/guide.md's example under "## Configuration", copied into a config file: every key
    // it shows must load (its `[keys]` once bound 'p', which the explorer already uses for the
    // presets, and was refused).
    let guide = include_str!("../../docs/guide.md");
    let section = &guide[guide.find("## Configuration").expect("the section")..];
    let start = section.find("```toml\n").expect("a toml block") + "```toml\n".len();
    let block = &section[start..start + section[start..].find("```").expect("closed")];
    assert!(block.contains("[keys]"), "{block}");
    let dir = temp("guide-config");
    std::fs::write(dir.join("config.toml"), block).unwrap();
    let (code, out, err) = bin_in(&dir, &["config", "show"]);
    assert_eq!(code, 0, "the guide's example is refused: {err}");
    let code = block.lines().map(|l| l.split('#').next().unwrap_or(""));
    for line in code.filter(|l| l.contains(" = ")) {
        let key = line.split(" = ").next().unwrap().trim();
        assert!(
            out.contains(&format!("{key} = ")),
            "{key} missing from {out}"
        );
    }
}

/// The README's config example loads as written, and its rebinding takes effect.
#[test]
fn the_readmes_config_example_is_accepted_as_written() {
    let readme = include_str!("../../README.md");
    let section = &readme[readme.find("## Configuration").expect("the section")..];
    let start = section.find("```toml\n").expect("a toml block") + "```toml\n".len();
    let block = &section[start..start + section[start..].find("```").expect("closed")];
    let dir = temp("readme-config");
    std::fs::write(dir.join("config.toml"), block).unwrap();
    let (code, out, err) = bin_in(&dir, &["config", "show"]);
    assert_eq!(code, 0, "the README's example is refused: {err}");
    assert!(out.contains("toggle_play = [\"none\", \"p\"]"), "{out}");
    let (code, out, _) = bin_in(&dir, &["doctor"]);
    assert_eq!(code, 0);
    assert!(out.contains("(valid)"), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn config_path_show_and_a_bad_config_file() {
    let dir = temp("config");
    let (code, out, _) = bin_in(&dir, &["config", "path"]);
    assert_eq!(code, 0);
    assert_eq!(out.trim(), dir.join("config.toml").display().to_string());
    let (code, out, _) = bin_in(&dir, &["config", "show"]);
    assert_eq!(code, 0);
    assert!(out.contains("# no config file"), "{out}");
    assert!(out.contains("# fps = 30"), "{out}");
    std::fs::write(
        dir.join("config.toml"),
        "preset = \"supercritical\"\nfps = 20\nmouse = true\n\n[keys]\nzoom_in = \"i\"\n",
    )
    .unwrap();
    let (code, out, err) = bin_in(&dir, &["config", "show"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("preset = \"supercritical\"") && out.contains("fps = 20"));
    assert!(out.contains("zoom_in = \"i\""));
    // A key taken by the explorer: the file, the line, the key, what holds it; exit 2 before
    // any terminal is touched.
    std::fs::write(
        dir.join("config.toml"),
        "fps = 20\n\n[keys]\nzoom_in = \"i\"\nzoom_out = \"q\"\n",
    )
    .unwrap();
    let (code, _, err) = bin_in(&dir, &[]);
    assert_eq!(code, 2);
    assert!(
        err.contains("config.toml:5: keys.zoom_out: 'q' is already bound to quit"),
        "{err}"
    );
    std::fs::write(dir.join("config.toml"), "fsp = 20\n").unwrap();
    let (code, _, err) = bin_in(&dir, &["config", "show"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("config.toml:1: fsp: unknown key `fsp`"),
        "{err}"
    );
    assert!(err.contains("did you mean `fps`?"), "{err}");
    // Every command reads it the same way (issue 54): a headless one is stopped by it too,
    // with the same message; `doctor` reports it.
    let (code, _, err) = bin_in(&dir, &["simulate", "--t-end", "1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("config.toml:1: fsp"), "{err}");
    let (code, out, _) = bin_in(&dir, &["doctor"]);
    assert_eq!(code, 0);
    assert!(out.contains("invalid"), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 28: keys can be rebound and unbound (`"none"` first takes an action's defaults away,
/// which frees them); the help and the footer show the keys in effect.
#[test]
fn keys_rebind_and_unbind_and_help_and_footer_follow() {
    let keys = UserKeys::parse(&[
        (
            "presets".to_owned(),
            vec!["none".to_owned(), "P".to_owned()],
        ),
        (
            "toggle_play".to_owned(),
            vec!["none".to_owned(), "p".to_owned()],
        ),
        ("clear_trail".to_owned(), vec!["none".to_owned()]),
    ])
    .unwrap();
    let options = Options {
        keys,
        ..Options::at(30.0)
    };
    let preset = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
    let (mut app, _) = rattleback::app::App::new(&preset, options);
    let draw = |app: &rattleback::app::App| -> String {
        let mut terminal =
            ratatui::Terminal::new(ratatui::backend::TestBackend::new(120, 44)).unwrap();
        let mut cache = rattleback::ui::Cache::default();
        terminal
            .draw(|f| {
                rattleback::ui::draw(f, app, &rattleback::ui::UiOptions::default(), &mut cache);
            })
            .unwrap();
        let b = terminal.backend().buffer();
        (0..b.area.height)
            .map(|y| {
                (0..b.area.width)
                    .map(|x| b[(x, y)].symbol().to_owned())
                    .collect::<String>()
                    + "\n"
            })
            .collect()
    };
    let screen = draw(&app);
    let footer = screen.lines().nth(43).unwrap();
    assert!(
        footer.contains("p play"),
        "the footer names the new key: {footer}"
    );
    assert!(!footer.contains("space play"), "{footer}");
    // space does nothing now; p plays.
    let playing = app.run.playing;
    app.on_key(Key::Char(' '));
    assert_eq!(app.run.playing, playing, "space no longer plays");
    app.on_key(Key::Char('p'));
    assert_ne!(app.run.playing, playing, "p toggles play");
    app.on_key(Key::Char('?'));
    let help = draw(&app);
    assert!(
        help.contains(" p ") && help.contains("play / pause"),
        "{help}"
    );
    assert!(
        help.contains(" P ") && help.contains("pick a preset"),
        "{help}"
    );
    let clear = help
        .lines()
        .find(|l| l.contains("clear the trail"))
        .unwrap();
    assert!(clear.contains("none"), "{clear}");
}

/// Issue 28: every problem of a config file is said in one run (in the file's order), with how
/// to free a held key; `--config FILE` reads another file, before or after the command.
#[test]
fn every_config_error_at_once_and_config_file() {
    // Every problem of a file in one run, in its order; exit 2.
    let dir = temp("config-errors");
    std::fs::write(
        dir.join("config.toml"),
        "fsp = 20\nmarker = \"brail\"\n[keys]\nzom_in = \"i\"\nzoom_out = \"q\"\ntoggle_play = \"p\"\n",
    )
    .unwrap();
    let (code, _, err) = bin_in(&dir, &["config", "show"]);
    assert_eq!(code, 2);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 5, "{err}");
    for (line, what) in [
        (1, "fsp"),
        (2, "marker"),
        (4, "keys.zom_in"),
        (5, "keys.zoom_out"),
        (6, "keys.toggle_play"),
    ] {
        assert!(
            lines
                .iter()
                .any(|l| l.contains(&format!("config.toml:{line}: {what}:"))),
            "{line} {what}: {err}"
        );
    }
    assert!(
        err.contains("presets = \"none\""),
        "how to free the key: {err}"
    );
    // --config FILE: another file, before or after the command; a missing one is exit 2.
    let other = dir.join("lecture.toml");
    std::fs::write(
        &other,
        "fps = 12\n[keys]\npresets = [\"none\", \"P\"]\ntoggle_play = [\"none\", \"p\"]\n",
    )
    .unwrap();
    let o = other.to_str().unwrap();
    for args in [
        vec!["--config", o, "config", "show"],
        vec!["config", "show", "--config", o],
    ] {
        let (code, out, err) = bin_in(&dir, &args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(
            out.contains(&format!("# from {o}")) && out.contains("fps = 12"),
            "{out}"
        );
    }
    let (code, out, _) = bin_in(&dir, &["--config", o, "config", "path"]);
    assert_eq!((code, out.trim()), (0, o));
    let (code, _, err) = bin_in(&dir, &["--config", "/nonexistent.toml", "config", "show"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--config /nonexistent.toml: no such file"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_dumb_terminal_gets_one_line_from_every_interactive_entry_point() {
    // Issue 28: with TERM=dumb the program used to draw a full screen of escape codes. Every
    // command that opens the explorer refuses it in one line (after the preset is checked);
    // the headless commands do not care.
    let session = concat!(root!(), "/tests/fixtures/sessions/lecture.jsonl");
    let run = |args: &[&str]| {
        let out = crate::common::rattleback()
            .args(args)
            .env("RATTLEBACK_CONFIG_DIR", temp("dumb"))
            .env("TERM", "dumb")
            .output()
            .expect("the binary runs");
        (
            out.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    for args in [
        &[][..],
        &["--preset", "kapitza-falls"],
        &["replay", session],
        &["follow", session],
        &["compare", "subcritical", "celt-clockwise"],
        &["lesson", "first-reversal"],
    ] {
        let (code, out, err) = run(args);
        // Exit 2, as the other refusals of a terminal (a redirection, ssh without -t).
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}: {out}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains("TERM=dumb"), "{args:?}: {err}");
    }
    // A bad preset is still named first; headless commands run.
    let (code, _, err) = run(&["--preset", "nope"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("no preset named"), "{err}");
    let (code, out, _) = run(&["simulate", "--format", "csv"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("# program"), "{out}");
}

#[test]
fn colours_follow_the_flag_then_no_color_then_clicolor() {
    use rattleback::commands::cli::ColorChoice::{Always, Auto, Never};
    // (choice, NO_COLOR, CLICOLOR, CLICOLOR_FORCE) → colours off?
    let cases = [
        (Auto, None, None, None, false),
        (Auto, Some("1"), None, None, true),
        (Auto, Some(""), None, None, false),
        (Auto, None, Some("0"), None, true),
        (Auto, None, Some("1"), None, false),
        (Auto, None, Some("0"), Some("1"), false),
        (Auto, None, Some("0"), Some("0"), true),
        (Auto, Some("1"), None, Some("1"), true),
        (Always, Some("1"), Some("0"), None, false),
        (Never, None, None, Some("1"), true),
    ];
    for (choice, no_color, clicolor, force, off) in cases {
        assert_eq!(
            choice.colours_off(no_color, clicolor, force),
            off,
            "{choice:?} NO_COLOR={no_color:?} CLICOLOR={clicolor:?} CLICOLOR_FORCE={force:?}"
        );
    }
    // End to end, through what a user can see: a cast exported with CLICOLOR=0, or with
    // --color never, has no colour in it; --color always overrides NO_COLOR.
    let session = concat!(root!(), "/tests/fixtures/sessions/subcritical.jsonl");
    let dir = temp("colour-cast");
    let cast = |name: &str, flag: &str, env: &[(&str, &str)]| {
        let out = dir.join(name);
        let mut cmd = crate::common::rattleback();
        cmd.args(["replay", session, "--export-cast"])
            .arg(&out)
            .args(["--color", flag])
            .env("RATTLEBACK_CONFIG_DIR", &dir)
            .env_remove("NO_COLOR")
            .env_remove("CLICOLOR")
            .env_remove("CLICOLOR_FORCE");
        for (k, v) in env {
            cmd.env(k, v);
        }
        assert!(cmd.output().unwrap().status.success());
        std::fs::read_to_string(out).unwrap()
    };
    let coloured = |text: &str| text.contains("\\u001b[38;");
    assert!(coloured(&cast("auto.cast", "auto", &[])));
    assert!(!coloured(&cast(
        "clicolor.cast",
        "auto",
        &[("CLICOLOR", "0")]
    )));
    assert!(!coloured(&cast("never.cast", "never", &[])));
    assert!(coloured(&cast(
        "always.cast",
        "always",
        &[("NO_COLOR", "1")]
    )));
}
