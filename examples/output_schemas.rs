//! Writes the JSON Schemas of the outputs other than `simulate`'s, generated from the types
//! (schemars), into `docs/schemas/NAME.schema.json`: `cargo run --example output_schemas`
//! (`tests/it/schemas.rs` checks the checked-in copies are this output and that real outputs
//! validate).

fn main() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/schemas");
    for (name, text) in rattleback::outputs::schemas() {
        let path = dir.join(format!("{name}.schema.json"));
        std::fs::write(&path, text).expect("docs/schemas is writable");
        println!("{}", path.display());
    }
}
