//! CPU mirror of `shaders/bloom.wgsl`: the bright pass of the HDR frame and its blur pyramid,
//! level by level as the compute stage writes it. The steps and why: `ocean_core::bloom`.

use ocean_core::bloom::BloomUniforms;
use ocean_core::frame_format::FrameFormat;
use ocean_core::plan::BloomInputs;
use rayon::prelude::*;

use crate::envelope::{Real, zip3};
use crate::mip::MipChain;
use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Vec3, max, min};

/// Largest finite f16 (`ocean_core::tonemap::HDR_MAX`), the tonemap's clamp.
pub const BLOOM_HDR_MAX: f32 = 65504.0;

/// `tap(x, y)`: texel (x, y) of `src`, clamped to its edge.
fn tap(src: &Texture2D, params: &BloomUniforms, x: i32, y: i32) -> Vec3 {
    let x = x.clamp(0, params.src_width as i32 - 1);
    let y = y.clamp(0, params.src_height as i32 - 1);
    let t = src.texel(x as u32, y as u32);
    [t[0], t[1], t[2]].into()
}

/// `bright(c)`: what exceeds the threshold of the sanitised exposed value.
pub fn bright(c: Vec3, params: &BloomUniforms) -> Vec3 {
    let x = min(max(c * params.exposure, Vec3::splat(0.0)), Vec3::splat(BLOOM_HDR_MAX));
    max(x - params.threshold, Vec3::splat(0.0))
}

fn source(src: &Texture2D, params: &BloomUniforms, x: i32, y: i32, bright_pass: bool) -> Vec3 {
    let c = tap(src, params, x, y);
    if bright_pass { bright(c, params) } else { c }
}

fn down_row(src: &Texture2D, p: &BloomUniforms, i: i32, y: i32, bright_pass: bool) -> Vec3 {
    let x = 2 * i - 1;
    ((0.125 * source(src, p, x, y, bright_pass) + 0.375 * source(src, p, x + 1, y, bright_pass))
        + 0.375 * source(src, p, x + 2, y, bright_pass))
        + 0.125 * source(src, p, x + 3, y, bright_pass)
}

/// `down(id, bright_pass)`: texel `id` of the level below `src`, the (1, 3, 3, 1)/8 tent.
pub fn down(id: [u32; 2], params: &BloomUniforms, src: &Texture2D, bright_pass: bool) -> Vec3 {
    let (i, y) = (id[0] as i32, 2 * id[1] as i32 - 1);
    let p = params;
    ((0.125 * down_row(src, p, i, y, bright_pass)
        + 0.375 * down_row(src, p, i, y + 1, bright_pass))
        + 0.375 * down_row(src, p, i, y + 2, bright_pass))
        + 0.125 * down_row(src, p, i, y + 3, bright_pass)
}

/// `upsample_at(p, size)` of `bloom.wgsl` (and `bloom_at` of `tonemap.wgsl`): the 2×
/// bilinear upsample of `coarse` at fine texel `p`, coarse coordinates clamped to its size.
pub fn upsample_at(coarse: &Texture2D, p: [i32; 2]) -> Vec3 {
    Vec3::from(upsample_at_r::<f32>(coarse, p))
}

/// [`upsample_at`] over any [`Real`] (each texel read exactly: a GPU's own texture, or the
/// oracle's in the exact frame).
pub fn upsample_at_r<R: Real>(coarse: &Texture2D, p: [i32; 2]) -> [R; 3] {
    let size = [coarse.width as i32, coarse.height as i32];
    let load = |x: i32, y: i32| {
        let t = coarse.texel(x as u32, y as u32);
        [R::lit(t[0]), R::lit(t[1]), R::lit(t[2])]
    };
    let m = p.map(|v| v >> 1);
    let far: [i32; 2] = std::array::from_fn(|k| if p[k] & 1 == 1 { m[k] + 1 } else { m[k] - 1 });
    let n: [i32; 2] = std::array::from_fn(|k| m[k].clamp(0, size[k] - 1));
    let f: [i32; 2] = std::array::from_fn(|k| far[k].clamp(0, size[k] - 1));
    let (near, far_w) = (R::lit(0.75), R::lit(0.25));
    let mix = |x: [R; 3], y: [R; 3]| zip3(x, y, |x, y| near * x + far_w * y);
    let a = mix(load(n[0], n[1]), load(f[0], n[1]));
    let b = mix(load(n[0], f[1]), load(f[0], f[1]));
    mix(a, b)
}

/// `upsample(id)`: texel `id` of `up[k]` = `detail` (`down[k]`) + the upsample of `coarse`
/// (`up[k + 1]`), at most `params.store_max`.
pub fn upsample(
    id: [u32; 2],
    params: &BloomUniforms,
    detail: &Texture2D,
    coarse: &Texture2D,
) -> Vec3 {
    let d = detail.texel(id[0], id[1]);
    let sum = Vec3::from([d[0], d[1], d[2]]) + upsample_at(coarse, [id[0] as i32, id[1] as i32]);
    min(sum, Vec3::splat(params.store_max))
}

/// One dispatch over a `w` × `h` level: `f` at every texel, rows in parallel, alpha 1, each
/// texel stored in the chain's `format` (a storage-texture write).
fn dispatch_level(
    w: u32,
    h: u32,
    format: FrameFormat,
    f: impl Fn([u32; 2]) -> Vec3 + Sync,
) -> Texture2D {
    let mut texels = vec![[0.0f32; 4]; w as usize * h as usize];
    texels.par_chunks_mut(w as usize).enumerate().for_each(|(j, row)| {
        for (i, t) in row.iter_mut().enumerate() {
            let v = f([i as u32, j as u32]);
            *t = format.store4([v.x, v.y, v.z, 1.0]);
        }
    });
    Texture2D::new(w, h, texels)
}

/// The pass: the down chain from the `hdr` frame (one `bright_down`, then a `downsample` per
/// level), then the up chain from the coarsest level back to level 0 (its last level is the
/// down chain's, copied, as the GPU copies it). Returns (down, up), packed as [`MipChain`]
/// holds a chain.
pub fn dispatch(hdr: &Texture2D, inputs: &BloomInputs) -> (MipChain, MipChain) {
    let mut down_levels: Vec<Texture2D> = Vec::with_capacity(inputs.down.len());
    for (k, params) in inputs.down.iter().enumerate() {
        let src = if k == 0 { hdr } else { &down_levels[k - 1] };
        let t = dispatch_level(params.width, params.height, inputs.format, |id| {
            down(id, params, src, k == 0)
        });
        down_levels.push(t);
    }
    let count = down_levels.len();
    let mut up_levels: Vec<Texture2D> = vec![down_levels[count - 1].clone()];
    for k in (0..count - 1).rev() {
        let params = inputs.up(k);
        let coarse = &up_levels[0];
        let detail = &down_levels[k];
        let t = dispatch_level(params.width, params.height, inputs.format, |id| {
            upsample(id, &params, detail, coarse)
        });
        up_levels.insert(0, t);
    }
    (MipChain::from_levels(&down_levels), MipChain::from_levels(&up_levels))
}

/// Level 0 of a chain as its own texture (what the tonemap binds of the up chain).
pub fn level0(chain: &MipChain) -> Texture2D {
    let (w, h) = (chain.width, chain.height);
    Texture2D::new(w, h, chain.atlas.texels[..w as usize * h as usize].to_vec())
}
