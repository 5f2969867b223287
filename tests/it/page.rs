//! Issue 28, item 6: `replay FILE --export-html OUT` writes one self-contained page: the
//! vendored player (its script, style sheet and licence inlined), the cast inlined as JSON that
//! cannot end its `<script>`, the chapters as links to the player's markers, no resource fetched
//! from anywhere; the cast it holds has no key footer and no frame that changes nothing.
//! (`.ci/run` also opens the page in headless Chromium and checks the player's last frame:
//! `scripts/check_page.mjs`.)

const LECTURE: &str = concat!(root!(), "/tests/fixtures/sessions/lecture.jsonl");

fn temp(name: &str) -> std::path::PathBuf {
    // One folder per test (they run in parallel, and each removes its own).
    let dir = std::env::temp_dir().join(format!(
        "rattleback-page-{}-{}",
        std::process::id(),
        name.replace('.', "-")
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The cast's events after its header line.
fn events(cast: &str) -> Vec<serde_json::Value> {
    cast.lines()
        .skip(1)
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn the_exported_page_is_self_contained_with_the_cast_and_chapter_links() {
    let (html, cast) = (temp("lecture.html"), temp("lecture.cast"));
    let (code, out, err) = crate::common::bin(&[
        "replay",
        LECTURE,
        "--export-html",
        html.to_str().unwrap(),
        "--export-cast",
        cast.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("frames"), "{out}");
    let page = std::fs::read_to_string(&html).unwrap();
    // Self-contained: the player inlined, nothing fetched.
    assert!(page.starts_with("<!DOCTYPE html>"));
    assert!(page.contains("AsciinemaPlayer.create"));
    let player = include_str!("../../assets/asciinema-player/asciinema-player.min.js");
    assert!(page.contains(player), "the vendored script, unmodified");
    assert!(page.contains(include_str!(
        "../../assets/asciinema-player/asciinema-player.css"
    )));
    assert!(page.contains("Apache License"), "the player's licence");
    for fetch in ["<script src", "<link", "@import", "url(http"] {
        assert!(!page.contains(fetch), "the page fetches something: {fetch}");
    }
    // The cast, inlined: the same text as --export-cast writes, safe inside <script>.
    let start = page
        .find("<script type=\"application/json\" id=\"cast\">")
        .unwrap();
    let json = &page[start..];
    let json = &json[json.find('>').unwrap() + 1..json.find("</script>").unwrap()];
    assert!(!json.contains('<'), "a '<' could end the script");
    let inlined: String = serde_json::from_str(json).unwrap();
    assert_eq!(
        inlined,
        std::fs::read_to_string(&cast).unwrap(),
        "the page's cast is the cast"
    );
    // Chapters: a link per chapter, seeking to its marker; the cast has the markers.
    let rec = rattleback::record::read(std::path::Path::new(LECTURE)).unwrap();
    let links = rattleback::commands::page::links(&rec);
    assert!(!links.is_empty());
    // Each link carries its marker's time on the player's clock, and says it.
    let times: Vec<f64> = rattleback::cast::player_clock(&inlined)
        .into_iter()
        .filter(|(_, kind)| kind == "m")
        .map(|(t, _)| t)
        .collect();
    for l in &links {
        let at = times[l.marker];
        let seconds = at.floor() as u64;
        assert!(
            page.contains(&format!(
                "data-marker=\"{}\" data-time=\"{at:.6}\">{}</a> <small>{}:{:02}</small>",
                l.marker,
                l.title,
                seconds / 60,
                seconds % 60
            )),
            "{l:?}"
        );
    }
    // The page opens on the last frame (a poster), and does not play by itself.
    let poster = rattleback::commands::page::poster_time(&inlined);
    assert!(page.contains(&format!("poster: \"npt:{poster:.6}\"")));
    assert!(!page.contains("autoPlay: true"));
    let ev = events(&inlined);
    let markers: Vec<&serde_json::Value> = ev.iter().filter(|e| e[1] == "m").collect();
    assert!(
        markers.len() > links.iter().map(|l| l.marker).max().unwrap(),
        "{markers:?}"
    );
    // No key footer, no frame that changes nothing.
    let frames: Vec<&str> = ev
        .iter()
        .filter(|e| e[1] == "o")
        .map(|e| e[2].as_str().unwrap())
        .collect();
    assert!(frames.len() > 10);
    for f in &frames {
        assert!(
            !f.contains("? help") && !f.contains("q quit"),
            "the footer is recorded: {f:?}"
        );
        assert!(
            rattleback::cast::changes_something(f.as_bytes()),
            "a frame that changes nothing: {f:?}"
        );
    }
    // The recorded title is escaped.
    assert!(page.contains("<title>rattleback: Subcritical start</title>"));
    // Refused where it would overwrite, or be the session itself.
    let (code, _, err) =
        crate::common::bin(&["replay", LECTURE, "--export-html", html.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--export-html") && err.contains("exists"),
        "{err}"
    );
    std::fs::remove_dir_all(html.parent().unwrap()).ok();
    std::fs::remove_dir_all(cast.parent().unwrap()).ok();
}

/// Issue 55: a lesson's page lists its steps as chapters, each a marker of the cast, in order;
/// the replay's `]` jumps to them as to a lecturer's chapters.
#[test]
fn a_lessons_steps_are_its_pages_chapters() {
    let lesson = concat!(
        root!(),
        "/tests/fixtures/sessions/lesson-kapitza-threshold.jsonl"
    );
    let rec = rattleback::record::read(std::path::Path::new(lesson)).unwrap();
    let titles: Vec<String> = rattleback::commands::page::links(&rec)
        .into_iter()
        .map(|l| l.title)
        .collect();
    assert_eq!(
        titles,
        [
            "step 1/3: Shaken, but not enough",
            "step 2/3: Shaken a little harder",
            "step 3/3: Find the threshold yourself"
        ]
    );
    let html = temp("lesson.html");
    let (code, _, err) = crate::common::bin(&[
        "replay",
        lesson,
        "--verify",
        "--export-html",
        html.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 0, "{err}");
    let page = std::fs::read_to_string(&html).unwrap();
    for t in &titles {
        assert!(page.contains(&format!(">{t}</a>")), "{t}");
    }
    std::fs::remove_dir_all(html.parent().unwrap()).ok();
    // In the replay, `]` goes from step to step, each at its start (t 0, the step's preset).
    let (app, effects) = rattleback::record::start(&rec, lesson).unwrap();
    let mut h = crate::common::Headless {
        app,
        engine: rattleback::sim::Engine::new(rattleback::record::plan_book(&rec)),
        effects: Vec::new(),
    };
    h.exec(effects);
    let lines: Vec<_> = rec.lines.iter().map(|(_, l)| l.clone()).collect();
    let mut r = rattleback::record::replayer::Replayer::new(lines);
    let e = r.catch_up(&mut h.app);
    h.exec(e);
    let preset = rattleback::scenario::shipped::resolve("kapitza-upright", &[]).unwrap();
    let rebuild = |old: &rattleback::app::App| {
        rattleback::app::App::new_after(&preset, rattleback::app::Options::at(30.0), old)
    };
    for step in 0..3 {
        let e = r.key(rattleback::app::Key::Char(']'), &mut h.app, &rebuild);
        h.exec(e);
        let state = h.app.lesson.as_ref().expect("the recorded lesson");
        assert_eq!(state.step, step, "] lands on step {}", step + 1);
        assert!(h.app.run.shown.abs() < 1e-12, "step {}: t 0", step + 1);
    }
}

#[test]
fn a_frame_of_escape_codes_alone_changes_nothing() {
    use rattleback::cast::changes_something;
    assert!(!changes_something(
        b"\x1b[?25l\x1b[23;4H\x1b[0m\x1b]0;title\x07"
    ));
    assert!(!changes_something(b""));
    assert!(changes_something(b"\x1b[1;1Hx"));
    assert!(changes_something("\x1b[2;3H⠞".as_bytes()));
}
