//! An orbit camera with z up: it circles a focus point at a distance, at a yaw and a
//! pitch. It projects world points to the screen and turns screen points into rays, for
//! drawing, picking and the browser tests' `screenPoint`.

use nalgebra::{Matrix4, Perspective3, Point3, Vector3, Vector4};

/// An orbiting perspective camera (f64, in the robot's length unit).
#[derive(Debug, Clone, PartialEq)]
pub struct OrbitCamera {
    /// The point the camera looks at and orbits.
    pub focus: Point3<f64>,
    /// Angle about the world z axis (radians); 0 looks along −x... from +x.
    pub yaw: f64,
    /// Elevation above the xy plane (radians), within ±89°.
    pub pitch: f64,
    /// Distance from the focus.
    pub distance: f64,
    /// Vertical field of view (radians).
    pub fov_y: f64,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        OrbitCamera {
            focus: Point3::origin(),
            yaw: 0.9,
            pitch: 0.45,
            distance: 3.0,
            fov_y: 40f64.to_radians(),
        }
    }
}

/// Standard views.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StandardView {
    /// Looking down −z.
    Top,
    /// Looking along −x... from +x toward the origin.
    Front,
    /// Looking from +y... toward the origin.
    Side,
    /// The default three-quarter view.
    Iso,
}

impl OrbitCamera {
    /// The eye position.
    pub fn eye(&self) -> Point3<f64> {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.focus + Vector3::new(cp * cy, cp * sy, sp) * self.distance
    }

    /// World → camera.
    pub fn view(&self) -> Matrix4<f64> {
        Matrix4::look_at_rh(&self.eye(), &self.focus, &Vector3::z())
    }

    /// Camera → clip space with depth in [0, 1] (wgpu's convention).
    pub fn projection(&self, aspect: f64) -> Matrix4<f64> {
        let near = self.distance * 0.01;
        let far = self.distance * 100.0;
        let gl = Perspective3::new(aspect.max(1e-3), self.fov_y, near, far).to_homogeneous();
        // Map OpenGL depth [−1, 1] to [0, 1].
        #[rustfmt::skip]
        let fix = Matrix4::new(
            1.0, 0.0, 0.0, 0.0,
            0.0, 1.0, 0.0, 0.0,
            0.0, 0.0, 0.5, 0.5,
            0.0, 0.0, 0.0, 1.0,
        );
        fix * gl
    }

    /// World → clip for a viewport of this aspect ratio.
    pub fn view_projection(&self, aspect: f64) -> Matrix4<f64> {
        self.projection(aspect) * self.view()
    }

    /// The screen position of a world point inside a viewport of `size` (any unit, origin
    /// top-left), or `None` when it is behind the camera.
    pub fn project(&self, p: &Point3<f64>, size: [f64; 2]) -> Option<[f64; 2]> {
        let clip = self.view_projection(size[0] / size[1]) * Vector4::new(p.x, p.y, p.z, 1.0);
        if clip.w <= 1e-12 {
            return None;
        }
        let ndc = [clip.x / clip.w, clip.y / clip.w];
        Some([
            (ndc[0] + 1.0) * 0.5 * size[0],
            (1.0 - ndc[1]) * 0.5 * size[1],
        ])
    }

    /// The ray (origin, unit direction) through a screen position inside a viewport of `size`.
    pub fn ray(&self, screen: [f64; 2], size: [f64; 2]) -> (Point3<f64>, Vector3<f64>) {
        let aspect = size[0] / size[1];
        let ndc_x = screen[0] / size[0] * 2.0 - 1.0;
        let ndc_y = 1.0 - screen[1] / size[1] * 2.0;
        let t = (self.fov_y * 0.5).tan();
        let eye = self.eye();
        let forward = (self.focus - eye).normalize();
        let right = forward.cross(&Vector3::z()).normalize();
        let up = right.cross(&forward);
        let dir = (forward + right * (ndc_x * t * aspect) + up * (ndc_y * t)).normalize();
        (eye, dir)
    }

    /// The length of one screen pixel at the focus distance, for sizing handles.
    pub fn world_per_pixel(&self, viewport_height: f64) -> f64 {
        2.0 * self.distance * (self.fov_y * 0.5).tan() / viewport_height.max(1.0)
    }

    /// Frames a sphere (centre, radius) in a viewport of `aspect` (width / height): looks
    /// at it from the current direction from the distance at which it fits the narrower
    /// of the two fields of view, with a tenth to spare.
    pub fn fit(&mut self, centre: Point3<f64>, radius: f64, aspect: f64) {
        let half_y = self.fov_y * 0.5;
        let half_x = (half_y.tan() * aspect.max(1e-3)).atan();
        self.focus = centre;
        self.distance = (radius.max(1e-6) / half_x.min(half_y).sin()) * 1.1;
    }

    /// Turns to a standard view, keeping the focus and distance.
    pub fn set_view(&mut self, view: StandardView) {
        let (yaw, pitch) = match view {
            StandardView::Top => (-std::f64::consts::FRAC_PI_2, 89f64.to_radians()),
            StandardView::Front => (0.0, 0.0),
            StandardView::Side => (std::f64::consts::FRAC_PI_2, 0.0),
            StandardView::Iso => (0.9, 0.45),
        };
        self.yaw = yaw;
        self.pitch = pitch;
    }

    /// Orbits by pixel deltas.
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * 0.008;
        self.pitch = (self.pitch + dy * 0.008).clamp(-89f64.to_radians(), 89f64.to_radians());
    }

    /// Pans by pixel deltas in a viewport of this height.
    pub fn pan(&mut self, dx: f64, dy: f64, viewport_height: f64) {
        let k = self.world_per_pixel(viewport_height);
        let forward = (self.focus - self.eye()).normalize();
        let right = forward.cross(&Vector3::z()).normalize();
        let up = right.cross(&forward);
        self.focus += (-right * dx + up * dy) * k;
    }

    /// Zooms by a factor (> 1 moves closer).
    pub fn zoom(&mut self, factor: f64) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance / factor).clamp(1e-4, 1e7);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fitted_sphere_lies_inside_the_view_at_any_aspect() {
        let centre = Point3::new(100.0, -50.0, 400.0);
        let radius = 900.0;
        for (w, h) in [(1024.0, 768.0), (400.0, 760.0), (1900.0, 300.0)] {
            let mut camera = OrbitCamera::default();
            camera.fit(centre, radius, w / h);
            let eye = camera.eye();
            let forward = (camera.focus - eye).normalize();
            let right = forward.cross(&Vector3::z()).normalize();
            let up = right.cross(&forward);
            // The sphere's extreme points across the view project inside it.
            for dir in [right, -right, up, -up] {
                let [x, y] = camera
                    .project(&(centre + dir * radius), [w, h])
                    .expect("in front");
                assert!(
                    (0.0..=w).contains(&x) && (0.0..=h).contains(&y),
                    "{x}, {y} in {w}×{h}"
                );
            }
        }
    }
}
