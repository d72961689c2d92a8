//! Unit meshes generated in code: box, cylinder, cone and sphere, each centred so that a
//! model matrix places and scales it.

use std::f32::consts::TAU;

/// One vertex: position and normal.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Position.
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
}

/// An indexed triangle mesh.
#[derive(Debug, Clone, Default)]
pub struct Mesh {
    /// Vertices.
    pub vertices: Vec<Vertex>,
    /// Triangle indices, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
}

impl Mesh {
    fn push(&mut self, position: [f32; 3], normal: [f32; 3]) -> u32 {
        self.vertices.push(Vertex { position, normal });
        (self.vertices.len() - 1) as u32
    }

    /// The cube [−½, ½]³ with flat faces.
    pub fn unit_box() -> Mesh {
        let mut m = Mesh::default();
        // (normal, u axis, v axis) per face; u × v = normal keeps the winding outward.
        let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        for (n, u, v) in faces {
            let corner = |su: f32, sv: f32| {
                [
                    0.5 * n[0] + 0.5 * (su * u[0] + sv * v[0]),
                    0.5 * n[1] + 0.5 * (su * u[1] + sv * v[1]),
                    0.5 * n[2] + 0.5 * (su * u[2] + sv * v[2]),
                ]
            };
            let a = m.push(corner(-1.0, -1.0), n);
            let b = m.push(corner(1.0, -1.0), n);
            let c = m.push(corner(1.0, 1.0), n);
            let d = m.push(corner(-1.0, 1.0), n);
            m.indices.extend_from_slice(&[a, b, c, a, c, d]);
        }
        m
    }

    /// A cylinder of radius ½ along z from −½ to ½, with caps.
    pub fn unit_cylinder(segments: u32) -> Mesh {
        let mut m = Mesh::default();
        for (z, nz) in [(-0.5_f32, -1.0_f32), (0.5, 1.0)] {
            let centre = m.push([0.0, 0.0, z], [0.0, 0.0, nz]);
            let first = m.vertices.len() as u32;
            for i in 0..segments {
                let t = TAU * i as f32 / segments as f32;
                m.push([0.5 * t.cos(), 0.5 * t.sin(), z], [0.0, 0.0, nz]);
            }
            for i in 0..segments {
                let (a, b) = (first + i, first + (i + 1) % segments);
                if nz > 0.0 {
                    m.indices.extend_from_slice(&[centre, a, b]);
                } else {
                    m.indices.extend_from_slice(&[centre, b, a]);
                }
            }
        }
        let first = m.vertices.len() as u32;
        for i in 0..segments {
            let t = TAU * i as f32 / segments as f32;
            let (c, s) = (t.cos(), t.sin());
            m.push([0.5 * c, 0.5 * s, -0.5], [c, s, 0.0]);
            m.push([0.5 * c, 0.5 * s, 0.5], [c, s, 0.0]);
        }
        for i in 0..segments {
            let a = first + 2 * i;
            let b = first + 2 * ((i + 1) % segments);
            m.indices.extend_from_slice(&[a, b, b + 1, a, b + 1, a + 1]);
        }
        m
    }

    /// A cone with a base of radius ½ at z = 0 and its apex at z = 1.
    pub fn unit_cone(segments: u32) -> Mesh {
        let mut m = Mesh::default();
        let centre = m.push([0.0, 0.0, 0.0], [0.0, 0.0, -1.0]);
        let first = m.vertices.len() as u32;
        for i in 0..segments {
            let t = TAU * i as f32 / segments as f32;
            m.push([0.5 * t.cos(), 0.5 * t.sin(), 0.0], [0.0, 0.0, -1.0]);
        }
        for i in 0..segments {
            m.indices
                .extend_from_slice(&[centre, first + (i + 1) % segments, first + i]);
        }
        // Side normals tilt up by the slope: radius ½ over height 1.
        let k = 1.0 / (1.0f32 + 0.25).sqrt();
        let first = m.vertices.len() as u32;
        for i in 0..segments {
            let t = TAU * (i as f32 + 0.5) / segments as f32;
            let t0 = TAU * i as f32 / segments as f32;
            let t1 = TAU * (i + 1) as f32 / segments as f32;
            let n = [t.cos() * k, t.sin() * k, 0.5 * k];
            m.push(
                [0.5 * t0.cos(), 0.5 * t0.sin(), 0.0],
                [t0.cos() * k, t0.sin() * k, 0.5 * k],
            );
            m.push(
                [0.5 * t1.cos(), 0.5 * t1.sin(), 0.0],
                [t1.cos() * k, t1.sin() * k, 0.5 * k],
            );
            m.push([0.0, 0.0, 1.0], n);
        }
        for i in 0..segments {
            let a = first + 3 * i;
            m.indices.extend_from_slice(&[a, a + 1, a + 2]);
        }
        m
    }

    /// A UV sphere of radius ½.
    pub fn unit_sphere(rings: u32, segments: u32) -> Mesh {
        let mut m = Mesh::default();
        for r in 0..=rings {
            let phi = std::f32::consts::PI * r as f32 / rings as f32;
            for s in 0..=segments {
                let t = TAU * s as f32 / segments as f32;
                let n = [phi.sin() * t.cos(), phi.sin() * t.sin(), phi.cos()];
                m.push([0.5 * n[0], 0.5 * n[1], 0.5 * n[2]], n);
            }
        }
        let row = segments + 1;
        for r in 0..rings {
            for s in 0..segments {
                let a = r * row + s;
                let b = a + row;
                m.indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
            }
        }
        m
    }
}
