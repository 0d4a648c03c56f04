// Shading `coastal` (seed 004, "Optical effects"), the water seen from above:
//   C = (F·C_reflect + (1 − F)·C_refract)·(1 − d) + C_dull·d + C_specular,
// F Schlick's F₀ + (1 − F₀)(1 − v·n)⁵ (the seed's cheap Fresnel) or, with `[coastal] fresnel =
// "exact"`, eq. 2 from the Fresnel texture; the reflection and refraction maps looked up at the
// screen point shifted by the bumped normal (the seed's `TexCoords − newNormal·0.2`); the
// sun's Blinn–Phong highlight (n·h)^s (the seed's exponent 30); and the seed's dull colour by
// the wave phase, d = saturate(k·(1 + q⁴)) with q = 2φ ∈ [−1, 1] the coastal waves' phase in
// half turns (0 under the other waves techniques), lit by the sky and the sun as an albedo.
// Implements the shading interface (shade_above) that water.wgsl imports as
// `technique/shading`. CPU mirror: ocean-cpu/src/shaders/shading/coastal.rs.

// 1/π: a Lambertian albedo's radiance per unit of irradiance.
const COASTAL_INV_PI: f32 = 0.31830987;

fn shade_above(in: VertexOut, p: SurfacePoint) -> vec3<f32> {
    let n = p.n;
    let view = p.view;
    let s = frame.coastal_shading;
    let cos_v = max(dot3(view, n), 0.0);
    var f = 0.0;
    if (s.schlick == SWITCH_ON) {
        let m = 1.0 - cos_v;
        let m2 = m * m;
        f = s.f0 + (1.0 - s.f0) * (m2 * m2 * m);
    } else {
        f = textureSampleLevel(fresnel_above, clamp_linear, fresnel_st(p.u_bumped), 0.0).w;
    }
    var r = n * (2.0 * cos_v) - view;
    r.y = max(r.y, 0.0);
    let sky_r = sky_radiance(sky, unit(r + vec3<f32>(0.0, 1e-6, 0.0)));
    let at = p.screen - vec2<f32>(n.x, n.z) * s.distortion;
    let refl = textureSampleLevel(reflection_map, clamp_linear, at, 0.0);
    let a_refl = refl.w * frame.passes.reflection_map;
    let c_reflect = sky_r * (1.0 - a_refl) + refl.xyz * a_refl;
    let refr = textureSampleLevel(refraction_map, clamp_linear, at, 0.0);
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = frame.water.color * (1.0 - a_refr) + refr.xyz * a_refr;
    let l = frame.sun.direction;
    let shadow = sun_visibility(in.rel) * frame.sun.lit;
    let lobe = pow_int(max(dot3(n, unit(l + view)), 0.0), u32(s.shininess));
    let q = 2.0 * p.coastal.x;
    let q2 = q * q;
    // Where the pixel spans the waves, q⁴ fades to its mean over a period, 1/5.
    var q4 = q2 * q2;
    if (p.coastal.z < 1.0) {
        q4 = 0.2 + (q4 - 0.2) * p.coastal.z;
    }
    let d = clamp(s.dull_factor * (1.0 + q4), 0.0, 1.0);
    let light = frame.ambient.sky + frame.sun.radiance * (max(dot3(n, l), 0.0) * shadow * COASTAL_INV_PI);
    let c = (c_reflect * f + c_refract * (1.0 - f)) * (1.0 - d) + s.dull_color * light * d;
    return c + frame.sun.radiance * (lobe * shadow);
}
