// Stage `fresnel_table`: the 2D Fresnel texture of seed 000 §5.1/§5.3, one invocation per
// texel: RGB = the normalised local view vector (normal = +Z), A = F of eq. 2 for it.
// Texel (i, j): s = (i + 0.5)/N, t = (j + 0.5)/N; whole hemisphere x = 2s − 1, y = 2t − 1,
// z = sqrt(max(0, 1 − x² − y²)), clamped to the rim outside the unit disc (DESIGN.md); or the
// paper's half range x = s − 0.5, y = t − 0.5.
// CPU mirror: crates/ocean-cpu/src/shaders/fresnel_table.rs; reference (f64):
// ocean-core's tables::FresnelTexture.

struct FresnelTableUniforms {
    eta: f32,
    size: u32,
    mapping: u32,
    pad: u32,
}

@group(0) @binding(0) var<uniform> params: FresnelTableUniforms;
@group(0) @binding(1) var table: texture_storage_2d<rgba32float, write>;

// Eq. 2 in the stable form of ocean-core's fresnel::fresnel_exact (same branches, same order
// of operations), for c ∈ [0, 1] and η > 0.
fn fresnel_exact(c: f32, eta: f32) -> f32 {
    if (eta == 1.0) {
        return 0.0;
    }
    if (c == 0.0) {
        return 1.0;
    }
    if (c == 1.0) {
        let r = (eta - 1.0) / (eta + 1.0);
        return r * r;
    }
    let sin2_theta_i = (1.0 - c) * (1.0 + c);
    var g: f32;
    var g_minus_c: f32;
    if (eta <= 2.0) {
        let eta2_minus_1 = (eta - 1.0) * (eta + 1.0);
        let g2 = eta2_minus_1 + c * c;
        if (g2 < 0.0) {
            return 1.0;
        }
        g = sqrt(g2);
        g_minus_c = eta2_minus_1 / (g + c);
    } else {
        g = eta * sqrt(1.0 - sin2_theta_i / eta / eta);
        g_minus_c = g - c;
    }
    let r_s = g_minus_c / (g + c);
    let cg = c * g;
    let p_over_s = (cg - sin2_theta_i) / (cg + sin2_theta_i);
    return min(0.5 * r_s * r_s * (1.0 + p_over_s * p_over_s), 1.0);
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
    let n = f32(params.size);
    let s = (f32(id.x) + 0.5) / n;
    let t = (f32(id.y) + 0.5) / n;
    let v = view_vector(s, t);
    textureStore(table, vec2<i32>(id.xy), vec4<f32>(v, fresnel_exact(v.z, params.eta)));
}
