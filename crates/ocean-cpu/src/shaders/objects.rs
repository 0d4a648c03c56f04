//! CPU mirror of `shaders/objects.wgsl`: the objects in the main view, mirrored into the
//! reflection map, and scaled and fogged into the refraction map (eq. 4).

use ocean_core::frame::{FrameUniforms, ObjectVertex};

use super::shared::floor::{FloorMaps, sun_reaches};
use super::shared::frame::{dot3, transform_point};
use super::shared::optics::water_volume_colour;
use super::water::WRAP_LINEAR;
use super::wgsl::{Vec2, Vec3, Vec4, exp, max, sqrt, texture_sample_level, vec2, vec3};
use crate::envelope::raster::{self, Shaded};
use crate::envelope::{Iv, Jitter, JitterRules, Real, mat4_mul_vec4, normalize3};
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
    let [n, c] = [normal, color].map(|v| [v.x, v.y, v.z]);
    let [x, y, z] = shade_r(frame, n, c, sun);
    vec3(x, y, z)
}

/// `shade(normal, color, sun)` over any [`Real`]: Lambert under the share `sun` of the sun
/// plus the sky's ambient.
pub fn shade_r<R: Real>(frame: &FrameUniforms, normal: [R; 3], color: [R; 3], sun: R) -> [R; 3] {
    let l = R::lit;
    let n = normalize3(normal);
    let cos_sun =
        crate::envelope::dot3(n, frame.sun.direction.map(l)).max(l(0.0)) * (l(frame.sun.lit) * sun);
    let s = cos_sun * l(INV_PI);
    std::array::from_fn(|i| color[i] * (l(frame.sun.radiance[i]) * s + l(frame.ambient.sky[i])))
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

/// What [`vs_reflect_r`] outputs: (clip position, normal, colour, world_y).
pub type ReflectedVertex<R> = ([R; 4], [R; 3], [R; 3], R);

/// [`vs_reflect`] over any [`Real`] (`rel` is only read by `clip_height` under shading
/// `chiu`, which the envelope does not carry yet).
pub fn vs_reflect_r<R: Real>(v: &ObjectVertex, frame: &FrameUniforms) -> ReflectedVertex<R> {
    let l = R::lit;
    let [x, y, z] = v.position.map(l);
    let eye = l(frame.view.eye_height);
    let mirrored = [x, -y - l(2.0) * eye, z];
    let clip =
        mat4_mul_vec4(&frame.view.view_proj, [mirrored[0], mirrored[1], mirrored[2], l(1.0)]);
    let normal = [l(v.normal[0]), -l(v.normal[1]), l(v.normal[2])];
    (clip, normal, v.color.map(l), y + eye)
}

/// The envelope of the reflection map a conformant GPU draws of `triangles` into a `size`
/// map of `format`, cleared to `clear` (`vs_reflect`, `fs_reflect`, reversed-Z `Greater`):
/// per texel its colour interval and whether its coverage is ambiguous. Each triangle's
/// fragments are shaded from the varyings' envelope at each sample (the barycentrics' bounds). `None` under shading `chiu`,
/// whose clip height is a texture lookup the envelope does not carry yet.
pub fn reflection_envelope(
    triangles: &[[ObjectVertex; 3]],
    frame: &FrameUniforms,
    size: [u32; 2],
    format: ocean_core::frame_format::FrameFormat,
    clear: [f32; 4],
) -> Option<(Vec<[Iv; 4]>, Vec<bool>)> {
    if frame.chiu.clip_waves != 0.0 {
        return None;
    }
    let mut screen = Vec::with_capacity(triangles.len());
    let mut owner = Vec::with_capacity(triangles.len());
    let mut verts = Vec::with_capacity(triangles.len());
    let full = || {
        let n = (size[0] as usize) * (size[1] as usize);
        (vec![[Iv::FULL; 4]; n], vec![true; n])
    };
    for t in triangles {
        let v = t.each_ref().map(|v| vs_reflect_r::<Iv>(v, frame));
        // Past the near or far plane: the clipper's polygon, each part with its vertices'
        // barycentrics in the original. One it cannot bound: anything.
        let Some(parts) = raster::clip_near_far(v.map(|(clip, ..)| clip)) else {
            return Some(full());
        };
        for part in parts {
            let s = part.map(|p| raster::to_screen(p.clip, size[0], size[1]));
            let [Some(a), Some(b), Some(c)] = s else { return Some(full()) };
            screen.push([a, b, c]);
            owner.push((verts.len(), part.map(|p| (p.bary, p.bary_err))));
        }
        verts.push(v);
    }
    let shade = |k: usize, interp: &raster::Interp| {
        let (t, bary) = owner[k];
        let v = &verts[t];
        // A part's vertices hold convex combinations of the original triangle's values.
        let at = |f: &dyn Fn(usize) -> Iv| -> [Iv; 3] {
            bary.map(|(b, err)| {
                if err == 0.0 && b.iter().filter(|&&x| x != 0.0).count() == 1 {
                    return f(b.iter().position(|&x| x != 0.0).unwrap_or(0));
                }
                let vals = [f(0), f(1), f(2)];
                let x = Iv::sum(&[0, 1, 2].map(|j| vals[j] * Iv::new(b[j], b[j])));
                let spread = vals.iter().map(|v| v.magnitude()).fold(0.0, f64::max);
                let u = raster::VARYING_ULPS * crate::envelope::f32_ulp(x.magnitude())
                    + 2.0 * err * spread;
                if x.full { x } else { Iv::new(x.lo - u, x.hi + u) }
            })
        };
        let mix = |f: &dyn Fn(usize) -> Iv| interp.varying(at(f));
        let normal: [Iv; 3] = std::array::from_fn(|c| mix(&|j| v[j].1[c]));
        let color: [Iv; 3] = std::array::from_fn(|c| mix(&|j| v[j].2[c]));
        let world_y = mix(&|j| v[j].3);
        // fs_reflect: discard below the plane (clip height 0); the mirrored normal lit.
        let kept = if world_y.full {
            None
        } else if world_y.lo >= 0.0 {
            Some(true)
        } else if world_y.hi < 0.0 {
            Some(false)
        } else {
            None
        };
        let n = [normal[0], -normal[1], normal[2]];
        let [r, g, b] = shade_r(frame, n, color, Iv::lit(1.0));
        Shaded { color: [r, g, b, Iv::lit(1.0)].map(|c| c.store(format)), kept }
    };
    Some(raster::color_pass_greater(&screen, size[0], size[1], clear, shade))
}

/// The reflection map as one random conformant GPU draws it (`rules.scale` times the rules),
/// under the same conditions as [`reflection_envelope`].
pub fn reflection_jitter(
    triangles: &[[ObjectVertex; 3]],
    frame: &FrameUniforms,
    size: [u32; 2],
    format: ocean_core::frame_format::FrameFormat,
    clear: [f32; 4],
    rules: JitterRules,
) -> Vec<[f32; 4]> {
    let verts: Vec<[ReflectedVertex<f32>; 3]> =
        triangles.iter().map(|t| t.each_ref().map(|v| vs_reflect_r::<f32>(v, frame))).collect();
    let clip: Vec<[[f32; 4]; 3]> = verts.iter().map(|t| t.map(|v| v.0)).collect();
    raster::jitter_pass(&clip, size[0], size[1], true, clear, rules, |k, w, _| {
        let t = &verts[k];
        let mix = |f: &dyn Fn(usize) -> f32| -> Jitter {
            Jitter(
                (w[0] * f64::from(f(0)) + w[1] * f64::from(f(1)) + w[2] * f64::from(f(2))) as f32,
            )
        };
        let world_y = mix(&|j| t[j].3);
        if world_y.0 < 0.0 {
            return None;
        }
        let normal: [Jitter; 3] = std::array::from_fn(|c| mix(&|j| t[j].1[c]));
        let color: [Jitter; 3] = std::array::from_fn(|c| mix(&|j| t[j].2[c]));
        let n = [normal[0], -normal[1], normal[2]];
        let [r, g, b] = shade_r(frame, n, color, Jitter::lit(1.0));
        Some([r, g, b, Jitter::lit(1.0)].map(|c| c.store(format).0))
    })
}
