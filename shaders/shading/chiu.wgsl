// Shading `chiu` (Chiu & Chang, seed 001 §3.5), the water seen from above:
//   eq. 2  C = F(θ)·C_reflect + (1 − F(θ))·C_refract, F the exact eq. 2 of seed 000 at the
//          angle θ between the eye and the bumped normal (shared/optics.wgsl);
//   eq. 3  C_reflect = C_sky + C_sun + C_localreflect; the sky along the bumped reflection
//          direction is the sky technique's (eq. 4's clouds come with `preetham_clouds`); the
//          local reflection map covers the sky where it holds an object (its alpha), rather
//          than adding to it, so a mirrored object does not show the sky through it;
//   eq. 5  C_sun = C_suncolor·(R·L)^(shininess·z), z the point's view depth (the paper's
//          post-perspective z, which for a perspective projection is the view depth less the
//          near plane): the glitter narrows with distance; shadowed by the shadow map;
//   eq. 6  the local reflection map at screen + ζ·n_xz/z;
//   eq. 7  C_refract: the refraction map (objects and the floor under the water, fogged by
//          e^(−K·dist) towards eq. 8's colour, objects.wgsl) over eq. 8's colour where it
//          holds nothing, shifted like eq. 6;
//   eq. 8  C_watcolor = (0.30, 0.73, 0.63)^(k_d·y) under the downwelling light, y the sea
//          floor's depth under the point (shared/optics.wgsl).
// Far field `variance`'s unresolved slopes are not used (the paper point-samples).
// Implements the shading interface (shade_above) that water.wgsl imports as
// `technique/shading`. CPU mirror: ocean-cpu/src/shaders/shading/chiu.rs.

// Eq. 5's exponent is clamped to [1, CHIU_MAX_EXPONENT] (x^65535 underflows for x < 0.9989,
// 0.05° from the peak: a narrower lobe is below a pixel).
const CHIU_MAX_EXPONENT: f32 = 65535.0;

// x^e for x ∈ [0, 1] and e ≥ 1 by multiplications only: the whole powers either side of e
// blended linearly, so the lobe changes continuously with e and both back ends round alike.
fn pow_blend(x: f32, e: f32) -> f32 {
    let n = floor(e);
    let lo = pow_int(x, u32(n));
    return lo + (lo * x - lo) * (e - n);
}

fn shade_above(in: VertexOut, p: SurfacePoint) -> vec3<f32> {
    let n = p.n;
    let view = p.view;
    // The view depth z: the clip-space w of the point.
    let z = max(transform_point(frame.view.view_proj, in.rel).w, 1e-3);
    // Eq. 2's F(θ).
    let vn = dot3(view, n);
    let f = fresnel_exact(vn, frame.water.eta);
    // Eq. 3, 4: the sky along the bumped reflection direction.
    let r = n * (2.0 * vn) - view;
    let r_up = vec3<f32>(r.x, max(r.y, 0.0), r.z);
    let c_sky = sky_radiance(sky, unit(r_up + vec3<f32>(0.0, 1e-6, 0.0)));
    // Eq. 6: the maps' shift by the bump, smaller with depth.
    let shift = vec2<f32>(n.x, n.z) * (frame.chiu.zeta_m / z);
    let refl = textureSampleLevel(reflection_map, clamp_linear, p.screen + shift, 0.0);
    let a_refl = refl.w * frame.passes.reflection_map;
    // Eq. 5: the sun's Phong lobe about the bumped reflection direction.
    let cos_sun = clamp(dot3(unit(r), frame.sun.direction), 0.0, 1.0);
    let e = clamp(frame.chiu.shininess_per_m * z, 1.0, CHIU_MAX_EXPONENT);
    let c_sun = frame.sun.radiance * (pow_blend(cos_sun, e) * frame.sun.lit * sun_visibility(in.rel));
    let c_reflect = c_sky * (1.0 - a_refl) + refl.xyz * a_refl + c_sun;
    // Eq. 7, 8.
    let refr = textureSampleLevel(refraction_map, clamp_linear, p.screen + shift, 0.0);
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = water_volume_colour(floor_depth(in.rel)) * (1.0 - a_refr) + refr.xyz * a_refr;
    return c_reflect * f + c_refract * (1.0 - f);
}
