//! Enters explorer mode, then panics: the terminal must come back in cooked mode on the main
//! screen with the panic message readable. Run it in a terminal:
//! `cargo run --example panic_restore; stty -a | head -2`.

fn main() {
    let _tty = rattleback::terminal::Tty::enter(false, rattleback::terminal::Depth::Indexed)
        .expect("an interactive terminal");
    std::thread::sleep(std::time::Duration::from_millis(300));
    panic!("deliberate panic to check that the terminal is restored");
}
