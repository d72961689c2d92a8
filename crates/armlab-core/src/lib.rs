//! The kinematics core: pure maths on nalgebra `f64`. No GUI, web or clock dependency:
//! it builds natively and for `wasm32-unknown-unknown`. Its errors are data; the
//! sentences people read are `armlab_text`'s.
//!
//! Data flow: [`Robot`] (a DH table) → [`ForwardKinematics`] (every A_i and T_0i) →
//! [`geometric_jacobian`] → measures and IK.

pub mod angles;
pub mod collision;
pub mod collision_wire;
pub mod convention;
pub mod edit;
pub mod error;
pub mod exercise;
pub mod exercise_wire;
pub mod file;
pub mod fk;
pub mod ik;
pub mod jacobian;
pub mod motion;
pub mod motion_error;
pub mod orientation;
pub mod parts;
pub mod path;
pub mod presets;
pub mod profile;
pub mod redundancy;
pub mod rng;
pub mod robot;
pub mod symbolic;
pub mod symbolic_jacobian;
pub mod symbolic_tables;
pub mod workspace;

pub use error::{DhColumn, Expected, Field, Place, RobotError};
pub use file::{robot_from_json, robot_from_value, robot_to_json, robot_to_value};
pub use fk::{
    ForwardKinematics, link_transform, modified_dh_transform, standard_dh_transform, tool_pose,
};
pub use ik::{
    BadTarget, Branch, BranchChoice, BranchStep, ClosedFormFamily, ClosedFormSet,
    ClosedFormSolution, DEFAULT_MAX_JOINT_CHANGE, DistinctSolutions, Elbow, FoundSolution, IkError,
    IkMethod, IkResult, IkSettings, IkSolver, IkStep, JacobianSource, MAX_CONTINUUM_SAMPLES,
    MAX_TARGET_DISTANCE, Objective, Reach, Shoulder, Wrist, branch_of, branch_step,
    closed_form_family, closed_form_solutions, distinct_solutions, drag_step, follow_branch, solve,
    wrapped_equivalent,
};
pub use jacobian::{
    JACOBIAN_AGREEMENT, JacobianAnalysis, JacobianMeasures, NUMERIC_EPSILON, SINGULARITY_THRESHOLD,
    Task, ToolAxis, geometric_jacobian, geometric_jacobian_into, jacobian_measures,
    linear_motion_space, lost_direction, numerical_jacobian, task_jacobian, tool_velocity,
};
pub use motion::{
    Controller, JointMeasures, MotionError, MotionSettings, MotionSim, PidGains, Plant, Record,
    Series, Setting,
};
pub use orientation::{AngleAxis, EulerParameters, Orientation, XyzFixed, ZyxEuler, rotation_log};
pub use presets::{PRESETS, preset, preset_ids, preset_names};
pub use profile::{JointProfile, MotionLimits, ProfileShape, Trajectory};
pub use rng::SplitMix64;
pub use robot::{
    Convention, DhRow, Joint, JointKind, JointLimits, LengthUnit, PartSizes, Robot, RobotParts,
};
pub use workspace::{
    DirectionReach, HeldAtLimit, NearestSample, WorkspaceCloud, WorkspaceMeasure,
    direction_reachability, joints_held_at_limits, linear_manipulability, linear_sigma_min,
    sphere_directions,
};
