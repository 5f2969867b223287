//! Prints the explorer's, the regime map's and the replay's key tables in Markdown, from the keymap tables
//! (docs/guide.md's tables are this output; `tests/it/readme.rs` checks it): `cargo run --example key_tables`.

fn main() {
    print!(
        "{}",
        rattleback::app::keys::markdown(&rattleback::app::keys::KEYMAP)
    );
    println!();
    print!("{}", rattleback::app::keys::map_markdown());
    println!();
    print!(
        "{}",
        rattleback::app::keys::markdown(rattleback::app::keys::REPLAY_KEYMAP)
    );
}
