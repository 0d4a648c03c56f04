//! Mirror of `shaders/tonemap.wgsl`: HDR linear frame → 8-bit sRGB, one compute invocation
//! per pixel. The steps and why: `ocean_core::tonemap`.

use rayon::prelude::*;

pub use ocean_core::tonemap::TonemapUniforms;

use crate::envelope::{ByteRange, Iv, Jitter, JitterRules, Real, map3, zip3};
use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Components, Vec2, Vec3, Vec4};

pub use ocean_core::tonemap::{HABLE_P, HABLE_Q, HABLE_R, HABLE_S, HABLE_T, HABLE_WHITE_SCALE};

/// Largest finite f16 (`ocean_core::tonemap::HDR_MAX`).
pub const HDR_MAX: f32 = 65504.0;
/// 1 / 2.4 as the nearest f32.
pub const SRGB_INV_GAMMA: f32 = 0.416_666_66;

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
    x.map(aces_r)
}

/// Hable's filmic curve (Uncharted 2), normalised so that the white point W maps to 1:
/// x (P x + Q) / (x (R x + S) + T) · (1/g(W)) (`ocean_core::tonemap`).
pub fn hable(x: Vec3) -> Vec3 {
    x.map(hable_r)
}

/// `tone_curve(x)`: the curve `tonemap.curve` selects (1 Hable, else ACES).
pub fn tone_curve(x: Vec3, tonemap: &TonemapUniforms) -> Vec3 {
    x.map(|c| curve_r(c, tonemap.curve))
}

/// `vignette_factor(p)`: max(1 − s·r², 0) at the pixel centre `p`, r = 0 at the centre and 1
/// at the corner.
pub fn vignette_factor(p: Vec2, tonemap: &TonemapUniforms) -> f32 {
    vignette_factor_r([p.x, p.y], tonemap)
}

/// sRGB OETF, IEC 61966-2-1: 12.92 c for c ≤ 0.0031308, else 1.055 c^(1/2.4) − 0.055.
pub fn srgb_oetf(c: Vec3) -> Vec3 {
    c.map(srgb_oetf_r)
}

/// Rounds to the nearest multiple of 1/255, ties to even: `round(v · 255) / 255` (WGSL
/// `round` is Rust's `round_ties_even`; both are exact).
pub fn quantize_unorm8(v: Vec3) -> Vec3 {
    v.map(quantize_r)
}

/// What the `bloom` binding holds without post `bloom`: one zero texel (× `bloom_scale` = 0).
static NO_BLOOM: std::sync::LazyLock<Texture2D> =
    std::sync::LazyLock::new(|| Texture2D::new(1, 1, vec![[0.0; 4]]));

/// `bloom_at(p)`: the bloom binding (the up chain's level 0) upsampled 2× at pixel `p`.
pub fn bloom_at(p: [i32; 2], bloom: &Texture2D) -> Vec3 {
    crate::shaders::bloom::upsample_at(bloom, p)
}

/// `cs_main(@builtin(global_invocation_id) id)` without post `bloom` (its binding the 1×1
/// zero texture): [`cs_main_with_bloom`].
pub fn cs_main(id: [u32; 2], tonemap: &TonemapUniforms, hdr_frame: &HdrFrame) -> [f32; 4] {
    cs_main_with_bloom(id, tonemap, hdr_frame, &NO_BLOOM)
}

/// `cs_main(@builtin(global_invocation_id) id)` with the `bloom` binding: the quantised sRGB
/// value, alpha 1, that it stores at texel `id` (inside the frame: the shader returns early
/// outside). The pixel centre `id + 0.5` is exact in f32 for any frame a GPU can hold.
pub fn cs_main_with_bloom(
    id: [u32; 2],
    tonemap: &TonemapUniforms,
    hdr_frame: &HdrFrame,
    bloom: &Texture2D,
) -> [f32; 4] {
    let texel = [id[0] as i32, id[1] as i32];
    let centre = [id[0] as f32 + 0.5, id[1] as f32 + 0.5];
    let hdr = hdr_frame.texture_load(texel).xyz();
    let b = bloom_at(texel, bloom);
    let [r, g, bl] = shade([hdr.x, hdr.y, hdr.z], [b.x, b.y, b.z], centre, tonemap);
    [r, g, bl, 1.0]
}

/// `cs_main`'s arithmetic after its texture reads, over any [`Real`]: `f32` for the exact
/// frame (lavapipe's bits), [`crate::envelope::Iv`] for the envelope of a hardware GPU,
/// [`crate::envelope::Jitter`] for a random conformant GPU. `hdr` is the HDR texel, `bloom`
/// `bloom_at(texel)` (zeros without post `bloom`), `p` the pixel centre.
pub fn shade<R: Real>(hdr: [R; 3], bloom: [R; 3], p: [R; 2], tonemap: &TonemapUniforms) -> [R; 3] {
    let exposure = R::lit(tonemap.exposure);
    let exposed = map3(hdr, |c| c * exposure);
    let sanitised = map3(exposed, |c| c.max(R::lit(0.0)).min(R::lit(HDR_MAX)));
    let bloom_scale = R::lit(tonemap.bloom_scale);
    let bloomed = zip3(sanitised, bloom, |s, b| s + bloom_scale * b);
    let v = vignette_factor_r(p, tonemap);
    let x = map3(bloomed, |c| c * v);
    let curve = tonemap.curve;
    let mapped = map3(x, |c| curve_r(c, curve).clamp(R::lit(0.0), R::lit(1.0)));
    let encoded = map3(mapped, srgb_oetf_r);
    map3(encoded, quantize_r)
}

/// `vignette_factor(p)` over any [`Real`].
fn vignette_factor_r<R: Real>(p: [R; 2], tonemap: &TonemapUniforms) -> R {
    let dx = p[0] - R::lit(tonemap.center[0]);
    let dy = p[1] - R::lit(tonemap.center[1]);
    let r2 = (dx * dx + dy * dy) * R::lit(tonemap.inv_corner2);
    (R::lit(1.0) - R::lit(tonemap.vignette) * r2).max(R::lit(0.0))
}

/// `tone_curve(x)` for one component over any [`Real`].
fn curve_r<R: Real>(x: R, curve: u32) -> R {
    if curve == 1 { hable_r(x) } else { aces_r(x) }
}

/// `aces_narkowicz` for one component over any [`Real`].
fn aces_r<R: Real>(x: R) -> R {
    let l = R::lit;
    (x * (l(2.51) * x + l(0.03))) / (x * (l(2.43) * x + l(0.59)) + l(0.14))
}

/// `hable` for one component over any [`Real`].
fn hable_r<R: Real>(x: R) -> R {
    let l = R::lit;
    (x * (l(HABLE_P) * x + l(HABLE_Q))) / (x * (l(HABLE_R) * x + l(HABLE_S)) + l(HABLE_T))
        * l(HABLE_WHITE_SCALE)
}

/// `quantize_unorm8` for one component over any [`Real`].
fn quantize_r<R: Real>(c: R) -> R {
    (c * R::lit(255.0)).round() / R::lit(255.0)
}

/// `srgb_oetf(c)` for one component over any [`Real`].
fn srgb_oetf_r<R: Real>(c: R) -> R {
    let lo = R::lit(12.92) * c;
    let hi = R::lit(1.055) * c.pow(R::lit(SRGB_INV_GAMMA)) - R::lit(0.055);
    R::select(hi, lo, c.le(R::lit(0.0031308)))
}

/// What lavapipe's `Rgba8Unorm` storage texture stores for a shader output `v`: v · 255 rounded to the
/// nearest integer. Vulkan requires only one of the two integers closest to v · 255 (nearest
/// is recommended), so for the outputs of [`cs_main`], within a few ULP of multiples of 1/255,
/// another conformant GPU may store one code less or more: [`crate::envelope`] carries that.
pub fn store_unorm8(v: f32) -> u8 {
    Real::store_unorm8(v).lo
}

/// The `tonemap` pass over a whole `width × height` HDR frame (row-major, row 0 at the top):
/// RGBA8 bytes, 4 per pixel in the same order, ready for a PNG.
///
/// The dispatch runs one invocation per pixel, so this calls [`cs_main`] at each pixel; rows
/// run in parallel and each pixel is a pure function of its texel.
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
            let rgba = cs_main_with_bloom([x as u32, y as u32], tonemap, &frame, bloom);
            for (byte, v) in px.iter_mut().zip(rgba) {
                *byte = store_unorm8(v);
            }
        }
    });
    out
}

/// [`shade`] at every pixel of a `width × height` frame over the scalar `R`, rows in
/// parallel: `texel(i)` gives pixel i's HDR texel and `bloom_at` value, `out` turns the shaded
/// value into what is kept.
fn shade_frame<R: Real, T: Send>(
    width: u32,
    height: u32,
    tonemap: &TonemapUniforms,
    texel: impl Fn(usize) -> ([R; 3], [R; 3]) + Sync,
    out: impl Fn(usize, [R; 3]) -> T + Sync,
) -> Vec<T> {
    use rayon::prelude::*;
    let w = width as usize;
    (0..w * height as usize)
        .into_par_iter()
        .with_min_len(w.max(1))
        .map(|i| {
            let p = [R::lit((i % w) as f32 + 0.5), R::lit((i / w) as f32 + 0.5)];
            let (hdr, bloom) = texel(i);
            out(i, shade(hdr, bloom, p, tonemap))
        })
        .collect()
}

/// The RGB of a texel as exact intervals.
fn points(t: [f32; 4]) -> [Iv; 3] {
    [Iv::point(t[0]), Iv::point(t[1]), Iv::point(t[2])]
}

/// The pixel index `i`'s texel coordinates in a `width`-wide frame.
fn texel_of(i: usize, width: u32) -> [i32; 2] {
    [(i % width as usize) as i32, (i / width as usize) as i32]
}

/// The tonemap pass's envelope: per pixel, the value each of R, G, B may take before the
/// store and the bytes a conformant GPU may store, given the HDR frame `hdr` as intervals
/// (points for a GPU's own frame) and the `bloom` binding's texels as read (a GPU's own up
/// chain's level 0; `None` without post `bloom`).
///
/// # Panics
/// If `hdr` does not hold `width · height` texels.
pub fn envelope(
    hdr: &[[Iv; 3]],
    bloom: Option<&Texture2D>,
    width: u32,
    height: u32,
    tonemap: &TonemapUniforms,
) -> Vec<[(Iv, ByteRange); 3]> {
    assert_eq!(hdr.len(), width as usize * height as usize, "HDR frame is not {width}x{height}");
    // Without post `bloom` the binding is one zero texel, whose upsample is exactly 0 on any
    // GPU (products and sums of zeros): the envelope takes that 0 without the twelve interval
    // operations that find it (a sixth of the pass's envelope).
    let glow = |i: usize| match bloom {
        Some(b) => crate::shaders::bloom::upsample_at_r(b, texel_of(i, width)),
        None => [Iv::point(0.0); 3],
    };
    shade_frame(
        width,
        height,
        tonemap,
        |i| (hdr[i], glow(i)),
        |_, v| v.map(|c| (c, c.store_unorm8())),
    )
}

/// [`envelope`] of a GPU's own HDR frame (every texel a point).
pub fn envelope_of(
    hdr: &[[f32; 4]],
    bloom: Option<&Texture2D>,
    width: u32,
    height: u32,
    tonemap: &TonemapUniforms,
) -> Vec<[(Iv, ByteRange); 3]> {
    let hdr: Vec<[Iv; 3]> = hdr.iter().map(|&t| points(t)).collect();
    envelope(&hdr, bloom, width, height, tonemap)
}

/// The tonemap pass as one random conformant GPU computes it (`rules`): per pixel, R, G, B
/// before the store and the bytes stored.
///
/// # Panics
/// If `hdr` does not hold `width · height` texels.
pub fn jitter(
    hdr: &[[f32; 4]],
    bloom: Option<&Texture2D>,
    width: u32,
    height: u32,
    tonemap: &TonemapUniforms,
    rules: JitterRules,
) -> Vec<[(f32, u8); 3]> {
    assert_eq!(hdr.len(), width as usize * height as usize, "HDR frame is not {width}x{height}");
    let bloom = bloom.unwrap_or(&NO_BLOOM);
    shade_frame(
        width,
        height,
        tonemap,
        |i| {
            Jitter::reseed(rules, i as u64);
            let t = hdr[i];
            let glow = crate::shaders::bloom::upsample_at_r(bloom, texel_of(i, width));
            ([Jitter(t[0]), Jitter(t[1]), Jitter(t[2])], glow)
        },
        |_, v| v.map(|c| (c.0, c.store_unorm8().lo)),
    )
}
