// The sun's shadow map (stage `shadow`, seed 000 §2.2) looked up at a point: shared by the
// stages that shade what the objects above the water shade (`water`, `objects`). Reads the
// importing stage's `frame` (FrameUniforms) and `shadow_map` (the plan's R32Float depth, 1
// where nothing was drawn). CPU mirror: ocean-cpu/src/shaders/shared/shadow.rs.

// Bias of the shadow-map depth comparison (depth units of the sun's ortho projection).
const SHADOW_BIAS: f32 = 0.002;

// 1 where the sun reaches the camera-relative point `rel`, 0 where the shadow map holds
// something nearer the sun.
fn sun_visibility(rel: vec3<f32>) -> f32 {
    if (frame.passes.shadow_map == SWITCH_OFF) {
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
    // A texel left at the clear value 1 has no caster: the point is lit, also beyond the map's
    // far plane (water farther from the sun than the casters' bounding sphere has s.z > 1, and
    // was shadowed wherever the map held nothing).
    if (occluder < 1.0 && occluder < s.z - SHADOW_BIAS) {
        return 0.0;
    }
    return 1.0;
}
