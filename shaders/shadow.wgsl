// Stage `shadow`: the depth of the objects seen from the sun (seed 000 §2.2), an
// orthographic view along the sun's direction; depth 0 at the sun's side, `Less` test.
// The water pass compares a point's depth with it to attenuate the sun's specular.
// CPU mirror: crates/ocean-cpu/src/shaders/shadow.rs.

// #import shared/frame.wgsl

@group(0) @binding(0) var<uniform> frame: FrameUniforms;

struct ShadowOut {
    @builtin(position) clip: vec4<f32>,
}

@vertex
fn vs_main(@location(0) position: vec3<f32>) -> ShadowOut {
    var out: ShadowOut;
    out.clip = transform_point(frame.sun.shadow_view_proj, position);
    return out;
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(frag.z, 0.0, 0.0, 0.0);
}
