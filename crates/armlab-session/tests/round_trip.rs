//! Random sessions of every preset survive the link and the stored JSON: `Session → link →
//! Session` and `Session → JSON → Session` are the identity (`==`), for random joint
//! values within the limits, targets, tasks, methods, display patches, cameras, motion
//! lab fields and exercises. The draws come from a seeded xorshift generator, so a
//! failure repeats with its seed.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_core::exercise::mystery_arm;
use armlab_core::motion::{Controller, MotionSettings, PidGains, Plant};
use armlab_core::path::PathKind;
use armlab_core::profile::ProfileShape;
use armlab_core::{IkMethod, Robot, Task, preset, preset_ids};
use armlab_session::exercise::ExerciseId;
use armlab_session::format::target_from_array;
use armlab_session::motion::MotionPatch;
use armlab_session::session::{RobotSource, Session};
use armlab_session::settings::{
    CameraPose, DisplayPatch, Hidden, HiddenSet, MatrixId, Overlay, OverlaySet, PanelKind, PanelSet,
};
use armlab_text::Lang;
use nalgebra::{IsometryMatrix3, Point3, Vector3};
use std::f64::consts::PI;

/// Sessions drawn per preset.
const SESSIONS_PER_PRESET: usize = 40;

/// xorshift64* (Vigna): small, seeded, the same natively and on wasm32.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn chance(&mut self) -> bool {
        self.next() & 1 == 1
    }

    /// A value the link writes with six decimals and reads back unchanged: drawn in
    /// [lo, hi] and rounded to the link's decimals (as the link's text parses).
    fn linked(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.range(lo, hi);
        format!("{v:.6}").parse().expect("a number")
    }

    /// A pose as the link writes it: a position and Z-Y-X Euler angles of six decimals,
    /// the angles clear of zero (the link writes a number below 10⁻⁴ in scientific form
    /// with all its digits, and an angle of zero reads back from the matrix as ±10⁻¹⁷)
    /// and β clear of the gimbal lock. The link and the stored JSON both keep a pose as
    /// these six numbers, so such a pose comes back exactly from either.
    fn pose(&mut self) -> IsometryMatrix3<f64> {
        let sign = |rng: &mut Rng| if rng.chance() { 1.0 } else { -1.0 };
        let angle = |rng: &mut Rng, max: f64| sign(rng) * rng.linked(0.001, max);
        target_from_array(&[
            self.linked(-1500.0, 1500.0),
            self.linked(-1500.0, 1500.0),
            self.linked(-1500.0, 1500.0),
            angle(self, 3.1),
            angle(self, 1.5),
            angle(self, 3.1),
        ])
    }

    fn pick<T: Copy>(&mut self, values: &[T]) -> T {
        values[self.below(values.len())]
    }
}

/// Joint values within the limits, of six decimals (a revolute joint without limits
/// spans the full turn).
fn joint_values(rng: &mut Rng, robot: &Robot) -> Vec<f64> {
    robot
        .joints
        .iter()
        .map(|j| rng.linked(j.limits.min + 1e-6, j.limits.max - 1e-6))
        .collect()
}

/// A display patch with each field present or not; hidden items only when there are
/// some (a link writes no empty `hide=`).
fn display_patch(rng: &mut Rng, dof: usize) -> DisplayPatch {
    let panels = |rng: &mut Rng| {
        let kinds: Vec<PanelKind> = PanelKind::ALL
            .into_iter()
            .filter(|_| rng.chance())
            .collect();
        PanelSet::of(&kinds)
    };
    let mut patch = DisplayPatch::default();
    if rng.chance() {
        patch.degrees = Some(rng.chance());
    }
    if rng.chance() {
        patch.show_frames = Some(rng.chance());
    }
    if rng.chance() {
        patch.precision = Some(rng.below(9));
    }
    if rng.chance() {
        patch.presentation = Some(rng.chance());
    }
    if rng.chance() {
        patch.lang = Some(rng.pick(&Lang::ALL));
    }
    if rng.chance() {
        patch.panels = Some(panels(rng));
    }
    if rng.chance() {
        patch.presentation_panels = Some(panels(rng));
    }
    if rng.chance() {
        let overlays: Vec<Overlay> = Overlay::ALL.into_iter().filter(|_| rng.chance()).collect();
        patch.overlays = Some(OverlaySet::of(&overlays));
    }
    if rng.chance() {
        patch.hidden = Some(hidden_items(rng, dof));
    }
    patch
}

/// One to four hidden items: matrices, entries and Jacobian columns of a `dof` arm.
fn hidden_items(rng: &mut Rng, dof: usize) -> HiddenSet {
    let mut set = HiddenSet::default();
    for _ in 0..1 + rng.below(4) {
        let i = 1 + rng.below(dof);
        let matrix = rng.pick(&[MatrixId::Tool, MatrixId::Link(i), MatrixId::Frame(i)]);
        let item = match rng.below(3) {
            0 => Hidden::Matrix(matrix),
            1 => Hidden::Entry(matrix, 1 + rng.below(4), 1 + rng.below(4)),
            _ => Hidden::JacobianColumn(i),
        };
        if !set.contains(item) {
            set.toggle(item);
        }
    }
    set
}

/// Motion settings the core accepts: a random controller and plant, drawn again until
/// [`MotionSettings::check`] passes.
fn motion_settings(rng: &mut Rng) -> MotionSettings {
    for _ in 0..100 {
        let controller = match rng.below(5) {
            0 => Controller::OnOff {
                dead_band: rng.linked(0.001, 0.1),
            },
            1 => Controller::Proportional {
                gain: rng.linked(0.5, 50.0),
            },
            2 => Controller::Pid(PidGains {
                kp: rng.linked(1.0, 300.0),
                ki: 0.0,
                kd: rng.linked(0.5, 40.0),
            }),
            3 => Controller::Pid(PidGains {
                kp: rng.linked(1.0, 300.0),
                ki: rng.linked(0.5, 100.0),
                kd: rng.linked(0.5, 40.0),
            }),
            _ => Controller::Profile {
                shape: rng.pick(&ProfileShape::ALL),
                synchronised: rng.chance(),
            },
        };
        let settings = MotionSettings {
            controller,
            plant: Plant {
                time_constant: rng.linked(0.005, 0.3),
                inertia: rng.linked(0.5, 5.0),
                friction: rng.linked(0.0, 2.0),
                load: rng.linked(0.0, 50.0),
            },
            ..MotionSettings::default()
        };
        if settings.check().is_ok() {
            return settings;
        }
    }
    MotionSettings::default()
}

/// A motion patch with each field present or not (the path kind only as a link writes
/// it: `line`, the default `joint` being no field).
fn motion_patch(rng: &mut Rng) -> MotionPatch {
    let mut patch = MotionPatch::default();
    if rng.chance() {
        patch.move_on = Some(rng.chance());
    }
    if rng.chance() {
        patch.settings = Some(motion_settings(rng));
    }
    if rng.chance() {
        patch.time_scale = Some(rng.linked(0.01, 5.0));
    }
    if rng.chance() {
        patch.collisions = Some(rng.chance());
    }
    if rng.chance() {
        let boxes = (0..rng.below(4))
            .map(|i| {
                let mut v = || rng.linked(-1000.0, 1000.0);
                let centre = Point3::new(v(), v(), v());
                let size = Vector3::new(
                    rng.linked(1.0, 500.0),
                    rng.linked(1.0, 500.0),
                    rng.linked(1.0, 500.0),
                );
                armlab_core::collision::KeepOut::new(i + 1, centre, size).expect("a box")
            })
            .collect();
        patch.keep_outs = Some(boxes);
    }
    if rng.chance() {
        patch.path_kind = Some(PathKind::Cartesian);
    }
    if rng.chance() {
        patch.waypoints = Some((0..1 + rng.below(4)).map(|_| rng.pose()).collect());
    }
    patch
}

/// The robot and where it comes from: the preset by id, the preset as a custom table, or
/// (an exercise) the preset's or a mystery arm's unnamed robot.
fn robot_of(rng: &mut Rng, id: &str) -> (Robot, RobotSource, Option<ExerciseId>) {
    match rng.below(6) {
        0 | 1 => (
            preset(id).expect("a preset"),
            RobotSource::Preset(id.to_string()),
            None,
        ),
        2 | 3 => (preset(id).expect("a preset"), RobotSource::Custom, None),
        4 => {
            let exercise = ExerciseId::Preset(id.to_string());
            (
                exercise.robot().expect("loads"),
                RobotSource::Custom,
                Some(exercise),
            )
        }
        _ => {
            let exercise = ExerciseId::Mystery(rng.next() % 1000);
            (
                exercise.robot().expect("loads"),
                RobotSource::Custom,
                Some(exercise),
            )
        }
    }
}

/// A random session of the preset `id`.
fn random_session(rng: &mut Rng, id: &str) -> Session {
    let (robot, source, exercise) = robot_of(rng, id);
    let dof = robot.dof();
    Session {
        q: joint_values(rng, &robot),
        robot,
        source,
        target: rng.chance().then(|| rng.pose()),
        task: rng.pick(&Task::ALL),
        method: rng.pick(&IkMethod::ALL),
        display: display_patch(rng, dof),
        camera: rng.chance().then(|| {
            CameraPose::from_array([
                rng.linked(-3.1, 3.1),
                rng.linked(-1.5, 1.5),
                rng.linked(1.0, 5000.0),
                rng.linked(-1000.0, 1000.0),
                rng.linked(-1000.0, 1000.0),
                rng.linked(-1000.0, 1000.0),
            ])
            .expect("a positive distance")
        }),
        motion: motion_patch(rng),
        exercise,
        dropped: Vec::new(),
    }
}

#[test]
fn every_preset_s_random_sessions_survive_the_link_and_the_json() {
    let ids: Vec<&str> = preset_ids().collect();
    assert_eq!(ids.len(), 9, "every preset");
    let mut rng = Rng(0x5E55_1011_2026);
    let mut exercises = 0;
    for id in ids {
        for n in 0..SESSIONS_PER_PRESET {
            let session = random_session(&mut rng, id);
            exercises += usize::from(session.exercise.is_some());
            let hash = session.to_hash();
            let linked = Session::from_hash(&hash)
                .unwrap_or_else(|e| panic!("{id} #{n}: {e}\n{hash}"))
                .expect("a session");
            assert_eq!(linked, session, "{id} #{n}: the link\n{hash}");
            let json = session.to_json();
            let stored =
                Session::from_json(&json).unwrap_or_else(|e| panic!("{id} #{n}: {e}\n{json}"));
            assert_eq!(stored, session, "{id} #{n}: the JSON\n{json}");
            // serde's own entry points give the same session.
            let through_serde: Session = serde_json::from_str(&json).expect("reads");
            assert_eq!(through_serde, session, "{id} #{n}: serde_json::from_str");
            let written: serde_json::Value =
                serde_json::from_str(&serde_json::to_string(&session).expect("writes"))
                    .expect("JSON");
            assert_eq!(
                written,
                serde_json::from_str::<serde_json::Value>(&json).expect("JSON")
            );
        }
    }
    assert!(exercises > 20, "{exercises} exercise sessions");
}

#[test]
fn an_exercise_s_stored_session_shows_none_of_its_table() {
    let mut session = Session::for_preset("rrr").expect("a preset");
    let exercise = ExerciseId::Mystery(17);
    session.robot = exercise.robot().expect("loads");
    session.q = session.robot.home();
    session.source = RobotSource::Custom;
    session.exercise = Some(exercise);
    let json = session.to_json();
    let value: serde_json::Value = serde_json::from_str(&json).expect("JSON");
    assert_eq!(value.get("robot"), None, "{json}");
    assert_eq!(value["exercise"], "mystery-17");
    for field in ["joints", "theta_deg", "alpha_deg", "convention"] {
        assert!(!json.contains(field), "{field}: {json}");
    }
    let back = Session::from_json(&json).expect("reads");
    assert_eq!(back.robot.joints.len(), mystery_arm(17).dof());
    assert_eq!(back, session);
}

#[test]
fn any_pose_survives_the_link_and_the_json_within_rounding() {
    let mut rng = Rng(7);
    for _ in 0..300 {
        let a = [
            rng.range(-1500.0, 1500.0),
            rng.range(-1500.0, 1500.0),
            rng.range(-1500.0, 1500.0),
            rng.range(-PI, PI),
            rng.range(-1.55, 1.55),
            rng.range(-PI, PI),
        ];
        let mut session = Session::default_session();
        session.target = Some(target_from_array(&a));
        let pose = session.target.expect("a target");
        let stored = Session::from_json(&session.to_json()).expect("reads");
        let linked = Session::from_hash(&session.to_hash())
            .expect("reads")
            .expect("a session");
        // Both keep the link's six decimals: a coordinate and an angle move by at most
        // 5·10⁻⁷ each, and both give the same pose.
        assert_eq!(stored.target, linked.target, "{a:?}");
        for (what, back, moves, turns) in
            [("JSON", stored, 1e-6, 5e-6), ("link", linked, 1e-6, 5e-6)]
        {
            let back = back.target.expect("a target");
            let moved = (back.translation.vector - pose.translation.vector).norm();
            let turned = (back.rotation.matrix() - pose.rotation.matrix()).norm();
            assert!(moved <= moves, "{what}: {a:?} moved {moved}");
            assert!(turned < turns, "{what}: {a:?} turned {turned}");
        }
    }
}
