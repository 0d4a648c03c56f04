// The uniforms of the `objects`, `shadow` and `water` stages: ocean-core's
// `frame::FrameUniforms` (same names, same layout; tests/wgsl.rs compares them).
struct FrameUniforms {
    view_proj: mat4x4<f32>,
    sun_view_proj: mat4x4<f32>,
    eye: vec4<f32>,
    patch_origin: vec4<f32>,
    mesh_offset: vec4<f32>,
    patch_scale: vec4<f32>,
    sun_dir: vec4<f32>,
    sun_radiance: vec4<f32>,
    water_color: vec4<f32>,
    water_params: vec4<f32>,
    viewport: vec4<f32>,
    passes: vec4<f32>,
    sky_ambient: vec4<f32>,
}

// m · (p, 1), written out so that the order of operations is fixed (the CPU mirror,
// ocean-cpu/src/shaders/common.rs, sums the columns in the same order).
fn transform_point(m: mat4x4<f32>, p: vec3<f32>) -> vec4<f32> {
    return m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3];
}

// v / |v|, with the dot product written out (WGSL's normalize() may use an inverse square
// root whose rounding is the implementation's).
fn unit(v: vec3<f32>) -> vec3<f32> {
    return v / sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

fn dot3(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
