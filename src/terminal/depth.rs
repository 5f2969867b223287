//! How many colours the terminal shows, and each frame's colour codes rewritten to fit.
//!
//! Crossterm writes every colour as a 256-colour code (`ESC[38;5;8m` for dark grey), and a
//! theme may ask for `#rrggbb`. A terminal whose terminfo entry says 8 colours (`linux`,
//! `screen`, `xterm`) or none (`vt100`, `vt220`) either shows them wrong or reads the
//! parameters one by one (the `5` of `38;5;8` is blink there). So the depth is read from
//! terminfo (`colors`, through `termini`), `COLORTERM=truecolor` adds 24-bit colour, and
//! [`fit`] rewrites each frame's Select Graphic Rendition codes: to `30–37` for 8 colours,
//! `90–97` for the bright half of 16, the nearest of the 256 for 24-bit colour on a 256-colour
//! terminal. A terminal with no colours at all gets none (the explorer then draws as under
//! `NO_COLOR`: shapes, bold and reverse video tell the curves apart).

/// The colours a terminal shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Depth {
    /// None (`vt100`, `vt220`: terminfo has no `colors`).
    None,
    /// The eight ANSI colours (`linux`, `screen`, `xterm`, `ansi`).
    Eight,
    /// Sixteen: the eight and their bright half.
    Sixteen,
    /// The 256-colour palette (`xterm-256color`, `tmux-256color`).
    Indexed,
    /// 24-bit colour (`COLORTERM=truecolor` or `24bit`, or a terminfo entry of 2^24 colours).
    Rgb,
}

/// What decided the depth, for `rattleback doctor`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Detected {
    /// The depth.
    pub depth: Depth,
    /// Why, in a few words.
    pub reason: String,
}

impl Depth {
    /// The name `doctor` prints.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Eight => "8",
            Self::Sixteen => "16",
            Self::Indexed => "256",
            Self::Rgb => "24-bit",
        }
    }

    /// The depth of a terminfo entry's `colors` (absent: none).
    #[must_use]
    pub fn of_count(colors: Option<i32>) -> Self {
        match colors.unwrap_or(-1) {
            n if n >= 1 << 24 => Self::Rgb,
            n if n >= 256 => Self::Indexed,
            n if n >= 16 => Self::Sixteen,
            n if n >= 8 => Self::Eight,
            _ => Self::None,
        }
    }

    /// The depth of this terminal: `COLORTERM` first (`truecolor` or `24bit`), then the
    /// terminfo entry of `TERM` (`lookup` reads its `colors`, `Err` when there is no entry), then,
    /// with no entry, the name: `…256color` 256, the monochrome VTs none, anything else 16 (the
    /// default theme's palette).
    #[must_use]
    pub fn detect(
        var: &dyn Fn(&str) -> Option<String>,
        lookup: &dyn Fn(&str) -> Result<Option<i32>, NoTerminfo>,
    ) -> Detected {
        let found = |depth, reason: String| Detected { depth, reason };
        let term = var("TERM").unwrap_or_default();
        if let Some(c) = var("COLORTERM").filter(|c| c == "truecolor" || c == "24bit") {
            return found(Self::Rgb, format!("COLORTERM={c}"));
        }
        match lookup(&term) {
            Ok(colors) => {
                let depth = Self::of_count(colors);
                let count =
                    colors.map_or_else(|| "no colors".to_owned(), |n| format!("colors#{n}"));
                found(depth, format!("terminfo {term}: {count}"))
            }
            Err(why) => {
                let depth = if term.contains("256color") {
                    Self::Indexed
                } else if ["vt52", "vt100", "vt102", "vt220", "dumb"].contains(&term.as_str()) {
                    Self::None
                } else {
                    Self::Sixteen
                };
                found(depth, format!("TERM={term} ({why}): by its name"))
            }
        }
    }
}

/// The colour count of `term`'s terminfo entry (`Err` when no entry is found).
///
/// # Errors
/// No entry for `term` in the terminfo database.
pub fn terminfo_colors(term: &str) -> Result<Option<i32>, NoTerminfo> {
    termini::TermInfo::from_name(term)
        .map(|t| t.number_cap(termini::NumberCapability::MaxColors))
        .map_err(|_| NoTerminfo)
}

/// No entry for a terminal in the terminfo database.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("no terminfo entry")]
pub struct NoTerminfo;

/// The 16 ANSI colours as xterm draws them, for the nearest match.
const ANSI16: [(u8, u8, u8); 16] = [
    (0, 0, 0),
    (205, 0, 0),
    (0, 205, 0),
    (205, 205, 0),
    (0, 0, 238),
    (205, 0, 205),
    (0, 205, 205),
    (229, 229, 229),
    (127, 127, 127),
    (255, 0, 0),
    (0, 255, 0),
    (255, 255, 0),
    (92, 92, 255),
    (255, 0, 255),
    (0, 255, 255),
    (255, 255, 255),
];

/// The RGB of a 256-palette index (xterm's palette).
fn rgb_of(index: u8) -> (u8, u8, u8) {
    const LEVELS: [u8; 6] = [0, 95, 135, 175, 215, 255];
    match index {
        0..=15 => ANSI16[index as usize],
        16..=231 => {
            let i = index - 16;
            (
                LEVELS[(i / 36) as usize],
                LEVELS[(i / 6 % 6) as usize],
                LEVELS[(i % 6) as usize],
            )
        }
        _ => {
            let v = 8 + 10 * (index - 232);
            (v, v, v)
        }
    }
}

fn distance(a: (u8, u8, u8), b: (u8, u8, u8)) -> u32 {
    let d = |x: u8, y: u8| u32::from(x.abs_diff(y)).pow(2);
    d(a.0, b.0) + d(a.1, b.1) + d(a.2, b.2)
}

/// The index among `candidates` nearest to `rgb`.
fn nearest(rgb: (u8, u8, u8), candidates: impl Iterator<Item = u8>) -> u8 {
    candidates
        .min_by_key(|&i| distance(rgb_of(i), rgb))
        .unwrap_or(0)
}

/// A colour as an SGR code asks for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Asked {
    Index(u8),
    Rgb(u8, u8, u8),
}

/// The parameters that set a foreground (`ground` 30) or background (40) colour at `depth`;
/// empty for none.
fn colour_params(asked: Asked, ground: u16, depth: Depth) -> Vec<String> {
    let extended = ground + 8;
    match (depth, asked) {
        (Depth::None, _) => Vec::new(),
        (Depth::Rgb, Asked::Rgb(r, g, b)) => {
            vec![format!("{extended};2;{r};{g};{b}")]
        }
        (Depth::Rgb | Depth::Indexed, Asked::Index(i)) => vec![format!("{extended};5;{i}")],
        (Depth::Indexed, Asked::Rgb(r, g, b)) => {
            vec![format!("{extended};5;{}", nearest((r, g, b), 16..=255))]
        }
        (Depth::Sixteen | Depth::Eight, asked) => {
            let index = match asked {
                Asked::Index(i) if i < 16 => i,
                Asked::Index(i) => nearest(rgb_of(i), 0..16),
                Asked::Rgb(r, g, b) => nearest((r, g, b), 0..16),
            };
            let code = match (depth, index) {
                (_, 0..=7) => ground + u16::from(index),
                (Depth::Sixteen, _) => ground + 60 + u16::from(index - 8),
                // Eight colours: the bright half folds onto its base (dark grey reads as grey,
                // not as black on a black screen).
                (_, 8) => ground + 7,
                _ => ground + u16::from(index - 8),
            };
            vec![code.to_string()]
        }
    }
}

/// One SGR code's parameters rewritten for `depth`.
fn rewrite_params(params: &str, depth: Depth) -> String {
    let parts: Vec<&str> = params.split(';').collect();
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    let number = |s: &str| s.parse::<u16>().ok();
    while i < parts.len() {
        match number(parts[i]) {
            Some(ground @ (38 | 48)) => {
                let base = ground - 8;
                match parts.get(i + 1).and_then(|p| number(p)) {
                    Some(5) => {
                        let index = parts.get(i + 2).and_then(|p| number(p)).unwrap_or(0);
                        let index = u8::try_from(index).unwrap_or(u8::MAX);
                        out.extend(colour_params(Asked::Index(index), base, depth));
                        i += 3;
                    }
                    Some(2) => {
                        let c = |k: usize| {
                            parts
                                .get(i + k)
                                .and_then(|p| number(p))
                                .map_or(0, |v| u8::try_from(v).unwrap_or(u8::MAX))
                        };
                        out.extend(colour_params(Asked::Rgb(c(2), c(3), c(4)), base, depth));
                        i += 5;
                    }
                    _ => {
                        out.push(parts[i].to_owned());
                        i += 1;
                    }
                }
            }
            // The basic and bright colours (30–37, 90–97 and their backgrounds) as asked, or
            // none at depth none; the default colours (39, 49) always.
            Some(code @ (30..=37 | 40..=47 | 90..=97 | 100..=107)) => {
                if depth != Depth::None {
                    let bright = code >= 90;
                    let ground = if (30..=37).contains(&code) || (90..=97).contains(&code) {
                        30
                    } else {
                        40
                    };
                    let index = (code % 10) as u8 + if bright { 8 } else { 0 };
                    out.extend(colour_params(Asked::Index(index), ground, depth));
                }
                i += 1;
            }
            _ => {
                out.push(parts[i].to_owned());
                i += 1;
            }
        }
    }
    if out.is_empty() {
        // Nothing left but a colour the terminal cannot show: a no-op that keeps the code whole.
        return String::new();
    }
    out.join(";")
}

/// `bytes` (a frame as crossterm writes it) with every SGR colour code rewritten for `depth`;
/// unchanged at 24-bit. Other escape sequences and the text pass as they are.
#[must_use]
pub fn fit(bytes: &[u8], depth: Depth) -> Vec<u8> {
    if depth == Depth::Rgb {
        return bytes.to_vec();
    }
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == 0x1b && bytes.get(i + 1) == Some(&b'[') {
            // A CSI: parameters (digits and `;`), then its final byte.
            let start = i + 2;
            let mut end = start;
            while end < bytes.len() && (bytes[end].is_ascii_digit() || bytes[end] == b';') {
                end += 1;
            }
            if bytes.get(end) == Some(&b'm') {
                let params = std::str::from_utf8(&bytes[start..end]).unwrap_or("");
                let fitted = rewrite_params(params, depth);
                if !fitted.is_empty() || params.is_empty() {
                    out.extend_from_slice(b"\x1b[");
                    out.extend_from_slice(fitted.as_bytes());
                    out.push(b'm');
                }
                i = end + 1;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(bytes: &[u8], depth: Depth) -> String {
        String::from_utf8(fit(bytes, depth)).unwrap()
    }

    #[test]
    fn colour_codes_fit_the_depth() {
        let frame = b"\x1b[38;5;8;49mab\x1b[1;38;5;1;48;5;15mc\x1b[0m\x1b[?25l";
        assert_eq!(
            s(frame, Depth::Eight),
            "\x1b[37;49mab\x1b[1;31;47mc\x1b[0m\x1b[?25l"
        );
        assert_eq!(
            s(frame, Depth::Sixteen),
            "\x1b[90;49mab\x1b[1;31;107mc\x1b[0m\x1b[?25l"
        );
        assert_eq!(s(frame, Depth::Indexed), String::from_utf8_lossy(frame));
        assert_eq!(s(frame, Depth::None), "\x1b[49mab\x1b[1mc\x1b[0m\x1b[?25l");
        // 24-bit colour: kept, the nearest of the 256, or of the 16.
        let rgb = b"\x1b[38;2;255;0;0mx";
        assert_eq!(s(rgb, Depth::Rgb), "\x1b[38;2;255;0;0mx");
        assert_eq!(s(rgb, Depth::Indexed), "\x1b[38;5;196mx");
        assert_eq!(s(rgb, Depth::Eight), "\x1b[31mx");
        // A lone colour the terminal cannot show leaves no empty code behind (an empty SGR
        // would reset everything).
        assert_eq!(s(b"\x1b[38;5;3mx", Depth::None), "x");
        // No 256-colour code and no `5` parameter left at 8 or 16 colours.
        for depth in [Depth::Eight, Depth::Sixteen] {
            for i in 0..=255u8 {
                let code = format!("\x1b[38;5;{i};48;5;{i}m");
                let out = s(code.as_bytes(), depth);
                assert!(
                    !out.contains(";5;") && !out.contains("38") && !out.contains("48;"),
                    "{i}: {out:?}"
                );
            }
        }
    }

    #[test]
    fn the_depth_comes_from_terminfo_then_the_name() {
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |name: &str| {
                pairs
                    .iter()
                    .find(|(n, _)| *n == name)
                    .map(|(_, v)| (*v).to_owned())
            }
        };
        let db = |term: &str| match term {
            "linux" | "xterm" | "screen" => Ok(Some(8)),
            "vt100" | "vt220" => Ok(None),
            "xterm-256color" => Ok(Some(256)),
            "xterm-direct" => Ok(Some(1 << 24)),
            _ => Err(NoTerminfo),
        };
        let depth = |pairs| Depth::detect(&env(pairs), &db).depth;
        assert_eq!(depth(&[("TERM", "linux")]), Depth::Eight);
        assert_eq!(depth(&[("TERM", "vt100")]), Depth::None);
        assert_eq!(depth(&[("TERM", "vt220")]), Depth::None);
        assert_eq!(depth(&[("TERM", "xterm-256color")]), Depth::Indexed);
        assert_eq!(depth(&[("TERM", "xterm-direct")]), Depth::Rgb);
        assert_eq!(
            depth(&[("TERM", "xterm-256color"), ("COLORTERM", "truecolor")]),
            Depth::Rgb
        );
        assert_eq!(depth(&[("TERM", "foot-256color")]), Depth::Indexed);
        assert_eq!(depth(&[("TERM", "strange")]), Depth::Sixteen);
    }

    /// The machine's own terminfo database, where it has one (Debian's ncurses-base).
    #[test]
    fn terminfo_says_eight_for_the_console_and_none_for_a_vt100() {
        if terminfo_colors("xterm-256color").is_err() {
            return;
        }
        assert_eq!(
            Depth::of_count(terminfo_colors("linux").unwrap()),
            Depth::Eight
        );
        assert_eq!(
            Depth::of_count(terminfo_colors("vt100").unwrap()),
            Depth::None
        );
        assert_eq!(
            Depth::of_count(terminfo_colors("xterm-256color").unwrap()),
            Depth::Indexed
        );
    }
}
