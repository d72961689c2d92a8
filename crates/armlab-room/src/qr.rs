//! The join link's QR code as modules (dark or light squares), and as the text the page's
//! lazily loaded module answers with: one line of `1` (dark) and `0` (light) per row.
//! Encoding needs the `qr` feature (the `qrcode` crate): the page's own wasm leaves it
//! out and asks the lazy module, which has it.

/// A QR code: `width` × `width` modules, row by row.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct QrModules {
    /// Modules per side.
    pub width: usize,
    /// Whether each module is dark, row by row.
    pub dark: Vec<bool>,
}

impl QrModules {
    /// The code of `text` at the medium error-correction level (a projected code stays
    /// readable with a few modules lost to glare); `None` when `text` is too long for a
    /// QR code.
    #[cfg(feature = "qr")]
    pub fn encode(text: &str) -> Option<QrModules> {
        let code = qrcode::QrCode::with_error_correction_level(text, qrcode::EcLevel::M).ok()?;
        let dark = code
            .to_colors()
            .into_iter()
            .map(|c| c == qrcode::Color::Dark)
            .collect();
        Some(QrModules {
            width: code.width(),
            dark,
        })
    }

    /// The modules as text: a line per row, `1` dark and `0` light.
    pub fn to_text(&self) -> String {
        let mut text = String::with_capacity(self.dark.len() + self.width);
        for row in self.dark.chunks(self.width.max(1)) {
            text.extend(row.iter().map(|&d| if d { '1' } else { '0' }));
            text.push('\n');
        }
        text
    }

    /// Reads [`QrModules::to_text`]'s text; `None` unless it is a square of `0` and `1`.
    pub fn from_text(text: &str) -> Option<QrModules> {
        let rows: Vec<&str> = text.lines().collect();
        let width = rows.len();
        let mut dark = Vec::with_capacity(width * width);
        for row in rows {
            if row.len() != width {
                return None;
            }
            for b in row.bytes() {
                dark.push(match b {
                    b'1' => true,
                    b'0' => false,
                    _ => return None,
                });
            }
        }
        (width > 0).then_some(QrModules { width, dark })
    }
}

#[cfg(test)]
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    use super::QrModules;

    #[test]
    fn modules_read_back_from_their_text_and_nothing_else_reads() {
        let code = QrModules {
            width: 3,
            dark: vec![true, false, true, false, true, false, true, true, false],
        };
        assert_eq!(code.to_text(), "101\n010\n110\n");
        assert_eq!(QrModules::from_text(&code.to_text()), Some(code));
        for bad in ["", "10\n1\n", "102\n010\n110\n", "1010\n0101\n"] {
            assert_eq!(QrModules::from_text(bad), None, "{bad:?}");
        }
    }

    #[cfg(feature = "qr")]
    #[test]
    fn a_join_link_encodes_with_its_finder_patterns() {
        let code = QrModules::encode("http://127.0.0.1:8080/#class=K7QH3MXP").unwrap();
        // Version 3 at level M holds up to 42 bytes: 29 × 29 modules.
        assert_eq!(code.width, 29);
        // The top-left finder pattern: a dark 7 × 7 ring around a light ring and a dark
        // 3 × 3 centre.
        let dark = |x: usize, y: usize| code.dark[y * code.width + x];
        assert!((0..7).all(|i| dark(i, 0) && dark(0, i) && dark(i, 6) && dark(6, i)));
        assert!((1..6).all(|i| !dark(i, 1) && !dark(1, i)));
        assert!((2..5).all(|x| (2..5).all(|y| dark(x, y))));
    }
}
