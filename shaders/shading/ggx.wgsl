// Shading `ggx` (Welch, seed 002 §Physically Based Rendering), the water seen from above:
//   C = F(n·v)·C_reflect + (1 − F(n·v))·C_refract + E_sun·f(l, v)·(n·l)·visibility,
//   f = F(v·h)·G(l, v)·D(h) / (4 (n·l)(n·v))   (Cook–Torrance, Walter et al. 2007),
// D the GGX distribution D = α²/(π((n·h)²(α² − 1) + 1)²); G Smith's height-correlated
// 1/(1 + Λ(l) + Λ(v)), Λ = (√(1 + α² tan²θ) − 1)/2 (Heitz 2014), or on request the seed's
// Schlick-GGX G1(l)·G1(v), k = α/2; F eq. 2 of seed 000, exact, or on request Schlick's.
// α = roughness² (`[ggx]`), widened by far field `variance`'s unresolved slope variance σ² per
// axis as α² + 2σ² (GGX and Beckmann share their slope variance α²/2 per axis for small α).
// The environment is the sky along the mirror direction of the bumped normal (the seed's own
// choice: "perfect sky reflections" from the procedural sky), under the local reflection map;
// C_refract is the water's colour under the refraction map, as in `hu`.
// The f64 model, tested against closed forms, is ocean_core::ggx.
// Implements the shading interface (shade_above) that water.wgsl imports as
// `technique/shading`. CPU mirror: ocean-cpu/src/shaders/shading/ggx.rs.

// f32(π).
const GGX_PI: f32 = 3.1415927;

// Sums and products of three or more terms put their constant last: lavapipe's compiler moves
// a constant out of (x + c) + y as (x + y) + c (and likewise for ×), so written in that form
// both back ends round alike.

// Smith's Λ for GGX at cos θ = c (c > 0) and α².
fn ggx_lambda(c: f32, alpha2: f32) -> f32 {
    let c2 = c * c;
    let tan2 = (1.0 - c2) / c2;
    return 0.5 * (sqrt(1.0 + alpha2 * tan2) - 1.0);
}

// The Fresnel term at cos θ = c: eq. 2 or Schlick's.
fn ggx_fresnel(c: f32) -> f32 {
    if (frame.ggx.schlick_fresnel == SWITCH_ON) {
        let m = 1.0 - clamp(c, 0.0, 1.0);
        let m2 = m * m;
        let m5 = m2 * m2 * m;
        return (frame.ggx.f0 + m5) - frame.ggx.f0 * m5;
    }
    return fresnel_exact(c, frame.water.eta);
}

// The geometry term for n·l = nl, n·v = nv (both > 0).
fn ggx_geometry(nl: f32, nv: f32, alpha2: f32) -> f32 {
    if (frame.ggx.schlick_geometry == SWITCH_ON) {
        let k = 0.5 * sqrt(alpha2);
        return (nl / (nl * (1.0 - k) + k)) * (nv / (nv * (1.0 - k) + k));
    }
    return 1.0 / ((ggx_lambda(nl, alpha2) + ggx_lambda(nv, alpha2)) + 1.0);
}

// f(l, v) for unit n, view, l with n·l = nl > 0 and n·v = nv > 0.
fn ggx_brdf(n: vec3<f32>, view: vec3<f32>, l: vec3<f32>, nl: f32, nv: f32, alpha2: f32) -> f32 {
    let h = unit(l + view);
    let nh = max(dot3(n, h), 0.0);
    let vh = max(dot3(view, h), 0.0);
    // (n·h)²(α² − 1) + 1 as |n × h|² + (n·h)²α²: no cancellation near the peak, where α is
    // small, and no a + t(b − a), which lavapipe fuses as a lerp.
    let c = vec3<f32>(n.y * h.z - n.z * h.y, n.z * h.x - n.x * h.z, n.x * h.y - n.y * h.x);
    let d_den = dot3(c, c) + (nh * nh) * alpha2;
    let d = alpha2 / ((d_den * d_den) * GGX_PI);
    return ggx_fresnel(vh) * ggx_geometry(nl, nv, alpha2) * d / (4.0 * nl * nv);
}

fn shade_above(in: VertexOut, p: SurfacePoint) -> vec3<f32> {
    let n = p.n;
    let view = p.view;
    let alpha2 = frame.ggx.alpha * frame.ggx.alpha + 2.0 * p.slopes.z;
    // A bumped normal may face away from the eye by a little: n·v is held above 1e-4 so the
    // BRDF's 1/(n·v) stays finite (the ray then grazes; F → 1).
    let vn = dot3(view, n);
    let nv = max(vn, 1e-4);
    let f_env = ggx_fresnel(nv);
    // The environment along the mirror direction, kept above the horizon.
    let r = n * (2.0 * vn) - view;
    let r_up = vec3<f32>(r.x, max(r.y, 0.0), r.z);
    let sky_r = sky_radiance(sky, unit(r_up + vec3<f32>(0.0, 1e-6, 0.0)));
    let refl = textureSampleLevel(reflection_map, clamp_linear, p.screen + vec2<f32>(n.x, n.z) * frame.hu.reflection_distortion, 0.0);
    let a_refl = refl.w * frame.passes.reflection_map;
    let c_reflect = sky_r * (1.0 - a_refl) + refl.xyz * a_refl;
    let refr = textureSampleLevel(refraction_map, clamp_linear, p.screen + vec2<f32>(n.x, n.z) * frame.hu.refraction_distortion, 0.0);
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = frame.water.color * (1.0 - a_refr) + refr.xyz * a_refr;
    // The sun: Cook–Torrance with GGX, lit only from above the bumped surface.
    let l = frame.sun.direction;
    let nl = dot3(n, l);
    var c_sun = vec3<f32>(0.0, 0.0, 0.0);
    if (nl > 0.0 && frame.sun.lit > 0.0) {
        c_sun = frame.sun.radiance * (ggx_brdf(n, view, l, nl, nv, alpha2) * nl * sun_visibility(in.rel));
    }
    return c_reflect * f_env + c_refract * (1.0 - f_env) + c_sun;
}
