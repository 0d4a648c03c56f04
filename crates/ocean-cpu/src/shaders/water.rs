//! CPU mirror of `shaders/water.wgsl`: the final pass of seed 000, eq. 3.
#![expect(clippy::manual_range_contains, reason = "mirrors the WGSL comparisons one to one")]

use ocean_core::frame::FrameUniforms;

use super::shared::frame::{add3, dot3, scale3, transform_point, unit, xyz};
use crate::sampler::{
    AddressMode, FilterMode, Sampler, Texture2D, texture_sample, texture_sample_level,
};

/// `wrap_linear`: repeat addressing, bilinear (the tiled wave maps).
pub const WRAP_LINEAR: Sampler = Sampler {
    address_mode_u: AddressMode::Repeat,
    address_mode_v: AddressMode::Repeat,
    filter: FilterMode::Linear,
};

/// `clamp_linear`: clamp-to-edge addressing, bilinear (screen-space maps, Fresnel texture).
pub const CLAMP_LINEAR: Sampler = Sampler {
    address_mode_u: AddressMode::ClampToEdge,
    address_mode_v: AddressMode::ClampToEdge,
    filter: FilterMode::Linear,
};

/// Bias of the shadow-map depth comparison.
pub const SHADOW_BIAS: f32 = 0.002;

/// The stage's bindings (group 0 in binding order, then the sky function of
/// `shared/preetham.wgsl` with its uniforms).
pub struct Bindings<'a> {
    /// binding 0.
    pub frame: &'a FrameUniforms,
    /// binding 1: (disp_x, height, disp_z, jacobian).
    pub displacement: &'a Texture2D,
    /// binding 2: (slope_x, slope_z, 0, 0).
    pub displacement_slopes: &'a Texture2D,
    /// binding 3: (slope_x, slope_z, height, jacobian).
    pub bump: &'a Texture2D,
    /// binding 4.
    pub fresnel_above: &'a Texture2D,
    /// binding 5.
    pub fresnel_below: &'a Texture2D,
    /// binding 6.
    pub reflection_map: &'a Texture2D,
    /// binding 7.
    pub refraction_map: &'a Texture2D,
    /// binding 8.
    pub shadow_map: &'a Texture2D,
    /// `sky_radiance(dir)`.
    pub sky_radiance: &'a (dyn Fn([f32; 3]) -> [f32; 3] + Sync),
}

/// `WaterVertex`: the vertex format is defined once, in ocean-core.
pub use ocean_core::geometry::WaterVertex;

/// `VertexOut`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub clip: [f32; 4],
    /// `@location(0)`.
    pub rel: [f32; 3],
    /// `@location(1)`.
    pub uv_d: [f32; 2],
    /// `@location(2)`.
    pub uv_b: [f32; 2],
    /// `@location(3)`.
    pub weight: f32,
}

/// Number of f32 varyings of [`VertexOut`].
pub const VARYINGS: usize = 8;

impl VertexOut {
    /// The varyings in declaration order.
    pub fn varyings(&self) -> [f32; VARYINGS] {
        let (r, d, b) = (self.rel, self.uv_d, self.uv_b);
        [r[0], r[1], r[2], d[0], d[1], b[0], b[1], self.weight]
    }

    /// The fragment stage's input: `clip` is the fragment's position (frag_coord).
    pub fn from_fragment(frag_coord: [f32; 4], v: &[f32; VARYINGS]) -> Self {
        Self {
            clip: frag_coord,
            rel: [v[0], v[1], v[2]],
            uv_d: [v[3], v[4]],
            uv_b: [v[5], v[6]],
            weight: v[7],
        }
    }
}

/// `vs_main`.
pub fn vs_main(v: &WaterVertex, b: &Bindings<'_>) -> VertexOut {
    let f = b.frame;
    let uv_d = [
        (v.pos[0] + f.tiling.displacement_origin[0]) * f.tiling.inv_displacement_size
            + f.tiling.displacement_half_texel,
        (v.pos[1] + f.tiling.displacement_origin[1]) * f.tiling.inv_displacement_size
            + f.tiling.displacement_half_texel,
    ];
    let uv_b = [
        (v.pos[0] + f.tiling.bump_origin[0]) * f.tiling.inv_bump_size + f.tiling.bump_half_texel,
        (v.pos[1] + f.tiling.bump_origin[1]) * f.tiling.inv_bump_size + f.tiling.bump_half_texel,
    ];
    let s = texture_sample_level(b.displacement, &WRAP_LINEAR, uv_d, 0.0);
    let w = v.weight * f.passes.waves;
    let d = [s[0] * w, s[1] * w, s[2] * w, s[3] * w];
    let plane = [v.pos[0] + f.tiling.mesh_offset[0], v.pos[1] + f.tiling.mesh_offset[1]];
    let rel = [plane[0] + d[0], d[1] - f.view.eye_height, plane[1] + d[2]];
    VertexOut { clip: transform_point(&f.view.view_proj, rel), rel, uv_d, uv_b, weight: v.weight }
}

/// `pow_int(x, n)`: x^n by binary exponentiation, multiplications in the WGSL's order.
pub fn pow_int(x: f32, n: u32) -> f32 {
    let mut result = 1.0;
    let mut base = x;
    let mut e = n;
    loop {
        if e & 1 == 1 {
            result *= base;
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        base *= base;
    }
    result
}

/// `sun_visibility(rel)`.
fn sun_visibility(rel: [f32; 3], b: &Bindings<'_>) -> f32 {
    let f = b.frame;
    if f.passes.shadow_map == 0.0 {
        return 1.0;
    }
    let s = transform_point(&f.sun.shadow_view_proj, rel);
    let u = s[0] * 0.5 + 0.5;
    let v = 0.5 - s[1] * 0.5;
    if u < 0.0 || u >= 1.0 || v < 0.0 || v >= 1.0 {
        return 1.0;
    }
    let dims = [b.shadow_map.width as i32, b.shadow_map.height as i32];
    let texel = [
        ((u * dims[0] as f32).floor() as i32).min(dims[0] - 1),
        ((v * dims[1] as f32).floor() as i32).min(dims[1] - 1),
    ];
    let occluder = b.shadow_map.texel(texel[0] as u32, texel[1] as u32)[0];
    if occluder < s[2] - SHADOW_BIAS {
        return 0.0;
    }
    1.0
}

/// `bumped_normal(in)`: the bumped unit normal (§5).
pub fn bumped_normal(input: &VertexOut, b: &Bindings<'_>) -> [f32; 3] {
    let f = b.frame;
    let sdt = texture_sample(b.displacement_slopes, &WRAP_LINEAR, input.uv_d);
    let wd = input.weight * f.passes.waves;
    let sd = [sdt[0] * wd, sdt[1] * wd];
    let sbt = texture_sample(b.bump, &WRAP_LINEAR, input.uv_b);
    let sb = [sbt[0] * f.passes.waves, sbt[1] * f.passes.waves];
    unit([-(sd[0] + sb[0]), 1.0, -(sd[1] + sb[1])])
}

/// `fresnel_st(view, n)`: the Fresnel texture's coordinates of the bumped view vector
/// (§5.1, Fig. 4).
pub fn fresnel_st(view: [f32; 3], n: [f32; 3]) -> [f32; 2] {
    [(view[0] - n[0]) * 0.5 + 0.5, (view[2] - n[2]) * 0.5 + 0.5]
}

/// `fs_main(in)`; `input.clip` is the fragment's position.
pub fn fs_main(input: &VertexOut, b: &Bindings<'_>) -> [f32; 4] {
    let f = b.frame;
    let n = bumped_normal(input, b);
    let du = n[0];
    let dv = n[2];
    let view = unit([-input.rel[0], -input.rel[1], -input.rel[2]]);
    let screen =
        [input.clip[0] * f.view.inv_viewport_size[0], input.clip[1] * f.view.inv_viewport_size[1]];
    if view[1] >= 0.0 {
        let st = fresnel_st(view, n);
        let fres = texture_sample(b.fresnel_above, &CLAMP_LINEAR, st);
        let fr = fres[3];
        let vn = dot3(view, n);
        let mut r =
            [n[0] * (2.0 * vn) - view[0], n[1] * (2.0 * vn) - view[1], n[2] * (2.0 * vn) - view[2]];
        r[1] = r[1].max(0.0);
        let sky = (b.sky_radiance)(unit(add3(r, [0.0, 1e-6, 0.0])));
        let refl = texture_sample(
            b.reflection_map,
            &CLAMP_LINEAR,
            [
                screen[0] + du * f.hu.reflection_distortion,
                screen[1] + dv * f.hu.reflection_distortion,
            ],
        );
        let a_refl = refl[3] * f.passes.reflection_map;
        let c_reflect = add3(scale3(sky, 1.0 - a_refl), scale3(xyz(refl), a_refl));
        let refr = texture_sample(
            b.refraction_map,
            &CLAMP_LINEAR,
            [
                screen[0] + du * f.hu.refraction_distortion,
                screen[1] + dv * f.hu.refraction_distortion,
            ],
        );
        let a_refr = refr[3] * f.passes.refraction_map;
        let c_refract = add3(scale3(f.water.color, 1.0 - a_refr), scale3(xyz(refr), a_refr));
        let vb = [fres[0], fres[2], fres[1]];
        let r_sun = [-f.sun.direction[0], f.sun.direction[1], -f.sun.direction[2]];
        let cos_spec = dot3(vb, r_sun).max(0.0);
        let spec =
            scale3(f.sun.radiance, pow_int(cos_spec, f.hu.phong_exponent as u32) * f.sun.lit);
        let shadow = sun_visibility(input.rel, b);
        let c =
            add3(add3(scale3(c_reflect, fr), scale3(c_refract, 1.0 - fr)), scale3(spec, shadow));
        return [c[0], c[1], c[2], 1.0];
    }
    let st = fresnel_st(view, n);
    let fr = texture_sample(b.fresnel_below, &CLAMP_LINEAR, st)[3];
    let eta = f.water.eta;
    let i = [-view[0], -view[1], -view[2]];
    let cos_i = dot3(i, n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    let mut sky = [0.0, 0.0, 0.0];
    if k > 0.0 {
        let t = add3(scale3(i, eta), scale3(n, k.sqrt() - eta * cos_i));
        sky = (b.sky_radiance)(unit([t[0], t[1].max(0.0) + 1e-6, t[2]]));
    }
    let c = add3(scale3(f.water.color, fr), scale3(sky, 1.0 - fr));
    [c[0], c[1], c[2], 1.0]
}
