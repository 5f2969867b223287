// Typed values are parsed exactly, so exact float comparison is the point here.
#![allow(clippy::float_cmp)]
//! The explorer's computed panes (sweep, weak-*, map, the partner) and their jobs: what they
//! show against the studies that compute the same, their progress, their price and their
//! refusals; split from `explorer_app.rs` (issue 69: no source file over 1,000 lines).
use crate::common;

use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::explorer_app::{app, spec, wait_for};
use common::Headless;
use rattleback::app::{App, Effect, Key, Mode, PlanState};
use rattleback::physics::Method;
use rattleback::physics::rattleback::effective::Effective;
use rattleback::scenario::shipped::resolve;
use rattleback::sim::{Command, SessionSpec, SimEvent, Worker};

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
    use rattleback::study::chart::Verdict;
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
                // The first 30 cells computed already (an 8×4 grid's refinement computes every
                // cell: its blocks have one interior cell, their sample).
                known: (0..32)
                    .map(|n| (n < 30).then(|| Verdict::counted(0)))
                    .collect(),
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
    let cells: Vec<usize> = events
        .iter()
        .filter_map(|e| match e {
            SimEvent::Job {
                stamp: 7,
                data: JobData::MapCells { cells },
            } => Some(cells.iter().map(|c| c.0)),
            _ => None,
        })
        .flatten()
        .collect();
    assert_eq!(cells, [30, 31], "resumes with the cells not computed");
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
        known: Vec::new(),
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
        rattleback::app::ShellError::Io {
            path: "/dev/null".into(),
            source: std::io::Error::from_raw_os_error(17),
        },
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
        known: Vec::new(),
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

/// The map pane says how long is left while its cells come in (issue 70): the cost model's
/// price of the cells the refinement still expects to compute, smaller as cells arrive; the
/// count of cells known; a complete map says its cells alone.
#[test]
fn the_map_pane_says_the_time_left_while_its_cells_come_in() {
    use rattleback::study::chart::Verdict;
    let mut h = Headless::new("celt-clockwise");
    h.key(Key::Char('M'));
    let m = &mut h.app.computed.map;
    // Back to a map whose cells are still coming: the first 100 computed.
    let total = m.cells.len();
    let id = m.id;
    m.cells = vec![None; total];
    m.done = false;
    let left_at_start = m.seconds_left().unwrap();
    assert!(left_at_start > 0.0);
    assert!(m.on_cells(id, (0..100).map(|n| (n, Verdict::counted(0))).collect()));
    let left = m.seconds_left().unwrap();
    assert!(
        left < left_at_start,
        "{left} after 100 cells, {left_at_start} before"
    );
    let screen = crate::explorer_ui::screen_text(&h.app, 80, 24);
    let heading = screen
        .lines()
        .find(|l| l.contains("reversals (T"))
        .unwrap_or_else(|| panic!("{screen}"));
    assert!(
        heading.contains(&format!("100/{total} cells ~")) && heading.contains(" s…"),
        "{heading}"
    );
    let m = &mut h.app.computed.map;
    assert!(m.on_done(id, None));
    let screen = crate::explorer_ui::screen_text(&h.app, 80, 24);
    assert!(screen.contains(&format!("{total} cells │")), "{screen}");
}
