//! The other DH convention's frames overlaid in 3D, dashed (docs/kinematics.md §14).

use nalgebra::Point3;

use armlab_core::Convention;
use armlab_core::convention::frames_in_both_conventions;

use crate::app::state::model::Model;
use crate::app::view3d::scene::{AXIS, segment};
use crate::render::{Instance, Shape};
use armlab_session::settings::Overlay;

/// The other convention's frames, each axis dashed (four dashes).
pub fn instances(model: &Model, reach: f64, out: &mut Vec<Instance>) {
    if !model.settings().overlays.contains(Overlay::OtherConvention) {
        return;
    }
    let Ok(both) = frames_in_both_conventions(model.robot(), model.q()) else {
        return;
    };
    let frames = match model.robot().convention {
        Convention::Standard => &both.modified_frames,
        Convention::Modified => &both.standard_frames,
    };
    let len = reach * 0.12;
    for f in frames {
        let o = Point3::from(f.translation.vector);
        for (c, color) in AXIS.iter().enumerate() {
            let dir = f.rotation.matrix().column(c).into_owned();
            for k in 0..4 {
                let a = o + dir * (len * (2 * k) as f64 / 8.0);
                let b = o + dir * (len * (2 * k + 1) as f64 / 8.0);
                out.extend(segment(Shape::Cylinder, &a, &b, len * 0.05, *color));
            }
        }
    }
}
