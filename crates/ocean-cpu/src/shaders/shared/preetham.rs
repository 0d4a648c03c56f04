//! Mirror of `shaders/shared/preetham.wgsl`: the Preetham sky in f32, which the sky
//! techniques `preetham` and `preetham_clouds` are built on. The physics and the f64 reference
//! are `ocean_core::sky`.

pub use ocean_core::sky::SkyUniforms;

use crate::envelope::{Cond, Real, cross3, dot3, length3};
use crate::shaders::wgsl::Vec3;

/// Smallest chromaticity y in xyY → XYZ (`ocean_core::sky::MIN_CHROMATICITY_Y`).
pub const MIN_CHROMATICITY_Y: f32 = 0.0001;

/// Perez et al. (1993) distribution for (Y, x, y):
/// (1 + A exp(B / cos θ)) (1 + C exp(D γ) + E cos² γ).
pub fn perez(sky: &SkyUniforms, cos_theta: f32, gamma: f32, cos_gamma: f32) -> Vec3 {
    Vec3::from(perez_r(sky, cos_theta, gamma, cos_gamma))
}

/// [`perez`] over any [`Real`].
pub fn perez_r<R: Real>(sky: &SkyUniforms, cos_theta: R, gamma: R, cos_gamma: R) -> [R; 3] {
    let l = R::lit;
    let one = l(1.0);
    std::array::from_fn(|i| {
        let (a, b, c) = (l(sky.perez_a[i]), l(sky.perez_b[i]), l(sky.perez_c[i]));
        let (d, e) = (l(sky.perez_d[i]), l(sky.perez_e[i]));
        (one + a * (b / cos_theta).exp())
            * (R::sum_as_written(&[one, c * (d * gamma).exp(), e * cos_gamma * cos_gamma], |t| {
                t[0] + t[1] + t[2]
            }))
    })
}

/// CIE XYZ → linear sRGB, IEC 61966-2-1.
pub fn xyz_to_linear_srgb(xyz: Vec3) -> Vec3 {
    Vec3::from(xyz_to_linear_srgb_r([xyz.x, xyz.y, xyz.z]))
}

/// [`xyz_to_linear_srgb`] over any [`Real`]: each row a sum a GPU may reassociate.
pub fn xyz_to_linear_srgb_r<R: Real>(xyz: [R; 3]) -> [R; 3] {
    const M: [[f32; 3]; 3] =
        [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]];
    M.map(|row| {
        R::sum(&[R::lit(row[0]) * xyz[0], R::lit(row[1]) * xyz[1], R::lit(row[2]) * xyz[2]])
    })
}

/// `preetham_radiance(sky, dir)`: sky radiance without the sun disc in unit direction `dir`
/// (linear sRGB, scene units).
pub fn preetham_radiance(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    Vec3::from(preetham_radiance_r(sky, [dir.x, dir.y, dir.z]))
}

/// [`preetham_radiance`] over any [`Real`].
pub fn preetham_radiance_r<R: Real>(sky: &SkyUniforms, dir: [R; 3]) -> [R; 3] {
    let l = R::lit;
    let sun = [0, 1, 2].map(|i| l(sky.sun_direction[i]));
    let cos_theta = dir[1].max(l(sky.cos_theta_min));
    let cos_gamma = dot3(dir, sun);
    let sin_gamma = length3(cross3(dir, sun));
    // The half-angle form (see the WGSL): atan2's x is 0 only opposite the sun.
    let gamma = l(2.0) * sin_gamma.atan2(l(1.0) + cos_gamma);
    let f = perez_r(sky, cos_theta, gamma, cos_gamma);
    let yxy: [R; 3] = std::array::from_fn(|i| l(sky.zenith[i]) * f[i] / l(sky.perez_zenith[i]));
    let big_y = yxy[0];
    let x = yxy[1];
    let y = yxy[2].max(l(MIN_CHROMATICITY_Y));
    let xyz = [x / y * big_y, big_y, (l(1.0) - x - y) / y * big_y];
    let rgb = xyz_to_linear_srgb_r(xyz);
    rgb.map(|c| c.max(l(0.0)) * l(sky.sky_scale))
}

/// `preetham_sun_disc(sky, dir)`: the sun disc in unit direction `dir`, `sun_radiance` times
/// its weight (1 inside, a linear rim in sin γ, 0 outside and below the horizon), with
/// sin γ = |(d − s) × s|.
pub fn preetham_sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    Vec3::from(preetham_sun_disc_r(sky, [dir.x, dir.y, dir.z]))
}

/// [`preetham_sun_disc`] over any [`Real`].
pub fn preetham_sun_disc_r<R: Real>(sky: &SkyUniforms, dir: [R; 3]) -> [R; 3] {
    let l = R::lit;
    let sun = [0, 1, 2].map(|i| l(sky.sun_direction[i]));
    let cos_gamma = dot3(dir, sun);
    let sin_gamma = length3(cross3([dir[0] - sun[0], dir[1] - sun[1], dir[2] - sun[2]], sun));
    let (outer, inner) = (l(sky.sun_sin_outer), l(sky.sun_sin_inner));
    let ramp = ((outer - sin_gamma) / (outer - inner)).clamp(l(0.0), l(1.0));
    let lit = l(0.0).lt(cos_gamma).and(l(0.0).le(dir[1]));
    let weight = R::select(l(0.0), ramp, lit);
    [0, 1, 2].map(|i| l(sky.sun_radiance[i]) * weight)
}
