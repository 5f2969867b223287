//! Issue 81: a program, not a checkout. Text that fits the terminal it is printed on (and
//! piped output as it was), popups that own their keys, prompts with their own footer, and
//! each small untruth of the newcomer's review (shared/docs/reviews/newcomer.md D-2…D-13, the
//! lecturer's L7), each with a test that fails on the binary before.

use crate::common;
use crate::explorer_ui::{render, text};

use common::Headless;
use rattleback::app::{App, Key, Mode, ReplayInfo};
use rattleback::scenario::shipped::resolve;

/// What `args` prints on stdout in a pseudo-terminal `cols` columns wide (carriage returns
/// dropped), and its exit status.
fn in_terminal(cols: u16, args: &str) -> (i32, String) {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("log");
    let line = format!(
        "stty cols {cols} rows 24; {} {args}",
        crate::common::program()
    );
    let status = common::in_pty(&line, &log)
        .env("RATTLEBACK_CONFIG_DIR", dir.path().join("cfg"))
        .env("HOME", dir.path())
        .env("LANG", "C.UTF-8")
        .stdin(std::process::Stdio::null())
        .status()
        .unwrap();
    // `script` frames the log with its own lines.
    let out = std::fs::read_to_string(&log)
        .unwrap()
        .replace('\r', "")
        .lines()
        .filter(|l| !l.starts_with("Script started") && !l.starts_with("Script done"))
        .fold(String::new(), |mut all, l| {
            all.push_str(l);
            all.push('\n');
            all
        });
    (status.code().unwrap_or(-1), out)
}

/// What `args` prints on stdout into a pipe.
fn piped(args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = common::rattleback()
        .args(args)
        .env("RATTLEBACK_CONFIG_DIR", dir.path().join("cfg"))
        .env("HOME", dir.path())
        .env("LANG", "C.UTF-8")
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    String::from_utf8(out.stdout).unwrap()
}

/// A number cut by a line's end: a line ending in a digit (or a decimal point) whose next line
/// goes on with a digit, as `… 24.383138, 2` / `8.816757` did.
fn split_numbers(out: &str) -> Vec<String> {
    let lines: Vec<&str> = out.lines().collect();
    lines
        .windows(2)
        .filter(|w| {
            w[0].ends_with(|c: char| c.is_ascii_digit() || c == '.')
                && w[1].trim_start().starts_with(|c: char| c.is_ascii_digit())
                // A table's next row starts with its name, never with a digit: a digit there
                // goes on the number above.
                && w[1].starts_with(' ')
        })
        .map(|w| format!("{} ⏎ {}", w[0], w[1]))
        .collect()
}

fn longest(out: &str) -> usize {
    out.lines().map(|l| l.chars().count()).max().unwrap_or(0)
}

/// Issue 81 (D-7): in a terminal 80 columns wide, no line of `simulate` (every scene),
/// `presets`, `lessons`, `themes` or `doctor` is wider than 80 and no number is split; the
/// words are the same words as piped, only the spaces differ.
#[test]
fn headless_text_wraps_at_the_terminals_width_between_words() {
    let cases: &[&str] = &[
        "simulate --preset subcritical",
        "simulate --preset kapitza-upright",
        "simulate --preset celt-clockwise",
        "simulate --preset tapping",
        "presets",
        "lessons",
        "themes",
        "doctor",
    ];
    for case in cases {
        let (rc, out) = in_terminal(80, case);
        assert_eq!(rc, 0, "{case}: {out}");
        assert!(
            longest(&out) <= 80,
            "{case}: a line of {} columns:\n{out}",
            longest(&out)
        );
        let split = split_numbers(&out);
        assert!(split.is_empty(), "{case}: numbers split: {split:?}\n{out}");
        // Only whitespace moves (the timings of `simulate` and the terminal of `doctor` are
        // facts of the run, not of the wrapping).
        if matches!(*case, "presets" | "lessons" | "themes") {
            let args: Vec<&str> = case.split(' ').collect();
            let words = |s: &str| s.split_whitespace().map(str::to_owned).collect::<Vec<_>>();
            assert_eq!(words(&out), words(&piped(&args)), "{case}");
        }
    }
}

/// Issue 81: piped, a report is as it was, one line per row however long: the reversal times
/// of `simulate` on one line.
#[test]
fn piped_text_is_not_wrapped() {
    let out = piped(&["simulate", "--preset", "subcritical"]);
    let full = out
        .lines()
        .find(|l| l.trim_start().starts_with("full at"))
        .unwrap_or_else(|| panic!("{out}"));
    assert!(
        full.contains("2.216604") && full.contains("28.816757"),
        "{full}"
    );
    assert!(full.chars().count() > 80, "{full}");
}

/// Issue 81 (D-10): the `--serve` address box closes on any key, which does nothing else: `q`
/// does not end the lecture, `space` does not play, `x` exports nothing.
#[test]
fn the_address_box_swallows_the_key_that_closes_it() {
    for key in [
        Key::Char('q'),
        Key::Char(' '),
        Key::Char('x'),
        Key::Char('r'),
    ] {
        let mut h = Headless::new("subcritical");
        h.app.mode = Mode::Address("http://127.0.0.1:8080/".to_owned());
        let before = (h.app.run.playing, h.app.run.shown, h.app.status.clone());
        let effects = h.app.on_key(key);
        assert!(effects.is_empty(), "{key:?}: {effects:?}");
        assert_eq!(h.app.mode, Mode::Normal, "{key:?} closes it");
        assert!(!h.app.quit, "{key:?} quit the lecture");
        assert_eq!(
            (h.app.run.playing, h.app.run.shown, h.app.status.clone()),
            before,
            "{key:?}"
        );
    }
    // An error's dialog keeps issue 66's choice, which its title states: "other keys act".
    let mut h = Headless::new("subcritical");
    h.app.mode = Mode::Dialog("something failed".to_owned());
    let screen = text(&render(&h.app, 80, 24));
    assert!(screen.contains("other keys act"), "{screen}");
}

/// Issue 81 (D-8): in `?`, typing `reset` filters the help to the lines holding it and leaves
/// the run as it was; Backspace takes letters back, Esc closes.
#[test]
fn typing_in_the_help_filters_it_and_does_nothing_else() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char(' '));
    h.tick(1.0);
    h.key(Key::Char(' '));
    let before = (h.app.run.playing, h.app.run.shown, h.app.view);
    assert!(before.1 > 0.0, "the run moved");
    h.key(Key::Char('?'));
    for c in "reset".chars() {
        let effects = h.app.on_key(Key::Char(c));
        assert!(effects.is_empty(), "{c}: {effects:?}");
    }
    let Mode::Help(help) = &h.app.mode else {
        panic!("the help stays open: {:?}", h.app.mode)
    };
    assert_eq!(help.filter, "reset");
    assert_eq!((h.app.run.playing, h.app.run.shown, h.app.view), before);
    let screen = text(&render(&h.app, 80, 24));
    assert!(screen.contains("holding 'reset'"), "{screen}");
    assert!(
        screen.contains("r ") || screen.contains("reset"),
        "{screen}"
    );
    // The key rows not holding the word are gone.
    assert!(!screen.contains("zoom in"), "{screen}");
    h.key(Key::Backspace);
    let Mode::Help(help) = &h.app.mode else {
        panic!("Backspace keeps it open")
    };
    assert_eq!(help.filter, "rese");
    h.key(Key::Esc);
    assert_eq!(h.app.mode, Mode::Normal);
    assert_eq!(h.app.run.shown.to_bits(), before.1.to_bits());
}

/// Issue 81 (D-3): while a prompt is typed the footer says what the keys do then, not
/// `space play · q quit`, and the message offers no `v`.
#[test]
fn a_prompt_shows_its_own_footer() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('s'));
    assert!(matches!(h.app.mode, Mode::Prompt(_)), "{:?}", h.app.mode);
    let screen = text(&render(&h.app, 80, 24));
    let footer = screen.lines().last().unwrap();
    assert!(
        footer.contains("Enter") && footer.contains("Esc"),
        "{footer}"
    );
    assert!(
        !footer.contains("space play") && !footer.contains("quit"),
        "{footer}"
    );
    assert!(!screen.contains("v: whole"), "{screen}");
}

/// Issue 81 (D-4): `x`'s message at 80 columns shows both files' names (their folders cut in
/// the middle).
#[test]
fn the_exports_message_names_both_files_at_80_columns() {
    let (mut app, _) = App::new(
        &resolve("subcritical", &[]).unwrap(),
        rattleback::app::Options::at(30.0),
    );
    let dir = "/home/a-lecturer/scratch/rev6-newcomer/cfg/sessions";
    let stem = "subcritical-start-2026-11-29-042228";
    let paths = vec![
        std::path::PathBuf::from(format!("{dir}/{stem}.svg")),
        std::path::PathBuf::from(format!("{dir}/{stem}.csv")),
    ];
    app.on_outcome(rattleback::app::Outcome::Exported(Ok(paths)));
    let screen = text(&render(&app, 80, 24));
    let line = screen
        .lines()
        .find(|l| l.contains("wrote"))
        .unwrap_or_else(|| panic!("{screen}"));
    assert!(line.contains("042228.svg"), "{line}");
    assert!(line.contains("042228.csv"), "{line}");
    assert!(!line.contains("v: whole"), "{line}");
}

fn replay(live: Option<bool>, ended: bool) -> ReplayInfo {
    ReplayInfo {
        pace: 1.0,
        paused: false,
        chapter: 0,
        chapters: 0,
        ended,
        at: 6.5,
        length: 6.5,
        live,
    }
}

/// Issue 81: a follower caught up with a live lecture offers `space` and `f`; once the lecture
/// has ended the state is not `▶` beside "lecture ended", and `f` is still offered.
#[test]
fn a_followers_status_and_footer_say_what_it_can_do() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char(' '));
    h.tick(0.5);
    assert!(h.app.run.playing);
    // Live, caught up with what was written.
    h.app.replay = Some(replay(Some(false), true));
    let screen = text(&render(&h.app, 80, 24));
    let footer = screen.lines().last().unwrap().to_owned();
    assert!(footer.contains("space pause"), "{footer}");
    assert!(footer.contains("f fork"), "{footer}");
    // The lecture ended.
    h.app.replay = Some(replay(Some(true), true));
    let screen = text(&render(&h.app, 80, 24));
    let lines: Vec<&str> = screen.lines().collect();
    let status = lines[lines.len() - 2];
    let footer = lines[lines.len() - 1];
    assert!(status.contains("lecture ended"), "{status}");
    assert!(
        !status.contains('▶') && status.contains("stopped"),
        "{status}"
    );
    assert!(footer.contains("f fork"), "{footer}");
    assert!(!footer.contains("space"), "{footer}");
    // A replay at its end: stopped too, and no `f` (nothing to fork from a file replayed).
    h.app.replay = Some(replay(None, true));
    let screen = text(&render(&h.app, 80, 24));
    let lines: Vec<&str> = screen.lines().collect();
    assert!(
        !lines[lines.len() - 2].contains('▶'),
        "{}",
        lines[lines.len() - 2]
    );
    assert!(!lines[lines.len() - 1].contains("fork"));
}

/// Issue 81 (D-2): `--fps`'s help says the default of each command that takes it: 10 for
/// `serve` and an exported cast, where 30 is the most.
#[test]
fn the_fps_help_says_the_defaults_that_hold() {
    for command in ["serve", "replay"] {
        let (rc, out, _) = common::bin(&[command, "--help"]);
        assert_eq!(rc, 0);
        let help = out.split_whitespace().collect::<Vec<_>>().join(" ");
        let at = help.find("--fps").unwrap_or_else(|| panic!("{help}"));
        let about = &help[at..(at + 200).min(help.len())];
        assert!(about.contains("10"), "{command}: {about}");
        assert!(!about.contains("[default: 30]"), "{command}: {about}");
    }
}

/// Issue 81 (D-13): what the guide says `--help` ends with is what it ends with.
#[test]
fn the_guide_says_what_help_holds() {
    let guide = include_str!(concat!(root!(), "/docs/guide.md"));
    let flat = guide.split_whitespace().collect::<Vec<_>>().join(" ");
    let at = flat
        .find("`rattleback --help` ends with")
        .expect("the guide says what --help ends with");
    // What it says `--help` itself holds: up to the parenthesis or the clause that follows.
    let sentence = &flat[at..flat[at..].find([';', '(']).map_or(flat.len(), |e| at + e)];
    let (rc, help, _) = common::bin(&["--help"]);
    assert_eq!(rc, 0);
    if sentence.contains("environment") {
        assert!(help.contains("RATTLEBACK_CONFIG_DIR"), "{sentence}");
    }
    if sentence.contains("exit codes") {
        assert!(help.to_lowercase().contains("exit"), "{sentence}");
    }
    assert!(
        help.contains("rattleback man"),
        "--help points to the manual"
    );
    let (rc, man, _) = common::bin(&["man"]);
    assert_eq!(rc, 0);
    assert!(man.contains("ENVIRONMENT") && man.contains("EXIT STATUS"));
}

/// Issue 81 (D-6): a chart over the budget names itself in words that read: not "this
/// reversals (T 10) (20000 cells to compute)".
#[test]
fn a_charts_refusal_reads() {
    let (rc, _, err) = common::bin(&[
        "study",
        "map",
        "--preset",
        "celt-clockwise",
        "--grid",
        "400x200",
    ]);
    assert_eq!(rc, 2, "{err}");
    assert!(err.contains("the chart reversals (T "), "{err}");
    assert!(err.contains("cells to compute, predicted"), "{err}");
    assert!(!err.contains("this reversals"), "{err}");
}

/// Issue 81 (D-11): a lesson writes a scene's value as the panel shows it.
#[test]
fn a_lessons_values_read_as_the_panel_shows_them() {
    let lesson = rattleback::scenario::lesson::resolve("kapitza-threshold").unwrap();
    let first = &lesson.steps[0].text;
    assert!(first.contains("b = 1.378405"), "{first}");
    assert!(!first.contains("1.3784048"), "{first}");
}

/// Issue 81 (D-12): an interrupted `bench` leaves no folder it made.
#[test]
fn an_interrupted_bench_leaves_no_empty_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench-results");
    let child = common::rattleback()
        .args(["bench", "--out"])
        .arg(&out)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // It has made its folder and is at work.
    let start = std::time::Instant::now();
    while !out.exists() && start.elapsed() < std::time::Duration::from_secs(30) {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    assert!(out.exists(), "bench made its folder");
    std::thread::sleep(std::time::Duration::from_millis(500));
    let sent = common::detached("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let output = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{err}");
    assert!(err.contains("nothing was written"), "{err}");
    assert!(!out.exists(), "an empty folder left: {}", out.display());
}

/// Issue 81 (D-12): a folder that was there before stays, empty or not.
#[test]
fn a_study_keeps_a_folder_it_did_not_make() {
    let dir = tempfile::tempdir().unwrap();
    let (rc, _, err) = common::bin(&[
        "study",
        "sweep",
        "--preset",
        "nope",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(rc, 2, "{err}");
    assert!(dir.path().is_dir());
    // A folder it made for a run refused after making it goes again.
    let made = dir.path().join("new");
    let (rc, _, err) = common::bin(&[
        "study",
        "sweep",
        "--preset",
        "subcritical",
        "--t-end",
        "1e9",
        "--out",
        made.to_str().unwrap(),
    ]);
    assert_ne!(rc, 0, "{err}");
    assert!(!made.exists(), "{err}");
}

/// Issue 81 (D-5): `themes show` and `lessons show` print a built-in file as `presets show`
/// does: the shipped text, which reads back.
#[test]
fn themes_and_lessons_show_their_files() {
    let (rc, out, err) = common::bin(&["themes", "show", "default"]);
    assert_eq!(rc, 0, "{err}");
    assert_eq!(
        out,
        include_str!(concat!(root!(), "/themes/default.toml")),
        "the shipped theme"
    );
    let (rc, out, err) = common::bin(&["lessons", "show", "first-reversal"]);
    assert_eq!(rc, 0, "{err}");
    assert_eq!(
        out,
        include_str!(concat!(root!(), "/lessons/first-reversal.toml"))
    );
    let (rc, _, err) = common::bin(&["lessons", "show", "first-reversl"]);
    assert_eq!(rc, 2);
    assert!(err.contains("did you mean `first-reversal`"), "{err}");
    let (_, list, _) = common::bin(&["themes"]);
    assert!(list.contains("rattleback themes show"), "{list}");
}

/// Issue 81 (L7): `check` counts steps as the explorer does, suggests the key that matches,
/// reports every key error at once, and says when the walk was not run.
#[test]
fn check_reports_every_problem_in_a_persons_words() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        "[lesson]\ntitle = \"Bad\"\n\n[[step]]\ntitle = \"One\"\ntext = \"x\"\npreset = \"celt-clockwise\"\n\n[step.until]\nparameter = \"celt.omega_z\"\nat_least = 1.0\ntime = 2.0\n\n[[step]]\ntitle = \"Two\"\ntext = \"y\"\npreset = \"nope-preset\"\npane = \"mapz\"\n\n[step.until]\ntime = 2.0\n",
    )
    .unwrap();
    let (rc, _, err) = common::bin(&["check", path.to_str().unwrap()]);
    assert_eq!(rc, 2, "{err}");
    assert!(err.contains("step 1, until.parameter"), "{err}");
    assert!(!err.contains("step.0"), "{err}");
    assert!(err.contains("did you mean `initial.omega_z`"), "{err}");
    assert!(err.contains("step 2, preset"), "{err}");
    assert!(err.contains("step 2, pane"), "{err}");
    assert!(err.contains("not walked"), "{err}");
}

/// Issue 82: `rattleback web DIR` refuses to replace an earlier site before any build, naming
/// the file and `--force`.
#[test]
fn web_refuses_to_replace_a_site_before_building() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("index.html"), "mine").unwrap();
    let (rc, _, err) = common::bin(&["web", dir.path().to_str().unwrap()]);
    assert_eq!(rc, 2, "{err}");
    assert!(
        err.contains("index.html exists; --force replaces it"),
        "{err}"
    );
    assert!(!err.contains("building"), "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("index.html")).unwrap(),
        "mine"
    );
}
