//! The motion lab (docs/kinematics.md §17–12): controllers simulated in 1 ms steps with
//! measured numbers, the profiles' limits, and the typed errors of bad settings.

#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

use armlab_text::Sentence;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_core::motion::{STEP, check_time_scale};
use armlab_core::{
    Controller, JointProfile, MotionError, MotionLimits, MotionSettings, MotionSim, PidGains,
    Plant, ProfileShape, RobotError, Series, Setting, Trajectory, preset, robot_from_json,
};
use armlab_text::Lang;
use std::f64::consts::PI;

/// One revolute joint limited to ±180° (it wraps) with a speed limit of 180°/s = π rad/s.
fn one_joint() -> armlab_core::Robot {
    robot_from_json(
        r#"{"name": "one", "convention": "standard", "length_unit": "m",
            "joints": [{"type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0,
                        "max_speed": 180, "max_acceleration": 720}]}"#,
    )
    .expect("the test robot loads")
}

fn settings(controller: Controller, plant: Plant) -> MotionSettings {
    MotionSettings {
        controller,
        plant,
        record_capacity: 20_000,
        record_every: 1,
    }
}

fn ideal() -> Plant {
    Plant {
        time_constant: 0.0,
        ..Plant::default()
    }
}

/// Simulates `seconds` in frames of 1/60 s, as the app does.
fn run(sim: &mut MotionSim, seconds: f64) {
    let frames = (seconds * 60.0).round() as usize;
    for _ in 0..frames {
        sim.advance(1.0 / 60.0).expect("a frame time");
    }
}

/// Sign changes of q̇ in the record after time `from`.
fn reversals(sim: &MotionSim, from: f64) -> usize {
    let v: Vec<f64> = sim
        .record()
        .joint(0, Series::Velocity)
        .filter(|p| p[0] >= from && p[1] != 0.0)
        .map(|p| p[1])
        .collect();
    v.windows(2)
        .filter(|w| w[0].signum() != w[1].signum())
        .count()
}

#[test]
fn on_off_with_a_dead_band_below_speed_times_step_never_stops() {
    // Ideal motor: each step moves π·1 ms = 3.14 mrad. A start error of 100.5 steps leaves
    // half a step (1.57 mrad) to go, outside a dead band of 1 mrad: the joint jumps across
    // the goal to −1.57 mrad and back, for ever.
    let robot = one_joint();
    let step = PI * STEP;
    let on_off = Controller::OnOff {
        dead_band: 0.4 * step,
    };
    let mut sim = MotionSim::new(&robot, &[0.0], settings(on_off, ideal())).unwrap();
    sim.set_goal(&[100.5 * step]).unwrap();
    run(&mut sim, 3.0);
    assert_eq!(sim.steps_run(), 3000);
    let last_second: Vec<f64> = sim
        .record()
        .joint(0, Series::Error)
        .filter(|p| p[0] > 2.0)
        .map(|p| p[1])
        .collect();
    assert_eq!(last_second.len(), 1000);
    for e in &last_second {
        assert!((e.abs() - 0.5 * step).abs() < 1e-9, "error {e}");
    }
    assert!(reversals(&sim, 2.0) >= 999, "{}", reversals(&sim, 2.0));
    // Inside the 2 % band of its start error, yet never at rest.
    assert!(!sim.at_rest(0.5 * step, 1.0));
}

#[test]
fn on_off_with_a_motor_lag_chatters_the_longer_the_smaller_the_dead_band() {
    // With τ = 50 ms the joint coasts v·τ = 157 mrad after the command stops, past the
    // goal, and the on/off rule drives it back: with a dead band of 1 mrad it reverses
    // 13 times over 0.7 s before it stops inside the band; each approach is shorter and
    // slower. (Through a first-order lag the chatter dies out; it lasts for ever only
    // when the dead band is below speed × step, as above.)
    let robot = one_joint();
    let lag = Plant {
        time_constant: 0.05,
        ..Plant::default()
    };
    let small = Controller::OnOff { dead_band: 0.001 };
    let mut sim = MotionSim::new(&robot, &[0.0], settings(small, lag)).unwrap();
    sim.set_goal(&[1.0]).unwrap();
    run(&mut sim, 4.0);
    let n = reversals(&sim, 0.0);
    assert!(n >= 10, "a small dead band chatters: {n} reversals");
    let late = reversals(&sim, 0.6);
    assert!(late >= 1, "still chattering after 0.6 s: {late}");
    assert!(sim.error()[0].abs() < 0.001);

    let wide = Controller::OnOff { dead_band: 0.1 };
    let mut sim = MotionSim::new(&robot, &[0.0], settings(wide, lag)).unwrap();
    sim.set_goal(&[1.0]).unwrap();
    run(&mut sim, 4.0);
    assert_eq!(reversals(&sim, 0.0), 0);
    assert!(sim.qd()[0].abs() < 1e-9, "at rest: {}", sim.qd()[0]);
    // It coasted v·τ past the band's edge: e ≈ 0.1 − π·0.05 = −0.057, inside the band.
    let e = sim.error()[0];
    assert!((e - (0.1 - PI * 0.05)).abs() < 0.005, "{e}");
    assert!(sim.measures()[0].overshoot > 0.05);
}

#[test]
fn proportional_control_of_a_first_order_joint_converges_without_overshoot() {
    let robot = one_joint();
    let p = Controller::Proportional { gain: 5.0 };
    let mut sim = MotionSim::new(&robot, &[0.0], settings(p, ideal())).unwrap();
    sim.set_goal(&[1.5]).unwrap();
    run(&mut sim, 5.0);
    let m = sim.measures()[0];
    assert_eq!(m.overshoot, 0.0);
    assert!(m.error.abs() < 1e-8, "{}", m.error);
    // Saturated at π rad/s until K·e = π (e = 0.628), then e = 0.628·exp(−5t):
    // (1.5 − 0.628)/π + ln(0.628/0.03)/5 = 0.278 + 0.608 = 0.886 s to the 2 % band.
    let ts = m.settling_time.unwrap();
    assert!((ts - 0.886).abs() < 0.01, "settling time {ts}");
    let speeds: Vec<f64> = sim
        .record()
        .joint(0, Series::Velocity)
        .map(|p| p[1])
        .collect();
    assert!(speeds.iter().all(|v| *v >= 0.0 && *v <= PI + 1e-12));
    // The error never grows.
    let errors: Vec<f64> = sim
        .record()
        .joint(0, Series::Error)
        .filter(|p| p[0] > 0.0)
        .map(|p| p[1])
        .collect();
    assert!(errors[0] > 1.49);
    assert!(errors.windows(2).all(|w| w[1] <= w[0] + 1e-12));
}

#[test]
fn proportional_control_through_a_lag_overshoots_as_the_second_order_formula_says() {
    // τ·ë + ė + K·e = 0 with K·τ = 1: ζ = 1/(2√(Kτ)) = 0.5, overshoot exp(−πζ/√(1−ζ²)) = 16.3 %.
    let robot = one_joint();
    let p = Controller::Proportional { gain: 20.0 };
    let lag = Plant {
        time_constant: 0.05,
        ..Plant::default()
    };
    let mut sim = MotionSim::new(&robot, &[0.0], settings(p, lag)).unwrap();
    sim.set_goal(&[0.1]).unwrap();
    run(&mut sim, 3.0);
    let ratio = sim.measures()[0].overshoot_ratio.unwrap();
    assert!((ratio - 0.163).abs() < 0.01, "overshoot {ratio}");
}

#[test]
fn pd_leaves_the_load_over_kp_and_pid_removes_it() {
    let robot = one_joint();
    let loaded = Plant {
        load: 20.0,
        ..Plant::default()
    };
    let pd = Controller::Pid(PidGains {
        kp: 100.0,
        ki: 0.0,
        kd: 20.0,
    });
    let mut sim = MotionSim::new(&robot, &[0.0], settings(pd, loaded)).unwrap();
    sim.set_goal(&[1.0]).unwrap();
    run(&mut sim, 5.0);
    let e = sim.measures()[0].error;
    assert!(
        (e - 0.2).abs() < 1e-4,
        "PD steady-state error L/Kp = 0.2: {e}"
    );

    let pid = Controller::Pid(PidGains::default());
    let mut sim = MotionSim::new(&robot, &[0.0], settings(pid, loaded)).unwrap();
    sim.set_goal(&[1.0]).unwrap();
    run(&mut sim, 10.0);
    let m = sim.measures()[0];
    assert!(m.error.abs() < 1e-4, "PID steady-state error: {}", m.error);
    assert!(m.settling_time.is_some());
    // Without a load the critically damped PD does not overshoot.
    let mut sim = MotionSim::new(&robot, &[0.0], settings(pd, Plant::default())).unwrap();
    sim.set_goal(&[0.5]).unwrap();
    run(&mut sim, 3.0);
    let m = sim.measures()[0];
    assert!(m.overshoot < 1e-3 * 0.5, "overshoot {}", m.overshoot);
    assert!(m.error.abs() < 1e-6);
}

#[test]
fn advance_runs_whole_steps_and_keeps_the_remainder() {
    let robot = one_joint();
    let mut sim = MotionSim::new(&robot, &[0.0], MotionSettings::default()).unwrap();
    assert_eq!(sim.advance(0.0025).unwrap(), 2);
    assert_eq!(sim.advance(0.0025).unwrap(), 3);
    assert_eq!(sim.advance(0.0).unwrap(), 0);
    // Sixty frames of 1/60 s: one second, 1000 steps, however the frames split.
    let mut total = 5;
    for _ in 0..60 {
        total += sim.advance(1.0 / 60.0).unwrap();
    }
    assert_eq!(total, 1005);
    assert!((sim.time() - 1.005).abs() < 1e-9);
    // A long pause is not caught up.
    assert_eq!(sim.advance(30.0).unwrap(), 1000);
    assert!(matches!(
        sim.advance(-0.1),
        Err(MotionError::Negative { .. })
    ));
    assert!(matches!(
        sim.advance(f64::NAN),
        Err(MotionError::NotFinite { .. })
    ));
}

#[test]
fn the_record_is_bounded_and_tracks_the_tool_distance() {
    let robot = preset("planar-2r").unwrap();
    let s = MotionSettings {
        record_capacity: 50,
        record_every: 10,
        ..MotionSettings::default()
    };
    let mut sim = MotionSim::new(&robot, &[0.0, 0.0], s).unwrap();
    let target = armlab_core::tool_pose(&robot, &[0.5, 0.5])
        .translation
        .vector;
    sim.set_tool_target(Some(target));
    sim.set_goal(&[0.5, 0.5]).unwrap();
    run(&mut sim, 1.0);
    assert_eq!(sim.record().len(), 50);
    let times: Vec<f64> = sim.record().times().collect();
    assert!((times[0] - 0.51).abs() < 1e-9 && (times[49] - 1.0).abs() < 1e-9);
    let d: Vec<[f64; 2]> = sim.record().tool_distance().collect();
    assert_eq!(d.len(), 50);
    assert!(d[49][1] < d[0][1] && d[49][1] < 0.05, "{:?}", d[49]);
}

#[test]
fn the_profile_controller_follows_its_plan_to_the_goal() {
    let robot = preset("ur10").unwrap();
    let q0 = robot.home();
    let goal: Vec<f64> = q0.iter().map(|v| v + 0.7).collect();
    let c = Controller::Profile {
        shape: ProfileShape::Quintic,
        synchronised: true,
    };
    let mut sim = MotionSim::new(&robot, &q0, settings(c, Plant::default())).unwrap();
    sim.set_goal(&goal).unwrap();
    let duration = sim.trajectory().unwrap().duration;
    run(&mut sim, duration + 0.01);
    for (q, g) in sim.q().iter().zip(&goal) {
        assert!((q - g).abs() < 1e-12, "{q} vs {g}");
    }
    assert!(sim.at_rest(1e-12, 1e-12));
}

#[test]
fn trapezoids_cubics_and_quintics_never_exceed_the_limits() {
    let limits = MotionLimits {
        max_speed: 2.0,
        max_acceleration: 5.0,
    };
    for shape in ProfileShape::ALL {
        for distance in [-3.0, -0.1, 0.01, 0.5, 0.8, 4.0] {
            for stretch in [1.0, 1.7] {
                let t_min = JointProfile::min_duration(shape, distance, &limits);
                let p = JointProfile::new(shape, 0.3, distance, &limits, t_min * stretch);
                let (mut vmax, mut amax) = (0.0_f64, 0.0_f64);
                let n = 2000;
                for k in 0..=n {
                    let s = p.sample(p.duration * k as f64 / n as f64);
                    vmax = vmax.max(s.qd.abs());
                    amax = amax.max(s.qdd.abs());
                }
                let end = p.sample(p.duration);
                assert!((end.q - (0.3 + distance)).abs() < 1e-12);
                assert!(vmax <= 2.0 * (1.0 + 1e-9), "{shape:?} {distance}: v {vmax}");
                assert!(amax <= 5.0 * (1.0 + 1e-9), "{shape:?} {distance}: a {amax}");
                // The shortest time really uses a limit.
                if stretch == 1.0 {
                    let used = (vmax / 2.0).max(amax / 5.0);
                    assert!(used > 0.99, "{shape:?} {distance}: {used}");
                }
            }
        }
    }
    // The trapezoid's textbook numbers: D = 4, v = 2, a = 5: T = D/v + v/a = 2.4 s.
    let t = JointProfile::min_duration(ProfileShape::Trapezoidal, 4.0, &limits);
    assert!((t - 2.4).abs() < 1e-12);
    // Too short to cruise: a triangle of 2√(D/a).
    let t = JointProfile::min_duration(ProfileShape::Trapezoidal, 0.5, &limits);
    assert!((t - 2.0 * (0.1f64).sqrt()).abs() < 1e-12);
}

#[test]
fn synchronised_joints_arrive_together() {
    let robot = preset("ur10").unwrap();
    let from = robot.home();
    let to: Vec<f64> = from
        .iter()
        .enumerate()
        .map(|(i, v)| v + 0.2 * (i as f64 + 1.0))
        .collect();
    let shape = ProfileShape::Trapezoidal;
    let own = Trajectory::plan(&robot, &from, &to, shape, false).unwrap();
    let sync = Trajectory::plan(&robot, &from, &to, shape, true).unwrap();
    assert!((own.duration - sync.duration).abs() < 1e-12);
    let spread = |t: &Trajectory| {
        let d: Vec<f64> = t.joints.iter().map(|j| j.duration).collect();
        d.iter().cloned().fold(0.0, f64::max) - d.iter().cloned().fold(f64::MAX, f64::min)
    };
    assert!(spread(&own) > 0.1);
    assert!(spread(&sync) < 1e-12);
    // UR10 limits from its file: 120°/s and 180°/s, with the default 4× per second.
    let limits = MotionLimits::of_robot(&robot);
    assert!((limits[0].max_speed - 120f64.to_radians()).abs() < 1e-12);
    assert!((limits[0].max_acceleration - 480f64.to_radians()).abs() < 1e-12);
    for (p, l) in sync.joints.iter().zip(&limits) {
        assert!(p.cruise_speed <= l.max_speed * (1.0 + 1e-12));
    }
}

#[test]
fn bad_gains_and_settings_get_typed_errors_in_both_languages() {
    let robot = one_joint();
    let with =
        |c: Controller| MotionSim::new(&robot, &[0.0], settings(c, Plant::default())).map(|_| ());
    assert_eq!(
        with(Controller::Proportional { gain: -1.0 }),
        Err(MotionError::NotPositive {
            setting: Setting::Gain,
            value: -1.0
        })
    );
    assert!(matches!(
        with(Controller::Proportional { gain: 5000.0 }),
        Err(MotionError::TooLarge { setting: Setting::Gain, max, .. }) if max == 1000.0
    ));
    assert!(matches!(
        with(Controller::OnOff {
            dead_band: f64::NAN
        }),
        Err(MotionError::NotFinite {
            setting: Setting::DeadBand,
            ..
        })
    ));
    assert!(matches!(
        with(Controller::Pid(PidGains {
            kp: 100.0,
            ki: 5000.0,
            kd: 20.0
        })),
        Err(MotionError::TooLarge { setting: Setting::Ki, max, .. }) if (max - 2000.0).abs() < 1e-9
    ));
    assert!(matches!(
        with(Controller::Pid(PidGains {
            kp: 2e6,
            ki: 0.0,
            kd: 0.0
        })),
        Err(MotionError::TooLarge {
            setting: Setting::Kp,
            ..
        })
    ));
    assert!(check_time_scale(0.25).is_ok());
    let e = check_time_scale(-1.0).unwrap_err();
    assert_eq!(
        e.sentence(Lang::En),
        "Not a valid value for the time scale: it cannot be negative (-1)."
    );
    assert_eq!(
        e.sentence(Lang::Fi),
        "Arvo ei kelpaa (aikaskaala): se ei voi olla negatiivinen (-1)."
    );
    // A goal of the wrong length or with NaN.
    let mut sim = MotionSim::new(&robot, &[0.0], MotionSettings::default()).unwrap();
    assert_eq!(
        sim.set_goal(&[0.0, 1.0]),
        Err(MotionError::WrongJointCount {
            expected: 1,
            found: 2
        })
    );
    assert!(matches!(
        sim.set_goal(&[f64::NAN]),
        Err(MotionError::Robot(RobotError::JointValueNotFinite { .. }))
    ));
    // The old settings stay after a bad change.
    let good = *sim.settings();
    assert!(
        sim.set_settings(settings(
            Controller::OnOff { dead_band: -1.0 },
            Plant::default()
        ))
        .is_err()
    );
    assert_eq!(*sim.settings(), good);
}

#[test]
fn acceleration_limits_in_robot_files_are_checked() {
    let file = |acc: &str| {
        robot_from_json(&format!(
            r#"{{"name": "one", "convention": "standard", "length_unit": "m",
                "joints": [{{"type": "revolute", "theta_deg": 0, "d": 0, "a": 1,
                             "alpha_deg": 0, "max_acceleration": {acc}}}]}}"#
        ))
    };
    let r = file("360").unwrap();
    assert!((r.joints[0].max_acceleration.unwrap() - 2.0 * PI).abs() < 1e-12);
    let e = file("-10").unwrap_err();
    assert!(matches!(e, RobotError::NotPositive { .. }), "{e:?}");
    assert!(e.sentence(Lang::En).contains("max_acceleration"));
    assert!(file("\"fast\"").is_err());
    // It survives a round trip through the file format.
    let text = armlab_core::robot_to_json(&r);
    let back = robot_from_json(&text).unwrap();
    assert!((back.joints[0].max_acceleration.unwrap() - 2.0 * PI).abs() < 1e-12);
    // Without it, the default: the speed limit (default 90°/s) in a quarter second.
    let plain = one_joint_without_limits();
    let l = MotionLimits::of(&plain.joints[0]);
    assert!((l.max_speed - PI / 2.0).abs() < 1e-12);
    assert!((l.max_acceleration - 2.0 * PI).abs() < 1e-12);
}

fn one_joint_without_limits() -> armlab_core::Robot {
    robot_from_json(
        r#"{"name": "one", "convention": "standard", "length_unit": "m",
            "joints": [{"type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0}]}"#,
    )
    .expect("the test robot loads")
}
