//! Paths (docs/kinematics.md §19): joint-space and Cartesian paths end at the same pose,
//! the Cartesian one stays on its line, and the line's problems are reported where they
//! happen.

#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

use armlab_text::Sentence;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::path::{
    CartesianSettings, PathIssue, PathKind, Waypoints, cartesian_path, interpolate_pose,
    joint_path, waypoint_path,
};
use armlab_core::{IkSolver, MotionError, SINGULARITY_THRESHOLD, Setting, preset, tool_pose};
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
    // From the UR10's home pose straight out, hand orientation kept, along the arm's
    // plane (horizontal, across the shoulder axis): the base joint and the wrist keep
    // their angles along such a line, so the wrist moves with the tool, and the arm
    // reaches exactly as long as the wrist-1 axis is within |a2| + |a3| of the shoulder
    // axis (the elbow stretched). Both axes are parallel and the line crosses them at a
    // right angle, so in the plane across them it is a line–circle crossing.
    let robot = preset("ur10").unwrap();
    let from = robot.home();
    let own = common::own_fk(&robot, &from);
    let start = own.tool;
    let (shoulder, axis) = own.axes[1];
    let elbow = own.axes[2].0;
    let wrist = own.axes[3].0;
    let across = |v: Vector3<f64>| v - axis * v.dot(&axis);
    // |a2| + |a3| from the axes themselves: the distances between parallel axes.
    let stretched = across(elbow - shoulder).norm() + across(wrist - elbow).norm();
    let mut out = Vector3::z().cross(&axis).normalize();
    if out.dot(&(wrist - shoulder)) < 0.0 {
        out = -out;
    }
    let length = LINE_LENGTH;
    let far = start.translation.vector + out * length;
    let target = IsometryMatrix3::from_parts(Translation3::from(far), start.rotation);
    // |w + s·d| = stretched, w the wrist axis' offset from the shoulder axis at s = 0.
    let (w, d) = (across(wrist - shoulder), out * length);
    let (a, b, c) = (d.dot(&d), w.dot(&d), w.dot(&w) - stretched * stretched);
    assert!(c < 0.0, "the home pose is inside the reach");
    let exit = (-b + (b * b - a * c).sqrt()) / a;
    assert!(exit > 0.2 && exit < 0.8, "the line leaves at s = {exit}");

    let mut settings = CartesianSettings::for_robot(&robot);
    settings.steps = 50;
    let step = 1.0 / settings.steps as f64;
    let path = cartesian_path(&robot, &from, &target, &settings, &mut IkSolver::new()).unwrap();
    let leave = path
        .problems
        .iter()
        .find(|p| p.issue == PathIssue::OutOfReach)
        .expect("out of reach reported");
    let at = path.points[leave.index].s;
    assert_eq!(at, leave.s);
    // Reported at the first step past the crossing: every step before it is reachable,
    // none after it is.
    assert!(
        leave.s >= exit && leave.s < exit + step,
        "reported at s = {} ({leave:?}); the line leaves the reach at s = {exit}, \
         so the first step out is at s = {}",
        leave.s,
        (exit / step).ceil() * step
    );
    let p_leave = start.translation.vector + (far - start.translation.vector) * leave.s;
    let p_exit = start.translation.vector + (far - start.translation.vector) * exit;
    assert!(
        (p_leave - p_exit).norm() < step * length,
        "reported {p_leave:?}, the crossing is at {p_exit:?}"
    );
    // Before it, every step was on the line, by the tests' own FK.
    for p in &path.points[..leave.index] {
        let want = interpolate_pose(&start, &target, p.s);
        let (dp, dr) = common::pose_distance(&common::own_fk(&robot, &p.q).tool, &want);
        assert!(dp < 1e-3 && dr < 1e-6, "s = {}: {dp} mm, {dr} rad", p.s);
    }
    // After it, none is: the arm stays short of the line.
    for p in &path.points[leave.index..] {
        let want = interpolate_pose(&start, &target, p.s);
        let (dp, _) = common::pose_distance(&common::own_fk(&robot, &p.q).tool, &want);
        assert!(dp > 1e-3, "s = {}: on the line beyond the reach", p.s);
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

/// How far the line of [`a_line_out_of_the_workspace_is_reported_where_it_leaves`] runs
/// from the home pose (mm): it crosses the edge of the reach between two of its 50 steps,
/// not on one, where the solver would need an exactly stretched arm.
const LINE_LENGTH: f64 = 1000.0;

#[test]
fn a_line_through_the_wrist_singularity_is_reported() {
    // UR10: θ5 = 0 is the wrist singularity. Go from θ5 = 0.4 to θ5 = −0.4 with the
    // other joints fixed, along the straight line between the two tool poses. The two
    // ends differ by turns of ±0.4 about joint 5's axis, so halfway the slerp gives the
    // hand the orientation of θ5 = 0: by this symmetry the arm comes nearest the
    // singularity at s = 0.5. With 20 steps s = 0.5 is a step, and its neighbours
    // (0.45, 0.55) are regular again (σ_min 0.013 and 0.023 against the threshold 0.01):
    // the singularity must be reported exactly there.
    let robot = preset("ur10").unwrap();
    let from = vec![0.3, 1.2, -1.4, 0.9, 0.4, 0.2];
    let mut to = from.clone();
    to[4] = -0.4;
    let target = tool_pose(&robot, &to);
    let mut straight = from.clone();
    straight[4] = 0.0;
    let start = tool_pose(&robot, &from);
    let (_, turned) = common::pose_distance(
        &common::own_fk(&robot, &straight).tool,
        &interpolate_pose(&start, &target, 0.5),
    );
    assert!(
        turned < 1e-12,
        "halfway the hand is {turned} rad from θ5 = 0"
    );
    let mut settings = CartesianSettings::for_robot(&robot);
    settings.steps = 20;
    let path = cartesian_path(&robot, &from, &target, &settings, &mut IkSolver::new()).unwrap();
    let singular: Vec<_> = path
        .problems
        .iter()
        .filter(|p| p.issue == PathIssue::Singular)
        .collect();
    assert_eq!(
        singular.len(),
        1,
        "one singular stretch: {:?}",
        path.problems
    );
    assert!(
        (singular[0].s - 0.5).abs() < 1e-12 && singular[0].index == 10,
        "the singularity is at s = 0.5 (step 10): {:?}",
        singular[0]
    );
    // By the tests' own Jacobian (own FK, SVD) at the path's joint values, step 10 is
    // the only one below the threshold.
    let sigma: Vec<f64> = path
        .points
        .iter()
        .map(|p| own_sigma_min(&robot, &p.q))
        .collect();
    let below: Vec<usize> = (0..sigma.len())
        .filter(|k| sigma[*k] < SINGULARITY_THRESHOLD)
        .collect();
    assert_eq!(below, vec![10], "own σ_min along the path: {sigma:?}");
}

/// The smallest singular value of the 6×n geometric Jacobian at `q` (revolute joints), its
/// linear rows divided by the arm's reach, from the tests' own FK and nalgebra's SVD.
fn own_sigma_min(robot: &armlab_core::Robot, q: &[f64]) -> f64 {
    let fk = common::own_fk(robot, q);
    let p = fk.tool.translation.vector;
    let columns: Vec<nalgebra::Vector6<f64>> = fk
        .axes
        .iter()
        .map(|(o, z)| {
            let v = z.cross(&(p - o)) / robot.reach();
            nalgebra::Vector6::new(v.x, v.y, v.z, z.x, z.y, z.z)
        })
        .collect();
    nalgebra::Matrix6xX::from_columns(&columns)
        .svd(false, false)
        .singular_values
        .min()
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
