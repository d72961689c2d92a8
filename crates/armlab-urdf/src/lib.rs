//! URDF in and out (docs/kinematics.md §16), through the `urdf-rs` crate (feature `urdf`).
//!
//! Export writes any robot as a chain of links and joints, each joint's origin the fixed
//! part of its DH transform and its axis z. Import reads a serial chain (revolute,
//! continuous, prismatic and fixed joints; fixed joints merged into their neighbours) and
//! turns it into ArmLab's one model: a standard DH table plus base and tool transforms,
//! with the same tool pose at every q. URDF lengths are metres; an imported robot is
//! written in metres.

use armlab_text::Sentence;
use nalgebra::{IsometryMatrix3, Rotation3, Translation3, Vector3};

use armlab_core::error::RobotError;
use armlab_core::robot::{
    Convention, DhRow, Joint, JointKind, JointLimits, LengthUnit, PartSizes, Robot, RobotParts,
};
use armlab_text::{Key, Lang, fill};

/// Why a URDF text does not give a robot. Every variant names the element.
#[derive(Debug, Clone, PartialEq)]
pub enum UrdfError {
    /// The text is not URDF XML (the parser's own message).
    Parse(String),
    /// A joint names a link that the file does not define.
    UnknownLink {
        /// The joint's name.
        joint: String,
        /// The missing link.
        link: String,
    },
    /// No link is the root of the chain (every link is some joint's child), or more than
    /// one is.
    NoSingleRoot,
    /// A link has more than one child joint: the robot is not a serial chain.
    Branches {
        /// The link.
        link: String,
    },
    /// A joint of a type ArmLab's chains do not have (floating, planar, spherical).
    UnsupportedJoint {
        /// The joint's name.
        joint: String,
        /// Its type as written.
        kind: String,
    },
    /// A joint's axis is the zero vector or not finite.
    BadAxis {
        /// The joint's name.
        joint: String,
    },
    /// A joint's origin holds a value that is not finite.
    BadOrigin {
        /// The joint's name.
        joint: String,
    },
    /// A prismatic joint without finite lower and upper limits.
    PrismaticWithoutLimits {
        /// The joint's name.
        joint: String,
    },
    /// The chain has no moving joint.
    NoMovingJoints,
    /// The DH table made from the file is not a valid robot.
    Robot(RobotError),
}

impl UrdfError {
    /// The error as a sentence in `lang` (from the catalogue).
    pub fn sentence(&self, lang: Lang) -> String {
        match self {
            UrdfError::Parse(message) => fill(lang, Key::UrdfParse, &[message]),
            UrdfError::UnknownLink { joint, link } => {
                fill(lang, Key::UrdfUnknownLink, &[joint, link])
            }
            UrdfError::NoSingleRoot => fill(lang, Key::UrdfNoSingleRoot, &[]),
            UrdfError::Branches { link } => fill(lang, Key::UrdfBranches, &[link]),
            UrdfError::UnsupportedJoint { joint, kind } => {
                fill(lang, Key::UrdfUnsupportedJoint, &[joint, kind])
            }
            UrdfError::BadAxis { joint } => fill(lang, Key::UrdfBadAxis, &[joint]),
            UrdfError::BadOrigin { joint } => fill(lang, Key::UrdfBadOrigin, &[joint]),
            UrdfError::PrismaticWithoutLimits { joint } => {
                fill(lang, Key::UrdfPrismaticWithoutLimits, &[joint])
            }
            UrdfError::NoMovingJoints => fill(lang, Key::UrdfNoMovingJoints, &[]),
            UrdfError::Robot(e) => e.sentence(lang),
        }
    }
}

impl std::fmt::Display for UrdfError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.sentence(Lang::En))
    }
}

impl std::error::Error for UrdfError {}

/// One step of a URDF chain: the joint's origin in its parent link, and its motion.
#[derive(Debug, Clone)]
struct Step {
    name: String,
    origin: IsometryMatrix3<f64>,
    /// `None` for a fixed joint; else the kind, the unit axis in the joint frame, limits
    /// and speed.
    motion: Option<(JointKind, Vector3<f64>, JointLimits, Option<f64>)>,
}

/// A parsed serial chain, root to leaf.
#[derive(Debug, Clone)]
pub struct UrdfChain {
    name: String,
    steps: Vec<Step>,
}

impl UrdfChain {
    /// Parses a URDF text and finds its serial chain.
    pub fn parse(text: &str) -> Result<Self, UrdfError> {
        let urdf = urdf_rs::read_from_string(text).map_err(|e| UrdfError::Parse(e.to_string()))?;
        let links: Vec<&str> = urdf.links.iter().map(|l| l.name.as_str()).collect();
        for j in &urdf.joints {
            for link in [&j.parent.link, &j.child.link] {
                if !links.contains(&link.as_str()) {
                    return Err(UrdfError::UnknownLink {
                        joint: j.name.clone(),
                        link: link.clone(),
                    });
                }
            }
        }
        let roots: Vec<&str> = links
            .iter()
            .copied()
            .filter(|l| !urdf.joints.iter().any(|j| j.child.link == *l))
            .collect();
        let [root] = roots.as_slice() else {
            return Err(UrdfError::NoSingleRoot);
        };
        let mut steps = Vec::new();
        let mut link = root.to_string();
        loop {
            let children: Vec<&urdf_rs::Joint> = urdf
                .joints
                .iter()
                .filter(|j| j.parent.link == link)
                .collect();
            let joint = match children.as_slice() {
                [] => break,
                [joint] => *joint,
                _ => return Err(UrdfError::Branches { link }),
            };
            if steps.len() > urdf.joints.len() {
                return Err(UrdfError::NoSingleRoot);
            }
            steps.push(step(joint)?);
            link = joint.child.link.clone();
        }
        if !steps.iter().any(|s| s.motion.is_some()) {
            return Err(UrdfError::NoMovingJoints);
        }
        Ok(UrdfChain {
            name: urdf.name,
            steps,
        })
    }

    /// The number of moving joints.
    pub fn dof(&self) -> usize {
        self.steps.iter().filter(|s| s.motion.is_some()).count()
    }

    /// The leaf link's pose in the root link at `q` (one value per moving joint, in
    /// chain order; radians and metres), computed on the URDF's own joints.
    pub fn tool_pose(&self, q: &[f64]) -> IsometryMatrix3<f64> {
        let mut pose = IsometryMatrix3::identity();
        let mut k = 0;
        for s in &self.steps {
            pose *= s.origin;
            if let Some((kind, axis, _, _)) = &s.motion {
                let v = q.get(k).copied().unwrap_or(0.0);
                k += 1;
                pose *= motion(*kind, axis, v);
            }
        }
        pose
    }
}

fn motion(kind: JointKind, axis: &Vector3<f64>, v: f64) -> IsometryMatrix3<f64> {
    match kind {
        JointKind::Revolute => IsometryMatrix3::from_parts(
            Translation3::identity(),
            Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(*axis), v),
        ),
        JointKind::Prismatic => {
            IsometryMatrix3::from_parts(Translation3::from(axis * v), Rotation3::identity())
        }
    }
}

fn step(j: &urdf_rs::Joint) -> Result<Step, UrdfError> {
    let [x, y, z] = j.origin.xyz.0;
    let [r, p, yaw] = j.origin.rpy.0;
    if ![x, y, z, r, p, yaw].iter().all(|v| v.is_finite()) {
        return Err(UrdfError::BadOrigin {
            joint: j.name.clone(),
        });
    }
    let origin = IsometryMatrix3::from_parts(
        Translation3::new(x, y, z),
        Rotation3::from_euler_angles(r, p, yaw),
    );
    let axis = Vector3::from(j.axis.xyz.0);
    let unit = || {
        let n = axis.norm();
        if n.is_finite() && n > 1e-12 {
            Ok(axis / n)
        } else {
            Err(UrdfError::BadAxis {
                joint: j.name.clone(),
            })
        }
    };
    let speed =
        (j.limit.velocity.is_finite() && j.limit.velocity > 0.0).then_some(j.limit.velocity);
    let (lower, upper) = (j.limit.lower, j.limit.upper);
    let finite = lower.is_finite() && upper.is_finite() && upper > lower;
    let motion = match j.joint_type {
        urdf_rs::JointType::Fixed => None,
        urdf_rs::JointType::Revolute => {
            let limits = if finite {
                JointLimits {
                    min: lower,
                    max: upper,
                }
            } else {
                JointLimits::FULL_TURN
            };
            Some((JointKind::Revolute, unit()?, limits, speed))
        }
        urdf_rs::JointType::Continuous => {
            Some((JointKind::Revolute, unit()?, JointLimits::FULL_TURN, speed))
        }
        urdf_rs::JointType::Prismatic => {
            if !finite {
                return Err(UrdfError::PrismaticWithoutLimits {
                    joint: j.name.clone(),
                });
            }
            let limits = JointLimits {
                min: lower,
                max: upper,
            };
            Some((JointKind::Prismatic, unit()?, limits, speed))
        }
        ref other => {
            return Err(UrdfError::UnsupportedJoint {
                joint: j.name.clone(),
                kind: format!("{other:?}").to_lowercase(),
            });
        }
    };
    Ok(Step {
        name: j.name.clone(),
        origin,
        motion,
    })
}

/// A frame from its origin and unit x and z axes.
fn frame(o: Vector3<f64>, x: Vector3<f64>, z: Vector3<f64>) -> IsometryMatrix3<f64> {
    let y = z.cross(&x);
    IsometryMatrix3::from_parts(
        Translation3::from(o),
        Rotation3::from_matrix_unchecked(nalgebra::Matrix3::from_columns(&[x, y, z])),
    )
}

/// A value within 1e−12 of 0 made 0 (rounding residue of the construction).
fn clean(v: f64) -> f64 {
    if v.abs() <= 1e-12 { 0.0 } else { v }
}

/// The robot a URDF text describes (docs/kinematics.md §16.2): a standard DH table whose
/// joint axes are the URDF's, frame 0 on joint 1's axis (the base transform), and the
/// leaf link as the tool; lengths in metres. Fixed joints are merged; parallel axes get
/// d = 0 on the common normal through the previous origin; intersecting axes get a = 0
/// and x along z_{i−1} × z_i.
pub fn robot_from_urdf(text: &str) -> Result<Robot, UrdfError> {
    robot_from_chain(&UrdfChain::parse(text)?)
}

/// The robot of an already parsed chain; see [`robot_from_urdf`].
pub fn robot_from_chain(chain: &UrdfChain) -> Result<Robot, UrdfError> {
    let (axes, leaf) = axis_lines(chain);
    let Some(first) = axes.first() else {
        return Err(UrdfError::NoMovingJoints);
    };
    let z0 = first.u;
    let (mut o, mut x) = frame_zero(first);
    let base = frame(o, x, z0);
    let scale = axes
        .iter()
        .map(|a| a.p.norm())
        .fold(leaf.translation.vector.norm(), f64::max)
        .max(1.0);
    let mut joints = Vec::with_capacity(axes.len());
    for (i, axis) in axes.iter().enumerate() {
        let (dh, next_x, next_o) = match axes.get(i + 1) {
            Some(next) => dh_row_to(o, x, axis.u, next, scale),
            // The last frame: frame n−1 turned (or slid) by the joint, nothing more.
            None => (dh_row(0.0, 0.0, 0.0, 0.0), x, o),
        };
        joints.push(joint_on(axis, dh));
        x = next_x;
        o = next_o;
    }
    // Frame n at q = 0 is frame n−1 (the last row is zero); the tool is the leaf in it.
    let last = frame(o, x, axes.last().map_or(z0, |a| a.u));
    let robot = Robot {
        name: if chain.name.is_empty() {
            "URDF".to_string()
        } else {
            chain.name.clone()
        },
        description: String::new(),
        convention: Convention::Standard,
        length_unit: LengthUnit::Metre,
        joints,
        world_from_base: base,
        flange_from_tool: last.inverse() * leaf,
        parts: RobotParts::default(),
        keep_outs: Vec::new(),
    };
    robot.validated().map_err(UrdfError::Robot)
}

/// A moving joint's axis line at q = 0 in the root frame.
struct Axis {
    name: String,
    kind: JointKind,
    /// A point on the line.
    p: Vector3<f64>,
    /// Its unit direction.
    u: Vector3<f64>,
    limits: JointLimits,
    speed: Option<f64>,
}

/// The chain's moving joints' axis lines, and the leaf link's pose, at q = 0.
fn axis_lines(chain: &UrdfChain) -> (Vec<Axis>, IsometryMatrix3<f64>) {
    let mut pose = IsometryMatrix3::identity();
    let mut axes = Vec::new();
    for s in &chain.steps {
        pose *= s.origin;
        if let Some((kind, axis, limits, speed)) = &s.motion {
            axes.push(Axis {
                name: s.name.clone(),
                kind: *kind,
                p: pose.translation.vector,
                u: pose.rotation * axis,
                limits: *limits,
                speed: *speed,
            });
        }
    }
    (axes, pose)
}

/// Frame 0's origin and x: z on joint 1's axis, the origin the foot of the root's origin
/// on it, x the root's x (or y) made perpendicular.
fn frame_zero(first: &Axis) -> (Vector3<f64>, Vector3<f64>) {
    let z0 = first.u;
    let o = first.p - z0 * first.p.dot(&z0);
    let ex = Vector3::x() - z0 * z0.x;
    let x = if ex.norm() > 1e-6 {
        ex.normalize()
    } else {
        (Vector3::y() - z0 * z0.y).normalize()
    };
    (o, x)
}

/// The DH row from the frame at `o` (x axis `x`, z axis `z`) to the next joint's axis
/// line, and the next frame's x and origin.
fn dh_row_to(
    o: Vector3<f64>,
    x: Vector3<f64>,
    z: Vector3<f64>,
    next: &Axis,
    scale: f64,
) -> (DhRow, Vector3<f64>, Vector3<f64>) {
    let (f1, f2, xi) = common_normal(o, x, z, next, scale);
    let dh = dh_row(
        x.cross(&xi).dot(&z).atan2(x.dot(&xi)),
        (f1 - o).dot(&z),
        (f2 - f1).dot(&xi),
        z.cross(&next.u).dot(&xi).atan2(z.dot(&next.u)),
    );
    (dh, xi, f2)
}

/// The common normal of the line through `o` along `z` and the next axis line: its feet
/// on both and its direction (the next frame's x). Parallel lines take the normal
/// through `o` (d = 0); lines that meet take x along z × z_next.
fn common_normal(
    o: Vector3<f64>,
    x: Vector3<f64>,
    z: Vector3<f64>,
    next: &Axis,
    scale: f64,
) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let n = z.cross(&next.u);
    if n.norm() > 1e-9 {
        // The common normal's feet on both lines.
        let w = o - next.p;
        let b = z.dot(&next.u);
        let (dd, e) = (z.dot(&w), next.u.dot(&w));
        let den = 1.0 - b * b;
        let f1 = o + z * ((b * e - dd) / den);
        let f2 = next.p + next.u * ((e - b * dd) / den);
        let gap = f2 - f1;
        let xi = if gap.norm() > 1e-9 * scale {
            gap.normalize()
        } else {
            n.normalize()
        };
        (f1, f2, xi)
    } else {
        // Parallel: the normal through the current origin (d = 0).
        let v = next.p - o;
        let perp = v - z * v.dot(&z);
        if perp.norm() > 1e-9 * scale {
            (o, o + perp, perp.normalize())
        } else {
            (o, o, x)
        }
    }
}

/// A DH row with values within 10⁻¹² of zero made zero.
fn dh_row(theta: f64, d: f64, a: f64, alpha: f64) -> DhRow {
    DhRow {
        theta: clean(theta),
        d: clean(d),
        a: clean(a),
        alpha: clean(alpha),
    }
}

/// The joint on `axis` with row `dh`, at home at 0 (or mid-range when 0 is outside its
/// limits).
fn joint_on(axis: &Axis, dh: DhRow) -> Joint {
    let home = if axis.limits.contains(0.0, 0.0) {
        0.0
    } else {
        axis.limits.mid()
    };
    Joint {
        name: axis.name.clone(),
        kind: axis.kind,
        dh,
        limits: axis.limits,
        max_speed: axis.speed,
        max_acceleration: None,
        home,
        parts: PartSizes::default(),
    }
}

/// The fixed parts around joint i's motion: `A_i = before · motion(q) · after`.
fn split_link(robot: &Robot, joint: &Joint) -> (IsometryMatrix3<f64>, IsometryMatrix3<f64>) {
    let m = robot.length_unit.in_metres();
    let rz = |t: f64| {
        IsometryMatrix3::from_parts(
            Translation3::identity(),
            Rotation3::from_axis_angle(&Vector3::z_axis(), t),
        )
    };
    let tz = |d: f64| {
        IsometryMatrix3::from_parts(Translation3::new(0.0, 0.0, d * m), Rotation3::identity())
    };
    let link = armlab_core::convention::link_part(joint.dh.a * m, joint.dh.alpha);
    match (robot.convention, joint.kind) {
        (Convention::Standard, JointKind::Revolute) => (rz(joint.dh.theta), tz(joint.dh.d) * link),
        (Convention::Standard, JointKind::Prismatic) => (rz(joint.dh.theta) * tz(joint.dh.d), link),
        (Convention::Modified, JointKind::Revolute) => (link * rz(joint.dh.theta), tz(joint.dh.d)),
        (Convention::Modified, JointKind::Prismatic) => (
            link * rz(joint.dh.theta) * tz(joint.dh.d),
            IsometryMatrix3::identity(),
        ),
    }
}

fn pose(iso: &IsometryMatrix3<f64>) -> urdf_rs::Pose {
    let t = iso.translation.vector;
    let (r, p, y) = iso.rotation.euler_angles();
    urdf_rs::Pose {
        xyz: urdf_rs::Vec3([clean(t.x), clean(t.y), clean(t.z)]),
        rpy: urdf_rs::Vec3([clean(r), clean(p), clean(y)]),
    }
}

fn link(name: String) -> urdf_rs::Link {
    urdf_rs::Link {
        name,
        inertial: urdf_rs::Inertial::default(),
        visual: Vec::new(),
        collision: Vec::new(),
    }
}

/// `robot` as a URDF text (docs/kinematics.md §16.1), lengths in metres: links `base`,
/// `link1` … `linkN` and `tool`; joint i (named as the robot's joint) turns or slides
/// about z of its frame, its origin the fixed part of the DH transforms between joint
/// i−1's motion and joint i's; a fixed joint `tool_joint` places the tool.
pub fn robot_to_urdf(robot: &Robot) -> Result<String, UrdfError> {
    let n = robot.dof();
    let m = robot.length_unit.in_metres();
    let mut links = vec![link("base".to_string())];
    let mut joints = Vec::with_capacity(n + 1);
    let link_name = |i: usize| {
        if i == 0 {
            "base".to_string()
        } else {
            format!("link{i}")
        }
    };
    let mut base = robot.world_from_base;
    base.translation.vector *= m;
    let mut before = base;
    for (i, joint) in robot.joints.iter().enumerate() {
        let (pre, post) = split_link(robot, joint);
        let origin = before * pre;
        let (joint_type, limit) = match joint.kind {
            JointKind::Revolute => (urdf_rs::JointType::Revolute, (1.0, 1.0)),
            JointKind::Prismatic => (urdf_rs::JointType::Prismatic, (m, m)),
        };
        links.push(link(link_name(i + 1)));
        joints.push(urdf_rs::Joint {
            name: joint.name.clone(),
            joint_type,
            origin: pose(&origin),
            parent: urdf_rs::LinkName { link: link_name(i) },
            child: urdf_rs::LinkName {
                link: link_name(i + 1),
            },
            axis: urdf_rs::Axis {
                xyz: urdf_rs::Vec3([0.0, 0.0, 1.0]),
            },
            limit: urdf_rs::JointLimit {
                lower: joint.limits.min * limit.0,
                upper: joint.limits.max * limit.1,
                effort: 0.0,
                velocity: joint.max_speed.map_or(1.0, |v| v * limit.0),
                ..urdf_rs::JointLimit::default()
            },
            calibration: None,
            dynamics: None,
            mimic: None,
            safety_controller: None,
        });
        before = post;
    }
    let mut tool = robot.flange_from_tool;
    tool.translation.vector *= m;
    links.push(link("tool".to_string()));
    joints.push(urdf_rs::Joint {
        name: "tool_joint".to_string(),
        joint_type: urdf_rs::JointType::Fixed,
        origin: pose(&(before * tool)),
        parent: urdf_rs::LinkName { link: link_name(n) },
        child: urdf_rs::LinkName {
            link: "tool".to_string(),
        },
        axis: urdf_rs::Axis::default(),
        limit: urdf_rs::JointLimit::default(),
        calibration: None,
        dynamics: None,
        mimic: None,
        safety_controller: None,
    });
    let urdf = urdf_rs::Robot {
        name: robot.name.clone(),
        version: None,
        links,
        joints,
        materials: Vec::new(),
    };
    urdf_rs::write_to_string(&urdf).map_err(|e| UrdfError::Parse(e.to_string()))
}

/// How many of a URDF text's link visuals are meshes (0 when it does not parse).
pub fn mesh_visuals(urdf: &str) -> usize {
    urdf_rs::read_from_string(urdf).map_or(0, |robot| {
        robot
            .links
            .iter()
            .flat_map(|link| &link.visual)
            .filter(|visual| matches!(visual.geometry, urdf_rs::Geometry::Mesh { .. }))
            .count()
    })
}
