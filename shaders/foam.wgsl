// Stage `foam`: one fixed step of foam `accumulated`'s field (ocean-core foam, whose
// accumulate_step this writes out): per texel, f ← min(f·e^(−Δt/τ) + g·Δt·clamp((threshold −
// J)/softness, 0, 1), 1), the field read from `src` and written to `dst` (the back end swaps
// them after each step). Under waves `fft` texel (i, j) takes J from the displacement map's
// texel (i, j) (J = 1 where the waves pass was skipped); under `gerstner` (analytic = 1) from the waves' Jacobian at its lattice point,
// start_rel + ((i, j) − start mod size)·cell, and a texel whose lattice point changed since
// the last step (the window moved with the camera) starts empty. One dispatch per step.
// The techniques' drawing of the field: shaders/foam/accumulated.wgsl.
// CPU mirror: crates/ocean-cpu/src/shaders/foam.rs.

// #import shared/frame.wgsl
// #import shared/gerstner.wgsl

struct FoamStepUniforms {
    size: u32,
    analytic: u32,
    start: vec2<u32>,
    start_prev: vec2<u32>,
    shift: vec2<i32>,
    start_rel: vec2<f32>,
    cell_m: f32,
    decay: f32,
    growth: f32,
    threshold: f32,
    inv_softness: f32,
    pad0: f32,
}

@group(0) @binding(0) var<uniform> params: FoamStepUniforms;
@group(0) @binding(1) var<uniform> frame: FrameUniforms;
// (disp_x, height, disp_z, jacobian) of the displacement map (waves `fft`).
@group(0) @binding(2) var displacement: texture_2d<f32>;
@group(0) @binding(3) var src: texture_2d<f32>;
@group(0) @binding(4) var dst: texture_storage_2d<rgba32float, write>;

// The texel's offset from the window's first point along one axis, 0..size.
fn texel_offset(i: u32, start: u32) -> u32 {
    return (i + params.size - start) % params.size;
}

// Whether the texel holds another lattice point than at the previous step.
fn texel_is_fresh(i: u32, start: u32, start_prev: u32, shift: i32) -> bool {
    let a = texel_offset(i, start);
    let b = texel_offset(i, start_prev);
    return shift + i32(a) - i32(b) != 0;
}

@compute @workgroup_size(8, 8, 1)
fn accumulate(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.size || id.y >= params.size) {
        return;
    }
    let fresh = texel_is_fresh(id.x, params.start.x, params.start_prev.x, params.shift.x)
        || texel_is_fresh(id.y, params.start.y, params.start_prev.y, params.shift.y);
    var j = 1.0;
    if (params.analytic == 1u) {
        let ox = f32(texel_offset(id.x, params.start.x));
        let oz = f32(texel_offset(id.y, params.start.y));
        let pos = vec2<f32>(params.start_rel.x + ox * params.cell_m, params.start_rel.y + oz * params.cell_m);
        j = gerstner_jacobian(pos);
    } else {
        // A skipped waves pass (a flat sea) leaves one zero texel: J is then 1.
        let last = textureDimensions(displacement) - vec2<u32>(1u, 1u);
        let t = textureLoad(displacement, vec2<i32>(min(id.xy, last)), 0).w;
        j = 1.0 + (t - 1.0) * frame.passes.waves;
    }
    var kept = textureLoad(src, vec2<i32>(id.xy), 0).x;
    if (fresh) {
        kept = 0.0;
    }
    let source = clamp((params.threshold - j) * params.inv_softness, 0.0, 1.0);
    let f = min(kept * params.decay + params.growth * source, 1.0);
    textureStore(dst, vec2<i32>(id.xy), vec4<f32>(f, 0.0, 0.0, 0.0));
}
