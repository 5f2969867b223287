//! What the terminal can show: the full Unicode set, the Linux console's fonts, or ASCII; and
//! the last pass of every frame, which folds each cell into that set.
//!
//! The screen is drawn once, in Unicode; [`fold_buffer`] then replaces what the terminal cannot
//! show, cell by cell, so the layout never moves (every replacement is one column wide). Under
//! `LANG=C` (or `--ascii`) every cell is ASCII; on the Linux console (`TERM=linux`) every cell
//! is in [`CONSOLE`], the characters Debian's console fonts all have
//! (`tests/fixtures/console/glyphs.txt`, made by `scripts/console_fonts.py` from the fonts).
//! Both also draw the canvases one point per cell (no Braille, no half blocks), each curve of
//! the portrait with its own character.

use ratatui::buffer::Buffer;

/// The characters a terminal shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Charset {
    /// UTF-8 with a font that has Braille, block elements and the symbols used.
    #[default]
    Unicode,
    /// The Linux console: UTF-8, but only the glyphs of its fonts ([`CONSOLE`] and ASCII).
    Console,
    /// ASCII only (a non-UTF-8 locale, an old terminal, or `--ascii`).
    Ascii,
}

/// Non-ASCII characters every one of Debian's console fonts Lat15-Fixed16, Lat2-Terminus16,
/// Uni2-Fixed16 and Uni3-Terminus16 has, among those the screen uses (a test checks each against
/// the fonts' tables). Greek letters are not among them.
pub const CONSOLE: &str = "·•●✗▶›×…─│┌┐└┘├┤┬┴┼═║█░▒←→↑↓≈≤≥±°";

/// What decided the character set, for `rattleback doctor`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Detected {
    /// The set chosen.
    pub charset: Charset,
    /// Why, in a few words (`--ascii`, `LANG=C is not a UTF-8 locale`, `TERM=linux`, …).
    pub reason: String,
}

impl Charset {
    /// The set for this terminal: `--ascii` first; then a locale that is set and not UTF-8
    /// (`LC_ALL`, else `LC_CTYPE`, else `LANG`, the first non-empty, as POSIX orders them)
    /// gives ASCII; then `TERM=linux…` gives the console's set and `TERM=vt100`, `vt102`,
    /// `vt220` or `ansi` ASCII; else Unicode. No locale at all is taken as UTF-8 (containers
    /// and CI set none, and their terminals are the host's).
    #[must_use]
    pub fn detect(ascii: bool, var: &dyn Fn(&str) -> Option<String>) -> Detected {
        let found = |charset, reason: String| Detected { charset, reason };
        if ascii {
            return found(Self::Ascii, "--ascii".to_owned());
        }
        let (utf8, locale) = crate::scenario::text::locale(var);
        if let (false, Some((name, value))) = (utf8, &locale) {
            return found(Self::Ascii, format!("{name}={value} is not a UTF-8 locale"));
        }
        let term = var("TERM").unwrap_or_default();
        if term.starts_with("linux") {
            return found(
                Self::Console,
                format!("TERM={term}: the console's fonts have no Braille"),
            );
        }
        if ["vt52", "vt100", "vt102", "vt220", "ansi"].contains(&term.as_str()) {
            return found(Self::Ascii, format!("TERM={term}"));
        }
        let why = match locale {
            Some((name, value)) => format!("{name}={value}"),
            None => "no locale set: taken as UTF-8".to_owned(),
        };
        found(Self::Unicode, why)
    }

    /// The name `doctor` prints.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Unicode => "unicode",
            Self::Console => "console",
            Self::Ascii => "ascii",
        }
    }

    /// Whether this set shows `c` as it is.
    #[must_use]
    pub fn shows(self, c: char) -> bool {
        match self {
            Self::Unicode => true,
            Self::Console => c.is_ascii() || CONSOLE.contains(c),
            Self::Ascii => c.is_ascii(),
        }
    }

    /// `text` as this set shows it, spelled out where the layout allows more than one column
    /// (the legend, messages): what the set shows stays, the rest is spelled in ASCII
    /// (`k → ∞` is `k -> inf` in ASCII, `k → inf` on the console).
    #[must_use]
    pub fn spell(self, text: &str) -> String {
        if self == Self::Unicode {
            return text.to_owned();
        }
        let mut out = String::with_capacity(text.len());
        let mut chars = text.chars().peekable();
        while let Some(c) = chars.next() {
            // A letter and its combining mark are spelled together (`α̇` is `alpha_dot`).
            let combined = chars.peek().is_some_and(|m| is_combining(*m));
            if self.shows(c) && !combined {
                out.push(c);
            } else if is_combining(c) {
                out.push_str(&crate::scenario::text::ascii(&c.to_string()));
            } else {
                out.push_str(&crate::scenario::text::spell(c));
            }
        }
        out
    }

    /// One cell's mark as this set draws it (the fold of [`Self::fold`], or the mark itself).
    #[must_use]
    pub fn mark(self, c: char) -> char {
        let mut tmp = [0u8; 4];
        self.fold(c.encode_utf8(&mut tmp)).unwrap_or(c)
    }

    /// `symbol` (one cell's grapheme) as this set shows it: unchanged when it can, else one
    /// ASCII character of the same width (combining marks dropped; `?` for what has no
    /// likeness).
    #[must_use]
    pub fn fold(self, symbol: &str) -> Option<char> {
        if symbol.chars().all(|c| self.shows(c)) {
            return None;
        }
        let base = symbol.chars().find(|c| !is_combining(*c)).unwrap_or(' ');
        if self.shows(base) {
            return Some(base);
        }
        Some(likeness(base))
    }
}

fn is_combining(c: char) -> bool {
    matches!(c, '\u{0300}'..='\u{036f}' | '\u{20d0}'..='\u{20ff}')
}

/// Non-ASCII characters and their ASCII likeness.
const LIKENESS: &[(&str, char)] = &[
    ("─━═┄┈╌−–—⁻", '-'),
    ("▏", '_'),
    ("│┃║┆┊╎▌▐", '|'),
    ("┌┐└┘├┤┬┴┼╭╮╰╯╔╗╚╝╠╣╦╩╬✓✔±", '+'),
    ("›▶▸→⟶»≥", '>'),
    ("‹◀◂←«≤", '<'),
    ("↑▲", '^'),
    ("↓▼ν", 'v'),
    ("●◉", '@'),
    ("∘○°ο", 'o'),
    ("•∙⋅", '*'),
    ("·…", '.'),
    ("×✗✘ξχ", 'x'),
    ("≈∼∞", '~'),
    ("²", '2'),
    ("³", '3'),
    ("½", '/'),
    // The map's density ramp stays a ramp: `:` `=` `%` `#`.
    ("█", '#'),
    ("▓", '%'),
    ("▒", '='),
    ("░", ':'),
    ("▀▄", '='),
    ("√", 'V'),
    ("α", 'a'),
    ("β", 'b'),
    ("γΓ", 'g'),
    ("δΔ", 'd'),
    ("ε", 'e'),
    ("ζ", 'z'),
    ("η", 'h'),
    ("θΘτ", 't'),
    ("ι", 'i'),
    ("κ", 'k'),
    ("λ", 'l'),
    ("μ", 'u'),
    ("πΠ", 'p'),
    ("ρ", 'r'),
    ("σΣ", 's'),
    ("φΦ", 'f'),
    ("ψΨ", 'y'),
    ("ωΩ", 'w'),
];

/// The ASCII character closest to `c`: a Braille cell is `.`, what has no likeness `?`.
fn likeness(c: char) -> char {
    if let Some((_, a)) = LIKENESS.iter().find(|(from, _)| from.contains(c)) {
        return *a;
    }
    match c {
        '\u{2800}'..='\u{28ff}' => '.',
        c if c.is_whitespace() => ' ',
        _ => '?',
    }
}

/// Folds every cell of `buf` into `charset` (nothing to do for Unicode).
pub fn fold_buffer(buf: &mut Buffer, charset: Charset) {
    if charset == Charset::Unicode {
        return;
    }
    let mut tmp = [0u8; 4];
    for cell in &mut buf.content {
        if let Some(c) = charset.fold(cell.symbol()) {
            cell.set_symbol(c.encode_utf8(&mut tmp));
        }
    }
}

/// A canvas over `x` × `y` in the theme's background, drawn with the terminal's marker (the
/// body panes': the rattleback's and the celt's in `body.rs`, the pendulum's in `pendulum.rs`).
pub(super) fn canvas<'a, F: Fn(&mut ratatui::widgets::canvas::Context<'_>)>(
    look: &super::Look,
    x: [f64; 2],
    y: [f64; 2],
    paint: F,
) -> ratatui::widgets::canvas::Canvas<'a, F> {
    ratatui::widgets::canvas::Canvas::default()
        .marker(look.marker)
        .background_color(look.theme.background)
        .x_bounds(x)
        .y_bounds(y)
        .paint(paint)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            pairs
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, v)| (*v).to_owned())
        }
    }

    #[test]
    fn the_locale_then_the_terminal_decide() {
        type Env<'a> = &'a [(&'a str, &'a str)];
        let cases: &[(Env, bool, Charset)] = &[
            (&[("LANG", "C"), ("TERM", "xterm")], false, Charset::Ascii),
            (&[("LANG", "POSIX")], false, Charset::Ascii),
            (&[("LANG", "en_GB.ISO-8859-1")], false, Charset::Ascii),
            (
                &[("LANG", "C.UTF-8"), ("TERM", "xterm")],
                false,
                Charset::Unicode,
            ),
            (&[("LANG", "en_US.utf8")], false, Charset::Unicode),
            // LC_ALL wins over LANG, LC_CTYPE too; empty ones are skipped.
            (
                &[("LC_ALL", "C"), ("LANG", "C.UTF-8")],
                false,
                Charset::Ascii,
            ),
            (
                &[("LC_CTYPE", "C.UTF-8"), ("LANG", "C")],
                false,
                Charset::Unicode,
            ),
            (&[("LC_ALL", ""), ("LANG", "C")], false, Charset::Ascii),
            (
                &[("LANG", "C.UTF-8"), ("TERM", "linux")],
                false,
                Charset::Console,
            ),
            (&[("TERM", "linux-16color")], false, Charset::Console),
            (&[("LANG", "C"), ("TERM", "linux")], false, Charset::Ascii),
            (&[("TERM", "vt100")], false, Charset::Ascii),
            (&[("TERM", "xterm-256color")], false, Charset::Unicode),
            (&[], false, Charset::Unicode),
            (&[("LANG", "C.UTF-8")], true, Charset::Ascii),
        ];
        for (pairs, ascii, want) in cases {
            let got = Charset::detect(*ascii, &env(pairs));
            assert_eq!(
                got.charset, *want,
                "{pairs:?} ascii={ascii}: {}",
                got.reason
            );
        }
    }

    #[test]
    fn a_fold_keeps_one_column_and_what_the_set_shows() {
        assert_eq!(Charset::Ascii.fold("a"), None);
        assert_eq!(Charset::Ascii.fold("α̇"), Some('a'));
        assert_eq!(Charset::Ascii.fold("─"), Some('-'));
        assert_eq!(Charset::Ascii.fold("⣿"), Some('.'));
        assert_eq!(Charset::Ascii.fold("漢"), Some('?'));
        assert_eq!(Charset::Console.fold("─"), None);
        assert_eq!(Charset::Console.fold("∘"), Some('o'));
        assert_eq!(Charset::Console.fold("Δ"), Some('d'));
        assert_eq!(Charset::Unicode.fold("∘"), None);
        for (from, to) in LIKENESS {
            assert!(
                to.is_ascii() && from.chars().all(|c| !c.is_ascii()),
                "{from}"
            );
        }
        for c in CONSOLE.chars() {
            assert!(!c.is_ascii());
            assert!(likeness(c).is_ascii() && likeness(c) != '?', "{c}");
        }
    }

    #[test]
    fn spelling_keeps_what_the_set_shows_and_spells_the_rest() {
        assert_eq!(
            Charset::Ascii.spell("k → ∞, ≥ 8, α̇"),
            "k -> inf, >= 8, alpha_dot"
        );
        assert_eq!(
            Charset::Console.spell("k → ∞, ≥ 8, α̇"),
            "k → inf, ≥ 8, alpha_dot"
        );
        assert_eq!(Charset::Unicode.spell("k → ∞"), "k → ∞");
        assert_eq!(Charset::Ascii.mark('•'), '*');
        assert_eq!(Charset::Console.mark('•'), '•');
        assert_eq!(Charset::Ascii.mark('x'), 'x');
    }
}
