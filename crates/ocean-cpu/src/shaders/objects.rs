//! CPU mirror of `shaders/objects.wgsl`: the objects in the main view, mirrored into the
//! reflection map, and scaled and fogged into the refraction map (eq. 4).

use ocean_core::frame::{FrameUniforms, ObjectVertex};

use super::shared::floor::{FloorMaps, sun_reaches};
use super::shared::frame::{dot3, transform_point, unit};
use super::shared::optics::water_volume_colour;
use super::water::WRAP_LINEAR;
use super::wgsl::{Vec2, Vec3, Vec4, exp, max, sqrt, texture_sample_level, vec2, vec3};
use crate::sampler::Texture2D;

/// `VertexOut` of objects.wgsl (clip position and the varyings, in declaration order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub clip: Vec4,
    /// `@location(0)`.
    pub normal: Vec3,
    /// `@location(1)`.
    pub color: Vec3,
    /// `@location(2)`: camera-relative position as drawn.
    pub rel: Vec3,
    /// `@location(3)`: height of the original point above the sea plane.
    pub world_y: f32,
}

/// Number of f32 varyings of [`VertexOut`].
pub const VARYINGS: usize = 10;

impl VertexOut {
    /// The varyings as the rasterizer interpolates them.
    pub fn varyings(&self) -> [f32; VARYINGS] {
        let (n, c, r) = (self.normal, self.color, self.rel);
        [n.x, n.y, n.z, c.x, c.y, c.z, r.x, r.y, r.z, self.world_y]
    }

    /// A fragment's interpolated varyings back in the struct (clip unused).
    pub fn from_varyings(v: &[f32; VARYINGS]) -> Self {
        Self {
            clip: Vec4::splat(0.0),
            normal: vec3(v[0], v[1], v[2]),
            color: vec3(v[3], v[4], v[5]),
            rel: vec3(v[6], v[7], v[8]),
            world_y: v[9],
        }
    }
}

/// WGSL `INV_PI` (0.31830988618 rounds to the same f32).
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;

/// The stage's textures: binding 1 (`displacement`), 3 (`shadow_map`) and 4 (`floor_map`).
#[derive(Clone, Copy)]
pub struct Maps<'a> {
    /// binding 1.
    pub displacement: &'a Texture2D,
    /// bindings 3 and 4.
    pub floor: FloorMaps<'a>,
}

/// A vertex entry point of the stage.
pub type VertexEntry = fn(&ObjectVertex, &FrameUniforms) -> VertexOut;
/// A map pass's fragment entry point (`None` is `discard`).
pub type MapFragmentEntry = fn(&VertexOut, &FrameUniforms, Maps<'_>) -> Option<[f32; 4]>;

/// `shade(normal, color, sun)`: Lambert under the share `sun` of the sun plus the sky's ambient.
fn shade(frame: &FrameUniforms, normal: Vec3, color: Vec3, sun: f32) -> Vec3 {
    let n = unit(normal);
    let cos_sun = max(dot3(n, frame.sun.direction.into()), 0.0) * (frame.sun.lit * sun);
    let direct = Vec3::from(frame.sun.radiance) * (cos_sun * INV_PI);
    color * (direct + Vec3::from(frame.ambient.sky))
}

/// `vs_main`.
pub fn vs_main(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let position = Vec3::from(v.position);
    VertexOut {
        clip: transform_point(&frame.view.view_proj, position),
        normal: v.normal.into(),
        color: v.color.into(),
        rel: position,
        world_y: position.y + frame.view.eye_height,
    }
}

/// `fs_main`.
pub fn fs_main(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> [f32; 4] {
    let sun = sun_reaches(input.rel, input.world_y, frame, maps.floor);
    shade(frame, input.normal, input.color, sun).extend(1.0).into()
}

/// `vs_reflect`.
pub fn vs_reflect(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let (position, normal) = (Vec3::from(v.position), Vec3::from(v.normal));
    let mirrored = vec3(position.x, -position.y - 2.0 * frame.view.eye_height, position.z);
    VertexOut {
        clip: transform_point(&frame.view.view_proj, mirrored),
        normal: vec3(normal.x, -normal.y, normal.z),
        color: v.color.into(),
        rel: mirrored,
        world_y: position.y + frame.view.eye_height,
    }
}

/// `clip_height(rel)`: where the maps clip the objects (the wave height under the point for
/// shading `chiu`, else 0); `displacement` is binding 1.
pub fn clip_height(rel: Vec3, frame: &FrameUniforms, displacement: &Texture2D) -> f32 {
    if frame.chiu.clip_waves == 0.0 {
        return 0.0;
    }
    let t = &frame.tiling;
    let pos = vec2(rel.x, rel.z) - Vec2::from(t.mesh_offset);
    let uv = (pos + Vec2::from(t.displacement_origin)) * t.inv_displacement_size
        + t.displacement_half_texel;
    texture_sample_level(displacement, &WRAP_LINEAR, uv, 0.0).y * frame.passes.waves
}

/// `fs_reflect`; `None` is `discard`.
pub fn fs_reflect(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> Option<[f32; 4]> {
    if input.world_y < clip_height(input.rel, frame, maps.displacement) {
        return None;
    }
    let n = vec3(input.normal.x, -input.normal.y, input.normal.z);
    Some(shade(frame, n, input.color, 1.0).extend(1.0).into())
}

/// `vs_refract`.
pub fn vs_refract(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let position = Vec3::from(v.position);
    let world_y = position.y + frame.view.eye_height;
    let scaled =
        vec3(position.x, world_y * frame.water.inv_eta - frame.view.eye_height, position.z);
    VertexOut {
        clip: transform_point(&frame.view.view_proj, scaled),
        normal: v.normal.into(),
        color: v.color.into(),
        rel: scaled,
        world_y,
    }
}

/// `fs_refract`; `None` is `discard`.
pub fn fs_refract(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> Option<[f32; 4]> {
    if input.world_y > clip_height(input.rel, frame, maps.displacement) {
        return None;
    }
    let depth_below = max(-(input.rel.y + frame.view.eye_height), 0.0);
    let height_above = max(frame.view.eye_height, 0.0);
    let dist = sqrt(dot3(input.rel, input.rel));
    let d = dist * (depth_below / (depth_below + height_above));
    let fog = 1.0 - exp(-frame.water.extinction_per_m * d);
    let at = vec3(input.rel.x, input.world_y - frame.view.eye_height, input.rel.z);
    let sun = sun_reaches(at, input.world_y, frame, maps.floor);
    let obj = shade(frame, input.normal, input.color, sun)
        * exp(-frame.water.extinction_per_m * max(-input.world_y, 0.0));
    Some((water_volume_colour(-input.world_y, frame) * fog + obj * (1.0 - fog)).extend(1.0).into())
}
