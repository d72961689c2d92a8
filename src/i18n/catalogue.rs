//! The catalogue: every key with its English and Finnish text, side by side, so a missing
//! translation cannot compile. Places `{0}`, `{1}`, … are filled in order by
//! [`fill`](super::fill).

macro_rules! catalogue {
    ($($key:ident: $en:literal / $fi:literal,)*) => {
        /// A user-facing text.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Key {
            $(
                #[doc = $en]
                $key,
            )*
        }

        impl Key {
            /// Every key.
            pub const ALL: &'static [Key] = &[$(Key::$key,)*];
        }

        /// The English text of a key.
        pub fn en(key: Key) -> &'static str {
            match key {
                $(Key::$key => $en,)*
            }
        }

        /// The Finnish text of a key.
        pub fn fi(key: Key) -> &'static str {
            match key {
                $(Key::$key => $fi,)*
            }
        }
    };
}

/// Keys whose text is the same in both languages (symbols, names, units).
#[cfg(test)]
pub(super) const SAME_IN_BOTH: &[Key] = &[Key::AppName, Key::TabIk];

catalogue! {
    // --- The frame: top bar, panels, tabs -----------------------------------------------
    AppName: "ArmLab" / "ArmLab",
    PanelJoints: "Joints" / "Nivelet",
    PanelIk: "Inverse kinematics" / "Käänteiskinematiikka",
    PanelMatrices: "Matrices" / "Matriisit",
    PanelRobot: "Robot" / "Robotti",
    TabIk: "IK" / "IK",
    ViewMenu: "View" / "Näkymä",
    ClosePanel: "Close this panel (its tab opens it again)" / "Sulje paneeli (välilehti avaa sen uudelleen)",
    Zero: "Zero" / "Nollaa",
    ZeroHint: "All joints to 0 (or the nearest limit)" / "Kaikki nivelet arvoon 0 (tai lähimpään rajaan)",
    Home: "Home" / "Kotiasento",
    HomeHint: "The robot's home pose" / "Robotin kotiasento",
    Fit: "Fit" / "Sovita",
    FitHint: "Frame the robot (F)" / "Rajaa robotti näkymään (F)",
    Menu: "≡ Menu" / "≡ Valikko",
    ShortcutHint: "keys: F fit   P presentation   1–9 joint N   Esc close" / "näppäimet: F sovita   P esitys   1–9 nivel N   Esc sulje",
    ViewTop: "Top" / "Ylhäältä",
    ViewFront: "Front" / "Edestä",
    ViewSide: "Side" / "Sivulta",
    View3d: "3D" / "3D-näkymä",
    CopyLink: "Copy link" / "Kopioi linkki",
    CopyLinkHint: "A link that opens this robot, pose, target, settings and view" / "Linkki, joka avaa tämän robotin, asennon, kohteen, asetukset ja näkymän",
    LinkCopied: "The link is on the clipboard." / "Linkki on leikepöydällä.",
    Degrees: "Degrees" / "Asteet",
    DegreesHint: "Show angles in degrees (off: radians)" / "Kulmat asteina (pois: radiaaneina)",
    DhFrames: "DH frames" / "DH-koordinaatistot",
    DhFramesHint: "Draw every DH frame: x red, y green, z blue" / "Piirrä jokainen DH-koordinaatisto: x punainen, y vihreä, z sininen",
    Presentation: "Presentation" / "Esitys",
    PresentationHint: "Large text and high contrast for a projector (P)" / "Suuri teksti ja vahva kontrasti videotykille (P)",
    LanguageHint: "The language of the interface" / "Käyttöliittymän kieli",
    Dismiss: "Dismiss" / "Sulje",
    GridControls: "grid {0} {1}   ·   {2}" / "ruudukko {0} {1}   ·   {2}",
    MouseControls: "drag: orbit   right-drag: pan   wheel: zoom" / "veto: kierrä   oikea veto: siirrä   rulla: zoomaa",
    TouchControls: "one finger: orbit   two fingers: pan   pinch: zoom" / "yksi sormi: kierrä   kaksi sormea: siirrä   nipistys: zoomaa",
    StatusReached: "target reached" / "kohde saavutettu",
    StatusOutOfReach: "target out of reach: the arm stretches toward it" / "kohde ulottumattomissa: käsi ojentuu sitä kohti",
    StatusPending: "drag the target ball, its arrows or rings" / "vedä kohdepalloa, sen nuolia tai renkaita",
    JointHighlighted: "joint {0}: {1} — A_{0} and T_0{0} highlighted" / "nivel {0}: {1} — A_{0} ja T_0{0} korostettu",
    ReachedIn: "Reached in {0} iterations" / "Saavutettu {0} iteraatiossa",
}
