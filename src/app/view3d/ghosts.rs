//! The other IK solutions of the target as translucent ghost arms: drawn, published as
//! screen points (`ghost-N`, N the solution's number in the IK panel's list) and picked
//! by a click.

use nalgebra::Point3;

use super::marker::{ViewGeometry, dist_to_segment};
use crate::app::state::model::Model;
use crate::app::view3d::scene;
use crate::render::Instance;
use armlab_core::ForwardKinematics;
use armlab_core::ik::joint_distance;
use armlab_session::settings::Overlay;

/// A ghost within the limits, and one with a joint outside them.
const GHOST: [u8; 4] = [150, 200, 255, 70];
const GHOST_OUTSIDE: [u8; 4] = [255, 110, 90, 70];

/// The ghosts to draw: the solution's index in the list, its frames, within limits.
fn ghosts(model: &Model) -> Vec<(usize, ForwardKinematics, bool)> {
    if !model.settings().overlays.contains(Overlay::Ghosts) {
        return Vec::new();
    }
    let Some(branches) = model.branches() else {
        return Vec::new();
    };
    branches
        .rows
        .iter()
        .enumerate()
        .filter(|(_, row)| joint_distance(model.robot(), &row.q, model.q()) > 1e-12)
        .filter_map(|(i, row)| {
            ForwardKinematics::new(model.robot(), &row.q)
                .ok()
                .map(|fk| (i, fk, row.within_limits))
        })
        .collect()
}

/// The ghosts' instances (translucent: appended last).
pub fn instances(model: &Model, out: &mut Vec<Instance>) {
    for (_, fk, inside) in ghosts(model) {
        let color = if inside { GHOST } else { GHOST_OUTSIDE };
        out.extend(scene::ghost_instances(model.robot(), &fk, color));
    }
}

/// The polyline of a ghost: base, every frame origin, the tool.
fn polyline(model: &Model, fk: &ForwardKinematics) -> Vec<Point3<f64>> {
    std::iter::once(Point3::from(
        model.robot().world_from_base.translation.vector,
    ))
    .chain(
        fk.base_from_frames
            .iter()
            .map(|f| Point3::from(f.translation.vector)),
    )
    .chain(std::iter::once(Point3::from(fk.tool_position())))
    .collect()
}

/// The solution (index in the list) whose ghost passes within 10 points of `at`.
pub fn pick(model: &Model, view: &ViewGeometry<'_>, at: [f64; 2]) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for (i, fk, _) in ghosts(model) {
        let points: Vec<[f64; 2]> = polyline(model, &fk)
            .iter()
            .filter_map(|p| view.project(p))
            .collect();
        for pair in points.windows(2) {
            let d = dist_to_segment(at, pair[0], pair[1]);
            if d < 10.0 && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, i));
            }
        }
    }
    best.map(|(_, i)| i)
}

/// `ghost-N` (N from 1) at the ghost's middle frame origin, where ghosts of one target
/// differ most (they share the base and the tool).
pub fn points(model: &Model, mut add: impl FnMut(String, &Point3<f64>)) {
    for (i, fk, _) in ghosts(model) {
        let middle = fk.base_from_frames.len() / 2;
        if let Some(frame) = fk.base_from_frames.get(middle.saturating_sub(1)) {
            add(
                format!("ghost-{}", i + 1),
                &Point3::from(frame.translation.vector),
            );
        }
    }
}
