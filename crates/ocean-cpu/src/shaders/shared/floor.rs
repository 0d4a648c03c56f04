//! Mirror of `shaders/shared/floor.wgsl`: the sea floor's height and depth under a point and
//! the sun reaching a point under the water.

use ocean_core::frame::FrameUniforms;

use super::shadow::sun_visibility_r;
use crate::envelope::{Cond, Iv, Jitter, Real, choose, filter};
use crate::sampler::CLAMP_LINEAR;
use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Vec3, clamp, max, texture_sample_level, vec2, vec3};

/// `RELIEF_SHADOW_BIAS`, m.
pub const RELIEF_SHADOW_BIAS: f32 = 0.05;

/// What the floor's functions read besides `frame`: the importing stage's `shadow_map` and
/// `floor_map` bindings.
#[derive(Clone, Copy)]
pub struct FloorMaps<'a> {
    /// `shadow_map`.
    pub shadow_map: &'a Texture2D,
    /// `floor_map`.
    pub floor_map: &'a Texture2D,
}

/// `floor_height(x, z)`.
pub fn floor_height(x: f32, z: f32, frame: &FrameUniforms, floor_map: &Texture2D) -> f32 {
    floor_height_r(x, z, frame, &|uv| relief_texel(uv, floor_map))
}

/// The relief map's `textureSampleLevel(floor_map, clamp_linear, uv, 0.0).x`, as lavapipe
/// filters.
fn relief_texel(uv: [f32; 2], floor_map: &Texture2D) -> f32 {
    texture_sample_level(floor_map, &CLAMP_LINEAR, vec2(uv[0], uv[1]), 0.0).x
}

/// [`floor_height`] over any [`Real`]; `relief_at(uv)` is the relief map's red channel
/// filtered at `uv` (the plane and the relief summed as written, or reassociated).
pub fn floor_height_r<R: Real>(
    x: R,
    z: R,
    frame: &FrameUniforms,
    relief_at: &dyn Fn([R; 2]) -> R,
) -> R {
    let l = R::lit;
    let f = frame.terrain.floor;
    let r = frame.terrain.relief;
    let relief = relief_at([x * l(r[0]) + l(r[2]), z * l(r[1]) + l(r[3])]);
    let terms = [l(f[2]), l(f[0]) * x, l(f[1]) * z, relief];
    R::sum_as_written(&terms, |t| ((t[0] + t[1]) + t[2]) + t[3])
}

/// `shore_weight(x, z, inv)`: the share of waves `fft`/`gerstner` kept over the floor.
pub fn shore_weight(x: f32, z: f32, inv: f32, frame: &FrameUniforms, floor_map: &Texture2D) -> f32 {
    if inv == 0.0 {
        return 1.0;
    }
    clamp(max(-floor_height(x, z, frame, floor_map), 0.0) * inv, 0.0, 1.0)
}

/// `floor_depth(rel)`.
pub fn floor_depth(rel: Vec3, frame: &FrameUniforms, floor_map: &Texture2D) -> f32 {
    max(-floor_height(rel.x, rel.z, frame, floor_map), 0.0)
}

/// `relief_sun(rel)`.
pub fn relief_sun(rel: Vec3, frame: &FrameUniforms, floor_map: &Texture2D) -> f32 {
    <f32 as ReliefMarch>::relief_sun([rel.x, rel.y, rel.z], frame, floor_map)
}

/// A scalar type that marches `relief_sun` over the relief map itself: the exact frame
/// (`f32`), its envelope ([`Iv`]) and a random conformant GPU ([`Jitter`]).
pub trait ReliefMarch: Real {
    /// `relief_sun(rel)` with `floor_map` the relief.
    fn relief_sun(rel: [Self; 3], frame: &FrameUniforms, floor_map: &Texture2D) -> Self;
}

impl ReliefMarch for f32 {
    fn relief_sun(rel: [f32; 3], frame: &FrameUniforms, floor_map: &Texture2D) -> f32 {
        relief_sun_r(rel, frame, &|uv| relief_texel(uv, floor_map))
    }
}

/// The march carried step by step, the relief map filtered by the filter's envelope at
/// Vulkan's minimum precision.
impl ReliefMarch for Iv {
    fn relief_sun(rel: [Iv; 3], frame: &FrameUniforms, floor_map: &Texture2D) -> Iv {
        relief_sun_r(rel, frame, &|uv| filter::sample_level0(floor_map, &CLAMP_LINEAR, uv)[0])
    }
}

/// The random GPU's roundings and its filter at Vulkan's minimum precision.
impl ReliefMarch for Jitter {
    fn relief_sun(rel: [Jitter; 3], frame: &FrameUniforms, floor_map: &Texture2D) -> Jitter {
        let at = |uv| filter::sample_level0_jitter(floor_map, &CLAMP_LINEAR, uv)[0];
        relief_sun_r(rel, frame, &at)
    }
}

/// [`relief_sun`] over any [`Real`]; `relief_at` as in [`floor_height_r`].
///
/// A comparison the bounds cannot decide ends the march for some GPUs and not for others:
/// its outcome is kept as possible and the march goes on for the rest, whose points are the
/// same intervals. A decided one ends the march of every GPU still marching. The result is
/// the march's one outcome, or the hull of 0 and 1 where both are possible.
pub fn relief_sun_r<R: Real>(
    rel: [R; 3],
    frame: &FrameUniforms,
    relief_at: &dyn Fn([R; 2]) -> R,
) -> R {
    let l = R::lit;
    let t = frame.terrain.sun_under;
    if frame.terrain.floor[3] == 0.0 || t[3] == 0.0 {
        return l(1.0);
    }
    let across = (l(t[0]) * l(t[0]) + l(t[2]) * l(t[2])).sqrt();
    // A sun overhead casts no shadow on a heightfield beyond the bias.
    choose(across.lt(l(1e-4)), || l(1.0), || march(rel, frame, across, relief_at))
}

/// `relief_sun`'s loop, from the horizontal length `across` of the sun's direction.
fn march<R: Real>(
    rel: [R; 3],
    frame: &FrameUniforms,
    across: R,
    relief_at: &dyn Fn([R; 2]) -> R,
) -> R {
    let l = R::lit;
    let t = frame.terrain.sun_under;
    let k = l(t[3]) / across;
    let step: [R; 3] = std::array::from_fn(|c| l(t[c]) * k);
    let (top, bias) = (l(frame.terrain.top[0]), l(RELIEF_SHADOW_BIAS));
    // The outcomes some GPU may reach: the sun (1), the relief's shadow (0).
    let (mut lit, mut shadowed) = (false, false);
    let mut all_ended = false;
    for i in 1..=frame.terrain.top[1] as u32 {
        let q: [R; 3] = std::array::from_fn(|c| rel[c] + step[c] * l(i as f32));
        let y = q[1] + l(frame.view.eye_height);
        match top.lt(y).decided() {
            Some(true) => (lit, all_ended) = (true, true),
            None => lit = true,
            Some(false) => {}
        }
        if all_ended {
            break;
        }
        match (y + bias).lt(floor_height_r(q[0], q[2], frame, relief_at)).decided() {
            Some(true) => (shadowed, all_ended) = (true, true),
            None => shadowed = true,
            Some(false) => {}
        }
        if all_ended {
            break;
        }
    }
    match (lit || !all_ended, shadowed) {
        (true, true) => l(0.0).hull(l(1.0)),
        (false, _) => l(0.0),
        (true, false) => l(1.0),
    }
}

/// `sun_reaches(rel, world_y)`.
pub fn sun_reaches(rel: Vec3, world_y: f32, frame: &FrameUniforms, maps: FloorMaps<'_>) -> f32 {
    let map = maps.shadow_map;
    let relief = |r: [f32; 3]| relief_sun(vec3(r[0], r[1], r[2]), frame, maps.floor_map);
    sun_reaches_r(
        [rel.x, rel.y, rel.z],
        world_y,
        frame,
        [map.width, map.height],
        &|x, y| map.texel(x, y)[0],
        &relief,
    )
}

/// [`sun_reaches`] over any [`Real`]: the shadow map `dims` texels, its texel read by
/// `occluder`; `relief` is `relief_sun`.
pub fn sun_reaches_r<R: Real>(
    rel: [R; 3],
    world_y: R,
    frame: &FrameUniforms,
    dims: [u32; 2],
    occluder: &dyn Fn(u32, u32) -> R,
    relief: &dyn Fn([R; 3]) -> R,
) -> R {
    let l = R::lit;
    let t = frame.terrain.sun_under;
    if t[1] <= 0.0 {
        return l(1.0);
    }
    choose(
        l(0.0).le(world_y),
        || l(1.0),
        || {
            let k = -world_y / l(t[1]);
            let surface: [R; 3] = std::array::from_fn(|i| rel[i] + l(t[i]) * k);
            sun_visibility_r(surface, frame, dims, occluder) * relief(rel)
        },
    )
}
