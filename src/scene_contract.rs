//! The scene contract (issue 69): a small scene registered only in this library's own test
//! build (`physics::models::oscillator`, a harmonic oscillator with an exact solution) goes
//! through every output a scene has — its preset, the explorer's screen and its chart pane,
//! `simulate` in JSON, CSV and table, `study map`'s chart with its table and CSV, shards and
//! their merge, a recording and its replay — so what a new scene costs outside its folder is
//! measured here, not estimated in a review. Its numbers are checked against the exact
//! solution, not against the code that computed them.

use crate::app::Key;
use crate::physics::ModelKind;
use crate::physics::models::oscillator::{Params, Problem, Start};
use crate::scenario::Preset;
use crate::study::chart::{Chart, StudyAsk};

const PRESET: &str = r#"
[preset]
name = "Oscillator: the contract's"
model = "oscillator"

[oscillator]
omega = 2.0

[initial]
x = 1.0
v = 0.5

[run]
t_end = 10.0
tolerance = 1e-8
"#;

fn preset() -> Preset {
    Preset::parse(PRESET, "oscillator.toml", "oscillator", &[]).expect("the contract's preset")
}

fn problem() -> Problem {
    Problem::new(Params { omega: 2.0 }, Start { x: 1.0, v: 0.5 }).unwrap()
}

/// The explorer, headless, its worker run in place (the lesson review's walk).
type Headless = crate::explorer::review::Walk;

fn screen(app: &Headless, width: u16, height: u16) -> String {
    app.screen_at((width, height)).join("\n")
}

/// `journal` written as a session file at `path`, a line every half second, then its end line;
/// read back.
fn write_session(
    path: &std::path::Path,
    header: &crate::record::Header,
    journal: Vec<(f64, u64, crate::app::journal::Event)>,
) -> crate::record::Recording {
    use crate::record::{Line, Recorder};
    let _ = std::fs::remove_file(path);
    let mut rec = Recorder::create(path, header, None).unwrap();
    let n = journal.len();
    // The end line as the explorer's recorder writes it: at the last line's time and run stamp.
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
    rec.write(&Line {
        wall: n as f64 * 0.5 + 1.0,
        t: last.0,
        generation: last.1,
        chain: None,
        event: crate::app::journal::Event::end(),
    })
    .unwrap();
    drop(rec);
    crate::record::read(path).unwrap()
}

#[test]
fn the_contract_scene_is_registered_and_its_preset_reads() {
    let kind = ModelKind::from_name("oscillator").unwrap();
    assert!(ModelKind::ALL.contains(&kind));
    let p = preset();
    assert_eq!(p.model.kind(), kind);
    assert_eq!(p.model.value("omega"), Some(2.0));
    // A typo and a value out of range are refused by the scene's own table.
    let typo = Preset::parse(
        &PRESET.replace("omega = 2.0", "omgea = 2.0"),
        "typo.toml",
        "t",
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(typo.contains("omgea"), "{typo}");
    let bad = Preset::parse(
        &PRESET.replace("omega = 2.0", "omega = -1"),
        "bad.toml",
        "b",
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(bad.contains("omega"), "{bad}");
    // Written back, it reads as itself.
    let again = Preset::parse(&p.to_toml(), "again.toml", "a", &[]).unwrap();
    assert_eq!(again.model, p.model);
}

#[test]
fn simulate_reports_the_contract_scene_in_every_format() {
    use crate::simulate::{Format, Request, resolve, simulate};
    let p = preset();
    let exact = problem().exact(10.0);
    let crossings = problem().exact_crossings(10.0);
    for method in [crate::physics::Method::Auto, crate::physics::Method::Dop853] {
        let request = Request {
            method: Some(method),
            tolerance: None,
            step: None,
            t_end: None,
            format: Format::Json,
            samples: 101,
            force: false,
        };
        let resolved = resolve(&p, &request);
        let json: serde_json::Value =
            serde_json::from_str(&simulate(&p, &resolved, Format::Json).unwrap()).unwrap();
        assert_eq!(json["model"], "oscillator");
        let (x, v) = (
            json["final"][0].as_f64().unwrap(),
            json["final"][1].as_f64().unwrap(),
        );
        assert!(
            (x - exact.0).abs() < 1e-6 && (v - exact.1).abs() < 1e-6,
            "{method}: ({x}, {v}) against {exact:?}"
        );
        assert_eq!(json["events"]["count"], crossings, "{method}");
        let csv = simulate(
            &p,
            &resolve(
                &p,
                &Request {
                    format: Format::Csv,
                    ..request
                },
            ),
            Format::Csv,
        )
        .unwrap();
        assert!(csv.contains("\nt,x,v\n"), "{csv}");
        let rows = csv.lines().filter(|l| !l.starts_with('#')).count();
        assert_eq!(rows, 1 + 101, "{method}");
        let table = simulate(&p, &resolved, Format::Table).unwrap();
        assert!(table.contains("oscillator to t = 10"), "{table}");
    }
}

#[test]
fn the_contract_scenes_chart_counts_as_the_exact_solution_and_merges_from_shards() {
    let p = preset();
    let ask = StudyAsk {
        grid: (6, 4),
        t_end: 10.0,
        tolerance: 1e-8,
        ..StudyAsk::default()
    };
    let chart = Chart::for_study(&p.model, &ask).unwrap();
    assert_eq!(chart.model(), p.model.kind());
    let c = chart
        .compute(false, None, &|_| true, &crate::study::chart::Tally::QUIET)
        .unwrap();
    let whole = chart.output(1, &p.name, &c.indices, &c.verdicts, None, false);
    let (x, y) = chart.axes();
    for cell in &whole.cells {
        let (i, j) = (cell.index % x.cells, cell.index / x.cells);
        let exact = Problem::new(Params { omega: x.at(i) }, Start { x: 1.0, v: y.at(j) })
            .unwrap()
            .exact_crossings(10.0);
        assert_eq!(cell.reversals, Some(exact), "cell {}", cell.index);
    }
    // A flag of another scene's chart is refused by name.
    let e = Chart::for_study(
        &p.model,
        &StudyAsk {
            k: Some(1e4),
            ..ask
        },
    )
    .unwrap_err();
    // Typed (issue 83): the flag and the scene are the error's, and so is the message.
    assert!(
        matches!(
            &e,
            crate::physics::chart::ChartError::Flag(f)
                if f.flag == crate::physics::chart::MapFlag::K
        ),
        "{e:?}"
    );
    let said = e.to_string();
    assert!(
        said.contains("--k") && said.contains("harmonic oscillator"),
        "{said}"
    );
    // Table and CSV in the scene's words and columns.
    assert!(whole.table().starts_with("crossings over oscillator.omega"));
    let csv = whole.csv();
    assert!(
        csv.starts_with("index,oscillator.omega,initial.v,reversals,mark\n"),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 1 + chart.len());
    // Three shards merge into the whole, byte for byte (but the wall time).
    let description = crate::study::ask::Description::new(PRESET.to_owned(), &ask);
    let parts: Vec<_> = (1..=3)
        .map(|i| {
            let s = crate::study::chart::Shard { index: i, count: 3 };
            let c = chart
                .compute(
                    false,
                    Some(s),
                    &|_| true,
                    &crate::study::chart::Tally::QUIET,
                )
                .unwrap();
            let mut out = chart.output(1, &p.name, &c.indices, &c.verdicts, Some(s), false);
            out.description = Some(description.clone());
            (format!("part{i}"), crate::study::part::sealed(out))
        })
        .collect();
    let mut merged = crate::study::part::merge(&chart, 1, &parts).unwrap();
    merged.wall_seconds = whole.wall_seconds;
    assert_eq!(
        serde_json::to_string(&merged).unwrap(),
        serde_json::to_string(&whole).unwrap()
    );
    // A cell loaded back is the problem at its coordinates.
    let loaded = chart.load(&p.model, (x.at(2), y.at(1))).unwrap();
    assert_eq!(loaded.value("omega"), Some(x.at(2)));
    assert_eq!(loaded.value("v"), Some(y.at(1)));
}

#[test]
fn the_explorer_shows_records_and_replays_the_contract_scene() {
    let mut h = Headless::of(&preset());
    let header = crate::record::active::header(&h.app, (80, 24), 30.0);
    h.app.on_key(Key::Char('R'));
    h.app.on_outcome(crate::app::Outcome::Recording(Ok(
        "oscillator.jsonl".to_owned()
    )));
    // Play at ×8 to t ≈ 4, pause, and compare the screen with the exact solution.
    for _ in 0..3 {
        h.key(Key::Char('+'));
    }
    h.key(Key::Char(' '));
    while h.app.run.shown < 4.0 && !h.app.run.done() {
        h.tick(1.0 / 30.0);
    }
    h.key(Key::Char(' '));
    let t = h.app.run.shown;
    let exact = Problem::new(Params { omega: 2.0 }, Start { x: 1.0, v: 0.5 })
        .unwrap()
        .exact_crossings(t);
    assert_eq!(h.app.run.reversals_shown(), exact, "at t = {t}");
    let text = screen(&h, 80, 24);
    // The panel holds the scene's table; the status bar its words (events, monitor).
    assert!(text.contains("Oscillator: the contract's"), "{text}");
    assert!(
        text.contains("omega") && text.contains("energy E"),
        "{text}"
    );
    assert!(text.contains(&format!("crossings {exact} ")), "{text}");
    assert!(text.contains("ΔE"), "{text}");
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    // The chart pane.
    h.key(Key::Char('M'));
    for _ in 0..200 {
        h.tick(1.0 / 30.0);
    }
    let text = screen(&h, 120, 40);
    assert!(
        text.contains("crossing chart") || text.contains("crossings (T"),
        "{text}"
    );
    // A change (ω one coarse step up, the first row) restarts the run; played to its end at
    // the top speed; then the recording closes and replays as shown.
    h.key(Key::Char('M'));
    h.key(Key::Char('L'));
    assert_eq!(h.app.scenario.settings.model.value("omega"), Some(3.0));
    while h.app.run.speed < 1024.0 {
        h.key(Key::Char('+'));
    }
    h.key(Key::Char(' '));
    while !h.app.run.done() {
        h.tick(1.0 / 30.0);
    }
    let at_end = Problem::new(Params { omega: 3.0 }, Start { x: 1.0, v: 0.5 })
        .unwrap()
        .exact_crossings(10.0);
    assert_eq!(h.app.run.reversals_shown(), at_end);
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    let mut journal = h.app.take_journal();
    h.key(Key::Char('R'));
    for _ in 0..100 {
        h.tick(0.0);
        if h.app.journal.state != crate::app::RecState::On {
            break;
        }
    }
    journal.extend(h.app.take_journal());
    let path = std::env::temp_dir().join(format!("oscillator-{}.jsonl", std::process::id()));
    let back = write_session(&path, &header, journal);
    assert!(back.header.preset.contains("model = \"oscillator\""));
    let report = crate::record::verify(&back, "oscillator", None).unwrap();
    assert!(report.checkpoints >= 2, "{report:?}");
    let _ = std::fs::remove_file(&path);
}
