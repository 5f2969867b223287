//! Frame time of the explorer at 160×48: the whole screen drawn into a `TestBackend` after
//! 20 simulated seconds of the default preset, steady state (level sets cached) and after a
//! view change (level sets recomputed). Run: `cargo bench --bench frame`.

use criterion::{Criterion, criterion_group, criterion_main};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use rattleback::app::effects::commands;
use rattleback::app::{App, Effect, Key, Options};
use rattleback::scenario::shipped::resolve;
use rattleback::sim::{Engine, PlanBook, drive};
use rattleback::ui::{self, Cache, UiOptions};

/// The default preset played to `t` through the worker's own interpreter, then paused.
fn app_at(t: f64) -> App {
    let preset = resolve("subcritical", &[]).expect("shipped preset");
    let (mut app, start) = App::new(&preset, Options::at(30.0));
    let mut engine = Engine::new(PlanBook::default());
    let mut exec = |app: &mut App, effects: Vec<Effect>| {
        drive(&mut engine, commands(effects), &mut |e| {
            app.on_sim(e);
        });
    };
    exec(&mut app, start);
    let play = app.on_key(Key::Char(' '));
    exec(&mut app, play);
    while app.run.shown < t {
        let tick = app.tick(1.0 / 30.0);
        exec(&mut app, tick);
    }
    let pause = app.on_key(Key::Char(' '));
    exec(&mut app, pause);
    app
}

fn frame(c: &mut Criterion) {
    let options = UiOptions::default();
    let mut group = c.benchmark_group("frame 160x48");
    group.sample_size(30);
    let mut app = app_at(20.0);
    app.on_key(Key::Char('t'));
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    eprintln!("trail points: {}", app.run.trail.len());
    let mut cache = Cache::default();
    group.bench_function("steady", |b| {
        b.iter(|| {
            terminal
                .draw(|f| ui::draw(f, &app, &options, &mut cache))
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
                .draw(|f| ui::draw(f, &app, &options, &mut cache))
                .unwrap()
                .area
                .width
        });
    });
    group.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
