// Shading `hu` (seed 000 §5, eq. 3), the water seen from above:
//   C_water = F·C_reflect + (1 − F)·C_refract + A_shadow·C_specular,
// F and the bumped view vector from the 2D Fresnel texture (§5.1, §5.3), the reflection- and
// refraction-map lookups shifted by the bump (§5.2), the sun's Phong highlight (§5.3); far
// field `variance` swaps in the filtered F̄, sky and sun lobe of water.wgsl.
// Implements the shading interface (shade_above) that water.wgsl imports as
// `technique/shading`. CPU mirror: ocean-cpu/src/shaders/shading/hu.rs.

fn shade_above(in: VertexOut, p: SurfacePoint) -> vec3<f32> {
    let n = p.n;
    let view = p.view;
    let variance = p.slopes.z;
    // (du, dv) of §5: the horizontal components of the bumped unit normal.
    let du = n.x;
    let dv = n.z;
    let st = fresnel_st(p.u_bumped);
    let fres = textureSampleLevel(fresnel_above, clamp_linear, st, 0.0);
    var f = fres.w;
    if (variance > 0.0) {
        f = fresnel_filtered(p.u_bumped, variance);
    }
    // Reflection (§4.2, §5.2): sky along the bumped reflection direction, mirrored objects
    // from the reflection map shifted by the bump, over it by coverage.
    let vn = dot3(view, n);
    var r = n * (2.0 * vn) - view;
    r.y = max(r.y, 0.0);
    var sky_r = sky_radiance(sky, unit(r + vec3<f32>(0.0, 1e-6, 0.0)));
    if (variance > 0.0) {
        sky_r = sky_filtered(view, p.slopes, variance);
    }
    let refl = textureSampleLevel(reflection_map, clamp_linear, p.screen + vec2<f32>(du, dv) * frame.hu.reflection_distortion, 0.0);
    let a_refl = refl.w * frame.passes.reflection_map;
    let c_reflect = sky_r * (1.0 - a_refl) + refl.xyz * a_refl;
    // Refraction (§5.2, eq. 4): the fogged objects under the water, over the water volume
    // colour.
    let refr = textureSampleLevel(refraction_map, clamp_linear, p.screen + vec2<f32>(du, dv) * frame.hu.refraction_distortion, 0.0);
    let a_refr = refr.w * frame.passes.refraction_map;
    let c_refract = frame.water.color * (1.0 - a_refr) + refr.xyz * a_refr;
    // Specular (§5.3): (V·R)^s with V the bumped view vector stored in the texture's RGB
    // (local z = world y) and R the sun's reflection about (0, 1, 0); s is whole.
    let vb = vec3<f32>(fres.x, fres.z, fres.y);
    let r_sun = vec3<f32>(-frame.sun.direction.x, frame.sun.direction.y, -frame.sun.direction.z);
    let cos_spec = max(dot3(vb, r_sun), 0.0);
    var lobe = pow_int(cos_spec, u32(frame.hu.phong_exponent));
    if (variance > 0.0) {
        lobe = sun_lobe_filtered(p.u_bumped, variance);
    }
    let spec = frame.sun.radiance * (lobe * frame.sun.lit);
    let shadow = sun_visibility(in.rel);
    return c_reflect * f + c_refract * (1.0 - f) + spec * shadow;
}
