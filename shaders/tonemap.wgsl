// Stage `tonemap`: HDR linear frame -> 8-bit sRGB, a compute pass of one invocation per pixel
// storing into an Rgba8Unorm storage texture. A full-screen pass is compute, not a triangle:
// on GPUs whose fragment work runs on a few units (Hopper's two graphics TPCs) a compute pass
// uses the whole chip (docs/design.md, "One frame, two back ends"). Each invocation
// computes what a fragment at the pixel centre did, so the bytes are the same. The steps,
// their order and the reasons: ocean_core::tonemap.
// CPU mirror: ocean-cpu/src/shaders/tonemap.rs.

struct TonemapUniforms {
    exposure: f32,
    // 0: ACES (Narkowicz), 1: Hable (Uncharted 2).
    curve: u32,
    // The vignette's strength s: x * max(1 - s r^2, 0).
    vignette: f32,
    // 1 / (c.x^2 + c.y^2): r^2 per squared pixel from the centre.
    inv_corner2: f32,
    // The image's centre, pixels.
    center: vec2<f32>,
    // Post `bloom`: level 0 of the up chain is added x this (strength / levels), else 0.
    bloom_scale: f32,
    pad1: f32,
}

@group(0) @binding(0) var<uniform> tonemap: TonemapUniforms;
@group(0) @binding(1) var hdr_frame: texture_2d<f32>;
// Post `bloom`: level 0 of the up chain, half the frame's size (a 1x1 zero texture without).
@group(0) @binding(2) var bloom: texture_2d<f32>;
// The 8-bit picture.
@group(0) @binding(3) var ldr: texture_storage_2d<rgba8unorm, write>;

// Largest finite f16 (ocean_core::tonemap::HDR_MAX).
const HDR_MAX: f32 = 65504.0;
// 1 / 2.4, the exponent of the sRGB OETF, as the nearest f32.
const SRGB_INV_GAMMA: f32 = 0.41666666;

// Hable's curve rearranged over one denominator, g(x) = x (P x + Q) / (x (R x + S) + T), and
// 1 / g(W): ocean_core::tonemap's HABLE_P ... HABLE_T and HABLE_WHITE_SCALE, from his
// published A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30, W = 11.2 (f64, rounded
// once to f32; tests/post.rs holds these literals to ocean-core's constants).
const HABLE_P: f32 = 0.042;
const HABLE_Q: f32 = 0.005;
const HABLE_R: f32 = 0.045;
const HABLE_S: f32 = 0.15;
const HABLE_T: f32 = 0.018;
const HABLE_WHITE_SCALE: f32 = 1.3790642;

// ACES filmic curve, K. Narkowicz's fit (2016): x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14).
fn aces_narkowicz(x: vec3<f32>) -> vec3<f32> {
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

// Hable's filmic curve (Uncharted 2), normalised so that the white point W maps to 1.
fn hable(x: vec3<f32>) -> vec3<f32> {
    return (x * (HABLE_P * x + HABLE_Q)) / (x * (HABLE_R * x + HABLE_S) + HABLE_T) * HABLE_WHITE_SCALE;
}

// The curve `tonemap.curve` selects (a uniform branch).
fn tone_curve(x: vec3<f32>) -> vec3<f32> {
    if (tonemap.curve == 1u) {
        return hable(x);
    }
    return aces_narkowicz(x);
}

// The vignette's factor at a pixel centre: max(1 - s r^2, 0), r = 0 at the centre, 1 at the
// corner.
fn vignette_factor(p: vec2<f32>) -> f32 {
    let d = p - tonemap.center;
    let r2 = (d.x * d.x + d.y * d.y) * tonemap.inv_corner2;
    return max(1.0 - tonemap.vignette * r2, 0.0);
}

// The bloom at pixel p: the up chain's level 0 upsampled 2x as the chain itself upsamples
// (ocean_core::bloom step 3; shaders/bloom.wgsl's upsample_at).
fn bloom_at(p: vec2<i32>) -> vec3<f32> {
    let size = vec2<i32>(textureDimensions(bloom, 0));
    let m = p >> vec2<u32>(1u);
    let far = select(m - 1, m + 1, (p & vec2<i32>(1)) == vec2<i32>(1));
    let hi = size - 1;
    let n = clamp(m, vec2<i32>(0), hi);
    let f = clamp(far, vec2<i32>(0), hi);
    let a = 0.75 * textureLoad(bloom, n, 0).rgb + 0.25 * textureLoad(bloom, vec2<i32>(f.x, n.y), 0).rgb;
    let b = 0.75 * textureLoad(bloom, vec2<i32>(n.x, f.y), 0).rgb + 0.25 * textureLoad(bloom, f, 0).rgb;
    return 0.75 * a + 0.25 * b;
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

// One pixel: what a fragment at its centre (`centre` = texel + 0.5, exact in f32) stores.
@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(ldr);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let texel = vec2<i32>(id.xy);
    let centre = vec2<f32>(id.xy) + vec2<f32>(0.5);
    let hdr = textureLoad(hdr_frame, texel, 0).rgb;
    let exposed = hdr * tonemap.exposure;
    let sanitised = min(max(exposed, vec3<f32>(0.0)), vec3<f32>(HDR_MAX));
    let bloomed = sanitised + tonemap.bloom_scale * bloom_at(texel);
    let x = bloomed * vignette_factor(centre);
    let mapped = clamp(tone_curve(x), vec3<f32>(0.0), vec3<f32>(1.0));
    let encoded = srgb_oetf(mapped);
    textureStore(ldr, texel, vec4<f32>(quantize_unorm8(encoded), 1.0));
}
