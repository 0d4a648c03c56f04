//! Mirror of `shaders/shared/fresnel.wgsl`: eq. 2 in f32.

/// `fresnel_exact(cos_theta_i, eta)`: eq. 2 for cos θ_i clamped to [0, 1] and η > 0. The
/// WGSL writes out ocean-core's `fresnel::fresnel_exact`, whose generic form in f32 takes the
/// same branches in the same order there.
pub fn fresnel_exact(cos_theta_i: f32, eta: f32) -> f32 {
    ocean_core::fresnel::fresnel_exact(cos_theta_i.clamp(0.0, 1.0), eta)
}
