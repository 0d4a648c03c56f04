//! The render target: an RGBA colour buffer (f32, or f32 values rounded to binary16 for an
//! `rgba16float` target) and an f32 depth buffer.

use ocean_core::frame_format::FrameFormat;

/// An f32 RGBA colour buffer with an f32 depth buffer, both row-major with row 0 at the top
/// (framebuffer y down, as in wgpu): pixel (x, y) is at index `y · width + x`.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderTarget {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Colour, `width · height` texels.
    pub color: Vec<[f32; 4]>,
    /// Depth, `width · height` values.
    pub depth: Vec<f32>,
    /// The colour buffer's format: every colour written (blended fragments, clears) goes
    /// through [`FrameFormat::store`], so an `rgba16float` target holds binary16 values.
    pub format: FrameFormat,
}

impl RenderTarget {
    /// Largest width or height the rasterizer accepts: it keeps the snapped coordinates within
    /// 23 bits, so edge functions fit comfortably in i64 (see `fixed_point`). wgpu's default
    /// `max_texture_dimension_2d` is 8192.
    pub const MAX_SIZE: u32 = 1 << 14;

    /// A target cleared to colour 0 and depth 1 (the far plane, what a `Less` test wants).
    ///
    /// # Panics
    /// If `width` or `height` exceeds [`Self::MAX_SIZE`].
    pub fn new(width: u32, height: u32) -> Self {
        assert!(
            width <= Self::MAX_SIZE && height <= Self::MAX_SIZE,
            "render target {width}x{height} exceeds {} pixels per side",
            Self::MAX_SIZE
        );
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            color: vec![[0.0; 4]; n],
            depth: vec![1.0; n],
            format: FrameFormat::Rgba32Float,
        }
    }

    /// [`Self::new`] with a colour buffer of `format`.
    ///
    /// # Panics
    /// As [`Self::new`].
    pub fn with_format(width: u32, height: u32, format: FrameFormat) -> Self {
        Self { format, ..Self::new(width, height) }
    }

    /// Sets every colour texel to `color` (as the format stores it, as a GPU's clear does).
    pub fn clear_color(&mut self, color: [f32; 4]) {
        self.color.fill(self.format.store4(color));
    }

    /// Sets every depth value to `depth`.
    pub fn clear_depth(&mut self, depth: f32) {
        self.depth.fill(depth);
    }

    /// The colour of pixel (x, y).
    ///
    /// # Panics
    /// If (x, y) is outside the target.
    pub fn pixel(&self, x: u32, y: u32) -> [f32; 4] {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside the target");
        self.color[y as usize * self.width as usize + x as usize]
    }
}
