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
pub(super) const SAME_IN_BOTH: &[Key] = &[
    Key::AppName,
    Key::TabIk,
    Key::CopyLatex,
    Key::CopyNumpy,
    Key::ErrorPlotRange,
];

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
    Task: "Task" / "Tehtävä",
    Method: "Method" / "Menetelmä",
    TaskPosition: "Position only (3 rows)" / "Vain paikka (3 riviä)",
    TaskAxisX: "Position + tool x axis (5D)" / "Paikka + työkalun x-akseli (5D)",
    TaskAxisY: "Position + tool y axis (5D)" / "Paikka + työkalun y-akseli (5D)",
    TaskAxisZ: "Position + tool z axis (5D)" / "Paikka + työkalun z-akseli (5D)",
    TaskFullPose: "Full pose (6 rows)" / "Paikka ja asento (6 riviä)",
    MethodDls: "Damped least squares" / "Vaimennettu pienimmän neliösumman menetelmä",
    MethodPinv: "Pseudo-inverse (Newton)" / "Pseudoinverssi (Newton)",
    MethodTranspose: "Jacobian transpose (gradient)" / "Jacobin matriisin transpoosi (gradientti)",
    MethodClosedForm: "Closed form" / "Suljettu muoto",
    NoClosedFormHint: "This robot has no closed-form IK here (the planar 2R, the RRR and the UR10 do)." / "Tällä robotilla ei ole täällä suljetun muodon ratkaisua (tason 2R-, RRR- ja UR10-roboteilla on).",
    SnapTarget: "Snap target to gripper" / "Siirrä kohde tarttujaan",
    Solve: "Solve" / "Ratkaise",
    SolveHint: "Run the method to convergence from the current pose and record every iteration" / "Aja menetelmä nykyisestä asennosta suppenemiseen asti ja tallenna jokainen iteraatio",
    TargetReached: "Target reached" / "Kohde saavutettu",
    TargetOutOfReach: "Target out of reach (closest pose shown)" / "Kohde ulottumattomissa (lähin asento näytetään)",
    TargetPending: "Target not at the target" / "Työkalu ei ole kohteessa",
    IkErrors: "error: {0} {1}, {2} rad  ·  {3} iterations" / "virhe: {0} {1}, {2} rad  ·  iteraatioita {3}",
    LastSolve: "Last solve: {0} iterations, {1}" / "Viimeisin ratkaisu: iteraatioita {0}, {1}",
    SolveConverged: "converged" / "suppeni",
    SolveOutOfReach: "target out of reach" / "kohde ulottumattomissa",
    SolveStopped: "stopped" / "pysähtyi",
    Iteration: "iteration" / "iteraatio",
    ReplayHint: "Replay the run: the arm shows q after this iteration" / "Toista ajo: käsivarsi näyttää q:n tämän iteraation jälkeen",
    StepLine: "‖e‖ = {0}   step = {1}   λ = {2}" / "‖e‖ = {0}   askel = {1}   λ = {2}",
    RawQ: "raw q: {0}" / "rajaamaton q: {0}",
    KeptQ: "kept q: {0}" / "rajattu q: {0}",
    ErrorPlotRange: "log10 ‖e‖: {0} … {1}" / "log10 ‖e‖: {0} … {1}",

    // --- The robot panel and its DH editor -------------------------------------------------
    Preset: "Preset" / "Valmisrobotti",
    Edited: "{0} (edited)" / "{0} (muokattu)",
    DhTable: "DH table (editable)" / "DH-taulukko (muokattava)",
    Convention: "Convention:" / "Konventio:",
    ConventionStandard: "standard (Spong)" / "tavallinen DH (Spong)",
    ConventionModified: "modified (Craig)" / "muunnettu DH (Craig)",
    LengthsIn: "Lengths in {0}; revolute limits in degrees, prismatic in {0}." / "Pituudet yksikössä {0}; kiertonivelten rajat asteina, liukunivelten yksikössä {0}.",
    ColumnType: "type" / "tyyppi",
    Revolute: "R  revolute" / "R  kiertonivel",
    Prismatic: "P  prismatic" / "P  liukunivel",
    RemoveJoint: "Remove this joint" / "Poista tämä nivel",
    AddJoint: "+ Add joint" / "+ Lisää nivel",
    CellEmpty: "Joint {0}, {1}: is empty." / "Nivel {0}, {1}: solu on tyhjä.",
    CellNotNumber: "Joint {0}, {1}: \"{2}\" is not a number." / "Nivel {0}, {1}: \"{2}\" ei ole luku.",
    SaveRobotDownload: "Save robot file" / "Tallenna robottitiedosto",
    LoadRobotFile: "Load robot file…" / "Lataa robottitiedosto…",
    SaveRobotFile: "Save robot file…" / "Tallenna robottitiedosto…",
    OpenRobotFile: "Open robot file…" / "Avaa robottitiedosto…",
    DropHint: "Or drop a robot file (.json) onto the window." / "Tai pudota robottitiedosto (.json) ikkunaan.",
    FileNotLoaded: "That robot file was not loaded: {0}" / "Robottitiedostoa ei ladattu: {0}",
    SavedDownload: "Saved the robot as a download ({0})." / "Robotti tallennettiin latauksena ({0}).",
    DownloadFailed: "Could not save the robot file: {0}." / "Robottitiedostoa ei voitu tallentaa: {0}.",
    DroppedUnreadable: "Could not read the dropped file: {0}." / "Pudotettua tiedostoa ei voitu lukea: {0}.",
    FileUnreadable: "Could not read {0}: {1}." / "Tiedostoa {0} ei voitu lukea: {1}.",
    SavedAs: "Saved the robot as {0}." / "Robotti tallennettiin tiedostoon {0}.",
    SaveFailed: "Could not save the robot file {0}: {1}." / "Robottitiedostoa {0} ei voitu tallentaa: {1}.",
    // The presets' descriptions (their robot files hold the English; a test keeps them equal).
    DescUr10: "Universal Robots UR10 in modified DH (Craig). Axes 2–4 are parallel; closed-form IK has up to eight solutions." / "Universal Robotsin UR10 muunnetuin DH-parametrein (Craig). Akselit 2–4 ovat yhdensuuntaiset; suljetun muodon käänteiskinematiikalla on enintään kahdeksan ratkaisua.",
    DescUr10Standard: "The same UR10 in standard DH (Spong), with offsets of 180° on θ2 and θ6: it gives exactly the same tool pose as the modified table for every q." / "Sama UR10 tavallisin DH-parametrein (Spong), θ2:lla ja θ6:lla 180°:n siirtymä: se antaa jokaisella q:lla täsmälleen saman työkalun aseman kuin muunnettu taulukko.",
    DescMetrover: "A hobby arm built for a student rover. The tool point lies on joint 5's axis, so joint 5 only rolls the hand: position IK is carried by joints 1–4. Drawn with its real part sizes." / "Opiskelijamönkijää varten rakennettu harrastekäsivarsi. Työkalupiste on nivelen 5 akselilla, joten nivel 5 vain kiertää kättä: paikan käänteiskinematiikan hoitavat nivelet 1–4. Piirretty osien todellisin mitoin.",
    DescPlanar2r: "Two revolute joints, l1 = 2 m, l2 = 1 m. x = l1 c1 + l2 c12, y = l1 s1 + l2 s12; singular when s2 = 0." / "Kaksi kiertoniveltä, l1 = 2 m, l2 = 1 m. x = l1 c1 + l2 c12, y = l1 s1 + l2 s12; singulaarinen, kun s2 = 0.",
    DescRrr: "A pen-holding arm from a robotics course: L1 = 100.9, L2 = 222.1, L3 = 136.2 mm. Closed-form IK has up to four solutions." / "Robotiikan kurssin kynää pitelevä käsivarsi: L1 = 100.9, L2 = 222.1, L3 = 136.2 mm. Suljetun muodon käänteiskinematiikalla on enintään neljä ratkaisua.",
    DescPuma560: "The classic Unimation Puma 560, standard DH (lengths in metres)." / "Klassinen Unimation Puma 560, tavallinen DH (pituudet metreinä).",
    DescPanda: "Franka Emika Panda, modified DH, seven joints: redundant, so IK has a null space. Home is the ready pose (q = 0 is outside joint 4's range)." / "Franka Emika Panda, muunnettu DH, seitsemän niveltä: redundantti, joten käänteiskinematiikalla on nolla-avaruus. Kotiasento on valmiusasento (q = 0 on nivelen 4 alueen ulkopuolella).",
    DescStanford: "Scheinman's Stanford arm, standard DH: a prismatic third joint (θ3 fixed at −90°) and a spherical wrist." / "Scheinmanin Stanford-käsivarsi, tavallinen DH: kolmas nivel on liukunivel (θ3 kiinteästi −90°) ja ranne pallomainen.",
    DescScara: "A SCARA arm, standard DH: two horizontal revolute joints, a vertical prismatic quill and a roll." / "SCARA-käsivarsi, tavallinen DH: kaksi vaakasuoraa kiertoniveltä, pystysuora liukuakseli ja kierto.",

    // --- The native file dialog ------------------------------------------------------------
    OpenDialogTitle: "Open a robot file" / "Avaa robottitiedosto",
    SaveDialogTitle: "Save the robot file" / "Tallenna robottitiedosto",
    Up: "Up" / "Ylös",
    UpHint: "The folder above" / "Yläkansio",
    FolderUnreadable: "The folder {0} cannot be read: {1}." / "Kansiota {0} ei voi lukea: {1}.",
    NoFiles: "No folders or .json files here." / "Täällä ei ole kansioita eikä .json-tiedostoja.",
    FileName: "File name" / "Tiedoston nimi",
    OverwriteWarning: "A file of that name is there: saving replaces it." / "Samanniminen tiedosto on jo olemassa: tallennus korvaa sen.",
    Open: "Open" / "Avaa",
    Save: "Save" / "Tallenna",

    // --- The matrices panel ----------------------------------------------------------------
    Decimals: "decimals:" / "desimaalit:",
    Copy: "copy:" / "kopioi:",
    CopyText: "Text" / "Teksti",
    CopyLatex: "LaTeX" / "LaTeX",
    CopyNumpy: "NumPy" / "NumPy",
    CopyAsText: "Copy as Text" / "Kopioi tekstinä",
    CopyAsLatex: "Copy as LaTeX" / "Kopioi LaTeX-muodossa",
    CopyAsNumpy: "Copy as NumPy" / "Kopioi NumPy-muodossa",
    ToolPoseTitle: "T_0{0}  (tool pose, {1})" / "T_0{0}  (työkalun paikka ja asento, {1})",
    ToolPoseHint: "The tool frame in the base frame: the product of every A_i" / "Työkalun koordinaatisto kantakoordinaatistossa: kaikkien A_i-matriisien tulo",
    Jacobian: "Jacobian" / "Jacobin matriisi",
    JacobianTitle: "J  (6×n, base frame)" / "J  (6×n, kantakoordinaatisto)",
    JacobianHint: "Geometric Jacobian, rows vx vy vz ωx ωy ωz: revolute J_v = z × (o_n − o), J_ω = z; prismatic J_v = z" / "Geometrinen Jacobin matriisi, rivit vx vy vz ωx ωy ωz: kiertonivel J_v = z × (o_n − o), J_ω = z; liukunivel J_v = z",
    CentralDifferences: "central differences (ε = 1e−6) agree to {0}" / "keskeisdifferenssit (ε = 1e−6) täsmäävät tarkkuudella {0}",
    AboveTolerance: "{0}: above the tolerance {1}" / "{0}: yli toleranssin {1}",
    TaskRows: "task rows" / "tehtävän rivit",
    TaskRowsHint: "The rows the IK task uses" / "IK-tehtävän käyttämät rivit",
    SingularValues: "singular values" / "singulaariarvot",
    SingularValuesHint: "Of the task Jacobian with the linear rows divided by the reach ({0} {1})" / "Tehtävän Jacobin matriisista, jonka lineaariset rivit on jaettu ulottumalla ({0} {1})",
    Manipulability: "manipulability" / "manipuloitavuus",
    ManipulabilityHint: "√det(J Jᵀ): the product of the singular values" / "√det(J Jᵀ): singulaariarvojen tulo",
    ConditionNumber: "condition number" / "ehtoluku",
    NearSingular: "At or near a singularity: some task direction needs very large joint speeds." / "Singulaarisuudessa tai sen lähellä: jokin tehtävän suunta vaatii hyvin suuria nivelnopeuksia.",
    LinkTransforms: "Link transforms A_i and running products T_0i" / "Linkkien muunnokset A_i ja kertyvät tulot T_0i",
    StandardFormula: "standard DH: A_i = Rz(θ)·Tz(d)·Tx(a)·Rx(α)" / "tavallinen DH: A_i = Rz(θ)·Tz(d)·Tx(a)·Rx(α)",
    ModifiedFormula: "modified DH: A_i = Rx(α_{i−1})·Tx(a_{i−1})·Rz(θ)·Tz(d)" / "muunnettu DH: A_i = Rx(α_{i−1})·Tx(a_{i−1})·Rz(θ)·Tz(d)",
    LinkTitle: "A_{0}  ({1}, {2}{0} variable)" / "A_{0}  ({1}, muuttuja {2}{0})",
    FrameInPrevious: "Frame i in frame i−1" / "Koordinaatisto i koordinaatistossa i−1",
    FrameInBase: "Frame i in the base frame: A_1·…·A_i" / "Koordinaatisto i kantakoordinaatistossa: A_1·…·A_i",
    ToolOrientation: "Tool orientation" / "Työkalun asento",
    ZyxEuler: "Z-Y-X Euler (α, β, γ)" / "Z-Y-X-Eulerin kulmat (α, β, γ)",
    ZyxDegenerate: "(β = ±90°: only α∓γ is defined)" / "(β = ±90°: vain α∓γ on määritelty)",
    XyzFixed: "X-Y-Z fixed (γ, β, α)" / "X-Y-Z-kiinteät kulmat (γ, β, α)",
    AngleAxis: "angle-axis (θ, k̂)" / "kulma ja akseli (θ, k̂)",
    AngleAxisDegenerate: "(θ = 0: any axis)" / "(θ = 0: mikä tahansa akseli)",
    EulerParameters: "Euler parameters (ε1..ε4)" / "Eulerin parametrit (ε1..ε4)",

    // --- Links ("This link could not be opened (…)") ---------------------------------------
    LinkNotOpened: "This link could not be opened ({0}); showing the default robot instead." / "Linkkiä ei voitu avata ({0}); näytetään oletusrobotti.",
    LinkNoEquals: "the link part \"{0}\" has no '='" / "linkin osassa \"{0}\" ei ole merkkiä '='",
    LinkUnknownPart: "the link has an unknown part \"{0}\"" / "linkissä on tuntematon osa \"{0}\"",
    LinkBrokenEscape: "the link has a broken %-escape" / "linkissä on rikkinäinen %-koodaus",
    LinkNotUtf8: "the link's text is not valid UTF-8" / "linkin teksti ei ole kelvollista UTF-8:aa",
    LinkNotANumber: "the link's {0} has \"{1}\", which is not a number" / "linkin kentässä {0} on \"{1}\", joka ei ole luku",
    LinkTargetLength: "the link's target needs six numbers (x, y, z, α, β, γ)" / "linkin kohde (target) tarvitsee kuusi lukua (x, y, z, α, β, γ)",
    LinkUnknownTask: "the link's task \"{0}\" is not known" / "linkin tehtävä \"{0}\" on tuntematon",
    LinkBadValue: "the link's {0} is \"{1}\"; it can be {2}" / "linkin kentän {0} arvo on \"{1}\"; sallittu arvo on {2}",
    LinkBadCamera: "the link's camera needs six numbers (yaw, pitch, distance, x, y, z), the distance above 0" / "linkin kamera (camera) tarvitsee kuusi lukua (kiertymä, kallistus, etäisyys, x, y, z), etäisyys yli 0",
    LinkUnknownMethod: "the link's method \"{0}\" is not known" / "linkin menetelmä \"{0}\" on tuntematon",
    LinkNoRobot: "the link names no robot (robot=...)" / "linkki ei nimeä robottia (robot=...)",
    LinkCustomWithoutTable: "the link says robot=custom but carries no dh= table" / "linkissä on robot=custom mutta ei dh=-taulukkoa",
    AllowedOnOff: "on or off" / "on tai off",
    AllowedDegRad: "deg or rad" / "deg tai rad",
    AllowedDecimals: "a whole number from 0 to 8" / "kokonaisluku väliltä 0–8",
    AllowedLang: "en or fi" / "en tai fi",
    AllowedPanels: "joints, ik, matrices, robot (joined by commas) or none" / "joints, ik, matrices, robot (pilkuin erotettuina) tai none",

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
    ErrJointOutsideStroke: "The value {1} of joint {0} lies outside its stroke {2} … {3}." / "Nivelen {0} arvo {1} on liikealueen {2} … {3} ulkopuolella.",
    ErrPoseNotFinite: "At these joint values the tool pose is not a finite number (a value overflows): nothing can be computed from it." / "Näillä nivelarvoilla työkalun asema ei ole äärellinen luku (jokin arvo ylivuotaa): siitä ei voi laskea mitään.",

    // --- The core's errors: inverse kinematics ---------------------------------------------
    IkBadTarget: "The target pose is not a valid pose: {0}." / "Kohteen paikka ja asento eivät kelpaa: {0}.",
    TargetNotFinite: "it holds a value that is not finite" / "jokin arvo ei ole äärellinen",
    TargetNotRotation: "its 3×3 part is not a rotation (orthonormal, determinant +1)" / "3×3-osa ei ole rotaatio (ortonormaali, determinantti +1)",
    IkBadSettings: "The IK settings are not valid: {0} must be a positive number, not {1}." / "IK-asetukset eivät kelpaa: arvon {0} on oltava positiivinen luku, ei {1}.",
    IkTargetTooFar: "The target is {0} from the base, farther than {1}, the most ArmLab accepts (in the robot's length unit)." / "Kohde on {0} päässä kannasta, kauempana kuin {1}, suurin ArmLabin hyväksymä etäisyys (robotin pituusyksikössä).",
    IkNoClosedForm: "\"{0}\" has no closed-form IK in ArmLab (only the planar 2R, the RRR arm and the UR family do): use a numeric method." / "Robotilla \"{0}\" ei ole ArmLabissa suljetun muodon käänteiskinematiikkaa (vain tason 2R-robotilla, RRR-käsivarrella ja UR-perheellä on): käytä numeerista menetelmää.",
}
