//! Mirror of `shaders/shared/optics.wgsl`: arithmetic-only e^x and the water-volume colour.

pub use super::fresnel::fresnel_exact;

use ocean_core::frame::FrameUniforms;

use crate::shaders::wgsl::{Vec3, clamp, ldexp, max, vec3};

/// `EXP_MIN`: `exp_arith`'s arguments are clamped to [EXP_MIN, 0].
pub const EXP_MIN: f32 = -80.0;

/// `exp_arith(x)`: e^x for x ≤ 0 by + − × only (the WGSL's).
pub fn exp_arith(x: f32) -> f32 {
    let z = clamp(x, EXP_MIN, 0.0) * std::f32::consts::LOG2_E;
    let n = (z + 0.5).floor();
    let y = (z - n) * std::f32::consts::LN_2;
    let p = 1.0
        + y * (1.0
            + y * (0.5
                + y * (0.166_666_67
                    + y * (0.041_666_668
                        + y * (0.008_333_334 + y * (0.001_388_888_9 + y * 0.000_198_412_7))))));
    p * ldexp(1.0, n as i32)
}

/// `EQ8_LN_R`: ln 0.30.
pub const EQ8_LN_R: f32 = -1.203_972_8;
/// `EQ8_LN_G`: ln 0.73.
pub const EQ8_LN_G: f32 = -0.314_710_74;
/// `EQ8_LN_B`: ln 0.63.
pub const EQ8_LN_B: f32 = -0.462_035_46;

/// `downwelling()`: the radiance of a white Lambertian surface facing up.
pub fn downwelling(frame: &FrameUniforms) -> Vec3 {
    let cos_sun = max(frame.sun.direction[1], 0.0) * frame.sun.lit;
    Vec3::from(frame.sun.radiance) * (cos_sun * std::f32::consts::FRAC_1_PI)
        + Vec3::from(frame.ambient.sky)
}

/// `water_volume_colour(depth)`.
pub fn water_volume_colour(depth: f32, frame: &FrameUniforms) -> Vec3 {
    if frame.water.volume_model == 0.0 {
        return Vec3::from(frame.water.color);
    }
    let k = frame.water.kd_per_m * max(depth, 0.0);
    downwelling(frame)
        * vec3(exp_arith(k * EQ8_LN_R), exp_arith(k * EQ8_LN_G), exp_arith(k * EQ8_LN_B))
}
