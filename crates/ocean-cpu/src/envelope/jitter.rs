//! [`Jitter`]: one conformant implementation drawn at random. Each operation takes the exact
//! result of its f32 operands and returns an f32 within the allowance [`super::Iv`] carries
//! (× [`JitterRules::scale`]): half the draws at the allowance's very edge, where an envelope
//! that is too narrow shows first. Subnormal results are flushed at random; an 8-bit store of
//! a non-integral r = v · 255 writes its floor or its ceiling.
//!
//! The draws come from a per-thread generator ([`Jitter::reseed`] before each pixel), so a
//! frame is reproducible for a seed at any number of threads.

use std::cell::Cell;
use std::ops::{Add, Div, Mul, Neg, Sub};

use ocean_core::rng::{SplitMix64, mix64};

use super::interval::{
    ATAN_ULPS, DIV_ULPS, exp2_ulps, f32_ulp, half_ceil, half_floor, half_subnormal, log2_allowance,
};
use super::{ByteRange, Real};

/// The rules a [`Jitter`] draws within.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JitterRules {
    /// The frame's seed (each pixel reseeds from it and its index).
    pub seed: u64,
    /// Multiplies every allowance: 1 for a conformant implementation, 2 for the negative
    /// control (an implementation twice as loose as the rules).
    pub scale: f64,
}

thread_local! {
    static STATE: Cell<(u64, f64)> = const { Cell::new((0, 1.0)) };
}

/// An f32 computed by a random conformant implementation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jitter(pub f32);

impl Jitter {
    /// Restarts this thread's draws for pixel `index` of a frame under `rules`.
    pub fn reseed(rules: JitterRules, index: u64) {
        let mut g = SplitMix64::new(rules.seed ^ index.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        STATE.set((g.next_u64(), rules.scale));
    }
}

/// The next draw in [0, 1) and the scale (for the other random conformant pieces: the
/// texture filter's weights).
pub(crate) fn draw() -> (f64, f64) {
    let (s, scale) = STATE.get();
    let s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
    STATE.set((s, scale));
    let v = mix64(s);
    ((v >> 11) as f64 / (1u64 << 53) as f64, scale)
}

/// An f32 within `allowance` of `exact` (at the edge half the time), rounded toward `exact`
/// so it stays inside; subnormals flushed half the time.
fn within(exact: f64, allowance: f64) -> Jitter {
    if !exact.is_finite() {
        return Jitter(exact as f32);
    }
    let (r, scale) = draw();
    let a = allowance * scale;
    let t = if r < 0.25 {
        exact - a
    } else if r < 0.5 {
        exact + a
    } else {
        exact + (4.0 * r - 3.0) * a
    };
    let mut v = toward(t, exact);
    // No rounding changes a result's sign.
    if (exact >= 0.0) != (v >= 0.0) || (exact <= 0.0) != (v <= 0.0) {
        v = 0.0;
    }
    if v != 0.0 && v.abs() < f32::MIN_POSITIVE && draw().0 < 0.5 {
        v = 0.0;
    }
    Jitter(v)
}

/// `t` rounded to an f32 on the side of `exact`.
fn toward(t: f64, exact: f64) -> f32 {
    let n = t as f32;
    let d = f64::from(n);
    if (d > t && t >= exact) || (d < t && t <= exact) {
        // Rounded away from exact: step back one f32.
        if d > t { n.next_down() } else { n.next_up() }
    } else {
        n
    }
}

/// An f32 operation with `ulps` ULP of allowance.
fn rounded(exact: f64, ulps: f64) -> Jitter {
    within(exact, ulps * f32_ulp(exact))
}

/// Addition, subtraction, multiplication: one of the two f32 neighbours of the exact result
/// (correct rounding either way; a representable result is itself), a subnormal one flushed
/// half the time; past scale 1, the looser [`within`].
fn neighbour(exact: f64) -> Jitter {
    let (r, scale) = draw();
    if scale > 1.0 || !exact.is_finite() {
        return rounded(exact, 1.0);
    }
    let n = exact as f32;
    let d = f64::from(n);
    let v = if d == exact || r < 0.5 {
        n
    } else if d < exact {
        n.next_up()
    } else {
        n.next_down()
    };
    if v != 0.0 && v.abs() < f32::MIN_POSITIVE && draw().0 < 0.5 {
        return Jitter(0.0);
    }
    Jitter(v)
}

impl Add for Jitter {
    type Output = Jitter;
    fn add(self, b: Jitter) -> Jitter {
        neighbour(f64::from(self.0) + f64::from(b.0))
    }
}

impl Sub for Jitter {
    type Output = Jitter;
    fn sub(self, b: Jitter) -> Jitter {
        neighbour(f64::from(self.0) - f64::from(b.0))
    }
}

impl Mul for Jitter {
    type Output = Jitter;
    fn mul(self, b: Jitter) -> Jitter {
        neighbour(f64::from(self.0) * f64::from(b.0))
    }
}

/// Negation is exact (a sign flip).
impl Neg for Jitter {
    type Output = Jitter;
    fn neg(self) -> Jitter {
        Jitter(-self.0)
    }
}

impl Div for Jitter {
    type Output = Jitter;
    fn div(self, b: Jitter) -> Jitter {
        rounded(f64::from(self.0) / f64::from(b.0), DIV_ULPS)
    }
}

impl Real for Jitter {
    type Cond = bool;
    /// A subnormal input is flushed half the time.
    fn lit(v: f32) -> Jitter {
        if v != 0.0 && v.abs() < f32::MIN_POSITIVE && draw().0 < 0.5 {
            return Jitter(0.0);
        }
        Jitter(v)
    }
    fn max(self, b: Jitter) -> Jitter {
        Jitter(self.0.max(b.0))
    }
    fn min(self, b: Jitter) -> Jitter {
        Jitter(self.0.min(b.0))
    }
    /// A subnormal or zero x is flushed (→ 0) half the time.
    fn pow(self, e: Jitter) -> Jitter {
        let x = f64::from(self.0);
        if x == 0.0 || x < f64::from(f32::MIN_POSITIVE) && draw().0 < 0.5 {
            return Jitter(0.0);
        }
        let exact = x.log2();
        let l = within(exact, log2_allowance(exact.abs()));
        let t = f64::from((l * e).0);
        let v = rounded(t.exp2(), exp2_ulps(t));
        Jitter(v.0.max(0.0))
    }
    fn sum_as_written(terms: &[Jitter], _: impl FnOnce(&[Jitter]) -> Jitter) -> Jitter {
        Self::sum(terms)
    }
    fn round(self) -> Jitter {
        Jitter(self.0.round_ties_even())
    }
    /// 1 / inversesqrt(x), each step jittered within its allowance.
    fn sqrt(self) -> Jitter {
        let x = f64::from(self.0);
        if x < f64::from(f32::MIN_POSITIVE) {
            return Jitter(if x < 0.0 { f32::NAN } else { 0.0 });
        }
        let inv = rounded(1.0 / x.sqrt(), 2.0);
        Jitter(1.0) / inv
    }
    fn abs(self) -> Jitter {
        Jitter(self.0.abs())
    }
    fn least(self) -> f64 {
        f64::from(self.0)
    }
    fn frexp_cases(self) -> Option<[Option<(i32, Jitter)>; 2]> {
        let (f, e) = crate::float::frexp(self.0);
        Some([Some((e, Jitter(f))), None])
    }
    fn floor_cases(self) -> Option<[Option<(f32, Jitter)>; 2]> {
        let k = self.0.floor();
        Some([Some((k, self - Jitter(k))), None])
    }
    fn exp(self) -> Jitter {
        let x = f64::from(self.0);
        let v = rounded(x.exp(), exp2_ulps(x));
        Jitter(v.0.max(0.0))
    }
    fn atan2(self, x: Jitter) -> Jitter {
        rounded(f64::from(self.0).atan2(f64::from(x.0)), ATAN_ULPS)
    }
    fn lt(self, b: Jitter) -> bool {
        self.0 < b.0
    }
    fn eq(self, b: Jitter) -> bool {
        self.0 == b.0
    }
    fn hull(self, _: Jitter) -> Jitter {
        self
    }
    fn le(self, b: Jitter) -> bool {
        self.0 <= b.0
    }
    fn select(f: Jitter, t: Jitter, cond: bool) -> Jitter {
        if cond { t } else { f }
    }
    /// A random binary16 neighbour (at scale s, up to s − 1 further binary16 steps either
    /// way: a store looser than the rules); a subnormal one flushed half the time.
    fn store_half(self) -> Jitter {
        let x = f64::from(self.0);
        if !x.is_finite() {
            return self;
        }
        let (lo, hi) = (half_floor(x), half_ceil(x));
        let (r, scale) = draw();
        let extra = (scale - 1.0).max(0.0).round();
        let k = (r * (2.0 * extra + 2.0)).floor() - extra;
        let step = hi - lo;
        let v = if step == 0.0 || !step.is_finite() {
            if draw().0 < 0.5 { lo } else { hi }
        } else {
            lo + k * step
        };
        if half_subnormal(v) && draw().0 < 0.5 {
            return Jitter(0.0);
        }
        Jitter(v as f32)
    }
    /// The terms in a random order, summed left to right or as a balanced tree (at random),
    /// each addition jittered.
    fn sum(terms: &[Jitter]) -> Jitter {
        let mut order: Vec<Jitter> = terms.to_vec();
        for i in (1..order.len()).rev() {
            let j = (draw().0 * (i + 1) as f64) as usize;
            order.swap(i, j.min(i));
        }
        if draw().0 < 0.5 {
            while order.len() > 1 {
                order = order
                    .chunks(2)
                    .map(|p| if p.len() == 2 { p[0] + p[1] } else { p[0] })
                    .collect();
            }
            return order[0];
        }
        let mut s = order[0];
        for &t in &order[1..] {
            s = s + t;
        }
        s
    }
    /// Floor or ceiling of v · 255 (at scale s, up to s − 1 codes further either way).
    fn store_unorm8(self) -> ByteRange {
        let r = f64::from(self.0.clamp(0.0, 1.0)) * 255.0;
        let (d, scale) = draw();
        let extra = (scale - 1.0).max(0.0).round();
        let b = if r.fract() == 0.0 {
            r
        } else {
            r.floor() + (d * (2.0 * extra + 2.0)).floor() - extra
        };
        let b = b.clamp(0.0, 255.0) as u8;
        ByteRange { lo: b, hi: b }
    }
}
