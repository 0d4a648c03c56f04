//! CPU mirror of `shaders/shading/coastal.wgsl`: seed 004's Blinn–Phong, Fresnel and dull
//! colour seen from above.

use crate::shaders::shared::frame::{dot3, unit};
use crate::shaders::water::{
    Bindings, CLAMP_LINEAR, SurfacePoint, VertexOut, fresnel_st, pow_int, sky_radiance,
    sun_visibility,
};
use crate::shaders::wgsl::{Vec3, clamp, max, texture_sample_level, vec2, vec3};
use ocean_core::switch::SWITCH_ON;

/// `COASTAL_INV_PI`.
pub const COASTAL_INV_PI: f32 = 0.318_309_87;

/// `shade_above(in, p)`.
pub fn shade_above(input: &VertexOut, p: &SurfacePoint, b: &Bindings<'_>) -> Vec3 {
    let frame = b.frame;
    let n = p.n;
    let view = p.view;
    let s = &frame.coastal_shading;
    let cos_v = max(dot3(view, n), 0.0);
    let f = if s.schlick == SWITCH_ON {
        let m = 1.0 - cos_v;
        let m2 = m * m;
        s.f0 + (1.0 - s.f0) * (m2 * m2 * m)
    } else {
        let st = fresnel_st(p.u_bumped, frame.hu.fresnel_scale);
        texture_sample_level(b.fresnel_above, &CLAMP_LINEAR, st, 0.0).w
    };
    let mut r = n * (2.0 * cos_v) - view;
    r.y = max(r.y, 0.0);
    let sky_r = sky_radiance(b, unit(r + vec3(0.0, 1e-6, 0.0)));
    let at = p.screen - vec2(n.x, n.z) * s.distortion;
    let refl = texture_sample_level(b.reflection_map, &CLAMP_LINEAR, at, 0.0);
    let a_refl = refl.w * frame.passes.reflection_map;
    let c_reflect = sky_r * (1.0 - a_refl) + refl.xyz() * a_refl;
    let refr = texture_sample_level(b.refraction_map, &CLAMP_LINEAR, at, 0.0);
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = Vec3::from(frame.water.color) * (1.0 - a_refr) + refr.xyz() * a_refr;
    let l = Vec3::from(frame.sun.direction);
    let shadow = sun_visibility(input.rel, b) * frame.sun.lit;
    let lobe = pow_int(max(dot3(n, unit(l + view)), 0.0), s.shininess as u32);
    let q = 2.0 * p.coastal.x;
    let q2 = q * q;
    let mut q4 = q2 * q2;
    if p.coastal.z < 1.0 {
        q4 = 0.2 + (q4 - 0.2) * p.coastal.z;
    }
    let d = clamp(s.dull_factor * (1.0 + q4), 0.0, 1.0);
    let radiance = Vec3::from(frame.sun.radiance);
    let light =
        Vec3::from(frame.ambient.sky) + radiance * (max(dot3(n, l), 0.0) * shadow * COASTAL_INV_PI);
    let c =
        (c_reflect * f + c_refract * (1.0 - f)) * (1.0 - d) + Vec3::from(s.dull_color) * light * d;
    c + radiance * (lobe * shadow)
}
