//! Mirror of `shaders/sky/preetham_clouds.wgsl` (technique `preetham_clouds` of stage `sky`,
//! seed 001 eq. 4): the Preetham sky under the cloud layer of `ocean_core::clouds` (whose f32
//! functions, written in the same order, give the CPU's physics the same clouds), over any
//! [`Real`].

pub use ocean_core::clouds::{CLOUD_HORIZON_GAIN, CLOUD_OCTAVES, CLOUD_PERIOD, cloud_hash};

use crate::envelope::{Real, choose, on_floor};
use crate::shaders::shared::preetham::{SkyUniforms, preetham_radiance_r, preetham_sun_disc_r};
use crate::shaders::wgsl::Vec3;

/// `cloud_value_noise(x, z, octave)`: the lattice cell is where `floor` puts x and z (every
/// cell, united, where an interval crosses lattice lines — the noise is continuous there);
/// past [`on_floor`]'s cells, a blend of hashes in [0, 1) by weights in [0, 1] (a few
/// roundings past it at most).
pub fn cloud_value_noise_r<R: Real>(x: R, z: R, octave: u32) -> R {
    let l = R::lit;
    let full = [l(-1e-6).hull(l(1.0 + 1e-6))];
    let [v] = on_floor(x, full, |fx, tx| {
        on_floor(z, full, |fz, tz| {
            let (i, j) = (fx as i32, fz as i32);
            let ux = tx * tx * (l(3.0) - l(2.0) * tx);
            let uz = tz * tz * (l(3.0) - l(2.0) * tz);
            let a = l(cloud_hash(i, j, octave));
            let b = l(cloud_hash(i.wrapping_add(1), j, octave));
            let c = l(cloud_hash(i, j.wrapping_add(1), octave));
            let d = l(cloud_hash(i.wrapping_add(1), j.wrapping_add(1), octave));
            let ab = a + (b - a) * ux;
            let cd = c + (d - c) * ux;
            [ab + (cd - ab) * uz]
        })
    });
    v
}

/// `cloud_fbm(x, z)`: five octaves, weights 1/2 … 1/32, over their sum.
pub fn cloud_fbm_r<R: Real>(x: R, z: R) -> R {
    let mut sum = R::lit(0.0);
    let (mut amp, mut freq) = (0.5f32, 1.0f32);
    for o in 0..CLOUD_OCTAVES {
        let f = R::lit(freq);
        sum = sum + R::lit(amp) * cloud_value_noise_r(x * f, z * f, o);
        amp *= 0.5;
        freq *= 2.0;
    }
    sum / R::lit(0.968_75)
}

/// `cloud_alpha(sky, dir)` over any [`Real`].
pub fn cloud_alpha_r<R: Real>(sky: &SkyUniforms, dir: [R; 3]) -> R {
    let l = R::lit;
    let origin = sky.cloud_origin;
    let mean = l(sky.cloud_color[3]);
    if origin[2] <= 0.0 {
        return l(0.0);
    }
    choose(
        dir[1].le(l(0.0)),
        || l(0.0),
        || {
            let w = (dir[1] * l(CLOUD_HORIZON_GAIN)).clamp(l(0.0), l(1.0));
            choose(
                w.eq(l(0.0)),
                || mean,
                || {
                    let t = l(origin[2]) / dir[1];
                    let fbm = cloud_fbm_r(l(origin[0]) + dir[0] * t, l(origin[1]) + dir[2] * t);
                    let a = ((fbm - l(origin[3])) * l(4.0)).clamp(l(0.0), l(1.0));
                    a * w + mean * (l(1.0) - w)
                },
            )
        },
    )
}

/// `cloud_alpha(sky, dir)`.
pub fn cloud_alpha(sky: &SkyUniforms, dir: Vec3) -> f32 {
    cloud_alpha_r(sky, [dir.x, dir.y, dir.z])
}

/// `sky_radiance(sky, dir)`: eq. 4.
pub fn sky_radiance(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    Vec3::from(sky_radiance_r(sky, [dir.x, dir.y, dir.z]))
}

/// [`sky_radiance`] over any [`Real`].
pub fn sky_radiance_r<R: Real>(sky: &SkyUniforms, dir: [R; 3]) -> [R; 3] {
    let alpha = cloud_alpha_r(sky, dir);
    let p = preetham_radiance_r(sky, dir);
    let one = R::lit(1.0);
    std::array::from_fn(|c| p[c] * (one - alpha) + R::lit(sky.cloud_color[c]) * alpha)
}

/// `sun_disc(sky, dir)`: the disc behind the cloud.
pub fn sun_disc(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    Vec3::from(sun_disc_r(sky, [dir.x, dir.y, dir.z]))
}

/// [`sun_disc`] over any [`Real`].
pub fn sun_disc_r<R: Real>(sky: &SkyUniforms, dir: [R; 3]) -> [R; 3] {
    let alpha = cloud_alpha_r(sky, dir);
    let d = preetham_sun_disc_r(sky, dir);
    d.map(|c| c * (R::lit(1.0) - alpha))
}
