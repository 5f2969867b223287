//! The scene contract (issues 69 and 83): one generic check, [`contract`], that every scene in
//! the registry passes, the shipped ones and the library's own test scene (the harmonic
//! oscillator in `physics/oscillator/`). A scene implements [`Contract`] in its folder
//! (`SCENE/contract.rs`): a preset, an independent reference for `simulate`'s numbers (an exact
//! solution, a high-precision run, an independent implementation, a theorem) and for its chart's
//! cells; the contract then takes the preset through every output a scene has — the preset read
//! and written back, `simulate` in JSON, CSV and table, `study map`'s chart against the
//! reference with its flags taken or refused and its shards merged, the explorer's screen
//! against `simulate`, a recording with a pause, a change and the top speed that verifies.
//!
//! The tests are generated from the registry's one list (`with_scenes!(contract_tests)`): a
//! scene's line registers it here too, and removing the line removes its test.

use crate::app::Key;
use crate::physics::ModelKind;
use crate::physics::chart::{ChartError, MapFlag};
pub use crate::physics::contract::{Contract, Mismatch, PresetText};
use crate::scenario::Preset;
use crate::study::chart::{Chart, StudyAsk};

/// Which step of the contract failed, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// The step.
    pub step: &'static str,
    /// Why.
    pub what: String,
}

fn fail<T>(step: &'static str, what: impl Into<String>) -> Result<T, Failure> {
    Err(Failure {
        step,
        what: what.into(),
    })
}

/// Every step, for scene `S`.
///
/// # Errors
/// The first step that fails.
pub fn contract<S: Contract>() -> Result<(), Failure> {
    let preset = preset_of::<S>()?;
    preset_reads(&preset)?;
    let json = run_matches_reference::<S>(&preset)?;
    let ask = ask_of::<S>(&preset);
    chart_matches_reference::<S>(&preset, &ask)?;
    flags_taken_or_refused(&preset, &ask, &|a| Chart::for_study(&preset.model, a))?;
    let shown = S::events(&json).ok_or(Failure {
        step: "run",
        what: "no event count in simulate's JSON".to_owned(),
    })?;
    explorer_shows_and_records(&preset, shown, &|_| {})
}

/// The scene's preset, read.
fn preset_of<S: Contract>() -> Result<Preset, Failure> {
    let read = match S::PRESET {
        PresetText::Shipped(name) => crate::scenario::shipped::resolve(name, &[]),
        PresetText::Toml(text) => Preset::parse(text, "contract.toml", "contract", &[]),
    };
    read.map_err(|e| Failure {
        step: "preset",
        what: format!("does not read: {e}"),
    })
}

/// The scene's chart ask, from the preset's horizon and tolerance as `study map` takes them.
fn ask_of<S: Contract>(p: &Preset) -> StudyAsk {
    S::chart(StudyAsk {
        t_end: p.run.t_end,
        tolerance: p.run.tolerance.unwrap_or(crate::physics::DEFAULT_TOLERANCE),
        ..StudyAsk::default()
    })
}

/// The preset is of a registered scene, refuses a misspelt key of the scene's table naming it,
/// and reads back as itself once written.
fn preset_reads(p: &Preset) -> Result<(), Failure> {
    let kind = p.model.kind();
    if !ModelKind::ALL.contains(&kind) || ModelKind::from_name(kind.name()) != Some(kind) {
        return fail("preset", format!("{kind:?} is not registered"));
    }
    let text = p.to_toml();
    let again = Preset::parse(&text, "again.toml", "again", &[]).map_err(|e| Failure {
        step: "preset",
        what: format!("written back, it does not read: {e}"),
    })?;
    if again.model != p.model {
        return fail("preset", "written back, it reads as another problem");
    }
    let Some(spec) = kind
        .params()
        .iter()
        .find(|s| text.contains(&format!("\n{} = ", s.key)))
    else {
        return fail(
            "preset",
            "the written preset names none of the scene's parameters",
        );
    };
    let typo = text.replacen(
        &format!("\n{} = ", spec.key),
        &format!("\n{}x = ", spec.key),
        1,
    );
    match Preset::parse(&typo, "typo.toml", "typo", &[]) {
        Ok(_) => fail("preset", format!("a misspelt `{}x` was accepted", spec.key)),
        Err(e) if !e.to_string().contains(&format!("{}x", spec.key)) => {
            fail("preset", format!("the refusal does not name the key: {e}"))
        }
        Err(_) => Ok(()),
    }
}

/// `simulate` in JSON against the scene's reference; its CSV and table in the scene's words.
fn run_matches_reference<S: Contract>(p: &Preset) -> Result<serde_json::Value, Failure> {
    use crate::simulate::{Format, Request, resolve, simulate};
    let request = Request {
        method: None,
        tolerance: None,
        step: None,
        t_end: None,
        format: Format::Json,
        samples: 51,
        force: true,
    };
    let run = |format| {
        simulate(p, &resolve(p, &Request { format, ..request }), format).map_err(|e| Failure {
            step: "run",
            what: format!("simulate failed: {e}"),
        })
    };
    let json: serde_json::Value =
        serde_json::from_str(&run(Format::Json)?).map_err(|e| Failure {
            step: "run",
            what: format!("simulate's JSON does not parse: {e}"),
        })?;
    let name = p.model.kind().name();
    if json["model"] != name {
        return fail("run", format!("JSON of model {}", json["model"]));
    }
    S::check_run(&json).map_err(|m| Failure {
        step: "run",
        what: m.0,
    })?;
    let csv = run(Format::Csv)?;
    let mut rows = csv.lines().filter(|l| !l.starts_with('#'));
    let head = rows.next().unwrap_or_default();
    if !csv.contains(&format!("# model = {name}\n"))
        || !head.starts_with("t,")
        || rows.count() != 51
    {
        return fail(
            "run",
            format!("CSV not of the scene, or not 51 rows:\n{csv}"),
        );
    }
    let table = run(Format::Table)?;
    if !table.contains(&p.name) && !table.contains(name) {
        return fail("run", "the table names neither the preset nor the scene");
    }
    Ok(json)
}

/// `study map`'s chart: its cells' columns (one answer, no field named twice), every cell
/// against the reference, three shards merged into the whole byte for byte, a cell loaded back
/// at its coordinates.
fn chart_matches_reference<S: Contract>(p: &Preset, ask: &StudyAsk) -> Result<(), Failure> {
    use crate::study::chart::{Shard, Tally};
    let chart = Chart::for_study(&p.model, ask).map_err(|e| Failure {
        step: "chart",
        what: format!("refused: {e}"),
    })?;
    if chart.model() != p.model.kind() {
        return fail("chart", "a chart of another scene");
    }
    crate::physics::chart::check_columns(chart.words().csv).map_err(|e| Failure {
        step: "chart",
        what: format!("its cells' columns: {e}"),
    })?;
    let computed = |shard| {
        chart
            .compute(false, shard, &|_| true, &Tally::QUIET)
            .map_err(|e| Failure {
                step: "chart",
                what: format!("not computed: {e}"),
            })
    };
    let c = computed(None)?;
    let whole = chart.output(1, &p.name, &c.indices, &c.verdicts, None, false);
    let value = serde_json::to_value(&whole).map_err(|e| Failure {
        step: "chart",
        what: e.to_string(),
    })?;
    let cells = value["cells"].as_array().cloned().unwrap_or_default();
    if cells.len() != chart.len() {
        return fail("chart", format!("{} cells of {}", cells.len(), chart.len()));
    }
    for cell in &cells {
        S::check_cell(cell, &value).map_err(|m| Failure {
            step: "chart",
            what: format!("cell {}: {}", cell["coords"], m.0),
        })?;
    }
    let description = crate::study::ask::Description::new(p.to_toml(), ask);
    let mut parts = Vec::new();
    for index in 1..=3 {
        let s = Shard { index, count: 3 };
        let c = computed(Some(s))?;
        let mut out = chart.output(1, &p.name, &c.indices, &c.verdicts, Some(s), false);
        out.description = Some(description.clone());
        parts.push((format!("part{index}"), crate::study::part::sealed(out)));
    }
    let mut merged = crate::study::part::merge(&chart, 1, &parts).map_err(|e| Failure {
        step: "shards",
        what: e.to_string(),
    })?;
    merged.wall_seconds = whole.wall_seconds;
    if serde_json::to_string(&merged).ok() != serde_json::to_string(&whole).ok() {
        return fail("shards", "three shards merged differ from the whole");
    }
    let (x, y) = chart.axes();
    let loaded = chart
        .load(&p.model, (x.at(1), y.at(1)))
        .map_err(|e| Failure {
            step: "chart",
            what: format!("a cell does not load: {e}"),
        })?;
    let at = Chart::for_study(&loaded, ask)
        .map(|c| c.preset_point())
        .map_err(|e| Failure {
            step: "chart",
            what: e.to_string(),
        })?;
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
    if !close(at.0, x.at(1)) || !close(at.1, y.at(1)) {
        return fail("chart", format!("a cell loaded at {at:?}"));
    }
    Ok(())
}

/// Each `study map` flag: refused naming the scene when its chart does not take it (a
/// [`ChartError::Flag`]), and when it does, changing the chart (a flag accepted and ignored
/// fails). `build` makes the chart of an ask (the scene's, or a faulty one in the tests).
fn flags_taken_or_refused(
    p: &Preset,
    ask: &StudyAsk,
    build: &dyn Fn(&StudyAsk) -> Result<Chart, ChartError>,
) -> Result<(), Failure> {
    use strum::IntoEnumIterator as _;
    let kind = p.model.kind();
    let takes = kind.studies().chart.flags;
    let plain = build(ask).map_err(|e| Failure {
        step: "flags",
        what: e.to_string(),
    })?;
    for flag in MapFlag::iter() {
        let given = given_to(flag, ask, &plain);
        if takes.contains(&flag) {
            // Alone, or with another flag it needs (the rattleback's `--tolerance` sets the
            // runs `--k` asks for): the chart with it differs from the chart without it.
            let mut pairs: Vec<(StudyAsk, Chart)> = vec![(*ask, plain)];
            for other in takes.iter().filter(|o| **o != flag) {
                for base in given_to(*other, ask, &plain) {
                    if let Ok(c) = build(&base) {
                        pairs.push((base, c));
                    }
                }
            }
            let changed = pairs.iter().any(|(base, without)| {
                given_to(flag, base, without)
                    .iter()
                    .any(|a| build(a).is_ok_and(|c| c != *without))
            });
            if !changed {
                return fail(
                    "flags",
                    format!("{} is accepted and changes nothing", flag.name()),
                );
            }
        } else {
            for a in &given {
                match build(a) {
                    Err(ChartError::Flag(f))
                        if f.flag == flag && f.to_string().contains(kind.title()) => {}
                    Err(e) => {
                        return fail("flags", format!("{} refused as {e}", flag.name()));
                    }
                    Ok(_) => return fail("flags", format!("{} is accepted", flag.name())),
                }
            }
        }
    }
    Ok(())
}

/// `ask` with `flag` given a valid value other than the chart's own (two for a choice).
fn given_to(flag: MapFlag, ask: &StudyAsk, chart: &Chart) -> Vec<StudyAsk> {
    let (x, y) = chart.axes();
    let narrower = |lo: f64, hi: f64| (lo + 0.25 * (hi - lo), hi - 0.25 * (hi - lo));
    let mut a = *ask;
    match flag {
        MapFlag::RatioMax => a.ratio_max = Some(0.5 * x.max),
        MapFlag::InertiaMin => a.inertia_min = Some(narrower(y.min, y.max).0),
        MapFlag::InertiaMax => a.inertia_max = Some(narrower(y.min, y.max).1),
        MapFlag::K => a.k = Some(12_345.0),
        MapFlag::Columns => a.columns = Some(narrower(x.min, x.max)),
        MapFlag::Rows => a.rows = Some(narrower(y.min, y.max)),
        MapFlag::TEnd => {
            a.t_end *= 0.5;
            a.asked_t_end = Some(a.t_end);
        }
        MapFlag::Tolerance => {
            a.tolerance *= 10.0;
            a.asked_tolerance = Some(a.tolerance);
        }
        MapFlag::Position => {
            let mut b = *ask;
            a.hanging = Some(true);
            b.hanging = Some(false);
            return vec![a, b];
        }
    }
    vec![a]
}

/// The explorer, headless, its worker run in place.
type Headless = crate::explorer::review::Walk;

/// The explorer on the preset: played to its end at the top speed, its status bar shows the
/// count `simulate` gave (`shown`); recording, a change (the first parameter one step up),
/// played at ×8, paused, a step, a checkpoint; the recording closed verifies. `tamper` edits
/// the recording before the check (the contract's own tests).
fn explorer_shows_and_records(
    p: &Preset,
    shown: u64,
    tamper: &dyn Fn(&mut crate::record::Recording),
) -> Result<(), Failure> {
    let mut h = Headless::of(p);
    let header = crate::record::active::header(&h.app, (80, 24), 30.0);
    h.key(Key::Char('R'));
    h.app.on_outcome(crate::app::Outcome::Recording(Ok(
        "contract.jsonl".to_owned()
    )));
    while h.app.run.speed < 1024.0 {
        h.key(Key::Char('+'));
    }
    h.key(Key::Char(' '));
    let mut frames = 0;
    while !h.app.run.done() && frames < 100_000 {
        h.tick(1.0 / 30.0);
        frames += 1;
    }
    let count = h.app.run.reversals_shown() as u64;
    let events = p.model.kind().words().events;
    let screen = h.screen_at((80, 24)).join("\n");
    if count != shown || !screen.contains(&format!("{events} {shown}")) {
        return fail(
            "explorer",
            format!("simulate counts {shown} {events}, the explorer {count}:\n{screen}"),
        );
    }
    let c = vec![h.app.checkpoint()];
    h.exec(c);
    // A change: the first parameter of the panel one coarse step up restarts the run.
    let before = h.app.scenario.settings.model;
    h.key(Key::Char('L'));
    if h.app.scenario.settings.model == before {
        return fail("explorer", "`L` changed nothing");
    }
    while h.app.run.speed > 8.0 {
        h.key(Key::Char('-'));
    }
    h.key(Key::Char(' '));
    let half = 0.5 * h.app.run.t_end;
    while h.app.run.shown < half && !h.app.run.done() && frames < 200_000 {
        h.tick(1.0 / 30.0);
        frames += 1;
    }
    h.key(Key::Char(' '));
    h.key(Key::Char('.'));
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
    let path = std::env::temp_dir().join(format!(
        "contract-{}-{}.jsonl",
        p.model.kind().name(),
        std::process::id()
    ));
    let mut back = write_session(&path, &header, journal);
    let _ = std::fs::remove_file(&path);
    tamper(&mut back);
    match crate::record::verify(&back, "contract", None) {
        Ok(r) if r.checkpoints >= 2 => Ok(()),
        Ok(r) => fail("recording", format!("{} checkpoints", r.checkpoints)),
        Err(e) => fail("recording", format!("does not verify: {e}")),
    }
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

/// One test a registered scene, named after its folder: `scene_contract::celt::contract`…
macro_rules! contract_tests {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $name:ident: $folder:ident, $chart:ident;
    )*) => {
        $(
            mod $folder {
                #[test]
                fn contract() {
                    if let Err(f) = super::contract::<crate::physics::$folder::contract::Case>() {
                        panic!("the {} scene fails the contract at {}: {}", stringify!($folder), f.step, f.what);
                    }
                }
            }
        )*

    };
}
crate::physics::models::with_scenes!(contract_tests);

#[cfg(test)]
mod own {
    //! The contract's own tests: each check can fail, on the oscillator made faulty.
    use super::*;
    use crate::physics::oscillator::contract::Case;

    /// A scene whose chart disagrees with its reference (each cell expected one more).
    struct WrongChart;

    impl Contract for WrongChart {
        const PRESET: PresetText = Case::PRESET;
        fn events(json: &serde_json::Value) -> Option<u64> {
            Case::events(json)
        }
        fn check_run(json: &serde_json::Value) -> Result<(), Mismatch> {
            Case::check_run(json)
        }
        fn chart(base: StudyAsk) -> StudyAsk {
            Case::chart(base)
        }
        fn check_cell(cell: &serde_json::Value, chart: &serde_json::Value) -> Result<(), Mismatch> {
            let mut shifted = cell.clone();
            shifted["crossings"] = serde_json::json!(cell["crossings"].as_u64().unwrap_or(0) + 1);
            Case::check_cell(&shifted, chart)
        }
    }

    #[test]
    fn the_contract_fails_a_chart_that_disagrees_with_its_reference() {
        let p = preset_of::<Case>().unwrap();
        let e = chart_matches_reference::<WrongChart>(&p, &ask_of::<WrongChart>(&p)).unwrap_err();
        assert_eq!(e.step, "chart", "{e:?}");
        chart_matches_reference::<Case>(&p, &ask_of::<Case>(&p)).unwrap();
    }

    #[test]
    fn the_contract_fails_a_recording_that_does_not_verify() {
        let p = preset_of::<Case>().unwrap();
        let json = run_matches_reference::<Case>(&p).unwrap();
        let shown = Case::events(&json).unwrap();
        assert!(explorer_shows_and_records(&p, shown, &|_| {}).is_ok());
        // The recording's last checkpoint says another point than the run reaches.
        let forged = |r: &mut crate::record::Recording| {
            use crate::app::journal::Event;
            let at = r
                .lines
                .iter()
                .rposition(|l| matches!(l.1.event, Event::Checkpoint { .. }))
                .expect("a checkpoint");
            if let Event::Checkpoint { state, .. } = &mut r.lines[at].1.event {
                state[0] += 1e-3;
            }
        };
        let e = explorer_shows_and_records(&p, shown, &forged).unwrap_err();
        assert_eq!(e.step, "recording", "{e:?}");
        // And a screen that shows another count than simulate's.
        let e = explorer_shows_and_records(&p, shown + 1, &|_| {}).unwrap_err();
        assert_eq!(e.step, "explorer", "{e:?}");
    }

    #[test]
    fn the_contract_fails_a_flag_accepted_and_ignored() {
        let p = preset_of::<Case>().unwrap();
        let ask = ask_of::<Case>(&p);
        assert!(flags_taken_or_refused(&p, &ask, &|a| Chart::for_study(&p.model, a)).is_ok());
        // A chart that takes `--t-end` and drops it.
        let ignoring = |a: &StudyAsk| {
            let mut a = *a;
            a.asked_t_end = None;
            a.t_end = ask.t_end;
            Chart::for_study(&p.model, &a)
        };
        let e = flags_taken_or_refused(&p, &ask, &ignoring).unwrap_err();
        assert_eq!(e.step, "flags", "{e:?}");
        assert!(e.what.contains("--t-end"), "{e:?}");
        // A chart that takes what the scene refuses.
        let lax = |a: &StudyAsk| {
            let mut a = *a;
            a.k = None;
            Chart::for_study(&p.model, &a)
        };
        let e = flags_taken_or_refused(&p, &ask, &lax).unwrap_err();
        assert!(e.what.contains("--k"), "{e:?}");
    }

    #[test]
    fn the_contract_fails_a_run_that_disagrees_with_its_reference() {
        let p = preset_of::<Case>().unwrap();
        let moved = Preset::parse(
            &p.to_toml().replace("omega = 2.0", "omega = 2.001"),
            "m.toml",
            "m",
            &[],
        )
        .unwrap();
        assert_ne!(moved.model, p.model);
        let e = run_matches_reference::<Case>(&moved).unwrap_err();
        assert_eq!(e.step, "run", "{e:?}");
    }
}
