//! Frame time of the explorer at 160×48: the whole screen drawn into a `TestBackend` after
//! 20 simulated seconds of the default preset, steady state (level sets cached) and after a
//! view change (level sets recomputed). Run: `cargo bench --bench frame`.

use criterion::{Criterion, criterion_group, criterion_main};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use rattleback::app::{App, Key, Options};
use rattleback::scenario::shipped::resolve;
use rattleback::sim::{Command, Session};
use rattleback::ui::{self, UiOptions};

fn app_at(t: f64) -> App {
    let preset = resolve("subcritical", &[]).expect("shipped preset");
    let (mut app, commands) = App::new(&preset, Options { fps: 30.0 });
    let spec = commands
        .iter()
        .find_map(|c| match c {
            Command::Restart { spec, .. } => Some(*spec),
            _ => None,
        })
        .expect("restart");
    let mut session = Session::new(app.generation, spec);
    let (events, _) = session.advance(t, 1.0 / 240.0, usize::MAX);
    for e in events {
        app.on_sim(e);
    }
    app
}

fn frame(c: &mut Criterion) {
    let options = UiOptions::default();
    let mut group = c.benchmark_group("frame 160x48");
    group.sample_size(30);
    let mut app = app_at(20.0);
    app.on_key(Key::Char('t'));
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    eprintln!("trail points: {}", app.trail.len());
    group.bench_function("steady", |b| {
        b.iter(|| {
            terminal
                .draw(|f| ui::draw(f, &mut app, &options))
                .unwrap()
                .area
                .width
        });
    });
    let mut zoom_in = true;
    group.bench_function("view changed", |b| {
        b.iter(|| {
            app.on_key(Key::Char(if zoom_in { 'z' } else { 'Z' }));
            zoom_in = !zoom_in;
            terminal
                .draw(|f| ui::draw(f, &mut app, &options))
                .unwrap()
                .area
                .width
        });
    });
    group.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
