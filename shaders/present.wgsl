// Stage `present`: copies the frame's 8-bit output (Rgba8Unorm, already tonemapped and
// sRGB-encoded) texel for texel into a window's surface, one full-screen triangle. The target
// is a non-sRGB view (Bgra8Unorm or Rgba8Unorm), so each byte k/255 is loaded as the float
// k/255 and stored back as k: the window shows exactly the bytes `ocean render` writes.
// Not part of the frame plan: only `ocean view` runs it. CPU mirror:
// ocean-cpu/src/shaders/present.rs.

// #import shared/fullscreen.wgsl

@group(0) @binding(0) var frame_output: texture_2d<f32>;

struct VertexOut {
    @builtin(position) position: vec4<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOut {
    var out: VertexOut;
    out.position = fullscreen_position(vertex_index);
    return out;
}

// Pixel centres sit at +0.5, so the integer part of the position is the texel. Alpha is 1:
// the window is opaque whatever the frame's alpha.
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let texel = textureLoad(frame_output, vec2<i32>(in.position.xy), 0);
    return vec4<f32>(texel.rgb, 1.0);
}
