//! Distinct solutions of arms without a closed form (docs/kinematics.md §9.7): damped
//! least squares from seeded random starts, deduplicated up to turns of 2π; for
//! redundant tasks (more joints than task rows) the solutions form a continuum, and a
//! few samples of it are kept, one per pattern of configuration signs.

use nalgebra::IsometryMatrix3;

use super::error::IkError;
use super::solver::IkSolver;
use super::{IkMethod, IkSettings, within_limits};
use crate::jacobian::Task;
use crate::rng::SplitMix64;
use crate::robot::{JointKind, Robot};

/// The most continuum samples kept (one per configuration-sign pattern).
pub const MAX_CONTINUUM_SAMPLES: usize = 8;

/// The most distinct solutions kept for a non-redundant task (a general 6R arm has up
/// to 16).
pub const MAX_DISTINCT: usize = 16;

/// Two solutions are the same when every joint differs by less than this (wrapped
/// difference; radians or length units).
pub const SAME_SOLUTION: f64 = 1e-4;

/// One solution found from a random start.
#[derive(Debug, Clone, PartialEq)]
pub struct FoundSolution {
    /// The joint vector (inside the limits, as the solver keeps it).
    pub q: Vec<f64>,
    /// The configuration signs: for each revolute joint between the first and the last,
    /// +1 when sin θ_i ≥ 0 (θ_i the DH angle, offset included), else −1. The base and
    /// flange joints turn the whole arm or the hand and are left out.
    pub signs: Vec<i8>,
    /// Every joint within its limits.
    pub within_limits: bool,
}

/// The distinct solutions of one target.
#[derive(Debug, Clone, PartialEq)]
pub struct DistinctSolutions {
    /// The solutions, sorted by their configuration signs (so equal patterns sit
    /// together).
    pub solutions: Vec<FoundSolution>,
    /// The task is redundant (more joints than task rows): the solutions are samples of
    /// a continuum, at most [`MAX_CONTINUUM_SAMPLES`], one per sign pattern.
    pub continuum: bool,
    /// Random starts tried.
    pub attempts: usize,
}

/// The configuration signs of `q` (see [`FoundSolution::signs`]).
pub fn configuration_signs(robot: &Robot, q: &[f64]) -> Vec<i8> {
    let n = robot.dof();
    robot
        .joints
        .iter()
        .zip(q)
        .enumerate()
        .filter(|(i, (j, _))| *i > 0 && *i + 1 < n && j.kind == JointKind::Revolute)
        .map(|(_, (j, v))| if (v + j.dh.theta).sin() >= 0.0 { 1 } else { -1 })
        .collect()
}

/// Runs damped least squares toward `target` for `task` from `attempts` random starts
/// within the limits (drawn from `settings.seed`; each start gets
/// `settings.max_iterations` iterations and no restarts of its own) and keeps the
/// distinct successes: those differing from every kept one by at least
/// [`SAME_SOLUTION`] in some joint (wrapped). A redundant task keeps one sample per
/// configuration-sign pattern, at most [`MAX_CONTINUUM_SAMPLES`]; a non-redundant one
/// at most [`MAX_DISTINCT`].
pub fn distinct_solutions(
    robot: &Robot,
    target: &IsometryMatrix3<f64>,
    task: Task,
    settings: &IkSettings,
    attempts: usize,
) -> Result<DistinctSolutions, IkError> {
    let continuum = robot.dof() > task.rows();
    let limit = if continuum {
        MAX_CONTINUUM_SAMPLES
    } else {
        MAX_DISTINCT
    };
    let per_start = IkSettings {
        restarts: 0,
        budget: settings.max_iterations,
        record_trace: false,
        max_joint_change: None,
        ..settings.clone()
    };
    let mut rng = SplitMix64::new(settings.seed);
    let mut solver = IkSolver::new();
    let mut found: Vec<FoundSolution> = Vec::new();
    let mut tried = 0;
    while tried < attempts && found.len() < limit {
        tried += 1;
        let start = rng.joint_vector(robot);
        let r = solver.solve(
            robot,
            target,
            task,
            &start,
            IkMethod::DampedLeastSquares,
            &per_start,
        )?;
        if !r.success {
            continue;
        }
        let same = |other: &FoundSolution| {
            robot
                .joints
                .iter()
                .zip(other.q.iter().zip(&r.q))
                .all(|(j, (a, b))| j.change(*a, *b).abs() < SAME_SOLUTION)
        };
        if found.iter().any(same) {
            continue;
        }
        let signs = configuration_signs(robot, &r.q);
        if continuum && found.iter().any(|f| f.signs == signs) {
            continue;
        }
        found.push(FoundSolution {
            within_limits: within_limits(robot, &r.q),
            q: r.q,
            signs,
        });
    }
    found.sort_by(|a, b| b.signs.cmp(&a.signs));
    Ok(DistinctSolutions {
        solutions: found,
        continuum,
        attempts: tried,
    })
}
