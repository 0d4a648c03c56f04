//! `shade_above` of the shading techniques the water pass's envelope carries, over any
//! [`Real`]: `hu` (seed 000's eq. 3, `shading/hu.wgsl`), `ggx` (seed 002's Cook–Torrance
//! BRDF, `shading/ggx.wgsl`) and `chiu` (seed 001's eqs. 2–8, `shading/chiu.wgsl`).

use ocean_core::frame::FrameUniforms;
use ocean_core::switch::SWITCH_ON;

use super::helpers::{
    fresnel_filtered, fresnel_st, pow_int, sky_filtered, sky_reflected, sun_lobe_filtered, unit,
};
use super::inputs::{Inputs, LEAST_POSITIVE, Tex};
use crate::envelope::{Real, choose, choose_n, dot3, mat4_mul_vec4, on_floor};
use crate::shaders::shading::chiu::CHIU_MAX_EXPONENT;
use crate::shaders::shading::coastal::COASTAL_INV_PI;
use crate::shaders::shared::fresnel::fresnel_exact_r;
use crate::shaders::shared::optics::water_volume_colour_r;
use crate::shaders::shared::shadow::sun_visibility_r;

/// The reflection and refraction maps as shadings `hu` and `ggx` blend them (§5.2): each
/// looked up at the screen position shifted by the bumped normal's horizontal part `d` times
/// its distortion, over the sky `sky_r` and over the water's colour by its coverage:
/// (C_reflect, C_refract).
fn screen_maps<R: Real>(
    sky_r: [R; 3],
    d: [R; 2],
    screen: [R; 2],
    inp: &Inputs<'_, R>,
) -> ([R; 3], [R; 3]) {
    let l = R::lit;
    let frame = inp.frame;
    let shifted = |k: f32| [screen[0] + d[0] * l(k), screen[1] + d[1] * l(k)];
    let refl = (inp.sample)(Tex::ReflectionMap, shifted(frame.hu.reflection_distortion), l(0.0));
    let a_refl = refl[3] * l(frame.passes.reflection_map);
    let c_reflect = std::array::from_fn(|c| sky_r[c] * (l(1.0) - a_refl) + refl[c] * a_refl);
    let refr = (inp.sample)(Tex::RefractionMap, shifted(frame.hu.refraction_distortion), l(0.0));
    let a_refr = refr[3] * l(frame.passes.refraction_map);
    let c_refract =
        std::array::from_fn(|c| l(frame.water.color[c]) * (l(1.0) - a_refr) + refr[c] * a_refr);
    (c_reflect, c_refract)
}

/// Shading `hu`'s `shade_above(in, p)`.
pub(super) fn shade_above_hu<R: Real>(
    rel: [R; 3],
    slopes: [R; 3],
    n: [R; 3],
    view: [R; 3],
    u_bumped: [R; 2],
    screen: [R; 2],
    inp: &Inputs<'_, R>,
) -> [R; 3] {
    let l = R::lit;
    let frame = inp.frame;
    let variance = slopes[2];
    let filtered = l(0.0).lt(variance);
    let vpos = variance.at_least(LEAST_POSITIVE);
    let (du, dv) = (n[0], n[2]);
    let st = fresnel_st(u_bumped, frame);
    let fres = (inp.sample)(Tex::FresnelAbove, st, l(0.0));
    let f = choose(filtered, || fresnel_filtered(u_bumped, vpos, inp), || fres[3]);
    let sky_r = choose_n(
        filtered,
        || sky_filtered(view, slopes, vpos, inp),
        || sky_reflected(view, n, inp),
    );
    let (c_reflect, c_refract) = screen_maps(sky_r, [du, dv], screen, inp);
    let vb = [fres[0], fres[2], fres[1]];
    let sd = frame.sun.direction;
    let r_sun = [-l(sd[0]), l(sd[1]), -l(sd[2])];
    let cos_spec = dot3(vb, r_sun).max(l(0.0));
    let lobe = choose(
        filtered,
        || sun_lobe_filtered(u_bumped, vpos, frame),
        || pow_int(cos_spec, frame.hu.phong_exponent as u32),
    );
    let spec_scale = lobe * l(frame.sun.lit);
    let shadow = sun_visibility_r(rel, frame, inp.shadow_dims, inp.occluder);
    std::array::from_fn(|c| {
        c_reflect[c] * f
            + c_refract[c] * (l(1.0) - f)
            + l(frame.sun.radiance[c]) * spec_scale * shadow
    })
}

/// `ggx_lambda(c, alpha2)`: Smith's Λ for GGX.
fn ggx_lambda<R: Real>(c: R, alpha2: R) -> R {
    let l = R::lit;
    let c2 = c.sq();
    let tan2 = (l(1.0) - c2) / c2;
    l(0.5) * ((l(1.0) + alpha2 * tan2).sqrt() - l(1.0))
}

/// `ggx_fresnel(c)`: eq. 2, or Schlick's.
fn ggx_fresnel<R: Real>(c: R, frame: &FrameUniforms) -> R {
    let l = R::lit;
    if frame.ggx.schlick_fresnel == SWITCH_ON {
        let m = l(1.0) - c.clamp(l(0.0), l(1.0));
        let m2 = m.sq();
        let m5 = m2.sq() * m;
        let f0 = l(frame.ggx.f0);
        return (f0 + m5) - f0 * m5;
    }
    fresnel_exact_r(c, l(frame.water.eta))
}

/// `ggx_geometry(nl, nv, alpha2)`.
fn ggx_geometry<R: Real>(nl: R, nv: R, alpha2: R, frame: &FrameUniforms) -> R {
    let l = R::lit;
    if frame.ggx.schlick_geometry == SWITCH_ON {
        let k = l(0.5) * alpha2.sqrt();
        return (nl / (nl * (l(1.0) - k) + k)) * (nv / (nv * (l(1.0) - k) + k));
    }
    l(1.0) / ((ggx_lambda(nl, alpha2) + ggx_lambda(nv, alpha2)) + l(1.0))
}

/// `ggx_brdf(n, view, l, nl, nv, alpha2)`.
fn ggx_brdf<R: Real>(
    n: [R; 3],
    view: [R; 3],
    sun: [R; 3],
    (nl, nv, alpha2): (R, R, R),
    frame: &FrameUniforms,
) -> R {
    let l = R::lit;
    let h = unit(std::array::from_fn(|c| sun[c] + view[c]));
    let nh = dot3(n, h).max(l(0.0));
    let vh = dot3(view, h).max(l(0.0));
    let c = [n[1] * h[2] - n[2] * h[1], n[2] * h[0] - n[0] * h[2], n[0] * h[1] - n[1] * h[0]];
    let d_den = R::sum(&[c[0].sq(), c[1].sq(), c[2].sq()]) + nh.sq() * alpha2;
    let d = alpha2 / (d_den.sq() * l(std::f32::consts::PI));
    ggx_fresnel(vh, frame) * ggx_geometry(nl, nv, alpha2, frame) * d / (l(4.0) * nl * nv)
}

/// Shading `ggx`'s `shade_above(in, p)`.
pub(super) fn shade_above_ggx<R: Real>(
    rel: [R; 3],
    slopes: [R; 3],
    n: [R; 3],
    view: [R; 3],
    screen: [R; 2],
    inp: &Inputs<'_, R>,
) -> [R; 3] {
    let l = R::lit;
    let frame = inp.frame;
    let alpha2 = l(frame.ggx.alpha) * l(frame.ggx.alpha) + l(2.0) * slopes[2];
    let vn = dot3(view, n);
    let nv = vn.max(l(1e-4));
    let f_env = ggx_fresnel(nv, frame);
    let sky_r = sky_reflected(view, n, inp);
    let (c_reflect, c_refract) = screen_maps(sky_r, [n[0], n[2]], screen, inp);
    let sd = frame.sun.direction;
    let sun = [l(sd[0]), l(sd[1]), l(sd[2])];
    let nl = dot3(n, sun);
    let c_sun = if frame.sun.lit > 0.0 {
        choose_n(
            l(0.0).lt(nl),
            || {
                let nl = nl.at_least(LEAST_POSITIVE);
                let f = ggx_brdf(n, view, sun, (nl, nv, alpha2), frame);
                let vis = sun_visibility_r(rel, frame, inp.shadow_dims, inp.occluder);
                let k = f * nl * vis;
                std::array::from_fn(|c| l(frame.sun.radiance[c]) * k)
            },
            || [l(0.0); 3],
        )
    } else {
        [l(0.0); 3]
    };
    std::array::from_fn(|c| c_reflect[c] * f_env + c_refract[c] * (l(1.0) - f_env) + c_sun[c])
}

/// `pow_blend(x, e)` of shading `chiu` for x ∈ [0, 1], e ≥ 1: the whole powers either side of
/// e blended. Where an interval puts e across more than one integer, anything in [0, 1] (the
/// blend of two powers of x ∈ [0, 1] by a weight in [0, 1] stays there, rounded monotonely).
/// Within one integer the blend lo·(1 − (1 − x)·t) lies between lo·x and lo, where intervals
/// lose the correlation of lo, x and t: each of its 4 roundings errs by at most an ULP of lo
/// (allowed 16).
fn pow_blend<R: Real>(x: R, e: R) -> R {
    let l = R::lit;
    let [v] = on_floor(e, [l(0.0).hull(l(1.0))], |n, _| {
        let lo = pow_int(x, n as u32);
        let v = lo + (lo * x - lo) * (e - l(n));
        if !R::INTERVAL {
            return [v];
        }
        let slack = 16.0 * crate::envelope::f32_ulp(lo.most().abs());
        let least = (lo * x).least().min(lo.least()).max(0.0);
        [v.within(least - slack, lo.most() + slack)]
    });
    v
}

/// Shading `chiu`'s `shade_above(in, p)` (seed 001's eqs. 2–8): `depth` is the floor's depth
/// under the point (`floor_depth(in.rel)`).
pub(super) fn shade_above_chiu<R: Real>(
    rel: [R; 3],
    n: [R; 3],
    view: [R; 3],
    screen: [R; 2],
    depth: R,
    inp: &Inputs<'_, R>,
) -> [R; 3] {
    let l = R::lit;
    let frame = inp.frame;
    let z = mat4_mul_vec4(&frame.view.view_proj, [rel[0], rel[1], rel[2], l(1.0)])[3].max(l(1e-3));
    let vn = dot3(view, n);
    let f = fresnel_exact_r(vn, l(frame.water.eta));
    let r: [R; 3] = std::array::from_fn(|c| n[c] * (l(2.0) * vn) - view[c]);
    let c_sky = sky_reflected(view, n, inp);
    let k = l(frame.chiu.zeta_m) / z;
    let shifted = [screen[0] + n[0] * k, screen[1] + n[2] * k];
    let refl = (inp.sample)(Tex::ReflectionMap, shifted, l(0.0));
    let a_refl = refl[3] * l(frame.passes.reflection_map);
    let sd = frame.sun.direction;
    let cos_sun = dot3(unit(r), [l(sd[0]), l(sd[1]), l(sd[2])]).clamp(l(0.0), l(1.0));
    let e = (l(frame.chiu.shininess_per_m) * z).clamp(l(1.0), l(CHIU_MAX_EXPONENT));
    let vis = sun_visibility_r(rel, frame, inp.shadow_dims, inp.occluder);
    let lobe = pow_blend(cos_sun, e) * l(frame.sun.lit) * vis;
    let refr = (inp.sample)(Tex::RefractionMap, shifted, l(0.0));
    let a_refr = refr[3] * l(frame.passes.refraction_map);
    let volume = water_volume_colour_r(depth, frame);
    std::array::from_fn(|c| {
        let c_reflect =
            c_sky[c] * (l(1.0) - a_refl) + refl[c] * a_refl + l(frame.sun.radiance[c]) * lobe;
        let c_refract = volume[c] * (l(1.0) - a_refr) + refr[c] * a_refr;
        c_reflect * f + c_refract * (l(1.0) - f)
    })
}

/// What shading `coastal` reads of `SurfacePoint`.
pub(super) struct Point<R> {
    /// The bumped unit normal.
    pub n: [R; 3],
    /// The unit vector to the eye.
    pub view: [R; 3],
    /// The bumped view vector's horizontal part.
    pub u_bumped: [R; 2],
    /// The fragment's normalised screen position.
    pub screen: [R; 2],
    /// `coastal_shore`'s (φ in turns, foam turbulence, share resolved).
    pub coastal: [R; 3],
}

/// Shading `coastal`'s `shade_above(in, p)` (seed 004).
pub(super) fn shade_above_coastal<R: Real>(
    rel: [R; 3],
    p: &Point<R>,
    inp: &Inputs<'_, R>,
) -> [R; 3] {
    let l = R::lit;
    let frame = inp.frame;
    let s = &frame.coastal_shading;
    let (n, view) = (p.n, p.view);
    let cos_v = dot3(view, n).max(l(0.0));
    let f = if s.schlick == SWITCH_ON {
        let m = l(1.0) - cos_v;
        let m2 = m * m;
        l(s.f0) + (l(1.0) - l(s.f0)) * (m2 * m2 * m)
    } else {
        (inp.sample)(Tex::FresnelAbove, fresnel_st(p.u_bumped, frame), l(0.0))[3]
    };
    let r: [R; 3] = std::array::from_fn(|c| n[c] * (l(2.0) * cos_v) - view[c]);
    let sky_r = (inp.sky)(unit([r[0] + l(0.0), r[1].max(l(0.0)) + l(1e-6), r[2] + l(0.0)]));
    let at = [p.screen[0] - n[0] * l(s.distortion), p.screen[1] - n[2] * l(s.distortion)];
    let refl = (inp.sample)(Tex::ReflectionMap, at, l(0.0));
    let a_refl = refl[3] * l(frame.passes.reflection_map);
    let refr = (inp.sample)(Tex::RefractionMap, at, l(0.0));
    let a_refr = refr[3] * l(frame.passes.refraction_map);
    let sd = frame.sun.direction.map(l);
    let shadow = sun_visibility_r(rel, frame, inp.shadow_dims, inp.occluder) * l(frame.sun.lit);
    let half = unit([sd[0] + view[0], sd[1] + view[1], sd[2] + view[2]]);
    let lobe = pow_int(dot3(n, half).max(l(0.0)), s.shininess as u32);
    let q = l(2.0) * p.coastal[0];
    let q2 = q * q;
    let q4 = q2 * q2;
    let q4 = choose(p.coastal[2].lt(l(1.0)), || l(0.2) + (q4 - l(0.2)) * p.coastal[2], || q4);
    let d = (l(s.dull_factor) * (l(1.0) + q4)).clamp(l(0.0), l(1.0));
    let lit = dot3(n, sd).max(l(0.0)) * shadow * l(COASTAL_INV_PI);
    std::array::from_fn(|c| {
        let c_reflect = sky_r[c] * (l(1.0) - a_refl) + refl[c] * a_refl;
        let c_refract = l(frame.water.color[c]) * (l(1.0) - a_refr) + refr[c] * a_refr;
        let light = l(frame.ambient.sky[c]) + l(frame.sun.radiance[c]) * lit;
        let col = (c_reflect * f + c_refract * (l(1.0) - f)) * (l(1.0) - d)
            + l(s.dull_color[c]) * light * d;
        col + l(frame.sun.radiance[c]) * (lobe * shadow)
    })
}
