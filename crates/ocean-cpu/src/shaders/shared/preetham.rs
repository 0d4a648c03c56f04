//! Mirror of `shaders/shared/preetham.wgsl`: the Preetham sky in f32, which the sky
//! techniques `preetham` and `preetham_clouds` are built on. The physics and the f64 reference
//! are `ocean_core::sky`.

pub use ocean_core::sky::SkyUniforms;

use crate::shaders::wgsl::{Vec3, Vec4, clamp, cross, dot, exp, length, max, select, vec3};

/// Smallest chromaticity y in xyY → XYZ (`ocean_core::sky::MIN_CHROMATICITY_Y`).
pub const MIN_CHROMATICITY_Y: f32 = 0.0001;

/// Perez et al. (1993) distribution for (Y, x, y):
/// (1 + A exp(B / cos θ)) (1 + C exp(D γ) + E cos² γ).
pub fn perez(sky: &SkyUniforms, cos_theta: f32, gamma: f32, cos_gamma: f32) -> Vec3 {
    let a = Vec4::from(sky.perez_a).xyz();
    let b = Vec4::from(sky.perez_b).xyz();
    let c = Vec4::from(sky.perez_c).xyz();
    let d = Vec4::from(sky.perez_d).xyz();
    let e = Vec4::from(sky.perez_e).xyz();
    (1.0 + a * exp(b / cos_theta)) * (1.0 + c * exp(d * gamma) + e * cos_gamma * cos_gamma)
}

/// CIE XYZ → linear sRGB, IEC 61966-2-1.
pub fn xyz_to_linear_srgb(xyz: Vec3) -> Vec3 {
    let r = 3.2406 * xyz.x - 1.5372 * xyz.y - 0.4986 * xyz.z;
    let g = -0.9689 * xyz.x + 1.8758 * xyz.y + 0.0415 * xyz.z;
    let b = 0.0557 * xyz.x - 0.2040 * xyz.y + 1.0570 * xyz.z;
    vec3(r, g, b)
}

/// `preetham_radiance(sky, dir)`: sky radiance without the sun disc in unit direction `dir`
/// (linear sRGB, scene units).
pub fn preetham_radiance(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    let sun = Vec4::from(sky.sun_direction).xyz();
    let cos_theta = max(dir.y, sky.cos_theta_min);
    let cos_gamma = dot(dir, sun);
    let sin_gamma = length(cross(dir, sun));
    let gamma = sin_gamma.atan2(cos_gamma);
    let f = perez(sky, cos_theta, gamma, cos_gamma);
    let yxy = Vec4::from(sky.zenith).xyz() * f / Vec4::from(sky.perez_zenith).xyz();
    let big_y = yxy.x;
    let x = yxy.y;
    let y = max(yxy.z, MIN_CHROMATICITY_Y);
    let xyz = vec3(x / y * big_y, big_y, (1.0 - x - y) / y * big_y);
    let rgb = xyz_to_linear_srgb(xyz);
    max(rgb, Vec3::splat(0.0)) * sky.sky_scale
}

/// `preetham_sun_disc(sky, dir)`: the sun disc in unit direction `dir`, `sun_radiance` times
/// its weight (1 inside, a linear rim in sin γ, 0 outside and below the horizon), with
/// sin γ = |(d − s) × s|.
pub fn preetham_sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    let sun = Vec4::from(sky.sun_direction).xyz();
    let cos_gamma = dot(dir, sun);
    let sin_gamma = length(cross(dir - sun, sun));
    let ramp =
        clamp((sky.sun_sin_outer - sin_gamma) / (sky.sun_sin_outer - sky.sun_sin_inner), 0.0, 1.0);
    let weight = select(0.0, ramp, cos_gamma > 0.0 && dir.y >= 0.0);
    Vec4::from(sky.sun_radiance).xyz() * weight
}
