//! Mirror of `shaders/sky/atmosphere.wgsl` (technique `atmosphere` of stage `sky`): the
//! single-scattering sky of ocean_core::atmosphere, read from the frame's sky-view table.

use ocean_core::atmosphere::SkyLut;

use crate::shaders::shared::preetham::SkyUniforms;
use crate::shaders::shared::sky_lut::sky_lut_radiance;
use crate::shaders::wgsl::{Vec3, vec3};

/// `sky_radiance(sky, dir)` (the WGSL reads the stage's `sky_lut`; here it is passed).
pub fn sky_radiance(sky: &SkyUniforms, lut: &SkyLut, dir: Vec3) -> Vec3 {
    let s = sky.sun_direction;
    sky_lut_radiance(lut, dir, vec3(s[0], s[1], s[2]))
}

/// `sun_disc(sky, dir)`: Preetham's disc with the atmosphere's sun radiance.
pub fn sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    crate::shaders::shared::preetham::preetham_sun_disc(sky, dir)
}
