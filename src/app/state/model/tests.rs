//! The model's tests: random call sequences keep every derived value fresh; the target,
//! the drag, the closed form's branches and the rescue behave as the panels promise.

use super::*;
use armlab_core::ik::{Elbow, Shoulder, Wrist, branch_of, closed_form_solutions, joint_distance};
use armlab_core::{SplitMix64, geometric_jacobian, preset, preset_ids, tool_pose};

/// One call of the model's writing API, drawn at random.
fn random_call(model: &mut Model, rng: &mut SplitMix64) {
    let robot = model.robot().clone();
    match rng.next_u64() % 12 {
        0 => model.set_q(rng.joint_vector(&robot)),
        1 => {
            // Slid or typed values, some outside the limits.
            let q = rng.joint_vector(&robot).iter().map(|v| v * 1.5).collect();
            model.set_q_exact(q);
        }
        2 | 3 => {
            let mut target = *model.target();
            let reach = robot.reach();
            target.translation.vector += nalgebra::Vector3::new(
                rng.uniform(-0.3, 0.3) * reach,
                rng.uniform(-0.3, 0.3) * reach,
                rng.uniform(-0.3, 0.3) * reach,
            );
            model.set_target(target);
        }
        4 => model.snap_target(),
        5 => model.set_task(Task::ALL[(rng.next_u64() % Task::ALL.len() as u64) as usize]),
        6 => {
            model.set_method(IkMethod::ALL[(rng.next_u64() % IkMethod::ALL.len() as u64) as usize])
        }
        7 => {
            let ids: Vec<&str> = preset_ids().collect();
            let id = ids[(rng.next_u64() % ids.len() as u64) as usize];
            let robot = preset(id).expect("presets load");
            model.load_robot(robot, RobotSource::Preset(id.to_string()));
        }
        8 => {
            // An edit of one DH length, as the editor makes it.
            let mut edited = robot.clone();
            let i = (rng.next_u64() % edited.dof() as u64) as usize;
            edited.joints[i].dh.a += rng.uniform(-0.2, 0.2) * robot.reach();
            model.edit_robot(edited, RobotSource::Custom);
        }
        9 | 10 => {
            model.drag_step();
        }
        _ => {
            model.solve_with_trace();
        }
    }
}

/// The derived values equal a fresh recomputation from the session alone.
fn assert_derived_values_fresh(model: &Model, context: &str) {
    let robot = model.robot();
    assert_eq!(model.q().len(), robot.dof(), "{context}");
    let fresh = ForwardKinematics::new(robot, model.q()).expect("a valid q");
    assert_eq!(model.fk().base_from_tool, fresh.base_from_tool, "{context}");
    assert_eq!(
        model.fk().base_from_frames,
        fresh.base_from_frames,
        "{context}"
    );
    assert_eq!(*model.jacobian(), geometric_jacobian(&fresh), "{context}");
    assert_eq!(
        *model.motion_space(),
        armlab_core::linear_motion_space(robot),
        "{context}"
    );
    let (position, orientation) = pose_error(robot, model.q(), model.target(), model.task());
    assert_eq!(model.ik().position_error, position, "{context}");
    assert_eq!(model.ik().orientation_error, orientation, "{context}");
    let tolerance = REACHED_POSITION_TOLERANCE_M / robot.length_unit.in_metres();
    let within = position <= tolerance && orientation <= REACHED_ORIENTATION_TOLERANCE;
    assert_eq!(model.ik().reach == Reach::Reached, within, "{context}");
    for (i, (v, joint)) in model.q().iter().zip(&robot.joints).enumerate() {
        assert!(
            joint.limits.contains(*v, 1e-9),
            "{context}: joint {} at {v} outside [{}, {}]",
            i + 1,
            joint.limits.min,
            joint.limits.max
        );
    }
    if model.method() == IkMethod::ClosedForm {
        assert!(model.has_closed_form(), "{context}");
    }
    if let Some(link) = model.hovered_link() {
        assert!(link <= robot.dof(), "{context}");
    }
}

#[test]
fn random_call_sequences_keep_every_derived_value_fresh() {
    let mut rng = SplitMix64::new(20_261_123);
    for sequence in 0..60 {
        let ids: Vec<&str> = preset_ids().collect();
        let id = ids[sequence % ids.len()];
        let mut model = Model::new(Session::for_preset(id).expect("presets load"));
        assert_derived_values_fresh(&model, &format!("{id}, new"));
        for call in 0..40 {
            random_call(&mut model, &mut rng);
            assert_derived_values_fresh(&model, &format!("{id}, sequence {sequence}, call {call}"));
        }
    }
}

#[test]
fn the_target_is_stored_once_and_travels_in_the_link() {
    let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
    let mut target = *model.target();
    target.translation.vector.x -= 150.0;
    model.set_target(target);
    assert_eq!(model.ik().reach, Reach::Pending);
    let reopened = Session::from_hash(&model.hash())
        .expect("a valid link")
        .expect("not empty");
    let back = reopened.target.expect("the link names the target");
    assert!((back.translation.vector - target.translation.vector).norm() < 1e-6);
    let again = Model::new(reopened);
    assert!((again.target().translation.vector - target.translation.vector).norm() < 1e-6);
}

#[test]
fn the_drag_step_runs_only_while_the_target_is_not_reached() {
    let mut model = Model::new(Session::for_preset("rrr").expect("preset"));
    assert_eq!(
        model.ik().reach,
        Reach::Reached,
        "the target opens on the tool"
    );
    assert!(!model.drag_step(), "nothing to do at the target");
    // Home is the stretched arm, a singular pose whose Jacobian has no component
    // toward the base: start from a bent elbow instead.
    model.set_q(vec![0.0, 0.5, -1.0]);
    model.snap_target();
    assert!(!model.drag_step(), "nothing to do at the target");
    let mut target = *model.target();
    target.translation.vector.x -= 40.0;
    model.set_target(target);
    model.set_task(Task::Position);
    let mut steps = 0;
    while model.drag_step() {
        steps += 1;
        assert!(
            steps < 200,
            "the drag converges: {:?} at {:?}",
            model.ik(),
            model.q()
        );
    }
    assert_eq!(model.ik().reach, Reach::Reached);
    assert!(model.ik().position_error < 1e-6);
}

#[test]
fn an_unreachable_target_is_out_of_reach_until_moved_back() {
    let mut model = Model::new(Session::for_preset("planar-2r").expect("preset"));
    model.set_task(Task::Position);
    let mut target = *model.target();
    target.translation.vector = nalgebra::Vector3::new(5.0, 1.0, 0.0);
    model.set_target(target);
    for _ in 0..100 {
        model.drag_step();
    }
    assert_eq!(model.ik().reach, Reach::OutOfReach);
    model.snap_target();
    assert_eq!(model.ik().reach, Reach::Reached);
}

#[test]
fn the_closed_form_is_kept_only_where_the_robot_has_one() {
    let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
    model.set_method(IkMethod::ClosedForm);
    assert_eq!(model.method(), IkMethod::ClosedForm);
    model.load_robot(
        preset("panda").expect("preset"),
        RobotSource::Preset("panda".into()),
    );
    assert_eq!(model.method(), IkMethod::DampedLeastSquares);
    model.set_method(IkMethod::ClosedForm);
    assert_eq!(model.method(), IkMethod::DampedLeastSquares);
}

/// A random q of `robot` (within its limits) whose closed-form branch is `branch`.
fn q_on_branch(robot: &Robot, branch: Branch, rng: &mut SplitMix64) -> Vec<f64> {
    loop {
        let q = rng.joint_vector(robot);
        if branch_of(robot, &q).ok().flatten() == Some(branch) {
            return q;
        }
    }
}

#[test]
fn a_closed_form_drag_keeps_its_branch_by_label_and_says_when_it_vanishes() {
    let mut rng = SplitMix64::new(12);
    let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
    model.set_method(IkMethod::ClosedForm);
    model.set_task(Task::FullPose);
    let robot = model.robot().clone();
    // Kept: targets of the arm's own branch, reached on that branch.
    for _ in 0..20 {
        let start = rng.joint_vector(&robot);
        let Some(branch) = branch_of(&robot, &start).expect("a valid q") else {
            panic!("the UR10 has a closed form");
        };
        model.set_q(start);
        let goal = q_on_branch(&robot, branch, &mut rng);
        model.set_target(tool_pose(&robot, &goal));
        for _ in 0..200 {
            if !model.drag_step() {
                break;
            }
            assert_eq!(model.kept_branch(), Some(branch), "the label is kept");
        }
        assert_eq!(model.ik().reach, Reach::Reached);
        assert_eq!(branch_of(&robot, model.q()).ok().flatten(), Some(branch));
        assert_eq!(model.branch_switch(), None);
    }
    // Vanished: a target with only some branches, the arm on a missing one.
    let mut switched = 0;
    for _ in 0..2000 {
        let goal = rng.joint_vector(&robot);
        let target = tool_pose(&robot, &goal);
        let set = closed_form_solutions(&robot, &target, &goal).expect("a valid target");
        let present: Vec<Branch> = set
            .solutions
            .iter()
            .filter(|s| s.exact)
            .map(|s| s.branch)
            .collect();
        let Some(missing) = [false, true]
            .iter()
            .flat_map(|&left| [false, true].map(|up| (left, up)))
            .flat_map(|(left, up)| {
                [false, true].map(|flip| Branch {
                    shoulder: Some(if left {
                        Shoulder::Left
                    } else {
                        Shoulder::Right
                    }),
                    elbow: Some(if up { Elbow::Up } else { Elbow::Down }),
                    wrist: Some(if flip {
                        Wrist::Flipped
                    } else {
                        Wrist::NotFlipped
                    }),
                })
            })
            .find(|b| !present.contains(b))
        else {
            continue;
        };
        model.set_q(q_on_branch(&robot, missing, &mut rng));
        model.set_target(target);
        model.drag_step();
        let Some((asked, taken)) = model.branch_switch() else {
            panic!("the branch {} vanished", missing.id());
        };
        assert_eq!(asked, missing);
        assert!(present.contains(&taken), "{} is a branch here", taken.id());
        assert_eq!(model.kept_branch(), Some(taken));
        switched += 1;
        if switched == 5 {
            break;
        }
    }
    assert_eq!(
        switched, 5,
        "targets with fewer than eight branches were found"
    );
}

#[test]
fn a_stalled_drag_offers_the_start_that_reaches_and_says_out_of_reach_only_when_none_does() {
    let mut rng = SplitMix64::new(5);
    let mut model = Model::new(Session::for_preset("puma560").expect("preset"));
    model.set_method(IkMethod::DampedLeastSquares);
    let robot = model.robot().clone();
    let mut rescued = 0;
    for _ in 0..400 {
        model.set_q(rng.joint_vector(&robot));
        let goal = rng.joint_vector(&robot);
        model.set_target(tool_pose(&robot, &goal));
        for _ in 0..300 {
            if !model.drag_step() || model.ik().reach == Reach::OutOfReach {
                break;
            }
        }
        if model.ik().reach != Reach::OutOfReach {
            continue;
        }
        // Every stall gets the search: which joint holds it, and the other starts.
        let rescue = model.rescue().cloned().expect("a stall is searched");
        // The target is FK of a q within the limits: some start usually reaches it.
        let Some(q) = rescue.reach.clone() else {
            assert_eq!(model.shown_reach(), Reach::OutOfReach);
            continue;
        };
        assert_eq!(
            model.shown_reach(),
            Reach::Pending,
            "not called out of reach"
        );
        if let Some((j, at_max)) = rescue.held {
            let joint = &robot.joints[j];
            let limit = if at_max {
                joint.limits.max
            } else {
                joint.limits.min
            };
            assert!((model.q()[j] - limit).abs() < 1e-5, "held at the limit");
        }
        model.take_rescue();
        assert!(
            joint_distance(&robot, model.q(), &q) < 1e-12,
            "the arm took it"
        );
        assert_eq!(
            model.ik().reach,
            Reach::Reached,
            "the other start reaches it"
        );
        rescued += 1;
        if rescued == 3 {
            break;
        }
    }
    assert!(rescued >= 3, "{rescued} stalls were rescued");
    // Far away: out of reach from every start, and said so.
    let mut far = *model.target();
    far.translation.vector *= 50.0;
    model.set_target(far);
    for _ in 0..300 {
        if !model.drag_step() || model.ik().reach == Reach::OutOfReach {
            break;
        }
    }
    assert_eq!(model.shown_reach(), Reach::OutOfReach);
    if let Some(rescue) = model.rescue() {
        assert_eq!(rescue.reach, None);
    }
}

#[test]
fn a_target_inside_the_ur10_s_base_cylinder_has_one_verdict_everywhere() {
    // Dragged to 135 mm from the base axis, inside the cylinder the shoulder offset
    // leaves unreachable, with the pseudo-inverse: its steps never settle.
    let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
    model.set_method(IkMethod::PseudoInverse);
    let start = *model.target();
    let mut goal = start;
    goal.translation.vector.x = -135.0;
    goal.translation.vector.y = 0.0;
    for i in 1..=60 {
        let mut t = start;
        let f = i as f64 / 60.0;
        t.translation.vector = start.translation.vector * (1.0 - f) + goal.translation.vector * f;
        model.set_target(t);
        model.drag_step();
    }
    for _ in 0..300 {
        model.drag_step();
    }
    let set = closed_form_solutions(model.robot(), model.target(), model.q()).expect("a set");
    assert!(set.unreachable, "the closed form has no exact solution");
    assert!(
        model.ik().position_error > 1.0,
        "{}",
        model.ik().position_error
    );
    assert_eq!(
        model.shown_reach(),
        Reach::OutOfReach,
        "the ball and the status"
    );
    let run = model.solve_with_trace().expect("a run");
    assert!(!run.success);
    assert!(run.unreachable, "Solve says out of reach, not stopped");
    assert_eq!(model.shown_reach(), Reach::OutOfReach);
    // Back at the tool: reached again.
    model.snap_target();
    assert_eq!(model.shown_reach(), Reach::Reached);
}
