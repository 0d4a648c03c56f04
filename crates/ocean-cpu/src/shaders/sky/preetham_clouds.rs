//! Mirror of `shaders/sky/preetham_clouds.wgsl` (technique `preetham_clouds` of stage `sky`,
//! seed 001 eq. 4): the Preetham sky under the cloud layer of `ocean_core::clouds`, whose f32
//! functions are the ones the WGSL writes out.

pub use ocean_core::clouds::{CLOUD_HORIZON_GAIN, CLOUD_OCTAVES, CLOUD_PERIOD};

use crate::shaders::shared::preetham::{SkyUniforms, preetham_radiance, preetham_sun_disc};
use crate::shaders::wgsl::{Vec3, Vec4};

/// `cloud_alpha(sky, dir)`.
pub fn cloud_alpha(sky: &SkyUniforms, dir: Vec3) -> f32 {
    ocean_core::clouds::cloud_alpha(sky.cloud_origin, sky.cloud_color[3], dir.into())
}

/// `sky_radiance(sky, dir)`: eq. 4.
pub fn sky_radiance(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    let alpha = cloud_alpha(sky, dir);
    preetham_radiance(sky, dir) * (1.0 - alpha) + Vec4::from(sky.cloud_color).xyz() * alpha
}

/// `sun_disc(sky, dir)`: the disc behind the cloud.
pub fn sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    preetham_sun_disc(sky, dir) * (1.0 - cloud_alpha(sky, dir))
}
