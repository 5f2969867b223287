//! The browser explorer's screen computed natively (issue 82): the same `Explorer` the module
//! wraps, on a preset, `+` pressed ten times (×1024), played until the status bar says `done`,
//! at 80×24; printed as text. `.ci/run` compares it, line for line, with what the module shows
//! under Node (`scripts/web_screen.mjs`) and in Chromium (`scripts/check_web.mjs`).
//!
//!     cargo run --release -p rattleback-web --example screen -- PRESET

fn main() {
    let preset = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "subcritical".to_owned());
    let mut e = match rattleback_web::Explorer::new(&preset, 80, 24) {
        Ok(e) => e,
        Err(why) => {
            eprintln!("screen: {why}");
            std::process::exit(2);
        }
    };
    for _ in 0..10 {
        e.key(rattleback::app::Key::Char('+'));
    }
    e.key(rattleback::app::Key::Char(' '));
    let mut frames = 0;
    while !e.app().run.done() && e.app().run.failed.is_none() && frames < 1_000_000 {
        // As the page passes it: milliseconds, divided by the module.
        e.tick((1000.0 / 30.0) / 1000.0);
        frames += 1;
    }
    e.draw();
    print!("{}", e.text());
}
