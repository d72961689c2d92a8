//! The geometric Jacobian against its central-difference check (docs/kinematics.md §4), the measures,
//! and velocity kinematics.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::{
    ForwardKinematics, NUMERIC_EPSILON, SINGULARITY_THRESHOLD, Task, ToolAxis, geometric_jacobian,
    jacobian_measures, linear_motion_space, lost_direction, numerical_jacobian, preset, preset_ids,
    rotation_log, tool_pose, tool_velocity,
};

/// Largest central-difference error of a linear entry, relative to the arm's reach: the
/// truncation error is about ε²·reach (1e−12) and the rounding error about
/// 1e−16·reach/ε (1e−10); measured at most 7.0e−10 over every preset and 1000 random q
/// (the test prints it with --nocapture). The limit keeps a margin of about 14.
const LINEAR_LIMIT: f64 = 1e-8;
/// Largest error of an angular entry (rad per rad or per length unit): the same sources,
/// measured at most 1.1e−9 (margin 9); a degree (1.7e−2) off fails by six orders of
/// magnitude, where a bound of 1e−5·‖J‖ shared with the linear entries lets it pass for
/// mm robots.
const ANGULAR_LIMIT: f64 = 1e-8;

#[test]
fn numeric_and_geometric_agree_for_every_preset_at_1000_random_q() {
    let (mut worst_linear, mut worst_angular) = (0.0_f64, 0.0_f64);
    for (id, robot) in common::all_presets() {
        let mut rng = common::rng(42);
        let reach = robot.reach();
        for _ in 0..1000 {
            let q = rng.joint_vector(&robot);
            let fk = ForwardKinematics::new(&robot, &q).unwrap();
            let geometric = geometric_jacobian(&fk);
            let numeric = numerical_jacobian(&robot, &q, NUMERIC_EPSILON);
            let diff = (&geometric - &numeric).abs();
            let linear = diff.fixed_rows::<3>(0).max() / reach;
            let angular = diff.fixed_rows::<3>(3).max();
            worst_linear = worst_linear.max(linear);
            worst_angular = worst_angular.max(angular);
            assert!(
                linear <= LINEAR_LIMIT,
                "{id} at q = {q:?}: a linear entry is off by {linear}·reach"
            );
            assert!(
                angular <= ANGULAR_LIMIT,
                "{id} at q = {q:?}: an angular entry is off by {angular} rad"
            );
        }
    }
    println!("worst linear error {worst_linear:e}·reach, worst angular {worst_angular:e} rad");
}

#[test]
fn the_agreement_check_catches_an_angular_row_off_by_a_degree() {
    let robot = preset("ur10").unwrap();
    let q = [0.3, -1.0, 1.2, -0.5, 0.8, 0.7];
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    let numeric = numerical_jacobian(&robot, &q, NUMERIC_EPSILON);
    let mut wrong = geometric_jacobian(&fk);
    wrong[(4, 2)] += 1f64.to_radians();
    assert!((&wrong - &numeric).fixed_rows::<3>(3).abs().max() > ANGULAR_LIMIT);
}

#[test]
fn standard_and_modified_ur10_have_the_same_jacobian() {
    let a = preset("ur10").unwrap();
    let b = preset("ur10-standard").unwrap();
    let mut rng = common::rng(7);
    for _ in 0..100 {
        let q = rng.joint_vector(&a);
        let ja = geometric_jacobian(&ForwardKinematics::new(&a, &q).unwrap());
        let jb = geometric_jacobian(&ForwardKinematics::new(&b, &q).unwrap());
        assert!((ja - jb).abs().max() < 1e-9);
    }
}

#[test]
fn equivalent_tables_give_the_same_unit_free_measures_and_the_displayed_det_is_det_j() {
    // The UR10 and its standard-DH twin are one arm: a length scale taken from how each
    // table pairs a and d in its rows would give them det −0.08615 and −0.06629.
    let a = preset("ur10").unwrap();
    let b = preset("ur10-standard").unwrap();
    assert_eq!(a.length_scale(), b.length_scale());
    assert!(
        (a.length_scale() - 1684.3).abs() < 1e-9,
        "{}",
        a.length_scale()
    );
    let mut rng = common::rng(12);
    for _ in 0..200 {
        let q = rng.joint_vector(&a);
        let (fa, fb) = (
            ForwardKinematics::new(&a, &q).unwrap(),
            ForwardKinematics::new(&b, &q).unwrap(),
        );
        let ja = geometric_jacobian(&fa);
        let ma = jacobian_measures(&ja, Task::FullPose, fa.tool_rotation(), a.length_scale());
        let mb = jacobian_measures(
            &geometric_jacobian(&fb),
            Task::FullPose,
            fb.tool_rotation(),
            b.length_scale(),
        );
        let (da, db) = (ma.determinant.unwrap(), mb.determinant.unwrap());
        assert!((da - db).abs() < 1e-12 * da.abs().max(1.0), "{da} vs {db}");
        assert!((ma.manipulability - mb.manipulability).abs() < 1e-12);
        // The displayed measures are those of the matrix on screen: det of the 6×6 J in mm,
        // and the unit-free det is it divided by L³ (three linear rows, one length each).
        let shown = ja.clone().remove_fixed_columns::<0>(0);
        let det = nalgebra::DMatrix::from_fn(6, 6, |r, c| shown[(r, c)]).determinant();
        let raw = ma.displayed.determinant.unwrap();
        assert!(
            (raw - det).abs() <= 1e-9 * det.abs().max(1.0),
            "{raw} vs {det}"
        );
        let l3 = a.length_scale().powi(3);
        assert!(
            (raw / l3 - da).abs() <= 1e-9 * da.abs().max(1e-12),
            "{raw} / L³ vs {da}"
        );
        assert!((ma.displayed.manipulability - raw.abs()).abs() <= 1e-6 * raw.abs().max(1.0));
    }
}

#[test]
fn planar_2r_jacobian_matches_textbook_and_is_singular_when_stretched() {
    let robot = preset("planar-2r").unwrap();
    let (t1, t2) = (0.4_f64, 1.1_f64);
    let fk = ForwardKinematics::new(&robot, &[t1, t2]).unwrap();
    let j = geometric_jacobian(&fk);
    let (s1, c1, s12, c12) = (t1.sin(), t1.cos(), (t1 + t2).sin(), (t1 + t2).cos());
    let want = [[-2.0 * s1 - s12, -s12], [2.0 * c1 + c12, c12]];
    for r in 0..2 {
        for c in 0..2 {
            assert!((j[(r, c)] - want[r][c]).abs() < 1e-12);
        }
    }
    // det J = l1 l2 s2 for the 2×2 position block (x, y).
    let det = j[(0, 0)] * j[(1, 1)] - j[(0, 1)] * j[(1, 0)];
    assert!((det - 2.0 * t2.sin()).abs() < 1e-12);

    let stretched = ForwardKinematics::new(&robot, &[0.3, 0.0]).unwrap();
    let m = jacobian_measures(
        &geometric_jacobian(&stretched),
        Task::Position,
        stretched.tool_rotation(),
        robot.reach(),
    );
    assert!(m.near_singular, "s2 = 0 is singular: {m:?}");
    assert!(m.manipulability.abs() < 1e-12);
    let bent = ForwardKinematics::new(&robot, &[0.3, 1.2]).unwrap();
    let m = jacobian_measures(
        &geometric_jacobian(&bent),
        Task::Position,
        bent.tool_rotation(),
        robot.reach(),
    );
    assert!(!m.near_singular, "a bent elbow is not singular: {m:?}");
}

#[test]
fn measures_do_not_depend_on_the_length_unit() {
    // The same arm in mm and in m gives the same scaled measures.
    let mm = preset("rrr").unwrap();
    let mut m = mm.clone();
    m.length_unit = armlab_core::LengthUnit::Metre;
    for j in &mut m.joints {
        j.dh.a /= 1000.0;
        j.dh.d /= 1000.0;
    }
    let q = [0.3, 0.8, -1.2];
    let fa = ForwardKinematics::new(&mm, &q).unwrap();
    let fb = ForwardKinematics::new(&m, &q).unwrap();
    let a = jacobian_measures(
        &geometric_jacobian(&fa),
        Task::FullPose,
        fa.tool_rotation(),
        mm.reach(),
    );
    let b = jacobian_measures(
        &geometric_jacobian(&fb),
        Task::FullPose,
        fb.tool_rotation(),
        m.reach(),
    );
    for (x, y) in a.singular_values.iter().zip(&b.singular_values) {
        assert!((x - y).abs() < 1e-9 * x.max(1.0), "{x} vs {y}");
    }
    assert!((a.manipulability - b.manipulability).abs() < 1e-12);
}

#[test]
fn rrr_singular_on_base_axis_and_with_straight_elbow() {
    let robot = preset("rrr").unwrap();
    let (l2, l3) = (222.1_f64, 136.2_f64);
    // L2 c2 + L3 c23 = 0: choose θ2 = 90°, θ3 = 0 (tool straight above the base).
    let on_axis = [0.2, std::f64::consts::FRAC_PI_2, 0.0];
    let elbow_straight = [0.2, 0.5, 0.0];
    let elbow_bent = [0.2, 0.5, 1.0];
    assert!((l2 * on_axis[1].cos() + l3 * (on_axis[1] + on_axis[2]).cos()).abs() < 1e-9);
    for (q, singular) in [(on_axis, true), (elbow_straight, true), (elbow_bent, false)] {
        let fk = ForwardKinematics::new(&robot, &q).unwrap();
        let m = jacobian_measures(
            &geometric_jacobian(&fk),
            Task::Position,
            fk.tool_rotation(),
            robot.reach(),
        );
        assert_eq!(m.near_singular, singular, "q = {q:?}: {m:?}");
        assert!(m.determinant.is_some(), "3×3 task is square");
    }
}

#[test]
fn ur10_wrist_singular_at_theta5_zero() {
    let robot = preset("ur10").unwrap();
    let q = [0.3, -1.0, 1.2, -0.5, 0.0, 0.7];
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    let m = jacobian_measures(
        &geometric_jacobian(&fk),
        Task::FullPose,
        fk.tool_rotation(),
        robot.reach(),
    );
    assert!(m.near_singular && m.determinant.unwrap().abs() < 1e-12);
    assert!(m.condition_number.is_none_or(|c| c > 1e10));
    let q = [0.3, -1.0, 1.2, -0.5, 0.8, 0.7];
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    let m = jacobian_measures(
        &geometric_jacobian(&fk),
        Task::FullPose,
        fk.tool_rotation(),
        robot.reach(),
    );
    assert!(!m.near_singular, "{m:?}");
    assert!(m.condition_number.unwrap() >= 1.0);
    let product: f64 = m.singular_values.iter().product();
    assert!((product - m.determinant.unwrap().abs()).abs() < 1e-12);
}

#[test]
fn five_axis_task_has_five_rows_and_full_rank_in_general() {
    let robot = preset("metrover").unwrap();
    let q = [0.3, 0.9, 0.4, 0.5, 0.2];
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    let j = geometric_jacobian(&fk);
    let m = jacobian_measures(
        &j,
        Task::PositionAndAxis(ToolAxis::Z),
        fk.tool_rotation(),
        robot.reach(),
    );
    assert_eq!(m.singular_values.len(), 5);
    assert!(!m.near_singular, "{m:?}");
    // Full pose on five joints: five singular values, no determinant.
    let m6 = jacobian_measures(&j, Task::FullPose, fk.tool_rotation(), robot.reach());
    assert_eq!(m6.singular_values.len(), 5);
    assert!(m6.determinant.is_none());
}

#[test]
fn velocity_kinematics_predicts_small_motions_linear_and_angular() {
    for (id, robot) in common::all_presets() {
        let mut rng = common::rng(99);
        for _ in 0..20 {
            let q = rng.joint_vector(&robot);
            let q_dot: Vec<f64> = (0..robot.dof()).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let fk = ForwardKinematics::new(&robot, &q).unwrap();
            let twist = tool_velocity(&geometric_jacobian(&fk), &q_dot);
            // Central differences along q̇: p and R at q ± h·q̇.
            let h = 1e-6;
            let at = |sign: f64| {
                let q: Vec<f64> = q
                    .iter()
                    .zip(&q_dot)
                    .map(|(a, b)| a + sign * h * b)
                    .collect();
                tool_pose(&robot, &q)
            };
            let (ahead, behind) = (at(1.0), at(-1.0));
            let v = (ahead.translation.vector - behind.translation.vector) / (2.0 * h);
            let relative = ahead.rotation.matrix() * behind.rotation.matrix().transpose();
            let w = rotation_log(&relative) / (2.0 * h);
            let reach = robot.reach();
            assert!(
                (v - twist.fixed_rows::<3>(0)).norm() < 1e-7 * reach,
                "{id}: v = J_v q̇ predicted {:?}, measured {v:?}",
                twist.fixed_rows::<3>(0)
            );
            assert!(
                (w - twist.fixed_rows::<3>(3)).norm() < 1e-7,
                "{id}: ω = J_ω q̇ predicted {:?}, measured {w:?}",
                twist.fixed_rows::<3>(3)
            );
        }
    }
}

/// The task rows the measures use, built here from their definition (docs/kinematics.md
/// §5–6): the linear rows divided by the reach; for a 5D task the angular rows projected
/// on the two tool axes perpendicular to the chosen one.
fn scaled_task_rows(
    j: &nalgebra::Matrix6xX<f64>,
    task: Task,
    r: &nalgebra::Matrix3<f64>,
    reach: f64,
) -> nalgebra::DMatrix<f64> {
    let n = j.ncols();
    let linear = j.fixed_rows::<3>(0) / reach;
    let angular = j.fixed_rows::<3>(3);
    let mut rows: Vec<nalgebra::RowDVector<f64>> =
        (0..3).map(|k| linear.row(k).into_owned()).collect();
    match task {
        Task::Position => {}
        Task::FullPose => rows.extend((0..3).map(|k| angular.row(k).into_owned())),
        Task::PositionAndAxis(axis) => {
            let k = match axis {
                ToolAxis::X => 0,
                ToolAxis::Y => 1,
                ToolAxis::Z => 2,
            };
            for other in [(k + 1) % 3, (k + 2) % 3] {
                rows.push(r.column(other).transpose() * angular);
            }
        }
    }
    nalgebra::DMatrix::from_fn(rows.len(), n, |i, c| rows[i][c])
}

#[test]
fn measures_equal_an_svd_of_the_scaled_task_rows() {
    for (id, robot) in common::all_presets() {
        let mut rng = common::rng(5);
        for _ in 0..50 {
            let q = rng.joint_vector(&robot);
            let fk = ForwardKinematics::new(&robot, &q).unwrap();
            let j = geometric_jacobian(&fk);
            for task in Task::ALL {
                let m = jacobian_measures(&j, task, fk.tool_rotation(), robot.reach());
                let rows = scaled_task_rows(&j, task, fk.tool_rotation(), robot.reach());
                let mut sigma: Vec<f64> = rows
                    .clone()
                    .svd(false, false)
                    .singular_values
                    .iter()
                    .copied()
                    .collect();
                sigma.sort_by(|a, b| b.total_cmp(a));
                let what = format!("{id}, {}, q = {q:?}", task.id());
                assert_eq!(m.singular_values.len(), sigma.len(), "{what}");
                for (a, b) in m.singular_values.iter().zip(&sigma) {
                    assert!((a - b).abs() < 1e-12, "{what}: σ {a} vs {b}");
                }
                let product: f64 = sigma.iter().product();
                assert!((m.manipulability - product).abs() < 1e-12, "{what}");
                if rows.nrows() <= rows.ncols() {
                    // w² = det(J Jᵀ) (compared squared: the root amplifies rounding near 0).
                    let gram = (&rows * rows.transpose()).determinant();
                    assert!(
                        (m.manipulability.powi(2) - gram).abs() < 1e-12,
                        "{what}: w² = {} but det(J Jᵀ) = {gram}",
                        m.manipulability.powi(2)
                    );
                }
                match m.determinant {
                    Some(det) => {
                        assert!(rows.is_square(), "{what}");
                        assert!((det - rows.determinant()).abs() < 1e-12, "{what}");
                        assert!((det.abs() - product).abs() < 1e-12, "{what}: |det| = Π σ");
                    }
                    None => assert!(!rows.is_square(), "{what}"),
                }
                let smallest = sigma.last().copied().unwrap_or(0.0);
                match m.condition_number {
                    Some(c) => assert!((c - sigma[0] / smallest).abs() <= 1e-9 * c, "{what}"),
                    None => assert_eq!(smallest, 0.0, "{what}"),
                }
                assert_eq!(m.near_singular, smallest < SINGULARITY_THRESHOLD, "{what}");
            }
        }
    }
}

#[test]
fn the_planar_2r_moves_its_tool_in_its_plane_and_every_other_preset_in_all_three_directions() {
    for id in preset_ids() {
        let robot = preset(id).expect("a preset");
        let space = linear_motion_space(&robot);
        // Orthonormal columns.
        let gram = space.transpose() * &space;
        let identity = nalgebra::DMatrix::<f64>::identity(space.ncols(), space.ncols());
        assert!((gram - identity).norm() < 1e-9, "{id}");
        if id == "planar-2r" {
            // Both joint axes are the base's z: the tool moves in the xy plane only.
            assert_eq!(space.ncols(), 2, "{id}");
            assert!(space.row(2).norm() < 1e-12, "{id}: {space}");
        } else {
            assert_eq!(space.ncols(), 3, "{id}");
        }
    }
}

#[test]
fn the_planar_2r_loses_the_radial_direction_at_a_straight_elbow_and_nothing_elsewhere() {
    let robot = preset("planar-2r").expect("a preset");
    let space = linear_motion_space(&robot);
    let lost_at = |q: &[f64]| {
        let fk = ForwardKinematics::new(&robot, q).expect("a pose");
        lost_direction(&geometric_jacobian(&fk), &space, 0.02)
    };
    // Straight elbow: the tool can only move across the arm, never along it.
    let q1: f64 = 0.3;
    let lost = lost_at(&[q1, 0.0]).expect("a lost direction at the straight elbow");
    let radial = nalgebra::Vector3::new(q1.cos(), q1.sin(), 0.0);
    assert!(
        lost.cross(&radial).norm() < 1e-9,
        "lost {lost}, radial {radial}"
    );
    assert!((lost.norm() - 1.0).abs() < 1e-12);
    // Bent: both directions of the plane are the arm's, and z was never its to lose.
    for q2 in [1.0, -0.7, 2.5] {
        assert_eq!(lost_at(&[q1, q2]), None, "q2 = {q2}");
    }
}

#[test]
fn a_spatial_arm_loses_a_direction_only_at_its_singular_poses() {
    // The RRR's position rows are 3×3: singular with the elbow straight, not bent.
    let robot = preset("rrr").expect("a preset");
    let space = linear_motion_space(&robot);
    let rows_at = |q: &[f64]| {
        let fk = ForwardKinematics::new(&robot, q).expect("a pose");
        geometric_jacobian(&fk)
    };
    assert_eq!(
        lost_direction(&rows_at(&[0.2, 0.5, 1.0]), &space, 0.02),
        None
    );
    // Straight: no joint speed moves the tool along the lost direction (J_vᵀ·u ≈ 0), which
    // is the arm's own direction from the shoulder, (cos θ1 cos θ2, sin θ1 cos θ2, sin θ2).
    let straight = rows_at(&[0.2, 0.5, 0.0]);
    let lost = lost_direction(&straight, &space, 0.02).expect("a lost direction");
    let jv = straight.fixed_rows::<3>(0);
    assert!((jv.transpose() * lost).norm() < 1e-9 * jv.norm());
    let along = nalgebra::Vector3::new(
        0.2f64.cos() * 0.5f64.cos(),
        0.2f64.sin() * 0.5f64.cos(),
        0.5f64.sin(),
    );
    assert!(
        lost.cross(&along).norm() < 1e-9,
        "lost {lost}, along the arm {along}"
    );
}
