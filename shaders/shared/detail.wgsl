// Shading `ggx`'s detail normal map (seed 002 §Normal maps; ocean-core detail): two layers of a
// static slope field of sinusoids drifting in opposite directions (`frame.detail`, one vec4 per
// sinusoid, both layers), added to the surface's slopes. Each sinusoid's slope is averaged over
// the pixel's footprint, a Gaussian of standard deviations (sigma_long, sigma_short) along and
// across h, the horizontal direction to the eye — the damping g of the Gerstner waves' filter —
// and under far field `variance` what the average removes goes to the BRDF. Reads the importing
// stage's `frame` and exp_arith (shared/optics.wgsl).
// CPU mirror: ocean-cpu/src/shaders/shared/detail.rs.

// #import shared/trig.wgsl

// (slope_x, slope_z, variance per axis) of the detail map at `pos` (m, relative to the mesh's
// reference point).
fn detail_slopes(pos: vec2<f32>, h: vec2<f32>, sigma_long: f32, sigma_short: f32) -> vec3<f32> {
    var s = vec2<f32>(0.0, 0.0);
    var variance = 0.0;
    for (var i = 0u; i < u32(frame.detail.count); i = i + 1u) {
        let w = frame.detail.waves[i];
        // In gerstner_cis's order (lavapipe reassociates the sum so).
        let p = (w.x * pos.x + w.z) + w.y * pos.y;
        let c = cis_turns(p - floor(p + 0.5)).x;
        let kx = TAU * w.x;
        let kz = TAU * w.y;
        let k_long = (kx * h.x + kz * h.y) * sigma_long;
        let k_short = (kz * h.x - kx * h.y) * sigma_short;
        let g = exp_arith(-0.5 * (k_long * k_long + k_short * k_short));
        s = s + vec2<f32>(w.x, w.y) * (w.w * (c * g));
        if (frame.far.mode == FAR_VARIANCE) {
            let g2 = g * g;
            let v = 0.5 * (1.0 - g2 * g2) + c * c * (g2 * g2 - g2);
            variance = variance + 0.5 * (w.w * w.w) * (w.x * w.x + w.y * w.y) * v;
        }
    }
    return vec3<f32>(s.x, s.y, variance);
}
