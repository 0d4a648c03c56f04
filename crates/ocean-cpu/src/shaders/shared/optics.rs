//! Mirror of `shaders/shared/optics.wgsl`: arithmetic-only e^x and the water-volume colour.

pub use super::fresnel::fresnel_exact;

use ocean_core::frame::FrameUniforms;

use crate::envelope::{Real, on_floor};
use crate::shaders::wgsl::{Vec3, ldexp, vec3};

/// `EXP_MIN`: `exp_arith`'s arguments are clamped to [EXP_MIN, 0].
pub const EXP_MIN: f32 = -80.0;

/// `exp_arith(x)`: e^x for x ≤ 0 by + − × only (the WGSL's).
pub fn exp_arith(x: f32) -> f32 {
    exp_arith_r(x)
}

/// [`exp_arith`] over any [`Real`]: where an interval puts z + ½ across an integer, both
/// n's results, united (the same value on either side).
pub fn exp_arith_r<R: Real>(x: R) -> R {
    let l = R::lit;
    let z = x.clamp(l(EXP_MIN), l(0.0)) * l(std::f32::consts::LOG2_E);
    // Past two integers, any n: e^x of a clamped x ≤ 0 lies in [0, 1] (the polynomial's few
    // ULP above it included).
    let any = l(0.0).hull(l(2.0));
    let [e] = on_floor(z + l(0.5), [any], |n, _| {
        let y = (z - l(n)) * l(std::f32::consts::LN_2);
        let p = l(1.0)
            + y * (l(1.0)
                + y * (l(0.5)
                    + y * (l(0.166_666_67)
                        + y * (l(0.041_666_668)
                            + y * (l(0.008_333_334)
                                + y * (l(0.001_388_888_9) + y * l(0.000_198_412_7)))))));
        [p * l(ldexp(1.0, n as i32))]
    });
    e
}

/// `EQ8_LN_R`: ln 0.30.
pub const EQ8_LN_R: f32 = -1.203_972_8;
/// `EQ8_LN_G`: ln 0.73.
pub const EQ8_LN_G: f32 = -0.314_710_74;
/// `EQ8_LN_B`: ln 0.63.
pub const EQ8_LN_B: f32 = -0.462_035_46;

/// `downwelling()`: the radiance of a white Lambertian surface facing up.
pub fn downwelling(frame: &FrameUniforms) -> Vec3 {
    let [x, y, z] = downwelling_r::<f32>(frame);
    vec3(x, y, z)
}

/// [`downwelling`] over any [`Real`].
pub fn downwelling_r<R: Real>(frame: &FrameUniforms) -> [R; 3] {
    let l = R::lit;
    let cos_sun = l(frame.sun.direction[1]).max(l(0.0)) * l(frame.sun.lit);
    let s = cos_sun * l(std::f32::consts::FRAC_1_PI);
    std::array::from_fn(|i| l(frame.sun.radiance[i]) * s + l(frame.ambient.sky[i]))
}

/// `water_volume_colour(depth)`.
pub fn water_volume_colour(depth: f32, frame: &FrameUniforms) -> Vec3 {
    let [x, y, z] = water_volume_colour_r(depth, frame);
    vec3(x, y, z)
}

/// [`water_volume_colour`] over any [`Real`].
pub fn water_volume_colour_r<R: Real>(depth: R, frame: &FrameUniforms) -> [R; 3] {
    let l = R::lit;
    if frame.water.volume_model == 0.0 {
        return frame.water.color.map(l);
    }
    let k = l(frame.water.kd_per_m) * depth.max(l(0.0));
    let d = downwelling_r::<R>(frame);
    let ln = [EQ8_LN_R, EQ8_LN_G, EQ8_LN_B];
    std::array::from_fn(|i| d[i] * exp_arith_r(k * l(ln[i])))
}
