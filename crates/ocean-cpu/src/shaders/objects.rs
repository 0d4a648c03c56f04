//! CPU mirror of `shaders/objects.wgsl`: the objects in the main view, mirrored into the
//! reflection map, and scaled and fogged into the refraction map (eq. 4).

use ocean_core::frame::{FrameUniforms, ObjectVertex};

use super::shared::frame::{add3, dot3, mul3, scale3, transform_point, unit};

/// `VertexOut` of objects.wgsl (clip position and the varyings, in declaration order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub clip: [f32; 4],
    /// `@location(0)`.
    pub normal: [f32; 3],
    /// `@location(1)`.
    pub color: [f32; 3],
    /// `@location(2)`: camera-relative position as drawn.
    pub rel: [f32; 3],
    /// `@location(3)`: height of the original point above the sea plane.
    pub world_y: f32,
}

/// Number of f32 varyings of [`VertexOut`].
pub const VARYINGS: usize = 10;

impl VertexOut {
    /// The varyings as the rasterizer interpolates them.
    pub fn varyings(&self) -> [f32; VARYINGS] {
        let (n, c, r) = (self.normal, self.color, self.rel);
        [n[0], n[1], n[2], c[0], c[1], c[2], r[0], r[1], r[2], self.world_y]
    }

    /// A fragment's interpolated varyings back in the struct (clip unused).
    pub fn from_varyings(v: &[f32; VARYINGS]) -> Self {
        Self {
            clip: [0.0; 4],
            normal: [v[0], v[1], v[2]],
            color: [v[3], v[4], v[5]],
            rel: [v[6], v[7], v[8]],
            world_y: v[9],
        }
    }
}

/// WGSL `INV_PI` (0.31830988618 rounds to the same f32).
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;

/// `shade(normal, color)`: Lambert under the sun plus the sky's ambient.
fn shade(frame: &FrameUniforms, normal: [f32; 3], color: [f32; 3]) -> [f32; 3] {
    let n = unit(normal);
    let cos_sun = dot3(n, frame.sun.direction).max(0.0) * frame.sun.lit;
    let direct = scale3(frame.sun.radiance, cos_sun * INV_PI);
    mul3(color, add3(direct, frame.ambient.sky))
}

/// `vs_main`.
pub fn vs_main(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    VertexOut {
        clip: transform_point(&frame.view.view_proj, v.position),
        normal: v.normal,
        color: v.color,
        rel: v.position,
        world_y: v.position[1] + frame.view.eye_height,
    }
}

/// `fs_main`.
pub fn fs_main(input: &VertexOut, frame: &FrameUniforms) -> [f32; 4] {
    let c = shade(frame, input.normal, input.color);
    [c[0], c[1], c[2], 1.0]
}

/// `vs_reflect`.
pub fn vs_reflect(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let p = v.position;
    let mirrored = [p[0], -p[1] - 2.0 * frame.view.eye_height, p[2]];
    VertexOut {
        clip: transform_point(&frame.view.view_proj, mirrored),
        normal: [v.normal[0], -v.normal[1], v.normal[2]],
        color: v.color,
        rel: mirrored,
        world_y: p[1] + frame.view.eye_height,
    }
}

/// `fs_reflect`; `None` is `discard`.
pub fn fs_reflect(input: &VertexOut, frame: &FrameUniforms) -> Option<[f32; 4]> {
    if input.world_y < 0.0 {
        return None;
    }
    let n = [input.normal[0], -input.normal[1], input.normal[2]];
    let c = shade(frame, n, input.color);
    Some([c[0], c[1], c[2], 1.0])
}

/// `vs_refract`.
pub fn vs_refract(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let world_y = v.position[1] + frame.view.eye_height;
    let scaled =
        [v.position[0], world_y * frame.water.inv_eta - frame.view.eye_height, v.position[2]];
    VertexOut {
        clip: transform_point(&frame.view.view_proj, scaled),
        normal: v.normal,
        color: v.color,
        rel: scaled,
        world_y,
    }
}

/// `fs_refract`; `None` is `discard`.
pub fn fs_refract(input: &VertexOut, frame: &FrameUniforms) -> Option<[f32; 4]> {
    if input.world_y > 0.0 {
        return None;
    }
    let depth_below = -(input.rel[1] + frame.view.eye_height);
    let height_above = frame.view.eye_height.max(0.0);
    let dist = dot3(input.rel, input.rel).sqrt();
    let d = dist * (depth_below / (depth_below + height_above));
    let fog = 1.0 - (-frame.water.extinction_per_m * d).exp();
    let obj = scale3(
        shade(frame, input.normal, input.color),
        (-frame.water.extinction_per_m * -input.world_y).exp(),
    );
    let c = add3(scale3(frame.water.color, fog), scale3(obj, 1.0 - fog));
    Some([c[0], c[1], c[2], 1.0])
}
