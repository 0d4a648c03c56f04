//! CPU mirror of `shaders/shading/hu.wgsl`: seed 000's eq. 3 seen from above.

use crate::shaders::shared::frame::{dot3, unit};
use crate::shaders::water::{
    Bindings, CLAMP_LINEAR, SurfacePoint, VertexOut, fresnel_filtered, fresnel_st, pow_int,
    sky_filtered, sky_radiance, sun_lobe_filtered, sun_visibility,
};
use crate::shaders::wgsl::{Vec3, max, texture_sample_level, vec2, vec3};

/// `shade_above(in, p)`.
pub fn shade_above(input: &VertexOut, p: &SurfacePoint, b: &Bindings<'_>) -> Vec3 {
    let frame = b.frame;
    let n = p.n;
    let view = p.view;
    let variance = p.slopes.z;
    let du = n.x;
    let dv = n.z;
    let st = fresnel_st(p.u_bumped, frame.hu.fresnel_scale);
    let fres = texture_sample_level(b.fresnel_above, &CLAMP_LINEAR, st, 0.0);
    let mut f = fres.w;
    if variance > 0.0 {
        f = fresnel_filtered(p.u_bumped, variance, b);
    }
    let vn = dot3(view, n);
    let mut r = n * (2.0 * vn) - view;
    r.y = max(r.y, 0.0);
    let mut sky_r = sky_radiance(b, unit(r + vec3(0.0, 1e-6, 0.0)));
    if variance > 0.0 {
        sky_r = sky_filtered(view, p.slopes, variance, b);
    }
    let refl = texture_sample_level(
        b.reflection_map,
        &CLAMP_LINEAR,
        p.screen + vec2(du, dv) * frame.hu.reflection_distortion,
        0.0,
    );
    let a_refl = refl.w * frame.passes.reflection_map;
    let c_reflect = sky_r * (1.0 - a_refl) + refl.xyz() * a_refl;
    let refr = texture_sample_level(
        b.refraction_map,
        &CLAMP_LINEAR,
        p.screen + vec2(du, dv) * frame.hu.refraction_distortion,
        0.0,
    );
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = Vec3::from(frame.water.color) * (1.0 - a_refr) + refr.xyz() * a_refr;
    let vb = vec3(fres.x, fres.z, fres.y);
    let sun_direction = Vec3::from(frame.sun.direction);
    let r_sun = vec3(-sun_direction.x, sun_direction.y, -sun_direction.z);
    let cos_spec = max(dot3(vb, r_sun), 0.0);
    let mut lobe = pow_int(cos_spec, frame.hu.phong_exponent as u32);
    if variance > 0.0 {
        lobe = sun_lobe_filtered(p.u_bumped, variance, frame);
    }
    let spec = Vec3::from(frame.sun.radiance) * (lobe * frame.sun.lit);
    let shadow = sun_visibility(input.rel, b);
    c_reflect * f + c_refract * (1.0 - f) + spec * shadow
}
