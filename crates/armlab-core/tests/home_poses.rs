//! Every preset opens in a recognisable, non-singular home pose (docs/kinematics.md §6):
//! within its limits, the smallest scaled singular value of its default task at least
//! 0.1, the tool above the floor (z > 0) and in front of the base (x > 0); planar arms
//! lie in their plane and are exempt from the last two.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::{ForwardKinematics, Task, geometric_jacobian, jacobian_measures};

#[test]
fn every_preset_opens_in_a_non_singular_home_pose_in_front_of_the_base() {
    for (id, robot) in common::all_presets() {
        let home = robot.home();
        common::assert_within_limits(&id, &robot, &home);
        let fk = ForwardKinematics::new(&robot, &home).unwrap();
        let task = Task::default_for(robot.dof());
        let m = jacobian_measures(
            &geometric_jacobian(&fk),
            task,
            fk.tool_rotation(),
            robot.reach(),
        );
        let smallest = m.singular_values.last().copied().unwrap_or(0.0);
        assert!(
            smallest >= 0.1,
            "{id}: home {home:?} is near a singularity of its {} task (σ_min = {smallest})",
            task.id()
        );
        let planar = fk
            .joint_axes
            .iter()
            .all(|z| (z.z.abs() - 1.0).abs() < 1e-12)
            && fk
                .base_from_frames
                .iter()
                .all(|f| f.translation.vector.z.abs() < 1e-12);
        if !planar {
            let p = fk.tool_position();
            assert!(
                p.z > 0.0,
                "{id}: the tool is below the floor at home ({p:?})"
            );
            assert!(
                p.x > 0.0,
                "{id}: the tool is behind the base at home ({p:?})"
            );
        }
    }
}

#[test]
fn arms_with_fewer_than_six_joints_open_with_the_position_task() {
    assert_eq!(Task::default_for(2), Task::Position);
    assert_eq!(Task::default_for(5), Task::Position);
    assert_eq!(Task::default_for(6), Task::FullPose);
    assert_eq!(Task::default_for(7), Task::FullPose);
}
