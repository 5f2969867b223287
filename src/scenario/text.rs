//! Untrusted text (preset names and descriptions, notes, values echoed in errors) made safe for
//! a terminal: control characters, escape sequences included, never reach it.

/// `text` [`clean`] on one line: newlines, tabs and line separators become spaces (a name in a
/// table's field, a CSV comment, a chapter list, a cast's title).
#[must_use]
pub fn one_line(text: &str) -> String {
    clean(text).replace(['\n', '\r', '\t'], " ")
}

/// `text` with what [`clean`] would remove or fold shown as a visible escape (`\u{1b}`,
/// `\n`): for a name that has such characters, so that a listing says what is there.
#[must_use]
pub fn visible(text: &str) -> String {
    text.chars()
        .map(|c| {
            if plain(c) {
                c.to_string()
            } else {
                c.escape_unicode().to_string()
            }
        })
        .collect()
}

/// Whether a name can be shown and typed as it is: no control, bidirectional, zero-width or
/// separator character (a preset file named `x<ESC>]0;…<BEL>.toml` or `a<LF>b.toml` is not).
#[must_use]
pub fn is_plain(name: &str) -> bool {
    name.chars().all(plain)
}

fn plain(c: char) -> bool {
    !(c.is_control() || invisible(c) || matches!(c, '\u{2028}' | '\u{2029}'))
}

/// Bidirectional overrides, isolates and marks (they can make a line read backwards) and
/// zero-width characters (they hide what is there).
fn invisible(c: char) -> bool {
    matches!(
        c,
        '\u{202a}'..='\u{202e}'
            | '\u{2066}'..='\u{2069}'
            | '\u{200b}'..='\u{200f}'
            | '\u{061c}'
            | '\u{feff}'
    )
}

/// `text` with every control character removed but newlines and tabs (callers that lay text
/// out on one line fold those). An ESC starts a sequence that is dropped whole (CSI, OSC, DCS).
#[must_use]
pub fn clean(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\u{1b}' => skip_sequence(&mut chars),
            '\n' | '\t' => out.push(c),
            c if c.is_control() => {}
            // Line and paragraph separators break a line as a newline does.
            '\u{2028}' | '\u{2029}' => out.push('\n'),
            c if invisible(c) => {}
            c => out.push(c),
        }
    }
    out
}

/// Serialized JSON made safe for a terminal: the characters JSON leaves raw inside strings but
/// a terminal acts on (C1 controls such as the 8-bit CSI U+009B and OSC U+009D, DEL, bidirectional
/// overrides and isolates, line and paragraph separators) are written as `\uXXXX` escapes, so
/// a parser reads the same strings and a terminal shows no control. Only valid on JSON text
/// (these characters can stand only inside strings there).
#[must_use]
pub fn json_safe(json: &str) -> String {
    use std::fmt::Write as _;
    if ascii_output() {
        // Under a locale that is not UTF-8, every non-ASCII character is escaped.
        return json_ascii(json);
    }
    let mut out = String::with_capacity(json.len());
    for c in json.chars() {
        match c {
            '\u{7f}'..='\u{9f}'
            | '\u{200b}'..='\u{200f}'
            | '\u{feff}'
            | '\u{061c}'
            | '\u{2028}'
            | '\u{2029}'
            | '\u{202a}'..='\u{202e}'
            | '\u{2066}'..='\u{2069}' => {
                let _ = write!(out, "\\u{:04x}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out
}

/// Non-ASCII characters the program writes and how they are spelled in ASCII, for a locale
/// that is not UTF-8 (`LANG=C`): headless text (tables, messages, `--help`) and the explorer's
/// legend read `k -> inf`, `>= 8`, `alpha_dot` there instead of `?` or a lookalike.
const SPELLING: &[(char, &str)] = &[
    ('→', "->"),
    ('←', "<-"),
    ('↑', "^"),
    ('↓', "v"),
    ('⇒', "=>"),
    ('≥', ">="),
    ('≤', "<="),
    ('≠', "!="),
    ('≈', "~"),
    ('∼', "~"),
    ('∞', "inf"),
    ('…', "..."),
    ('·', "."),
    ('•', "*"),
    ('∙', "*"),
    ('×', "x"),
    ('−', "-"),
    ('–', "-"),
    ('—', "--"),
    ('±', "+/-"),
    ('°', " deg"),
    ('²', "^2"),
    ('³', "^3"),
    ('½', "1/2"),
    ('√', "sqrt"),
    ('∘', "o"),
    ('○', "o"),
    ('●', "@"),
    ('▶', ">"),
    ('✓', "ok"),
    ('✔', "ok"),
    ('✗', "x"),
    ('│', "|"),
    ('┃', "|"),
    ('─', "-"),
    ('━', "-"),
    ('▏', "_"),
    ('‘', "'"),
    ('’', "'"),
    ('“', "\""),
    ('”', "\""),
    ('\u{a0}', " "),
    ('α', "alpha"),
    ('β', "beta"),
    ('γ', "gamma"),
    ('Γ', "Gamma"),
    ('δ', "delta"),
    ('Δ', "d"),
    ('ε', "eps"),
    ('ζ', "zeta"),
    ('η', "eta"),
    ('θ', "theta"),
    ('Θ', "Theta"),
    ('κ', "kappa"),
    ('λ', "lambda"),
    ('μ', "mu"),
    ('ν', "nu"),
    ('ξ', "xi"),
    ('π', "pi"),
    ('ρ', "rho"),
    ('σ', "sigma"),
    ('τ', "tau"),
    ('φ', "phi"),
    ('χ', "chi"),
    ('ψ', "psi"),
    ('ω', "omega"),
    ('Ω', "Omega"),
];

/// How `c` is spelled in ASCII: itself when it is ASCII, else `SPELLING`'s words, else `?`.
#[must_use]
pub fn spell(c: char) -> std::borrow::Cow<'static, str> {
    if c.is_ascii() {
        return std::borrow::Cow::Owned(c.to_string());
    }
    match SPELLING.iter().find(|(from, _)| *from == c) {
        Some((_, to)) => std::borrow::Cow::Borrowed(to),
        None if ('\u{2800}'..='\u{28ff}').contains(&c) => std::borrow::Cow::Borrowed("."),
        None => std::borrow::Cow::Borrowed("?"),
    }
}

/// `text` spelled in ASCII (`SPELLING`): `k → ∞` is `k -> inf`, `≥ 8` is `>= 8`; a combining
/// dot above is `_dot` after its letter (`α̇` is `alpha_dot`), two dots `_ddot`; other
/// combining marks are dropped; what has no spelling is `?`.
#[must_use]
pub fn ascii(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '\u{307}' => out.push_str("_dot"),
            '\u{308}' => out.push_str("_ddot"),
            '\u{300}'..='\u{36f}' | '\u{20d0}'..='\u{20ff}' => {}
            c => out.push_str(&spell(c)),
        }
    }
    out
}

/// Serialized JSON in ASCII: every non-ASCII character as a `\uXXXX` escape (a surrogate pair
/// above the basic plane), so a parser reads the same strings. Only valid on JSON text.
#[must_use]
pub fn json_ascii(json: &str) -> String {
    use std::fmt::Write as _;
    let mut out = String::with_capacity(json.len());
    for c in json.chars() {
        if c.is_ascii() {
            out.push(c);
        } else {
            let mut units = [0u16; 2];
            for unit in c.encode_utf16(&mut units) {
                let _ = write!(out, "\\u{unit:04x}");
            }
        }
    }
    out
}

/// Whether a locale (`LC_ALL`, else `LC_CTYPE`, else `LANG`: the first one set and not empty,
/// as POSIX orders them) is UTF-8; no locale at all is taken as UTF-8 (containers and CI set
/// none, and their terminals are the host's). `var` reads the environment. Returns the variable
/// that decided, when one did.
#[must_use]
pub fn locale(var: &dyn Fn(&str) -> Option<String>) -> (bool, Option<(&'static str, String)>) {
    let found = ["LC_ALL", "LC_CTYPE", "LANG"]
        .into_iter()
        .find_map(|name| var(name).filter(|v| !v.is_empty()).map(|v| (name, v)));
    let utf8 = found.as_ref().is_none_or(|(_, value)| {
        let v = value.to_ascii_lowercase();
        v.contains("utf-8") || v.contains("utf8")
    });
    (utf8, found)
}

/// Whether this process writes its text in ASCII: decided once from the locale, by `main`.
static ASCII_OUTPUT: std::sync::OnceLock<bool> = std::sync::OnceLock::new();

/// Decides, once, that this process's text output is ASCII (a locale that is not UTF-8).
pub fn set_ascii_output(ascii: bool) {
    let _ = ASCII_OUTPUT.set(ascii);
}

/// Whether text output is ASCII ([`set_ascii_output`]; UTF-8 when nothing was decided).
#[must_use]
pub fn ascii_output() -> bool {
    ASCII_OUTPUT.get().copied().unwrap_or(false)
}

/// Text as this process writes it to a terminal or a file: control characters stripped
/// ([`clean`]), then spelled in ASCII under a locale that is not UTF-8 ([`ascii`]).
#[must_use]
pub fn shown(text: &str) -> String {
    let text = clean(text);
    if ascii_output() { ascii(&text) } else { text }
}

fn skip_sequence(chars: &mut std::iter::Peekable<std::str::Chars<'_>>) {
    match chars.peek() {
        Some('[') => {
            chars.next();
            // CSI: parameters and intermediates, then one final byte in @..~.
            for c in chars.by_ref() {
                if ('@'..='~').contains(&c) {
                    break;
                }
            }
        }
        Some(']' | 'P' | '_' | '^') => {
            chars.next();
            // OSC / DCS / APC / PM: up to BEL or ST (ESC \).
            while let Some(c) = chars.next() {
                if c == '\u{7}' {
                    break;
                }
                if c == '\u{1b}' {
                    if chars.peek() == Some(&'\\') {
                        chars.next();
                    }
                    break;
                }
            }
        }
        Some(_) => {
            chars.next();
        }
        None => {}
    }
}

/// The 1-based line of byte offset `at` in `bytes` (for errors found in raw bytes, such as
/// invalid UTF-8).
#[must_use]
pub fn line_at(bytes: &[u8], at: usize) -> usize {
    bytes[..at.min(bytes.len())].split(|&b| b == b'\n').count()
}

#[cfg(test)]
mod tests {
    use super::clean;

    #[test]
    fn escape_sequences_and_controls_are_dropped() {
        assert_eq!(clean("a\u{1b}]0;pwned\u{7}b"), "ab");
        assert_eq!(clean("a\u{1b}[2Jb\u{1b}[31mc"), "abc");
        assert_eq!(clean("x\u{1b}]52;c;aGk=\u{1b}\\y"), "xy");
        assert_eq!(clean("tab\there\r\u{8}\u{0}"), "tab\there");
        assert_eq!(clean("line\nnext"), "line\nnext");
        assert_eq!(
            clean("a\u{200f}b\u{200e}c\u{61c}d\u{200b}e\u{feff}f"),
            "abcdef"
        );
        assert_eq!(clean("a\u{2028}b\u{2029}c"), "a\nb\nc");
        assert_eq!(clean("spin α̇ ≥ 0 ✓"), "spin α̇ ≥ 0 ✓");
    }

    #[test]
    fn ascii_spells_what_the_program_writes() {
        use super::{ascii, json_ascii};
        assert_eq!(ascii("effective (k → ∞)"), "effective (k -> inf)");
        assert_eq!(
            ascii("α̇0²/γ̇0² ≥ 8 … ΔE/E ✓"),
            "alpha_dot0^2/gamma_dot0^2 >= 8 ... dE/E ok"
        );
        assert_eq!(ascii("θ̈ ε → 0"), "theta_ddot eps -> 0");
        assert_eq!(ascii("漢"), "?");
        assert!(ascii("δ° ∘ ● ▶ × − ± ½ √ · •").is_ascii());
        for (c, s) in super::SPELLING {
            assert!(!c.is_ascii() && s.is_ascii() && !s.is_empty(), "{c}");
        }
        assert_eq!(
            json_ascii("{\"n\":\"é→𝔸\"}"),
            "{\"n\":\"\\u00e9\\u2192\\ud835\\udd38\"}"
        );
        let back: serde_json::Value = serde_json::from_str(&json_ascii("{\"n\":\"é→𝔸\"}")).unwrap();
        assert_eq!(back["n"], "é→𝔸");
    }
}

/// The candidate closest to `word` when one is close enough to be a typo, for "did you mean"
/// hints: one edit away (Damerau–Levenshtein, so `fsp` finds `fps`) or similar by Jaro–Winkler
/// (≥ 0.8, so `tolerence` finds `tolerance`); case ignored.
#[must_use]
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let candidates: Vec<&'a str> = candidates.into_iter().collect();
    // A dotted key whose last part is exactly a candidate's (`celt.omega_z` for
    // `initial.omega_z`): the section was mistaken, not the name (issue 81, L7: it suggested
    // `celt.a`).
    if let Some((_, tail)) = word.rsplit_once('.') {
        let same_tail: Vec<&str> = candidates
            .iter()
            .copied()
            .filter(|c| {
                c.rsplit_once('.')
                    .is_some_and(|(_, t)| t.eq_ignore_ascii_case(tail))
            })
            .collect();
        if let [only] = same_tail[..] {
            return Some(only);
        }
    }
    let word = word.to_lowercase();
    candidates
        .into_iter()
        .map(|c| {
            let c_low = c.to_lowercase();
            let edits = strsim::damerau_levenshtein(&word, &c_low);
            (edits, strsim::jaro_winkler(&word, &c_low), c)
        })
        .filter(|(edits, jw, _)| (*edits <= 1 && word.len() >= 2) || *jw >= 0.8)
        .min_by(|a, b| a.0.cmp(&b.0).then(b.1.total_cmp(&a.1)))
        .map(|(_, _, c)| c)
}

/// `"; did you mean `x`?"` when a candidate is close to `word`, else nothing.
#[must_use]
pub fn did_you_mean<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    closest(word, candidates).map_or_else(String::new, |c| format!("; did you mean `{c}`?"))
}

#[cfg(test)]
mod suggestion_tests {
    use super::*;

    #[test]
    fn typos_get_the_closest_name_and_nonsense_gets_none() {
        let keys = ["ix", "iy", "iz", "k", "t_end", "method", "tolerance"];
        assert_eq!(closest("tolerence", keys), Some("tolerance"));
        assert_eq!(closest("Methd", keys), Some("method"));
        assert_eq!(closest("t-end", keys), Some("t_end"));
        assert_eq!(closest("banana", keys), None);
        assert_eq!(closest("fsp", ["fps", "preset", "theme"]), Some("fps"));
        assert_eq!(
            closest("x", ["ix", "iy"]),
            None,
            "one letter suggests nothing"
        );
        assert_eq!(did_you_mean("banana", keys), "");
        // A mistaken section, the name right (issue 81, L7).
        assert_eq!(
            closest(
                "celt.omega_z",
                ["celt.a", "celt.b", "initial.omega_x", "initial.omega_z"]
            ),
            Some("initial.omega_z")
        );
        assert_eq!(
            did_you_mean("subcritcal", ["subcritical", "supercritical"]),
            "; did you mean `subcritical`?"
        );
    }
}

/// Prints [`shown`] text on standard error. A failed write is ignored (`eprintln!` would panic):
/// standard error may be a terminal that hung up, and the exit status still says what happened.
pub fn warn_raw(text: &str) {
    use std::io::Write as _;
    let _ = std::io::stderr().lock().write_all(shown(text).as_bytes());
}

/// [`warn_raw`] of one line.
pub fn warn(text: &str) {
    warn_raw(&format!("{text}\n"));
}

/// The most error lines a command says.
pub const MAX_LINES: usize = 30;
/// The most characters of one error line (an echoed list of 200,000 numbers is cut).
pub const MAX_LINE: usize = 400;

/// Problems as said anywhere (an error, `doctor`): at most [`MAX_LINES`], each cut to
/// [`MAX_LINE`] characters, and a count of the rest.
#[must_use]
pub fn bounded<L: AsRef<str>>(lines: &[L]) -> Vec<String> {
    let mut out: Vec<String> = lines
        .iter()
        .take(MAX_LINES)
        .map(|l| cut(l.as_ref(), MAX_LINE))
        .collect();
    let rest = lines.len().saturating_sub(MAX_LINES);
    if rest > 0 {
        out.push(format!(
            "… and {rest} more problem(s) (fix the first ones: the rest are often the same mistake)"
        ));
    }
    out
}

/// `line` cut to `max` characters, saying how much was left out: its head and its tail are
/// kept (an error's end says what to do: `did you mean …?`).
#[must_use]
pub fn cut(line: &str, max: usize) -> String {
    let n = line.chars().count();
    if n <= max {
        return line.to_owned();
    }
    let chars: Vec<char> = line.chars().collect();
    let tail = max / 4;
    let mut head = max - tail;
    let mut from = n - tail;
    // At word boundaries, so no name in a list is cut in two (`celt-anti … …`).
    let gap = |c: char| c.is_whitespace() || c == ',';
    if let Some(i) = (head / 2..head).rev().find(|&i| gap(chars[i])) {
        head = i;
    }
    if let Some(i) = (from..n - tail / 2).find(|&i| gap(chars[i])) {
        from = i + 1;
    }
    let first: String = chars[..head].iter().collect();
    let last: String = chars[from..].iter().collect();
    format!(
        "{} … ({} characters cut) … {}",
        first.trim_end_matches([',', ' ']),
        from - head,
        last.trim_start()
    )
}

/// `word` in at most `max` characters (at least 12): its head and its longer tail kept around
/// a `…`, so a path keeps its file's name.
#[must_use]
pub fn middle(word: &str, max: usize) -> String {
    let chars: Vec<char> = word.chars().collect();
    let max = max.max(12);
    if chars.len() <= max {
        return word.to_owned();
    }
    let head = (max - 1) / 3;
    let tail = max - 1 - head;
    let first: String = chars[..head].iter().collect();
    let last: String = chars[chars.len() - tail..].iter().collect();
    format!("{first}…{last}")
}

/// A compact number: up to 6 significant digits, no trailing zeros.
#[must_use]
pub fn format_number(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e6) {
        return format!("{v:.4e}");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// `word` as the shell reads it back: as is when it holds only letters, digits and `-_./=:,@+`,
/// else in single quotes (a quote inside written `'\''`).
#[must_use]
pub fn shell_word(word: &str) -> String {
    if !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,@+".contains(c))
    {
        word.to_owned()
    } else {
        format!("'{}'", word.replace('\'', "'\\''"))
    }
}
