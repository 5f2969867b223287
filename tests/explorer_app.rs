// Typed values are parsed exactly, so exact float comparison is the point here.
#![allow(clippy::float_cmp)]
//! The explorer's decisions, driven through keys and the update function, without rendering;
//! and the worker driven by commands with timeouts.

use std::sync::mpsc;
use std::time::{Duration, Instant};

use rattleback::app::{App, Key, Options};
use rattleback::physics::Method;
use rattleback::scenario::shipped::resolve;
use rattleback::sim::{self, Command, Session, SimEvent, Worker};

fn app() -> (App, Vec<Command>) {
    let preset = resolve("subcritical", &[]).expect("shipped preset");
    App::new(&preset, Options { fps: 30.0 })
}

fn restarts(commands: &[Command]) -> usize {
    commands
        .iter()
        .filter(|c| matches!(c, Command::Restart { .. }))
        .count()
}

#[test]
fn opening_starts_a_paused_run() {
    let (app, commands) = app();
    assert!(!app.playing);
    assert_eq!(restarts(&commands), 1);
    assert_eq!(app.settings.method, Method::Auto);
}

#[test]
fn typing_a_value_restarts_and_a_bad_one_is_refused_in_place() {
    let (mut app, _) = app();
    app.on_key(Key::Down); // iy
    app.on_key(Key::Enter);
    for c in "1.5".chars() {
        app.on_key(Key::Char(c));
    }
    let commands = app.on_key(Key::Enter);
    assert_eq!(app.settings.params.iy, 1.5);
    assert_eq!(restarts(&commands), 1);
    let generation = app.generation;

    app.on_key(Key::Enter);
    for c in "-2".chars() {
        app.on_key(Key::Char(c));
    }
    let commands = app.on_key(Key::Enter);
    assert!(commands.is_empty(), "a refused value must not restart");
    assert_eq!(app.settings.params.iy, 1.5, "old value kept");
    assert_eq!(app.generation, generation);
    let (message, is_error) = app.message.clone().expect("reason shown");
    assert!(is_error && message.contains("> 0"), "{message}");
    // Esc while typing cancels without quitting.
    app.on_key(Key::Enter);
    app.on_key(Key::Esc);
    assert!(app.editing.is_none() && !app.quit);
}

#[test]
fn nudging_k_uses_a_log_scale_and_restarts() {
    let (mut app, _) = app();
    for _ in 0..3 {
        app.on_key(Key::Char('j'));
    }
    assert_eq!(app.field().label(), "k");
    let commands = app.on_key(Key::Char('L'));
    assert_eq!(app.settings.params.k, 1e5);
    assert_eq!(restarts(&commands), 1);
    app.on_key(Key::Char('h'));
    assert!((app.settings.params.k - 1e5 / 10f64.powf(0.1)).abs() < 1e-6);
}

#[test]
fn playing_advances_the_clock_by_speed_times_wall_time() {
    let (mut app, _) = app();
    assert!(app.tick(0.5).is_empty(), "paused: no work asked");
    app.on_key(Key::Char(' '));
    app.on_key(Key::Char('+'));
    let commands = app.tick(0.5);
    match commands.as_slice() {
        [Command::AdvanceTo { t, .. }] => assert!((t - 1.0).abs() < 1e-12, "{t}"),
        other => panic!("{other:?}"),
    }
    app.on_key(Key::Char(' '));
    app.on_key(Key::Char('.'));
    assert!(!app.playing);
    assert!(app.target > 1.0);
}

#[test]
fn toggles_zoom_wrap_help_and_quit() {
    let (mut app, _) = app();
    assert_eq!(
        app.on_key(Key::Char('e')),
        vec![Command::SetEffective(false)]
    );
    app.on_key(Key::Char('t'));
    assert!(app.show_series);
    let before = app.bounds();
    app.on_key(Key::Char('z'));
    let after = app.bounds();
    assert!(after.x[1] - after.x[0] < before.x[1] - before.x[0]);
    app.on_key(Key::ShiftRight);
    assert!(app.bounds().x[0] > after.x[0]);
    app.on_key(Key::Char('w'));
    assert!(app.view.wrap);
    app.on_key(Key::Char('?'));
    assert!(app.show_help);
    app.on_key(Key::Esc);
    assert!(!app.show_help && !app.quit, "Esc closes the help first");
    app.on_key(Key::Char('q'));
    assert!(app.quit);
}

#[test]
fn stale_events_are_ignored() {
    let (mut app, _) = app();
    let old = app.generation;
    app.on_key(Key::Char('r'));
    let stale = SimEvent::Reversal {
        generation: old,
        t: 1.0,
        effective: false,
    };
    assert!(!app.on_sim(stale));
    assert!(app.reversals.is_empty());
}

/// Frame pacing must not change the trajectory: one big advance and many small ones give
/// the same bits at the same sample times (replays rely on it).
#[test]
fn pacing_does_not_change_the_trajectory() {
    let preset = resolve("subcritical", &[]).unwrap();
    let spec = sim::spec(preset.problem, Method::Dop853, 1e-9, 30.0, true);
    let collect = |chunks: &[f64]| {
        let mut s = Session::new(1, spec);
        let mut points = Vec::new();
        let mut reversals = Vec::new();
        for &t in chunks {
            let (events, _) = s.advance(t, 0.25, usize::MAX);
            for e in events {
                match e {
                    SimEvent::Samples { full, .. } => points.extend(full),
                    SimEvent::Reversal {
                        t,
                        effective: false,
                        ..
                    } => reversals.push(t.to_bits()),
                    _ => {}
                }
            }
        }
        let bits: Vec<[u64; 3]> = points
            .iter()
            .map(|p| [p.t.to_bits(), p.alpha.to_bits(), p.alpha_dot.to_bits()])
            .collect();
        (bits, reversals)
    };
    let once = collect(&[10.0]);
    let many: Vec<f64> = (1..=37).map(|i| f64::from(i) * 10.0 / 37.0).collect();
    let paced = collect(&many);
    assert_eq!(once.0.len(), 41);
    assert_eq!(once, paced);
}

fn wait_for(
    rx: &mpsc::Receiver<SimEvent>,
    limit: Duration,
    mut done: impl FnMut(&SimEvent) -> bool,
) -> Vec<SimEvent> {
    let start = Instant::now();
    let mut seen = Vec::new();
    while start.elapsed() < limit {
        if let Ok(e) = rx.recv_timeout(Duration::from_millis(50)) {
            let stop = done(&e);
            seen.push(e);
            if stop {
                return seen;
            }
        }
    }
    panic!("timed out after {limit:?}; saw {} events", seen.len());
}

#[test]
fn worker_runs_on_command_and_a_restart_cancels_in_flight_work() {
    let (tx, rx) = mpsc::sync_channel(8);
    let worker = Worker::spawn(move |e| tx.send(e).is_ok());
    let preset = resolve("subcritical", &[]).unwrap();
    let spec = sim::spec(preset.problem, Method::Dop853, 1e-9, 30.0, false);
    worker.send(Command::Restart {
        generation: 1,
        spec,
    });
    worker.send(Command::AdvanceTo {
        generation: 1,
        t: 5.0,
        sample_dt: 0.1,
    });
    let events = wait_for(
        &rx,
        Duration::from_secs(10),
        |e| matches!(e, SimEvent::Samples { t, .. } if *t >= 5.0 - 1e-9),
    );
    assert!(matches!(
        events[0],
        SimEvent::Started {
            generation: 1,
            method: Method::Dop853
        }
    ));
    assert!(
        events
            .iter()
            .any(|e| matches!(e, SimEvent::Reversal { .. })),
        "reversal near t = 2.2 expected"
    );

    // A very stiff run with a resolving method would take minutes; a restart must cut it.
    let slow = sim::spec(
        preset.problem.with_k(1e12).unwrap(),
        Method::Dop853,
        1e-12,
        30.0,
        false,
    );
    worker.send(Command::Restart {
        generation: 2,
        spec: slow,
    });
    worker.send(Command::AdvanceTo {
        generation: 2,
        t: 30.0,
        sample_dt: 0.1,
    });
    // Proof that it is busy: samples of generation 2 keep coming, and none reaches the end.
    wait_for(
        &rx,
        Duration::from_secs(5),
        |e| matches!(e, SimEvent::Samples { generation: 2, steps, .. } if *steps > 10_000),
    );
    worker.send(Command::Restart {
        generation: 3,
        spec,
    });
    let cut = Instant::now();
    wait_for(&rx, Duration::from_secs(5), |e| {
        matches!(e, SimEvent::Started { generation: 3, .. })
    });
    assert!(
        cut.elapsed() < Duration::from_secs(2),
        "restart took {:?}",
        cut.elapsed()
    );
    worker.join();
}
