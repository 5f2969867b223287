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
