//! The task error every IK method shares (docs/kinematics.md §5): the target in the form
//! the error needs, the error vector e and its cost at one pose, and the rotation vector
//! it is built on. Apart from the iterations, which only call it, because the solver's
//! interface and the closed form's branch choice evaluate it too.

use nalgebra::{IsometryMatrix3, Matrix3, Vector3, Vector6};

use crate::angles::{self, constant_table};
use crate::jacobian::Task;
use crate::orientation::rotation_log;

/// The target in the form the error function needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TaskTarget {
    pub task: Task,
    pub position: Vector3<f64>,
    pub rotation: Matrix3<f64>,
}

impl TaskTarget {
    pub fn new(target: &IsometryMatrix3<f64>, task: Task) -> Self {
        TaskTarget {
            task,
            position: target.translation.vector,
            rotation: *target.rotation.matrix(),
        }
    }
}

/// The task error at one pose.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    /// The error vector: linear rows scaled, then the task's angular rows (unused rows 0).
    pub e: Vector6<f64>,
    /// ½‖e‖².
    pub cost: f64,
    /// ‖p_target − p‖ (robot units).
    pub position_error: f64,
    /// The task's orientation error (radians).
    pub orientation_error: f64,
}

/// `vee(log R)`, fast for rotations below ~170° and through [`rotation_log`] beyond.
// Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
#[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
pub(crate) fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    let v = 0.5
        * Vector3::new(
            r[(2, 1)] - r[(1, 2)],
            r[(0, 2)] - r[(2, 0)],
            r[(1, 0)] - r[(0, 1)],
        );
    let c = 0.5 * (r.trace() - 1.0);
    let s2 = v.norm_squared();
    if c > 0.0 && s2 < SMALL_SIN2 {
        // The late iterations: θ/sin θ from sin² θ alone, no square root or division.
        return v * asin_over_sin(s2);
    }
    if c > -0.98 {
        let s = s2.sqrt();
        if s < 1e-300 {
            return Vector3::zeros();
        }
        v * angle_over_sin(s, c)
    } else {
        rotation_log(r)
    }
}

/// Below this sin² θ (θ < 0.05 rad, θ < π/2) [`rotation_vector`] uses [`asin_over_sin`].
const SMALL_SIN2: f64 = 0.0025;

/// `asin(s) / s` from `s2 = s²` for `s² <` [`SMALL_SIN2`] (θ/sin θ for θ < π/2):
/// `1 + s²/6 + 3s⁴/40 + 5s⁶/112 + 35s⁸/1152 + 63s¹⁰/2816 + …`; the first omitted term,
/// `231s¹²/13312`, is below 5·10⁻¹⁸ there.
#[inline]
fn asin_over_sin(s2: f64) -> f64 {
    let k = constant_table!(
        5,
        [
            1.0 / 6.0,
            3.0 / 40.0,
            5.0 / 112.0,
            35.0 / 1152.0,
            63.0 / 2816.0
        ]
    );
    1.0 + s2 * (k(0) + s2 * (k(1) + s2 * (k(2) + s2 * (k(3) + s2 * k(4)))))
}

/// `atan2(s, c) / s` for `s > 0`: below 0.05 rad a polynomial (the late iterations of a
/// solve, where the library's atan2 would take a tenth of the time), [`angles::atan2`] above
/// (the library's natively; in the core's wasm the polynomial one, within 2 ulp, as the
/// library's is software there).
///
/// With `t = s/c`, `atan(t)/s = (1/c)·(1 − t²/3 + t⁴/5 − t⁶/7 + t⁸/9 − …)`; for t < 0.05
/// the first omitted term is below 10⁻¹⁴ of the sum.
#[inline]
fn angle_over_sin(s: f64, c: f64) -> f64 {
    if c > 0.0 && s < 0.05 * c {
        let k = constant_table!(4, [-1.0 / 3.0, 1.0 / 5.0, -1.0 / 7.0, 1.0 / 9.0]);
        let t = s / c;
        let t2 = t * t;
        (1.0 + t2 * (k(0) + t2 * (k(1) + t2 * (k(2) + t2 * k(3))))) / c
    } else {
        angles::atan2(s, c) / s
    }
}

/// The rotation vector turning unit axis `a` onto unit axis `b` (perpendicular to `a`,
/// of length the angle), and the angle; `fallback` is a unit vector perpendicular to `a`
/// used when they are opposite. The angle's atan2 is [`angles::atan2`], as in
/// [`angle_over_sin`].
fn axis_rotation(
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    fallback: &Vector3<f64>,
) -> (Vector3<f64>, f64) {
    let c = a.cross(b);
    let s = c.norm();
    let angle = angles::atan2(s, a.dot(b));
    if s > 1e-300 {
        (c * (angle / s), angle)
    } else if angle > 1.0 {
        (fallback * angle, angle)
    } else {
        (Vector3::zeros(), 0.0)
    }
}

/// The task error of `pose` against `tt`, linear rows multiplied by `inv_len`.
// Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
#[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
pub(crate) fn evaluate(tt: &TaskTarget, pose: &IsometryMatrix3<f64>, inv_len: f64) -> Eval {
    let dp = tt.position - pose.translation.vector;
    let r = pose.rotation.matrix();
    let mut e = Vector6::zeros();
    e.fixed_rows_mut::<3>(0).copy_from(&(dp * inv_len));
    let orientation_error = match tt.task {
        Task::Position => 0.0,
        Task::FullPose => {
            let w = rotation_vector(&(tt.rotation * r.transpose()));
            e.fixed_rows_mut::<3>(3).copy_from(&w);
            w.norm()
        }
        Task::PositionAndAxis(axis) => {
            let k = axis.index();
            let a = r.column(k).into_owned();
            let u = r.column((k + 1) % 3).into_owned();
            let w = r.column((k + 2) % 3).into_owned();
            let (rv, angle) = axis_rotation(&a, &tt.rotation.column(k).into_owned(), &u);
            e[3] = u.dot(&rv);
            e[4] = w.dot(&rv);
            angle
        }
    };
    let position_error = dp.norm();
    let cost = 0.5 * e.norm_squared();
    Eval {
        e,
        cost: if cost.is_finite() {
            cost
        } else {
            f64::INFINITY
        },
        position_error,
        orientation_error,
    }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
mod tests {
    use super::{SMALL_SIN2, angle_over_sin, asin_over_sin, rotation_vector};
    use crate::orientation::rotation_log;
    use nalgebra::{Rotation3, Vector3};
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn angle_over_sin_is_atan2_over_sin() {
        for k in 1..2000 {
            let theta = std::f64::consts::PI * k as f64 / 2000.0;
            let (s, c) = theta.sin_cos();
            let want = s.atan2(c) / s;
            let got = angle_over_sin(s, c);
            assert!(
                (got - want).abs() <= 1e-14 * want,
                "θ = {theta}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn asin_over_sin_is_the_angle_over_its_sine_below_the_switch() {
        // θ from 10⁻⁸ up to the switch (sin θ = 0.05): within 2 ulp of θ / sin θ.
        let top = SMALL_SIN2.sqrt().asin();
        for k in 0..=2000 {
            let theta = 1e-8 + (top - 1e-8) * k as f64 / 2000.0;
            let s = theta.sin();
            if s * s >= SMALL_SIN2 {
                continue;
            }
            let want = theta / s;
            let got = asin_over_sin(s * s);
            assert!(
                (got - want).abs() <= 4.5e-16 * want,
                "θ = {theta}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn rotation_vector_matches_the_rotation_log_on_both_sides_of_the_switch() {
        let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
        for theta in [1e-9, 1e-5, 0.01, 0.049, 0.0501, 0.051, 0.3, 1.5, 2.9, 3.1] {
            let r = *Rotation3::from_scaled_axis(axis * theta).matrix();
            let got = rotation_vector(&r);
            let want = rotation_log(&r);
            assert!(
                (got - want).norm() <= 1e-15 * theta.max(1.0),
                "θ = {theta}: {got} vs {want}"
            );
            assert!(
                (got.norm() - theta).abs() <= 1e-15 * theta.max(1.0),
                "θ = {theta}"
            );
        }
    }
}
