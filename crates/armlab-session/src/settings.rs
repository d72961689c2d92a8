//! Display settings: angle units, DH frames, decimals, presentation mode, language, which
//! panels are open, and the camera. A link carries all of them (`Display`), so a
//! lecturer's link opens the same view on every screen.

use armlab_text::{Key, Lang};

/// A panel the user can open and close.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PanelKind {
    /// The joint sliders.
    Joints,
    /// The IK target, task, method and solve.
    Ik,
    /// The matrices and the Jacobian.
    Matrices,
    /// The robot: presets, the DH table, files.
    Robot,
    /// The motion lab: controllers, the simulation's plots (closed unless opened).
    Motion,
}

impl PanelKind {
    /// Every panel, in the order of the tabs.
    pub const ALL: [PanelKind; 5] = [
        PanelKind::Joints,
        PanelKind::Ik,
        PanelKind::Matrices,
        PanelKind::Robot,
        PanelKind::Motion,
    ];

    /// The id a link uses.
    pub fn id(self) -> &'static str {
        match self {
            PanelKind::Joints => "joints",
            PanelKind::Ik => "ik",
            PanelKind::Matrices => "matrices",
            PanelKind::Robot => "robot",
            PanelKind::Motion => "motion",
        }
    }

    /// The panel of an id.
    pub fn from_id(id: &str) -> Option<PanelKind> {
        PanelKind::ALL.into_iter().find(|k| k.id() == id)
    }
}

/// What the 3D view can draw besides the arm (docs/kinematics.md §6 and §4.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Overlay {
    /// The Jacobian's columns as arrows at the tool: the linear velocity each joint gives.
    JacobianColumns,
    /// The columns' angular parts.
    AngularColumns,
    /// The velocity manipulability ellipsoid.
    VelocityEllipsoid,
    /// The force manipulability ellipsoid.
    ForceEllipsoid,
    /// How each joint origin moves along the self-motion (redundant arms).
    NullSpace,
    /// The tool's velocity v and ω for the joint speeds q̇.
    Twist,
    /// Every other IK solution of the target as a translucent arm.
    Ghosts,
    /// The sampled reachable workspace as a point cloud.
    Workspace,
    /// Only the cloud's slice through the target (a horizontal layer).
    WorkspaceSlice,
    /// Colour the cloud by σ_min (distance to a singularity) instead of manipulability.
    WorkspaceSigma,
    /// The other DH convention's frames, dashed.
    OtherConvention,
    /// At the target's position, the tool directions the arm can reach (a 5-axis arm
    /// reaches only some: why five joints cannot set a full pose).
    Directions,
}

impl Overlay {
    /// Every overlay, in the order of the switches.
    pub const ALL: [Overlay; 12] = [
        Overlay::JacobianColumns,
        Overlay::AngularColumns,
        Overlay::VelocityEllipsoid,
        Overlay::ForceEllipsoid,
        Overlay::NullSpace,
        Overlay::Twist,
        Overlay::Ghosts,
        Overlay::Workspace,
        Overlay::WorkspaceSlice,
        Overlay::WorkspaceSigma,
        Overlay::OtherConvention,
        Overlay::Directions,
    ];

    /// The id a link uses.
    pub fn id(self) -> &'static str {
        match self {
            Overlay::JacobianColumns => "jcols",
            Overlay::AngularColumns => "jang",
            Overlay::VelocityEllipsoid => "vel",
            Overlay::ForceEllipsoid => "force",
            Overlay::NullSpace => "null",
            Overlay::Twist => "twist",
            Overlay::Ghosts => "ghosts",
            Overlay::Workspace => "cloud",
            Overlay::WorkspaceSlice => "slice",
            Overlay::WorkspaceSigma => "sigma",
            Overlay::OtherConvention => "both",
            Overlay::Directions => "dirs",
        }
    }
}

/// A kind a [`FlagSet`] holds: a few named values with link ids.
pub trait Flag: Copy + Eq + 'static {
    /// Every value, in display order (at most 16).
    const VALUES: &'static [Self];
    /// The id a link uses.
    fn link_id(self) -> &'static str;
}

impl Flag for PanelKind {
    const VALUES: &'static [Self] = &PanelKind::ALL;
    fn link_id(self) -> &'static str {
        self.id()
    }
}

impl Flag for Overlay {
    const VALUES: &'static [Self] = &Overlay::ALL;
    fn link_id(self) -> &'static str {
        self.id()
    }
}

/// A set of flags (which panels are open, which overlays are drawn).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FlagSet<K>(u16, std::marker::PhantomData<K>);

/// Which panels are open.
pub type PanelSet = FlagSet<PanelKind>;
/// Which overlays the 3D view draws.
pub type OverlaySet = FlagSet<Overlay>;

impl<K: Flag> Default for FlagSet<K> {
    fn default() -> Self {
        Self::NONE
    }
}

impl<K: Flag> FlagSet<K> {
    /// Every value.
    pub const ALL: Self = FlagSet((1 << K::VALUES.len()) - 1, std::marker::PhantomData);
    /// None.
    pub const NONE: Self = FlagSet(0, std::marker::PhantomData);

    fn bit(kind: K) -> u16 {
        let index = K::VALUES.iter().position(|k| *k == kind).unwrap_or(0);
        1 << index
    }

    /// A set of the given values.
    pub fn of(kinds: &[K]) -> Self {
        FlagSet(
            kinds.iter().fold(0, |bits, k| bits | Self::bit(*k)),
            std::marker::PhantomData,
        )
    }

    /// Whether `kind` is in the set.
    pub fn contains(self, kind: K) -> bool {
        self.0 & Self::bit(kind) != 0
    }

    /// Adds or removes `kind`.
    pub fn set(&mut self, kind: K, on: bool) {
        if on {
            self.0 |= Self::bit(kind);
        } else {
            self.0 &= !Self::bit(kind);
        }
    }

    /// The values in the set, in display order.
    pub fn iter(self) -> impl Iterator<Item = K> {
        K::VALUES.iter().copied().filter(move |k| self.contains(*k))
    }

    /// The link form: ids joined by commas, `none` for the empty set.
    pub fn to_link(self) -> String {
        if self == Self::NONE {
            return "none".to_string();
        }
        self.iter().map(K::link_id).collect::<Vec<_>>().join(",")
    }

    /// Reads the link form; the first unknown id is the error.
    pub fn from_link(text: &str) -> Result<Self, String> {
        if text == "none" {
            return Ok(Self::NONE);
        }
        let mut set = Self::NONE;
        for id in text.split(',') {
            let kind = K::VALUES
                .iter()
                .find(|k| k.link_id() == id)
                .ok_or_else(|| id.to_string())?;
            set.set(*kind, true);
        }
        Ok(set)
    }
}

/// A matrix of the matrices panel that entries can be hidden in (predict, then reveal).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum MatrixId {
    /// The tool pose T_0n (link id `Tn`).
    Tool,
    /// The link transform A_i, i from 1 (`A3`).
    Link(usize),
    /// The running product T_0i, i from 1 (`T3`).
    Frame(usize),
}

/// One thing the lecturer hides behind a "?" until a click (presentation mode).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Hidden {
    /// A whole matrix (`A3`, `T3`, `Tn`).
    Matrix(MatrixId),
    /// One entry, row and column from 1 (`A3.14`: row 1, column 4).
    Entry(MatrixId, usize, usize),
    /// A column of the Jacobian, from 1 (`J4`).
    JacobianColumn(usize),
}

/// The largest matrix or column index a link may name.
pub const MAX_HIDDEN_INDEX: usize = 99;

impl Hidden {
    /// The link form of one item.
    pub fn to_link(self) -> String {
        let matrix = |m: MatrixId| match m {
            MatrixId::Tool => "Tn".to_string(),
            MatrixId::Link(i) => format!("A{i}"),
            MatrixId::Frame(i) => format!("T{i}"),
        };
        match self {
            Hidden::Matrix(m) => matrix(m),
            Hidden::Entry(m, r, c) => format!("{}.{r}{c}", matrix(m)),
            Hidden::JacobianColumn(c) => format!("J{c}"),
        }
    }

    /// Reads one item of the link form; `None` when it is not one.
    pub fn from_link(text: &str) -> Option<Hidden> {
        let index = |s: &str| {
            (!s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()))
                .then(|| s.parse::<usize>().ok())
                .flatten()
                .filter(|i| (1..=MAX_HIDDEN_INDEX).contains(i))
        };
        if let Some(c) = text.strip_prefix('J') {
            return index(c).map(Hidden::JacobianColumn);
        }
        let (name, entry) = match text.split_once('.') {
            Some((name, entry)) => (name, Some(entry)),
            None => (text, None),
        };
        let matrix = match name {
            "Tn" => MatrixId::Tool,
            _ => match name.split_at_checked(1)? {
                ("A", i) => MatrixId::Link(index(i)?),
                ("T", i) => MatrixId::Frame(index(i)?),
                _ => return None,
            },
        };
        let Some(entry) = entry else {
            return Some(Hidden::Matrix(matrix));
        };
        let digit = |b: u8| (b'1'..=b'4').contains(&b).then(|| usize::from(b - b'0'));
        match entry.as_bytes() {
            [r, c] => Some(Hidden::Entry(matrix, digit(*r)?, digit(*c)?)),
            _ => None,
        }
    }
}

/// What the lecturer hides (`hide=A2,T3.14,Tn,J4`): kept sorted, each item once.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct HiddenSet(Vec<Hidden>);

impl HiddenSet {
    /// Whether nothing is hidden.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// How many items are hidden.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// The items, sorted.
    pub fn items(&self) -> &[Hidden] {
        &self.0
    }

    /// Whether `item` itself is in the set.
    pub fn contains(&self, item: Hidden) -> bool {
        self.0.binary_search(&item).is_ok()
    }

    /// Adds `item`, or removes it when it is there.
    pub fn toggle(&mut self, item: Hidden) {
        match self.0.binary_search(&item) {
            Ok(i) => {
                self.0.remove(i);
            }
            Err(i) => self.0.insert(i, item),
        }
    }

    /// The link form: items joined by commas, `none` for the empty set.
    pub fn to_link(&self) -> String {
        if self.0.is_empty() {
            return "none".to_string();
        }
        self.0
            .iter()
            .map(|h| h.to_link())
            .collect::<Vec<_>>()
            .join(",")
    }

    /// Reads the link form; the first item that is not one is the error.
    pub fn from_link(text: &str) -> Result<HiddenSet, String> {
        let mut set = HiddenSet::default();
        if text == "none" {
            return Ok(set);
        }
        for item in text.split(',') {
            let hidden = Hidden::from_link(item).ok_or_else(|| item.to_string())?;
            if !set.contains(hidden) {
                set.toggle(hidden);
            }
        }
        Ok(set)
    }
}

/// Display preferences.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Angles in degrees (true) or radians.
    pub degrees: bool,
    /// Draw the DH frames (x red, y green, z blue).
    pub show_frames: bool,
    /// Decimals in the matrices.
    pub precision: usize,
    /// Large fonts and high contrast for projectors.
    pub presentation: bool,
    /// The language of the interface.
    pub lang: Lang,
    /// The panels open in the normal layout.
    pub panels: PanelSet,
    /// The panels open in presentation mode (the lecturer's choice, kept apart).
    pub presentation_panels: PanelSet,
    /// What the 3D view draws besides the arm.
    pub overlays: OverlaySet,
    /// What presentation mode hides behind a "?" until a click.
    pub hidden: HiddenSet,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            degrees: true,
            show_frames: true,
            precision: 3,
            presentation: false,
            lang: Lang::En,
            panels: PanelSet::of(&[
                PanelKind::Joints,
                PanelKind::Ik,
                PanelKind::Matrices,
                PanelKind::Robot,
            ]),
            presentation_panels: PanelSet::of(&[PanelKind::Joints, PanelKind::Matrices]),
            overlays: OverlaySet::NONE,
            hidden: HiddenSet::default(),
        }
    }
}

impl Settings {
    /// The panels open in the current mode.
    pub fn open_panels(&self) -> PanelSet {
        if self.presentation {
            self.presentation_panels
        } else {
            self.panels
        }
    }

    /// Opens or closes a panel in the current mode.
    pub fn set_panel_open(&mut self, kind: PanelKind, open: bool) {
        if self.presentation {
            self.presentation_panels.set(kind, open);
        } else {
            self.panels.set(kind, open);
        }
    }
}

/// Display settings as a link carries them: each field that the link has.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DisplayPatch {
    /// `units=deg|rad`.
    pub degrees: Option<bool>,
    /// `frames=on|off`.
    pub show_frames: Option<bool>,
    /// `decimals=0..8`.
    pub precision: Option<usize>,
    /// `present=on|off`.
    pub presentation: Option<bool>,
    /// `lang=en|fi`.
    pub lang: Option<Lang>,
    /// `panels=joints,ik,...` (or `none`).
    pub panels: Option<PanelSet>,
    /// `ppanels=...`: presentation mode's panels.
    pub presentation_panels: Option<PanelSet>,
    /// `show=jcols,jang,vel,force,null,twist,ghosts,cloud,slice,sigma,both` (or `none`): the 3D view's overlays.
    pub overlays: Option<OverlaySet>,
    /// `hide=A2,T3.14,Tn,J4`: what presentation mode hides behind a "?" (written only
    /// when something is hidden).
    pub hidden: Option<HiddenSet>,
}

/// The most decimals the matrices show.
pub const MAX_DECIMALS: usize = 8;

impl DisplayPatch {
    /// Every field of `settings`.
    pub fn of(settings: &Settings) -> DisplayPatch {
        DisplayPatch {
            degrees: Some(settings.degrees),
            show_frames: Some(settings.show_frames),
            precision: Some(settings.precision),
            presentation: Some(settings.presentation),
            lang: Some(settings.lang),
            panels: Some(settings.panels),
            presentation_panels: Some(settings.presentation_panels),
            overlays: Some(settings.overlays),
            hidden: Some(settings.hidden.clone()),
        }
    }

    /// Writes the fields it has into `settings`.
    pub fn apply(&self, settings: &mut Settings) {
        let DisplayPatch {
            degrees,
            show_frames,
            precision,
            presentation,
            lang,
            panels,
            presentation_panels,
            overlays,
            hidden,
        } = self.clone();
        settings.degrees = degrees.unwrap_or(settings.degrees);
        settings.show_frames = show_frames.unwrap_or(settings.show_frames);
        settings.precision = precision.unwrap_or(settings.precision);
        settings.presentation = presentation.unwrap_or(settings.presentation);
        settings.lang = lang.unwrap_or(settings.lang);
        settings.panels = panels.unwrap_or(settings.panels);
        settings.presentation_panels = presentation_panels.unwrap_or(settings.presentation_panels);
        settings.overlays = overlays.unwrap_or(settings.overlays);
        if let Some(hidden) = hidden {
            settings.hidden = hidden;
        }
    }

    /// The link's `key=value` parts for the fields it has.
    pub fn to_parts(&self) -> Vec<String> {
        let on = |b: bool| if b { "on" } else { "off" };
        let mut parts = Vec::new();
        if let Some(d) = self.degrees {
            parts.push(format!("units={}", if d { "deg" } else { "rad" }));
        }
        if let Some(f) = self.show_frames {
            parts.push(format!("frames={}", on(f)));
        }
        if let Some(p) = self.precision {
            parts.push(format!("decimals={p}"));
        }
        if let Some(p) = self.presentation {
            parts.push(format!("present={}", on(p)));
        }
        if let Some(l) = self.lang {
            parts.push(format!("lang={}", l.id()));
        }
        if let Some(p) = self.panels {
            parts.push(format!("panels={}", p.to_link()));
        }
        if let Some(p) = self.presentation_panels {
            parts.push(format!("ppanels={}", p.to_link()));
        }
        if let Some(o) = self.overlays {
            parts.push(format!("show={}", o.to_link()));
        }
        if let Some(h) = self.hidden.as_ref().filter(|h| !h.is_empty()) {
            parts.push(format!("hide={}", h.to_link()));
        }
        parts
    }

    /// Reads one `key=value` part if it is a display field: `Ok(true)` when read,
    /// `Ok(false)` when the key is not a display field, and the catalogue's text of the
    /// allowed values when the value is not one of them.
    pub fn read(&mut self, key: &str, value: &str) -> Result<bool, Key> {
        let switch = |v: &str| match v {
            "on" | "1" | "true" => Ok(true),
            "off" | "0" | "false" => Ok(false),
            _ => Err(Key::AllowedOnOff),
        };
        match key {
            "units" => {
                self.degrees = Some(match value {
                    "deg" => true,
                    "rad" => false,
                    _ => return Err(Key::AllowedDegRad),
                });
            }
            "frames" => self.show_frames = Some(switch(value)?),
            "present" => self.presentation = Some(switch(value)?),
            "decimals" => {
                self.precision = Some(
                    value
                        .parse()
                        .ok()
                        .filter(|d| *d <= MAX_DECIMALS)
                        .ok_or(Key::AllowedDecimals)?,
                );
            }
            "lang" => self.lang = Some(Lang::from_id(value).ok_or(Key::AllowedLang)?),
            "panels" | "ppanels" => {
                let set = PanelSet::from_link(value).map_err(|_| Key::AllowedPanels)?;
                if key == "panels" {
                    self.panels = Some(set);
                } else {
                    self.presentation_panels = Some(set);
                }
            }
            "show" => {
                self.overlays = Some(OverlaySet::from_link(value).map_err(|_| Key::AllowedShow)?);
            }
            "hide" => {
                self.hidden = Some(HiddenSet::from_link(value).map_err(|_| Key::AllowedHide)?);
            }
            _ => return Ok(false),
        }
        Ok(true)
    }
}

/// Where the camera looks from: yaw and pitch (radians), distance and focus (robot units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraPose {
    /// Angle about the world z axis.
    pub yaw: f64,
    /// Elevation above the xy plane.
    pub pitch: f64,
    /// Distance from the focus.
    pub distance: f64,
    /// The point looked at.
    pub focus: [f64; 3],
}

impl CameraPose {
    /// `[yaw, pitch, distance, x, y, z]`, the link's order.
    pub fn to_array(self) -> [f64; 6] {
        let [x, y, z] = self.focus;
        [self.yaw, self.pitch, self.distance, x, y, z]
    }

    /// From the link's six numbers; `None` unless the distance is positive.
    pub fn from_array(a: [f64; 6]) -> Option<CameraPose> {
        (a[2] > 0.0).then_some(CameraPose {
            yaw: a[0],
            pitch: a[1].clamp(-89f64.to_radians(), 89f64.to_radians()),
            distance: a[2],
            focus: [a[3], a[4], a[5]],
        })
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
    fn panel_sets_round_trip_through_the_link_form() {
        for bits in 0..32u16 {
            let set = PanelSet::of(
                &PanelKind::ALL
                    .into_iter()
                    .enumerate()
                    .filter(|(i, _)| bits & (1 << i) != 0)
                    .map(|(_, k)| k)
                    .collect::<Vec<_>>(),
            );
            assert_eq!(PanelSet::from_link(&set.to_link()), Ok(set));
        }
        assert_eq!(PanelSet::ALL.iter().count(), 5);
        assert_eq!(
            OverlaySet::from_link("jcols,vel").map(|s| s.iter().count()),
            Ok(2)
        );
        assert_eq!(OverlaySet::from_link("vel,ghost"), Err("ghost".to_string()));
        assert_eq!(PanelSet::from_link("joints,arms"), Err("arms".to_string()));
    }

    #[test]
    fn a_display_patch_round_trips_through_its_parts() {
        let settings = Settings {
            degrees: false,
            show_frames: false,
            precision: 5,
            presentation: true,
            lang: Lang::Fi,
            panels: PanelSet::of(&[PanelKind::Ik]),
            presentation_panels: PanelSet::NONE,
            overlays: OverlaySet::of(&[Overlay::JacobianColumns, Overlay::ForceEllipsoid]),
            hidden: HiddenSet::from_link("A2,T3.14,Tn,J4").expect("valid"),
        };
        let mut read = DisplayPatch::default();
        for part in DisplayPatch::of(&settings).to_parts() {
            let (k, v) = part.split_once('=').unwrap();
            assert_eq!(read.read(k, v), Ok(true), "{part}");
        }
        let mut back = Settings::default();
        read.apply(&mut back);
        assert_eq!(back, settings);
        assert_eq!(read.read("units", "grad"), Err(Key::AllowedDegRad));
        assert_eq!(read.read("decimals", "9"), Err(Key::AllowedDecimals));
        assert_eq!(read.read("q", "1"), Ok(false));
    }

    #[test]
    fn each_mode_keeps_its_own_open_panels() {
        let mut s = Settings::default();
        s.set_panel_open(PanelKind::Robot, false);
        s.presentation = true;
        assert!(!s.open_panels().contains(PanelKind::Robot));
        assert!(s.open_panels().contains(PanelKind::Joints));
        s.set_panel_open(PanelKind::Ik, true);
        s.presentation = false;
        assert!(s.open_panels().contains(PanelKind::Ik));
        assert!(!s.open_panels().contains(PanelKind::Robot));
        assert_eq!(s.presentation_panels.iter().count(), 3);
    }

    #[test]
    fn a_hidden_set_round_trips_and_names_its_first_bad_item() {
        let set = HiddenSet::from_link("J4,A2,T3.14,Tn,A2,Tn.34").expect("valid");
        assert_eq!(set.len(), 5, "A2 once");
        assert_eq!(set.to_link(), "Tn,A2,Tn.34,T3.14,J4");
        assert_eq!(HiddenSet::from_link(&set.to_link()), Ok(set.clone()));
        assert!(set.contains(Hidden::Entry(MatrixId::Frame(3), 1, 4)));
        assert!(set.contains(Hidden::JacobianColumn(4)));
        assert!(!set.contains(Hidden::Matrix(MatrixId::Frame(3))));
        for bad in [
            "A0", "A100", "T3.15", "T3.1", "X2", "J", "A2.104", "Tn.", "", "A+2", "J-1",
        ] {
            assert_eq!(
                HiddenSet::from_link(&format!("A2,{bad}")),
                Err(bad.to_string()),
                "{bad}"
            );
        }
        assert_eq!(HiddenSet::from_link("none"), Ok(HiddenSet::default()));
        let mut toggled = set;
        toggled.toggle(Hidden::JacobianColumn(4));
        toggled.toggle(Hidden::JacobianColumn(1));
        assert_eq!(toggled.to_link(), "Tn,A2,Tn.34,T3.14,J1");
    }
}
