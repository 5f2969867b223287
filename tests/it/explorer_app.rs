// Typed values are parsed exactly, so exact float comparison is the point here.
#![allow(clippy::float_cmp)]
//! The explorer's decisions, driven through keys, the worker's interpreter and the clock's
//! ticks, without rendering; and the worker thread driven by commands with timeouts.

use crate::common;

use std::sync::mpsc;
use std::time::{Duration, Instant};

use common::Headless;
use rattleback::app::mode::{Confirm, PromptFor};
use rattleback::app::{App, Effect, Key, Mode, Options, PlanState};
use rattleback::physics::Method;
use rattleback::physics::method::RunSpec;
use rattleback::physics::plan::AutoRules;
use rattleback::physics::rattleback::effective::Effective;
use rattleback::physics::rattleback::plan::resolve as resolve_plan;
use rattleback::physics::rattleback::run;
use rattleback::scenario::shipped::{SHIPPED, resolve};
use rattleback::sim::{Command, SessionSpec, SimEvent, Worker};

fn app() -> (App, Vec<Effect>) {
    let preset = resolve("subcritical", &[]).expect("shipped preset");
    App::new(&preset, Options::at(30.0))
}

fn restarts(effects: &[Effect]) -> usize {
    effects
        .iter()
        .filter(|c| matches!(c, Effect::Sim(Command::Restart { .. })))
        .count()
}

#[test]
fn opening_starts_a_paused_run_at_the_shared_default_tolerance() {
    let (app, effects) = app();
    assert!(!app.run.playing);
    assert_eq!(restarts(&effects), 1);
    assert_eq!(app.scenario.settings.method, Method::Auto);
    // A preset without a tolerance gets the one `simulate` uses.
    let mut preset = resolve("subcritical", &[]).unwrap();
    preset.run.tolerance = None;
    let (app, _) = App::new(&preset, Options::at(30.0));
    assert_eq!(
        app.scenario.settings.tolerance,
        rattleback::simulate::DEFAULT_TOLERANCE
    );
}

#[test]
fn typing_a_value_restarts_and_a_bad_one_is_refused_in_place() {
    let (mut app, _) = app();
    app.on_key(Key::Down); // iy
    app.on_key(Key::Enter);
    for c in "1.5".chars() {
        app.on_key(Key::Char(c));
    }
    let effects = app.on_key(Key::Enter);
    assert_eq!(app.scenario.settings.rattleback().unwrap().params().iy, 1.5);
    assert_eq!(restarts(&effects), 1);
    let generation = app.run.generation;

    app.on_key(Key::Enter);
    for c in "-2".chars() {
        app.on_key(Key::Char(c));
    }
    let effects = app.on_key(Key::Enter);
    assert!(effects.is_empty(), "a refused value must not restart");
    assert_eq!(
        app.scenario.settings.rattleback().unwrap().params().iy,
        1.5,
        "old value kept"
    );
    assert_eq!(app.run.generation, generation);
    let m = app.status.clone().expect("reason shown");
    assert!(m.error && m.text.contains("> 0"), "{}", m.text);
    // Esc while typing cancels without quitting.
    app.on_key(Key::Enter);
    app.on_key(Key::Esc);
    assert!(app.mode == Mode::Normal && !app.quit);
}

#[test]
fn nudging_k_uses_a_log_scale_and_restarts() {
    let (mut app, _) = app();
    for _ in 0..3 {
        app.on_key(Key::Char('j'));
    }
    assert_eq!(app.field().label(), "k");
    let effects = app.on_key(Key::Char('L'));
    assert_eq!(app.scenario.settings.rattleback().unwrap().params().k, 1e5);
    assert_eq!(restarts(&effects), 1);
    app.on_key(Key::Char('h'));
    assert!(
        (app.scenario.settings.rattleback().unwrap().params().k - 1e5 / 10f64.powf(0.1)).abs()
            < 1e-6
    );
}

#[test]
fn modifiers_are_not_dropped() {
    let (mut app, _) = app();
    let k = app.scenario.settings.rattleback().unwrap().params().ix;
    // Ctrl-L redraws; it does not raise the selected parameter (l) nor restart.
    assert_eq!(app.on_key(Key::Ctrl('l')), vec![Effect::Redraw]);
    assert_eq!(app.scenario.settings.rattleback().unwrap().params().ix, k);
    // Ctrl-P and Alt-q are not p and q.
    assert!(app.on_key(Key::Ctrl('p')).is_empty());
    assert_eq!(app.mode, Mode::Normal);
    app.on_key(Key::Alt('q'));
    assert!(!app.quit);
    assert_eq!(app.on_key(Key::Ctrl('z')), vec![Effect::Suspend]);
    app.on_key(Key::Ctrl('c'));
    assert!(app.quit);
}

#[test]
fn toggles_zoom_wrap_reset_help_and_quit() {
    let (mut app, _) = app();
    match app.on_key(Key::Char('e')).as_slice() {
        [Effect::Sim(Command::SetEffective { on: false, .. })] => {}
        other => panic!("{other:?}"),
    }
    app.on_key(Key::Char('t'));
    assert!(app.series());
    let before = app.bounds();
    app.on_key(Key::Char('z'));
    let after = app.bounds();
    assert!(after.x[1] - after.x[0] < before.x[1] - before.x[0]);
    app.on_key(Key::ShiftRight);
    assert!(app.bounds().x[0] > after.x[0]);
    app.on_key(Key::Char('0'));
    assert_eq!(app.bounds(), before, "0 resets zoom and pan");
    app.on_key(Key::Char('w'));
    assert!(app.view.view.wrap);
    app.on_key(Key::Char('?'));
    assert!(matches!(app.mode, Mode::Help(_)));
    app.on_key(Key::Char('?'));
    assert!(
        matches!(
            app.mode,
            Mode::Help(rattleback::app::mode::Help {
                page: rattleback::app::mode::HelpPage::Legend,
                ..
            })
        ),
        "? again shows the legend"
    );
    app.on_key(Key::Esc);
    assert!(
        app.mode == Mode::Normal && !app.quit,
        "Esc closes the help first"
    );
    // A key that closes the help does nothing else (issue 54: Down closed it and moved the
    // selection); the arrows scroll it.
    let selected = app.scenario.selected;
    app.on_key(Key::Char('?'));
    app.on_key(Key::Down);
    assert!(matches!(app.mode, Mode::Help(_)), "the arrows scroll");
    app.on_key(Key::Char('h'));
    assert_eq!(app.mode, Mode::Normal, "another key closes it");
    assert_eq!(app.scenario.selected, selected, "and does nothing else");
    app.on_key(Key::Char('?'));
    app.on_key(Key::Char('q'));
    assert!(app.quit, "q still quits from the help");
    app.quit = false;
    app.on_key(Key::Char('T'));
    let m = app.status.clone().expect("T names the theme");
    assert!(m.text.contains("theme"), "{}", m.text);
    app.on_key(Key::Char('q'));
    assert!(app.quit);
}

#[test]
fn stale_events_are_ignored() {
    let (mut app, _) = app();
    let old = app.run.generation;
    app.on_key(Key::Char('r'));
    let stale = SimEvent::Counted {
        generation: old,
        epoch: 0,
        t: 0.0,
        effective: false,
    };
    assert!(!app.on_sim(stale));
    assert!(app.run.reversals.is_empty());
}

/// Item 1: what the explorer shows at `t_end`, through the worker's interpreter at ×1024, is
/// `simulate`'s trajectory (the same verified plan, bit for bit) and within 100× the stated
/// tolerance of DOP853 at 1e-12, on every shipped preset.
#[test]
fn every_shipped_preset_ends_where_simulate_and_a_tight_reference_end() {
    for (name, _) in SHIPPED {
        if resolve(name, &[]).unwrap().problem().is_none() {
            continue; // the pendulum's presets: every_kapitza_preset_ends_where_…
        }
        let mut h = Headless::new(name);
        h.play_until(f64::INFINITY, 1024.0);
        let app = &h.app;
        let s = app.scenario.settings;
        assert!(app.run.done(), "{name}: not done");
        let shown = *app.run.current().expect("a point at t_end");
        assert_eq!(shown.t, s.t_end, "{name}: the last sample is at t_end");
        let PlanState::Running { plan, estimate } = app.run.plan else {
            panic!("{name}: no plan")
        };
        if s.method == Method::Auto {
            let e = estimate.expect("auto is verified");
            assert!(e <= s.tolerance, "{name}: estimate {e:e}");
        }
        // simulate: the same resolution of the same request.
        let resolution = resolve_plan(
            resolve(name, &[]).unwrap().problem().unwrap(),
            s.method,
            s.tolerance,
            s.t_end,
            AutoRules::Verified,
            f64::INFINITY,
            &mut |_| true,
        )
        .unwrap();
        assert_eq!(resolution.plan, plan, "{name}: the explorer's plan");
        let problem = *s.rattleback().unwrap();
        // `auto`'s verified run is its plan run again, bit for bit.
        let simulated = run(
            &problem,
            &RunSpec {
                method: plan.method,
                tolerance: plan.tolerance,
                step: plan.step,
                t_end: s.t_end,
                samples: 0,
                monitor_energy: false,
            },
        )
        .unwrap();
        assert_eq!(
            [shown.slow.to_bits(), shown.rate.to_bits()],
            [
                simulated.final_state[1].to_bits(),
                simulated.final_state[3].to_bits()
            ],
            "{name}: the screen and simulate differ"
        );
        assert_eq!(
            app.run.reversals_shown(),
            simulated.reversals.len(),
            "{name}: reversal count"
        );
        let reference = run(
            &problem,
            &RunSpec {
                method: Method::Dop853,
                tolerance: 1e-12,
                step: None,
                t_end: s.t_end,
                samples: 0,
                monitor_energy: false,
            },
        )
        .unwrap();
        let err = (shown.slow - reference.final_state[1])
            .abs()
            .max((shown.rate - reference.final_state[3]).abs());
        // The tight reference resolves the full motion only where it can (k = 1e10 is past
        // it): there the verified plan's own estimate is the check above.
        if problem.params().k <= 1e6 {
            assert!(
                err <= 100.0 * s.tolerance,
                "{name}: error {err:e} vs tolerance {:e}",
                s.tolerance
            );
        }
    }
}

/// Item 2: counters and the point never run ahead of the displayed time, at any speed.
#[test]
fn counted_events_never_run_ahead_of_the_display() {
    for speed in [4.0, 1024.0] {
        let mut h = Headless::new("stiff-spring");
        h.play_until(0.0, speed);
        for _ in 0..400 {
            h.tick(1.0 / 30.0);
            let run = &h.app.run;
            let shown = run.shown;
            assert!(run.reversal_ticks().iter().all(|t| *t <= shown));
            if let Some(p) = run.current() {
                assert!(p.t <= shown);
            }
            // Every reversal before the shown time is counted.
            let all = run.reversals.kept().iter().filter(|t| **t <= shown).count();
            assert_eq!(run.reversals_shown(), all);
            let limit = run
                .effective_reversals
                .kept()
                .iter()
                .filter(|t| **t <= shown)
                .count();
            assert_eq!(run.effective_reversals_shown(), limit);
            if run.done() {
                break;
            }
        }
    }
}

/// Item 2: hiding the limit stops its integration; showing it again catches up with its
/// samples and reversals.
#[test]
fn the_limit_hidden_then_shown_catches_up() {
    let mut h = Headless::new("subcritical");
    h.play_until(12.0, 4.0);
    let before = h.app.run.effective_reversals_shown();
    assert!(before >= 2, "the limit reverses twice before t = 12");
    h.key(Key::Char('e'));
    assert!(h.app.run.effective_trail.is_empty());
    h.play_until(20.0, 4.0);
    h.key(Key::Char('e'));
    h.tick(1.0 / 30.0);
    let run = &h.app.run;
    let expected = h
        .app
        .scenario
        .derived
        .limit
        .effective()
        .unwrap()
        .reversal_times(run.shown)
        .len();
    assert_eq!(run.effective_reversals_shown(), expected);
    assert!(run.effective_reversals_shown() > before);
    let first = run.effective_shown().first().expect("caught-up trail");
    assert_eq!(first.t, 0.0, "the trail is back from t = 0");
}

/// Item 3: the trail is sampled on a grid set by the dynamics: the same at ×1 and ×1024.
#[test]
fn the_trail_does_not_depend_on_the_speed() {
    let trail = |speed: f64| {
        let mut h = Headless::new("subcritical");
        h.play_until(f64::INFINITY, speed);
        h.app
            .run
            .trail
            .iter()
            .map(|p| [p.t.to_bits(), p.slow.to_bits(), p.rate.to_bits()])
            .collect::<Vec<_>>()
    };
    let slow = trail(1.0);
    assert_eq!(slow, trail(1024.0));
    assert!(slow.len() > 1000, "{} samples", slow.len());
}

/// Item 4: a pause stops the display and the worker at once, however far ahead the clock
/// was asked to go; a step moves one frame.
#[test]
fn pause_and_step_take_effect_at_once() {
    let mut h = Headless::new("subcritical");
    h.play_until(5.0, 64.0);
    assert!(h.app.run.playing);
    h.key(Key::Char(' '));
    let paused = h.app.run.shown;
    assert!(paused >= 5.0);
    for _ in 0..30 {
        h.tick(1.0 / 30.0);
    }
    assert_eq!(h.app.run.shown, paused, "the display moved after pause");
    h.key(Key::Char('.'));
    let stepped = h.app.run.shown;
    assert!(stepped > paused && stepped <= paused + 64.0 / 30.0 + 1e-9);
    assert!(!h.app.run.playing);
}

#[test]
fn a_slow_worker_does_not_pile_up_a_backlog() {
    let (mut app, _) = app();
    app.on_key(Key::Char(' '));
    // No samples arrive: the clock may not run further than one frame ahead of them.
    for _ in 0..100 {
        app.tick(1.0);
    }
    let asked = app.run.target();
    assert!(asked <= 1.0 + 0.25 + 1e-12, "asked for {asked}");
    app.on_key(Key::Char(' '));
    // Paused: one sample past the displayed time, no more (so the display sits on its time).
    assert_eq!(app.run.target(), app.run.shown + app.run.sample_dt);
    assert!(app.run.sample_dt > 0.0);
}

/// Item 9: the start is inside the view for any inertia order, and long rotating runs are
/// followed instead of crushed.
#[test]
fn the_view_holds_the_start_and_follows_long_runs() {
    for name in ["iy-greater", "subcritical", "supercritical"] {
        let h = Headless::new(name);
        let b = h.app.bounds();
        let a0 = h.app.scenario.settings.rattleback().unwrap().start().alpha;
        let margin = 0.05 * (b.x[1] - b.x[0]);
        assert!(
            a0 > b.x[0] + margin && a0 < b.x[1] - margin,
            "{name}: {b:?}"
        );
    }
    let mut h = Headless::new("supercritical");
    h.key(Key::Char('w')); // unwrapped: the run turns many times
    h.play_until(f64::INFINITY, 1024.0);
    let b = h.app.bounds();
    assert!(
        b.x[1] - b.x[0] <= 3.0 * std::f64::consts::PI + 1e-9,
        "crushed: {b:?}"
    );
    let last = h.app.run.current().unwrap().slow;
    assert!(last > b.x[0] && last < b.x[1]);
}

/// Item 8: prompts say what they are for; a shipped name asks explicitly; the description is
/// asked for, or marked as a copy.
#[test]
fn saving_asks_what_it_must() {
    let (mut app, _) = app();
    app.on_key(Key::Char('s'));
    let Mode::Prompt(p) = &app.mode else {
        panic!("no prompt")
    };
    assert_eq!(p.purpose.label(), "save as");
    for c in "subcritical".chars() {
        app.on_key(Key::Char(c));
    }
    assert!(
        app.on_key(Key::Enter).is_empty(),
        "a shipped name asks first"
    );
    let Mode::Prompt(p) = &app.mode else {
        panic!("prompt closed")
    };
    assert_eq!(p.confirm, Confirm::Shipped);
    assert!(app.status.as_ref().unwrap().text.contains("shipped"));
    // Saved at once (no second prompt to take the next keys), described as a copy.
    let effects = app.on_key(Key::Enter);
    let [Effect::SavePreset { name, text, .. }] = effects.as_slice() else {
        panic!("{effects:?}")
    };
    assert_eq!(name, "subcritical");
    assert!(
        text.contains("Saved from the explorer as subcritical"),
        "{text}"
    );
    // Notes need a recording and are labelled as notes.
    let (mut app, _) = self::app();
    app.on_key(Key::Char('n'));
    assert!(app.status.as_ref().unwrap().error);
    app.on_outcome(rattleback::app::Outcome::Recording(
        Ok("x.jsonl".to_owned()),
    ));
    app.on_key(Key::Char('n'));
    let Mode::Prompt(p) = &app.mode else {
        panic!("no note prompt")
    };
    assert_eq!(p.purpose, PromptFor::Note);
    assert_eq!(p.purpose.label(), "note");
    // Once entered, the hint gives way to what was done (issue 68).
    for c in "first reversal".chars() {
        app.on_key(Key::Char(c));
    }
    app.on_key(Key::Enter);
    assert_eq!(app.mode, Mode::Normal);
    let said = &app.status.as_ref().unwrap().text;
    assert!(said.starts_with("note marked at t "), "{said}");
}

#[test]
fn the_picker_scrolls_and_keeps_errors_on_their_rows() {
    let (mut app, _) = app();
    assert_eq!(app.on_key(Key::Char('p')), vec![Effect::ReadCatalogue]);
    let (entries, _) = rattleback::scenario::shipped::catalogue();
    let mut many = Vec::new();
    for i in 0..3 {
        many.extend(entries.iter().cloned().map(|mut e| {
            e.name = format!("{}-{i}", e.name);
            e
        }));
    }
    let broken = vec![(
        "bad".to_owned(),
        "bad.toml:3: body.ix: must be > 0".to_owned(),
    )];
    app.on_outcome(rattleback::app::Outcome::Catalogue(many.clone(), broken));
    for _ in 0..many.len() {
        app.on_key(Key::Down);
    }
    let Mode::Picker(p) = &app.mode else {
        panic!("no picker")
    };
    assert!(matches!(
        p.rows[p.selected],
        rattleback::app::mode::PickerRow::Broken { .. }
    ));
    let first = p.first_visible(15);
    assert!(
        p.selected >= first && p.selected < first + 15,
        "selection off screen"
    );
    app.on_key(Key::Enter);
    assert!(matches!(&app.mode, Mode::Dialog(t) if t.contains("must be > 0")));
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
    panic!(
        "timed out after {limit:?}; saw {} events: {:?}",
        seen.len(),
        seen.iter()
            .map(|e| format!("{e:?}").chars().take(200).collect::<String>())
            .collect::<Vec<_>>()
    );
}

fn spec(
    problem: rattleback::physics::rattleback::Problem,
    method: Method,
    tolerance: f64,
) -> SessionSpec {
    SessionSpec {
        model: problem.into(),
        method,
        tolerance,
        t_end: 30.0,
        effective: false,
        sample_dt: 0.1,
        step: None,
    }
}

#[test]
fn worker_runs_on_command_and_a_restart_cancels_in_flight_work() {
    let (tx, rx) = mpsc::sync_channel(8);
    let worker = Worker::spawn(move |e| tx.send(e).is_ok());
    let preset = resolve("subcritical", &[]).unwrap();
    let quick = spec(*preset.problem().unwrap(), Method::Dop853, 1e-9);
    worker.send(Command::Restart {
        generation: 1,
        spec: quick,
    });
    worker.send(Command::AdvanceTo {
        generation: 1,
        t: 5.0,
    });
    let events = wait_for(
        &rx,
        Duration::from_secs(10),
        |e| matches!(e, SimEvent::Samples { t: Some(t), .. } if *t >= 5.0 - 1e-9),
    );
    assert_eq!(events[0].method(), Some(Method::Dop853));
    assert!(
        events.iter().any(|e| matches!(e, SimEvent::Counted { .. })),
        "reversal near t = 2.2 expected"
    );

    // A very stiff run with a resolving method would take minutes; a restart must cut it.
    let slow = spec(
        preset.problem().unwrap().with_k(1e12).unwrap(),
        Method::Dop853,
        1e-12,
    );
    worker.send(Command::Restart {
        generation: 2,
        spec: slow,
    });
    worker.send(Command::AdvanceTo {
        generation: 2,
        t: 30.0,
    });
    wait_for(&rx, Duration::from_secs(5), |e| {
        matches!(e, SimEvent::Started { generation: 2, .. })
    });
    worker.send(Command::Restart {
        generation: 3,
        spec: quick,
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

    // auto's verification over a long horizon is cancelled by a restart too.
    let long = SessionSpec {
        t_end: 1e6,
        ..spec(
            preset.problem().unwrap().with_k(1e8).unwrap(),
            Method::Auto,
            1e-10,
        )
    };
    worker.send(Command::Restart {
        generation: 4,
        spec: long,
    });
    wait_for(&rx, Duration::from_secs(5), |e| {
        matches!(e, SimEvent::Planning { generation: 4 })
    });
    std::thread::sleep(Duration::from_millis(100));
    worker.send(Command::Restart {
        generation: 5,
        spec: quick,
    });
    let cut = Instant::now();
    wait_for(&rx, Duration::from_secs(5), |e| {
        matches!(e, SimEvent::Started { generation: 5, .. })
    });
    assert!(
        cut.elapsed() < Duration::from_secs(1),
        "planning was not cancelled: {:?}",
        cut.elapsed()
    );
    let joined = Instant::now();
    worker.join();
    assert!(joined.elapsed() < Duration::from_secs(1));
}

/// Item 3: on every shipped preset, consecutive samples of the ×1024 trail are at most two
/// cells apart on the 160×48 portrait (120 × 43 cells of plot): the trail is a curve.
#[test]
fn the_trail_has_no_gap_wider_than_two_cells() {
    use rattleback::app::portrait::{display_alpha, wrap_centre};
    for (name, _) in SHIPPED {
        if resolve(name, &[]).unwrap().problem().is_none() {
            continue; // the pendulum's full trail is a band by design: its own test below
        }
        let mut h = Headless::new(name);
        h.play_until(f64::INFINITY, 1024.0);
        let app = &h.app;
        let b = app.bounds();
        let (dx, dy) = ((b.x[1] - b.x[0]) / 120.0, (b.y[1] - b.y[0]) / 43.0);
        let centre = wrap_centre(&app.scenario.derived.limit);
        let wrap = app.view.view.wrap;
        let inside = |x: f64, y: f64| x >= b.x[0] && x <= b.x[1] && y >= b.y[0] && y <= b.y[1];
        let mut worst: f64 = 0.0;
        for w in app.run.trail_shown().windows(2) {
            let (x0, x1) = (
                display_alpha(w[0].slow, centre, wrap, std::f64::consts::PI),
                display_alpha(w[1].slow, centre, wrap, std::f64::consts::PI),
            );
            if !inside(x0, w[0].rate) || !inside(x1, w[1].rate) {
                continue;
            }
            if wrap && (x1 - x0).abs() > 0.5 * std::f64::consts::PI {
                continue; // across the fold
            }
            let gap = ((x1 - x0) / dx)
                .abs()
                .max(((w[1].rate - w[0].rate) / dy).abs());
            worst = worst.max(gap);
        }
        assert!(worst <= 2.0, "{name}: a gap of {worst:.2} cells");
    }
}

/// Memory stays bounded however many reversals a run makes: old times are counted, not kept.
#[test]
fn reversal_history_is_bounded_and_counts_stay_exact() {
    let mut e = rattleback::app::Events::default();
    for i in 0..100_000 {
        let t = f64::from(i) * 0.01;
        e.push(t, t);
    }
    assert!(e.kept().len() <= rattleback::app::run::EVENTS_CAP);
    assert_eq!(e.count_upto(1e9), 100_000);
    assert_eq!(e.count_upto(999.995), 100_000);
    assert_eq!(e.count_upto(999.985), 99_999);
}

#[test]
fn the_sweep_pane_shows_what_study_sweep_computes_and_follows_the_parameters() {
    use rattleback::app::panes::Pane;
    use rattleback::study::sweep::{ladder, sweep};
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('K'));
    assert!(h.app.view.panes.shows(Pane::Sweep));
    let s = &h.app.computed.sweep;
    assert!(s.done && s.failed.is_none(), "{s:?}");
    assert_eq!(
        s.points.len(),
        ladder(rattleback::physics::ModelKind::Rattleback).len()
    );
    // The same numbers as the headless study (one rung at a time here, in parallel there).
    let settings = h.app.scenario.settings;
    let headless = sweep(
        &settings.model,
        ladder(rattleback::physics::ModelKind::Rattleback),
        settings.t_end,
        settings.tolerance,
        &|_| true,
        &|| {},
    )
    .unwrap();
    for (shown, computed) in s.points.iter().zip(&headless.rungs) {
        assert_eq!(shown.parameter, computed.parameter);
        assert_eq!(shown.sup_error.to_bits(), computed.sup_error.to_bits());
    }
    let slope = s.slope().unwrap();
    assert!((slope + 1.0).abs() < 0.2, "{slope}");
    // A change of the start restarts the sweep for the new parameters.
    let before = s.points[3].sup_error;
    h.key(Key::Down);
    h.key(Key::Down);
    h.key(Key::Down);
    h.key(Key::Down); // gamma
    h.key(Key::Down); // alpha
    h.key(Key::Down); // gamma_dot
    h.key(Key::Down); // alpha_dot
    h.key(Key::Right);
    let s = &h.app.computed.sweep;
    assert_eq!(s.generation, h.app.run.generation);
    assert!(s.done && s.points.len() == ladder(rattleback::physics::ModelKind::Rattleback).len());
    assert_ne!(
        s.points[3].sup_error, before,
        "the sweep follows the parameters"
    );
    // Hidden, it stops and nothing more is computed.
    h.key(Key::Char('K'));
    assert!(!h.app.view.panes.shows(Pane::Sweep));
}

#[test]
fn the_weak_star_pane_settles_on_theta_as_the_window_widens() {
    use rattleback::app::panes::Pane;
    let preset = resolve("subcritical", &["spring.k=1e6".parse().unwrap()]).unwrap();
    let mut h = Headless::of(&preset);
    h.key(Key::Char('W'));
    assert!(h.app.view.panes.shows(Pane::Weak));
    let w = &h.app.computed.weak;
    assert!(w.done && w.failed.is_none(), "{:?}", w.failed);
    let theta = w.theta;
    let (lo, hi) = w
        .pointwise
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &q| (a.min(q), b.max(q)));
    assert!(
        lo < 0.01 * theta && hi > 1.98 * theta,
        "[{lo}, {hi}] θ {theta}"
    );
    assert!(w.worst_deviation() < 0.01, "{}", w.worst_deviation());
    // A window shorter than the fast period does not settle.
    for _ in 0..12 {
        h.key(Key::Char('<'));
    }
    assert!(h.app.computed.weak.window <= 2e-3);
    assert!(h.app.computed.weak.worst_deviation() > 0.1);
    h.key(Key::Char('W'));
    assert!(!h.app.view.panes.shows(Pane::Weak));
}

/// The start's ratio as the parameter panel shows it.
fn shown_ratio(d: &rattleback::app::Derived) -> Option<f64> {
    d.summary.iter().find_map(|l| match (l.label, l.value) {
        ("ratio", rattleback::physics::scene::Shown::Number(r)) => r,
        _ => None,
    })
}

#[test]
#[allow(clippy::too_many_lines)] // one user path, pane to load to full model, step by step
fn the_map_pane_shows_what_study_map_computes_and_loads_the_cell_under_the_cursor() {
    use rattleback::app::Mode;
    use rattleback::app::computed::map::{
        FULL_GRID, FULL_TOLERANCE, LIMIT_GRID, MapSource, PANE_INERTIA,
    };
    use rattleback::app::panes::Pane;
    use rattleback::study::map::{Grid, Source, regime_map};
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('M'));
    assert!(h.app.view.panes.shows(Pane::Map));
    assert_eq!(h.app.mode, Mode::Map, "the map takes the arrows");
    let s = h.app.scenario.settings;
    let m = &h.app.computed.map;
    assert!(m.done && m.failed.is_none(), "{m:?}");
    // The same counts as `study map` on the same grid (row by row here, all at once there).
    let (p, g0) = (
        s.rattleback().unwrap().params(),
        s.rattleback().unwrap().start().gamma_dot,
    );
    let (cols, rows) = LIMIT_GRID;
    let grid = Grid {
        ratio_max: p.ix / p.iz,
        inertia: PANE_INERTIA,
        ..Grid::new(cols, rows, p.ix, p.iz, g0, s.t_end)
    };
    let study = regime_map(&grid, Source::Limit, &|_| true).unwrap();
    let shown: Vec<usize> = m
        .cells
        .iter()
        .map(|c| c.as_ref().unwrap().count().unwrap())
        .collect();
    let expected: Vec<usize> = study.cells.iter().map(|c| c.reversals).collect();
    assert_eq!(shown, expected);
    assert!(
        shown.iter().any(|&c| c > 0) && shown.contains(&0),
        "both regimes show"
    );

    // Arrows move the cursor, not the parameters; Enter loads the cell.
    let selected = h.app.scenario.selected;
    let start = h.app.computed.map.cursor;
    for k in [Key::Right, Key::Right, Key::Up, Key::ShiftRight] {
        h.key(k);
    }
    assert_eq!(h.app.computed.map.cursor, (start.0 + 6, start.1 + 1));
    assert_eq!(h.app.scenario.selected, selected);
    assert_eq!(
        h.app.scenario.settings, s,
        "moving the cursor changes nothing"
    );
    let cell = h.app.computed.map.cursor;
    let count = h
        .app
        .computed
        .map
        .cell(cell.0, cell.1)
        .unwrap()
        .count()
        .unwrap();
    let generation = h.app.run.generation;
    h.key(Key::Enter);
    let loaded = h.app.scenario.settings;
    assert!(
        h.app.run.generation > generation,
        "loading restarts the run"
    );
    assert_eq!(
        loaded.rattleback().unwrap().params().iy,
        s.rattleback().unwrap().params().ix * grid.inertia_ratio(cell.1)
    );
    assert_eq!(
        (
            loaded.rattleback().unwrap().start().gamma,
            loaded.rattleback().unwrap().start().alpha
        ),
        (0.0, 0.0)
    );
    let ratio = shown_ratio(&h.app.scenario.derived).expect("the panel shows the ratio");
    assert!((ratio - grid.ratio(cell.0)).abs() < 1e-12, "{ratio}");
    assert_eq!(
        h.app.mode,
        Mode::Map,
        "the map keeps the arrows after a load"
    );
    assert!(h.app.computed.map.done, "the same body keeps its map");
    // The loaded start's limit reverses as often as its cell said.
    let limit = Effective::new(loaded.rattleback().unwrap());
    assert_eq!(limit.reversal_count(loaded.t_end), count);

    // `f`: the full model at this k, on its own grid; Esc gives the arrows back.
    h.key(Key::Char('f'));
    let m = &h.app.computed.map;
    assert_eq!(m.source, MapSource::Full);
    assert!(m.done && m.failed.is_none(), "{m:?}");
    assert_eq!(m.cells.len(), FULL_GRID.0 * FULL_GRID.1);
    let full = Grid {
        cols: FULL_GRID.0,
        rows: FULL_GRID.1,
        ..grid
    };
    let source = Source::Full {
        k: loaded.rattleback().unwrap().params().k,
        tolerance: loaded.tolerance.max(FULL_TOLERANCE),
    };
    let study = regime_map(&full, source, &|_| true).unwrap();
    let shown: Vec<usize> = m
        .cells
        .iter()
        .map(|c| c.as_ref().unwrap().count().unwrap())
        .collect();
    let expected: Vec<usize> = study.cells.iter().map(|c| c.reversals).collect();
    assert_eq!(shown, expected);
    h.key(Key::Esc);
    assert_eq!(h.app.mode, Mode::Normal);
    assert!(h.app.view.panes.shows(Pane::Map), "Esc keeps the map");
    h.key(Key::Right);
    assert_ne!(
        h.app.scenario.settings, loaded,
        "the arrows edit the parameters again"
    );
    h.key(Key::Char('M'));
    assert!(!h.app.view.panes.shows(Pane::Map));
}

#[test]
fn a_map_resumes_where_it_stopped_on_a_thread_of_its_own() {
    use rattleback::sim::jobs::MapSpec;
    use rattleback::sim::{Command, Engine, JobData, JobSpec, PlanBook, SimEvent};
    use rattleback::study::map::{Grid, Source};
    let grid = Grid::new(8, 4, 2.0, 1.0, 1.0, 30.0);
    let spec = MapSpec::rattleback(
        grid,
        Source::Full {
            k: 1e4,
            tolerance: 1e-6,
        },
    );
    let mut engine = Engine::new(PlanBook::default());
    let events = std::cell::RefCell::new(Vec::new());
    let mut sink = |e: SimEvent| {
        events.borrow_mut().push(e);
        true
    };
    engine.handle(
        &Command::start_job(
            7,
            JobSpec::Map {
                spec: Box::new(spec),
                from: 30,
            },
        ),
        &mut sink,
    );
    // The job works on its own thread: the engine has nothing to do for it but take what it
    // sends.
    assert!(engine.jobs_running());
    assert!(!engine.busy(), "a pane's job is not the run's work");
    assert!(engine.settle_jobs(|| true, &mut sink));
    assert!(!engine.jobs_running());
    let events = events.into_inner();
    let cells: Vec<(usize, usize)> = events
        .iter()
        .filter_map(|e| match e {
            SimEvent::Job {
                stamp: 7,
                data: JobData::MapCells { first, verdicts },
            } => Some((*first, verdicts.len())),
            _ => None,
        })
        .collect();
    assert_eq!(cells.first().map(|c| c.0), Some(30), "resumes at `from`");
    assert_eq!(cells.iter().map(|c| c.1).sum::<usize>(), 2);
    assert!(matches!(
        events.last(),
        Some(SimEvent::Job {
            stamp: 7,
            data: JobData::MapDone { failed: None }
        })
    ));
}

/// Hiding the map takes back its hint: the status line no longer says the arrows move a cursor
/// that is gone (it stayed until the next message).
#[test]
fn hiding_the_map_takes_back_its_hint() {
    use rattleback::app::Mode;
    use rattleback::app::panes::Pane;
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('M'));
    assert!(h.app.status.as_ref().unwrap().text.contains("arrows move"));
    h.key(Key::Char('M'));
    assert!(!h.app.view.panes.shows(Pane::Map));
    assert_eq!(h.app.mode, Mode::Normal);
    let said = &h.app.status.as_ref().unwrap().text;
    assert!(!said.contains("arrows move"), "{said}");
}

/// Issue 27: `auto`'s planning reports its progress while it plans (not when it is done): a
/// long verification sends `PlanProgress` events, counting its integrations and the percent of
/// the horizon each has reached, before anything starts; the status bar shows them.
#[test]
fn a_long_verification_reports_its_progress_as_it_goes() {
    // Unbounded: the test reads only some of the worker's events.
    let (tx, rx) = mpsc::channel();
    // In one piece, as a replay of a file older than format 9 verifies it (the explorer now
    // draws after the first segment: `segments::the_explorer_draws_after_the_first_segment`).
    let book = rattleback::sim::PlanBook {
        segmented: false,
        ..rattleback::sim::PlanBook::default()
    };
    let worker = Worker::spawn_with(book, move |e| tx.send(e).is_ok());
    let preset = resolve("subcritical", &[]).unwrap();
    // The case: the default preset to t = 1000 (about 9 s of verification).
    let long = SessionSpec {
        t_end: 1000.0,
        ..spec(*preset.problem().unwrap(), Method::Auto, 1e-9)
    };
    let quick = spec(*preset.problem().unwrap(), Method::Dop853, 1e-9);
    worker.send(Command::Restart {
        generation: 1,
        spec: long,
    });
    let mut progress = Vec::new();
    wait_for(&rx, Duration::from_secs(30), |e| {
        if let SimEvent::PlanProgress {
            generation: 1,
            run,
            percent,
        } = e
        {
            progress.push((*run, *percent));
        }
        progress.len() >= 3
    });
    assert!(
        progress[0].0 >= 1,
        "integrations count from 1: {progress:?}"
    );
    assert!(
        progress.windows(2).all(|w| w[1] > w[0]),
        "each report is further on: {progress:?}"
    );
    // Planning is still going on, so a restart cancels it and it never starts. Had the reports
    // been held until planning was done, it would have started, right behind them.
    worker.send(Command::Restart {
        generation: 2,
        spec: quick,
    });
    let rest = wait_for(&rx, Duration::from_secs(30), |e| {
        matches!(e, SimEvent::Started { generation: 2, .. })
    });
    assert!(
        !rest
            .iter()
            .any(|e| matches!(e, SimEvent::Started { generation: 1, .. })),
        "the progress came with the start, not before it"
    );
    worker.send(Command::Quit);
    worker.join();
}

#[test]
fn the_status_bar_shows_autos_progress() {
    let mut h = Headless::new("subcritical");
    h.app.run.plan = PlanState::Verifying {
        run: 3,
        percent: 42,
    };
    let screen = crate::explorer_ui::screen_text(&h.app, 120, 30);
    assert!(screen.contains("verifying auto… run 3 at 42%"), "{screen}");
    h.app.run.plan = PlanState::Verifying { run: 0, percent: 0 };
    let screen = crate::explorer_ui::screen_text(&h.app, 120, 30);
    assert!(screen.contains("verifying auto…"), "{screen}");
    assert!(!screen.contains(" run 0"), "{screen}");
}

/// Issue 56 (R4, R1): a pane's job is cancelled at once when it is dropped (its pane closed, its
/// inputs changed): a map of the full model whose cells each verify for seconds ends within a
/// cell's planning step, not after the row.
#[test]
fn a_dropped_job_stops_computing_at_once() {
    use rattleback::sim::jobs::{MapSpec, Running};
    use rattleback::sim::{JobSpec, PlanBook, Planner};
    use rattleback::study::map::{Grid, Source};
    let spec = MapSpec::rattleback(
        Grid::new(8, 4, 2.0, 1.0, 1.0, 3000.0),
        Source::Full {
            k: 1e8,
            tolerance: 1e-10,
        },
    );
    let map = JobSpec::Map {
        spec: Box::new(spec),
        from: 0,
    };
    // A job its cost model lets start (else it would end at once, refused).
    assert!(map.predicted_seconds() < rattleback::physics::budget::BUDGET_SECONDS);
    let job = map.job(1);
    let running = Running::spawn(job, Planner::new(PlanBook::default()), || true);
    std::thread::sleep(std::time::Duration::from_millis(50));
    assert!(
        running.cancel_within(std::time::Duration::from_millis(500)),
        "the job's thread went on computing after it was cancelled"
    );
}

/// Issue 56 (R4): a heavy comparison partner (the celt spun at ω = 1e5, a minute of `auto`)
/// held the run at "verifying auto… 88%" for 60 s, then at 0 steps/s: the partner worked before
/// the run, in the worker's own thread. On its own thread now, the run reaches its target while
/// the partner still computes.
#[test]
fn a_heavy_partner_never_starves_the_run() {
    use rattleback::sim::{Command, Engine, JobSpec, PlanBook, SessionSpec, SimEvent};
    let run = rattleback::scenario::shipped::resolve("subcritical", &[]).unwrap();
    let heavy = rattleback::scenario::shipped::resolve(
        "celt-clockwise",
        &["initial.omega_z=-1e5".parse().unwrap()],
    )
    .unwrap();
    let spec = |p: &rattleback::scenario::Preset| -> SessionSpec {
        App::new(p, rattleback::app::Options::at(30.0))
            .0
            .scenario
            .spec(false)
    };
    let mut engine = Engine::new(PlanBook::default());
    let mut started = false;
    let mut sink = |e: SimEvent| {
        started |= matches!(e, SimEvent::Started { .. });
        true
    };
    engine.handle(
        &Command::start_job(1, JobSpec::Partner(spec(&heavy))),
        &mut sink,
    );
    engine.handle(
        &Command::Restart {
            generation: 1,
            spec: spec(&run),
        },
        &mut sink,
    );
    engine.handle(
        &Command::AdvanceTo {
            generation: 1,
            t: 5.0,
        },
        &mut sink,
    );
    let start = std::time::Instant::now();
    while engine.busy() {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(20),
            "the run did not reach t = 5 beside the partner"
        );
        engine.work(256, &mut |_| true, &mut sink);
    }
    assert!(started, "the run started");
    assert!(
        engine.jobs_running(),
        "the partner is still computing: the run went on beside it"
    );
}

/// Issue 56 (R17): `R` with an unusable sessions folder says why and where the folder comes
/// from; no recording starts.
#[test]
fn a_recording_that_cannot_start_says_why() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('R'));
    let effects = h.app.on_outcome(rattleback::app::Outcome::Recording(Err(
        "/dev/null: File exists (os error 17)".to_owned(),
    )));
    h.exec(effects);
    let Mode::Dialog(text) = &h.app.mode else {
        panic!("no dialog: {:?}", h.app.mode);
    };
    assert!(text.contains("cannot record: /dev/null"), "{text}");
    assert!(text.contains("`sessions`"), "{text}");
    assert_eq!(h.app.journal.state, rattleback::app::RecState::Off);
}

/// Issue 56, the door: every pane's job has a cost model asked before it starts (the partner,
/// the weak-* view, the sweep, the map of the limit and of the full model). On the shipped
/// presets each is priced finite and within the budget; at hostile inputs each is refused with
/// its reason in its pane's event, at once, without computing.
#[test]
fn every_panes_job_is_priced_before_it_starts_and_refused_over_the_budget() {
    use rattleback::physics::budget::BUDGET_SECONDS;
    use rattleback::sim::JobSpec;
    use rattleback::sim::jobs::{JobKind, MapSpec, SweepSpec, WeakSpec};
    use rattleback::study::map::{Grid, Source};
    let model = |name: &str, set: &[&str]| {
        let o: Vec<_> = set.iter().map(|s| s.parse().unwrap()).collect();
        rattleback::scenario::shipped::resolve(name, &o)
            .unwrap()
            .model
    };
    let map = |t_end: f64, source| JobSpec::Map {
        spec: Box::new(MapSpec::rattleback(
            Grid::new(40, 20, 2.0, 1.0, 1.0, t_end),
            source,
        )),
        from: 0,
    };
    let full = Source::Full {
        k: 1e4,
        tolerance: 1e-9,
    };
    let partner = |m: rattleback::physics::Model, t_end: f64| {
        JobSpec::Partner(rattleback::sim::SessionSpec {
            model: m,
            method: Method::Auto,
            tolerance: 1e-8,
            t_end,
            effective: false,
            sample_dt: 0.01,
            step: None,
        })
    };
    // (kind, within the budget, over it)
    let cases = [
        (
            JobKind::Weak,
            JobSpec::Weak(WeakSpec {
                model: model("subcritical", &[]),
                t_end: 30.0,
            }),
            // Bounded by construction (a few thousand fast periods whatever the input): no
            // weak-* view is over the budget, checked at the extremes below.
            None,
        ),
        (
            JobKind::Sweep,
            JobSpec::Sweep(SweepSpec {
                model: model("subcritical", &[]),
                t_end: 30.0,
                tolerance: 1e-8,
            }),
            Some(JobSpec::Sweep(SweepSpec {
                model: model("subcritical", &[]),
                t_end: 1e12,
                tolerance: 1e-12,
            })),
        ),
        (JobKind::Map, map(30.0, Source::Limit), Some(map(1e9, full))),
        (
            JobKind::Partner,
            partner(model("celt-clockwise", &[]), 10.0),
            Some(partner(model("celt-clockwise", &[]), 1e9)),
        ),
    ];
    for (name, set) in [
        ("kapitza-upright", &["pendulum.epsilon=1e-9"][..]),
        ("subcritical", &["spring.k=1e12"]),
        ("stiff-spring", &[]),
    ] {
        let weak = JobSpec::Weak(WeakSpec {
            model: model(name, set),
            t_end: 1e15,
        });
        let p = weak.predicted_seconds();
        assert!(p.is_finite() && p < BUDGET_SECONDS, "{name} {set:?}: {p}");
    }
    for (kind, fine, heavy) in cases {
        assert_eq!(fine.kind(), kind);
        let p = fine.predicted_seconds();
        assert!(
            p.is_finite() && p > 0.0 && p < BUDGET_SECONDS,
            "{kind:?}: {p}"
        );
        let Some(heavy) = heavy else { continue };
        let p = heavy.predicted_seconds();
        assert!(
            p > BUDGET_SECONDS,
            "{kind:?}: the hostile case is priced {p}"
        );
        let started = Instant::now();
        let reason = refusal(heavy);
        assert!(reason.contains("(budget 60 s)"), "{kind:?}: {reason}");
        assert!(
            started.elapsed() < Duration::from_secs(5),
            "{kind:?}: refused only after {:?}",
            started.elapsed()
        );
    }
}

/// Why a job refused itself: its failure event, run on a thread as the engine runs it.
fn refusal(job: rattleback::sim::JobSpec) -> String {
    use rattleback::sim::jobs::{JobData, Running};
    use rattleback::sim::{PlanBook, Planner, SimEvent};
    let kind = job.kind();
    let running = Running::spawn(job.job(3), Planner::new(PlanBook::default()), || true);
    let mut reason = None;
    running.finish(
        || true,
        &mut |e| {
            if let SimEvent::Job { stamp: 3, data } = e {
                reason = match data {
                    JobData::Partner(Err(r)) => Some(r),
                    JobData::Weak { failed, .. }
                    | JobData::SweepDone { failed }
                    | JobData::MapDone { failed } => failed,
                    _ => reason.take(),
                };
            }
            true
        },
        &mut |_| {},
    );
    reason.unwrap_or_else(|| panic!("{kind:?}: no reason"))
}

/// Issue 68: `y` says where the command went: tmux's buffer when tmux took it, else the file
/// it was saved to beside the sessions (OSC 52 is never acknowledged), whole on the messages.
#[test]
fn y_says_where_the_command_went() {
    let (mut app, _) = app();
    let effects = app.on_key(Key::Char('y'));
    let Some(Effect::Copy(text)) = effects.iter().find(|e| matches!(e, Effect::Copy(_))) else {
        panic!("{effects:?}")
    };
    let text = text.clone();
    assert!(
        text.starts_with("rattleback simulate --preset subcritical"),
        "{text}"
    );
    app.on_outcome(rattleback::app::Outcome::Copied {
        text: text.clone(),
        tmux: true,
        file: None,
    });
    let said = app.status.as_ref().unwrap().text.clone();
    assert!(
        said.starts_with("command in tmux's buffer") && said.ends_with(&text),
        "{said}"
    );
    let file = std::path::PathBuf::from("/tmp/sessions/last-command.sh");
    app.on_outcome(rattleback::app::Outcome::Copied {
        text: text.clone(),
        tmux: false,
        file: Some(Ok(file.clone())),
    });
    let said = app.status.as_ref().unwrap().text.clone();
    assert!(
        said.starts_with("command saved to /tmp/sessions/last-command.sh"),
        "{said}"
    );
    assert!(
        app.messages
            .written
            .iter()
            .any(|l| l == "command saved to /tmp/sessions/last-command.sh"),
        "{:?}",
        app.messages.written
    );
}
