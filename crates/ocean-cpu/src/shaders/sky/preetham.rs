//! Mirror of `shaders/sky/preetham.wgsl` (technique `preetham` of stage `sky`): the Preetham
//! sky in f32. The physics and the f64
//! reference are `ocean_core::sky`.

pub use ocean_core::sky::SkyUniforms;

use crate::shaders::wgsl::{Vec3, clamp, cross, dot, length, select, xyz};

/// Smallest chromaticity y in xyY → XYZ (`ocean_core::sky::MIN_CHROMATICITY_Y`).
pub const MIN_CHROMATICITY_Y: f32 = 0.0001;

/// Perez et al. (1993) distribution for (Y, x, y):
/// (1 + A exp(B / cos θ)) (1 + C exp(D γ) + E cos² γ).
pub fn perez(sky: &SkyUniforms, cos_theta: f32, gamma: f32, cos_gamma: f32) -> Vec3 {
    let a = xyz(sky.perez_a);
    let b = xyz(sky.perez_b);
    let c = xyz(sky.perez_c);
    let d = xyz(sky.perez_d);
    let e = xyz(sky.perez_e);
    std::array::from_fn(|i| {
        (1.0 + a[i] * (b[i] / cos_theta).exp())
            * (1.0 + c[i] * (d[i] * gamma).exp() + e[i] * cos_gamma * cos_gamma)
    })
}

/// CIE XYZ → linear sRGB, IEC 61966-2-1.
pub fn xyz_to_linear_srgb(xyz: Vec3) -> Vec3 {
    let r = 3.2406 * xyz[0] - 1.5372 * xyz[1] - 0.4986 * xyz[2];
    let g = -0.9689 * xyz[0] + 1.8758 * xyz[1] + 0.0415 * xyz[2];
    let b = 0.0557 * xyz[0] - 0.2040 * xyz[1] + 1.0570 * xyz[2];
    [r, g, b]
}

/// Sky radiance without the sun disc in unit direction `dir` (linear sRGB, scene units).
pub fn sky_radiance(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    let sun = xyz(sky.sun_direction);
    let cos_theta = dir[1].max(sky.cos_theta_min);
    let cos_gamma = dot(dir, sun);
    let sin_gamma = length(cross(dir, sun));
    let gamma = sin_gamma.atan2(cos_gamma);
    let f = perez(sky, cos_theta, gamma, cos_gamma);
    let yxy: Vec3 = std::array::from_fn(|i| sky.zenith[i] * f[i] / sky.perez_zenith[i]);
    let big_y = yxy[0];
    let x = yxy[1];
    let y = yxy[2].max(MIN_CHROMATICITY_Y);
    let xyz = [x / y * big_y, big_y, (1.0 - x - y) / y * big_y];
    let rgb = xyz_to_linear_srgb(xyz);
    rgb.map(|c| c.max(0.0) * sky.sky_scale)
}

/// The sun disc in unit direction `dir`: `sun_radiance` times its weight (1 inside, a linear
/// rim in sin γ, 0 outside and below the horizon).
pub fn sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    let sun = xyz(sky.sun_direction);
    let cos_gamma = dot(dir, sun);
    let sin_gamma = length(cross(dir, sun));
    let ramp =
        clamp((sky.sun_sin_outer - sin_gamma) / (sky.sun_sin_outer - sky.sun_sin_inner), 0.0, 1.0);
    let weight = select(0.0, ramp, cos_gamma > 0.0 && dir[1] >= 0.0);
    xyz(sky.sun_radiance).map(|c| c * weight)
}
