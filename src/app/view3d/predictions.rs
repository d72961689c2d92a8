//! The room's predictions of where the tool will be, on the lecturer's view (and on a
//! student's once revealed): each answer a small magenta sphere, their mean a larger one inside a
//! translucent sphere whose radius is the spread (the root-mean-square distance from the
//! mean), and the truth, once revealed, in the reached colour.

use nalgebra::{Point3, Rotation3, Vector3};

use crate::app::view3d::scene::instance;
use crate::app::widgets::style;
use crate::render::{Instance, Shape};

/// The predicted points and the truth (robot units), as the view draws them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Predictions {
    /// Each answer's point.
    pub points: Vec<[f64; 3]>,
    /// The truth, once revealed.
    pub truth: Option<[f64; 3]>,
}

/// The predictions' colour: magenta, apart from the arm's blues, the target's reach
/// colours and the axes' red, green and blue.
pub const COLOUR: [u8; 4] = [235, 90, 235, 255];
/// A prediction's sphere, as a share of the arm's reach.
const POINT: f64 = 0.04;
/// The spread's sphere: see-through.
const SPREAD_ALPHA: u8 = 70;

/// The predictions as spheres for an arm of `reach`.
pub fn instances(predictions: &Predictions, reach: f64, out: &mut Vec<Instance>) {
    let rot = Rotation3::identity();
    let point = Vector3::repeat(reach * POINT);
    let colour = COLOUR;
    for p in &predictions.points {
        out.push(instance(
            Shape::Sphere,
            &Point3::from(*p),
            &rot,
            point,
            colour,
        ));
    }
    if let Some((mean, spread)) = crate::app::state::classroom::mean_and_spread(&predictions.points)
    {
        let mean = Point3::from(mean);
        out.push(instance(Shape::Sphere, &mean, &rot, point * 1.8, colour));
        let [r, g, b, _] = colour;
        let diameter = Vector3::repeat(2.0 * spread);
        out.push(instance(
            Shape::Sphere,
            &mean,
            &rot,
            diameter,
            [r, g, b, SPREAD_ALPHA],
        ));
    }
    if let Some(truth) = predictions.truth {
        let reached = style::REACHED.to_array();
        out.push(instance(
            Shape::Sphere,
            &Point3::from(truth),
            &rot,
            point * 1.8,
            reached,
        ));
    }
}
