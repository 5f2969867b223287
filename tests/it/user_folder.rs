//! The user's folder (`RATTLEBACK_CONFIG_DIR`): user presets are found by name and listed,
//! shadow shipped ones, duplicates are refused, and the explorer's picker and save use it;
//! a preset that breaks between listing and loading shows a dialog and the explorer goes on.
//! The binary gets the folder through `RATTLEBACK_CONFIG_DIR`; the app through its field.

use rattleback::app::mode::{Confirm, PickerRow};
use rattleback::app::{App, Key, Mode, Options};
use rattleback::scenario::shipped::resolve;

const USER: &str = "[preset]\nname = \"My lecture\"\ndescription = \"A user preset.\"\n[body]\nix = 3.0\niy = 1.0\niz = 1.0\n[spring]\nk = 100.0\n[initial]\ngamma_dot = 1.0\nalpha_dot = 0.2\n[run]\nt_end = 5.0\n";

fn bin(config: &std::path::Path, args: &[&str]) -> (i32, String, String) {
    let out = crate::common::rattleback()
        .args(args)
        .env("RATTLEBACK_CONFIG_DIR", config)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
#[allow(clippy::too_many_lines)] // One scenario, told start to end.
fn user_folder_end_to_end() {
    let config = std::env::temp_dir().join(format!("rattleback-config-{}", std::process::id()));
    let presets = config.join("presets");
    let _ = std::fs::remove_dir_all(&config);
    std::fs::create_dir_all(&presets).unwrap();
    std::fs::write(presets.join("lecture.toml"), USER).unwrap();

    // Found by name, listed as a user preset with its path.
    let (code, out, err) = bin(
        &config,
        &["simulate", "--preset", "lecture", "--format", "json"],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("\"My lecture\""));
    let (code, out, _) = bin(&config, &["presets", "--format", "json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let mine = v["presets"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["name"] == "lecture")
        .expect("listed");
    assert_eq!(mine["source"], "user");
    assert!(
        mine["path"]
            .as_str()
            .unwrap()
            .ends_with("presets/lecture.toml")
    );

    // Two presets with the same name: reported, exit 2.
    std::fs::write(presets.join("lecture-copy.toml"), USER).unwrap();
    let (code, _, err) = bin(&config, &["presets"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("two presets are named \"My lecture\""),
        "{err}"
    );
    std::fs::remove_file(presets.join("lecture-copy.toml")).unwrap();

    // The explorer: save a user preset, pick it, and survive a broken one. File effects run
    // as the loop runs them.
    let (mut app, _) = App::new(&resolve("subcritical", &[]).unwrap(), Options::at(30.0));
    let dir = Some(presets.clone());
    let mut press = |app: &mut App, key: Key| {
        let mut effects = app.on_key(key);
        let mut n = 0;
        while let Some(e) = effects.pop() {
            if let Some(o) = rattleback::explorer::file_outcome(&e, dir.as_deref()) {
                effects.extend(app.on_outcome(o));
            }
            n += 1;
        }
        n
    };
    let type_in = |app: &mut App, text: &str| {
        for c in text.chars() {
            press(app, Key::Char(c));
        }
    };
    press(&mut app, Key::Char('s'));
    type_in(&mut app, "saved-one: for the lecture");
    press(&mut app, Key::Enter);
    let saved = std::fs::read_to_string(presets.join("saved-one.toml"))
        .unwrap_or_else(|e| panic!("{e}: {:?}", app.status));
    assert!(saved.contains("for the lecture"), "{saved}");
    // Saving again under the same name asks first.
    press(&mut app, Key::Char('s'));
    type_in(&mut app, "saved-one");
    press(&mut app, Key::Enter);
    assert!(
        matches!(&app.mode, Mode::Prompt(p) if p.confirm == Confirm::Overwrite),
        "must ask before overwriting: {:?}",
        app.mode
    );
    press(&mut app, Key::Esc);

    let select = |app: &mut App, press: &mut dyn FnMut(&mut App, Key) -> usize| {
        press(app, Key::Char('p'));
        let Mode::Picker(picker) = &app.mode else {
            panic!("picker open")
        };
        let i = picker
            .rows
            .iter()
            .position(|r| matches!(r, PickerRow::Preset(e) if e.name == "lecture"))
            .expect("user preset in picker");
        while !matches!(&app.mode, Mode::Picker(p) if p.selected == i) {
            press(app, Key::Down);
        }
    };
    select(&mut app, &mut press);
    press(&mut app, Key::Enter);
    assert_eq!(app.scenario.name, "My lecture");
    assert!((app.scenario.settings.rattleback().unwrap().params().ix - 3.0).abs() < 1e-15);

    // Broken between listing and loading: a dialog, and the current scenario stays.
    select(&mut app, &mut press);
    std::fs::write(presets.join("lecture.toml"), "[body]\nix = -1\n").unwrap();
    press(&mut app, Key::Enter);
    let Mode::Dialog(dialog) = app.mode.clone() else {
        panic!("error dialog expected: {:?}", app.mode)
    };
    assert!(
        dialog.contains("lecture.toml") && dialog.contains("keeps the current"),
        "{dialog}"
    );
    assert_eq!(app.scenario.name, "My lecture");
    press(&mut app, Key::Char('x'));
    assert!(app.mode == Mode::Normal && !app.quit);
    // The broken file is its own row of the picker, with its own error.
    press(&mut app, Key::Char('p'));
    let Mode::Picker(picker) = &app.mode else {
        panic!("picker open")
    };
    assert!(picker.rows.iter().any(|r| matches!(r, PickerRow::Broken { name, error } if name == "lecture" && error.contains("ix"))));
    let _ = std::fs::remove_dir_all(&config);
}
