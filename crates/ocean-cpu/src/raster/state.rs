//! Fixed-function state of a draw: culling, depth test, blending (the parts of a wgpu
//! `RenderPipelineDescriptor` the rasterizer honours).

/// Which winding is the front face, as seen on screen — the same as in wgpu NDC (x right, y up).
///
/// This is wgpu's `FrontFace` and Vulkan's `VkFrontFace`: wgpu flips y with a negative viewport
/// height, so a triangle that is counter-clockwise in NDC (y up) is counter-clockwise as
/// displayed (row 0 at the top), which is Vulkan's `a > 0` in framebuffer coordinates. In terms
/// of the snapped framebuffer coordinates (y down) used inside the rasterizer, counter-clockwise
/// means `(x1 − x0)(y2 − y0) − (y1 − y0)(x2 − x0) < 0`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FrontFace {
    /// Counter-clockwise triangles are front-facing (wgpu's default).
    #[default]
    Ccw,
    /// Clockwise triangles are front-facing.
    Cw,
}

/// Which faces are discarded before rasterization (wgpu's `Option<Face>`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CullMode {
    /// Draw both faces.
    #[default]
    None,
    /// Discard front-facing triangles.
    Front,
    /// Discard back-facing triangles.
    Back,
}

/// Depth comparison (wgpu's `CompareFunction`): a fragment passes when
/// `new_depth <op> stored_depth`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CompareFunction {
    /// Never passes.
    Never,
    /// `new < stored`.
    #[default]
    Less,
    /// `new == stored`.
    Equal,
    /// `new <= stored`.
    LessEqual,
    /// `new > stored`.
    Greater,
    /// `new != stored`.
    NotEqual,
    /// `new >= stored`.
    GreaterEqual,
    /// Always passes (with `depth_write: false` this disables the depth test).
    Always,
}

impl CompareFunction {
    /// Whether a fragment at depth `new` passes against the stored depth `stored`.
    #[inline]
    pub fn passes(self, new: f32, stored: f32) -> bool {
        match self {
            Self::Never => false,
            Self::Less => new < stored,
            Self::Equal => new == stored,
            Self::LessEqual => new <= stored,
            Self::Greater => new > stored,
            Self::NotEqual => new != stored,
            Self::GreaterEqual => new >= stored,
            Self::Always => true,
        }
    }
}

/// How a shaded fragment's colour `src` is combined with the stored colour `dst`, per channel,
/// in f32 (the target is f32, so a GPU blends in f32 too).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BlendMode {
    /// `dst = src` (wgpu `BlendState::REPLACE` / no blending).
    #[default]
    Replace,
    /// `dst = src + dst · (1 − src.a)` on all four channels (wgpu
    /// `BlendState::PREMULTIPLIED_ALPHA_BLENDING`).
    PremultipliedOver,
    /// `dst = src + dst` (`BlendFactor::One`, `BlendFactor::One`, `BlendOperation::Add`); also
    /// how tests count how often each pixel is written.
    Add,
}

impl BlendMode {
    /// The blended colour; the order of operations is the one written in each variant's doc.
    #[inline]
    pub fn apply(self, src: [f32; 4], dst: [f32; 4]) -> [f32; 4] {
        match self {
            Self::Replace => src,
            Self::PremultipliedOver => {
                let k = 1.0 - src[3];
                std::array::from_fn(|c| src[c] + dst[c] * k)
            }
            Self::Add => std::array::from_fn(|c| src[c] + dst[c]),
        }
    }
}

/// The fixed-function state of one draw.
///
/// The default is wgpu's defaults for a pipeline with a depth attachment: no culling,
/// counter-clockwise front faces, `Less` depth test with depth writes, no blending.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RasterState {
    /// Which winding is the front face.
    pub front_face: FrontFace,
    /// Which faces are discarded.
    pub cull_mode: CullMode,
    /// Depth comparison against the target's depth buffer.
    pub depth_compare: CompareFunction,
    /// Whether passing fragments write their depth.
    pub depth_write: bool,
    /// Colour blending.
    pub blend: BlendMode,
}

impl Default for RasterState {
    fn default() -> Self {
        Self {
            front_face: FrontFace::Ccw,
            cull_mode: CullMode::None,
            depth_compare: CompareFunction::Less,
            depth_write: true,
            blend: BlendMode::Replace,
        }
    }
}
