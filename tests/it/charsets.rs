//! Issue 28, item 1: terminals as they are. Under `LANG=C` (or `--ascii`) every cell the
//! explorer draws is ASCII; on the Linux console every cell is a character Debian's console
//! fonts have (`tests/fixtures/console/glyphs.txt`, read from the fonts by
//! `scripts/console_fonts.py`); the portrait's curves keep distinct characters in both. Checked
//! on every shipped preset at ×1 and top speed, with every pane and the help open, at 80×24 and
//! 160×48, through the worker and the `TestBackend`; and end to end through the binary.

use std::collections::BTreeSet;

use crate::common::{self, Headless};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;

use rattleback::app::{App, Key};
use rattleback::scenario::shipped::SHIPPED;
use rattleback::ui::glyphs::{CONSOLE, Charset};
use rattleback::ui::{self, Cache, UiOptions};

fn render(app: &App, width: u16, height: u16, charset: Charset) -> Buffer {
    let options = UiOptions::default().with_charset(charset);
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal
        .draw(|f| ui::draw(f, app, &options, &mut Cache::default()))
        .unwrap();
    terminal.backend().buffer().clone()
}

fn text(buffer: &Buffer) -> String {
    let mut out = String::new();
    for y in 0..buffer.area.height {
        for x in 0..buffer.area.width {
            out.push_str(buffer[(x, y)].symbol());
        }
        out.push('\n');
    }
    out
}

/// The code points every console font has, from the fixture.
fn console_fonts() -> BTreeSet<char> {
    let path = std::path::Path::new(root!()).join("tests/fixtures/console/glyphs.txt");
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
        .map(|l| char::from_u32(u32::from_str_radix(l, 16).unwrap()).unwrap())
        .collect()
}

/// Every screen a user can reach on `name` (paused at t = 2 after playing at `speed`), drawn in
/// `charset`: the explorer alone and with the help; at ×1 also with each pane opened in turn.
fn screens(name: &str, speed: f64, charsets: &[Charset]) -> Vec<(String, Charset, String)> {
    let mut h = Headless::new(name);
    h.play_until(2.0, speed);
    h.key(Key::Char(' '));
    let mut out = Vec::new();
    let mut shoot = |h: &Headless, what: &str| {
        for &charset in charsets {
            for (w, ht) in [(80, 24), (160, 48)] {
                out.push((
                    format!("{name} ×{speed} {what} {w}x{ht}"),
                    charset,
                    text(&render(&h.app, w, ht, charset)),
                ));
            }
        }
    };
    shoot(&h, "explorer");
    if speed < 2.0 {
        for pane in ['t', 'K', 'W', 'B', 'M'] {
            h.key(Key::Char(pane));
            shoot(&h, &format!("pane {pane}"));
            h.key(Key::Char(pane));
        }
    }
    h.key(Key::Char('?'));
    shoot(&h, "help");
    out
}

#[test]
fn every_screen_of_every_preset_fits_ascii_and_the_console_fonts() {
    let fonts = console_fonts();
    for c in CONSOLE.chars() {
        assert!(
            fonts.contains(&c),
            "{c} (U+{:04X}) is not in every console font",
            c as u32
        );
    }
    for (name, _) in SHIPPED {
        for speed in [1.0, 1024.0] {
            for (what, charset, screen) in screens(name, speed, &[Charset::Ascii, Charset::Console])
            {
                let bad: BTreeSet<char> = match charset {
                    Charset::Ascii => screen.chars().filter(|c| !c.is_ascii()).collect(),
                    _ => screen
                        .chars()
                        .filter(|c| *c != '\n' && !fonts.contains(c))
                        .collect(),
                };
                assert!(bad.is_empty(), "{what} {charset:?}: {bad:?}\n{screen}");
                // Not a screen of question marks: what was folded has a likeness.
                assert!(
                    screen.matches('?').count() < 20,
                    "{what}: too many '?'\n{screen}"
                );
            }
        }
    }
    // The check can fail: the Unicode screen has Braille, which no console font has.
    let unicode = &screens("subcritical", 1024.0, &[Charset::Unicode])[0].2;
    assert!(unicode.chars().any(|c| !fonts.contains(&c)));
}

/// The portrait's curves keep one character each when each cell holds one point: levels `.`,
/// the start's level `:`, the separatrix `+`, the trail `*` (`•` on the console), the limit `o`,
/// the current point `@` (`●`).
#[test]
fn the_portraits_curves_stay_apart_in_ascii_and_on_the_console() {
    let mut h = Headless::new("subcritical");
    h.play_until(6.0, 4.0);
    h.key(Key::Char(' '));
    for (charset, marks) in [
        (Charset::Ascii, ['.', ':', '+', '*', 'o', '@']),
        (Charset::Console, ['.', ':', '+', '•', 'o', '●']),
    ] {
        let buffer = render(&h.app, 120, 40, charset);
        let screen = text(&buffer);
        // The plot: right of the panel, below the title, above the axis labels.
        let plot: String = screen
            .lines()
            .skip(2)
            .take(30)
            .map(|l| l.chars().skip(40).collect::<String>())
            .collect();
        for m in marks {
            assert!(
                plot.contains(m),
                "{charset:?}: no '{m}' in the portrait\n{screen}"
            );
        }
    }
}

/// The binary: `--ascii` reaches the cast export (the bytes a player gets are ASCII), and the
/// same export without it has Braille.
#[test]
fn an_exported_cast_is_ascii_with_the_flag() {
    let dir = std::env::temp_dir().join(format!("rattleback-charsets-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = concat!(root!(), "/tests/fixtures/sessions/subcritical.jsonl");
    for (flag, ascii) in [(Some("--ascii"), true), (None, false)] {
        let cast = dir.join(format!("{ascii}.cast"));
        let (s, p) = (session, cast.to_str().unwrap());
        let mut args = vec!["replay", s, "--export-cast", p, "--force"];
        args.extend(flag);
        let (code, _, err) = common::bin(&args);
        assert_eq!(code, 0, "{err}");
        let bytes = std::fs::read(&cast).unwrap();
        assert_eq!(bytes.iter().all(u8::is_ascii), ascii, "{flag:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `rattleback doctor` reports the same decisions the explorer makes, with the reason.
#[test]
fn doctor_says_what_was_chosen_and_why() {
    let run = |env: &[(&str, &str)], args: &[&str]| -> serde_json::Value {
        let mut cmd = crate::common::rattleback();
        cmd.args(["doctor", "--format", "json"]).args(args);
        for name in ["LC_ALL", "LC_CTYPE", "LANG", "TERM", "NO_COLOR", "CLICOLOR"] {
            cmd.env_remove(name);
        }
        cmd.envs(env.iter().copied());
        let out = cmd.output().unwrap();
        assert!(out.status.success());
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let d = run(&[("LANG", "C"), ("TERM", "xterm")], &[]);
    assert_eq!(d["chosen"]["characters"], "ascii");
    assert!(
        d["chosen"]["characters_because"]
            .as_str()
            .unwrap()
            .contains("LANG=C")
    );
    let d = run(&[("LANG", "C.UTF-8"), ("TERM", "linux")], &[]);
    assert_eq!(d["chosen"]["characters"], "console");
    let d = run(
        &[("LANG", "C.UTF-8"), ("TERM", "xterm-256color")],
        &["--ascii"],
    );
    assert_eq!(d["chosen"]["characters"], "ascii");
    let d = run(&[("LANG", "C.UTF-8"), ("TERM", "xterm-256color")], &[]);
    assert_eq!(d["chosen"]["characters"], "unicode");
    assert_eq!(d["chosen"]["colours"], true);
    let d = run(&[("NO_COLOR", "1")], &[]);
    assert_eq!(d["chosen"]["colours"], false);
    let d = run(&[("TERM", "dumb")], &[]);
    assert_eq!(d["chosen"]["explorer"], "refused: TERM=dumb");
    // An invalid config file is named, with its problem.
    let dir = std::env::temp_dir().join(format!("rattleback-doctor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("config.toml"), "fsp = 20\n").unwrap();
    let out = crate::common::rattleback()
        .args(["doctor"])
        .env("RATTLEBACK_CONFIG_DIR", &dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("invalid") && text.contains("fps"), "{text}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The weak-* pane, too, keeps one character per curve with one point per cell: `.` the
/// samples, `-` the dashed reference, `*` the average (`•` on the console).
#[test]
fn the_weak_star_curves_stay_apart_in_ascii() {
    let mut h = Headless::new("subcritical");
    h.key(Key::Char('W'));
    for (charset, average) in [(Charset::Ascii, '*'), (Charset::Console, '•')] {
        let screen = text(&render(&h.app, 120, 40, charset));
        let lines: Vec<&str> = screen.lines().collect();
        let top = lines
            .iter()
            .position(|l| l.contains("weak-*:"))
            .unwrap_or_else(|| panic!("no weak-* pane\n{screen}"));
        // The pane's rows, right of the panel, until its bottom border.
        let pane: String = lines[top + 1..]
            .iter()
            .take(10)
            .map(|l| l.chars().skip(40).collect::<String>())
            .collect();
        for m in ['.', '-', average] {
            assert!(
                pane.contains(m),
                "{charset:?}: no '{m}' in the weak-* pane\n{screen}"
            );
        }
    }
}

/// Under a locale that is not UTF-8 the headless text is ASCII, as the explorer's screen is:
/// tables, lists, messages, `--help`, the refusals (issue 54: `effective (k → ∞)`, `…`). The
/// JSON escapes what is not ASCII, so it parses to the same strings.
#[test]
fn headless_text_is_ascii_under_a_non_utf8_locale() {
    let session = "tests/fixtures/sessions/lecture.jsonl";
    let runs: &[&[&str]] = &[
        &["--help"],
        &["simulate", "--help"],
        &["study", "sweep", "--help"],
        &["simulate", "--format", "table"],
        &[
            "simulate",
            "--preset",
            "kapitza-upright",
            "--format",
            "table",
        ],
        &[
            "simulate",
            "--preset",
            "celt-clockwise",
            "--format",
            "table",
        ],
        &["simulate", "--format", "csv"],
        &["study", "sweep"],
        &["study", "map", "--grid", "8x4"],
        &["presets"],
        &["lessons"],
        &["themes"],
        &["doctor"],
        &["replay", session, "--verify"],
        &["replay", session, "--chapters"],
        &["simulate", "--preset", "nonesuch"],
        &["simulate", "--set", "spring.k=-1"],
        &[],
    ];
    for args in runs {
        for term in ["xterm", "dumb"] {
            let out = crate::common::rattleback()
                .args(*args)
                .current_dir(root!())
                .env("LANG", "C")
                .env("TERM", term)
                .output()
                .unwrap();
            for (what, bytes) in [("stdout", &out.stdout), ("stderr", &out.stderr)] {
                let text = String::from_utf8_lossy(bytes);
                assert!(
                    bytes.is_ascii(),
                    "LANG=C TERM={term} {args:?}: {what} is not ASCII:\n{text}"
                );
            }
        }
    }
    let out = crate::common::rattleback()
        .args(["simulate", "--format", "table"])
        .env("LANG", "C")
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stdout).contains("effective (k -> inf)"));
}
