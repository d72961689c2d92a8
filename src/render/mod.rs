//! The 3D renderer: a real wgpu pipeline with a depth buffer (and 4× MSAA where the
//! backend allows it) that draws the scene into an offscreen texture, which egui then
//! shows as an image. Shading is done in linear light and the shader writes sRGB-encoded
//! values into a plain `Rgba8Unorm` texture, which is what egui expects of its textures
//! (WebGL2 cannot reinterpret an sRGB texture as unorm, so the encoding is explicit). The same code runs on WebGPU, WebGL2 and native Vulkan (lavapipe in
//! the UI tests). The renderer never computes kinematics: it draws a [`Scene`].

pub mod camera;
pub mod mesh;

use eframe::egui_wgpu::RenderState;
use eframe::wgpu;
use eframe::wgpu::util::DeviceExt;
use nalgebra::{Matrix3, Matrix4};

use mesh::{Mesh, Vertex};

/// The shapes a scene is built from (unit size; the instance's model matrix scales them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Shape {
    /// The cube [−½, ½]³.
    Box,
    /// Radius ½ along z from −½ to ½.
    Cylinder,
    /// Base radius ½ at z = 0, apex at z = 1.
    Cone,
    /// Radius ½.
    Sphere,
}

const SHAPES: [Shape; 4] = [Shape::Box, Shape::Cylinder, Shape::Cone, Shape::Sphere];

/// One placed, coloured shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Instance {
    /// Which mesh.
    pub shape: Shape,
    /// World from unit mesh.
    pub model: Matrix4<f32>,
    /// sRGB colour with alpha, 0–255.
    pub color: [u8; 4],
    /// Drawn over everything else (handles of the target marker).
    pub on_top: bool,
}

/// A coloured line segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Start and end in world coordinates.
    pub ends: [[f32; 3]; 2],
    /// sRGB colour with alpha, 0–255.
    pub color: [u8; 4],
}

/// What to draw in one frame.
#[derive(Debug, Clone, Default)]
pub struct Scene {
    /// World → clip.
    pub view_proj: Matrix4<f32>,
    /// Eye position.
    pub eye: [f32; 3],
    /// Direction the key light travels.
    pub light_dir: [f32; 3],
    /// sRGB background.
    pub background: [u8; 3],
    /// Shapes.
    pub instances: Vec<Instance>,
    /// Lines (the ground grid).
    pub lines: Vec<Line>,
}

/// sRGB 0–255 to linear 0–1.
pub fn srgb_to_linear(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_color(c: [u8; 4]) -> [f32; 4] {
    [
        srgb_to_linear(c[0]),
        srgb_to_linear(c[1]),
        srgb_to_linear(c[2]),
        c[3] as f32 / 255.0,
    ]
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    light_dir: [f32; 4],
    eye: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct InstanceRaw {
    model: [[f32; 4]; 4],
    normal: [[f32; 4]; 3],
    color: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LineVertex {
    position: [f32; 3],
    color: [f32; 4],
}

struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
}

struct Targets {
    size: [u32; 2],
    msaa: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
    resolved: wgpu::TextureView,
}

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth24Plus;

/// Owns the pipelines, meshes and offscreen targets.
pub struct SceneRenderer {
    mesh_pipeline: wgpu::RenderPipeline,
    mesh_on_top_pipeline: wgpu::RenderPipeline,
    line_pipeline: wgpu::RenderPipeline,
    globals: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    meshes: Vec<GpuMesh>,
    instance_buffer: wgpu::Buffer,
    instance_capacity: usize,
    line_buffer: wgpu::Buffer,
    line_capacity: usize,
    sample_count: u32,
    targets: Option<Targets>,
    texture_id: Option<egui::TextureId>,
    raw_instances: Vec<InstanceRaw>,
    raw_lines: Vec<LineVertex>,
}

impl SceneRenderer {
    /// Creates the pipelines and meshes on the app's wgpu device.
    pub fn new(render_state: &RenderState) -> Self {
        let device = &render_state.device;
        let features = render_state
            .adapter
            .get_texture_format_features(COLOR_FORMAT);
        let sample_count = if features.flags.sample_count_supported(4) {
            4
        } else {
            1
        };
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("armlab scene"),
            source: wgpu::ShaderSource::Wgsl(include_str!("scene.wgsl").into()),
        });
        let layout_entry = wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let bind_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("armlab globals"),
            entries: &[layout_entry],
        });
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("armlab globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("armlab globals"),
            layout: &bind_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            }],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("armlab scene"),
            bind_group_layouts: &[Some(&bind_layout)],
            immediate_size: 0,
        });
        let mesh_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
        let instance_attrs = wgpu::vertex_attr_array![
            2 => Float32x4, 3 => Float32x4, 4 => Float32x4, 5 => Float32x4,
            6 => Float32x4, 7 => Float32x4, 8 => Float32x4, 9 => Float32x4
        ];
        let line_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x4];
        let blend = Some(wgpu::BlendState::ALPHA_BLENDING);
        let make = |label: &str,
                    vs: &str,
                    fs: &str,
                    buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
                    topology: wgpu::PrimitiveTopology,
                    depth_test: bool| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vs),
                    buffers,
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(depth_test),
                    depth_compare: Some(if depth_test {
                        wgpu::CompareFunction::LessEqual
                    } else {
                        wgpu::CompareFunction::Always
                    }),
                    stencil: wgpu::StencilState::default(),
                    bias: wgpu::DepthBiasState::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: sample_count,
                    mask: !0,
                    alpha_to_coverage_enabled: false,
                },
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(fs),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: COLOR_FORMAT,
                        blend,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let mesh_buffers = [
            Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &mesh_attrs,
            }),
            Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<InstanceRaw>() as u64,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &instance_attrs,
            }),
        ];
        let line_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<LineVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &line_attrs,
        })];
        let tri = wgpu::PrimitiveTopology::TriangleList;
        let mesh_pipeline = make(
            "armlab meshes",
            "vs_mesh",
            "fs_mesh",
            &mesh_buffers,
            tri,
            true,
        );
        let mesh_on_top_pipeline = make(
            "armlab handles",
            "vs_mesh",
            "fs_mesh",
            &mesh_buffers,
            tri,
            false,
        );
        let line_pipeline = make(
            "armlab lines",
            "vs_line",
            "fs_line",
            &line_buffers,
            wgpu::PrimitiveTopology::LineList,
            true,
        );
        let meshes = SHAPES
            .iter()
            .map(|shape| {
                let mesh = match shape {
                    Shape::Box => Mesh::unit_box(),
                    Shape::Cylinder => Mesh::unit_cylinder(32),
                    Shape::Cone => Mesh::unit_cone(32),
                    Shape::Sphere => Mesh::unit_sphere(16, 32),
                };
                GpuMesh {
                    vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some("armlab mesh vertices"),
                        contents: bytemuck::cast_slice(&mesh.vertices),
                        usage: wgpu::BufferUsages::VERTEX,
                    }),
                    indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some("armlab mesh indices"),
                        contents: bytemuck::cast_slice(&mesh.indices),
                        usage: wgpu::BufferUsages::INDEX,
                    }),
                    count: mesh.indices.len() as u32,
                }
            })
            .collect();
        let instance_capacity = 256;
        let line_capacity = 1024;
        SceneRenderer {
            instance_buffer: vertex_buffer(
                device,
                instance_capacity * std::mem::size_of::<InstanceRaw>(),
            ),
            line_buffer: vertex_buffer(device, line_capacity * std::mem::size_of::<LineVertex>()),
            mesh_pipeline,
            mesh_on_top_pipeline,
            line_pipeline,
            globals,
            bind_group,
            meshes,
            instance_capacity,
            line_capacity,
            sample_count,
            targets: None,
            texture_id: None,
            raw_instances: Vec::new(),
            raw_lines: Vec::new(),
        }
    }

    /// Whether the scene is antialiased (4× MSAA).
    pub fn msaa(&self) -> bool {
        self.sample_count > 1
    }

    fn ensure_targets(&mut self, render_state: &RenderState, size: [u32; 2]) -> egui::TextureId {
        let device = &render_state.device;
        let size = [size[0].clamp(1, 8192), size[1].clamp(1, 8192)];
        let stale = self.targets.as_ref().is_none_or(|t| t.size != size);
        if stale {
            let extent = wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: 1,
            };
            let texture = |label: &str, format, samples, usage| {
                device
                    .create_texture(&wgpu::TextureDescriptor {
                        label: Some(label),
                        size: extent,
                        mip_level_count: 1,
                        sample_count: samples,
                        dimension: wgpu::TextureDimension::D2,
                        format,
                        usage,
                        view_formats: &[],
                    })
                    .create_view(&wgpu::TextureViewDescriptor::default())
            };
            let attach = wgpu::TextureUsages::RENDER_ATTACHMENT;
            let resolved = texture(
                "armlab scene",
                COLOR_FORMAT,
                1,
                attach | wgpu::TextureUsages::TEXTURE_BINDING,
            );
            let msaa = (self.sample_count > 1)
                .then(|| texture("armlab scene msaa", COLOR_FORMAT, self.sample_count, attach));
            let depth = texture("armlab depth", DEPTH_FORMAT, self.sample_count, attach);
            let mut renderer = render_state.renderer.write();
            match self.texture_id {
                Some(id) => renderer.update_egui_texture_from_wgpu_texture(
                    device,
                    &resolved,
                    wgpu::FilterMode::Linear,
                    id,
                ),
                None => {
                    self.texture_id = Some(renderer.register_native_texture(
                        device,
                        &resolved,
                        wgpu::FilterMode::Linear,
                    ));
                }
            }
            self.targets = Some(Targets {
                size,
                msaa,
                depth,
                resolved,
            });
        }
        self.texture_id.unwrap_or_default()
    }

    /// Draws `scene` at `size` pixels and returns the egui texture that holds the picture.
    pub fn render(
        &mut self,
        render_state: &RenderState,
        size: [u32; 2],
        scene: &Scene,
    ) -> egui::TextureId {
        let texture_id = self.ensure_targets(render_state, size);
        let device = &render_state.device;
        let queue = &render_state.queue;

        // Instances grouped by shape, on-top ones last.
        self.raw_instances.clear();
        let mut ranges = Vec::with_capacity(8);
        for on_top in [false, true] {
            for (mesh_index, shape) in SHAPES.iter().enumerate() {
                let start = self.raw_instances.len() as u32;
                for inst in scene
                    .instances
                    .iter()
                    .filter(|i| i.shape == *shape && i.on_top == on_top)
                {
                    self.raw_instances.push(raw_instance(inst));
                }
                let end = self.raw_instances.len() as u32;
                if end > start {
                    ranges.push((on_top, mesh_index, start..end));
                }
            }
        }
        if self.raw_instances.len() > self.instance_capacity {
            self.instance_capacity = self.raw_instances.len().next_power_of_two();
            self.instance_buffer = vertex_buffer(
                device,
                self.instance_capacity * std::mem::size_of::<InstanceRaw>(),
            );
        }
        if !self.raw_instances.is_empty() {
            queue.write_buffer(
                &self.instance_buffer,
                0,
                bytemuck::cast_slice(&self.raw_instances),
            );
        }
        self.raw_lines.clear();
        for line in &scene.lines {
            let color = linear_color(line.color);
            for end in line.ends {
                self.raw_lines.push(LineVertex {
                    position: end,
                    color,
                });
            }
        }
        if self.raw_lines.len() > self.line_capacity {
            self.line_capacity = self.raw_lines.len().next_power_of_two();
            self.line_buffer = vertex_buffer(
                device,
                self.line_capacity * std::mem::size_of::<LineVertex>(),
            );
        }
        if !self.raw_lines.is_empty() {
            queue.write_buffer(&self.line_buffer, 0, bytemuck::cast_slice(&self.raw_lines));
        }
        let globals = Globals {
            view_proj: scene.view_proj.into(),
            light_dir: [
                scene.light_dir[0],
                scene.light_dir[1],
                scene.light_dir[2],
                0.0,
            ],
            eye: [scene.eye[0], scene.eye[1], scene.eye[2], 1.0],
        };
        queue.write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));

        let Some(targets) = &self.targets else {
            return texture_id;
        };
        // The target holds sRGB-encoded values: the clear colour goes in as it is.
        let bg = scene.background;
        let clear = wgpu::Color {
            r: bg[0] as f64 / 255.0,
            g: bg[1] as f64 / 255.0,
            b: bg[2] as f64 / 255.0,
            a: 1.0,
        };
        let (view, resolve_target) = match &targets.msaa {
            Some(msaa) => (msaa, Some(&targets.resolved)),
            None => (&targets.resolved, None),
        };
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("armlab scene"),
        });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("armlab scene"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(clear),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.bind_group, &[]);
            if !self.raw_lines.is_empty() {
                pass.set_pipeline(&self.line_pipeline);
                pass.set_vertex_buffer(0, self.line_buffer.slice(..));
                pass.draw(0..self.raw_lines.len() as u32, 0..1);
            }
            pass.set_vertex_buffer(1, self.instance_buffer.slice(..));
            for (on_top, mesh_index, range) in ranges {
                pass.set_pipeline(if on_top {
                    &self.mesh_on_top_pipeline
                } else {
                    &self.mesh_pipeline
                });
                let mesh = &self.meshes[mesh_index];
                pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..mesh.count, 0, range);
            }
        }
        queue.submit(Some(encoder.finish()));
        texture_id
    }
}

fn vertex_buffer(device: &wgpu::Device, bytes: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("armlab vertex data"),
        size: bytes as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn raw_instance(inst: &Instance) -> InstanceRaw {
    let m = inst.model;
    let linear: Matrix3<f32> = m.fixed_view::<3, 3>(0, 0).into_owned();
    // Normals transform by the inverse transpose; a degenerate (zero-scale) model keeps its own.
    let normal = linear.try_inverse().map_or(linear, |inv| inv.transpose());
    let col = |c: usize| [normal[(0, c)], normal[(1, c)], normal[(2, c)], 0.0];
    InstanceRaw {
        model: m.into(),
        normal: [col(0), col(1), col(2)],
        color: linear_color(inst.color),
    }
}
