//! The offscreen targets the scene is drawn into and shown from, and the two qualities of
//! the picture: the full one, and the moving one a software renderer draws while the
//! scene changes.

use eframe::egui_wgpu::RenderState;
use eframe::wgpu;

use super::{COLOR_FORMAT, DEPTH_FORMAT};

/// The textures of one picture: the multisampled one drawn into (with more than one
/// sample), the depth buffer, and the resolved one egui shows.
pub(super) struct Targets {
    pub(super) size: [u32; 2],
    pub(super) msaa: Option<wgpu::TextureView>,
    pub(super) depth: wgpu::TextureView,
    pub(super) resolved: wgpu::TextureView,
}

/// The picture while the scene moves on a software renderer (see [`Drawn`]), or the
/// full-quality one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Quality {
    Full,
    Moving,
}

/// What [`super::SceneRenderer::render`] gives back: the texture that holds the picture, and,
/// while that picture is a moving one, the seconds after which the full-quality picture
/// is due (the caller asks for a frame then, so the view rests sharp).
#[derive(Debug, Clone, Copy)]
pub struct Drawn {
    /// The egui texture to show.
    pub texture: egui::TextureId,
    /// Seconds until the full-quality picture replaces a moving one.
    pub sharpen_in: Option<f64>,
}

/// On a software renderer, the picture stays a moving one until the scene has not
/// changed for this long (s): egui draws two more frames after each input event, and a
/// full-quality picture in between would cost a slow frame at every step of a drag.
pub(super) const REST_S: f64 = 0.3;

/// The moving picture's width and height as a share of the view's pixels.
pub(super) const MOVING_SCALE: f32 = 0.5;

/// The moving picture's size for a view of `size` pixels.
pub(super) fn moving_size(size: [u32; 2]) -> [u32; 2] {
    size.map(|n| ((n as f32 * MOVING_SCALE).round() as u32).max(1))
}

/// A picture's targets at `size`: the resolved texture egui shows, the multisampled one
/// drawn into (with more than one sample) and the depth buffer.
pub(super) fn make_targets(device: &wgpu::Device, size: [u32; 2], samples: u32) -> Targets {
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
    let msaa = (samples > 1).then(|| texture("armlab scene msaa", COLOR_FORMAT, samples, attach));
    let depth = texture("armlab depth", DEPTH_FORMAT, samples, attach);
    Targets {
        size,
        msaa,
        depth,
        resolved,
    }
}

/// Registers `targets`' resolved texture with egui (or points the texture `id` at it),
/// sampled as a picture of `quality` is shown.
///
/// The full-quality picture has the view's own size in pixels and lies on whole pixels,
/// one texel to a pixel: the nearest texel is the same picture as a bilinear filter's,
/// and on a software renderer (SwiftShader) the filter cost about 13 ms of CPU a frame at
/// 1400×860, every frame the view is shown. The moving picture is drawn at half the width
/// and height and is stretched over the view: it keeps the filter.
pub(super) fn show_texture(
    render_state: &RenderState,
    targets: &Targets,
    id: Option<egui::TextureId>,
    quality: Quality,
) -> egui::TextureId {
    let device = &render_state.device;
    let mut renderer = render_state.renderer.write();
    let filter = match quality {
        Quality::Full => wgpu::FilterMode::Nearest,
        Quality::Moving => wgpu::FilterMode::Linear,
    };
    match id {
        Some(id) => {
            renderer.update_egui_texture_from_wgpu_texture(device, &targets.resolved, filter, id);
            id
        }
        None => renderer.register_native_texture(device, &targets.resolved, filter),
    }
}
