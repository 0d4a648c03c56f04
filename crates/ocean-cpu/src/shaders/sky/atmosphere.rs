//! Mirror of `shaders/sky/atmosphere.wgsl` (technique `atmosphere` of stage `sky`): the
//! single-scattering sky of ocean_core::atmosphere, read from the frame's sky-view table.

use ocean_core::atmosphere::SkyLut;

use crate::shaders::shared::preetham::SkyUniforms;
use crate::shaders::shared::sky_lut::sky_lut_radiance;
use crate::shaders::wgsl::{Vec3, Vec4, clamp, cross, dot, length, select, vec3};

/// `sky_radiance(sky, dir)` (the WGSL reads the stage's `sky_lut`; here it is passed).
pub fn sky_radiance(sky: &SkyUniforms, lut: &SkyLut, dir: Vec3) -> Vec3 {
    let s = sky.sun_direction;
    sky_lut_radiance(lut, dir, vec3(s[0], s[1], s[2]))
}

/// `sun_disc(sky, dir)`: sin γ = |(d − s) × s|.
pub fn sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    let sun = Vec4::from(sky.sun_direction).xyz();
    let cos_gamma = dot(dir, sun);
    let sin_gamma = length(cross(dir - sun, sun));
    let ramp =
        clamp((sky.sun_sin_outer - sin_gamma) / (sky.sun_sin_outer - sky.sun_sin_inner), 0.0, 1.0);
    let weight = select(0.0, ramp, cos_gamma > 0.0 && dir.y >= 0.0);
    Vec4::from(sky.sun_radiance).xyz() * weight
}
