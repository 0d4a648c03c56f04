//! Mirror of `shaders/tonemap.wgsl`: HDR linear frame → 8-bit sRGB. The steps and why:
//! `ocean_core::tonemap`.

use rayon::prelude::*;

pub use ocean_core::tonemap::TonemapUniforms;

use crate::sampler::Texture2D;
use crate::shaders::shared::fullscreen::fullscreen_position;
use crate::shaders::wgsl::{Vec2, Vec3, Vec4, clamp, max, min, pow, round, select, vec4};

pub use ocean_core::tonemap::{HABLE_P, HABLE_Q, HABLE_R, HABLE_S, HABLE_T, HABLE_WHITE_SCALE};

/// Largest finite f16 (`ocean_core::tonemap::HDR_MAX`).
pub const HDR_MAX: f32 = 65504.0;
/// 1 / 2.4 as the nearest f32.
pub const SRGB_INV_GAMMA: f32 = 0.416_666_66;

/// `VertexOut` of `tonemap.wgsl`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub position: Vec4,
}

/// The `hdr_frame: texture_2d<f32>` binding: a borrowed row-major RGBA f32 image, texel
/// (x, y) at `y · width + x`, row 0 at the top.
#[derive(Clone, Copy, Debug)]
pub struct HdrFrame<'a> {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width · height` texels.
    pub texels: &'a [[f32; 4]],
}

impl HdrFrame<'_> {
    /// `textureLoad(hdr_frame, texel, 0)`: the texel, or zeros out of bounds (what Vulkan's
    /// robust image access returns).
    pub fn texture_load(&self, texel: [i32; 2]) -> Vec4 {
        let [x, y] = texel;
        if x < 0 || y < 0 || x as u32 >= self.width || y as u32 >= self.height {
            return Vec4::splat(0.0);
        }
        self.texels[y as usize * self.width as usize + x as usize].into()
    }
}

/// ACES filmic curve, K. Narkowicz's fit: x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14).
pub fn aces_narkowicz(x: Vec3) -> Vec3 {
    (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)
}

/// Hable's filmic curve (Uncharted 2), normalised so that the white point W maps to 1:
/// x (P x + Q) / (x (R x + S) + T) · (1/g(W)) (`ocean_core::tonemap`).
pub fn hable(x: Vec3) -> Vec3 {
    (x * (HABLE_P * x + HABLE_Q)) / (x * (HABLE_R * x + HABLE_S) + HABLE_T) * HABLE_WHITE_SCALE
}

/// `tone_curve(x)`: the curve `tonemap.curve` selects (1 Hable, else ACES).
pub fn tone_curve(x: Vec3, tonemap: &TonemapUniforms) -> Vec3 {
    if tonemap.curve == 1 { hable(x) } else { aces_narkowicz(x) }
}

/// `vignette_factor(p)`: max(1 − s·r², 0) at the pixel centre `p`, r = 0 at the centre and 1
/// at the corner.
pub fn vignette_factor(p: Vec2, tonemap: &TonemapUniforms) -> f32 {
    let d = p - Vec2::from(tonemap.center);
    let r2 = (d.x * d.x + d.y * d.y) * tonemap.inv_corner2;
    max(1.0 - tonemap.vignette * r2, 0.0)
}

/// sRGB OETF, IEC 61966-2-1: 12.92 c for c ≤ 0.0031308, else 1.055 c^(1/2.4) − 0.055.
pub fn srgb_oetf(c: Vec3) -> Vec3 {
    let lo = 12.92 * c;
    let hi = 1.055 * pow(c, Vec3::splat(SRGB_INV_GAMMA)) - 0.055;
    select(hi, lo, c.le(Vec3::splat(0.0031308)))
}

/// Rounds to the nearest multiple of 1/255, ties to even: `round(v · 255) / 255` (WGSL
/// `round` is Rust's `round_ties_even`; both are exact).
pub fn quantize_unorm8(v: Vec3) -> Vec3 {
    round(v * 255.0) / 255.0
}

/// `vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOut`.
pub fn vs_main(vertex_index: u32) -> VertexOut {
    VertexOut { position: fullscreen_position(vertex_index) }
}

/// What the `bloom` binding holds without post `bloom`: one zero texel (× `bloom_scale` = 0).
static NO_BLOOM: std::sync::LazyLock<Texture2D> =
    std::sync::LazyLock::new(|| Texture2D::new(1, 1, vec![[0.0; 4]]));

/// `bloom_at(p)`: the bloom binding (the up chain's level 0) upsampled 2× at pixel `p`.
pub fn bloom_at(p: [i32; 2], bloom: &Texture2D) -> Vec3 {
    crate::shaders::bloom::upsample_at(bloom, p)
}

/// `fs_main(in: VertexOut) -> @location(0) vec4<f32>` without post `bloom` (its binding the
/// 1×1 zero texture): [`fs_main_with_bloom`].
pub fn fs_main(input: &VertexOut, tonemap: &TonemapUniforms, hdr_frame: &HdrFrame) -> [f32; 4] {
    fs_main_with_bloom(input, tonemap, hdr_frame, &NO_BLOOM)
}

/// `fs_main(in: VertexOut) -> @location(0) vec4<f32>` with the `bloom` binding: the quantised
/// sRGB value, alpha 1.
pub fn fs_main_with_bloom(
    input: &VertexOut,
    tonemap: &TonemapUniforms,
    hdr_frame: &HdrFrame,
    bloom: &Texture2D,
) -> [f32; 4] {
    let texel = [input.position.x as i32, input.position.y as i32];
    let hdr = hdr_frame.texture_load(texel).xyz();
    let exposed = hdr * tonemap.exposure;
    let sanitised = min(max(exposed, Vec3::splat(0.0)), Vec3::splat(HDR_MAX));
    let bloomed = sanitised + tonemap.bloom_scale * bloom_at(texel, bloom);
    let x = bloomed * vignette_factor(input.position.xy(), tonemap);
    let mapped = clamp(tone_curve(x, tonemap), Vec3::splat(0.0), Vec3::splat(1.0));
    let encoded = srgb_oetf(mapped);
    quantize_unorm8(encoded).extend(1.0).into()
}

/// What an `Rgba8Unorm` target stores for a shader output `v` in [0, 1]: v · 255 rounded to
/// the nearest integer. For the outputs of [`fs_main`], multiples of 1/255, v · 255 is within
/// 2·10⁻⁵ of an integer, so every rounding Vulkan allows gives the same byte.
pub fn store_unorm8(v: f32) -> u8 {
    (clamp(v, 0.0, 1.0) * 255.0).round_ties_even() as u8
}

/// The `tonemap` pass over a whole `width × height` HDR frame (row-major, row 0 at the top):
/// RGBA8 bytes, 4 per pixel in the same order, ready for a PNG.
///
/// The full-screen triangle covers every pixel centre exactly once, so this calls
/// [`fs_main`] at each centre (x + 0.5, y + 0.5) directly rather than through the
/// rasterizer; rows run in parallel and each pixel is a pure function of its texel.
///
/// # Panics
/// If `hdr` does not hold `width · height` texels.
pub fn tonemap_to_rgba8(
    hdr: &[[f32; 4]],
    width: u32,
    height: u32,
    tonemap: &TonemapUniforms,
) -> Vec<u8> {
    tonemap_to_rgba8_with_bloom(hdr, width, height, tonemap, &NO_BLOOM)
}

/// [`tonemap_to_rgba8`] with the `bloom` binding (post `bloom`: the up chain's level 0).
///
/// # Panics
/// If `hdr` does not hold `width · height` texels.
pub fn tonemap_to_rgba8_with_bloom(
    hdr: &[[f32; 4]],
    width: u32,
    height: u32,
    tonemap: &TonemapUniforms,
    bloom: &Texture2D,
) -> Vec<u8> {
    assert_eq!(hdr.len(), width as usize * height as usize, "HDR frame is not {width}x{height}");
    let frame = HdrFrame { width, height, texels: hdr };
    let mut out = vec![0u8; hdr.len() * 4];
    if out.is_empty() {
        return out;
    }
    out.par_chunks_mut(width as usize * 4).enumerate().for_each(|(y, row)| {
        for (x, px) in row.chunks_exact_mut(4).enumerate() {
            let position = vec4(x as f32 + 0.5, y as f32 + 0.5, 0.0, 1.0);
            let rgba = fs_main_with_bloom(&VertexOut { position }, tonemap, &frame, bloom);
            for (byte, v) in px.iter_mut().zip(rgba) {
                *byte = store_unorm8(v);
            }
        }
    });
    out
}
