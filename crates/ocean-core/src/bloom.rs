//! Post technique `bloom` (seed 002 §post-processing: "a bloom effect produced by a high-pass
//! filter as well as several blurs", mixed with the colour in the final compositing pass; the
//! pyramid in the spirit of Jimenez 2014, "Next Generation Post Processing in Call of Duty:
//! Advanced Warfare"). Pass `bloom` (`shaders/bloom.wgsl`, compute, one dispatch per level;
//! CPU mirror `ocean-cpu/src/shaders/bloom.rs`) fills two mip chains; the `tonemap` pass adds
//! the result to the frame before its curve.
//!
//! With x = min(max(hdr · exposure, 0), HDR_MAX) (the tonemap's own sanitised exposure):
//!
//! 1. **Bright pass**, fused into the first downsample: b = max(x − threshold, 0) per channel
//!    (a hard knee: what exceeds `[post] bloom_threshold` in exposed units, 1 ≈ display white
//!    under ACES, spills; nothing below it).
//! 2. **Down**: level 0 of chain `bloom_down` is the bright pass of the frame downsampled by 2,
//!    each level after it the level before downsampled by 2. The sizes are Vulkan's mip rule
//!    on the base max(1, ⌊W/2⌋) × max(1, ⌊H/2⌋): level k is max(1, base >> k); there are
//!    L = min(`bloom_levels`, the base's full chain) levels. Texel (i, j) of the level below
//!    is Σ w_a w_b s(2i − 1 + a, 2j − 1 + b), a, b ∈ 0..4, w = (1, 3, 3, 1)/8 — the tent
//!    (bilinear) filter centred on the texel, separable, rows first, summed left to right;
//!    the taps reach one texel beyond the level, which repeats its edge texel (clamp to
//!    edge: the edge texel then gives ⅛ + ⅜ like any other). Each source texel gives away
//!    exactly ¼ of itself in total (½ per axis), so the sum × texel area is kept wherever
//!    the sides are even; an odd side's last column or row gives only ⅛ per axis (it has no
//!    texel of the coarser level centred beside it).
//! 3. **Up**: chain `bloom_up` has the same levels; u_{L−1} = d_{L−1}, u_k = d_k +
//!    up(u_{k+1}), where up is the 2× bilinear upsample: fine texel 2m takes ¾ of coarse m and
//!    ¼ of m − 1, texel 2m + 1 ¾ of m and ¼ of m + 1 (rows first, then columns), coarse
//!    coordinates clamped to the level (so an edge texel keeps its whole weight: the upsample
//!    also keeps the sum × texel area on even sides). u_0 is then the sum of L blurs of the
//!    bright pass, each wider by 2× than the one before.
//! 4. **Composite** (in the `tonemap` pass): x ← x + (strength / L) · up(u_0), the same 2×
//!    upsample to the frame's size; then the vignette and the curve. Dividing by L makes the
//!    added light's sum equal the bright pass's sum × strength: bloom moves light, it does
//!    not make it (`tests/post.rs` measures it).
//!
//! Every step is + − × on f32 with fixed weights and a fixed order, so the GPU's chains are
//! the CPU's within the float tolerance. The chains have the frame's format
//! (`crate::frame_format`): `Rgba32Float`, or under `rgba16float` (system `welch`, seed 002's
//! 16-bit frame buffers) every texel written is truncated to binary16 on both back ends, as
//! lavapipe stores it (measured), and the up chain's sums are clamped to 65504 first
//! ([`BloomUniforms::store_max`], so a GPU that rounds to nearest cannot make an infinity).
//! The values stay finite: b ≤ 65504 and each level is a weighted mean, so u_0 ≤ L · 65504
//! (≤ 65504 in binary16).

use bytemuck::{Pod, Zeroable};

use crate::far_field::{mip_level_count, mip_level_size};

/// The most levels `[post] bloom_levels` may ask for: level 8 of a 16384-wide frame is 32
/// texels wide, already wider than any bloom a picture wants.
pub const MAX_BLOOM_LEVELS: u32 = 8;

/// Uniforms of one dispatch of the `bloom` stage (WGSL `BloomUniforms`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct BloomUniforms {
    /// Width of the level written, texels.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// Width of the level (or frame) read.
    pub src_width: u32,
    /// Its height.
    pub src_height: u32,
    /// The frame's exposure (`bright_down` only).
    pub exposure: f32,
    /// The bright pass's threshold in exposed units (`bright_down` only).
    pub threshold: f32,
    /// `upsample` only: the most a written channel may be, the largest value the chain's
    /// format holds (f16: 65504; f32: `f32::MAX`, no clamp for any finite sum). Only the up
    /// chain's sums can pass 65504 (each down level is a weighted mean of values ≤ 65504).
    pub store_max: f32,
    /// Padding (unused, 0).
    pub pad1: f32,
}

impl BloomUniforms {
    /// A dispatch writing a `dst`-sized level from a `src`-sized one.
    pub fn new(dst: [u32; 2], src: [u32; 2], exposure: f32, threshold: f32) -> Self {
        Self {
            width: dst[0],
            height: dst[1],
            src_width: src[0],
            src_height: src[1],
            exposure,
            threshold,
            store_max: f32::MAX,
            pad1: 0.0,
        }
    }
}

/// Size of the chains' level 0 for a `width` × `height` frame: ⌊side/2⌋, at least 1.
pub fn base_size(width: u32, height: u32) -> [u32; 2] {
    [(width / 2).max(1), (height / 2).max(1)]
}

/// The levels the chains of a `width` × `height` frame have when `requested` are asked for:
/// as many as asked, at most the base's full chain, at least 1.
pub fn level_count(width: u32, height: u32, requested: u32) -> u32 {
    let [w, h] = base_size(width, height);
    requested.clamp(1, mip_level_count(w, h))
}

/// Size of level `k` of the chains of a `width` × `height` frame.
pub fn level_size(width: u32, height: u32, k: u32) -> [u32; 2] {
    let [w, h] = base_size(width, height);
    mip_level_size(w, h, k)
}

/// The weights of the downsample's four taps along one axis, (1, 3, 3, 1)/8 (exact in f32).
pub const DOWN_WEIGHTS: [f32; 4] = [0.125, 0.375, 0.375, 0.125];
