//! Headless text that fits the terminal (issue 81, newcomer.md D-7): when standard output is a
//! terminal, a report or a list is wrapped at its width, between words and numbers (never
//! inside one), each continuation indented under the line's first value, as clap wraps help.
//! Piped, the text is unchanged, byte for byte: scripts read it.

use unicode_width::UnicodeWidthStr as _;

/// `text` with every line wider than `width` columns broken between words, continuations
/// indented to the line's value column (see [`hanging_indent`]). A word wider than what is left
/// stands alone on its line; nothing is ever cut.
#[must_use]
pub fn fit(text: &str, width: usize) -> String {
    let mut out = String::with_capacity(text.len() + text.len() / 16);
    for (i, line) in text.split('\n').enumerate() {
        if i > 0 {
            out.push('\n');
        }
        if line.width() <= width {
            out.push_str(line);
            continue;
        }
        let indent = hanging_indent(line, width);
        let mut column = 0;
        for (n, (lead, word)) in words(line).into_iter().enumerate() {
            let (lead_w, word_w) = (lead.width(), word.width());
            if n > 0 && column + lead_w + word_w > width {
                out.push('\n');
                out.push_str(&" ".repeat(indent));
                column = indent;
            } else {
                out.push_str(lead);
                column += lead_w;
            }
            out.push_str(word);
            column += word_w;
        }
    }
    out
}

/// The column a line's continuations start at: after its label (the first run of two or more
/// spaces after some text: `full at      2.21, 6.64` continues under `2.21`), else its own
/// indentation (a paragraph); at most half the width, so a continuation has room.
#[must_use]
pub fn hanging_indent(line: &str, width: usize) -> usize {
    let lead = line.len() - line.trim_start().len();
    let body = &line[lead..];
    let mut gap = None;
    let bytes = body.as_bytes();
    let mut i = 0;
    while i + 1 < bytes.len() {
        if bytes[i] == b' ' && bytes[i + 1] == b' ' {
            let mut j = i;
            while j < bytes.len() && bytes[j] == b' ' {
                j += 1;
            }
            if j < bytes.len() {
                gap = Some(line[..lead + j].width());
            }
            break;
        }
        i += 1;
    }
    gap.unwrap_or(line[..lead].width()).min(width / 2)
}

/// The words of a line, each with the spaces before it (the first with the line's indentation).
fn words(line: &str) -> Vec<(&str, &str)> {
    let mut out = Vec::new();
    let mut rest = line;
    while !rest.is_empty() {
        let trimmed = rest.trim_start_matches(' ');
        let lead = &rest[..rest.len() - trimmed.len()];
        if trimmed.is_empty() {
            break;
        }
        let end = trimmed.find(' ').unwrap_or(trimmed.len());
        out.push((lead, &trimmed[..end]));
        rest = &trimmed[end..];
    }
    out
}

/// The terminal's width when standard output is one (`None` when piped or unknown): what
/// [`print`] wraps at. `COLUMNS` is read first, as clap reads it.
#[must_use]
pub fn terminal_width() -> Option<usize> {
    use std::io::IsTerminal as _;
    if !std::io::stdout().is_terminal() {
        return None;
    }
    if let Some(w) = std::env::var("COLUMNS")
        .ok()
        .and_then(|c| c.trim().parse::<usize>().ok())
        .filter(|&w| w > 0)
    {
        return Some(w);
    }
    ratatui::crossterm::terminal::size()
        .ok()
        .map(|(w, _)| usize::from(w))
        .filter(|&w| w > 0)
}

/// `text` as it is printed on standard output: fitted to the terminal when it is one, else
/// unchanged.
#[must_use]
pub fn for_stdout(text: &str) -> String {
    match terminal_width() {
        Some(w) => fit(text, w.max(20)),
        None => text.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_list_of_numbers_breaks_between_numbers_under_its_first_value() {
        let line = "  full at      2.216604, 6.649819, 11.083057, 15.516338, 19.949686, 24.383138, 28.816757";
        let got = fit(line, 80);
        for l in got.lines() {
            assert!(l.width() <= 80, "{l}");
        }
        assert_eq!(
            got,
            "  full at      2.216604, 6.649819, 11.083057, 15.516338, 19.949686, 24.383138,\n               28.816757"
        );
        // Every number whole.
        let numbers: Vec<&str> = got
            .split([' ', ',', '\n'])
            .filter(|w| !w.is_empty())
            .collect();
        assert!(numbers.contains(&"28.816757"));
    }

    #[test]
    fn words_break_between_words_and_short_lines_are_untouched() {
        let text = "short line\n                 Within a second of the critical ratio, auto takes care near the separatrix: a slow run";
        let got = fit(text, 60);
        assert!(got.starts_with("short line\n"));
        for l in got.lines() {
            assert!(l.width() <= 60, "{l}");
        }
        assert!(
            got.contains("\n                 W") || got.contains("\n                 "),
            "{got}"
        );
        assert!(!got.contains("Wit\n") && got.contains("Within"), "{got}");
        // Piped text (no width) is what fit leaves when nothing is too long.
        assert_eq!(fit("a  b\nc", 80), "a  b\nc");
    }

    #[test]
    fn a_word_longer_than_the_line_stands_alone() {
        let got = fit("x  short long-long-long-long-long", 12);
        assert_eq!(got, "x  short\n   long-long-long-long-long");
    }
}
