//! CPU mirror of `shaders/bloom.wgsl`: the bright pass of the HDR frame and its blur pyramid,
//! level by level as the compute stage writes it. The steps and why: `ocean_core::bloom`.

use ocean_core::bloom::{BloomUniforms, DOWN_WEIGHTS};
use ocean_core::frame_format::FrameFormat;
use ocean_core::graph::BloomInputs;
use rayon::prelude::*;

use crate::envelope::{AtlasEnvelope, Iv, Jitter, JitterRules, Real, zip3};
use crate::mip::MipChain;
use crate::sampler::Texture2D;
use crate::shaders::wgsl::Vec3;

/// Largest finite f16 (`ocean_core::tonemap::HDR_MAX`), the tonemap's clamp.
pub const BLOOM_HDR_MAX: f32 = 65504.0;

/// `tap(x, y)`: texel (x, y) of `src`, clamped to its edge.
fn tap<R: Real>(src: &Texture2D, params: &BloomUniforms, x: i32, y: i32) -> [R; 3] {
    let x = x.clamp(0, params.src_width as i32 - 1);
    let y = y.clamp(0, params.src_height as i32 - 1);
    let t = src.texel(x as u32, y as u32);
    [R::lit(t[0]), R::lit(t[1]), R::lit(t[2])]
}

/// `bright(c)`: what exceeds the threshold of the sanitised exposed value.
pub fn bright(c: Vec3, params: &BloomUniforms) -> Vec3 {
    Vec3::from(bright_r([c.x, c.y, c.z], params))
}

/// [`bright`] over any [`Real`].
pub fn bright_r<R: Real>(c: [R; 3], params: &BloomUniforms) -> [R; 3] {
    c.map(|c| {
        let x = (c * R::lit(params.exposure)).max(R::lit(0.0)).min(R::lit(BLOOM_HDR_MAX));
        (x - R::lit(params.threshold)).max(R::lit(0.0))
    })
}

fn source<R: Real>(
    src: &Texture2D,
    params: &BloomUniforms,
    x: i32,
    y: i32,
    bright_pass: bool,
) -> [R; 3] {
    let c = tap(src, params, x, y);
    if bright_pass { bright_r(c, params) } else { c }
}

/// The (1, 3, 3, 1)/8 tent of four values per component, summed left to right as written.
fn tent<R: Real>(v: [[R; 3]; 4]) -> [R; 3] {
    let w = DOWN_WEIGHTS.map(R::lit);
    std::array::from_fn(|c| {
        R::sum(&[w[0] * v[0][c], w[1] * v[1][c], w[2] * v[2][c], w[3] * v[3][c]])
    })
}

fn down_row<R: Real>(
    src: &Texture2D,
    p: &BloomUniforms,
    i: i32,
    y: i32,
    bright_pass: bool,
) -> [R; 3] {
    let x = 2 * i - 1;
    tent(std::array::from_fn(|k| source(src, p, x + k as i32, y, bright_pass)))
}

/// `down(id, bright_pass)`: texel `id` of the level below `src`, the (1, 3, 3, 1)/8 tent.
pub fn down(id: [u32; 2], params: &BloomUniforms, src: &Texture2D, bright_pass: bool) -> Vec3 {
    Vec3::from(down_r(id, params, src, bright_pass))
}

/// [`down`] over any [`Real`].
pub fn down_r<R: Real>(
    id: [u32; 2],
    params: &BloomUniforms,
    src: &Texture2D,
    bright_pass: bool,
) -> [R; 3] {
    let (i, y) = (id[0] as i32, 2 * id[1] as i32 - 1);
    tent(std::array::from_fn(|k| down_row(src, params, i, y + k as i32, bright_pass)))
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
    Vec3::from(upsample_r(id, params, detail, coarse))
}

/// [`upsample`] over any [`Real`].
pub fn upsample_r<R: Real>(
    id: [u32; 2],
    params: &BloomUniforms,
    detail: &Texture2D,
    coarse: &Texture2D,
) -> [R; 3] {
    let d = detail.texel(id[0], id[1]);
    let up = upsample_at_r::<R>(coarse, [id[0] as i32, id[1] as i32]);
    let store_max = R::lit(params.store_max);
    std::array::from_fn(|c| (R::lit(d[c]) + up[c]).min(store_max))
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

/// One level over any [`Real`]: `f` at every texel, stored in `format`.
fn level_r<R: Real + Send>(
    w: u32,
    h: u32,
    format: FrameFormat,
    f: impl Fn(usize, [u32; 2]) -> [R; 3] + Sync,
) -> Vec<[R; 3]> {
    (0..w as usize * h as usize)
        .into_par_iter()
        .map(|i| {
            let id = [(i % w as usize) as u32, (i / w as usize) as u32];
            f(i, id).map(|c| c.store(format))
        })
        .collect()
}

/// The pass's envelope given what the GPU read: each level of the down chain from the GPU's
/// own level above it (level 0 from `hdr`), each level of the up chain from the GPU's own
/// down level and up level below it; the up chain's last level is a copy of the down chain's
/// (exact). Atlases in [`MipChain`]'s layout, `None` in the padding.
///
/// # Panics
/// If the GPU's chains do not have the plan's levels.
pub fn envelope(
    hdr: &Texture2D,
    down: &MipChain,
    up: &MipChain,
    inputs: &BloomInputs,
) -> (AtlasEnvelope, AtlasEnvelope) {
    let count = inputs.down.len();
    assert_eq!(down.levels as usize, count, "the down chain's levels");
    assert_eq!(up.levels as usize, count, "the up chain's levels");
    let mut down_env = Vec::with_capacity(count);
    for (k, params) in inputs.down.iter().enumerate() {
        let src = if k == 0 { hdr.clone() } else { down.level(k as u32 - 1) };
        down_env.push(level_r(params.width, params.height, inputs.format, |_, id| {
            down_r::<Iv>(id, params, &src, k == 0)
        }));
    }
    let top = down.level(count as u32 - 1);
    let mut up_env: Vec<Vec<[Iv; 3]>> = vec![Vec::new(); count];
    up_env[count - 1] =
        top.texels.iter().map(|t| [Iv::point(t[0]), Iv::point(t[1]), Iv::point(t[2])]).collect();
    for k in (0..count - 1).rev() {
        let params = inputs.up(k);
        let (detail, coarse) = (down.level(k as u32), up.level(k as u32 + 1));
        up_env[k] = level_r(params.width, params.height, inputs.format, |_, id| {
            upsample_r::<Iv>(id, &params, &detail, &coarse)
        });
    }
    (
        crate::envelope::atlas_of(down.width, down.height, &down_env),
        crate::envelope::atlas_of(up.width, up.height, &up_env),
    )
}

/// The pass as one random conformant GPU runs it (`rules`): (down, up) as [`dispatch`] returns
/// them.
pub fn jitter(hdr: &Texture2D, inputs: &BloomInputs, rules: JitterRules) -> (MipChain, MipChain) {
    let to_texture = |w: u32, h: u32, v: Vec<[Jitter; 3]>| {
        Texture2D::new(w, h, v.into_iter().map(|c| [c[0].0, c[1].0, c[2].0, 1.0]).collect())
    };
    let mut salt = 0u64;
    let mut down_levels: Vec<Texture2D> = Vec::with_capacity(inputs.down.len());
    for (k, params) in inputs.down.iter().enumerate() {
        let src = if k == 0 { hdr } else { &down_levels[k - 1] };
        let v = level_r(params.width, params.height, inputs.format, |i, id| {
            Jitter::reseed(rules, salt + i as u64);
            down_r::<Jitter>(id, params, src, k == 0)
        });
        salt += 1 << 32;
        down_levels.push(to_texture(params.width, params.height, v));
    }
    let count = down_levels.len();
    let mut up_levels: Vec<Texture2D> = vec![down_levels[count - 1].clone()];
    for k in (0..count - 1).rev() {
        let params = inputs.up(k);
        let (detail, coarse) = (&down_levels[k], &up_levels[0]);
        let v = level_r(params.width, params.height, inputs.format, |i, id| {
            Jitter::reseed(rules, salt + i as u64);
            upsample_r::<Jitter>(id, &params, detail, coarse)
        });
        salt += 1 << 32;
        up_levels.insert(0, to_texture(params.width, params.height, v));
    }
    (MipChain::from_levels(&down_levels), MipChain::from_levels(&up_levels))
}
