//! Writes the JSON Schemas of the outputs other than `simulate`'s, and the lesson file's, generated from the types
//! (schemars), into `docs/schemas/NAME.schema.json`: `cargo run --example output_schemas`
//! (`tests/it/schemas.rs` checks the checked-in copies are this output and that real outputs
//! validate).

fn main() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/schemas");
    for (name, text) in rattleback::commands::outputs::schemas() {
        let path = dir.join(format!("{name}.schema.json"));
        std::fs::write(&path, text).expect("docs/schemas is writable");
        println!("{}", path.display());
    }
    // The lesson file's schema (an input: no version or scene fields).
    let path = dir.join("lesson.schema.json");
    std::fs::write(&path, rattleback::scenario::lesson::file::schema())
        .expect("docs/schemas is writable");
    println!("{}", path.display());
}
