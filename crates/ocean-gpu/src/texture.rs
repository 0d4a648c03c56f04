//! Textures of the frame: their formats, the plain texture and the mip chain.
//!
//! Formats (docs/design.md, "Determinism contract"): every intermediate map is `Rgba32Float`, which
//! lavapipe filters with full-float weights, as the CPU's sampler does, but for the frame's
//! colour buffers under frame format `rgba16float` ([`HALF_FORMAT`], read back exactly as
//! f32; `ocean_core::frame_format` says how a value is stored); the shadow map is
//! `R32Float` (the shadow stage writes depth to red; read back as (r, 0, 0, 0), the CPU's
//! layout); the 8-bit output is `Rgba8Unorm`; depth is `Depth32Float`.
//! Reading them back is [`crate::readback`]'s.

use crate::created::{Counted, CountedView};

use crate::device::Gpu;
use ocean_core::far_field::{mip_level_count, mip_level_row, mip_level_size};

/// Format of the wave maps, Fresnel tables, foam field, and of the frame's colour buffers
/// (reflection/refraction maps, HDR frame, bloom chains) under frame format `rgba32float`.
pub const MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// Format of the frame's colour buffers under frame format `rgba16float` (seed 002;
/// `ocean_core::frame_format`); read back as the f32 values it holds.
pub const HALF_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The wgpu format of the frame's colour buffers.
pub fn frame_format(f: ocean_core::frame_format::FrameFormat) -> wgpu::TextureFormat {
    match f {
        ocean_core::frame_format::FrameFormat::Rgba32Float => MAP_FORMAT,
        ocean_core::frame_format::FrameFormat::Rgba16Float => HALF_FORMAT,
    }
}
/// Format of the shadow map (depth in red).
pub const SHADOW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// Format of the tonemapped output.
pub const LDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Format of every depth buffer.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A 2D texture with its default view.
#[derive(Debug, Clone)]
pub struct GpuTexture {
    /// The texture.
    pub texture: wgpu::Texture,
    /// A view of its only level.
    pub view: wgpu::TextureView,
    /// Width, texels.
    pub width: u32,
    /// Height, texels.
    pub height: u32,
}

impl GpuTexture {
    /// A `width × height` texture of `format` with `usage`.
    pub fn new(
        device: &wgpu::Device,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> Self {
        let texture = device.new_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        });
        let view = texture.new_view(&wgpu::TextureViewDescriptor::default());
        Self { texture, view, width, height }
    }

    /// A colour target of `format` that the frame samples and reads back.
    pub fn target(
        device: &wgpu::Device,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
    ) -> Self {
        Self::new(device, label, width, height, format, target_usage())
    }

    /// A depth buffer.
    pub fn depth(device: &wgpu::Device, label: &str, width: u32, height: u32) -> Self {
        Self::new(device, label, width, height, DEPTH_FORMAT, depth_usage())
    }

    /// An `Rgba32Float` texture holding `texels` (row-major, row 0 first), which the frame
    /// samples, reads back and may overwrite (copy or storage).
    ///
    /// # Panics
    /// If `texels` does not hold `width · height` texels (a bug in the caller).
    pub fn upload_map(
        gpu: &Gpu,
        label: &str,
        width: u32,
        height: u32,
        texels: &[[f32; 4]],
    ) -> Self {
        assert_eq!(texels.len(), width as usize * height as usize, "{label}: texel count");
        let t = Self::new(&gpu.device, label, width, height, MAP_FORMAT, map_usage());
        gpu.queue.write_texture(
            t.texture.as_image_copy(),
            bytemuck::cast_slice(texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(width * 16),
                rows_per_image: Some(height),
            },
            wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        );
        t
    }

    /// The 1×1 zero `Rgba32Float` texture bound where a skipped pass would have left its map
    /// (the CPU binds the same; the shaders multiply what they read from it by 0).
    pub fn empty_map(gpu: &Gpu, label: &str) -> Self {
        Self::upload_map(gpu, label, 1, 1, &[[0.0; 4]])
    }
}

/// Usage of a colour target that the frame samples and reads back.
pub fn target_usage() -> wgpu::TextureUsages {
    wgpu::TextureUsages::RENDER_ATTACHMENT
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
}

/// Usage of a depth buffer: sampled and copied by the embedding composite and its test
/// (`crate::embed`).
pub fn depth_usage() -> wgpu::TextureUsages {
    wgpu::TextureUsages::RENDER_ATTACHMENT
        | wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::COPY_SRC
}

/// Usage of a map that a stage writes (copy or storage), the frame samples and the tests read
/// back.
pub fn map_usage() -> wgpu::TextureUsages {
    wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::STORAGE_BINDING
        | wgpu::TextureUsages::COPY_DST
        | wgpu::TextureUsages::COPY_SRC
}

/// An `Rgba32Float` texture (post `bloom`'s: the frame's format) with a mip chain and a view
/// of each level.
#[derive(Clone)]
pub struct GpuMipChain {
    /// The texture.
    pub texture: wgpu::Texture,
    /// A view of every level (what the water pass samples).
    pub view: wgpu::TextureView,
    /// One view per level.
    pub levels: Vec<wgpu::TextureView>,
    /// Width of level 0.
    pub width: u32,
    /// Height of level 0.
    pub height: u32,
    /// Its texel format.
    pub format: wgpu::TextureFormat,
}

impl GpuMipChain {
    /// A chain of `width` × `height` at level 0.
    pub fn new(device: &wgpu::Device, label: &str, width: u32, height: u32) -> Self {
        Self::with_levels(device, label, width, height, mip_level_count(width, height))
    }

    /// A chain of `width` × `height` at level 0 with `count` levels (post `bloom`'s chains
    /// stop where the plan says).
    pub fn with_levels(
        device: &wgpu::Device,
        label: &str,
        width: u32,
        height: u32,
        count: u32,
    ) -> Self {
        Self::with_format(device, label, width, height, count, MAP_FORMAT)
    }

    /// [`Self::with_levels`] in `format` (post `bloom`'s chains are in the frame's format).
    pub fn with_format(
        device: &wgpu::Device,
        label: &str,
        width: u32,
        height: u32,
        count: u32,
        format: wgpu::TextureFormat,
    ) -> Self {
        let texture = device.new_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: count,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: map_usage(),
            view_formats: &[],
        });
        let view = texture.new_view(&wgpu::TextureViewDescriptor::default());
        let levels = (0..count)
            .map(|k| {
                texture.new_view(&wgpu::TextureViewDescriptor {
                    base_mip_level: k,
                    mip_level_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        Self { texture, view, levels, width, height, format }
    }

    /// Records copies of every level into one atlas texture laid out as
    /// `ocean_core::far_field::mip_level_row` says (the read-back and the cross-check).
    pub fn pack(&self, device: &wgpu::Device, encoder: &mut wgpu::CommandEncoder) -> GpuTexture {
        let count = self.levels.len() as u32;
        let rows = mip_level_row(self.height, count);
        let atlas =
            GpuTexture::new(device, "ocean.mip_atlas", self.width, rows, self.format, map_usage());
        for k in 0..count {
            let [w, h] = mip_level_size(self.width, self.height, k);
            encoder.copy_texture_to_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &self.texture,
                    mip_level: k,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyTextureInfo {
                    texture: &atlas.texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y: mip_level_row(self.height, k), z: 0 },
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
        }
        atlas
    }
}
