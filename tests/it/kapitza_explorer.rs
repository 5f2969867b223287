//! Issue 11 in the explorer: Kapitza's pendulum through the worker's interpreter and the
//! `TestBackend`, on every shipped pendulum preset, at ×1 and at top speed; the pendulum drawn
//! on its shaken pivot (issue 59); a recorded session replayed and verified.

use crate::common;

use common::Headless;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use rattleback::app::journal::Event;
use rattleback::app::panes::Pane;
use rattleback::app::{App, Key, Outcome, PlanState};
use rattleback::physics::kapitza::run::run;
use rattleback::physics::method::RunSpec;
use rattleback::physics::{Method, Model, ModelKind};
use rattleback::record::{self, Line, Recorder};
use rattleback::scenario::shipped::{SHIPPED, resolve};
use rattleback::ui::{self, Cache, UiOptions};

fn pendulum_presets() -> Vec<&'static str> {
    let names: Vec<&str> = SHIPPED
        .iter()
        .map(|(n, _)| *n)
        .filter(|n| resolve(n, &[]).unwrap().model.kind() == ModelKind::Kapitza)
        .collect();
    assert!(names.len() >= 5, "{names:?}");
    names
}

fn render(app: &App, width: u16, height: u16) -> Buffer {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| ui::draw(f, app, &UiOptions::default(), &mut Cache::default()))
        .unwrap();
    terminal.backend().buffer().clone()
}

fn text(buffer: &Buffer) -> String {
    let area = buffer.area;
    let mut out = String::new();
    for y in 0..area.height {
        for x in 0..area.width {
            out.push_str(buffer[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

/// What the explorer shows at `t_end` at ×1024 is `simulate`'s run bit for bit (the same plan),
/// with the same swings and falls, and within 100× the tolerance of DOP853 at 1e-12.
#[test]
fn every_pendulum_preset_ends_where_simulate_and_a_tight_reference_end() {
    for name in pendulum_presets() {
        let mut h = Headless::new(name);
        h.play_until(f64::INFINITY, 1024.0);
        let app = &h.app;
        let s = app.scenario.settings;
        let Model::Kapitza(problem) = s.model else {
            panic!("{name}: not the pendulum")
        };
        assert!(app.run.done(), "{name}: not done");
        let shown = *app.run.current().expect("a point at t_end");
        assert_eq!(
            shown.t.to_bits(),
            s.t_end.to_bits(),
            "{name}: the last sample is at t_end"
        );
        let PlanState::Running { plan, .. } = app.run.plan else {
            panic!("{name}: no plan")
        };
        let spec = RunSpec {
            method: plan.method,
            tolerance: plan.tolerance,
            step: plan.step,
            t_end: s.t_end,
            samples: 0,
            monitor_energy: true,
        };
        let simulated = run(&problem, &spec, &mut |_| true).unwrap();
        assert_eq!(
            [shown.slow.to_bits(), shown.rate.to_bits()],
            [simulated.theta.to_bits(), simulated.theta_dot.to_bits()],
            "{name}: the screen and simulate differ"
        );
        assert_eq!(
            app.run.reversals_shown(),
            simulated.events.swing_count,
            "{name}: swings"
        );
        assert_eq!(
            app.run.falls_shown(),
            Some(simulated.events.fall_count),
            "{name}: falls"
        );
        let reference = run(
            &problem,
            &RunSpec {
                method: Method::Dop853,
                tolerance: 1e-12,
                step: None,
                t_end: s.t_end,
                samples: 0,
                monitor_energy: true,
            },
            &mut |_| true,
        )
        .unwrap();
        let err = (shown.slow - reference.theta)
            .abs()
            .max((shown.rate - reference.theta_dot).abs());
        assert!(
            err <= 100.0 * s.tolerance,
            "{name}: {err:e} from dop853 at 1e-12 (tolerance {:e}, {})",
            s.tolerance,
            plan.method
        );
    }
}

/// The sweep pane (`K`) sweeps the pendulum's ε: the same numbers as `study sweep`, converging
/// at first order (positions: O(ε)), drawn against ε.
#[test]
fn the_sweep_pane_sweeps_epsilon() {
    use rattleback::study::sweep::{ladder, sweep};
    let mut h = Headless::new("kapitza-upright");
    h.key(Key::Char('K'));
    assert!(h.app.view.panes.shows(Pane::Sweep));
    let s = &h.app.computed.sweep;
    assert!(s.done && s.failed.is_none(), "{s:?}");
    assert_eq!(
        s.points.len(),
        ladder(rattleback::physics::ModelKind::Kapitza).len()
    );
    let settings = h.app.scenario.settings;
    let headless = sweep(
        &settings.model,
        ladder(rattleback::physics::ModelKind::Kapitza),
        settings.t_end,
        settings.tolerance,
        &|_| true,
        &|| {},
    )
    .unwrap();
    for (shown, computed) in s.points.iter().zip(&headless.rungs) {
        assert_eq!(shown.parameter.to_bits(), computed.parameter.to_bits());
        assert_eq!(shown.sup_error.to_bits(), computed.sup_error.to_bits());
    }
    let slope = s.slope().unwrap();
    assert!((slope - 1.0).abs() < 0.1, "{slope}");
    let screen = text(&render(&h.app, 160, 48));
    assert!(screen.contains("ε-sweep: slope 1.00"), "{screen}");
    assert!(
        screen.contains("sup|theta_eps − theta_lim| against ε"),
        "{screen}"
    );
}

/// The weak-* pane (`W`) on the pendulum: `θ̇_ε` pointwise keeps its O(1) ripple, while its
/// moving average over a window of many fast periods follows the limit's velocity (averaged
/// alike): the paper's weak-* convergence, in the system where students know it.
#[test]
fn the_weak_star_pane_shows_the_velocity_converging_only_on_average() {
    let mut h = Headless::new("kapitza-upright");
    h.key(Key::Char('W'));
    assert!(h.app.view.panes.shows(Pane::Weak));
    let w = &h.app.computed.weak;
    assert!(w.done && w.failed.is_none(), "{:?}", w.failed);
    assert_eq!(w.reference.len(), w.pointwise.len());
    // Pointwise: the ripple b sin(t/ε) sin θ, about ±0.6 here, never goes away.
    let spread = w
        .pointwise
        .iter()
        .zip(&w.reference)
        .map(|(q, r)| (q - r).abs())
        .fold(0.0f64, f64::max);
    assert!(spread > 0.3, "pointwise spread {spread}");
    // Averaged over w = 1 (160 fast periods) the two agree to O(ε).
    let dev = w.worst_deviation();
    println!("spread {spread}, averaged deviation {dev}");
    assert!(dev < 0.01, "averaged deviation {dev}");
    let screen = text(&render(&h.app, 160, 48));
    assert!(screen.contains("limit's theta_dot (dashed)"), "{screen}");
    // A narrower window (w = 1/64: about 2.5 fast periods) lets the ripple through less well.
    for _ in 0..6 {
        h.key(Key::Char('<'));
    }
    let narrow = h.app.computed.weak.worst_deviation();
    assert!(narrow > dev, "{narrow} vs {dev}");
}

/// The full motion is a ripple band around the limit: `θ` within `2 ε b` of the limit and `θ̇`
/// spread over the band `± b |sin θ|` on both sides (the samples visit every phase of the
/// ripple), while the limit drawn beside it is a curve.
#[test]
fn the_full_trail_is_a_ripple_band_around_the_limit() {
    let mut h = Headless::new("kapitza-upright");
    h.play_until(10.0, 64.0);
    let app = &h.app;
    let Model::Kapitza(problem) = app.scenario.settings.model else {
        panic!("not the pendulum")
    };
    let p = *problem.params();
    let full = app.run.trail_shown();
    let limit = app.run.effective_shown();
    assert!(full.len() > 500 && limit.len() > 500);
    let (mut above, mut below, mut widest) = (0, 0, 0.0f64);
    for (f, l) in full.iter().zip(limit) {
        assert_eq!(f.t.to_bits(), l.t.to_bits(), "one sample grid");
        // The limit from (θ0, θ̇0) drifts from the full motion by O(ε) over the run.
        assert!(
            (f.slow - l.slow).abs() < 4.0 * p.epsilon * p.b + 0.02,
            "t {}",
            f.t
        );
        let band = p.b * l.slow.sin().abs() + 0.05;
        let d = f.rate - l.rate;
        assert!(d.abs() <= band, "t {}: {d} outside ±{band}", f.t);
        if d > 0.0 {
            above += 1;
        } else {
            below += 1;
        }
        widest = widest.max(d.abs() / band);
    }
    assert!(above > 100 && below > 100, "{above} above, {below} below");
    assert!(widest > 0.7, "the band is filled: {widest}");
}

type Cell = (u16, u16);
type Inner = (u16, u16, u16, u16);

/// The cell of `c` inside the pane whose title starts with `title`, with the pane's inner
/// area: `(cell, (left, top, right, bottom))`, the bounds exclusive of the frame.
fn in_pane(buffer: &Buffer, title: &str, c: &str) -> (Option<Cell>, Inner) {
    let (x, y) = crate::explorer_ui::find(buffer, title).expect("the pane's title");
    let left = x - 2;
    assert_eq!(buffer[(left, y)].symbol(), "┌");
    let mut right = x;
    while buffer[(right, y)].symbol() != "┐" {
        right += 1;
    }
    let mut bottom = y;
    while buffer[(left, bottom)].symbol() != "└" {
        bottom += 1;
    }
    let inner = (left + 1, y + 1, right, bottom);
    let found = (inner.1..inner.3)
        .flat_map(|row| (inner.0..inner.2).map(move |col| (col, row)))
        .find(|&cell| buffer[cell].symbol() == c);
    (found, inner)
}

/// Issue 59, item 4: `B` draws the pendulum on its shaken pivot, on every pendulum preset at
/// ×1 and at top speed, at 80×24 and 160×48: the heading's `θ` and `Θ` are the displayed
/// sample's; the bob lies where the drawn angle puts it about the pivot (right of it when the
/// rod leans right, above it while it is above the horizontal); the exaggeration of the pivot's
/// travel is printed, or "to scale" when it needs none.
#[test]
fn the_pendulum_is_drawn_on_its_shaken_pivot() {
    let mut checked = 0;
    for name in pendulum_presets() {
        for (speed, until) in [(1.0, 2.0), (1024.0, f64::INFINITY)] {
            let mut h = Headless::new(name);
            h.key(Key::Char('B'));
            assert!(h.app.view.panes.shows(Pane::Body), "{name}");
            h.play_until(until, speed);
            let p = *h.app.run.current().expect("a sample on display");
            let Model::Kapitza(problem) = h.app.scenario.settings.model else {
                panic!("{name}: not a pendulum");
            };
            let params = problem.params();
            let stroke = params.b.abs() * params.epsilon;
            for (w, hgt) in [(80, 24), (160, 48)] {
                let buffer = render(&h.app, w, hgt);
                let screen = text(&buffer);
                let angles = format!("θ {:+.3}, Θ {:+.3}", p.slow, p.slow - p.fast);
                assert!(
                    screen.contains(&angles),
                    "{name} ×{speed} {w}x{hgt}: {angles}\n{screen}"
                );
                let (bob, inner) = in_pane(&buffer, "pendulum (B)", "●");
                let (pivot, _) = in_pane(&buffer, "pendulum (B)", "▲");
                let (bob, pivot) = (bob.expect("the bob"), pivot.expect("the pivot"));
                let label = if stroke < 0.15 {
                    format!("drawn ×{}", gain(stroke))
                } else {
                    "to scale".to_owned()
                };
                let bottom: String = (inner.0..inner.2)
                    .map(|x| buffer[(x, inner.3 - 1)].symbol().to_owned())
                    .collect();
                assert!(
                    bottom.contains(&label),
                    "{name} {w}x{hgt}: {label} in {bottom:?}"
                );
                // The drawn angle: the averaged one plus the ripple times the gain.
                let drawn = (p.slow - p.fast) + gain(stroke) * p.fast;
                let (dx, dy) = (
                    i32::from(bob.0) - i32::from(pivot.0),
                    i32::from(pivot.1) - i32::from(bob.1),
                );
                if drawn.sin().abs() > 0.3 {
                    assert_eq!(
                        dx.signum(),
                        drawn.sin().signum() as i32,
                        "{name} {w}x{hgt}: {drawn}\n{screen}"
                    );
                }
                if drawn.cos().abs() > 0.3 {
                    assert_eq!(
                        dy.signum(),
                        drawn.cos().signum() as i32,
                        "{name} {w}x{hgt}: {drawn}\n{screen}"
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 20, "{checked}");
    // Open on the rattleback, then the pendulum is loaded: the body pane stays and draws the
    // pendulum; the map stays and becomes the pendulum's chart.
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('M'));
    h.key(Key::Char('B'));
    let effects = h.app.load(&resolve("kapitza-falls", &[]).unwrap());
    h.exec(effects);
    assert!(h.app.view.panes.shows(Pane::Body) && h.app.view.panes.shows(Pane::Map));
    assert_eq!(
        h.app.computed.map.spec.map(|s| s.chart.model()),
        Some(ModelKind::Kapitza)
    );
    h.play_until(5.0, 4.0);
    h.key(Key::Char(' '));
    h.key(Key::Char('M'));
    let screen = text(&render(&h.app, 80, 24));
    assert!(screen.contains("pendulum (B)"), "{screen}");
    insta::assert_snapshot!("kapitza_body_80x24", screen);
}

/// The exaggeration the pane states: 1, 2 or 5 times a power of ten, drawing the travel as
/// about 0.15 of the rod, never below 1 (written again here from its definition).
fn gain(stroke: f64) -> f64 {
    if stroke >= 0.15 {
        return 1.0;
    }
    let want = 0.15 / stroke;
    let decade = 10f64.powi(want.log10().floor() as i32);
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&g| g <= want)
        .unwrap()
}

#[test]
fn the_pendulum_draws_at_80x24_and_160x48_at_x1_and_top_speed() {
    for name in pendulum_presets() {
        for speed in [1.0, 1024.0] {
            let mut h = Headless::new(name);
            h.play_until(2.0, speed);
            for (w, hgt) in [(80, 24), (160, 48)] {
                let screen = text(&render(&h.app, w, hgt));
                let status = screen.lines().nth(usize::from(hgt) - 2).unwrap();
                assert!(
                    status.contains(&format!("t {:.2}", h.app.run.shown)),
                    "{name}: {status}"
                );
                assert!(
                    status.contains(&format!("swings {}", h.app.run.reversals_shown())),
                    "{name}: {status}"
                );
                assert!(screen.contains("theta_dot"), "{name} {w}x{hgt}");
                assert!(screen.contains("b^2-2a"), "{name} {w}x{hgt}: the verdict");
                assert!(
                    screen.contains("stable") || screen.contains("unstable"),
                    "{name}"
                );
            }
        }
    }
    let mut h = Headless::new("kapitza-upright");
    h.play_until(5.0, 4.0);
    h.key(Key::Char(' '));
    insta::assert_snapshot!("kapitza_80x24", text(&render(&h.app, 80, 24)));
    h.key(Key::Char('t'));
    insta::assert_snapshot!("kapitza_160x48_series", text(&render(&h.app, 160, 48)));
}

#[test]
fn the_picker_lists_both_scenes() {
    let (entries, problems) = rattleback::scenario::shipped::catalogue();
    assert!(problems.is_empty());
    for kind in ModelKind::ALL {
        assert!(entries.iter().any(|e| e.model == kind), "{kind:?}");
    }
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('p'));
    h.app.on_outcome(Outcome::Catalogue(entries, Vec::new()));
    let screen = text(&render(&h.app, 100, 40));
    assert!(
        screen.contains("rattleback") && screen.contains("kapitza"),
        "{screen}"
    );
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rattleback-kap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    let _ = std::fs::remove_file(&p);
    p
}

/// A pendulum session recorded through the app's update function replays bit for bit: its
/// checkpoints (the state `(θ, θ̇)`) verify, after a change of ε that restarts the run.
#[test]
#[allow(clippy::too_many_lines)] // one recording, written, read back, verified and tampered with
fn a_recorded_pendulum_session_verifies() {
    let mut h = Headless::new("kapitza-upright");
    let app = &h.app;
    let header = crate::common::header_of(app);
    h.app.on_key(Key::Char('R'));
    h.app
        .on_outcome(Outcome::Recording(Ok("recorded.jsonl".to_owned())));
    h.key(Key::Char(' '));
    h.tick(1.7);
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    // ε one decade coarser (row 3, coarse nudge): restarts.
    for k in [Key::Char('j'), Key::Char('j'), Key::Char('L')] {
        h.key(k);
    }
    assert!(
        (h.app
            .scenario
            .settings
            .model
            .kapitza()
            .unwrap()
            .params()
            .epsilon
            - 1e-2)
            .abs()
            < 1e-15
    );
    for _ in 0..3 {
        h.tick(0.9);
    }
    h.key(Key::Char(' '));
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    let journal = h.app.take_journal();
    let checkpoints: Vec<usize> = journal
        .iter()
        .filter_map(|(_, _, e)| match e {
            Event::Checkpoint { state, .. } => Some(state.len()),
            _ => None,
        })
        .collect();
    assert_eq!(checkpoints, vec![2, 2], "(θ, θ̇) twice");
    assert!(
        journal
            .iter()
            .any(|(_, _, e)| matches!(e, Event::Set { field, .. } if field == "epsilon"))
    );
    let mut journal = journal;
    h.stop_recording();
    journal.extend(h.app.take_journal());
    let path = temp("pendulum.jsonl");
    let mut rec = Recorder::create(&path, &header, None).unwrap();
    let last = journal.last().map_or((0.0, 0), |(t, g, _)| (*t, *g));
    for (i, (t, generation, event)) in journal.into_iter().enumerate() {
        rec.write(&Line {
            wall: i as f64 * 0.5,
            t,
            generation,
            chain: None,
            event,
        })
        .unwrap();
    }
    let end = Line {
        wall: 60.0,
        t: last.0,
        generation: last.1,
        chain: None,
        event: Event::end(),
    };
    rec.write(&end).unwrap();
    drop(rec);
    let back = record::read(&path).unwrap();
    assert!(back.header.preset.contains("model = \"kapitza\""));
    // The two taken while recording, and the two of the last frames (the pause's and the
    // stop's); the last frame is checked.
    let report = record::verify(&back, "pendulum", None).unwrap();
    assert_eq!(report.checkpoints, 4);
    assert!(report.final_screen);
    // Tampering with the state is caught.
    let text = std::fs::read_to_string(&path).unwrap();
    let tampered = temp("tampered.jsonl");
    let line = text
        .lines()
        .position(|l| l.contains("\"checkpoint\""))
        .unwrap();
    let changed: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == line {
                l.replacen("\"reversals\":", "\"reversals\":1", 1)
            } else {
                l.to_owned()
            }
        })
        .collect();
    std::fs::write(&tampered, changed.join("\n") + "\n").unwrap();
    let back = record::read(&tampered);
    assert!(
        back.map_or(true, |b| record::verify(&b, "tampered", None).is_err()),
        "a changed checkpoint is reported"
    );
}
