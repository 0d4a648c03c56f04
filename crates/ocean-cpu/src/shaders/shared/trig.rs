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
/// cells `on_floor` follows, a p below 2⁴⁶ in magnitude still reduces to 0 or −ulp(p) turn
/// (within [−1, ½] below 2²⁴; p − k is exact for the k so near p, and p + ½ may round up a
/// whole ULP), which `cis_turns` reduces again to within a quarter turn, where both
/// polynomials stay within [−1.0001, 1.0001]. Past 2⁴⁶ the second reduction may leave |x| ≥ π
/// (cos's polynomial reaches −1.0018 at π): anything.
#[inline]
pub fn cis_reduced_r<R: Real>(p: R) -> [R; 2] {
    let l = R::lit;
    let limit = 7.036_874_417_766_4e13; // 2⁴⁶
    let reduced = if p.least() > -limit && p.most() < limit {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envelope::{Iv, Jitter, JitterRules};

    /// A phase interval too wide to follow cell by cell: below 2⁴⁶ bounded by ±1.0001, and
    /// every f32 and random conformant result there inside; past it anything (where the
    /// second reduction may leave |x| ≥ π).
    #[test]
    fn a_wide_reduced_phase_is_bounded_below_two_to_the_46() {
        for (lo, hi) in [(1.0e6, 2.0e6), (3.0e12, 9.0e12), (1.6e7, 1.7e7)] {
            let e = cis_reduced_r(Iv::new(lo, hi));
            assert!(e.iter().all(|c| !c.full && c.lo >= -1.000_11 && c.hi <= 1.000_11), "{e:?}");
            for k in 0..=64u32 {
                let p = (lo + (hi - lo) * f64::from(k) / 64.0) as f32;
                let exact = cis_reduced_r(p);
                assert!((0..2).all(|c| e[c].contains(exact[c])), "{p}: {exact:?} not in {e:?}");
                for seed in 0..4 {
                    Jitter::reseed(JitterRules { seed, scale: 1.0 }, u64::from(k));
                    let j = cis_reduced_r(Jitter(p));
                    assert!((0..2).all(|c| e[c].contains(j[c].0)), "{p}: {j:?} not in {e:?}");
                }
            }
        }
        let far = cis_reduced_r(Iv::new(1.5e14, 3.0e14));
        assert!(far.iter().all(|c| c.full), "{far:?}");
    }
}
