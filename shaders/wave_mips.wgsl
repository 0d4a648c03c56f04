// Stage `wave_mips`: the mip chains of the slope maps that far fields `mip` and `variance`
// sample (ocean-core far_field). Entry `moments` writes level 0 of a chain from a slope map's
// first two channels: (s_x, s_z, s_x², s_z²), so that each level also holds the mean squared
// slopes and E[s²] − E[s]² is the variance a footprint averages away. Entry `downsample`
// writes level k + 1 from level k: texel (i, j) is the 2×2 box of level k's texels (2i, 2j),
// (2i + 1, 2j), (2i, 2j + 1), (2i + 1, 2j + 1), summed as ((a + b) + (c + d)) · 0.25 (the
// quarter is exact); coordinates beyond a level of odd or unit size are clamped to its last
// texel. One dispatch per level.
// CPU mirror: crates/ocean-cpu/src/shaders/wave_mips.rs.

struct WaveMipsUniforms {
    // Size of the level written, texels.
    width: u32,
    height: u32,
    // Size of the level read (`downsample`), texels.
    src_width: u32,
    src_height: u32,
}

@group(0) @binding(0) var<uniform> params: WaveMipsUniforms;
@group(0) @binding(1) var src: texture_2d<f32>;
@group(0) @binding(2) var dst: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8, 1)
fn moments(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.width || id.y >= params.height) {
        return;
    }
    let s = textureLoad(src, vec2<i32>(id.xy), 0);
    textureStore(dst, vec2<i32>(id.xy), vec4<f32>(s.x, s.y, s.x * s.x, s.y * s.y));
}

@compute @workgroup_size(8, 8, 1)
fn downsample(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.width || id.y >= params.height) {
        return;
    }
    let x0 = min(2u * id.x, params.src_width - 1u);
    let x1 = min(2u * id.x + 1u, params.src_width - 1u);
    let y0 = min(2u * id.y, params.src_height - 1u);
    let y1 = min(2u * id.y + 1u, params.src_height - 1u);
    let a = textureLoad(src, vec2<i32>(vec2<u32>(x0, y0)), 0);
    let b = textureLoad(src, vec2<i32>(vec2<u32>(x1, y0)), 0);
    let c = textureLoad(src, vec2<i32>(vec2<u32>(x0, y1)), 0);
    let d = textureLoad(src, vec2<i32>(vec2<u32>(x1, y1)), 0);
    textureStore(dst, vec2<i32>(id.xy), ((a + b) + (c + d)) * 0.25);
}
