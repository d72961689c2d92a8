//! Self-collision, the floor and keep-out boxes (docs/kinematics.md §20), checked on the
//! arm's parts ([`crate::parts`]) with the parry collision library (its
//! 64-bit build, `parry3d-f64`).
//!
//! - Two parts are checked against each other when their bodies are not neighbours: a
//!   joint's two sides always touch at the joint. A body without a link of its own (both
//!   DH offsets zero, as the UR10's shoulder or a spherical wrist) sits inside the joint
//!   before it, so neighbours are counted over the bodies that have a link: bodies i < j
//!   are neighbours when at most one body in i+1..=j has a link part ([`body_ranks`]).
//! - Parts count as touching when they overlap by more than a tolerance: each part is
//!   shrunk by [`TOUCH_TOLERANCE`] × the arm's reach on every side, so parts drawn
//!   exactly side by side (the Metrover's links, sized from the real arm) do not touch.
//! - The floor is the plane z = 0 of the world (the drawn ground grid), solid below. The
//!   base stands in it and the first moving body turns on the base, so the floor is
//!   checked against bodies of rank 2 and up. (An arm drawn in the plane z = 0, the
//!   planar 2R, always lies on the floor: switch the floor off for it.)
//! - Keep-out boxes are checked against every part except the base's.
//!
//! A bounding-sphere test skips pairs that are far apart before parry's exact test.

use nalgebra::{Point3, Rotation3, UnitQuaternion, Vector3};
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::query::intersection_test;
use parry3d_f64::shape::{Cuboid, Cylinder, HalfSpace, Shape};

use super::fk::ForwardKinematics;
use super::motion_error::{MotionError, Setting};
use super::parts::{Part, PartKind, PartShape, robot_parts_into};
use super::robot::Robot;
pub use super::robot::{KeepOut, MAX_KEEP_OUTS};

/// How far two parts may overlap before they count as touching, as a fraction of the
/// arm's reach (each part is shrunk by this on every side): 0.2 %, 2.6 mm on the UR10.
pub const TOUCH_TOLERANCE: f64 = 0.002;

impl KeepOut {
    /// An axis-aligned box, checked: every number finite and at most 10⁶ in size, every
    /// extent above zero. `index` (1-based) names the box in the error.
    pub fn new(
        index: usize,
        centre: Point3<f64>,
        size: Vector3<f64>,
    ) -> Result<KeepOut, MotionError> {
        let setting = Setting::KeepOut(index);
        for v in centre.iter() {
            if !v.is_finite() {
                return Err(MotionError::NotFinite { setting, value: *v });
            }
            if v.abs() > 1e6 {
                return Err(MotionError::TooLarge {
                    setting,
                    value: *v,
                    max: 1e6,
                });
            }
        }
        for v in size.iter() {
            super::motion_error::check_positive(setting, *v, 1e6)?;
        }
        Ok(KeepOut {
            centre,
            size,
            rotation: Rotation3::identity(),
        })
    }
}

/// What a part touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Obstacle {
    /// Another part of the arm (its index in the part list).
    Part(usize),
    /// The floor.
    Floor,
    /// A keep-out box (its index in the list, 0-based).
    KeepOut(usize),
}

/// One contact: part `part` (its index in the part list) touches `other`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Contact {
    /// The part's index in the list the check was given.
    pub part: usize,
    /// What it touches.
    pub other: Obstacle,
}

/// The result of one check.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CollisionReport {
    /// Every contact found, in part order.
    pub contacts: Vec<Contact>,
    /// One flag per part: whether it touches anything (the renderer draws it red).
    pub colliding: Vec<bool>,
    /// Pairs given to parry's exact test (after the bounding-sphere test).
    pub exact_tests: usize,
}

impl CollisionReport {
    /// Whether nothing touches.
    pub fn is_free(&self) -> bool {
        self.contacts.is_empty()
    }
}

/// A part as parry sees it.
enum Solid {
    Box(Cuboid),
    Cylinder(Cylinder),
}

impl Solid {
    fn shape(&self) -> &dyn Shape {
        match self {
            Solid::Box(c) => c,
            Solid::Cylinder(c) => c,
        }
    }
}

fn pose(centre: &Point3<f64>, rotation: &Rotation3<f64>) -> Pose {
    let q = UnitQuaternion::from_rotation_matrix(rotation);
    Pose::from_parts(
        Vector::new(centre.x, centre.y, centre.z),
        Rotation::from_xyzw(q.i, q.j, q.k, q.w),
    )
}

/// The parry shape and pose of a part. Parry's cylinders run along their local y, ours
/// along z: the pose turns y onto z with a quarter turn about x.
fn solid(part: &Part, shrink: f64) -> (Solid, Pose) {
    let size = part.size.map(|v| (v - 2.0 * shrink).max(v * 0.5));
    match part.shape {
        PartShape::Box => (
            Solid::Box(Cuboid::new(Vector::new(
                size.x * 0.5,
                size.y * 0.5,
                size.z * 0.5,
            ))),
            pose(&part.centre, &part.rotation),
        ),
        PartShape::Cylinder => {
            let y_to_z =
                Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2);
            (
                Solid::Cylinder(Cylinder::new(size.z * 0.5, size.x * 0.5)),
                pose(&part.centre, &(part.rotation * y_to_z)),
            )
        }
    }
}

/// Half the diagonal: a sphere around the centre holding the whole part.
fn bounding_radius(size: &Vector3<f64>) -> f64 {
    0.5 * size.norm()
}

/// Whether two parry solids overlap or touch. Parry answers every pair of boxes,
/// cylinders and half-spaces; an unsupported pair would count as touching (the safe side).
fn touching(pa: &Pose, a: &dyn Shape, pb: &Pose, b: &dyn Shape) -> bool {
    intersection_test(pa, a, pb, b).map_or(true, |r| r.intersecting)
}

/// The collision check of one scene: the floor (on or off) and the keep-out boxes. It
/// keeps a part list and reuses it, so checking a pose allocates only on the first call.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CollisionChecker {
    /// Check the floor at z = 0.
    pub floor: bool,
    keep_outs: Vec<KeepOut>,
    parts: Vec<Part>,
}

impl CollisionChecker {
    /// A checker with the floor on or off and these keep-out boxes (at most
    /// [`MAX_KEEP_OUTS`]).
    pub fn new(floor: bool, keep_outs: Vec<KeepOut>) -> Result<CollisionChecker, MotionError> {
        if keep_outs.len() > MAX_KEEP_OUTS {
            return Err(MotionError::TooLarge {
                setting: Setting::KeepOut(keep_outs.len()),
                value: keep_outs.len() as f64,
                max: MAX_KEEP_OUTS as f64,
            });
        }
        Ok(CollisionChecker {
            floor,
            keep_outs,
            parts: Vec::new(),
        })
    }

    /// The keep-out boxes.
    pub fn keep_outs(&self) -> &[KeepOut] {
        &self.keep_outs
    }

    /// The parts of the last [`CollisionChecker::check`], for naming contacts.
    pub fn parts(&self) -> &[Part] {
        &self.parts
    }

    /// Derives the parts of `robot` at the frames `fk` and checks them, with the
    /// tolerance [`TOUCH_TOLERANCE`] × the reach.
    pub fn check(&mut self, robot: &Robot, fk: &ForwardKinematics) -> CollisionReport {
        self.check_with(robot, fk, |checker, parts, tolerance| {
            Some(checker.check_parts(parts, tolerance))
        })
        .unwrap_or_default()
    }

    /// As [`CollisionChecker::check`], with the parts checked by `check` (given this
    /// checker, the parts and the tolerance): the page sends them to the module that holds
    /// the collision library ([`super::collision_wire`]), which may not be there yet
    /// (`None`).
    pub fn check_with(
        &mut self,
        robot: &Robot,
        fk: &ForwardKinematics,
        check: impl FnOnce(&CollisionChecker, &[Part], f64) -> Option<CollisionReport>,
    ) -> Option<CollisionReport> {
        let mut parts = std::mem::take(&mut self.parts);
        robot_parts_into(robot, fk, &mut parts);
        let report = check(self, &parts, TOUCH_TOLERANCE * robot.reach());
        self.parts = parts;
        report
    }

    /// Checks a list of parts, each shrunk by `tolerance` on every side: non-neighbouring
    /// pairs, the floor, the keep-out boxes.
    pub fn check_parts(&self, parts: &[Part], tolerance: f64) -> CollisionReport {
        let shrink = if tolerance.is_finite() {
            tolerance.max(0.0)
        } else {
            0.0
        };
        let solids: Vec<(Solid, Pose)> = parts.iter().map(|p| solid(p, shrink)).collect();
        let rank = body_ranks(parts);
        let rank_of = |body: usize| rank.get(body).copied().unwrap_or(0);
        let mut report = CollisionReport {
            contacts: Vec::new(),
            colliding: vec![false; parts.len()],
            exact_tests: 0,
        };
        let floor = HalfSpace::new(Vector::Z);
        let floor_pose = Pose::IDENTITY;
        let zones: Vec<(Cuboid, Pose, f64)> = self
            .keep_outs
            .iter()
            .map(|k| {
                (
                    Cuboid::new(Vector::new(k.size.x * 0.5, k.size.y * 0.5, k.size.z * 0.5)),
                    pose(&k.centre, &k.rotation),
                    bounding_radius(&k.size),
                )
            })
            .collect();
        for (i, a) in parts.iter().enumerate() {
            let (sa, pa) = &solids[i];
            let ra = bounding_radius(&a.size);
            for (j, b) in parts.iter().enumerate().skip(i + 1) {
                if rank_of(a.body).abs_diff(rank_of(b.body)) < 2 {
                    continue;
                }
                if (a.centre - b.centre).norm() > ra + bounding_radius(&b.size) {
                    continue;
                }
                report.exact_tests += 1;
                let (sb, pb) = &solids[j];
                if touching(pa, sa.shape(), pb, sb.shape()) {
                    report.contacts.push(Contact {
                        part: i,
                        other: Obstacle::Part(j),
                    });
                    report.colliding[i] = true;
                    report.colliding[j] = true;
                }
            }
            if self.floor && rank_of(a.body) >= 2 && a.centre.z - ra <= 0.0 {
                report.exact_tests += 1;
                if touching(pa, sa.shape(), &floor_pose, &floor) {
                    report.contacts.push(Contact {
                        part: i,
                        other: Obstacle::Floor,
                    });
                    report.colliding[i] = true;
                }
            }
            if a.body == 0 {
                continue;
            }
            for (k, (zone, pz, rz)) in zones.iter().enumerate() {
                let zc = &self.keep_outs[k].centre;
                if (a.centre - zc).norm() > ra + rz {
                    continue;
                }
                report.exact_tests += 1;
                if touching(pa, sa.shape(), pz, zone) {
                    report.contacts.push(Contact {
                        part: i,
                        other: Obstacle::KeepOut(k),
                    });
                    report.colliding[i] = true;
                }
            }
        }
        report
    }
}

/// Each body's rank: the number of bodies from 1 up to it that have a link part (body 0,
/// the base, has rank 0). Bodies whose ranks differ by less than two are neighbours.
pub fn body_ranks(parts: &[Part]) -> Vec<usize> {
    let bodies = parts.iter().map(|p| p.body).max().map_or(1, |b| b + 1);
    let mut has_link = vec![false; bodies];
    for p in parts {
        if p.kind == PartKind::Link {
            has_link[p.body] = true;
        }
    }
    let mut rank = vec![0; bodies];
    for b in 1..bodies {
        rank[b] = rank[b - 1] + usize::from(has_link[b]);
    }
    rank
}
