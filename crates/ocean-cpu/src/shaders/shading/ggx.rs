//! CPU mirror of `shaders/shading/ggx.wgsl`: seed 002's Cook–Torrance BRDF with GGX.

use crate::shaders::shared::frame::{dot3, unit};
use crate::shaders::shared::optics::fresnel_exact;
use crate::shaders::water::{
    Bindings, CLAMP_LINEAR, SurfacePoint, VertexOut, sky_radiance, sun_visibility,
};
use crate::shaders::wgsl::{Vec3, clamp, max, texture_sample_level, vec2, vec3};
use ocean_core::frame::FrameUniforms;
use ocean_core::switch::SWITCH_ON;

/// `GGX_PI`: f32(π).
pub const GGX_PI: f32 = std::f32::consts::PI;

/// `ggx_lambda(c, alpha2)`: Smith's Λ for GGX.
pub fn ggx_lambda(c: f32, alpha2: f32) -> f32 {
    let c2 = c * c;
    let tan2 = (1.0 - c2) / c2;
    0.5 * ((1.0 + alpha2 * tan2).sqrt() - 1.0)
}

/// `ggx_fresnel(c)`: eq. 2 or Schlick's.
pub fn ggx_fresnel(c: f32, frame: &FrameUniforms) -> f32 {
    if frame.ggx.schlick_fresnel == SWITCH_ON {
        let m = 1.0 - clamp(c, 0.0, 1.0);
        let m2 = m * m;
        let m5 = m2 * m2 * m;
        return (frame.ggx.f0 + m5) - frame.ggx.f0 * m5;
    }
    fresnel_exact(c, frame.water.eta)
}

/// `ggx_geometry(nl, nv, alpha2)`.
pub fn ggx_geometry(nl: f32, nv: f32, alpha2: f32, frame: &FrameUniforms) -> f32 {
    if frame.ggx.schlick_geometry == SWITCH_ON {
        let k = 0.5 * alpha2.sqrt();
        return (nl / (nl * (1.0 - k) + k)) * (nv / (nv * (1.0 - k) + k));
    }
    1.0 / ((ggx_lambda(nl, alpha2) + ggx_lambda(nv, alpha2)) + 1.0)
}

/// `ggx_brdf(n, view, l, nl, nv, alpha2)`: f(l, v) for n·l = nl > 0 and n·v = nv > 0.
pub fn ggx_brdf(
    n: Vec3,
    view: Vec3,
    l: Vec3,
    nl: f32,
    nv: f32,
    alpha2: f32,
    frame: &FrameUniforms,
) -> f32 {
    let h = unit(l + view);
    let nh = max(dot3(n, h), 0.0);
    let vh = max(dot3(view, h), 0.0);
    let c = vec3(n.y * h.z - n.z * h.y, n.z * h.x - n.x * h.z, n.x * h.y - n.y * h.x);
    let d_den = dot3(c, c) + (nh * nh) * alpha2;
    let d = alpha2 / ((d_den * d_den) * GGX_PI);
    ggx_fresnel(vh, frame) * ggx_geometry(nl, nv, alpha2, frame) * d / (4.0 * nl * nv)
}

/// `shade_above(in, p)`.
pub fn shade_above(input: &VertexOut, p: &SurfacePoint, b: &Bindings<'_>) -> Vec3 {
    let frame = b.frame;
    let n = p.n;
    let view = p.view;
    let alpha2 = frame.ggx.alpha * frame.ggx.alpha + 2.0 * p.slopes.z;
    let vn = dot3(view, n);
    let nv = max(vn, 1e-4);
    let f_env = ggx_fresnel(nv, frame);
    let r = n * (2.0 * vn) - view;
    let r_up = vec3(r.x, max(r.y, 0.0), r.z);
    let sky_r = sky_radiance(b, unit(r_up + vec3(0.0, 1e-6, 0.0)));
    let refl = texture_sample_level(
        b.reflection_map,
        &CLAMP_LINEAR,
        p.screen + vec2(n.x, n.z) * frame.hu.reflection_distortion,
        0.0,
    );
    let a_refl = refl.w * frame.passes.reflection_map;
    let c_reflect = sky_r * (1.0 - a_refl) + refl.xyz() * a_refl;
    let refr = texture_sample_level(
        b.refraction_map,
        &CLAMP_LINEAR,
        p.screen + vec2(n.x, n.z) * frame.hu.refraction_distortion,
        0.0,
    );
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = Vec3::from(frame.water.color) * (1.0 - a_refr) + refr.xyz() * a_refr;
    let l = Vec3::from(frame.sun.direction);
    let nl = dot3(n, l);
    let mut c_sun = vec3(0.0, 0.0, 0.0);
    if nl > 0.0 && frame.sun.lit > 0.0 {
        let f = ggx_brdf(n, view, l, nl, nv, alpha2, frame);
        c_sun = Vec3::from(frame.sun.radiance) * (f * nl * sun_visibility(input.rel, b));
    }
    c_reflect * f_env + c_refract * (1.0 - f_env) + c_sun
}
