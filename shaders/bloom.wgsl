// Stage `bloom` (post technique `bloom`): the bright pass of the HDR frame and its blur
// pyramid, ocean_core::bloom (the steps, the filters, why). Entry `bright_down` writes level 0
// of the down chain from the frame, `downsample` each level after it from the one before,
// `upsample` level k of the up chain as down[k] + the 2x upsample of up[k + 1]. One dispatch
// per level, each reading a one-level view and writing another.
// CPU mirror: crates/ocean-cpu/src/shaders/bloom.rs.

struct BloomUniforms {
    // Size of the level written, texels.
    width: u32,
    height: u32,
    // Size of the level (or frame) read.
    src_width: u32,
    src_height: u32,
    // The frame's exposure and the bright pass's threshold (exposed units): `bright_down`.
    exposure: f32,
    threshold: f32,
    // `upsample`: the largest value the chain's format holds (f16 65504, f32 its max).
    store_max: f32,
    pad1: f32,
}

@group(0) @binding(0) var<uniform> params: BloomUniforms;
// `bright_down`: the HDR frame; `downsample`: the level below; `upsample`: up[k + 1].
@group(0) @binding(1) var src: texture_2d<f32>;
// The chains' format: ocean-gpu makes an `rgba16float` variant of this line for frame format
// `rgba16float` (ocean_core::frame_format), the only difference between the two modules.
@group(0) @binding(2) var dst: texture_storage_2d<rgba32float, write>;
// `upsample`: down[k], the detail the coarser sum is added to (unused by the others).
@group(0) @binding(3) var detail: texture_2d<f32>;

// Largest finite f16 (ocean_core::tonemap::HDR_MAX), the tonemap's clamp.
const BLOOM_HDR_MAX: f32 = 65504.0;

// Texel (x, y) of `src`, clamped to its edge (the downsample reaches one texel beyond it).
fn tap(x: i32, y: i32) -> vec3<f32> {
    let hi = vec2<i32>(i32(params.src_width) - 1, i32(params.src_height) - 1);
    return textureLoad(src, clamp(vec2<i32>(x, y), vec2<i32>(0), hi), 0).rgb;
}

// The bright pass: what exceeds the threshold of the sanitised exposed value (NaN -> 0, as
// the tonemap does).
fn bright(c: vec3<f32>) -> vec3<f32> {
    let x = min(max(c * params.exposure, vec3<f32>(0.0)), vec3<f32>(BLOOM_HDR_MAX));
    return max(x - params.threshold, vec3<f32>(0.0));
}

// A tap of the level read: through the bright pass when `bright_pass` is set.
fn source(x: i32, y: i32, bright_pass: bool) -> vec3<f32> {
    let c = tap(x, y);
    if (bright_pass) {
        return bright(c);
    }
    return c;
}

// The (1, 3, 3, 1)/8 tent over taps 2i - 1 .. 2i + 2 of row y, summed left to right.
fn down_row(i: i32, y: i32, bright_pass: bool) -> vec3<f32> {
    let x = 2 * i - 1;
    return ((0.125 * source(x, y, bright_pass) + 0.375 * source(x + 1, y, bright_pass))
        + 0.375 * source(x + 2, y, bright_pass)) + 0.125 * source(x + 3, y, bright_pass);
}

// Texel id of the level below: the tent over rows 2j - 1 .. 2j + 2 of the rows' tents.
fn down(id: vec2<u32>, bright_pass: bool) -> vec3<f32> {
    let i = i32(id.x);
    let y = 2 * i32(id.y) - 1;
    return ((0.125 * down_row(i, y, bright_pass) + 0.375 * down_row(i, y + 1, bright_pass))
        + 0.375 * down_row(i, y + 2, bright_pass)) + 0.125 * down_row(i, y + 3, bright_pass);
}

@compute @workgroup_size(8, 8, 1)
fn bright_down(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.width || id.y >= params.height) {
        return;
    }
    textureStore(dst, vec2<i32>(id.xy), vec4<f32>(down(id.xy, true), 1.0));
}

@compute @workgroup_size(8, 8, 1)
fn downsample(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.width || id.y >= params.height) {
        return;
    }
    textureStore(dst, vec2<i32>(id.xy), vec4<f32>(down(id.xy, false), 1.0));
}

// The 2x bilinear upsample of `coarse` (size `size`) at fine texel p: ocean_core::bloom step
// 3 (coarse m with 3/4 and its neighbour towards p with 1/4, rows first, clamped to the
// level). The tonemap's composite is the same function (shaders/tonemap.wgsl).
fn upsample_at(p: vec2<i32>, size: vec2<i32>) -> vec3<f32> {
    let m = p >> vec2<u32>(1u);
    let far = select(m - 1, m + 1, (p & vec2<i32>(1)) == vec2<i32>(1));
    let hi = size - 1;
    let n = clamp(m, vec2<i32>(0), hi);
    let f = clamp(far, vec2<i32>(0), hi);
    let a = 0.75 * textureLoad(src, n, 0).rgb + 0.25 * textureLoad(src, vec2<i32>(f.x, n.y), 0).rgb;
    let b = 0.75 * textureLoad(src, vec2<i32>(n.x, f.y), 0).rgb + 0.25 * textureLoad(src, f, 0).rgb;
    return 0.75 * a + 0.25 * b;
}

@compute @workgroup_size(8, 8, 1)
fn upsample(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.width || id.y >= params.height) {
        return;
    }
    let p = vec2<i32>(id.xy);
    let size = vec2<i32>(i32(params.src_width), i32(params.src_height));
    let sum = textureLoad(detail, p, 0).rgb + upsample_at(p, size);
    textureStore(dst, p, vec4<f32>(min(sum, vec3<f32>(params.store_max)), 1.0));
}
