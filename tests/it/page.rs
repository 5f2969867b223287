//! Issue 28, item 6: `replay FILE --export-html OUT` writes one self-contained page: the
//! vendored player (its script, style sheet and licence inlined), the cast inlined as JSON that
//! cannot end its `<script>`, the chapters as links to the player's markers, no resource fetched
//! from anywhere; the cast it holds has no key footer and no frame that changes nothing.
//! (`.ci/run` also opens the page in headless Chromium and checks the player's last frame:
//! `scripts/check_page.mjs`.)

const LECTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/sessions/lecture.jsonl"
);

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rattleback-page-{}", std::process::id()));
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
    let links = rattleback::page::links(&rec);
    assert!(!links.is_empty());
    for l in &links {
        assert!(
            page.contains(&format!("data-marker=\"{}\">{}</a>", l.marker, l.title)),
            "{l:?}"
        );
    }
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
