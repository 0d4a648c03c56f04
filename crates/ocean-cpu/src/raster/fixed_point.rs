//! Viewport transform and snapping of framebuffer coordinates to 8 sub-pixel bits.
//!
//! Rounding mode: round half to even. llvmpipe (lavapipe's rasterizer) snaps with
//! `lrintf(x · 256)`, which rounds with the current FPU rounding mode, i.e. to nearest with ties
//! to even; `f32::round_ties_even` does the same without depending on a global mode. Scaling by
//! 256 is exact in f32, so the only rounding is the final one.
//!
//! Range: the clipper ([`super::clip`]) leaves every vertex inside the view volume, so its
//! framebuffer coordinates lie in `[0, size]` up to a few ulp. [`to_framebuffer`] clamps them
//! to `[−CLAMP_MARGIN_PX, size + CLAMP_MARGIN_PX]` as a last line of defence (a
//! `debug_assert!` checks that the clamp only ever removes rounding noise). With sizes up to
//! [`super::RenderTarget::MAX_SIZE`] = 2^14, snapped coordinates are below 2^23 in magnitude,
//! coordinate differences below 2^24, and the edge-function products in [`super::edge`] below
//! 2^50: i64 cannot overflow. There is no guard band (see [`super::clip`]).

/// Sub-pixel bits of the snapped coordinates (llvmpipe's `FIXED_ORDER`).
pub const SUBPIXEL_BITS: u32 = 8;

/// One pixel in snapped units.
pub const FIXED_ONE: i64 = 1 << SUBPIXEL_BITS;

/// Half a pixel in snapped units: pixel (x, y) is sampled at `(x·FIXED_ONE + FIXED_HALF,
/// y·FIXED_ONE + FIXED_HALF)`.
pub const FIXED_HALF: i64 = FIXED_ONE / 2;

/// How far outside the target a clipped vertex may land through rounding before it is clamped.
pub const CLAMP_MARGIN_PX: f32 = 1.0;

/// Snaps a framebuffer coordinate (pixels) to 1/256 pixel, ties to even.
#[inline]
pub fn snap(coord_px: f32) -> i64 {
    debug_assert!(coord_px.is_finite() && coord_px.abs() < (1u32 << 24) as f32);
    (coord_px * FIXED_ONE as f32).round_ties_even() as i64
}

/// A vertex after the perspective divide and the viewport transform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenVertex {
    /// Framebuffer x, snapped (coverage).
    pub x: i64,
    /// Framebuffer y (down), snapped (coverage).
    pub y: i64,
    /// Framebuffer x before snapping (interpolation, [`super::setup`]).
    pub x_win: f32,
    /// Framebuffer y before snapping.
    pub y_win: f32,
    /// Framebuffer depth: z_ndc (the viewport's depth range is [0, 1]).
    pub z: f32,
    /// 1 / w_clip.
    pub inv_w: f32,
}

/// The perspective divide and the viewport transform of wgpu on Vulkan (viewport origin (0, H),
/// extent (W, −H), depth range [0, 1]), in lavapipe's order of operations:
///
/// ```text
/// inv_w = 1 / w
/// x_fb = fma(x · inv_w, W/2, W/2)          an input vertex (llvmpipe's JIT fuses)
/// x_fb = (x · inv_w) · (W/2) + W/2         a vertex the clipper made (Mesa's C code)
/// y_fb likewise with (−H/2, H/2)
/// z_fb =  z · inv_w
/// ```
///
/// Then x_fb, y_fb are snapped with [`snap`] for coverage; interpolation uses them unsnapped.
#[inline]
pub fn to_framebuffer(
    clip: [f32; 4],
    made_by_clipper: bool,
    width: u32,
    height: u32,
) -> ScreenVertex {
    debug_assert!(clip[3] > 0.0, "vertex not clipped to w > 0: {clip:?}");
    let half_w = width as f32 * 0.5;
    let half_h = height as f32 * 0.5;
    let inv_w = 1.0 / clip[3];
    let (x_fb, y_fb) = if made_by_clipper {
        ((clip[0] * inv_w) * half_w + half_w, (clip[1] * inv_w) * -half_h + half_h)
    } else {
        ((clip[0] * inv_w).mul_add(half_w, half_w), (clip[1] * inv_w).mul_add(-half_h, half_h))
    };
    let z_fb = clip[2] * inv_w;
    ScreenVertex {
        x: snap(clamp_to_target(x_fb, width)),
        y: snap(clamp_to_target(y_fb, height)),
        x_win: x_fb,
        y_win: y_fb,
        z: z_fb,
        inv_w,
    }
}

/// Clamps a clipped vertex's coordinate into the target plus [`CLAMP_MARGIN_PX`].
#[inline]
fn clamp_to_target(coord_px: f32, size: u32) -> f32 {
    let hi = size as f32 + CLAMP_MARGIN_PX;
    debug_assert!(
        (-CLAMP_MARGIN_PX..=hi).contains(&coord_px),
        "clipped vertex at {coord_px} px, outside the target of {size} px by more than rounding"
    );
    coord_px.clamp(-CLAMP_MARGIN_PX, hi)
}
