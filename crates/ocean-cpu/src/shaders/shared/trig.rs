//! Mirror of `shaders/shared/trig.wgsl`: (cos 2πp, sin 2πp) by + − × only.

/// `TAU`: f32(2π).
pub const TAU: f32 = 6.283_185_5;

/// `SIN_C3`…`SIN_C9`, `COS_C2`…`COS_C10`: the Taylor coefficients of `cis_turns`.
pub const SIN_C3: f32 = -0.166_666_67;
/// `SIN_C5`.
pub const SIN_C5: f32 = 0.008_333_334;
/// `SIN_C7`.
pub const SIN_C7: f32 = -0.000_198_412_7;
/// `SIN_C9`.
pub const SIN_C9: f32 = 0.000_002_755_731_9;
/// `COS_C2`.
pub const COS_C2: f32 = -0.5;
/// `COS_C4`.
pub const COS_C4: f32 = 0.041_666_668;
/// `COS_C6`.
pub const COS_C6: f32 = -0.001_388_888_9;
/// `COS_C8`.
pub const COS_C8: f32 = 0.000_024_801_587;
/// `COS_C10`.
pub const COS_C10: f32 = -2.755_732e-7;

/// `cis_turns(p)`: (cos 2πp, sin 2πp) for |p| ≤ ½ turn, + − × only (the WGSL's order), as
/// `[x, y]`.
#[inline]
pub fn cis_turns(p: f32) -> [f32; 2] {
    let q = (p * 4.0 + 0.5).floor();
    let x = (p - q * 0.25) * TAU;
    let x2 = x * x;
    let s = x + x * x2 * (SIN_C3 + x2 * (SIN_C5 + x2 * (SIN_C7 + x2 * SIN_C9)));
    let c = 1.0 + x2 * (COS_C2 + x2 * (COS_C4 + x2 * (COS_C6 + x2 * (COS_C8 + x2 * COS_C10))));
    match (q as i32 + 4) & 3 {
        0 => [c, s],
        1 => [-s, c],
        2 => [-c, -s],
        _ => [s, -c],
    }
}
