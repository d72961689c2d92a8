//! A robot change leaves nothing of the old robot behind: random sequences of robot
//! changes and panel actions, and the notebook's run followed by another robot.

use super::*;
use crate::app::state::notebook::NotebookDemo;
use armlab_core::workspace::WorkspaceMeasure;
use armlab_core::{SplitMix64, preset, preset_ids};

/// A robot change: a preset, an edit of one DH length, or an edit of the joint count.
fn change_robot(model: &mut Model, rng: &mut SplitMix64) {
    let robot = model.robot().clone();
    match rng.next_u64() % 3 {
        0 => {
            let ids: Vec<&str> = preset_ids().collect();
            let id = ids[(rng.next_u64() % ids.len() as u64) as usize];
            model.load_robot(
                preset(id).expect("presets load"),
                RobotSource::Preset(id.into()),
            );
        }
        1 => {
            let mut edited = robot.clone();
            let i = (rng.next_u64() % edited.dof() as u64) as usize;
            edited.joints[i].dh.a += rng.uniform(-0.6, 0.6) * robot.reach();
            model.edit_robot(edited, RobotSource::Custom);
        }
        _ => {
            let mut edited = robot.clone();
            if edited.dof() > 2 {
                edited.joints.pop();
            } else {
                edited.joints.push(edited.joints[0].clone());
            }
            model.edit_robot(edited, RobotSource::Custom);
        }
    }
}

/// A panel action that leaves state found for the current robot.
fn panel_action(model: &mut Model, rng: &mut SplitMix64) {
    let robot = model.robot().clone();
    match rng.next_u64() % 8 {
        0 => {
            let mut target = *model.target();
            target.translation.vector.x += rng.uniform(-0.5, 0.5) * robot.reach();
            model.set_target(target);
            if let Some(run) = model.solve_with_trace() {
                model.keep_replay(run, None);
            }
        }
        1 => {
            let step = model.replay().map_or(0, |r| r.step / 2);
            model.replay_step(step);
        }
        2 => {
            let rows = vec![BranchRow {
                q: rng.joint_vector(&robot),
                label: "a".into(),
                within_limits: true,
            }];
            model.set_branches(rows, false);
        }
        3 => {
            model.fill_workspace(WorkspaceMeasure::Manipulability, 64, 1.0, || 0.0);
        }
        4 => {
            // Far out along the tool: the drag stalls and the rescue is searched.
            let mut target = *model.target();
            target.translation.vector *= 3.0;
            model.set_target(target);
            for _ in 0..3 {
                model.drag_step();
            }
        }
        5 => {
            let _ = model.add_waypoint();
        }
        6 => model.set_hovered_column(Some(robot.dof() - 1), HoverSource::Matrices),
        _ => {
            if let Some(run) = NotebookDemo::Gradient.run(model) {
                model.keep_replay(run, Some(NotebookDemo::Gradient));
            }
        }
    }
}

/// Nothing the model shows was found for another robot than its own.
fn assert_of_this_robot(model: &Model, context: &str) {
    let dof = model.robot().dof();
    if let Some(replay) = model.replay() {
        assert!(
            replay.run.trace.iter().all(|s| s.q.len() == dof),
            "{context}"
        );
        assert_eq!(replay.run.q.len(), dof, "{context}");
    }
    if let Some(b) = model.branches() {
        assert!(b.rows.iter().all(|r| r.q.len() == dof), "{context}");
    }
    assert!(model.hovered_column().is_none_or(|c| c < dof), "{context}");
}

#[test]
fn a_robot_change_clears_every_state_of_the_old_robot() {
    let mut rng = SplitMix64::new(0x0b07);
    let mut unit_changes_with_waypoints = 0;
    for sequence in 0..12 {
        let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
        for call in 0..30 {
            let context = format!("sequence {sequence}, call {call}");
            if rng.next_u64().is_multiple_of(3) {
                let unit = model.robot().length_unit;
                let waypoints = model.paths().waypoints().len();
                change_robot(&mut model, &mut rng);
                assert!(model.replay().is_none(), "{context}: a replay");
                assert!(model.branches().is_none(), "{context}: solutions");
                assert!(model.workspace().is_none(), "{context}: a cloud");
                assert!(model.rescue().is_none(), "{context}: a rescue");
                assert!(model.directions().is_none(), "{context}: directions");
                assert!(model.kept_branch().is_none(), "{context}: a kept branch");
                assert!(model.branch_switch().is_none(), "{context}: a switch");
                if model.robot().length_unit != unit && waypoints > 0 {
                    unit_changes_with_waypoints += 1;
                    assert!(model.paths().waypoints().is_empty(), "{context}");
                    assert!(model.message().is_some(), "{context}: no sentence");
                } else {
                    assert_eq!(model.paths().waypoints().len(), waypoints, "{context}");
                }
            } else {
                panel_action(&mut model, &mut rng);
            }
            assert_of_this_robot(&model, &context);
        }
    }
    assert!(
        unit_changes_with_waypoints > 0,
        "the sequences change units"
    );
}

#[test]
fn the_notebook_replay_ends_when_the_ur10_opens() {
    let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
    let run = NotebookDemo::Gradient.run(&mut model).expect("the run");
    model.keep_replay(run, Some(NotebookDemo::Gradient));
    assert_eq!(model.replay().map(|r| r.run.iterations), Some(1000));
    model.load_robot(
        preset("ur10").expect("preset"),
        RobotSource::Preset("ur10".into()),
    );
    assert!(model.replay().is_none());
    let home = model.q().to_vec();
    model.replay_step(3);
    assert_eq!(model.q(), home.as_slice(), "the old run moved the UR10");
}
