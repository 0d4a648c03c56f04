// Stage `fresnel_table`: the 2D Fresnel texture of seed 000 §5.1/§5.3, one invocation per
// texel: RGB = the normalised local view vector (normal = +Z), A = F of eq. 2 for it.
// Texel (i, j): s = (i + 0.5)/N, t = (j + 0.5)/N; whole hemisphere x = 2s − 1, y = 2t − 1,
// z = sqrt(max(0, 1 − x² − y²)), clamped to the rim outside the unit disc (docs/design.md); the
// paper's half range x = s − 0.5, y = t − 0.5; or the grazing mapping the renderer uses: texel
// i at u = 2i/(N − 1) − 1 (the rim on the edge texels' centres), the square to the disc by the
// elliptical grid mapping d, ρ = |d| = sqrt(1 − z), V = (d·sqrt(1 + z), z).
// CPU mirror: crates/ocean-cpu/src/shaders/fresnel_table.rs; reference (f64):
// ocean-core's tables::FresnelTexture.

struct FresnelTableUniforms {
    eta: f32,
    size: u32,
    mapping: u32,
    // 2/(N − 1) from the CPU (f64, rounded once): lavapipe's division is not always the
    // correctly rounded one, a multiplication is.
    step: f32,
    // 4/(N − 1)², likewise.
    step2: f32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

// #import shared/fresnel.wgsl

@group(0) @binding(0) var<uniform> params: FresnelTableUniforms;
@group(0) @binding(1) var table: texture_storage_2d<rgba32float, write>;

// The grazing mapping's view vector of texel `id` (ocean-core tables::TextureMapping):
// u = i·step − 1, the elliptical grid mapping d = (u sqrt(1 − v²/2), v sqrt(1 − u²/2)), and
// z = 1 − |d|² = (1 − u²)(1 − v²), where 1 − u² = 4 i (N − 1 − i)/(N − 1)² is formed from the
// whole number i (N − 1 − i) (exact in f32 up to N = 8192) times step2: exactly 0 on the edge
// texels, no cancellation, and no sum of products a compiler may fuse or reorder (lavapipe
// simplified (1 − u)(1 + u) with u = i·step − 1 to one ulp off the CPU's).
fn grazing_view_vector(id: vec2<u32>) -> vec3<f32> {
    let u = f32(id.x) * params.step - 1.0;
    let v = f32(id.y) * params.step - 1.0;
    let d = vec2<f32>(u * sqrt(1.0 - 0.5 * v * v), v * sqrt(1.0 - 0.5 * u * u));
    let last = params.size - 1u;
    let z = (f32(id.x * (last - id.x)) * params.step2) * (f32(id.y * (last - id.y)) * params.step2);
    let k = sqrt(1.0 + z);
    return vec3<f32>(d.x * k, d.y * k, z);
}

fn view_vector(s: f32, t: f32) -> vec3<f32> {
    if (params.mapping == 1u) {
        let x = s - 0.5;
        let y = t - 0.5;
        return vec3<f32>(x, y, sqrt(max(1.0 - x * x - y * y, 0.0)));
    }
    let x = 2.0 * s - 1.0;
    let y = 2.0 * t - 1.0;
    let r2 = x * x + y * y;
    if (r2 > 1.0) {
        let r = sqrt(r2);
        return vec3<f32>(x / r, y / r, 0.0);
    }
    return vec3<f32>(x, y, sqrt(max(1.0 - r2, 0.0)));
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.size || id.y >= params.size) {
        return;
    }
    var v: vec3<f32>;
    if (params.mapping == 2u) {
        v = grazing_view_vector(id.xy);
    } else {
        let n = f32(params.size);
        let s = (f32(id.x) + 0.5) / n;
        let t = (f32(id.y) + 0.5) / n;
        v = view_vector(s, t);
    }
    textureStore(table, vec2<i32>(id.xy), vec4<f32>(v, fresnel_exact(v.z, params.eta)));
}
