//! Mirror of `shaders/shared/trig.wgsl`: (cos 2πp, sin 2πp) by + − × only, over any
//! [`Real`].

use crate::envelope::{Real, on_floor};

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
    cis_turns_r(p)
}

/// [`cis_turns`] over any [`Real`]. The quadrant is where `floor` puts 4p + ½; where an
/// interval straddles a quadrant's edge both quadrants are taken, and their union stays narrow
/// because both evaluate the same angle there.
#[inline]
pub fn cis_turns_r<R: Real>(p: R) -> [R; 2] {
    let l = R::lit;
    on_floor(p * l(4.0) + l(0.5), unknown_quadrant(p), |q, _| {
        let x = (p - l(q) * l(0.25)) * l(TAU);
        let x2 = x * x;
        let s = x + x * x2 * (l(SIN_C3) + x2 * (l(SIN_C5) + x2 * (l(SIN_C7) + x2 * l(SIN_C9))));
        let c = l(1.0)
            + x2 * (l(COS_C2)
                + x2 * (l(COS_C4) + x2 * (l(COS_C6) + x2 * (l(COS_C8) + x2 * l(COS_C10)))));
        match (q as i32 + 4) & 3 {
            0 => [c, s],
            1 => [-s, c],
            2 => [-c, -s],
            _ => [s, -c],
        }
    })
}

/// `cis_turns(p - floor(p + 0.5))`: the phase reduced to [−½, ½] turn first, as the WGSL
/// writes it wherever a phase may leave that range. Over any [`Real`]: where an interval
/// straddles a half turn, every reduction, united (the same angle, so still narrow). Past the
/// cells `on_floor` follows, any finite p still reduces to within [−1, ½] turn (p − k is exact
/// for the k so near p; past 2²³, p + ½ may round up a whole turn), where both polynomials stay
/// within [−1.0001, 1.0001].
#[inline]
pub fn cis_reduced_r<R: Real>(p: R) -> [R; 2] {
    let l = R::lit;
    let reduced = if p.least().is_finite() && p.most().is_finite() {
        let b = l(-1.0001).hull(l(1.0001));
        [b, b]
    } else {
        [l(f32::NAN); 2]
    };
    on_floor(p + l(0.5), reduced, |k, _| cis_turns_r(p - l(k)))
}

/// What `cis_turns` gives where the bounds cannot tell which quarter turn (or which whole
/// turn) the GPU reduces `p` by, past the two cells `on_floor` follows: whichever it takes,
/// the reduced angle is within an eighth of a turn of 0 (plus the rounding of 4p, under 2⁻⁵
/// of a quarter turn for |p| < 2¹⁶), where both polynomials stay within [−1, 1] but for
/// their own roundings; so each component lies in [−1.0001, 1.0001]. Anything for a larger
/// or unbounded p.
fn unknown_quadrant<R: Real>(p: R) -> [R; 2] {
    let l = R::lit;
    let limit = 65536.0;
    // A scalar never gets here (one cell): the test compiles away for it.
    if R::INTERVAL && p.least() > -limit && p.most() < limit {
        let b = l(-1.0001).hull(l(1.0001));
        [b, b]
    } else {
        [l(f32::NAN); 2]
    }
}
