//! The served address as a QR code drawn with text, for a hall to scan from the projector:
//! two rows of modules a line (`▀`, `▄`, `█`), dark on light with its quiet zone, or `#` in
//! ASCII (one row a line, two characters a module: a terminal's cells are twice as tall).

use qrcode::{Color, EcLevel, QrCode};

/// The lines that draw `text` as a QR code (`None` when it is too long for one).
#[must_use]
pub fn lines(text: &str, ascii: bool) -> Option<Vec<String>> {
    let code = QrCode::with_error_correction_level(text.as_bytes(), EcLevel::L).ok()?;
    let width = code.width();
    let colors = code.to_colors();
    // With a quiet zone of 2 modules: light around the code.
    let quiet = 2;
    let side = width + 2 * quiet;
    let dark = |x: usize, y: usize| {
        x >= quiet
            && y >= quiet
            && x < quiet + width
            && y < quiet + width
            && colors[(y - quiet) * width + (x - quiet)] == Color::Dark
    };
    let mut out = Vec::new();
    if ascii {
        for y in 0..side {
            out.push(
                (0..side)
                    .map(|x| if dark(x, y) { "  " } else { "##" })
                    .collect(),
            );
        }
    } else {
        // Light modules are drawn (the terminal's background may be dark): a full block is two
        // light modules, a space two dark ones.
        for y in (0..side).step_by(2) {
            out.push(
                (0..side)
                    .map(|x| match (dark(x, y), y + 1 < side && dark(x, y + 1)) {
                        (false, false) if y + 1 < side => '█',
                        (false, false | true) => '▀',
                        (true, false) if y + 1 < side => '▄',
                        _ => ' ',
                    })
                    .collect(),
            );
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_address_fits_a_small_terminal_and_decodes_to_itself() {
        let url = "http://192.168.100.200:54321/?token=0123456789abcdef0123456789abcdef";
        let drawn = lines(url, false).unwrap();
        // 37 modules (version 5) and the quiet zone: 41 columns, 21 lines.
        assert!(drawn.len() <= 22, "{}", drawn.len());
        assert!(
            drawn
                .iter()
                .all(|l| l.chars().count() == drawn[0].chars().count())
        );
        // The modules read back from the drawing are the code's.
        let code = QrCode::with_error_correction_level(url.as_bytes(), EcLevel::L).unwrap();
        let w = code.width();
        let colors = code.to_colors();
        for y in 0..w {
            for x in 0..w {
                let (row, upper) = (y / 2 + 1, y % 2 == 0);
                let c = drawn[row].chars().nth(x + 2).unwrap();
                let dark = match c {
                    '█' => false,
                    ' ' => true,
                    '▀' => !upper,
                    '▄' => upper,
                    other => panic!("{other}"),
                };
                assert_eq!(dark, colors[y * w + x] == Color::Dark, "module {x},{y}");
            }
        }
        let ascii = lines(url, true).unwrap();
        assert!(ascii.iter().all(|l| l.is_ascii()));
        assert!(lines(&"x".repeat(4000), false).is_none());
    }
}
