// Waves technique `gerstner` (seed 002; ocean-core waves::gerstner) evaluated at a point of
// the mesh: the sum of the frame's Gerstner waves (`frame.gerstner`, FrameUniforms), with θ in
// turns from the mesh's reference point so that both back ends form the same f32 phase, and
// (cos θ, sin θ) by cis_turns. Reads the importing stage's `frame`.
// CPU mirror: ocean-cpu/src/shaders/shared/gerstner.rs.

// #import shared/trig.wgsl

// The wave i's (cos θ, sin θ) at `pos` (m, relative to the mesh's reference point).
fn gerstner_cis(i: u32, pos: vec2<f32>) -> vec2<f32> {
    let a = frame.gerstner.waves[2u * i];
    // In this order because lavapipe's compiler reassociates a.x·x + a.y·z + a.z so (measured:
    // 1-ulp phases near the horizon otherwise); written so, both back ends round alike.
    let p = (a.x * pos.x + a.z) + a.y * pos.y;
    return cis_turns(p - floor(p + 0.5));
}

// (disp_x, height, disp_z, 0): Σ (s/k) D cos θ and Σ A sin θ.
fn gerstner_displacement(pos: vec2<f32>) -> vec4<f32> {
    var d = vec4<f32>(0.0, 0.0, 0.0, 0.0);
    for (var i = 0u; i < u32(frame.gerstner.count); i = i + 1u) {
        let cs = gerstner_cis(i, pos);
        let a = frame.gerstner.waves[2u * i];
        let b = frame.gerstner.waves[2u * i + 1u];
        d = d + vec4<f32>(b.x * cs.x, a.w * cs.y, b.y * cs.x, 0.0);
    }
    return d;
}

// gerstner_displacement for a mesh whose vertices are `spacing` m apart (surface `clipmap`):
// each wave times g = clamp(2 − 8·spacing/λ, 0, 1), whole down to 8 vertices per wavelength
// and gone at 4, so that no wave the vertices cannot carry aliases into the geometry.
fn gerstner_displacement_filtered(pos: vec2<f32>, spacing: f32) -> vec4<f32> {
    var d = vec4<f32>(0.0, 0.0, 0.0, 0.0);
    for (var i = 0u; i < u32(frame.gerstner.count); i = i + 1u) {
        let a = frame.gerstner.waves[2u * i];
        let g = clamp(2.0 - 8.0 * (spacing * sqrt(a.x * a.x + a.y * a.y)), 0.0, 1.0);
        if (g > 0.0) {
            let cs = gerstner_cis(i, pos) * g;
            let b = frame.gerstner.waves[2u * i + 1u];
            d = d + vec4<f32>(b.x * cs.x, a.w * cs.y, b.y * cs.x, 0.0);
        }
    }
    return d;
}

// (∂h/∂x, ∂h/∂z) at the undisplaced point: Σ A k D cos θ.
fn gerstner_slopes(pos: vec2<f32>) -> vec2<f32> {
    var s = vec2<f32>(0.0, 0.0);
    for (var i = 0u; i < u32(frame.gerstner.count); i = i + 1u) {
        let cs = gerstner_cis(i, pos);
        let b = frame.gerstner.waves[2u * i + 1u];
        s = s + vec2<f32>(b.z * cs.x, b.w * cs.x);
    }
    return s;
}

// J = (1 + ∂Dx/∂x)(1 + ∂Dz/∂z) − (∂Dx/∂z)² at the undisplaced point, with
// ∂Dx/∂x = −Σ s Dx² sin θ, ∂Dz/∂z = −Σ s Dz² sin θ, ∂Dx/∂z = ∂Dz/∂x = −Σ s Dx Dz sin θ
// (s Dx² = qx·kx, kx = 2π fx; ocean-core waves::gerstner::GerstnerSea::sample in f64).
fn gerstner_jacobian(pos: vec2<f32>) -> f32 {
    var dxx = 0.0;
    var dzz = 0.0;
    var dxz = 0.0;
    for (var i = 0u; i < u32(frame.gerstner.count); i = i + 1u) {
        let sn = gerstner_cis(i, pos).y;
        let a = frame.gerstner.waves[2u * i];
        let b = frame.gerstner.waves[2u * i + 1u];
        let kx = TAU * a.x;
        let kz = TAU * a.y;
        dxx = dxx - (b.x * kx) * sn;
        dzz = dzz - (b.y * kz) * sn;
        dxz = dxz - (b.x * kz) * sn;
    }
    return (1.0 + dxx) * (1.0 + dzz) - dxz * dxz;
}
