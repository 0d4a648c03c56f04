//! The fast paths of [`super`] against the direct formulas they replace: the ULP from the
//! binade's exponent, the next power of two, and the rounding of an operation's bounds must
//! give the same bits as the branchy definitions on every kind of input.

use super::*;
use ocean_core::rng::SplitMix64;

/// The ULP by its definition: the binade's exponent, clamped at f32's top binade.
fn ulp_by_definition(m: f64) -> f64 {
    let m = m.abs();
    if !m.is_finite() {
        return f64::INFINITY;
    }
    if m < F32_MIN_NORMAL {
        return f64::from(f32::from_bits(1));
    }
    let e = m.log2().floor() as i32;
    // log2's rounding may misplace a value just under a power of two.
    let e = if 2f64.powi(e) > m { e - 1 } else { e };
    2f64.powi(e.min(127) - 23)
}

fn pow2_above_by_definition(x: f64) -> f64 {
    let e = ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    f64::from_bits(((e + 1 + 1023) as u64) << 52)
}

/// `Iv::rounded` as first written: a NaN test, the magnitude's range, each end widened by
/// its own ULP (or the next binade's), the f64 slack, the sign kept, then stored.
fn rounded_by_definition(lo: f64, hi: f64, ulps: f64) -> Iv {
    if lo.is_nan() || hi.is_nan() {
        return Iv::FULL;
    }
    let m = lo.abs().max(hi.abs());
    if m > F32_MAX {
        return Iv::FULL;
    }
    let l = {
        let w = lo - ulps * ulp_by_definition(lo);
        let b = if lo > 0.0 { pow2_above_by_definition(lo) } else { f64::INFINITY };
        if hi >= b { w.min(b - ulps * ulp_by_definition(b)) } else { w }
    } - lo.abs() * F64_SLACK;
    let h = {
        let w = hi + ulps * ulp_by_definition(hi);
        let b = if hi < 0.0 { -pow2_above_by_definition(-hi) } else { f64::NEG_INFINITY };
        if lo <= b { w.max(b + ulps * ulp_by_definition(b)) } else { w }
    } + hi.abs() * F64_SLACK;
    let l = if lo >= 0.0 { l.max(0.0) } else { l };
    let h = if hi <= 0.0 { h.min(0.0) } else { h };
    if l.is_nan() || h.is_nan() || h > F32_MAX || l < -F32_MAX {
        return Iv::FULL;
    }
    let l = if l > 0.0 && l < F32_MIN_NORMAL { 0.0 } else { l };
    let h = if h < 0.0 && h > -F32_MIN_NORMAL { 0.0 } else { h };
    Iv::new(l, h)
}

/// Values of every kind: 0, f32 and f64 subnormals, powers of two and their neighbours,
/// f32's extremes and just past them, infinities, NaN, and random magnitudes from 2⁻¹⁶⁰ to
/// 2¹³⁰ of either sign.
fn samples(n: usize) -> Vec<f64> {
    let mut v = vec![
        0.0,
        -0.0,
        f64::from(f32::from_bits(1)),
        F32_MIN_NORMAL,
        F32_MIN_NORMAL.next_down(),
        F32_MAX,
        F32_MAX.next_up(),
        2f64.powi(128),
        f64::MIN_POSITIVE / 4.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
    ];
    for e in -150..130 {
        let p = 2f64.powi(e);
        v.extend([p, p.next_down(), p.next_up(), p * (1.0 - 1e-7), p * (1.0 + 1e-7)]);
    }
    let mut g = SplitMix64::new(7);
    while v.len() < n {
        let e = -160.0 + 290.0 * g.next_open_closed();
        let x = 2f64.powf(e);
        v.push(if g.next_open_closed() < 0.5 { -x } else { x });
    }
    let negated: Vec<f64> = v.iter().map(|x| -x).collect();
    v.extend(negated);
    v
}

fn same(a: Iv, b: Iv) -> bool {
    a.full == b.full
        && (a.full || a.lo.to_bits() == b.lo.to_bits() && a.hi.to_bits() == b.hi.to_bits())
}

#[test]
fn ulp_from_the_exponent_is_the_definition() {
    for m in samples(20_000) {
        let (fast, def) = (f32_ulp(m), ulp_by_definition(m));
        assert_eq!(
            fast.to_bits(),
            def.to_bits(),
            "f32_ulp({m:e}) = {fast:e}, by definition {def:e}"
        );
    }
}

#[test]
fn next_power_of_two_is_the_definition() {
    for x in samples(20_000).into_iter().filter(|x| *x > 0.0 && x.is_finite()) {
        assert_eq!(pow2_above(x).to_bits(), pow2_above_by_definition(x).to_bits(), "{x:e}");
        // An f64 subnormal has 2⁻¹⁰²² above it, not the binade's double.
        assert!(pow2_above(x) > x && (x < f64::MIN_POSITIVE || pow2_above(x) / 2.0 <= x), "{x:e}");
    }
}

#[test]
fn rounded_is_the_definition() {
    let xs = samples(3_000);
    let mut g = SplitMix64::new(11);
    let mut checked = 0usize;
    for _ in 0..400_000 {
        let a = xs[(g.next_open_closed() * xs.len() as f64) as usize % xs.len()];
        // Half the pairs close together (one binade, a crossing), half anywhere.
        let b = if g.next_open_closed() < 0.5 {
            a + a.abs() * (g.next_open_closed() - 0.3) * 1e-6
        } else {
            xs[(g.next_open_closed() * xs.len() as f64) as usize % xs.len()]
        };
        let (lo, hi) = if a <= b || b.is_nan() { (a, b) } else { (b, a) };
        for ulps in [1.0, DIV_ULPS, 2.0, ATAN_ULPS] {
            let (fast, def) = (Iv::rounded(lo, hi, ulps), rounded_by_definition(lo, hi, ulps));
            assert!(
                same(fast, def),
                "rounded({lo:e}, {hi:e}, {ulps}) = {fast:?}, by definition {def:?}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 1_600_000);
}

/// A negative control: the comparison above sees a one-ULP change of either end.
#[test]
fn the_comparison_sees_one_bit() {
    let a = Iv::rounded(1.5, 2.5, 1.0);
    assert!(!same(a, Iv::new(a.lo.next_down(), a.hi)));
    assert!(!same(a, Iv::new(a.lo, a.hi.next_up())));
    assert!(!same(a, Iv::FULL));
}
