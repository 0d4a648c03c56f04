// Stage `sky`: the environment (the frame's sky technique, imported as `technique/sky`)
// behind everything, a compute pass of one invocation per pixel storing into the HDR frame
// (the frame's depth is cleared apart). A full-screen pass is compute, not a triangle: on GPUs
// whose fragment work runs on a few units (Hopper's two graphics TPCs) a compute pass uses the
// whole chip. Each invocation computes what a fragment at the pixel centre did. Output:
// linear HDR radiance in scene units, alpha 1. CPU mirror: ocean-cpu/src/shaders/sky.rs.

// #import shared/camera.wgsl
// #import shared/sky_lut.wgsl
// #import technique/sky

@group(0) @binding(0) var<uniform> camera: CameraUniforms;
// The HDR frame. ocean-gpu makes the rgba16float variant by replacing this one declaration.
@group(0) @binding(1) var hdr_frame: texture_storage_2d<rgba32float, write>;
@group(1) @binding(0) var<uniform> sky: SkyUniforms;
// Sky `atmosphere`'s sky-view table (zeros under the other sky techniques, which ignore it).
@group(1) @binding(1) var<uniform> sky_lut: SkyLut;

// One pixel: the radiance along the ray through its centre (`id + 0.5`, exact in f32).
@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(hdr_frame);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let dir = view_ray(camera, vec2<f32>(id.xy) + vec2<f32>(0.5));
    let radiance = sky_radiance(sky, dir) + sun_disc(sky, dir);
    textureStore(hdr_frame, vec2<i32>(id.xy), vec4<f32>(radiance, 1.0));
}
