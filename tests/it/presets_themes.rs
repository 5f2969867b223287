//! Issue 5: shipped presets and themes, `presets`, `check`, themes and `NO_COLOR`, saving.

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::style::{Color, Modifier};
use rattleback::app::{App, Options};
use rattleback::scenario::preset::{self, Preset};
use rattleback::scenario::shipped::{SHIPPED, resolve};
use rattleback::scenario::store::{self, SaveError};
use rattleback::scenario::theme::{SHIPPED_THEMES, ThemeSpec};
use rattleback::ui::{self, UiOptions};

fn bin(args: &[&str]) -> (i32, String, String) {
    let out = crate::common::rattleback()
        .args(args)
        .env("RATTLEBACK_CONFIG_DIR", "/nonexistent/rattleback-test")
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn fixture(name: &str) -> String {
    format!("{}/tests/fixtures/{name}", root!())
}

#[test]
fn every_shipped_preset_and_theme_is_valid_and_described() {
    assert!(SHIPPED.len() >= 10);
    for (name, src) in SHIPPED {
        let p = Preset::parse(src, name, name, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            p.description.len() > 40,
            "{name} needs a description of what to look for"
        );
        // The file on disk is the one embedded.
        let disk = std::fs::read_to_string(format!("{}/presets/{name}.toml", root!())).unwrap();
        assert_eq!(&disk, src);
        // Saving and reading back gives the same preset.
        let again = Preset::parse(&p.to_toml(), "roundtrip", name, &[]).unwrap();
        assert_eq!(again, p, "{name} does not round-trip");
    }
    assert!(SHIPPED_THEMES.len() >= 4);
    for (name, src) in SHIPPED_THEMES {
        ThemeSpec::parse(src, name, name).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    }
}

#[test]
fn presets_lists_name_source_path_description_as_json() {
    let (code, out, err) = bin(&["presets", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let list = v["presets"].as_array().unwrap();
    assert_eq!(list.len(), SHIPPED.len());
    for e in list {
        for key in ["name", "source", "path", "description"] {
            assert!(e[key].is_string(), "{key} in {e}");
        }
        assert_eq!(e["source"], "shipped");
    }
}

#[test]
fn check_reports_every_problem_with_line_and_key() {
    let (code, out, err) = bin(&["check", &fixture("bad/many-problems.toml")]);
    assert_eq!(code, 2, "{out}");
    for needle in [
        ":5: body.ix",
        ":6: body.iyy",
        ":7: body.iz",
        ":10: spring.k",
        ":13: initial.gamma_dot",
        ":17: run.t_end",
        ":18: run.method",
        "body.iy: missing",
    ] {
        assert!(err.contains(needle), "missing '{needle}' in:\n{err}");
    }
    let shipped: Vec<String> = SHIPPED
        .iter()
        .map(|(n, _)| format!("{}/presets/{n}.toml", root!()))
        .collect();
    let mut args = vec!["check"];
    args.extend(shipped.iter().map(String::as_str));
    let (code, out, err) = bin(&args);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains(&format!("{} file(s) ok", SHIPPED.len())),
        "{out}"
    );
}

#[test]
fn bad_theme_colours_are_named_with_line_and_allowed_values() {
    let (code, _, err) = bin(&["check", &fixture("bad-themes/unknown-colour.toml")]);
    assert_eq!(code, 2);
    assert!(
        err.contains(":6: colors.separatrix: unknown colour 'yelow'; allowed:"),
        "{err}"
    );
    assert!(
        err.contains(":8: colors.trail") && err.contains("#rrggbb"),
        "{err}"
    );
    let (code, _, err) = bin(&["--theme", "nonesuch"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("nonesuch") && err.contains("high-contrast"),
        "{err}"
    );
}

#[test]
fn unreadable_file_is_reported_not_panicked() {
    let dir = fixture("bad");
    let (code, _, err) = bin(&["check", &dir]);
    assert_eq!(code, 2);
    assert!(
        err.contains("cannot read") && !err.contains("panicked"),
        "{err}"
    );
}

#[test]
fn no_color_leaves_no_colour_but_keeps_the_selection_visible() {
    let preset = resolve("subcritical", &[]).unwrap();
    let (app, _) = App::new(&preset, Options::at(30.0));
    let spec = ThemeSpec::parse(SHIPPED_THEMES[0].1, "default", "default").unwrap();
    let options = UiOptions::new(ratatui::symbols::Marker::Braille, &spec, &[], true);
    let mut terminal = Terminal::new(TestBackend::new(80, 24)).unwrap();
    terminal
        .draw(|f| ui::draw(f, &app, &options, &mut ui::Cache::default()))
        .unwrap();
    let buffer = terminal.backend().buffer();
    assert!(
        buffer.content().iter().all(|c| c.fg == Color::Reset),
        "a coloured cell under NO_COLOR"
    );
    let selected = buffer
        .content()
        .iter()
        .filter(|c| c.modifier.contains(Modifier::REVERSED))
        .count();
    assert!(
        selected > 20,
        "selection and status must stay visible without colour"
    );
}

#[test]
fn saving_is_atomic_and_never_overwrites_without_consent() {
    let dir = std::env::temp_dir().join(format!("rattleback-save-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let text = resolve("tapping", &[]).unwrap().to_toml();
    let path = store::save(Some(&dir), "mine", &text, false).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
    assert!(matches!(
        store::save(Some(&dir), "mine", "x", false),
        Err(SaveError::Exists(_))
    ));
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        text,
        "refused save changed the file"
    );
    store::save(Some(&dir), "mine", &text, true).unwrap();
    assert!(matches!(
        store::save(Some(&dir), "../evil", &text, false),
        Err(SaveError::BadName(_))
    ));
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(Result::ok)
        .filter(|e| e.file_name().to_string_lossy().contains("tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left behind");
    assert!(preset::check(&text, "saved").is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 28: themes take the 256-colour palette (an index 0–255, bare or in quotes) and short
/// hex (`#rgb`) beside names and `#rrggbb`; each reaches the screen as that colour; an index
/// out of range is named with its line.
#[test]
fn themes_take_palette_indices_and_short_hex() {
    let dir = std::env::temp_dir().join(format!("rattleback-palette-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("palette.toml");
    std::fs::write(
        &path,
        "[theme]\nname = \"Palette\"\n\n[colors]\ncontour = \"238\"\nseparatrix = 214\nstart_level = 6\ntrail = 114\neffective = \"#c6d\"\ncurrent = \"#ff0000\"\nreversal = \"yellow\"\nerror = \"red\"\ndim = 245\n",
    )
    .unwrap();
    let p = path.to_str().unwrap();
    let (code, _, err) = bin(&["check", p]);
    assert_eq!(code, 0, "{err}");
    let spec = rattleback::scenario::theme::theme(p).unwrap();
    let t = rattleback::ui::Theme::from_spec(&spec, false);
    assert_eq!(t.contour, Color::Indexed(238));
    assert_eq!(t.separatrix, Color::Indexed(214));
    assert_eq!(t.start_level, Color::Cyan, "0–15 are the ANSI colours");
    assert_eq!(t.trail, Color::Indexed(114));
    assert_eq!(t.effective, Color::Rgb(0xcc, 0x66, 0xdd));
    assert_eq!(t.dim, Color::Indexed(245));
    // On screen: the trail is drawn in colour 114.
    let mut h = crate::common::Headless::new("subcritical");
    h.play_until(3.0, 4.0);
    let options =
        rattleback::ui::UiOptions::new(ratatui::symbols::Marker::Braille, &spec, &[], false);
    let mut terminal = ratatui::Terminal::new(ratatui::backend::TestBackend::new(80, 24)).unwrap();
    terminal
        .draw(|f| rattleback::ui::draw(f, &h.app, &options, &mut rattleback::ui::Cache::default()))
        .unwrap();
    let cells = terminal.backend().buffer().content();
    assert!(
        cells.iter().any(|c| c.fg == Color::Indexed(114)),
        "no trail cell in 114"
    );
    assert!(
        cells.iter().any(|c| c.fg == Color::Indexed(238)),
        "no level cell in 238"
    );
    // Out of range, bare or quoted; a bad short hex.
    std::fs::write(
        &path,
        "[theme]\nname = \"Bad\"\n\n[colors]\ncontour = 256\nseparatrix = \"300\"\nstart_level = \"#12\"\ntrail = \"green\"\neffective = \"magenta\"\ncurrent = \"red\"\nreversal = \"yellow\"\nerror = \"red\"\ndim = \"gray\"\n",
    )
    .unwrap();
    let (code, _, err) = bin(&["check", p]);
    assert_eq!(code, 2);
    assert!(err.contains(":5: colors.contour: 256 is not a colour: a palette index is a whole number from 0 to 255"), "{err}");
    assert!(
        err.contains(":6: colors.separatrix:") && err.contains("0 to 255"),
        "{err}"
    );
    assert!(
        err.contains(":7: colors.start_level:") && err.contains("#rgb"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
