//! Mirror of `shaders/shared/foam.wgsl`: the foam texture, the coverage and the foam's light,
//! whose f32 arithmetic is ocean-core `foam`'s.

pub use ocean_core::foam::{FOAM_INV_PI, FOAM_MIN_JACOBIAN, FOAM_NOISE_PERIOD, foam_texture};

use ocean_core::frame::FrameUniforms;

use super::frame::dot3;
use super::shadow::sun_visibility;
use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Vec2, Vec3, max, vec2};

/// `foam_texture_at(pos)`.
pub fn foam_texture_at(pos: Vec2, frame: &FrameUniforms) -> f32 {
    let f = &frame.foam;
    let along = (pos.x * f.wind[0] + f.noise_origin[0]) + pos.y * f.wind[1];
    let across = (pos.y * f.wind[0] + f.noise_origin[1]) - pos.x * f.wind[1];
    let q = vec2(along, across) * vec2(f.inv_noise_cell_along, f.inv_noise_cell);
    foam_texture(q.x, q.y, f.seed)
}

/// `foam_mix(t, n)`.
pub fn foam_mix(t: f32, n: f32, frame: &FrameUniforms) -> f32 {
    ocean_core::foam::foam_mix(t, n, frame.foam.intensity)
}

/// `heuristic_turbulence(h, s, j)`.
pub fn heuristic_turbulence(h: f32, s: f32, j: f32, frame: &FrameUniforms) -> f32 {
    ocean_core::foam::heuristic_turbulence(h, s, j, &frame.foam)
}

/// `jacobian_turbulence(j)`.
pub fn jacobian_turbulence(j: f32, frame: &FrameUniforms) -> f32 {
    ocean_core::foam::jacobian_turbulence(j, &frame.foam)
}

/// `foam_radiance(n, rel)`.
pub fn foam_radiance(n: Vec3, rel: Vec3, frame: &FrameUniforms, shadow_map: &Texture2D) -> Vec3 {
    let cos_sun = max(dot3(n, Vec3::from(frame.sun.direction)), 0.0)
        * (frame.sun.lit * sun_visibility(rel, frame, shadow_map));
    let direct = Vec3::from(frame.sun.radiance) * (cos_sun * FOAM_INV_PI);
    Vec3::from(frame.foam.color) * (direct + Vec3::from(frame.ambient.sky))
}

/// `foam_over(c, cover, n, rel)`.
pub fn foam_over(
    c: Vec3,
    cover: f32,
    n: Vec3,
    rel: Vec3,
    frame: &FrameUniforms,
    shadow_map: &Texture2D,
) -> Vec3 {
    if cover <= 0.0 {
        return c;
    }
    c * (1.0 - cover) + foam_radiance(n, rel, frame, shadow_map) * cover
}
