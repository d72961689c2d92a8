//! Paths (docs/kinematics.md §19): joint-space and Cartesian paths end at the same pose,
//! the Cartesian one stays on its line, and the line's problems are reported where they
//! happen.

#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

use armlab_text::Sentence;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_core::path::{
    CartesianSettings, PathIssue, PathKind, Waypoints, cartesian_path, interpolate_pose,
    joint_path, waypoint_path,
};
use armlab_core::{IkSolver, MotionError, Setting, preset, tool_pose};
use armlab_text::Lang;
use nalgebra::{IsometryMatrix3, Matrix3, Rotation3, Translation3, Vector3};

fn pose_diff(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>) -> (f64, f64) {
    let dp = (a.translation.vector - b.translation.vector).norm();
    let dr = (a.rotation.matrix() - b.rotation.matrix()).abs().max();
    (dp, dr)
}

#[test]
fn joint_and_cartesian_paths_end_at_the_same_pose() {
    let robot = preset("ur10").unwrap();
    let from = robot.home();
    let to: Vec<f64> = vec![0.6, 1.3, -1.2, 1.7, 1.4, 0.4];
    let target = tool_pose(&robot, &to);
    let joint = joint_path(&robot, &from, &to, 100).unwrap();
    let settings = CartesianSettings::for_robot(&robot);
    let line = cartesian_path(&robot, &from, &target, &settings, &mut IkSolver::new()).unwrap();
    assert_eq!(joint.points.len(), 101);
    assert_eq!(line.points.len(), 101);
    let end_j = joint.points.last().unwrap().tool;
    let end_c = line.points.last().unwrap().tool;
    let (dp, dr) = pose_diff(&end_j, &target);
    assert!(dp < 1e-9 && dr < 1e-12, "joint path end: {dp} mm, {dr}");
    let (dp, dr) = pose_diff(&end_c, &end_j);
    assert!(
        dp < 1e-3 && dr < 1e-6,
        "Cartesian end vs joint end: {dp} mm, {dr}"
    );
    assert!(line.problems.is_empty(), "{:?}", line.problems);

    // The Cartesian tool stays on the segment; the joint-space tool does not.
    let a = line.points[0].tool.translation.vector;
    let b = target.translation.vector;
    let off_line = |p: &Vector3<f64>| {
        let u = (b - a).normalize();
        let v = p - a;
        (v - u * v.dot(&u)).norm()
    };
    let worst_line = line
        .tool_positions()
        .map(|p| off_line(&p.coords))
        .fold(0.0, f64::max);
    let worst_joint = joint
        .tool_positions()
        .map(|p| off_line(&p.coords))
        .fold(0.0, f64::max);
    assert!(worst_line < 1e-3, "the line: {worst_line} mm off");
    assert!(
        worst_joint > 50.0,
        "the joint path curves: {worst_joint} mm off"
    );
    // Orientation along the line is the slerp at each s.
    let start = line.points[0].tool;
    for p in line.points.iter().step_by(10) {
        let want = interpolate_pose(&start, &target, p.s);
        let (dp, dr) = pose_diff(&p.tool, &want);
        assert!(dp < 1e-3 && dr < 1e-6, "s = {}: {dp}, {dr}", p.s);
    }
}

#[test]
fn slerp_halfway_turns_half_the_angle() {
    let a = IsometryMatrix3::identity();
    let b = IsometryMatrix3::from_parts(
        Translation3::new(100.0, 0.0, 0.0),
        Rotation3::from_axis_angle(&Vector3::z_axis(), 1.2),
    );
    let mid = interpolate_pose(&a, &b, 0.5);
    assert!((mid.translation.vector.x - 50.0).abs() < 1e-12);
    assert!((mid.rotation.angle() - 0.6).abs() < 1e-12);
    // Half a turn apart: still a rotation, half of it.
    let c = IsometryMatrix3::from_parts(
        Translation3::new(0.0, 0.0, 0.0),
        Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
    );
    let mid = interpolate_pose(&a, &c, 0.5);
    assert!((mid.rotation.angle() - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
}

#[test]
fn a_line_out_of_the_workspace_is_reported_where_it_leaves() {
    // From the UR10's home pose straight out to 2 m: beyond its reach of about 1.3 m.
    let robot = preset("ur10").unwrap();
    let from = robot.home();
    let start = tool_pose(&robot, &from);
    let dir = start.translation.vector.xy().normalize();
    let far = Vector3::new(dir.x, dir.y, 0.0) * 2000.0 + Vector3::z() * start.translation.z;
    let target = IsometryMatrix3::from_parts(Translation3::from(far), start.rotation);
    let mut settings = CartesianSettings::for_robot(&robot);
    settings.steps = 50;
    let path = cartesian_path(&robot, &from, &target, &settings, &mut IkSolver::new()).unwrap();
    let leave = path
        .problems
        .iter()
        .find(|p| p.issue == PathIssue::OutOfReach)
        .expect("out of reach reported");
    // Where the line crosses the reach sphere: compute it from the distances.
    let r0 = start.translation.vector.norm();
    assert!(leave.s > 0.0 && leave.s < 1.0, "{leave:?}");
    let at = path.points[leave.index].s;
    assert_eq!(at, leave.s);
    let p_leave = start.translation.vector + (far - start.translation.vector) * leave.s;
    assert!(p_leave.norm() > r0, "it leaves further out than it starts");
    // Before it, every step was on the line.
    for p in &path.points[..leave.index] {
        let want = interpolate_pose(&start, &target, p.s);
        assert!(pose_diff(&p.tool, &want).0 < 1e-3);
    }
    let sentence = leave.sentence(Lang::En);
    assert!(sentence.contains("leaves the workspace"), "{sentence}");
    assert!(leave.sentence(Lang::Fi).contains("työalueelta"));
    // The stretched arm at the edge of the workspace is singular too.
    assert!(
        path.problems.iter().any(|p| p.issue == PathIssue::Singular),
        "{:?}",
        path.problems
    );
}

#[test]
fn a_line_through_the_wrist_singularity_is_reported() {
    // UR10: θ5 = 0 is the wrist singularity. Go from θ5 = 0.4 to θ5 = −0.4 with the
    // other joints fixed, along the straight line between the two tool poses.
    let robot = preset("ur10").unwrap();
    let from = vec![0.3, 1.2, -1.4, 0.9, 0.4, 0.2];
    let mut to = from.clone();
    to[4] = -0.4;
    let target = tool_pose(&robot, &to);
    let mut settings = CartesianSettings::for_robot(&robot);
    settings.steps = 80;
    let path = cartesian_path(&robot, &from, &target, &settings, &mut IkSolver::new()).unwrap();
    let singular = path
        .problems
        .iter()
        .find(|p| p.issue == PathIssue::Singular)
        .expect("singularity reported");
    assert!(
        singular.s > 0.2 && singular.s < 0.8,
        "near the middle: {singular:?}"
    );
}

#[test]
fn waypoints_are_visited_in_order_and_bad_ones_get_typed_errors() {
    let robot = preset("ur10").unwrap();
    let from = robot.home();
    let qs = [
        vec![0.2, 1.1, -1.4, 1.8, 1.5, 0.1],
        vec![-0.3, 1.0, -1.2, 1.6, 1.4, -0.2],
    ];
    let poses: Vec<_> = qs.iter().map(|q| tool_pose(&robot, q)).collect();
    let wps = Waypoints::new(poses.clone()).unwrap();
    let mut settings = CartesianSettings::for_robot(&robot);
    settings.steps = 40;
    for kind in [PathKind::Joint, PathKind::Cartesian] {
        let path =
            waypoint_path(&robot, &from, &wps, kind, &settings, &mut IkSolver::new()).unwrap();
        assert_eq!(path.points.len(), 81, "{kind:?}");
        for (k, pose) in poses.iter().enumerate() {
            let at = &path.points[40 * (k + 1)];
            assert_eq!(at.s, (k + 1) as f64);
            let (dp, dr) = pose_diff(&at.tool, pose);
            assert!(dp < 1e-3 && dr < 1e-6, "{kind:?} waypoint {k}: {dp}, {dr}");
        }
    }
    let mut bad = poses[0];
    bad.translation.vector.x = f64::NAN;
    let e = Waypoints::new(vec![poses[0], bad]).unwrap_err();
    assert!(matches!(
        e,
        MotionError::BadPose {
            setting: Setting::Waypoint(2),
            ..
        }
    ));
    assert_eq!(
        e.sentence(Lang::En),
        "Not a valid pose for waypoint 2: it holds a value that is not finite."
    );
    let mut list = wps.clone();
    let skew = IsometryMatrix3::from_parts(
        Translation3::new(0.0, 0.0, 0.0),
        Rotation3::from_matrix_unchecked(Matrix3::new(1.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)),
    );
    assert!(list.push(skew).is_err());
    assert_eq!(list.len(), 2);
    assert!(list.remove(0).is_some());
    assert!(list.remove(5).is_none());
    assert_eq!(list.len(), 1);
    assert!(joint_path(&robot, &from, &from, 0).is_err());
}
