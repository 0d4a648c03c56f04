// Stage `waves`: the wave maps of seed 000 §2.1 (Tessendorf's eq. 1 and the fields derived
// from it) on the GPU, every frame, from the h0(k) ocean-core drew:
//
//   spectrum     h~(k, t) = h0(k) e^{iωt} + conj(h0(−k) e^{iωt}) and the eight multiplied
//                spectra, packed two per complex array (four N×N arrays in `dst`)
//   fft_rows     one radix-2 Stockham stage along x of all four arrays (`src` → `dst`)
//   fft_columns  the same along z
//   spectrum_rows_shared
//                `spectrum` and every stage along x in one dispatch: a workgroup per row
//                holds its lines (all four arrays for N ≤ 256) in workgroup memory (two
//                halves, ping and pong) between pairs of stages (radix 4)
//   columns_pack_shared
//                every stage along z and `pack` in one dispatch: a workgroup per column,
//                each thread keeping its texels' four arrays in registers until it packs
//                them. Both do the same operations as `spectrum`, the one-stage entry points
//                and `pack`, so the same results; N ≤ FFT_SHARED_MAX
//   pack         the maps as the water stage binds them: displacement (disp_x, height,
//                disp_z, jacobian), displacement_slopes (slope_x, slope_z, 0, 0), bump
//                (slope_x, slope_z, height, jacobian)
//
// A frame: spectrum into ping, log2(N) fft_rows then log2(N) fft_columns stages alternating
// ping → pong → ping …, pack from ping (2·log2(N) passes is even); or, for N ≤ FFT_SHARED_MAX,
// spectrum_rows_shared (→ pong) and columns_pack_shared (pong → the textures), two dispatches.
// Conventions (unnormalised inverse DFT, bin (n mod N, m mod N), the multipliers,
// λ = −choppiness, the pairs) are ocean-core's (waves::synthesis); the phase in integer turns
// and the FFT stage formula are documented in ocean-core's waves::uniforms. CPU mirror:
// crates/ocean-cpu/src/shaders/waves.rs, the shared-memory entry points in its
// waves/shared_memory.rs.
// Array layout: element (field f, bin) at f·N² + bin, bin = j·N + i (z row j, x column i).

// #import shared/trig.wgsl

struct WavesUniforms {
    size: u32,
    log2_size: u32,
    time_ticks: vec2<u32>,
    time_remainder: f32,
    lambda: f32,
    pad0: u32,
    pad1: u32,
}

struct WaveMode {
    h0: vec2<f32>,
    k: vec2<f32>,
    phase_rate: vec2<u32>,
    inv_k: f32,
    frequency: f32,
}

struct FftPassUniforms {
    stage: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> params: WavesUniforms;
@group(0) @binding(1) var<storage, read> modes: array<WaveMode>;
@group(0) @binding(2) var<storage, read> twiddles: array<vec2<f32>>;
@group(1) @binding(0) var<uniform> fft_pass: FftPassUniforms;
@group(1) @binding(1) var<storage, read> src: array<vec2<f32>>;
@group(1) @binding(2) var<storage, read_write> dst: array<vec2<f32>>;
@group(2) @binding(0) var displacement: texture_storage_2d<rgba32float, write>;
@group(2) @binding(1) var displacement_slopes: texture_storage_2d<rgba32float, write>;
@group(2) @binding(2) var bump: texture_storage_2d<rgba32float, write>;

// 2^-24: one unit of the 24-bit turn count.
const TURN_UNIT: f32 = 5.9604645e-8;

// The high 32 bits of the 64-bit product a·b (WGSL has no 64-bit integers): 16-bit halves,
// each partial product < 2^32, the middle column summed without overflow (< 3·2^16).
fn mul_hi(a: u32, b: u32) -> u32 {
    let a0 = a & 0xffffu;
    let a1 = a >> 16u;
    let b0 = b & 0xffffu;
    let b1 = b >> 16u;
    let p00 = a0 * b0;
    let p01 = a0 * b1;
    let p10 = a1 * b0;
    let p11 = a1 * b1;
    let mid = (p00 >> 16u) + (p01 & 0xffffu) + (p10 & 0xffffu);
    return p11 + (p01 >> 16u) + (p10 >> 16u) + (mid >> 16u);
}

// frac(f·t) in turns, in [−½, ½]: the high word of Q·ticks mod 2^64 (wrapping u32
// arithmetic), rounded to 24 bits and read as signed, plus the sub-tick term f·r.
fn phase_turns(rate: vec2<u32>, frequency: f32) -> f32 {
    let ticks = params.time_ticks;
    let turns_fixed = mul_hi(rate.x, ticks.x) + rate.y * ticks.x + rate.x * ticks.y;
    let coarse = f32(bitcast<i32>(turns_fixed + 128u) >> 8u) * TURN_UNIT;
    let c = coarse + frequency * params.time_remainder;
    return c - floor(c + 0.5);
}

// a·b of complex numbers (x = real part).
fn complex_mul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

// Â + iB̂ of two spectra whose inverse transforms are real.
fn pack_pair(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x - b.y, a.y + b.x);
}

// The four packed spectra of bin (i, j), in array order: h~ = h0·e + conj(h0(−k)·e) and
// the multiplied spectra, paired as `pack_pair` pairs them.
fn spectrum_of(i: u32, j: u32) -> array<vec2<f32>, 4> {
    let n = params.size;
    let bin = j * n + i;
    let partner = ((n - j) & (n - 1u)) * n + ((n - i) & (n - 1u));
    let mode = modes[bin];
    let h0_minus = modes[partner].h0;
    // The same rate at k and −k (same |k|), so h~(−k) = conj(h~(k)) bit for bit.
    let e = cis_turns(phase_turns(mode.phase_rate, mode.frequency));
    // h~ = h0·e + conj(h0(−k)·e), written factored: lavapipe's compiler factors the
    // unfactored sum (a·e.x + b·e.x → (a + b)·e.x), so this is the form both evaluate alike.
    let s = mode.h0 + h0_minus;
    let d = mode.h0 - h0_minus;
    let h = vec2<f32>(s.x * e.x - s.y * e.y, d.x * e.y + d.y * e.x);

    let kx = mode.k.x;
    let kz = mode.k.y;
    let inv_k = mode.inv_k;
    let lambda = params.lambda;
    let i_h = vec2<f32>(-h.y, h.x);
    let minus_i_h = vec2<f32>(h.y, -h.x);
    let disp_x = minus_i_h * (lambda * kx * inv_k);
    let disp_z = minus_i_h * (lambda * kz * inv_k);
    let slope_x = i_h * kx;
    let slope_z = i_h * kz;
    let disp_x_dx = h * (lambda * kx * kx * inv_k);
    let disp_z_dz = h * (lambda * kz * kz * inv_k);
    let disp_x_dz = h * (lambda * kx * kz * inv_k);
    return array<vec2<f32>, 4>(
        pack_pair(h, disp_x),
        pack_pair(disp_z, disp_x_dz),
        pack_pair(slope_x, slope_z),
        pack_pair(disp_x_dx, disp_z_dz),
    );
}

@compute @workgroup_size(8, 8, 1)
fn spectrum(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = params.size;
    if (id.x >= n || id.y >= n) {
        return;
    }
    let bin = id.y * n + id.x;
    let plane = n * n;
    let arrays = spectrum_of(id.x, id.y);
    dst[bin] = arrays[0];
    dst[plane + bin] = arrays[1];
    dst[2u * plane + bin] = arrays[2];
    dst[3u * plane + bin] = arrays[3];
}

// Butterfly j of the current stage on the line starting at `base` with element `stride`.
fn butterfly(base: u32, stride: u32, j: u32) {
    let half = params.size / 2u;
    let s = 1u << fft_pass.stage;
    let q = j & (s - 1u);
    let a = src[base + j * stride];
    let b = src[base + (j + half) * stride];
    let w = twiddles[j - q];
    let d = a - b;
    let out = 2u * j - q;
    dst[base + out * stride] = a + b;
    dst[base + (out + s) * stride] = complex_mul(d, w);
}

// The largest N the shared-memory FFT holds (two lines of N complex f32: 16 KiB, WebGPU's
// guaranteed workgroup storage), and its threads per workgroup (WebGPU's guaranteed
// invocations per workgroup).
const FFT_SHARED_MAX: u32 = 1024u;
const FFT_SHARED_THREADS: u32 = 256u;
// The arrays of a frame, and the elements of a line one thread keeps (N / FFT_SHARED_THREADS).
const WAVE_ARRAYS: u32 = 4u;
const FFT_KEPT_PER_ARRAY: u32 = 4u;

var<workgroup> fft_line: array<vec2<f32>, 2048>;

// How many lines of N elements each half of `fft_line` holds at once, up to the four arrays:
// 4 for N ≤ 256, 2 for N = 512, 1 for N = 1024.
fn shared_lines() -> u32 {
    return min(WAVE_ARRAYS, FFT_SHARED_MAX / params.size);
}

// Every stage of the FFT of `count` lines held in workgroup memory, line l at [l·N, l·N + N)
// of the half at 0; the two halves, at 0 and at FFT_SHARED_MAX, take turns to be read and
// written. Returns the offset of the half that holds the result. The caller has written the
// lines and passed a barrier; every write here is followed by a barrier.
//
// Stages go two at a time between barriers (radix 4): the butterflies j and j + N/4 of stage
// s (s ≤ N/4, so both have the same q = j mod s) write the elements 2j − q, 2j − q + s,
// 2j − q + N/2 and 2j − q + s + N/2, which are exactly the inputs of butterflies 2j − q and
// 2j − q + s of stage 2s (q' = q and q + s, one twiddle 2j − 2q for both); one thread does
// all four in registers. The same butterflies, twiddles and operations as `butterfly`, so the
// same results, with half the barriers and half the workgroup-memory traffic; an odd log2(N)
// ends with one radix-2 stage. Thread `local` does quads local, local + FFT_SHARED_THREADS, …
// of all lines of each pair of stages.
fn fft_lines_shared(count: u32, local: u32) -> u32 {
    let n = params.size;
    let half = n / 2u;
    let quarter = n / 4u;
    var read_at = 0u;
    var write_at = FFT_SHARED_MAX;
    var stage = 0u;
    for (; stage + 1u < params.log2_size; stage += 2u) {
        let s = 1u << stage;
        let quads_log2 = params.log2_size - 2u;
        for (var t = local; t < (count << quads_log2); t += FFT_SHARED_THREADS) {
            let line = (t >> quads_log2) * n;
            let j = t & (quarter - 1u);
            let q = j & (s - 1u);
            let line_at = read_at + line;
            let a0 = fft_line[line_at + j];
            let b0 = fft_line[line_at + j + half];
            let a1 = fft_line[line_at + j + quarter];
            let b1 = fft_line[line_at + j + quarter + half];
            let d0 = a0 - b0;
            let d1 = a1 - b1;
            let y0 = a0 + b0;
            let y1 = complex_mul(d0, twiddles[j - q]);
            let y2 = a1 + b1;
            let y3 = complex_mul(d1, twiddles[j + quarter - q]);
            let w = twiddles[2u * (j - q)];
            let e0 = y0 - y2;
            let e1 = y1 - y3;
            let out = write_at + line + 4u * j - 3u * q;
            fft_line[out] = y0 + y2;
            fft_line[out + s] = y1 + y3;
            fft_line[out + 2u * s] = complex_mul(e0, w);
            fft_line[out + 3u * s] = complex_mul(e1, w);
        }
        workgroupBarrier();
        let t = read_at;
        read_at = write_at;
        write_at = t;
    }
    if (stage < params.log2_size) {
        let s = 1u << stage;
        let pairs_log2 = params.log2_size - 1u;
        for (var t = local; t < (count << pairs_log2); t += FFT_SHARED_THREADS) {
            let line = (t >> pairs_log2) * n;
            let j = t & (half - 1u);
            let q = j & (s - 1u);
            let a = fft_line[read_at + line + j];
            let b = fft_line[read_at + line + j + half];
            let w = twiddles[j - q];
            let d = a - b;
            let out = write_at + line + 2u * j - q;
            fft_line[out] = a + b;
            fft_line[out + s] = complex_mul(d, w);
        }
        workgroupBarrier();
        let t = read_at;
        read_at = write_at;
        write_at = t;
    }
    return read_at;
}

// `spectrum` and every stage along x in one dispatch. Workgroup (row j, batch): the spectra
// of row j's bins, arrays batch·L … batch·L + L − 1 (L = shared_lines()), transformed in
// workgroup memory and written to `dst`.
@compute @workgroup_size(256, 1, 1)
fn spectrum_rows_shared(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
) {
    let n = params.size;
    let count = shared_lines();
    let first = group.y * count;
    for (var i = local.x; i < n; i += FFT_SHARED_THREADS) {
        var arrays = spectrum_of(i, group.x);
        for (var l = 0u; l < count; l++) {
            fft_line[l * n + i] = arrays[first + l];
        }
    }
    workgroupBarrier();
    let at = fft_lines_shared(count, local.x);
    for (var l = 0u; l < count; l++) {
        let base = (first + l) * n * n + group.x * n;
        for (var i = local.x; i < n; i += FFT_SHARED_THREADS) {
            dst[base + i] = fft_line[at + l * n + i];
        }
    }
}

// Every stage along z and `pack` in one dispatch. Workgroup (column i): the four arrays'
// column i from `src`, L lines at a time, transformed in workgroup memory; each thread keeps
// its elements z = local, local + FFT_SHARED_THREADS, … of every array in registers and packs
// those texels once all four are done.
@compute @workgroup_size(256, 1, 1)
fn columns_pack_shared(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
) {
    let n = params.size;
    let count = shared_lines();
    var kept: array<vec2<f32>, WAVE_ARRAYS * FFT_KEPT_PER_ARRAY>;
    for (var first = 0u; first < WAVE_ARRAYS; first += count) {
        for (var l = 0u; l < count; l++) {
            let base = (first + l) * n * n + group.x;
            for (var z = local.x; z < n; z += FFT_SHARED_THREADS) {
                fft_line[l * n + z] = src[base + z * n];
            }
        }
        workgroupBarrier();
        let at = fft_lines_shared(count, local.x);
        for (var l = 0u; l < count; l++) {
            var k = 0u;
            for (var z = local.x; z < n; z += FFT_SHARED_THREADS) {
                kept[(first + l) * FFT_KEPT_PER_ARRAY + k] = fft_line[at + l * n + z];
                k++;
            }
        }
        // The next batch overwrites the lines read above.
        workgroupBarrier();
    }
    var k = 0u;
    for (var z = local.x; z < n; z += FFT_SHARED_THREADS) {
        store_texel(
            vec2<i32>(vec2<u32>(group.x, z)),
            kept[k],
            kept[FFT_KEPT_PER_ARRAY + k],
            kept[2u * FFT_KEPT_PER_ARRAY + k],
            kept[3u * FFT_KEPT_PER_ARRAY + k],
        );
        k++;
    }
}

// id.x: butterfly, id.y: row (z index j), id.z: array.
@compute @workgroup_size(64, 1, 1)
fn fft_rows(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = params.size;
    if (id.x >= n / 2u || id.y >= n || id.z >= 4u) {
        return;
    }
    butterfly(id.z * n * n + id.y * n, 1u, id.x);
}

// id.x: butterfly, id.y: column (x index i), id.z: array.
@compute @workgroup_size(64, 1, 1)
fn fft_columns(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = params.size;
    if (id.x >= n / 2u || id.y >= n || id.z >= 4u) {
        return;
    }
    butterfly(id.z * n * n + id.y, n, id.x);
}

// The three texels of one bin from its four transformed arrays.
fn store_texel(
    texel: vec2<i32>,
    height_disp_x: vec2<f32>,
    disp_z_disp_x_dz: vec2<f32>,
    slopes: vec2<f32>,
    disp_x_dx_disp_z_dz: vec2<f32>,
) {
    let height = height_disp_x.x;
    // With λ = 0 the imaginary part of the first array is only the round-off of the height's
    // transform: ocean-core writes an exact 0 there, and so does this.
    let disp_x = select(height_disp_x.y, 0.0, params.lambda == 0.0);
    let disp_z = disp_z_disp_x_dz.x;
    let disp_x_dz = disp_z_disp_x_dz.y;
    let jacobian = (1.0 + disp_x_dx_disp_z_dz.x) * (1.0 + disp_x_dx_disp_z_dz.y)
        - disp_x_dz * disp_x_dz;
    textureStore(displacement, texel, vec4<f32>(disp_x, height, disp_z, jacobian));
    textureStore(displacement_slopes, texel, vec4<f32>(slopes.x, slopes.y, 0.0, 0.0));
    textureStore(bump, texel, vec4<f32>(slopes.x, slopes.y, height, jacobian));
}

@compute @workgroup_size(8, 8, 1)
fn pack(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = params.size;
    if (id.x >= n || id.y >= n) {
        return;
    }
    let bin = id.y * n + id.x;
    let plane = n * n;
    store_texel(
        vec2<i32>(id.xy),
        src[bin],
        src[plane + bin],
        src[2u * plane + bin],
        src[3u * plane + bin],
    );
}
