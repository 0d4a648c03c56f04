// Stage `composite`: the last pass of a sea drawn inside someone else's wgpu program
// (ocean-gpu's `embed`). One full-screen triangle copies the frame's picture into the
// caller's colour target and writes the depth each pixel's surface point has under the
// caller's projection (ocean-core's `composite` module: the formulas), tested against the
// caller's depth buffer, so the caller's objects and the sea hide each other correctly.
// Not part of the frame plan. CPU mirror: ocean-cpu/src/shaders/composite.rs.

// #import shared/fullscreen.wgsl

struct CompositeUniforms {
    // The caller's projection's (P22, P32, P23, P33): clip z = x·z_view + y, w = z·z_view + w.
    depth: vec4<f32>,
    // (this crate's near plane in m, the caller's far depth, 1 to invert the sRGB curve, 0).
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> composite: CompositeUniforms;
// The frame's output: the 8-bit sRGB picture, or with `radiance` the HDR frame.
@group(0) @binding(1) var frame_output: texture_2d<f32>;
// The frame's reversed-Z depth: near / distance, 0 where only the sky is.
@group(0) @binding(2) var frame_depth: texture_depth_2d;

struct VertexOut {
    @builtin(position) position: vec4<f32>,
}

struct FragmentOut {
    @location(0) color: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOut {
    var out: VertexOut;
    out.position = fullscreen_position(vertex_index);
    return out;
}

// The sRGB curve inverted (IEC 61966-2-1).
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        return c / 12.92;
    }
    return pow((c + 0.055) / 1.055, 2.4);
}

// The caller's depth of the surface point the frame's depth `d` stands for.
fn caller_depth(d: f32) -> f32 {
    if d <= 0.0 {
        return composite.params.y;
    }
    let z_view = -(composite.params.x / d);
    let z = composite.depth.x * z_view + composite.depth.y;
    let w = composite.depth.z * z_view + composite.depth.w;
    return clamp(z / w, 0.0, 1.0);
}

// Pixel centres sit at +0.5, so the integer part of the position is the frame's texel (the
// frame has the target's size). Alpha is 1: the sea is opaque.
@fragment
fn fs_main(in: VertexOut) -> FragmentOut {
    let p = vec2<i32>(in.position.xy);
    var rgb = textureLoad(frame_output, p, 0).rgb;
    if composite.params.z > 0.5 {
        rgb = vec3<f32>(srgb_to_linear(rgb.r), srgb_to_linear(rgb.g), srgb_to_linear(rgb.b));
    }
    var out: FragmentOut;
    out.color = vec4<f32>(rgb, 1.0);
    out.depth = caller_depth(textureLoad(frame_depth, p, 0));
    return out;
}
