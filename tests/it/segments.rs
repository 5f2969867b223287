//! Issue 27, item 4: verification in segments. A run longer than the first segment is verified
//! over nested horizons; the explorer draws once the first is verified and verifies the others
//! ahead of the display; what it shows ends where the run in one piece (`simulate`'s) ends.

use std::sync::mpsc;
use std::time::{Duration, Instant};

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use rattleback::physics::method::Method;
use rattleback::scenario::shipped::resolve;
use rattleback::sim::segments::{FIRST_SEGMENT, horizons};
use rattleback::sim::{Command, Engine, PlanBook, SessionSpec, SimEvent, Worker, drive};
use rattleback::ui::{self, Cache, UiOptions};

fn long(t_end: f64) -> SessionSpec {
    let preset = resolve("subcritical", &[]).unwrap();
    SessionSpec {
        model: (*preset.problem().unwrap()).into(),
        method: Method::Auto,
        tolerance: 1e-8,
        t_end,
        effective: false,
        sample_dt: 0.1,
        step: None,
    }
}

fn one_piece() -> PlanBook {
    PlanBook {
        segmented: false,
        ..PlanBook::default()
    }
}

/// Starts `spec`, integrates to `t` and asks the exact state there.
fn to(spec: SessionSpec, t: f64) -> Vec<Command> {
    vec![
        Command::Restart {
            generation: 1,
            spec,
        },
        Command::AdvanceTo { generation: 1, t },
        Command::Checkpoint { generation: 1, t },
    ]
}

/// Runs `commands` on a fresh engine of `book`, returning its events.
fn events(book: PlanBook, commands: Vec<Command>) -> (Engine, Vec<SimEvent>) {
    let mut engine = Engine::new(book);
    let mut out = Vec::new();
    drive(&mut engine, commands, &mut |e| out.push(e));
    (engine, out)
}

fn checkpoints(events: &[SimEvent]) -> Vec<(f64, Vec<f64>, usize)> {
    events
        .iter()
        .filter_map(|e| match e {
            SimEvent::Checkpoint {
                t,
                state,
                reversals,
                ..
            } => Some((*t, state.clone(), *reversals)),
            _ => None,
        })
        .collect()
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn a_long_run_is_shown_in_segments_and_ends_where_the_run_in_one_piece_ends() {
    let t_end = 200.0;
    assert_eq!(horizons(t_end), vec![50.0, 100.0, 200.0]);
    let spec = long(t_end);
    let run = |book| events(book, to(spec, t_end)).1;
    let segmented = run(PlanBook::default());
    let whole = run(one_piece());

    // The first plan covers the first segment only; the others come verified, in order.
    let started: Vec<f64> = segmented
        .iter()
        .filter_map(|e| match e {
            SimEvent::Started { until, .. } => Some(*until),
            _ => None,
        })
        .collect();
    assert_eq!(started, vec![50.0]);
    let verified: Vec<(f64, f64)> = segmented
        .iter()
        .filter_map(|e| match e {
            SimEvent::Verified { from, until, .. } => Some((*from, *until)),
            _ => None,
        })
        .collect();
    assert_eq!(verified, vec![(50.0, 100.0), (100.0, 200.0)]);
    assert!(
        whole
            .iter()
            .all(|e| !matches!(e, SimEvent::Verified { .. })),
        "in one piece, nothing is verified ahead"
    );

    // The samples run on one grid, each time once, to the end.
    let times: Vec<f64> = segmented
        .iter()
        .filter_map(|e| match e {
            SimEvent::Samples { full, .. } => Some(full.iter().map(|p| p.t).collect::<Vec<_>>()),
            _ => None,
        })
        .flatten()
        .collect();
    assert!(
        times.windows(2).all(|w| w[1] > w[0]),
        "each time once, in order"
    );
    assert_eq!(times.last().map(|t| t.to_bits()), Some(t_end.to_bits()));
    assert_eq!(times.len(), (t_end / 0.1).round() as usize + 1);

    // The last segment is the run in one piece: the same plan, the same end, bit for bit.
    let last_plan = segmented.iter().rev().find_map(|e| match e {
        SimEvent::Verified { plan, .. } => Some(*plan),
        _ => None,
    });
    let whole_plan = whole.iter().find_map(|e| match e {
        SimEvent::Started { plan, .. } => Some(*plan),
        _ => None,
    });
    assert_eq!(last_plan, whole_plan);
    let (a, b) = (checkpoints(&segmented), checkpoints(&whole));
    assert_eq!(a.len(), 1);
    assert_eq!(bits(&a[0].1), bits(&b[0].1), "the end state");
    assert_eq!(a[0].2, b[0].2, "the reversals");
    // And the samples shown after the last switch are the run's in one piece.
    let after = |events: &[SimEvent]| -> Vec<(u64, u64)> {
        events
            .iter()
            .filter_map(|e| match e {
                SimEvent::Samples { full, .. } => Some(full.clone()),
                _ => None,
            })
            .flatten()
            .filter(|p| p.t > 100.0)
            .map(|p| (p.slow.to_bits(), p.rate.to_bits()))
            .collect()
    };
    assert_eq!(after(&segmented), after(&whole));
}

#[test]
fn a_checkpoint_behind_a_switch_is_the_state_its_segment_showed() {
    let spec = long(200.0);
    // The first segment alone, stopped at t = 40: what the display showed there.
    let (_, first) = events(PlanBook::default(), to(spec, 40.0));
    // The worker ran past both switches before the pause at t = 40 was checkpointed (it
    // computes ahead of the display), and a pause at t = 150 after that.
    let (mut engine, _) = events(
        PlanBook::default(),
        vec![
            Command::Restart {
                generation: 1,
                spec,
            },
            Command::AdvanceTo {
                generation: 1,
                t: 200.0,
            },
        ],
    );
    let mut late = Vec::new();
    drive(
        &mut engine,
        vec![
            Command::Checkpoint {
                generation: 1,
                t: 40.0,
            },
            Command::Checkpoint {
                generation: 1,
                t: 150.0,
            },
        ],
        &mut |e| late.push(e),
    );
    let (a, b) = (checkpoints(&first), checkpoints(&late));
    assert_eq!(b.len(), 2);
    assert_eq!(bits(&a[0].1), bits(&b[0].1), "t = 40, behind two switches");
    assert_eq!(a[0].2, b[0].2);
    // t = 150 lies in the last segment: the run in one piece's state there.
    let (_, whole) = events(one_piece(), to(spec, 150.0));
    let c = checkpoints(&whole);
    assert_eq!(bits(&c[0].1), bits(&b[1].1), "t = 150");
    assert_eq!(c[0].2, b[1].2);
}

/// The explorer's worker draws the start of a long run while `auto` still verifies the rest:
/// samples come before the last segment is verified, and the verification ahead reports its
/// progress.
#[test]
fn the_explorer_draws_after_the_first_segment() {
    let (tx, rx) = mpsc::channel();
    let worker = Worker::spawn(move |e| tx.send(e).is_ok());
    // The case: the default preset to t = 1000 at a tight tolerance (about 9 s in one
    // piece before this issue).
    let mut spec = long(1000.0);
    spec.tolerance = 1e-9;
    worker.send(Command::Restart {
        generation: 1,
        spec,
    });
    worker.send(Command::AdvanceTo {
        generation: 1,
        t: 20.0,
    });
    let start = Instant::now();
    let mut seen = Vec::new();
    let mut drawn_at = None;
    loop {
        let e = rx
            .recv_timeout(Duration::from_secs(120))
            .expect("the worker answers");
        if let SimEvent::Samples { full, .. } = &e
            && !full.is_empty()
            && drawn_at.is_none()
        {
            drawn_at = Some(seen.len());
        }
        let last = matches!(e, SimEvent::Verified { until, .. } if until.to_bits() == 1000.0_f64.to_bits());
        seen.push(e);
        if last || start.elapsed() > Duration::from_secs(120) {
            break;
        }
    }
    let drawn_at = drawn_at.expect("samples came");
    let verified_at = seen.len() - 1;
    assert!(
        drawn_at < verified_at,
        "the display had samples before the whole run was verified"
    );
    assert!(
        seen[drawn_at..]
            .iter()
            .any(|e| matches!(e, SimEvent::Ahead { until, .. } if *until > FIRST_SEGMENT)),
        "the verification ahead reports its progress"
    );
    worker.send(Command::Quit);
    worker.join();
}

fn status_row(app: &mut rattleback::app::App, width: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, 24)).unwrap();
    terminal
        .draw(|f| ui::draw(f, app, &UiOptions::default(), &mut Cache::default()))
        .unwrap();
    let b = terminal.backend().buffer();
    (0..width).map(|x| b[(x, 22)].symbol().to_owned()).collect()
}

/// What the status bar says while the run is verified ahead: how far, that the display waits
/// at the frontier, and a missed tolerance as soon as a segment ahead is known to miss it.
#[test]
fn the_status_bar_says_how_far_the_run_is_verified() {
    let mut preset = resolve("subcritical", &[]).unwrap();
    preset.run.t_end = 200.0;
    let (mut app, _) = rattleback::app::App::new(&preset, rattleback::app::Options::at(30.0));
    let generation = app.run.generation;
    let plan = rattleback::physics::Resolved {
        method: Method::Dop853,
        tolerance: 1e-10,
        step: None,
    };
    app.on_sim(SimEvent::Started {
        generation,
        plan,
        error_estimate: Some(2e-10),
        until: 50.0,
    });
    let row = status_row(&mut app, 120);
    assert!(row.contains("verified to 50"), "{row}");
    // The display reaches the frontier while playing: it waits for the verification ahead.
    app.on_sim(SimEvent::Samples {
        generation,
        epoch: 0,
        full: vec![rattleback::sim::Point {
            t: 50.0,
            slow: 0.0,
            rate: 0.0,
            energy_error: 0.0,
            fast: 0.0,
            lean: None,
        }],
        effective: Vec::new(),
        t: Some(50.0),
        steps: 10,
    });
    app.on_sim(SimEvent::Ahead {
        generation,
        until: 100.0,
        run: 3,
        percent: 42,
    });
    app.run.playing = true;
    let _ = app.tick(100.0);
    assert_eq!(app.run.shown.to_bits(), 50.0_f64.to_bits());
    let row = status_row(&mut app, 120);
    assert!(row.contains("verifying ahead… run 3 at 42%"), "{row}");
    // A segment ahead misses the tolerance: said before it is shown, at 80 columns too.
    app.on_sim(SimEvent::Verified {
        generation,
        from: 50.0,
        until: 100.0,
        plan,
        error_estimate: Some(3e-7),
    });
    app.run.playing = false;
    let row = status_row(&mut app, 80);
    assert!(row.contains("✗ tol missed after t 50"), "{row}");
    assert!(
        row.contains("est 2e-10 ✓") || !row.contains("est"),
        "the shown segment's estimate: {row}"
    );
}

/// `rattleback bench --only segments` measures the wait before the first frame of long runs
/// (the numbers are in docs/benchmarks.md; here the table's shape and the horizons).
#[test]
fn the_bench_measures_the_first_segment_against_the_whole() {
    let dir = std::env::temp_dir().join(format!("rattleback-bench-seg-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let (code, out, err) = crate::common::bin(&[
        "bench",
        "--quick",
        "--only",
        "segments",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("whole/1st"), "{out}");
    let csv = std::fs::read_to_string(dir.join("segments.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 2, "{csv}");
    let cells: Vec<&str> = rows[1].split(',').collect();
    assert_eq!(&cells[..2], ["subcritical", "1000"]);
    assert_eq!(cells[3], "5", "five horizons");
    assert_eq!(cells[4], "62.5", "the first");
    for c in &cells[5..8] {
        let seconds: f64 = c.parse().unwrap();
        assert!(seconds > 0.0 && seconds.is_finite(), "{c}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// What the explorer shows at the end of a run verified in segments (played through the worker
/// at top speed, as a user would) is what `simulate` reports for the same horizon, bit for bit:
/// the rattleback and the pendulum.
#[test]
fn the_screen_ends_where_simulate_ends() {
    for (name, slow) in [
        ("subcritical", ["alpha", "alpha_dot"]),
        ("kapitza-falls", ["theta", "theta_dot"]),
    ] {
        let mut preset = resolve(name, &[]).unwrap();
        preset.run.t_end = 200.0;
        let mut h = crate::common::Headless::of(&preset);
        h.play_until(f64::INFINITY, 1024.0);
        assert!(h.app.run.done(), "{name}: not done");
        assert!(
            h.app.run.segments.len() > 1,
            "{name}: shown in segments ({:?})",
            h.app.run.segments
        );
        let shown = *h.app.run.current().expect("a point at the end");
        let json = crate::common::simulate_json(&["--preset", name, "--set", "run.t_end=200"]);
        let end = &json["final"];
        assert_eq!(
            [shown.slow.to_bits(), shown.rate.to_bits()],
            [
                end[slow[0]].as_f64().unwrap().to_bits(),
                end[slow[1]].as_f64().unwrap().to_bits()
            ],
            "{name}: the screen and simulate differ"
        );
        if let Some(n) = json["reversals"]["count"].as_u64() {
            assert_eq!(h.app.run.reversals_shown() as u64, n, "{name}: reversals");
        }
    }
}

/// A replay (`drive`) waits for the verification ahead only where the run needs it: a session
/// that showed the first seconds of a long, heavy run replays them without verifying the rest
/// (minutes here), which goes on, cancellable, behind it.
#[test]
fn a_replay_never_waits_for_segments_it_does_not_show() {
    let spec = long(1e5);
    let (engine, out) = events(PlanBook::default(), to(spec, 10.0));
    assert_eq!(checkpoints(&out).len(), 1, "t = 10 was reached");
    assert!(
        engine.waiting(),
        "the later segments are still being verified, and nothing waited for them"
    );
    // Dropping the engine cancels them.
    drop(engine);
}

/// A later horizon over the budget: the run is shown up to the last horizon within it, the
/// stop is said at once (`Stops`, before any sample), and the run fails there, with the budget's
/// words; nothing past it is integrated.
#[test]
fn a_run_stops_where_its_verification_would_pass_the_budget() {
    let spec = long(200.0);
    let predicted = |t: f64| {
        let mut s = spec;
        s.t_end = t;
        match (PlanBook {
            budget: 0.0,
            ..PlanBook::default()
        })
        .check_auto(&s)
        {
            Err(rattleback::physics::StepError::OverBudget { over, .. }) => over.predicted,
            other => panic!("{other:?}"),
        }
    };
    let (p100, p200) = (predicted(100.0), predicted(200.0));
    assert!(p100 < p200);
    let book = PlanBook {
        budget: 0.5 * (p100 + p200),
        ..PlanBook::default()
    };
    let (_, out) = events(book, to(spec, 200.0));
    let stops = out
        .iter()
        .position(
            |e| matches!(e, SimEvent::Stops { at, .. } if at.to_bits() == 100.0_f64.to_bits()),
        )
        .expect("the stop said");
    let first_sample = out
        .iter()
        .position(|e| matches!(e, SimEvent::Samples { full, .. } if !full.is_empty()))
        .expect("samples");
    assert!(stops < first_sample, "said before anything is shown");
    let last = out
        .iter()
        .filter_map(|e| match e {
            SimEvent::Samples { full, .. } => full.last().map(|p| p.t),
            _ => None,
        })
        .fold(0.0, f64::max);
    assert!((99.9..=100.0).contains(&last), "shown to the stop: {last}");
    let failed = out.iter().find_map(|e| match e {
        SimEvent::Failed { message, .. } => Some(message.clone()),
        _ => None,
    });
    let failed = failed.expect("the run fails at the stop");
    assert!(
        failed.contains("beyond t = 100") && failed.contains("auto needs about"),
        "{failed}"
    );
    assert!(checkpoints(&out).is_empty(), "nothing at t = 200");

    // On screen, played at top speed: everything before the stop is shown, then the run fails
    // there (the worker gets there first, a lead ahead of the display).
    let mut preset = resolve("subcritical", &[]).unwrap();
    preset.run.t_end = 200.0;
    preset.run.tolerance = Some(spec.tolerance);
    let (app, effects) = rattleback::app::App::new(&preset, rattleback::app::Options::at(30.0));
    let mut h = crate::common::Headless {
        app,
        engine: Engine::new(PlanBook {
            budget: 0.5 * (p100 + p200),
            ..PlanBook::default()
        }),
        effects: Vec::new(),
    };
    h.exec(effects);
    assert_eq!(h.app.run.stops, Some(100.0));
    h.play_until(f64::INFINITY, 1024.0);
    let failed = h.app.run.failed.clone().expect("failed at the stop");
    assert!(failed.contains("beyond t = 100"), "{failed}");
    let run = &h.app.run;
    assert!(
        run.shown.to_bits() == run.reached.to_bits()
            && run.shown <= 100.0
            && 100.0 - run.shown < run.sample_dt,
        "shown to the last sample before the stop: {} of {} (grid {})",
        run.shown,
        run.reached,
        run.sample_dt
    );
}

/// The lecturer's plans of every horizon of `spec` after the first, as its worker resolves
/// them.
fn lecturers_plans(
    spec: SessionSpec,
) -> Vec<(
    f64,
    rattleback::sim::PlanKey,
    rattleback::physics::Resolved,
    Option<f64>,
)> {
    let book = PlanBook::default();
    horizons(spec.t_end)
        .into_iter()
        .skip(1)
        .map(|t_end| {
            let mut asked = spec;
            asked.t_end = t_end;
            let r = spec
                .model
                .resolve(&book.request(&asked), &mut |_| true)
                .unwrap();
            (
                t_end,
                rattleback::sim::PlanKey::of(&asked),
                r.plan,
                r.estimate,
            )
        })
        .collect()
}

/// The plans a verification ahead reported, by horizon, and how many progress reports it sent.
fn reports(
    ahead: &rattleback::sim::segments::Ahead,
) -> (Vec<(f64, rattleback::physics::Resolved)>, usize) {
    use rattleback::sim::segments::Report;
    let (mut verified, mut progress) = (Vec::new(), 0);
    while let Some(report) = ahead.next() {
        match report {
            Report::Verified { until, plan, .. } => verified.push((until, plan)),
            Report::Progress { .. } => progress += 1,
            _ => {}
        }
    }
    (verified, progress)
}

fn awaiting() -> PlanBook {
    PlanBook {
        awaits: true,
        ..PlanBook::default()
    }
}

#[test]
fn a_followers_verification_ahead_waits_for_the_lecturers_plans() {
    // A follower's worker waits for the lecturer's plans of the later segments instead of
    // verifying them at the same moment as the lecturer: it verifies nothing, and takes what
    // it is given. Plans no `auto` would pick (dop853 at 1e-9) show they were taken.
    use rattleback::physics::Resolved;
    use rattleback::sim::segments::{Ahead, Forward};
    let spec = long(200.0);
    let ahead = Ahead::spawn(awaiting(), spec, &[50.0, 100.0, 200.0]);
    let given = Resolved {
        method: Method::Dop853,
        tolerance: 1e-9,
        step: None,
    };
    for (_, key, _, _) in lecturers_plans(spec) {
        ahead.forward(Forward::Plan(key, given, Some(1e-9)));
    }
    let (verified, progress) = reports(&ahead);
    assert_eq!(verified, vec![(100.0, given), (200.0, given)]);
    assert_eq!(progress, 0, "the follower verified");
}

#[test]
fn a_released_follower_verifies_what_it_lacks() {
    // The lecture ended (or the follower forked): what the book lacks is verified here, and
    // comes out as the lecturer's worker resolved it.
    use rattleback::sim::segments::{Ahead, Forward};
    let spec = long(200.0);
    let ahead = Ahead::spawn(awaiting(), spec, &[50.0, 100.0, 200.0]);
    ahead.forward(Forward::Release);
    let (verified, progress) = reports(&ahead);
    let lecturer: Vec<_> = lecturers_plans(spec)
        .into_iter()
        .map(|(t, _, plan, _)| (t, plan))
        .collect();
    assert_eq!(verified, lecturer);
    assert!(progress > 0);
}

#[test]
fn a_follower_shows_the_lecturers_bits_from_the_plans_it_is_given() {
    // Through the engine: the lecturer's plan lines handed over as `Book` commands after the
    // restart they belong to; the run ends on the lecturer's bits without verifying ahead.
    let t_end = 200.0;
    let spec = long(t_end);
    let (_, lecturer) = events(PlanBook::default(), to(spec, t_end));
    let mut commands = to(spec, t_end);
    let books = lecturers_plans(spec)
        .into_iter()
        .map(|(_, key, plan, estimate)| Command::Book {
            key,
            plan,
            estimate,
        });
    commands.splice(1..1, books);
    let (_, follower) = events(awaiting(), commands);
    assert!(
        !follower.iter().any(|e| matches!(e, SimEvent::Ahead { .. })),
        "the follower verified ahead"
    );
    assert!(lecturer.iter().any(|e| matches!(e, SimEvent::Ahead { .. })));
    let (a, b) = (checkpoints(&lecturer), checkpoints(&follower));
    assert_eq!(a.len(), 1);
    assert_eq!(bits(&a[0].1), bits(&b[0].1));
    assert_eq!(a[0].2, b[0].2);
}
