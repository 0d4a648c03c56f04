//! CPU mirror of `shaders/shading/chiu.wgsl`: seed 001's eqs. 2–8 seen from above.

use crate::shaders::shared::floor::floor_depth;
use crate::shaders::shared::frame::{dot3, transform_point, unit};
use crate::shaders::shared::optics::{fresnel_exact, water_volume_colour};
use crate::shaders::water::{
    Bindings, CLAMP_LINEAR, SurfacePoint, VertexOut, pow_int, sky_radiance, sun_visibility,
};
use crate::shaders::wgsl::{Vec3, clamp, max, texture_sample_level, vec2, vec3};

/// `CHIU_MAX_EXPONENT`: eq. 5's exponent is clamped to [1, this].
pub const CHIU_MAX_EXPONENT: f32 = 65535.0;

/// `pow_blend(x, e)`: the whole powers either side of e blended linearly.
pub fn pow_blend(x: f32, e: f32) -> f32 {
    let n = e.floor();
    let lo = pow_int(x, n as u32);
    lo + (lo * x - lo) * (e - n)
}

/// `shade_above(in, p)`.
pub fn shade_above(input: &VertexOut, p: &SurfacePoint, b: &Bindings<'_>) -> Vec3 {
    let frame = b.frame;
    let n = p.n;
    let view = p.view;
    let z = max(transform_point(&frame.view.view_proj, input.rel).w, 1e-3);
    let vn = dot3(view, n);
    let f = fresnel_exact(vn, frame.water.eta);
    let r = n * (2.0 * vn) - view;
    let r_up = vec3(r.x, max(r.y, 0.0), r.z);
    let c_sky = sky_radiance(b, unit(r_up + vec3(0.0, 1e-6, 0.0)));
    let shift = vec2(n.x, n.z) * (frame.chiu.zeta_m / z);
    let refl = texture_sample_level(b.reflection_map, &CLAMP_LINEAR, p.screen + shift, 0.0);
    let a_refl = refl.w * frame.passes.reflection_map;
    let cos_sun = clamp(dot3(unit(r), Vec3::from(frame.sun.direction)), 0.0, 1.0);
    let e = clamp(frame.chiu.shininess_per_m * z, 1.0, CHIU_MAX_EXPONENT);
    let c_sun = Vec3::from(frame.sun.radiance)
        * (pow_blend(cos_sun, e) * frame.sun.lit * sun_visibility(input.rel, b));
    let c_reflect = c_sky * (1.0 - a_refl) + refl.xyz() * a_refl + c_sun;
    let refr = texture_sample_level(b.refraction_map, &CLAMP_LINEAR, p.screen + shift, 0.0);
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = water_volume_colour(floor_depth(input.rel, frame, b.floor_map), frame)
        * (1.0 - a_refr)
        + refr.xyz() * a_refr;
    c_reflect * f + c_refract * (1.0 - f)
}
