//! The branch labels of the closed forms (docs/kinematics.md §9.6): which shoulder, elbow
//! and wrist a solution uses.

/// Which of the two base angles a solution uses (Lee's "arm" indicator).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Shoulder {
    /// The wrist point lies in front of the shoulder along the arm plane's x axis
    /// (`o_w · x_1 ≥ 0`): the first root `θ1 = φ + asin(σ1·D/ρ)`.
    Right,
    /// The wrist point lies behind it (`o_w · x_1 < 0`): the second root
    /// `θ1 = φ + π − asin(σ1·D/ρ)`, the arm reaching over its back.
    Left,
}

/// Which of the two planar 2R solutions a solution uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Elbow {
    /// The elbow lies above the line from the shoulder to the wrist (vertical arms), or
    /// `sin θ_elbow < 0` for links of positive length (horizontal arms: the planar 2R and
    /// the SCARA, where "up" is the textbook's name for that sign).
    Up,
    /// The elbow lies below that line (or `sin θ_elbow > 0`).
    Down,
}

/// Which of the two wrist solutions a solution uses (6-axis arms).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Wrist {
    /// `sin θ5 ≥ 0` (θ5 the DH angle of the wrist's middle joint, its offset included).
    NotFlipped,
    /// `sin θ5 < 0`: the wrist turned over, θ4 and θ6 half a turn away.
    Flipped,
}

/// The branch of a closed-form solution: one choice per binary decision of the family.
/// A field is `None` when the family has no such decision (the planar 2R has no shoulder
/// or wrist; the RRR arm and the SCARA have no wrist; the Stanford arm has no elbow).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Branch {
    /// The base angle's root.
    pub shoulder: Option<Shoulder>,
    /// The elbow's side.
    pub elbow: Option<Elbow>,
    /// The wrist's flip.
    pub wrist: Option<Wrist>,
}

impl Branch {
    /// A machine id: the parts present, joined by `-`: shoulder `right`/`left`, elbow
    /// `up`/`down`, wrist `noflip`/`flip` (`"right-up-noflip"`, `"down"`). The app
    /// translates the parts; this id is for links, the JSON API and tests.
    pub fn id(&self) -> String {
        let mut parts: Vec<&str> = Vec::with_capacity(3);
        if let Some(s) = self.shoulder {
            parts.push(match s {
                Shoulder::Right => "right",
                Shoulder::Left => "left",
            });
        }
        if let Some(e) = self.elbow {
            parts.push(match e {
                Elbow::Up => "up",
                Elbow::Down => "down",
            });
        }
        if let Some(w) = self.wrist {
            parts.push(match w {
                Wrist::NotFlipped => "noflip",
                Wrist::Flipped => "flip",
            });
        }
        parts.join("-")
    }

    /// The branch of an id written by [`Branch::id`]; `None` for an unknown part.
    pub fn from_id(id: &str) -> Option<Branch> {
        let mut b = Branch::default();
        for part in id.split('-').filter(|p| !p.is_empty()) {
            match part {
                "right" => b.shoulder = Some(Shoulder::Right),
                "left" => b.shoulder = Some(Shoulder::Left),
                "up" => b.elbow = Some(Elbow::Up),
                "down" => b.elbow = Some(Elbow::Down),
                "noflip" => b.wrist = Some(Wrist::NotFlipped),
                "flip" => b.wrist = Some(Wrist::Flipped),
                _ => return None,
            }
        }
        Some(b)
    }
}
