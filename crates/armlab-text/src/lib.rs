//! The one catalogue of user-facing text, in English and Finnish.
//!
//! Every sentence the app shows, and the sentences of the core's typed errors ([`words`]),
//! come from here: a [`Key`]
//! names a text, and `catalogue.rs` gives every key its English and Finnish text side by
//! side (one macro writes both languages' exhaustive `match`, so both have the same keys by
//! construction). Texts with values carry numbered places, `{0}`, `{1}`, …, filled by
//! [`fill`]. The JSON API keeps to English.

mod catalogue;
pub mod echo;
pub mod words;

pub use catalogue::Key;
pub use words::{Labelled, Name, Sentence, contact_sentence};

/// The text of `key` in `lang`.
pub fn text(lang: Lang, key: Key) -> &'static str {
    match lang {
        Lang::En => catalogue::en(key),
        Lang::Fi => catalogue::fi(key),
    }
}

/// The text of `key` in `lang` with its places `{0}`, `{1}`, … filled by `args` in order.
///
/// One pass over the text: a value that itself holds `{1}` (a typed cell, a name) is
/// written as it is, never filled again. A place without a value stays as written.
pub fn fill(lang: Lang, key: Key, args: &[&dyn std::fmt::Display]) -> String {
    let text = text(lang, key);
    let mut out = String::with_capacity(text.len() + 16 * args.len());
    let mut rest = text;
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let place = after
            .split_once('}')
            .and_then(|(n, tail)| Some((n.parse::<usize>().ok()?, tail)))
            .and_then(|(n, tail)| Some((args.get(n)?, tail)));
        match place {
            Some((arg, tail)) => {
                out.push_str(&arg.to_string());
                rest = tail;
            }
            None => {
                out.push('{');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The numbered places a text has (`{0}` → 0), sorted.
pub fn places(text: &str) -> Vec<usize> {
    let mut found: Vec<usize> = text
        .split('{')
        .skip(1)
        .filter_map(|rest| rest.split_once('}').and_then(|(n, _)| n.parse().ok()))
        .collect();
    found.sort_unstable();
    found.dedup();
    found
}

/// A language of the interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Lang {
    /// English.
    #[default]
    En,
    /// Finnish (suomi): the Metrover thesis and the lecture slides are Finnish.
    Fi,
}

impl Lang {
    /// Every language, in the order of the switch.
    pub const ALL: [Lang; 2] = [Lang::En, Lang::Fi];

    /// The id a link uses (`en`, `fi`).
    pub fn id(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Fi => "fi",
        }
    }

    /// The language of an id.
    pub fn from_id(id: &str) -> Option<Lang> {
        Lang::ALL.into_iter().find(|l| l.id() == id)
    }

    /// The language's own name.
    pub fn name(self) -> &'static str {
        match self {
            Lang::En => "English",
            Lang::Fi => "Suomi",
        }
    }

    /// The first language ArmLab has among a browser's preferred languages (BCP 47 tags
    /// such as `fi-FI`, `en-GB`), English when none.
    pub fn from_tags<'a>(tags: impl IntoIterator<Item = &'a str>) -> Lang {
        tags.into_iter()
            .find_map(|tag| {
                let primary = tag.split(['-', '_']).next().unwrap_or_default();
                Lang::from_id(&primary.to_ascii_lowercase())
            })
            .unwrap_or_default()
    }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn both_catalogues_answer_every_key_with_the_same_places() {
        for key in Key::ALL {
            let (en, fi) = (text(Lang::En, *key), text(Lang::Fi, *key));
            assert!(
                !en.trim().is_empty() && !fi.trim().is_empty(),
                "{key:?} is empty"
            );
            assert_eq!(places(en), places(fi), "{key:?}: {en:?} / {fi:?}");
            let n = places(en).len();
            assert_eq!(
                places(en),
                (0..n).collect::<Vec<_>>(),
                "{key:?} numbers its places from 0"
            );
        }
    }

    #[test]
    fn the_finnish_catalogue_is_translated() {
        // Symbols and names read the same in both languages.
        let same: Vec<&Key> = Key::ALL
            .iter()
            .filter(|k| text(Lang::En, **k) == text(Lang::Fi, **k))
            .filter(|k| !catalogue::SAME_IN_BOTH.contains(k))
            .collect();
        assert!(same.is_empty(), "untranslated: {same:?}");
    }

    #[test]
    fn every_text_has_its_glyphs_in_the_font() {
        // The ranges of assets/fonts/README.md: a glyph outside them panics in the UI tests.
        const RANGES: &[(u32, u32)] = &[
            (0x20, 0x7E),
            (0xA0, 0xFF),
            (0x131, 0x131),
            (0x152, 0x153),
            (0x2C6, 0x2DC),
            (0x300, 0x308),
            (0x391, 0x3C9),
            (0x1D40, 0x1D40),
            (0x2010, 0x2027),
            (0x2030, 0x203A),
            (0x2070, 0x209C),
            (0x2190, 0x21FF),
            (0x2200, 0x22FF),
            (0x2300, 0x231F),
            (0x25A0, 0x25FF),
            (0x2610, 0x2612),
            (0x26A0, 0x26A0),
            (0x2713, 0x2718),
            (0x27E8, 0x27E9),
        ];
        for key in Key::ALL {
            for lang in Lang::ALL {
                for c in text(lang, *key).chars() {
                    let known = RANGES
                        .iter()
                        .any(|(lo, hi)| (*lo..=*hi).contains(&(c as u32)));
                    assert!(known, "{key:?} ({lang:?}) has {c:?} (U+{:04X})", c as u32);
                }
            }
        }
    }

    #[test]
    fn fill_puts_values_in_their_places() {
        assert_eq!(places("a {1} b {0} {1}"), vec![0, 1]);
        let s = fill(Lang::En, Key::ReachedIn, &[&3, &"x"]);
        assert!(s.contains('3'), "{s}");
        // A value holding a place is written as it is.
        let s = fill(Lang::En, Key::JointHighlighted, &[&"{1}", &"x"]);
        assert_eq!(s, "joint {1}: x — A_{1} and T_0{1} highlighted");
        // Braces that are not places stay.
        let s = fill(Lang::En, Key::ModifiedFormula, &[]);
        assert!(s.contains("α_{i−1}"), "{s}");
    }

    #[test]
    fn the_browser_language_picks_the_first_one_armlab_has() {
        assert_eq!(Lang::from_tags(["fi-FI", "en-US"]), Lang::Fi);
        assert_eq!(Lang::from_tags(["sv-FI", "FI", "en"]), Lang::Fi);
        assert_eq!(Lang::from_tags(["de-DE", "en-GB"]), Lang::En);
        assert_eq!(Lang::from_tags([]), Lang::En);
    }
}
