//! Untrusted text (preset names and descriptions, notes, values echoed in errors) made safe for
//! a terminal: control characters, escape sequences included, never reach it.

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
            // Bidirectional overrides can make a line read backwards.
            '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' => {}
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
    let mut out = String::with_capacity(json.len());
    for c in json.chars() {
        match c {
            '\u{7f}'..='\u{9f}'
            | '\u{200e}'
            | '\u{200f}'
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
        assert_eq!(clean("spin α̇ ≥ 0 ✓"), "spin α̇ ≥ 0 ✓");
    }
}

/// The candidate closest to `word` when one is close enough to be a typo, for "did you mean"
/// hints: one edit away (Damerau–Levenshtein, so `fsp` finds `fps`) or similar by Jaro–Winkler
/// (≥ 0.8, so `tolerence` finds `tolerance`); case ignored.
#[must_use]
pub fn closest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
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
        assert_eq!(
            did_you_mean("subcritcal", ["subcritical", "supercritical"]),
            "; did you mean `subcritical`?"
        );
    }
}
