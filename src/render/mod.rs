//! The 3D renderer: a real wgpu pipeline with a depth buffer (and 4× MSAA where the
//! backend allows it) that draws the scene into an offscreen texture, which egui then
//! shows as an image. Shading is done in linear light and the shader writes sRGB-encoded
//! values into a plain `Rgba8Unorm` texture, which is what egui expects of its textures
//! (WebGL2 cannot reinterpret an sRGB texture as unorm, so the encoding is explicit). The same code runs on WebGPU, WebGL2 and native Vulkan (lavapipe in
//! the UI tests). The renderer never computes kinematics: it draws a [`Scene`].
#![deny(clippy::too_many_lines)]

pub mod camera;
pub mod mesh;
mod targets;

use eframe::egui_wgpu::RenderState;
use eframe::wgpu;
use eframe::wgpu::util::DeviceExt;
use nalgebra::Matrix4;

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

pub use targets::Drawn;
use targets::{Quality, REST_S, Targets, make_targets, moving_size, show_texture};

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth24Plus;

/// Owns the pipelines, meshes and offscreen targets.
pub struct SceneRenderer {
    pipelines: Pipelines,
    globals_layout: wgpu::BindGroupLayout,
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
    /// The pipelines, targets and texture of the moving picture, made on its first use.
    moving: Option<(Pipelines, Option<Targets>, egui::TextureId)>,
    /// Whether the adapter is a CPU (SwiftShader, llvmpipe/lavapipe): there every pixel
    /// and every MSAA sample is the CPU's work, so a moving scene is drawn with fewer.
    software: bool,
    /// The quality of the picture last drawn, and when (egui's time, s) the scene last
    /// changed after a first picture.
    drawn_quality: Quality,
    changed_at: Option<f64>,
    raw_instances: Vec<InstanceRaw>,
    raw_lines: Vec<LineVertex>,
    /// Everything the render pass of the picture in the texture read, as bytes (empty
    /// before the first picture and after the targets were made anew).
    drawn: Vec<u8>,
    /// The same bytes for the frame being drawn.
    next: Vec<u8>,
    /// Render passes drawn so far.
    passes: u64,
}

/// The uniform buffer of [`Globals`] and its bind group.
struct GlobalsBinding {
    layout: wgpu::BindGroupLayout,
    buffer: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl GlobalsBinding {
    fn new(device: &wgpu::Device) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("armlab globals"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("armlab globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("armlab globals"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        });
        GlobalsBinding {
            layout,
            buffer,
            bind_group,
        }
    }
}

/// What differs between the three pipelines.
struct PipelineSpec<'a> {
    label: &'a str,
    vertex_entry: &'a str,
    fragment_entry: &'a str,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    topology: wgpu::PrimitiveTopology,
    /// Depth-tested (and depth-writing); off for the marker drawn on top.
    depth_test: bool,
}

/// The shader, layout and sample count every pipeline shares.
struct PipelineBase<'a> {
    device: &'a wgpu::Device,
    shader: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    sample_count: u32,
}

impl PipelineBase<'_> {
    fn pipeline(&self, spec: &PipelineSpec<'_>) -> wgpu::RenderPipeline {
        let depth_compare = if spec.depth_test {
            wgpu::CompareFunction::LessEqual
        } else {
            wgpu::CompareFunction::Always
        };
        self.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(spec.label),
                layout: Some(&self.layout),
                vertex: wgpu::VertexState {
                    module: &self.shader,
                    entry_point: Some(spec.vertex_entry),
                    buffers: spec.buffers,
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                },
                primitive: wgpu::PrimitiveState {
                    topology: spec.topology,
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(spec.depth_test),
                    depth_compare: Some(depth_compare),
                    stencil: wgpu::StencilState::default(),
                    bias: wgpu::DepthBiasState::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: self.sample_count,
                    mask: !0,
                    alpha_to_coverage_enabled: false,
                },
                fragment: Some(wgpu::FragmentState {
                    module: &self.shader,
                    entry_point: Some(spec.fragment_entry),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: COLOR_FORMAT,
                        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                }),
                multiview_mask: None,
                cache: None,
            })
    }
}

/// The meshes drawn depth-tested, the same drawn on top (the marker), and the lines.
struct Pipelines {
    mesh: wgpu::RenderPipeline,
    mesh_on_top: wgpu::RenderPipeline,
    line: wgpu::RenderPipeline,
}

impl Pipelines {
    fn new(device: &wgpu::Device, globals: &wgpu::BindGroupLayout, sample_count: u32) -> Self {
        let base = PipelineBase {
            device,
            shader: device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("armlab scene"),
                source: wgpu::ShaderSource::Wgsl(include_str!("scene.wgsl").into()),
            }),
            layout: device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("armlab scene"),
                bind_group_layouts: &[Some(globals)],
                immediate_size: 0,
            }),
            sample_count,
        };
        let mesh_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
        let instance_attrs = wgpu::vertex_attr_array![
            2 => Float32x4, 3 => Float32x4, 4 => Float32x4, 5 => Float32x4, 6 => Float32x4
        ];
        let line_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x4];
        let mesh_buffers = [
            Some(vertex_layout::<Vertex>(
                wgpu::VertexStepMode::Vertex,
                &mesh_attrs,
            )),
            Some(vertex_layout::<InstanceRaw>(
                wgpu::VertexStepMode::Instance,
                &instance_attrs,
            )),
        ];
        let line_buffers = [Some(vertex_layout::<LineVertex>(
            wgpu::VertexStepMode::Vertex,
            &line_attrs,
        ))];
        let meshes = |label, depth_test| PipelineSpec {
            label,
            vertex_entry: "vs_mesh",
            fragment_entry: "fs_mesh",
            buffers: &mesh_buffers,
            topology: wgpu::PrimitiveTopology::TriangleList,
            depth_test,
        };
        Pipelines {
            mesh: base.pipeline(&meshes("armlab meshes", true)),
            mesh_on_top: base.pipeline(&meshes("armlab handles", false)),
            line: base.pipeline(&PipelineSpec {
                label: "armlab lines",
                vertex_entry: "vs_line",
                fragment_entry: "fs_line",
                buffers: &line_buffers,
                topology: wgpu::PrimitiveTopology::LineList,
                depth_test: true,
            }),
        }
    }
}

fn vertex_layout<'a, T>(
    step_mode: wgpu::VertexStepMode,
    attributes: &'a [wgpu::VertexAttribute],
) -> wgpu::VertexBufferLayout<'a> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<T>() as u64,
        step_mode,
        attributes,
    }
}

/// The unit meshes of every [`Shape`], in [`SHAPES`] order, on the GPU.
fn upload_meshes(device: &wgpu::Device) -> Vec<GpuMesh> {
    SHAPES
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
        .collect()
}

/// A run of instances of one mesh, drawn on top or depth-tested.
struct DrawRange {
    on_top: bool,
    mesh: usize,
    instances: std::ops::Range<u32>,
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
        let globals = GlobalsBinding::new(device);
        let pipelines = Pipelines::new(device, &globals.layout, sample_count);
        let instance_capacity = 256;
        let line_capacity = 1024;
        SceneRenderer {
            instance_buffer: vertex_buffer(
                device,
                instance_capacity * std::mem::size_of::<InstanceRaw>(),
            ),
            line_buffer: vertex_buffer(device, line_capacity * std::mem::size_of::<LineVertex>()),
            pipelines,
            globals_layout: globals.layout,
            globals: globals.buffer,
            bind_group: globals.bind_group,
            meshes: upload_meshes(device),
            instance_capacity,
            line_capacity,
            sample_count,
            targets: None,
            texture_id: None,
            moving: None,
            // The page only: natively the UI tests draw on lavapipe, a CPU adapter too,
            // and show what a GPU shows (`adapt_to_software` turns it on there).
            software: cfg!(target_arch = "wasm32")
                && render_state.adapter.get_info().device_type == wgpu::DeviceType::Cpu,
            drawn_quality: Quality::Full,
            changed_at: None,
            raw_instances: Vec::new(),
            raw_lines: Vec::new(),
            drawn: Vec::new(),
            next: Vec::new(),
            passes: 0,
        }
    }

    /// The render passes drawn so far: one for each frame whose scene differed from the
    /// picture already in the texture.
    pub fn passes(&self) -> u64 {
        self.passes
    }

    /// Whether the scene is antialiased (4× MSAA).
    pub fn msaa(&self) -> bool {
        self.sample_count > 1
    }

    /// Draws moving scenes as on a software renderer (fewer pixels and samples until
    /// the scene rests), whatever the adapter.
    pub fn adapt_to_software(&mut self) {
        self.software = true;
    }

    /// Whether the picture last drawn is a moving one (a software renderer's fast picture
    /// while the scene changes), not the full-quality one.
    pub fn moving(&self) -> bool {
        self.drawn_quality == Quality::Moving
    }

    fn ensure_targets(&mut self, render_state: &RenderState, size: [u32; 2]) -> egui::TextureId {
        let size = [size[0].clamp(1, 8192), size[1].clamp(1, 8192)];
        let stale = self.targets.as_ref().is_none_or(|t| t.size != size);
        if stale {
            let targets = make_targets(&render_state.device, size, self.sample_count);
            self.texture_id = Some(show_texture(
                render_state,
                &targets,
                self.texture_id,
                Quality::Full,
            ));
            self.drawn.clear();
            self.changed_at = None;
            self.targets = Some(targets);
        }
        self.texture_id.unwrap_or_default()
    }

    /// The moving picture's pipelines (one sample) and targets at `size` (a share of the
    /// view's), made when first needed or when the size changed.
    fn ensure_moving(&mut self, render_state: &RenderState, size: [u32; 2]) -> egui::TextureId {
        let device = &render_state.device;
        let size = [size[0].clamp(1, 8192), size[1].clamp(1, 8192)];
        let layout = &self.globals_layout;
        let moving = self.moving.get_or_insert_with(|| {
            let pipelines = Pipelines::new(device, layout, 1);
            let targets = make_targets(device, size, 1);
            let id = show_texture(render_state, &targets, None, Quality::Moving);
            (pipelines, Some(targets), id)
        });
        if moving.1.as_ref().is_none_or(|t| t.size != size) {
            let targets = make_targets(device, size, 1);
            moving.2 = show_texture(render_state, &targets, Some(moving.2), Quality::Moving);
            moving.1 = Some(targets);
        }
        moving.2
    }

    /// Draws `scene` at `size` pixels at egui's time `now` (s) and returns the egui
    /// texture that holds the picture.
    ///
    /// A scene whose pass would read exactly what the picture in the texture was drawn
    /// from is not drawn again. egui repaints twice more after every input event (and
    /// for its own animations), so two frames in three of a drag or a hover change nothing
    /// in the 3D view; on WebGL2 each pass is GL calls on the main thread, and without a
    /// GPU the pixels are the CPU's work too.
    ///
    /// On a software renderer, a scene that changed after the first picture (an orbit, a
    /// drag, the arm moving) is drawn without MSAA at half the width and height (a
    /// sixteenth of the samples) until it has rested for `REST_S` (0.3 s): then the
    /// full-quality picture, the same as on a GPU, is drawn once and kept.
    pub fn render(
        &mut self,
        render_state: &RenderState,
        size: [u32; 2],
        scene: &Scene,
        now: f64,
    ) -> Drawn {
        let full = self.ensure_targets(render_state, size);
        let ranges = self.group_instances(scene);
        self.line_vertices(scene);
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
        self.scene_bytes(&globals, scene.background, &ranges);
        let changed = self.next != self.drawn;
        let (quality, sharpen_in) = self.quality(changed, now);
        let texture = match quality {
            Quality::Full => full,
            Quality::Moving => self.ensure_moving(render_state, moving_size(size)),
        };
        if !changed && quality == self.drawn_quality {
            return Drawn {
                texture,
                sharpen_in,
            };
        }
        if changed {
            std::mem::swap(&mut self.next, &mut self.drawn);
        }
        self.drawn_quality = quality;
        self.passes += 1;
        self.upload(render_state);
        render_state
            .queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
        let mut encoder =
            render_state
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("armlab scene"),
                });
        self.encode_pass(&mut encoder, scene.background, &ranges, quality);
        render_state.queue.submit(Some(encoder.finish()));
        Drawn {
            texture,
            sharpen_in,
        }
    }

    /// This frame's picture quality, and the seconds until a moving picture is due to
    /// be sharpened: on a software renderer a scene that changed after the first picture
    /// moves until it has rested for [`REST_S`].
    fn quality(&mut self, changed: bool, now: f64) -> (Quality, Option<f64>) {
        if changed && self.software && !self.drawn.is_empty() {
            self.changed_at = Some(now);
        }
        let sharpen_in = self
            .changed_at
            .map(|t| REST_S - (now - t))
            .filter(|s| *s > 0.0);
        let quality = if sharpen_in.is_some() {
            Quality::Moving
        } else {
            Quality::Full
        };
        (quality, sharpen_in)
    }

    /// Everything the render pass of `scene` reads, as bytes, into `next`.
    fn scene_bytes(&mut self, globals: &Globals, background: [u8; 3], ranges: &[DrawRange]) {
        self.next.clear();
        self.next.extend_from_slice(bytemuck::bytes_of(globals));
        self.next.extend_from_slice(&background);
        for range in ranges {
            let (start, end) = (range.instances.start, range.instances.end);
            let words = [u32::from(range.on_top), range.mesh as u32, start, end];
            self.next.extend_from_slice(bytemuck::bytes_of(&words));
        }
        self.next
            .extend_from_slice(bytemuck::cast_slice(&self.raw_instances));
        self.next
            .extend_from_slice(bytemuck::cast_slice(&self.raw_lines));
    }

    /// Lists the scene's instances grouped by shape, on-top ones last; returns the draw
    /// ranges.
    fn group_instances(&mut self, scene: &Scene) -> Vec<DrawRange> {
        self.raw_instances.clear();
        let mut ranges = Vec::with_capacity(8);
        for on_top in [false, true] {
            for (mesh, shape) in SHAPES.iter().enumerate() {
                let start = self.raw_instances.len() as u32;
                let group = scene
                    .instances
                    .iter()
                    .filter(|i| i.shape == *shape && i.on_top == on_top);
                self.raw_instances.extend(group.map(raw_instance));
                let end = self.raw_instances.len() as u32;
                if end > start {
                    ranges.push(DrawRange {
                        on_top,
                        mesh,
                        instances: start..end,
                    });
                }
            }
        }
        ranges
    }

    /// Lists the two ends of each of the scene's lines.
    fn line_vertices(&mut self, scene: &Scene) {
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
    }

    /// Writes the listed instances and line ends into their buffers (grown as needed).
    fn upload(&mut self, render_state: &RenderState) {
        if self.raw_instances.len() > self.instance_capacity {
            self.instance_capacity = self.raw_instances.len().next_power_of_two();
            self.instance_buffer = vertex_buffer(
                &render_state.device,
                self.instance_capacity * std::mem::size_of::<InstanceRaw>(),
            );
        }
        if !self.raw_instances.is_empty() {
            render_state.queue.write_buffer(
                &self.instance_buffer,
                0,
                bytemuck::cast_slice(&self.raw_instances),
            );
        }
        if self.raw_lines.len() > self.line_capacity {
            self.line_capacity = self.raw_lines.len().next_power_of_two();
            self.line_buffer = vertex_buffer(
                &render_state.device,
                self.line_capacity * std::mem::size_of::<LineVertex>(),
            );
        }
        if !self.raw_lines.is_empty() {
            render_state.queue.write_buffer(
                &self.line_buffer,
                0,
                bytemuck::cast_slice(&self.raw_lines),
            );
        }
    }

    /// The render pass: clear, the grid lines, then each range of instances.
    fn encode_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        background: [u8; 3],
        ranges: &[DrawRange],
        quality: Quality,
    ) {
        let (pipelines, targets) = match (quality, &self.moving) {
            (Quality::Full, _) => (&self.pipelines, &self.targets),
            (Quality::Moving, Some((pipelines, targets, _))) => (pipelines, targets),
            (Quality::Moving, None) => return,
        };
        let Some(targets) = targets else {
            return;
        };
        // The target holds sRGB-encoded values: the clear colour goes in as it is.
        let clear = wgpu::Color {
            r: background[0] as f64 / 255.0,
            g: background[1] as f64 / 255.0,
            b: background[2] as f64 / 255.0,
            a: 1.0,
        };
        let (view, resolve_target) = match &targets.msaa {
            Some(msaa) => (msaa, Some(&targets.resolved)),
            None => (&targets.resolved, None),
        };
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
            pass.set_pipeline(&pipelines.line);
            pass.set_vertex_buffer(0, self.line_buffer.slice(..));
            pass.draw(0..self.raw_lines.len() as u32, 0..1);
        }
        pass.set_vertex_buffer(1, self.instance_buffer.slice(..));
        for range in ranges {
            pass.set_pipeline(if range.on_top {
                &pipelines.mesh_on_top
            } else {
                &pipelines.mesh
            });
            let mesh = &self.meshes[range.mesh];
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.count, 0, range.instances.clone());
        }
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
    InstanceRaw {
        model: inst.model.into(),
        color: linear_color(inst.color),
    }
}
