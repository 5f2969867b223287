//! The program's own integration test target, named `it` like the tests' package's one
//! (`tests/it/Cargo.toml`): cargo builds a package's binary before its integration tests, so
//! `cargo test --test it ...` builds `rattleback` fresh before the tests that drive it run, even
//! when a filter selects only those tests.

#[test]
fn the_program_is_built_and_answers() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_rattleback"))
        .arg("--version")
        .stdin(std::process::Stdio::null())
        .output()
        .expect("the program runs");
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("rattleback "), "{text}");
}
