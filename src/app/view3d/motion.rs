//! The motion lab in the 3D view: the tool's trail and the keep-out boxes.

use crate::app::state::model::Model;
use crate::app::widgets::style;

/// The tool's trail as line segments for the 3D view (yellow, like the highlight).
pub fn trail_lines(model: &Model, out: &mut Vec<crate::render::Line>) {
    let trail = model.motion().trail();
    let c = style::HIGHLIGHT;
    let f = |p: &nalgebra::Point3<f64>| [p.x as f32, p.y as f32, p.z as f32];
    out.extend(
        trail
            .iter()
            .zip(trail.iter().skip(1))
            .map(|(a, b)| crate::render::Line {
                ends: [f(a), f(b)],
                color: [c.r(), c.g(), c.b(), 255],
            }),
    );
}

/// The keep-out boxes as translucent red boxes for the 3D view.
pub fn keep_out_instances(model: &Model, out: &mut Vec<crate::render::Instance>) {
    for b in model.motion().keep_outs() {
        out.push(crate::app::view3d::scene::instance(
            crate::render::Shape::Box,
            &b.centre,
            &b.rotation,
            b.size,
            [230, 60, 50, 90],
        ));
    }
}
