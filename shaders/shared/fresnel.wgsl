// The exact Fresnel reflectance of eq. 2 (seed 000), for every stage that needs it
// (`fresnel_table`'s texture, shading `chiu`'s per-pixel F).
// CPU mirror: ocean-cpu/src/shaders/shared/fresnel.rs.

// Eq. 2 of seed 000 (ocean-core fresnel::fresnel_exact) for cos θ_i ∈ [0, 1] on the side of
// index 1 and η = n_t/n_i > 0, evaluated as ocean-core does (g − c as (η² − 1)/(g + c), the
// p/s ratio from c·g ∓ sin²θ_i, so nothing cancels as η → 1), by + − × ÷ sqrt only: both
// back ends round alike. Total internal reflection and grazing incidence give 1, η = 1 gives 0.
fn fresnel_exact(cos_theta_i: f32, eta: f32) -> f32 {
    let c = clamp(cos_theta_i, 0.0, 1.0);
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
    var g = 0.0;
    var g_minus_c = 0.0;
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
