//! The reachable workspace (docs/kinematics.md §12): a cloud of tool positions from random
//! joint vectors, filled a few milliseconds per frame, coloured by a measure, optionally
//! only its slice through the target (the IK panel's workspace fold switches it).

use nalgebra::{Point3, Rotation3, Vector3};

use armlab_core::workspace::WorkspaceMeasure;

use crate::app::state::model::Model;
use crate::app::view3d::scene::instance;
use crate::render::{Instance, Shape};
use armlab_session::settings::Overlay;

/// Samples in the cloud.
pub const SAMPLES: usize = 20_000;
/// Milliseconds a frame may spend filling it.
pub const BUDGET_MS: f64 = 4.0;

/// The measure the cloud is coloured by.
pub fn measure(model: &Model) -> WorkspaceMeasure {
    if model.settings().overlays.contains(Overlay::WorkspaceSigma) {
        WorkspaceMeasure::SigmaMin
    } else {
        WorkspaceMeasure::Manipulability
    }
}

/// Blue (low) to yellow (high): the colour of a sample whose measure is `t` of the
/// cloud's largest.
pub fn ramp(t: f64) -> [u8; 4] {
    let t = t.clamp(0.0, 1.0);
    let lerp = |a: f64, b: f64| (a + (b - a) * t) as u8;
    [lerp(40.0, 250.0), lerp(90.0, 220.0), lerp(220.0, 60.0), 255]
}

/// The cloud's points as small cubes (only the slice through the target when asked).
pub fn instances(model: &Model, out: &mut Vec<Instance>) {
    let Some(cloud) = model.shown_workspace() else {
        return;
    };
    let spacing = cloud.spacing();
    let size = Vector3::repeat(spacing * 0.2);
    let largest = cloud.largest_value().max(1e-300);
    let target_z = model.target().translation.vector.z;
    let slice = model.settings().overlays.contains(Overlay::WorkspaceSlice);
    let rot = Rotation3::identity();
    for (p, v) in cloud.positions.iter().zip(&cloud.values) {
        if slice && (p.z - target_z).abs() > spacing {
            continue;
        }
        out.push(instance(
            Shape::Box,
            &Point3::from(*p),
            &rot,
            size,
            ramp(v / largest),
        ));
    }
}

/// At the target's position, a small sphere of the tool directions tested: green where
/// the arm reaches the position with its tool axis along that direction (to half the
/// lattice's spacing), grey where not.
pub fn direction_instances(model: &Model, out: &mut Vec<Instance>) {
    let Some(sphere) = model
        .directions()
        .filter(|_| model.settings().overlays.contains(Overlay::Directions))
    else {
        return;
    };
    let radius = 0.12 * model.robot().length_scale();
    let size = Vector3::repeat(radius * 0.09);
    let rot = Rotation3::identity();
    for (d, near) in sphere.directions.iter().zip(&sphere.near) {
        let p = Point3::from(sphere.position + d.direction * radius);
        let color = if *near {
            [60, 200, 90, 255]
        } else {
            [110, 110, 120, 255]
        };
        out.push(instance(Shape::Box, &p, &rot, size, color));
    }
    // The sampled directions themselves, smaller: on a 5-axis arm they trace the curve.
    for s in &sphere.samples {
        let p = Point3::from(sphere.position + s * radius);
        out.push(instance(
            Shape::Box,
            &p,
            &rot,
            size * 0.6,
            [150, 240, 120, 255],
        ));
    }
}
