//! Mirror of `shaders/sky/preetham.wgsl` (technique `preetham` of stage `sky`): the clear
//! Preetham sky of [`crate::shaders::shared::preetham`].

pub use crate::shaders::shared::preetham::{MIN_CHROMATICITY_Y, SkyUniforms};

use crate::shaders::shared::preetham::{preetham_radiance, preetham_sun_disc};
use crate::shaders::wgsl::Vec3;

/// `sky_radiance(sky, dir)`.
pub fn sky_radiance(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    preetham_radiance(sky, dir)
}

/// `sun_disc(sky, dir)`.
pub fn sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    preetham_sun_disc(sky, dir)
}
