//! Prints the JSON Schema of a session file's lines, generated from the types (schemars):
//! `cargo run --example session_schema > docs/session.schema.json` (`tests/it/session_format.rs`
//! checks the checked-in copy is this output and that the checked-in sessions validate).

fn main() {
    print!("{}", rattleback::record::session_schema());
}
