//! The user's folder (`RATTLEBACK_CONFIG_DIR`): user presets are found by name and listed,
//! shadow shipped ones, duplicates are refused, and the explorer's picker and save use it;
//! a preset that breaks between listing and loading shows a dialog and the explorer goes on.
//! The binary gets the folder through `RATTLEBACK_CONFIG_DIR`; the app through its field.

use std::process::Command;

use rattleback::app::{App, Key, Options};
use rattleback::scenario::shipped::resolve;

const USER: &str = "[preset]\nname = \"My lecture\"\ndescription = \"A user preset.\"\n[body]\nix = 3.0\niy = 1.0\niz = 1.0\n[spring]\nk = 100.0\n[initial]\ngamma_dot = 1.0\nalpha_dot = 0.2\n[run]\nt_end = 5.0\n";

fn bin(config: &std::path::Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rattleback"))
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
    let mine = v
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

    // The explorer: save a user preset, pick it, and survive a broken one.
    let (mut app, _) = App::new(&resolve("subcritical", &[]).unwrap(), Options { fps: 30.0 });
    app.user_dir = Some(presets.clone());
    app.on_key(Key::Char('s'));
    for c in "saved-one".chars() {
        app.on_key(Key::Char(c));
    }
    app.on_key(Key::Enter);
    assert!(
        presets.join("saved-one.toml").is_file(),
        "{:?}",
        app.message
    );
    // Saving again under the same name asks first.
    app.on_key(Key::Char('s'));
    for c in "saved-one".chars() {
        app.on_key(Key::Char(c));
    }
    app.on_key(Key::Enter);
    assert!(
        app.saving.as_ref().is_some_and(|p| p.confirm),
        "must ask before overwriting"
    );
    app.on_key(Key::Esc);

    app.on_key(Key::Char('p'));
    let picker = app.picker.as_ref().expect("picker open");
    let i = picker
        .entries
        .iter()
        .position(|e| e.name == "lecture")
        .expect("user preset in picker");
    while app.picker.as_ref().unwrap().selected != i {
        app.on_key(Key::Down);
    }
    let commands = app.on_key(Key::Enter);
    assert!(!commands.is_empty(), "loading restarts");
    assert_eq!(app.name, "My lecture");
    assert!((app.settings.params.ix - 3.0).abs() < 1e-15);

    // Broken between listing and loading: a dialog, and the current scenario stays.
    app.on_key(Key::Char('p'));
    let i = app
        .picker
        .as_ref()
        .unwrap()
        .entries
        .iter()
        .position(|e| e.name == "lecture")
        .unwrap();
    while app.picker.as_ref().unwrap().selected != i {
        app.on_key(Key::Down);
    }
    std::fs::write(presets.join("lecture.toml"), "[body]\nix = -1\n").unwrap();
    app.on_key(Key::Enter);
    let dialog = app.dialog.clone().expect("error dialog");
    assert!(
        dialog.contains("lecture.toml") && dialog.contains("keeps the current"),
        "{dialog}"
    );
    assert_eq!(app.name, "My lecture");
    app.on_key(Key::Char('x'));
    assert!(app.dialog.is_none() && !app.quit);
    let _ = std::fs::remove_dir_all(&config);
}
