// The sea floor (`[terrain]`, ocean-core terrain.rs): its height under a point, eq. 8's depth
// y (seed 001), and the sun reaching a point under the water. Shared by `water` and
// `objects`; reads the importing stage's `frame`, `floor_map` (the relief, height in red; one
// zero texel without one), `clamp_linear` and, through shadow.wgsl, `shadow_map`.
// CPU mirror: ocean-cpu/src/shaders/shared/floor.rs.

// #import shared/shadow.wgsl

// How far the floor may stand above a point of the self-shadow march before it shadows the
// point, m: the drawn triangles and the bilinear map differ inside a texel.
const RELIEF_SHADOW_BIAS: f32 = 0.05;

// The floor's height (world y, m) under camera-relative (x, z): the plane, plus the relief map
// (bilinear, clamped to its edge).
fn floor_height(x: f32, z: f32) -> f32 {
    let f = frame.terrain.floor;
    let r = frame.terrain.relief;
    let uv = vec2<f32>(x * r.x + r.z, z * r.y + r.w);
    let relief = textureSampleLevel(floor_map, clamp_linear, uv, 0.0).x;
    return f.z + f.x * x + f.y * z + relief;
}

// The share of waves `fft` and `gerstner` kept over the floor under camera-relative (x, z):
// clamp(h·inv, 0, 1) with h the depth and inv = 1/(r·λ) of `[terrain] wave_damping` r (the
// block's top.z or top.w); 1 for inv = 0 (undamped).
fn shore_weight(x: f32, z: f32, inv: f32) -> f32 {
    if (inv == 0.0) {
        return 1.0;
    }
    return clamp(max(-floor_height(x, z), 0.0) * inv, 0.0, 1.0);
}

// The sea floor's depth below the sea plane under the camera-relative point `rel` (m, ≥ 0):
// `[terrain]`'s, or the open sea's depth of `[chiu]` without a floor.
fn floor_depth(rel: vec3<f32>) -> f32 {
    return max(-floor_height(rel.x, rel.z), 0.0);
}

// 1 where the relief does not hide the sun from the camera-relative point `rel` (under the
// water): a march towards the sun (refracted) in steps of about a texel, until the ray is
// above the highest floor or the steps run out; 0 where the floor rises above the ray.
fn relief_sun(rel: vec3<f32>) -> f32 {
    let t = frame.terrain.sun_under;
    if (frame.terrain.floor.w == 0.0 || t.w == 0.0) {
        return 1.0;
    }
    let across = sqrt(t.x * t.x + t.z * t.z);
    // A sun overhead casts no shadow on a heightfield beyond the bias.
    if (across < 1e-4) {
        return 1.0;
    }
    let step = t.xyz * (t.w / across);
    let steps = u32(frame.terrain.top.y);
    for (var i = 1u; i <= steps; i = i + 1u) {
        let q = rel + step * f32(i);
        let y = q.y + frame.view.eye_height;
        if (y > frame.terrain.top.x) {
            return 1.0;
        }
        if (floor_height(q.x, q.z) > y + RELIEF_SHADOW_BIAS) {
            return 0.0;
        }
    }
    return 1.0;
}

// 1 where the sun reaches the camera-relative point `rel` at world height `world_y`, else 0.
// Under the water: the shadow map where the refracted ray towards the sun leaves the water (the
// flat surface y = 0; the map's casters are above the water), times the relief's own shadow.
// Above the water: 1 (objects are not shadowed there; the map shades only the water).
fn sun_reaches(rel: vec3<f32>, world_y: f32) -> f32 {
    let t = frame.terrain.sun_under;
    if (world_y >= 0.0 || t.y <= 0.0) {
        return 1.0;
    }
    let surface = rel + t.xyz * (-world_y / t.y);
    return sun_visibility(surface) * relief_sun(rel);
}
