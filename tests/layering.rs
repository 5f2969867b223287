//! The physics core stays headless: no file under `src/physics/` may mention a terminal crate.

use std::path::Path;

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable source dir") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn physics_never_mentions_a_terminal_crate() {
    let mut files = Vec::new();
    rust_files(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src/physics"),
        &mut files,
    );
    assert!(files.len() > 5, "physics sources not found");
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable");
        for banned in [
            "ratatui",
            "crossterm",
            "std::thread",
            "std::time",
            "Instant",
        ] {
            assert!(
                !text.contains(banned),
                "{} mentions {banned}",
                file.display()
            );
        }
    }
}
