// Stage `sky`: the environment (the frame's sky technique, imported as `technique/sky`;
// `preetham` for every system built so far) behind everything, drawn with one
// full-screen triangle at the far plane (reversed Z: z = 0). Output: linear HDR radiance in
// scene units, alpha 1. CPU mirror: ocean-cpu/src/shaders/sky.rs.

// #import shared/camera.wgsl
// #import shared/fullscreen.wgsl
// #import shared/sky_lut.wgsl
// #import technique/sky

@group(0) @binding(0) var<uniform> camera: CameraUniforms;
@group(1) @binding(0) var<uniform> sky: SkyUniforms;
// Sky `atmosphere`'s sky-view table (zeros under the other sky techniques, which ignore it).
@group(1) @binding(1) var<uniform> sky_lut: SkyLut;

struct VertexOut {
    @builtin(position) position: vec4<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOut {
    var out: VertexOut;
    out.position = fullscreen_position(vertex_index);
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let dir = view_ray(camera, in.position.xy);
    let radiance = sky_radiance(sky, dir) + sun_disc(sky, dir);
    return vec4<f32>(radiance, 1.0);
}
