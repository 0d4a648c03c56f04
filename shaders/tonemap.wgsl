// Stage `tonemap`: HDR linear frame -> 8-bit sRGB, one full-screen triangle, written to an
// Rgba8Unorm target. The steps, their order and the reasons: ocean_core::tonemap.
// CPU mirror: ocean-cpu/src/shaders/tonemap.rs.

// #import shared/fullscreen.wgsl

struct TonemapUniforms {
    exposure: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
}

@group(0) @binding(0) var<uniform> tonemap: TonemapUniforms;
@group(0) @binding(1) var hdr_frame: texture_2d<f32>;

// Largest finite f16 (ocean_core::tonemap::HDR_MAX).
const HDR_MAX: f32 = 65504.0;
// 1 / 2.4, the exponent of the sRGB OETF, as the nearest f32.
const SRGB_INV_GAMMA: f32 = 0.41666666;

struct VertexOut {
    @builtin(position) position: vec4<f32>,
}

// ACES filmic curve, K. Narkowicz's fit (2016): x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14).
fn aces_narkowicz(x: vec3<f32>) -> vec3<f32> {
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

// sRGB OETF, IEC 61966-2-1: 12.92 c for c <= 0.0031308, else 1.055 c^(1/2.4) - 0.055.
fn srgb_oetf(c: vec3<f32>) -> vec3<f32> {
    let lo = 12.92 * c;
    let hi = 1.055 * pow(c, vec3<f32>(SRGB_INV_GAMMA)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

// Round to the nearest multiple of 1/255, ties to even: round(v * 255) / 255 (WGSL's round
// rounds halves to even, exactly).
fn quantize_unorm8(v: vec3<f32>) -> vec3<f32> {
    return round(v * 255.0) / 255.0;
}

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOut {
    var out: VertexOut;
    out.position = fullscreen_position(vertex_index);
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let texel = vec2<i32>(in.position.xy);
    let hdr = textureLoad(hdr_frame, texel, 0).rgb;
    let exposed = hdr * tonemap.exposure;
    let x = min(max(exposed, vec3<f32>(0.0)), vec3<f32>(HDR_MAX));
    let mapped = clamp(aces_narkowicz(x), vec3<f32>(0.0), vec3<f32>(1.0));
    let encoded = srgb_oetf(mapped);
    return vec4<f32>(quantize_unorm8(encoded), 1.0);
}
