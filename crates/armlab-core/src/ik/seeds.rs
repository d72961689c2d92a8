//! A seed table (docs/kinematics.md §8.10): a few joint vectors sampled within the limits,
//! each stored with its tool pose, so that a cold solve can start from the sampled `q`
//! whose pose is nearest the target instead of from a fixed point.
//!
//! Nearness is the solver's own weighting (§8.3): `d² = (w·‖p − p_t‖)² + (3 − tr(Rᵀ·R_t))`
//! with `w` = 4 / reach, so that a position error of a quarter of the reach weighs as one
//! radian (`3 − tr(Rᵀ·R_t) = 2(1 − cos θ) ≈ θ²` for the angle θ between the orientations).
//! The search is a linear scan over flat arrays of 12 numbers per entry (about 15
//! multiply-adds each): with a few dozen entries it costs a fraction of one iteration.

use nalgebra::IsometryMatrix3;

use crate::fk::tool_pose;
use crate::rng::SplitMix64;
use crate::robot::Robot;

/// The most entries a table may have (the scan is linear).
pub const MAX_SEED_TABLE: usize = 4096;

/// Sampled joint vectors of one robot with their tool poses; see the module docs.
#[derive(Debug, Clone, PartialEq)]
pub struct SeedTable {
    /// The joints per entry.
    dof: usize,
    /// The sampled joint vectors, `dof` numbers per entry.
    qs: Vec<f64>,
    /// Per entry: the weighted position (3 numbers) and the rotation matrix (9, by columns).
    poses: Vec<[f64; 12]>,
    /// The position weight `w`.
    weight: f64,
}

impl SeedTable {
    /// A table of `count` joint vectors (at least one, at most [`MAX_SEED_TABLE`]) drawn
    /// uniformly within `robot`'s limits with a [`SplitMix64`] seeded with `rng_seed`.
    /// Use a seed other than the one that draws the targets being solved.
    pub fn sample(robot: &Robot, count: usize, rng_seed: u64) -> SeedTable {
        let count = count.clamp(1, MAX_SEED_TABLE);
        let mut rng = SplitMix64::new(rng_seed);
        let weight = 4.0 / robot.reach();
        let mut table = SeedTable {
            dof: robot.dof(),
            qs: Vec::with_capacity(count * robot.dof()),
            poses: Vec::with_capacity(count),
            weight,
        };
        for _ in 0..count {
            let q = rng.joint_vector(robot);
            let pose = tool_pose(robot, &q);
            let p = pose.translation.vector * weight;
            let r = pose.rotation.matrix();
            let mut entry = [0.0; 12];
            entry[..3].copy_from_slice(p.as_slice());
            entry[3..].copy_from_slice(r.as_slice());
            table.poses.push(entry);
            table.qs.extend_from_slice(&q);
        }
        table
    }

    /// The number of entries.
    pub fn len(&self) -> usize {
        self.poses.len()
    }

    /// Whether the table has no entry (never, when built by [`SeedTable::sample`]).
    pub fn is_empty(&self) -> bool {
        self.poses.is_empty()
    }

    /// The joint vector of entry `k` (`None` past the end).
    pub fn q(&self, k: usize) -> Option<&[f64]> {
        self.qs.get(k * self.dof..(k + 1) * self.dof)
    }

    /// The index of the entry whose tool pose is nearest `target` (the weighted distance
    /// of the module docs) and that distance squared; `None` for an empty table or a
    /// target that is not finite.
    pub fn nearest_index(&self, target: &IsometryMatrix3<f64>) -> Option<(usize, f64)> {
        let p = target.translation.vector * self.weight;
        let r = target.rotation.matrix();
        let rt = r.as_slice();
        if !p.iter().chain(rt).all(|v| v.is_finite()) {
            return None;
        }
        let mut best: Option<(usize, f64)> = None;
        for (k, e) in self.poses.iter().enumerate() {
            let (dx, dy, dz) = (e[0] - p.x, e[1] - p.y, e[2] - p.z);
            let mut trace = 0.0;
            for (a, b) in e[3..].iter().zip(rt) {
                trace += a * b;
            }
            let d2 = dx * dx + dy * dy + dz * dz + (3.0 - trace);
            if best.is_none_or(|(_, b)| d2 < b) {
                best = Some((k, d2));
            }
        }
        best
    }

    /// The joint vector whose tool pose is nearest `target` (see
    /// [`SeedTable::nearest_index`]); `None` when there is none.
    pub fn nearest(&self, target: &IsometryMatrix3<f64>) -> Option<&[f64]> {
        self.nearest_index(target).and_then(|(k, _)| self.q(k))
    }
}
