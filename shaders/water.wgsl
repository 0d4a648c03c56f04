// Stage `water`: the final pass of seed 000 (§2.3, §5, eq. 3),
//   C_water = F·C_reflect + (1 − F)·C_refract + A_shadow·C_specular,
// on the near/far patch mesh (§3): the vertex shader displaces the mesh by the displacement
// map (§5.4; the weight w forces the near patch's boundary and the far patch flat), the
// fragment shader bumps the normal with the bump map (§5), looks the Fresnel term and the
// bumped view vector up in the 2D Fresnel texture (§5.1, §5.3), shifts the reflection- and
// refraction-map lookups by the bump (§5.2), and adds the sun's Phong highlight attenuated
// by the shadow map (§5.3). The environment (the sky technique's radiance, imported as
// `technique/sky`) is reflected analytically along the bumped reflection direction; the
// reflection map adds the mirrored objects over it by coverage.
// Seen from below (camera under the water) the surface reflects the water volume and
// transmits the sky through Snell's window, with F for η⁻¹ (total internal reflection).
// CPU mirror: crates/ocean-cpu/src/shaders/water.rs.

// #import shared/frame.wgsl
// #import technique/sky

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
// (disp_x, height, disp_z, jacobian) of the displacement map.
@group(0) @binding(1) var displacement: texture_2d<f32>;
// (slope_x, slope_z, 0, 0) of the displacement map.
@group(0) @binding(2) var displacement_slopes: texture_2d<f32>;
// (slope_x, slope_z, height, jacobian) of the bump map.
@group(0) @binding(3) var bump: texture_2d<f32>;
// The 2D Fresnel textures for η (seen from above) and η⁻¹ (from below): RGB = local view
// vector, A = F.
@group(0) @binding(4) var fresnel_above: texture_2d<f32>;
@group(0) @binding(5) var fresnel_below: texture_2d<f32>;
@group(0) @binding(6) var reflection_map: texture_2d<f32>;
@group(0) @binding(7) var refraction_map: texture_2d<f32>;
@group(0) @binding(8) var shadow_map: texture_2d<f32>;
@group(0) @binding(9) var wrap_linear: sampler;
@group(0) @binding(10) var clamp_linear: sampler;
// The environment the water reflects: the frame's sky technique (its interface: SkyUniforms,
// sky_radiance), a resource of the plan that the water reads.
@group(1) @binding(0) var<uniform> sky: SkyUniforms;

struct WaterVertex {
    // Position on the sea plane relative to the mesh's reference point c, (x, z), m
    // (ocean-core's geometry::WaterVertex).
    @location(0) pos: vec2<f32>,
    // Displacement weight: 1 inside the near patch, 0 on its boundary and the far patch.
    @location(1) weight: f32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    // Camera-relative position of the displaced surface point.
    @location(0) rel: vec3<f32>,
    @location(1) uv_d: vec2<f32>,
    @location(2) uv_b: vec2<f32>,
    @location(3) weight: f32,
}

// Bias of the shadow-map depth comparison (depth units of the sun's ortho projection).
const SHADOW_BIAS: f32 = 0.002;

// x^n for a whole n by binary exponentiation: multiplications only, so every implementation
// rounds alike. (pow() is exp2(n·log2(x)) with the implementation's approximations: on
// lavapipe x^400 came out up to 4e-5 relative off the correctly rounded value, enough to
// move the sun's glitter beyond the CPU/GPU float tolerance.)
fn pow_int(x: f32, n: u32) -> f32 {
    var result = 1.0;
    var base = x;
    var e = n;
    loop {
        if ((e & 1u) == 1u) {
            result = result * base;
        }
        e = e >> 1u;
        if (e == 0u) {
            break;
        }
        base = base * base;
    }
    return result;
}

@vertex
fn vs_main(v: WaterVertex) -> VertexOut {
    // Texel (i, j) of an N×N map holds the sample at (i, j)·L/N: u = x/L + ½/N.
    let uv_d = (v.pos + frame.tiling.displacement_origin) * frame.tiling.inv_displacement_size + frame.tiling.displacement_half_texel;
    let uv_b = (v.pos + frame.tiling.bump_origin) * frame.tiling.inv_bump_size + frame.tiling.bump_half_texel;
    let d = textureSampleLevel(displacement, wrap_linear, uv_d, 0.0) * (v.weight * frame.passes.waves);
    // Camera-relative: c − eye (formed in f64 on the CPU) plus the vertex's offset from c.
    let plane = v.pos + frame.tiling.mesh_offset;
    let rel = vec3<f32>(plane.x + d.x, d.y - frame.view.eye_height, plane.y + d.z);
    var out: VertexOut;
    out.clip = transform_point(frame.view.view_proj, rel);
    out.rel = rel;
    out.uv_d = uv_d;
    out.uv_b = uv_b;
    out.weight = v.weight;
    return out;
}

// 1 where the sun reaches the point, 0 where the shadow map holds something nearer the sun.
fn sun_visibility(rel: vec3<f32>) -> f32 {
    if (frame.passes.shadow_map == 0.0) {
        return 1.0;
    }
    let s = transform_point(frame.sun.shadow_view_proj, rel);
    let u = s.x * 0.5 + 0.5;
    let v = 0.5 - s.y * 0.5;
    if (u < 0.0 || u >= 1.0 || v < 0.0 || v >= 1.0) {
        return 1.0;
    }
    let dims = vec2<i32>(textureDimensions(shadow_map));
    // u < 1 can still round to u·size = size: clamp to the last texel.
    let texel = vec2<i32>(
        min(i32(floor(u * f32(dims.x))), dims.x - 1),
        min(i32(floor(v * f32(dims.y))), dims.y - 1),
    );
    let occluder = textureLoad(shadow_map, texel, 0).x;
    if (occluder < s.z - SHADOW_BIAS) {
        return 0.0;
    }
    return 1.0;
}

// Bumped normal (§5): the slopes of the displacement map (faded with w like the displacement
// itself) plus those of the bump map.
fn bumped_normal(in: VertexOut) -> vec3<f32> {
    let sd = textureSample(displacement_slopes, wrap_linear, in.uv_d).xy * (in.weight * frame.passes.waves);
    let sb = textureSample(bump, wrap_linear, in.uv_b).xy * frame.passes.waves;
    return unit(vec3<f32>(-(sd.x + sb.x), 1.0, -(sd.y + sb.y)));
}

// √2 of the elliptical grid mapping's inverse.
const SQRT2: f32 = 1.4142135623730951;

// One axis of the disc-to-square map of the grazing mapping (ocean-core
// tables::grazing_square), u = ½ sqrt(2 + a² − b² + 2√2 a) − ½ sqrt(2 + a² − b² − 2√2 a),
// with each root's argument factorised, (√2 ± a)² − b² = (√2 ± a − b)(√2 ± a + b): where it
// vanishes (the corners' images on the rim) the factors are accurate and the expanded sum is
// not. max(0) guards round-off.
fn grazing_square_axis(a: f32, b: f32) -> f32 {
    let plus = (SQRT2 + a - b) * (SQRT2 + a + b);
    let minus = (SQRT2 - a - b) * (SQRT2 - a + b);
    return 0.5 * (sqrt(max(plus, 0.0)) - sqrt(max(minus, 0.0)));
}

// Fresnel bump mapping (§5.1, Fig. 4): the view vector bumped by (−du, −dv), (du, dv) the
// horizontal components of the bumped unit normal, looked up in the grazing-mapped texture
// (the plan's `fresnel_mapping`): z = sqrt(1 − r²), the disc point d = (x, y)/sqrt(1 + z)
// (|d|² = 1 − z), a bumped vector beyond the rim (r > 1) put on the rim at its azimuth by
// max(…, r), then d to the square u ∈ [−1, 1]² and s = a·u + ½.
fn fresnel_st(view: vec3<f32>, n: vec3<f32>) -> vec2<f32> {
    let x = view.x - n.x;
    let y = view.z - n.z;
    let r2 = x * x + y * y;
    let z = sqrt(max(1.0 - r2, 0.0));
    let d = vec2<f32>(x, y) / max(sqrt(1.0 + z), sqrt(r2));
    let u = vec2<f32>(grazing_square_axis(d.x, d.y), grazing_square_axis(d.y, d.x));
    return u * frame.hu.fresnel_scale + 0.5;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let n = bumped_normal(in);
    // (du, dv) of §5: the horizontal components of the bumped unit normal.
    let du = n.x;
    let dv = n.z;
    let view = unit(-in.rel);
    // In the fragment stage `clip` is the fragment's position: (x + 0.5, y + 0.5, depth, 1/w).
    let screen = in.clip.xy * frame.view.inv_viewport_size;
    if (view.y >= 0.0) {
        let st = fresnel_st(view, n);
        let fres = textureSample(fresnel_above, clamp_linear, st);
        let f = fres.w;
        // Reflection (§4.2, §5.2): sky along the bumped reflection direction, mirrored
        // objects from the reflection map shifted by the bump, over it by coverage.
        let vn = dot3(view, n);
        var r = n * (2.0 * vn) - view;
        r.y = max(r.y, 0.0);
        let sky_r = sky_radiance(sky, unit(r + vec3<f32>(0.0, 1e-6, 0.0)));
        let refl = textureSample(reflection_map, clamp_linear, screen + vec2<f32>(du, dv) * frame.hu.reflection_distortion);
        let a_refl = refl.w * frame.passes.reflection_map;
        let c_reflect = sky_r * (1.0 - a_refl) + refl.xyz * a_refl;
        // Refraction (§5.2, eq. 4): the fogged objects under the water, over the water
        // volume colour.
        let refr = textureSample(refraction_map, clamp_linear, screen + vec2<f32>(du, dv) * frame.hu.refraction_distortion);
        let a_refr = refr.w * frame.passes.refraction_map;
        let c_refract = frame.water.color * (1.0 - a_refr) + refr.xyz * a_refr;
        // Specular (§5.3): (V·R)^s with V the bumped view vector stored in the texture's RGB
        // (local z = world y) and R the sun's reflection about (0, 1, 0); s is whole.
        let vb = vec3<f32>(fres.x, fres.z, fres.y);
        let r_sun = vec3<f32>(-frame.sun.direction.x, frame.sun.direction.y, -frame.sun.direction.z);
        let cos_spec = max(dot3(vb, r_sun), 0.0);
        let spec = frame.sun.radiance * (pow_int(cos_spec, u32(frame.hu.phong_exponent)) * frame.sun.lit);
        let shadow = sun_visibility(in.rel);
        let c = c_reflect * f + c_refract * (1.0 - f) + spec * shadow;
        return vec4<f32>(c, 1.0);
    }
    // From below: the normal facing the eye is (n.x, −n.y, n.z), its horizontal part again
    // (du, dv); F for η⁻¹ (1 beyond the critical angle: total internal reflection).
    let st = fresnel_st(view, n);
    let f = textureSample(fresnel_below, clamp_linear, st).w;
    // Snell's window: the ray i from the eye meets the surface from below (the normal facing
    // it is −n) and leaves into the air, η_i/η_t = η (water to air):
    // t = η i + (η cos θ_i − cos θ_t)(−n), cos θ_i = i·n, cos² θ_t = 1 − η² sin² θ_i.
    let eta = frame.water.eta;
    let i = -view;
    let cos_i = dot3(i, n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    var sky_t = vec3<f32>(0.0, 0.0, 0.0);
    if (k > 0.0) {
        let t = i * eta + n * (sqrt(k) - eta * cos_i);
        sky_t = sky_radiance(sky, unit(vec3<f32>(t.x, max(t.y, 0.0) + 1e-6, t.z)));
    }
    let c = frame.water.color * f + sky_t * (1.0 - f);
    return vec4<f32>(c, 1.0);
}
