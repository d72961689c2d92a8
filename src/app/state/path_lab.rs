//! The motion lab's paths and waypoints in the app (docs/kinematics.md §19): the
//! path kind the arm travels by (joint space or a straight Cartesian line), the waypoint
//! list, the two planned paths drawn side by side, and a visit of the waypoints that the
//! motion simulation drives in time. No egui here: the model owns one [`PathLab`] and the
//! Motion panel draws it.
//!
//! A visit follows its planned path with a "carrot": the simulation's goal is a point of
//! the path a little ahead of the arm ([`LOOKAHEAD`] in joint space), moved on as the arm
//! catches up, and held at each waypoint until the arm has arrived there
//! ([`STOP_ERROR`]), so every waypoint is reached, not cut short.

use nalgebra::IsometryMatrix3;

use armlab_core::Robot;
use armlab_core::ik::IkSolver;
use armlab_core::motion::MotionError;
use armlab_core::path::{CartesianSettings, Path, PathKind, Waypoints, joint_gap, waypoint_path};

/// How far ahead of the arm (the largest joint distance, radians; a prismatic joint this
/// fraction of π of its stroke) the goal of a visit runs along the path.
pub const LOOKAHEAD: f64 = 0.05;
/// A visit moves on from a waypoint when every joint is this close to it (radians or
/// units; the on/off controller's dead band when that is larger).
pub const STOP_ERROR: f64 = 1e-3;

/// The two planned paths from the arm: through the waypoints, or to the target when
/// there are none.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Interpolated in joint space.
    pub joint: Path,
    /// The straight line with slerped orientation, by IK at every step.
    pub line: Path,
}

/// What a plan is made from: q, the waypoints (the target when none), the robot's change
/// count.
type PlanInputs = (Vec<f64>, Vec<IsometryMatrix3<f64>>, u64);

/// A visit under way: its path, the index of the path point that is the goal now, and
/// the indices of the waypoints (where the visit waits for the arm).
#[derive(Debug, Clone, PartialEq)]
pub struct Visit {
    /// The path followed.
    pub path: Path,
    /// The goal's index in the path.
    pub index: usize,
    stops: Vec<usize>,
    /// The joint values the visit last left the arm at (anything else moving the arm
    /// ends the visit).
    last_q: Vec<f64>,
    /// The robot-change count the path was planned for.
    robot_changes: u64,
}

impl Visit {
    /// Whether the goal is the path's last point.
    pub fn at_end(&self) -> bool {
        self.index + 1 >= self.path.points.len()
    }

    /// The waypoints passed (the goal is past their point).
    pub fn passed(&self) -> usize {
        self.stops.iter().filter(|s| **s < self.index).count()
    }
}

/// The path lab's state.
#[derive(Debug, Clone, Default)]
pub struct PathLab {
    kind: PathKind,
    waypoints: Waypoints,
    shown: bool,
    plan: Option<Plan>,
    /// The inputs of the last planning, whether it gave a plan or not (a list that cannot
    /// be planned is not planned again every frame).
    planned_from: Option<PlanInputs>,
    visit: Option<Visit>,
    /// The last visit ran to its end (kept until the next one or a change).
    finished: bool,
}

impl PathLab {
    /// How the arm goes from one pose to the next.
    pub fn kind(&self) -> PathKind {
        self.kind
    }

    /// Chooses the path kind (a visit under way goes on as planned).
    pub fn set_kind(&mut self, kind: PathKind) {
        self.kind = kind;
    }

    /// The waypoints.
    pub fn waypoints(&self) -> &Waypoints {
        &self.waypoints
    }

    /// The waypoints, to change them (the plan is redone from the new list).
    pub fn waypoints_mut(&mut self) -> &mut Waypoints {
        self.finished = false;
        &mut self.waypoints
    }

    /// Whether both planned paths are drawn.
    pub fn shown(&self) -> bool {
        self.shown
    }

    /// Draws both planned paths or stops drawing them.
    pub fn set_shown(&mut self, shown: bool) {
        self.shown = shown;
        if !shown {
            self.plan = None;
            self.planned_from = None;
        }
    }

    /// The planned paths, when drawn.
    pub fn plan(&self) -> Option<&Plan> {
        self.plan.as_ref().filter(|_| self.shown)
    }

    /// The visit under way.
    pub fn visit(&self) -> Option<&Visit> {
        self.visit.as_ref()
    }

    /// Whether the last visit ran to its end.
    pub fn finished(&self) -> bool {
        self.finished
    }

    /// The poses the paths go through: the waypoints, or the target when there are none.
    fn goals(&self, target: &IsometryMatrix3<f64>) -> Vec<IsometryMatrix3<f64>> {
        if self.waypoints.is_empty() {
            vec![*target]
        } else {
            self.waypoints.poses().to_vec()
        }
    }

    /// Plans both paths from `q` anew when they are drawn and what they start from or go
    /// through changed (not during a visit, whose own path is drawn instead).
    pub fn update_plan(
        &mut self,
        robot: &Robot,
        q: &[f64],
        target: &IsometryMatrix3<f64>,
        robot_changes: u64,
        solver: &mut IkSolver,
    ) {
        if !self.shown || self.visit.is_some() {
            return;
        }
        let made_from = (q.to_vec(), self.goals(target), robot_changes);
        if self.planned_from.as_ref() == Some(&made_from) {
            return;
        }
        let plan = |kind, solver: &mut IkSolver| -> Result<Path, MotionError> {
            let list = Waypoints::new(made_from.1.clone())?;
            let settings = CartesianSettings::for_robot(robot);
            waypoint_path(robot, q, &list, kind, &settings, solver)
        };
        self.plan = match (
            plan(PathKind::Joint, solver),
            plan(PathKind::Cartesian, solver),
        ) {
            (Ok(joint), Ok(line)) => Some(Plan { joint, line }),
            _ => None,
        };
        self.planned_from = Some(made_from);
    }

    /// Plans a visit of every waypoint from `q` along the chosen kind; returns the first
    /// goal. An empty list visits nothing.
    pub fn start_visit(
        &mut self,
        robot: &Robot,
        q: &[f64],
        robot_changes: u64,
        solver: &mut IkSolver,
    ) -> Result<Option<Vec<f64>>, MotionError> {
        self.visit = None;
        self.finished = false;
        if self.waypoints.is_empty() {
            return Ok(None);
        }
        let settings = CartesianSettings::for_robot(robot);
        let path = waypoint_path(robot, q, &self.waypoints, self.kind, &settings, solver)?;
        // Segment k ends at s = k + 1, at the segment's last step.
        let stops = (1..=self.waypoints.len())
            .filter_map(|k| path.points.iter().position(|p| p.s == k as f64))
            .collect();
        let mut visit = Visit {
            path,
            index: 0,
            stops,
            last_q: q.to_vec(),
            robot_changes,
        };
        let goal = follow(robot, &mut visit, q, false).unwrap_or_else(|| q.to_vec());
        self.visit = Some(visit);
        Ok(Some(goal))
    }

    /// Ends the visit (something else moved the arm or set its goal).
    pub fn stop_visit(&mut self) {
        self.visit = None;
    }

    /// Whether a visit is under way for this robot and the arm is where the visit left
    /// it.
    pub fn visiting_at(&self, q: &[f64], robot_changes: u64) -> bool {
        self.visit
            .as_ref()
            .is_some_and(|v| v.last_q == q && v.robot_changes == robot_changes)
    }

    /// The visit's next goal once the arm is at `q`: `None` while the goal stays.
    /// `arrived`: every joint is within [`STOP_ERROR`] of the goal. At the path's end
    /// with the arm arrived, the visit is finished.
    pub fn follow(&mut self, robot: &Robot, q: &[f64], arrived: bool) -> Option<Vec<f64>> {
        let visit = self.visit.as_mut()?;
        visit.last_q = q.to_vec();
        let was_at_end = visit.at_end();
        let next = follow(robot, visit, q, arrived);
        if was_at_end && arrived {
            self.finished = true;
            self.visit = None;
        }
        next
    }
}

/// Moves the visit's goal along its path while the arm is within [`LOOKAHEAD`] of it,
/// never past a waypoint the arm has not arrived at (`arrived` tells of the goal now);
/// the new goal when it moved.
fn follow(robot: &Robot, visit: &mut Visit, q: &[f64], arrived: bool) -> Option<Vec<f64>> {
    let before = visit.index;
    while !visit.at_end() {
        let here = &visit.path.points[visit.index].q;
        let stop = visit.stops.contains(&visit.index);
        if (stop && !(arrived && visit.index == before)) || joint_gap(robot, q, here) > LOOKAHEAD {
            break;
        }
        visit.index += 1;
    }
    (visit.index != before).then(|| visit.path.points[visit.index].q.clone())
}

#[cfg(test)]
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    use crate::app::state::model::Model;
    use armlab_core::ik::{REACHED_ORIENTATION_TOLERANCE, REACHED_POSITION_TOLERANCE_M};
    use armlab_core::tool_pose;
    use armlab_session::session::Session;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    /// The UR10 with three waypoints at the tool poses of three joint vectors.
    fn ur10_with_waypoints(kind: PathKind) -> (Model, Vec<IsometryMatrix3<f64>>) {
        let mut model = Model::new(Session::for_preset("ur10").expect("the UR10"));
        model.set_q_exact(vec![0.0, -1.2, 1.4, -1.8, -1.5, 0.0]);
        let start = model.q().to_vec();
        let mut poses = Vec::new();
        for q in [
            [0.5, -1.0, 1.2, -1.7, -1.5, 0.3],
            [0.9, -1.4, 1.6, -1.9, -1.3, 0.1],
            [0.2, -0.9, 1.0, -1.5, -1.6, -0.4],
        ] {
            let pose = tool_pose(model.robot(), &q);
            model.set_target(pose);
            model.add_waypoint().expect("a pose");
            poses.push(pose);
        }
        model.set_q_exact(start);
        model.set_path_kind(kind);
        (model, poses)
    }

    /// Runs the visit at 60 frames a second until done (at most 60 simulated seconds);
    /// returns the tool's positions after each frame.
    fn run_visit(model: &mut Model) -> Vec<nalgebra::Vector3<f64>> {
        model.visit_waypoints().expect("the visit starts");
        let mut tool = Vec::new();
        for _ in 0..3600 {
            model.advance_motion(1.0 / 60.0);
            tool.push(model.fk().tool_position());
            if model.paths().finished() && !model.motion().moving() {
                break;
            }
        }
        tool
    }

    #[test]
    fn a_visit_of_three_waypoints_ends_at_the_last_pose_along_either_path_kind() {
        for kind in [PathKind::Joint, PathKind::Cartesian] {
            let (mut model, poses) = ur10_with_waypoints(kind);
            let tool = run_visit(&mut model);
            assert!(
                model.paths().finished(),
                "{kind:?}: the visit ran to its end"
            );
            assert!(model.paths().visit().is_none());
            let reach = model.robot().reach();
            let end = model.fk().base_from_tool;
            let last = poses[2];
            let dp = (end.translation.vector - last.translation.vector).norm();
            let dr = (end.rotation.inverse() * last.rotation).angle();
            let tol = REACHED_POSITION_TOLERANCE_M / model.robot().length_unit.in_metres();
            assert!(dp <= tol, "{kind:?}: {dp} mm from the last waypoint");
            assert!(dr <= REACHED_ORIENTATION_TOLERANCE, "{kind:?}: {dr} rad");
            // Every waypoint was passed on the way, in order.
            let mut from = 0;
            for (i, pose) in poses.iter().enumerate() {
                let gaps: Vec<f64> = tool[from..]
                    .iter()
                    .map(|p| (p - pose.translation.vector).norm())
                    .collect();
                let (at, closest) =
                    gaps.iter().enumerate().fold(
                        (0, f64::MAX),
                        |b, (k, g)| if *g < b.1 { (k, *g) } else { b },
                    );
                assert!(
                    closest < 2e-3 * reach,
                    "{kind:?}: waypoint {} passed at {closest} mm",
                    i + 1
                );
                from += at;
            }
            assert!(model.motion().trail().len() > 10, "the trail is drawn");
        }
    }

    #[test]
    fn a_visit_along_the_line_keeps_the_tool_near_each_straight_segment() {
        let mut worst = [0.0; 2];
        for (n, kind) in [PathKind::Cartesian, PathKind::Joint]
            .into_iter()
            .enumerate()
        {
            let (mut model, poses) = ur10_with_waypoints(kind);
            let mut ends = vec![model.fk().tool_position()];
            ends.extend(poses.iter().map(|p| p.translation.vector));
            let tool = run_visit(&mut model);
            // The distance of each tool position from the nearest segment of the polyline.
            worst[n] = tool
                .iter()
                .map(|p| {
                    ends.windows(2)
                        .map(|w| {
                            let (a, b) = (w[0], w[1]);
                            let t =
                                ((p - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
                            (p - (a + (b - a) * t)).norm()
                        })
                        .fold(f64::MAX, f64::min)
                })
                .fold(0.0, f64::max);
        }
        let reach = ur10_with_waypoints(PathKind::Joint).0.robot().reach();
        println!(
            "farthest from the polyline: line visit {:.3} mm, joint-space visit {:.3} mm",
            worst[0], worst[1]
        );
        assert!(
            worst[0] < 0.01 * reach,
            "the line visit strays {} mm from the segments",
            worst[0]
        );
        assert!(
            worst[1] > 3.0 * worst[0],
            "the joint-space visit curves away ({} mm vs {} mm)",
            worst[1],
            worst[0]
        );
    }

    #[test]
    fn a_bad_waypoint_keeps_the_last_good_pose_and_a_link_carries_the_list() {
        let (mut model, poses) = ur10_with_waypoints(PathKind::Cartesian);
        let mut bad = poses[1];
        bad.translation.vector.x = f64::NAN;
        let e = model.set_waypoint(1, bad).expect_err("NaN is refused");
        assert!(
            armlab_text::Sentence::sentence(&e, armlab_text::Lang::En).contains("waypoint 2"),
            "{e}"
        );
        assert_eq!(model.paths().waypoints().poses()[1], poses[1]);
        // The link round trip: kind and every pose.
        let session = Session::from_hash(&model.hash())
            .expect("reads")
            .expect("a session");
        let back = Model::new(session);
        assert_eq!(back.paths().kind(), PathKind::Cartesian);
        assert_eq!(back.paths().waypoints().len(), 3);
        for (a, b) in back.paths().waypoints().poses().iter().zip(&poses) {
            assert!((a.translation.vector - b.translation.vector).norm() < 1e-5);
            assert!((a.rotation.inverse() * b.rotation).angle() < 1e-5);
        }
        // A bad path kind and a bad waypoint are left out with a sentence; the rest
        // (the robot, q, the good waypoint) applies.
        let hash =
            "robot=ur10&q=0.1,-1,1,-1,-1.5,0&path=zigzag&wp=600,100,400,0,0,0;1,2,x,0,0,0;5,6";
        let session = Session::from_hash(hash).expect("opens").expect("a session");
        let model = Model::new(session);
        assert_eq!(model.q()[0], 0.1);
        assert_eq!(model.paths().kind(), PathKind::Joint);
        assert_eq!(model.paths().waypoints().len(), 1);
        let text = model.message().map(|m| m.text.clone()).unwrap_or_default();
        for part in [
            "zigzag",
            "joint or line",
            "waypoint 2",
            "\"x\"",
            "waypoint 3",
            "6",
        ] {
            assert!(text.contains(part), "{part} in: {text}");
        }
    }

    #[test]
    fn moving_the_arm_otherwise_ends_a_visit() {
        let (mut model, _) = ur10_with_waypoints(PathKind::Joint);
        model.visit_waypoints().expect("starts");
        model.advance_motion(0.1);
        assert!(model.paths().visit().is_some());
        model.set_q_exact(vec![0.0; 6]);
        model.advance_motion(0.1);
        assert!(model.paths().visit().is_none(), "a slider ends the visit");
        assert!(!model.paths().finished());
    }
}
