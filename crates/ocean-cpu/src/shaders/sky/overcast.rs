//! Mirror of `shaders/sky/overcast.wgsl` (technique `overcast` of stage `sky`): the CIE
//! standard overcast sky (Moon & Spencer 1942; CIE S 011/E:2003 sky type 1), grey, with the
//! clear sky's zenith luminance and no sun disc.

use crate::envelope::Real;
use crate::shaders::shared::preetham::SkyUniforms;
use crate::shaders::wgsl::Vec3;

/// `sky_radiance(sky, dir)` over any [`Real`]: L_z (1 + 2 cos θ) / 3 in every channel, cos θ
/// clamped below at the horizon.
pub fn sky_radiance_r<R: Real>(sky: &SkyUniforms, dir: [R; 3]) -> [R; 3] {
    let l = R::lit;
    let cos_theta = dir[1].max(l(sky.cos_theta_min));
    let luminance = l(sky.zenith[0]) * (l(1.0) + l(2.0) * cos_theta) / l(3.0);
    [luminance * l(sky.sky_scale); 3]
}

/// `sky_radiance(sky, dir)`.
pub fn sky_radiance(sky: &SkyUniforms, dir: Vec3) -> Vec3 {
    Vec3::from(sky_radiance_r(sky, [dir.x, dir.y, dir.z]))
}

/// `sun_disc(sky, dir)`: none under the cloud deck.
pub fn sun_disc(_sky: &SkyUniforms, _dir: Vec3) -> Vec3 {
    Vec3::splat(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shaders::wgsl::vec3;

    fn sky() -> SkyUniforms {
        let params = ocean_core::sky::SkyParams::new([0.3, 0.5, -1.0], 2.5, [1.0; 3], 5.0);
        ocean_core::sky::PreethamSky::new(params.unwrap()).uniforms()
    }

    /// The zenith's luminance in scene units, from the uniforms by f64 (the formula, apart
    /// from the mirror).
    fn zenith(sky: &SkyUniforms) -> f64 {
        f64::from(sky.zenith[0]) * f64::from(sky.sky_scale)
    }

    #[test]
    fn is_moon_and_spencer_grey_and_a_third_of_the_zenith_at_the_horizon() {
        let s = sky();
        let lz = zenith(&s);
        assert!(lz > 0.0);
        for deg in [0.0f64, 10.0, 30.0, 45.0, 60.0, 89.0, 90.0] {
            let (sin, cos) = deg.to_radians().sin_cos();
            let dir = vec3(sin as f32, cos as f32, 0.0);
            let got = sky_radiance(&s, dir);
            assert!(got.x == got.y && got.y == got.z, "{deg}°: not grey: {got:?}");
            let want = lz * (1.0 + 2.0 * cos.max(f64::from(s.cos_theta_min))) / 3.0;
            let rel = (f64::from(got.x) - want).abs() / want;
            assert!(rel < 4.0 * f64::from(f32::EPSILON), "{deg}°: {} against {want}", got.x);
        }
        // Below the horizon: the horizon's value (the clamp), not less.
        let below = sky_radiance(&s, vec3(0.8, -0.6, 0.0)).x;
        let horizon = sky_radiance(&s, vec3(1.0, 0.0, 0.0)).x;
        assert_eq!(below, horizon);
        assert_eq!(sun_disc(&s, vec3(0.0, 1.0, 0.0)), Vec3::splat(0.0));
    }

    /// The CIE overcast sky's illuminance on a horizontal plane, ∫ L cos θ dω = 7π L_z / 9
    /// (Moon & Spencer's distribution integrated by hand), against the mirror integrated
    /// numerically: midpoint rule in cos θ (the integrand is polynomial in it); a wrong
    /// weight or a missing third fails by far more than the 1e-4 allowed.
    #[test]
    fn horizontal_illuminance_is_seven_ninths_pi_zenith_luminance() {
        let s = sky();
        let n = 4000;
        let mut e = 0.0;
        for i in 0..n {
            let mu = (i as f64 + 0.5) / n as f64;
            let dir = vec3((1.0 - mu * mu).sqrt() as f32, mu as f32, 0.0);
            // dω = 2π dμ over the azimuth (the sky has none).
            e += f64::from(sky_radiance(&s, dir).y) * mu * 2.0 * std::f64::consts::PI / n as f64;
        }
        let want = 7.0 * std::f64::consts::PI / 9.0 * zenith(&s);
        // The clamp at cos θ_min = 0.01 adds 2π·(2/3)·L_z·0.01³/6 ≈ 6e-7 of it.
        assert!((e - want).abs() / want < 1e-4, "E_h = {e}, 7π L_z / 9 = {want}");
    }
}
