//! The README's key tables and screenshot are the program's own output: they cannot drift.

use rattleback::app::keys::{KEYMAP, REPLAY_KEYMAP, map_markdown, markdown};

fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap()
}

#[test]
fn key_tables_are_generated_from_the_keymaps() {
    let text = readme();
    for (what, table) in [
        ("explorer", markdown(KEYMAP)),
        ("replay", markdown(REPLAY_KEYMAP)),
        ("regime map", map_markdown()),
    ] {
        assert!(
            text.contains(&table),
            "the README's {what} key table differs from `cargo run --example key_tables`:\n{table}"
        );
    }
}

#[test]
fn the_screenshot_is_the_snapshot_of_the_80x24_screen() {
    let snap = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/snapshots/explorer_ui__screen_80x24.snap"
    ))
    .unwrap();
    let screen = snap.splitn(3, "---\n").nth(2).expect("insta header");
    assert!(
        readme().contains(&format!("```text\n{screen}```")),
        "copy tests/snapshots/explorer_ui__screen_80x24.snap into the README"
    );
}
