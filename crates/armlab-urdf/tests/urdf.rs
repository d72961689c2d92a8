//! docs/kinematics.md §16: URDF out and in. Every preset exported, read back as a URDF
//! chain and imported as a DH table gives the same tool pose at 1000 random q; a Panda
//! URDF written from its published joint origins gives SPEC §1.5's flange pose; bad URDF
//! gets a typed error naming the element; a UR10 URDF as `ur_description` writes it stands
//! as tall as UR's published numbers say.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[path = "../../armlab-core/tests/common/mod.rs"]
mod common;

use armlab_core::{JointKind, Robot, tool_pose};
use armlab_text::Lang;
use armlab_urdf::{UrdfChain, UrdfError, robot_from_urdf, robot_to_urdf};
use nalgebra::IsometryMatrix3;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// A pose with its translation in metres.
fn in_metres(robot: &Robot, pose: IsometryMatrix3<f64>) -> IsometryMatrix3<f64> {
    let mut p = pose;
    p.translation.vector *= robot.length_unit.in_metres();
    p
}

fn difference(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>) -> f64 {
    (a.to_homogeneous() - b.to_homogeneous()).abs().max()
}

#[test]
fn every_preset_round_trips_through_urdf_at_1000_random_q() {
    for (id, robot) in common::all_presets() {
        let text = robot_to_urdf(&robot).unwrap();
        let chain = UrdfChain::parse(&text).unwrap();
        assert_eq!(chain.dof(), robot.dof(), "{id}");
        let imported = robot_from_urdf(&text).unwrap();
        assert_eq!(imported.dof(), robot.dof(), "{id}");
        let mut rng = common::rng(31);
        let (mut worst_export, mut worst_import): (f64, f64) = (0.0, 0.0);
        for _ in 0..1000 {
            let q = rng.joint_vector(&robot);
            // URDF values are radians and metres.
            let q_m: Vec<f64> = q
                .iter()
                .zip(&robot.joints)
                .map(|(v, j)| match j.kind {
                    JointKind::Revolute => *v,
                    JointKind::Prismatic => v * robot.length_unit.in_metres(),
                })
                .collect();
            let dh = in_metres(&robot, tool_pose(&robot, &q));
            worst_export = worst_export.max(difference(&dh, &chain.tool_pose(&q_m)));
            worst_import = worst_import.max(difference(&dh, &tool_pose(&imported, &q_m)));
        }
        assert!(
            worst_export <= 1e-9,
            "{id}: export differs by {worst_export} m"
        );
        assert!(
            worst_import <= 1e-9,
            "{id}: import differs by {worst_import} m"
        );
    }
}

/// The Franka Emika Panda arm as franka_description's panda_arm.urdf.xacro publishes it
/// (joint origins and limits, in metres and radians), with the flange as a fixed joint
/// 0.107 m along joint 7's axis and an empty hand link; written down by hand here.
const PANDA_URDF: &str = r#"<?xml version="1.0"?>
<robot name="panda">
  <link name="panda_link0"/>
  <link name="panda_link1"/>
  <link name="panda_link2"/>
  <link name="panda_link3"/>
  <link name="panda_link4"/>
  <link name="panda_link5"/>
  <link name="panda_link6"/>
  <link name="panda_link7"/>
  <link name="panda_link8"/>
  <joint name="panda_joint1" type="revolute">
    <origin xyz="0 0 0.333" rpy="0 0 0"/>
    <parent link="panda_link0"/><child link="panda_link1"/>
    <axis xyz="0 0 1"/>
    <limit lower="-2.8973" upper="2.8973" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint2" type="revolute">
    <origin xyz="0 0 0" rpy="-1.5707963267948966 0 0"/>
    <parent link="panda_link1"/><child link="panda_link2"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1.7628" upper="1.7628" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint3" type="revolute">
    <origin xyz="0 -0.316 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link2"/><child link="panda_link3"/>
    <axis xyz="0 0 1"/>
    <limit lower="-2.8973" upper="2.8973" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint4" type="revolute">
    <origin xyz="0.0825 0 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link3"/><child link="panda_link4"/>
    <axis xyz="0 0 1"/>
    <limit lower="-3.0718" upper="-0.0698" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint5" type="revolute">
    <origin xyz="-0.0825 0.384 0" rpy="-1.5707963267948966 0 0"/>
    <parent link="panda_link4"/><child link="panda_link5"/>
    <axis xyz="0 0 1"/>
    <limit lower="-2.8973" upper="2.8973" effort="12" velocity="2.6100"/>
  </joint>
  <joint name="panda_joint6" type="revolute">
    <origin xyz="0 0 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link5"/><child link="panda_link6"/>
    <axis xyz="0 0 1"/>
    <limit lower="-0.0175" upper="3.7525" effort="12" velocity="2.6100"/>
  </joint>
  <joint name="panda_joint7" type="revolute">
    <origin xyz="0.088 0 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link6"/><child link="panda_link7"/>
    <axis xyz="0 0 1"/>
    <limit lower="-2.8973" upper="2.8973" effort="12" velocity="2.6100"/>
  </joint>
  <joint name="panda_joint8" type="fixed">
    <origin xyz="0 0 0.107" rpy="0 0 0"/>
    <parent link="panda_link7"/><child link="panda_link8"/>
  </joint>
</robot>
"#;

#[test]
#[allow(clippy::approx_constant)] // SPEC §1.5's published 0.7071, kept as printed.
fn a_panda_urdf_from_its_published_origins_gives_the_spec_flange_pose() {
    let robot = robot_from_urdf(PANDA_URDF).unwrap();
    assert_eq!(robot.dof(), 7);
    assert_eq!(robot.joints[0].name, "panda_joint1");
    let ready = [
        0.0,
        -FRAC_PI_4,
        0.0,
        -3.0 * FRAC_PI_4,
        0.0,
        FRAC_PI_2,
        FRAC_PI_4,
    ];
    let flange = tool_pose(&robot, &ready);
    common::assert_vec_near("p", &flange.translation.vector, [0.3069, 0.0, 0.5903], 1e-4);
    common::assert_rot_near(
        "R",
        flange.rotation.matrix(),
        [
            [0.7071, -0.7071, 0.0],
            [-0.7071, -0.7071, 0.0],
            [0.0, 0.0, -1.0],
        ],
        1e-4,
    );
    // And the same pose as the shipped modified-DH preset at random q.
    let preset = armlab_core::preset("panda").unwrap();
    let mut rng = common::rng(32);
    for _ in 0..1000 {
        let q = rng.joint_vector(&preset);
        let d = difference(&tool_pose(&preset, &q), &tool_pose(&robot, &q));
        assert!(d <= 1e-9, "differs by {d} m");
    }
}

fn error_of(text: &str) -> UrdfError {
    robot_from_urdf(text).expect_err("bad URDF")
}

#[test]
fn bad_urdf_gets_an_error_naming_the_element() {
    assert!(matches!(
        error_of("<robot name='x'><link"),
        UrdfError::Parse(_)
    ));
    let unknown = PANDA_URDF.replace(
        r#"<child link="panda_link8"/>"#,
        r#"<child link="panda_hand"/>"#,
    );
    assert_eq!(
        error_of(&unknown),
        UrdfError::UnknownLink {
            joint: "panda_joint8".into(),
            link: "panda_hand".into()
        }
    );
    let branch = PANDA_URDF.replace(
        "</robot>",
        r#"<link name="camera"/><joint name="cam" type="fixed"><parent link="panda_link3"/><child link="camera"/></joint></robot>"#,
    );
    assert_eq!(
        error_of(&branch),
        UrdfError::Branches {
            link: "panda_link3".into()
        }
    );
    let floating = PANDA_URDF.replace(
        r#"<joint name="panda_joint8" type="fixed">"#,
        r#"<joint name="panda_joint8" type="floating">"#,
    );
    let e = error_of(&floating);
    assert_eq!(
        e,
        UrdfError::UnsupportedJoint {
            joint: "panda_joint8".into(),
            kind: "floating".into()
        }
    );
    assert_eq!(
        e.sentence(Lang::En),
        "The URDF joint \"panda_joint8\" is of type \"floating\": ArmLab reads revolute, continuous, prismatic and fixed joints."
    );
    assert!(e.sentence(Lang::Fi).contains("\"panda_joint8\""));
    let prismatic = PANDA_URDF.replace(
        r#"<joint name="panda_joint8" type="fixed">"#,
        r#"<joint name="panda_joint8" type="prismatic">"#,
    );
    assert_eq!(
        error_of(&prismatic),
        UrdfError::PrismaticWithoutLimits {
            joint: "panda_joint8".into()
        }
    );
    let axis = PANDA_URDF.replacen(r#"<axis xyz="0 0 1"/>"#, r#"<axis xyz="0 0 0"/>"#, 1);
    assert_eq!(
        error_of(&axis),
        UrdfError::BadAxis {
            joint: "panda_joint1".into()
        }
    );
    let only_fixed = r#"<robot name="x"><link name="a"/><link name="b"/>
        <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>"#;
    assert_eq!(error_of(only_fixed), UrdfError::NoMovingJoints);
}

#[test]
fn continuous_joints_and_offset_axes_import() {
    // A planar 2R in URDF: one continuous joint about z, the next 0.5 m along x and
    // turned about y by 90° with its axis along x (so it is again vertical).
    let text = r#"<robot name="two"><link name="a"/><link name="b"/><link name="c"/><link name="t"/>
      <joint name="j1" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
      <joint name="j2" type="revolute"><origin xyz="0.5 0 0.1" rpy="0 1.5707963267948966 0"/>
        <parent link="b"/><child link="c"/><axis xyz="-1 0 0"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="tool" type="fixed"><origin xyz="0 0 0.3"/><parent link="c"/><child link="t"/></joint>
    </robot>"#;
    let robot = robot_from_urdf(text).unwrap();
    let chain = UrdfChain::parse(text).unwrap();
    assert_eq!(robot.joints[0].limits.max, std::f64::consts::PI);
    assert_eq!(robot.joints[1].limits.min, -1.0);
    // Parallel axes: a = 0.5 between them, no twist.
    assert!((robot.joints[0].dh.a - 0.5).abs() < 1e-12);
    assert!(robot.joints[0].dh.alpha.abs() < 1e-12);
    let mut rng = common::rng(33);
    for _ in 0..200 {
        let q = [rng.uniform(-3.0, 3.0), rng.uniform(-1.0, 1.0)];
        assert!(difference(&chain.tool_pose(&q), &tool_pose(&robot, &q)) <= 1e-12);
    }
}

/// The UR10 as ROS-Industrial's `ur_description` (ur10.urdf.xacro, the pre-2020 "ur10"
/// macro) writes it: joint origins from Universal Robots' published DH numbers
/// (d1 = 0.1273, a2 = 0.612, a3 = 0.5723, d4 = 0.163941, d5 = 0.1157, d6 = 0.0922 m), the
/// shoulder offset 0.220941 and elbow offset 0.1719 of the drawn links, and axes along y
/// for the parallel joints.
const UR10_URDF: &str = r#"<?xml version="1.0"?>
<robot name="ur10">
  <link name="base_link"/><link name="shoulder_link"/><link name="upper_arm_link"/>
  <link name="forearm_link"/><link name="wrist_1_link"/><link name="wrist_2_link"/>
  <link name="wrist_3_link"/><link name="ee_link"/>
  <joint name="shoulder_pan_joint" type="revolute">
    <parent link="base_link"/><child link="shoulder_link"/>
    <origin xyz="0.0 0.0 0.1273" rpy="0.0 0.0 0.0"/><axis xyz="0 0 1"/>
    <limit lower="-6.2832" upper="6.2832" effort="330.0" velocity="2.16"/>
  </joint>
  <joint name="shoulder_lift_joint" type="revolute">
    <parent link="shoulder_link"/><child link="upper_arm_link"/>
    <origin xyz="0.0 0.220941 0.0" rpy="0.0 1.570796325 0.0"/><axis xyz="0 1 0"/>
    <limit lower="-6.2832" upper="6.2832" effort="330.0" velocity="2.16"/>
  </joint>
  <joint name="elbow_joint" type="revolute">
    <parent link="upper_arm_link"/><child link="forearm_link"/>
    <origin xyz="0.0 -0.1719 0.612" rpy="0.0 0.0 0.0"/><axis xyz="0 1 0"/>
    <limit lower="-6.2832" upper="6.2832" effort="150.0" velocity="3.15"/>
  </joint>
  <joint name="wrist_1_joint" type="revolute">
    <parent link="forearm_link"/><child link="wrist_1_link"/>
    <origin xyz="0.0 0.0 0.5723" rpy="0.0 1.570796325 0.0"/><axis xyz="0 1 0"/>
    <limit lower="-6.2832" upper="6.2832" effort="54.0" velocity="3.2"/>
  </joint>
  <joint name="wrist_2_joint" type="revolute">
    <parent link="wrist_1_link"/><child link="wrist_2_link"/>
    <origin xyz="0.0 0.1149 0.0" rpy="0.0 0.0 0.0"/><axis xyz="0 0 1"/>
    <limit lower="-6.2832" upper="6.2832" effort="54.0" velocity="3.2"/>
  </joint>
  <joint name="wrist_3_joint" type="revolute">
    <parent link="wrist_2_link"/><child link="wrist_3_link"/>
    <origin xyz="0.0 0.0 0.1157" rpy="0.0 0.0 0.0"/><axis xyz="0 1 0"/>
    <limit lower="-6.2832" upper="6.2832" effort="54.0" velocity="3.2"/>
  </joint>
  <joint name="ee_fixed_joint" type="fixed">
    <parent link="wrist_3_link"/><child link="ee_link"/>
    <origin xyz="0.0 0.0922 0.0" rpy="0.0 0.0 1.570796325"/>
  </joint>
</robot>
"#;

#[test]
fn a_ur10_urdf_from_ur_description_stands_as_tall_as_urs_published_numbers() {
    let robot = robot_from_urdf(UR10_URDF).unwrap();
    let chain = UrdfChain::parse(UR10_URDF).unwrap();
    assert_eq!(robot.dof(), 6);
    let mut rng = common::rng(34);
    for _ in 0..1000 {
        let q: Vec<f64> = (0..6).map(|_| rng.uniform(-3.0, 3.0)).collect();
        let d = difference(&chain.tool_pose(&q), &tool_pose(&robot, &q));
        assert!(
            d <= 1e-9,
            "the DH import differs from the URDF chain by {d}"
        );
    }
    // Straight up (UR's own (0, -90°, 0, -90°, 0, 0)): the flange is d1 + a2 + a3 + d5 =
    // 1.4273 m high and d4 + d6 = 0.256141 m off the base axis (UR's published numbers).
    let straight = [0.0, -FRAC_PI_2, 0.0, -FRAC_PI_2, 0.0, 0.0];
    let up = tool_pose(&robot, &straight).translation.vector;
    assert!((up.z - 1.4273).abs() < 1e-9, "height {}", up.z);
    let off_axis = (up.x * up.x + up.y * up.y).sqrt();
    assert!(
        (off_axis - 0.256141).abs() < 1e-9,
        "off the axis {off_axis}"
    );
}
