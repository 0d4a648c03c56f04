//! Mirror of `shaders/shared/floor.wgsl`: the sea floor's height and depth under a point and
//! the sun reaching a point under the water.

use ocean_core::frame::FrameUniforms;

use super::shadow::sun_visibility_r;
use crate::envelope::{Real, choose};
use crate::sampler::CLAMP_LINEAR;
use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Vec3, clamp, max, sqrt, texture_sample_level, vec2, vec3};

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
    let f = frame.terrain.floor;
    let r = frame.terrain.relief;
    let uv = vec2(x * r[0] + r[2], z * r[1] + r[3]);
    let relief = texture_sample_level(floor_map, &CLAMP_LINEAR, uv, 0.0).x;
    f[2] + f[0] * x + f[1] * z + relief
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
    let t = frame.terrain.sun_under;
    if frame.terrain.floor[3] == 0.0 || t[3] == 0.0 {
        return 1.0;
    }
    let across = sqrt(t[0] * t[0] + t[2] * t[2]);
    if across < 1e-4 {
        return 1.0;
    }
    let step = vec3(t[0], t[1], t[2]) * (t[3] / across);
    let steps = frame.terrain.top[1] as u32;
    for i in 1..=steps {
        let q = rel + step * i as f32;
        let y = q.y + frame.view.eye_height;
        if y > frame.terrain.top[0] {
            return 1.0;
        }
        if floor_height(q.x, q.z, frame, floor_map) > y + RELIEF_SHADOW_BIAS {
            return 0.0;
        }
    }
    1.0
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
