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

    // --- The IK panel ---------------------------------------------------------------------
    TaskPosition: "Position only (3 rows)" / "Vain paikka (3 riviä)",
    TaskAxisX: "Position + tool x axis (5D)" / "Paikka + työkalun x-akseli (5D)",
    TaskAxisY: "Position + tool y axis (5D)" / "Paikka + työkalun y-akseli (5D)",
    TaskAxisZ: "Position + tool z axis (5D)" / "Paikka + työkalun z-akseli (5D)",
    TaskFullPose: "Full pose (6 rows)" / "Paikka ja asento (6 riviä)",
    MethodDls: "Damped least squares" / "Vaimennettu pienimmän neliösumman menetelmä",
    MethodPinv: "Pseudo-inverse (Newton)" / "Pseudoinverssi (Newton)",
    MethodTranspose: "Jacobian transpose (gradient)" / "Jacobin matriisin transpoosi (gradientti)",
    MethodClosedForm: "Closed form" / "Suljettu muoto",

    // --- The core's errors: robot descriptions -----------------------------------------------
    // A place opens the Finnish sentence, inflected ("Nivelessä 2 …"); English keeps "In".
    PlaceRobot: "the robot" / "Robotin kuvauksessa",
    PlaceJoint: "joint {0}" / "Nivelessä {0}",
    PlaceBase: "the base transform" / "Kannan muunnoksessa",
    PlaceTool: "the tool transform" / "Työkalun muunnoksessa",
    ExpectedObject: "a JSON object { ... }" / "JSON-olio { ... }",
    ExpectedJointList: "a list of joints [ {...}, ... ]" / "nivelten lista [ {...}, ... ]",
    ExpectedTransform: "an object { \"xyz\": [..], \"rpy_deg\": [..] }" / "olio { \"xyz\": [..], \"rpy_deg\": [..] }",
    ExpectedText: "a text in quotes" / "lainausmerkeissä oleva teksti",
    ExpectedNumber: "a number" / "luku",
    ExpectedTriple: "a list of 3 numbers" / "kolmen luvun lista",
    ErrSyntax: "The robot file is not valid JSON (line {0}, column {1}): {2}." / "Robottitiedosto ei ole kelvollista JSONia (rivi {0}, sarake {1}): {2}.",
    ErrMissingField: "In {0}, the field \"{1}\" is missing." / "{0} puuttuu kenttä \"{1}\".",
    ErrUnknownField: "In {0}, the field \"{1}\" is not known; the known fields are: {2}." / "{0} kenttä \"{1}\" on tuntematon; tunnetut kentät ovat: {2}.",
    ErrWrongType: "In {0}, the field \"{1}\" must be {2}." / "{0} kentän \"{1}\" on oltava {2}.",
    ErrUnknownConvention: "The convention \"{0}\" is not known: use \"standard\" (Denavit–Hartenberg, Spong) or \"modified\" (Craig)." / "Konventio \"{0}\" on tuntematon: käytä arvoa \"standard\" (Denavit–Hartenberg, Spong) tai \"modified\" (Craig).",
    ErrUnknownJointType: "Joint {0} has the type \"{1}\": use \"revolute\" or \"prismatic\"." / "Nivelen {0} tyyppi on \"{1}\": käytä arvoa \"revolute\" tai \"prismatic\".",
    ErrUnknownLengthUnit: "The length unit \"{0}\" is not known: use \"mm\" or \"m\"." / "Pituusyksikkö \"{0}\" on tuntematon: käytä yksikköä \"mm\" tai \"m\".",
    ErrNotFinite: "In {0}, the field \"{1}\" is not a finite number ({2})." / "{0} kenttä \"{1}\" ei ole äärellinen luku ({2}).",
    ErrEmptyChain: "The robot has no joints: a chain needs at least one." / "Robotilla ei ole niveliä: ketjussa on oltava vähintään yksi.",
    ErrTooManyJoints: "The robot has {0} joints; ArmLab handles at most {1}." / "Robotilla on {0} niveltä; ArmLab käsittelee enintään {1}.",
    ErrTooLarge: "In {0}, the field \"{1}\" is {2}, larger in size than the limit {3}." / "{0} kentän \"{1}\" arvo on {2}, itseisarvoltaan suurempi kuin raja {3}.",
    ErrNegativeSize: "In {0}, the field \"{1}\" holds {2}: a size cannot be negative." / "{0} kentässä \"{1}\" on {2}: koko ei voi olla negatiivinen.",
    ErrLimitsReversed: "Joint {0}: the lower limit {1} is above the upper limit {2}." / "Nivel {0}: alaraja {1} on ylärajaa {2} suurempi.",
    ErrPrismaticWithoutLimits: "Joint {0} is prismatic and needs both limits (\"min\" and \"max\", in length units)." / "Nivel {0} on liukunivel ja tarvitsee molemmat rajat (\"min\" ja \"max\", pituusyksiköissä).",
    ErrUnknownPreset: "There is no robot called \"{0}\"; the presets are: {1}." / "Robottia nimeltä \"{0}\" ei ole; valmisrobotit ovat: {1}.",
    ErrWrongJointCount: "The robot has {0} joints but {1} joint values were given." / "Robotilla on {0} niveltä, mutta nivelarvoja annettiin {1}.",
    ErrJointValueNotFinite: "The value of joint {0} is not a finite number ({1})." / "Nivelen {0} arvo ei ole äärellinen luku ({1}).",

    // --- The core's errors: inverse kinematics ---------------------------------------------
    IkBadTarget: "The target pose is not a valid pose: {0}." / "Kohteen paikka ja asento eivät kelpaa: {0}.",
    TargetNotFinite: "it holds a value that is not finite" / "jokin arvo ei ole äärellinen",
    TargetNotRotation: "its 3×3 part is not a rotation (orthonormal, determinant +1)" / "3×3-osa ei ole rotaatio (ortonormaali, determinantti +1)",
    IkBadSettings: "The IK settings are not valid: {0} must be a positive number, not {1}." / "IK-asetukset eivät kelpaa: arvon {0} on oltava positiivinen luku, ei {1}.",
    IkNoClosedForm: "\"{0}\" has no closed-form IK in ArmLab (only the planar 2R, the RRR arm and the UR family do): use a numeric method." / "Robotilla \"{0}\" ei ole ArmLabissa suljetun muodon käänteiskinematiikkaa (vain tason 2R-robotilla, RRR-käsivarrella ja UR-perheellä on): käytä numeerista menetelmää.",
}
