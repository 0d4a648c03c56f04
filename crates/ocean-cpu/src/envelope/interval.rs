//! [`Iv`]: an f32 value's envelope, [lo, hi] in f64, each operation widened by what the Vulkan
//! precision rules ("Precision and Operation of SPIR-V Instructions") and WGSL's "Floating
//! Point Accuracy" allow it. The bounds are computed in f64 and rounded outward, so the f64
//! arithmetic never narrows them.
//!
//! The rules carried (docs/tolerances.md has the table):
//! - `+ − ×`: either f32 neighbour of the exact result (rounding either way), so 1 ULP; a fused
//!   `a·b + c` is one rounding of the exact value, inside the unfused interval;
//! - `÷`: 2.5 ULP for |divisor| in [2⁻¹²⁶, 2¹²⁶], anything outside;
//! - `pow(x, y)`: exp2(y · log2 x) with log2 within 2⁻²¹ absolute on [0.5, 2] and 3 ULP
//!   elsewhere (the larger of both is taken everywhere), exp2 within 3 + 2|t| ULP;
//! - subnormal results may be flushed to 0;
//! - a result beyond f32's range may be ±∞; an operation the rules leave undefined (0 · ∞,
//!   division by a subnormal, log of a negative) or a possible NaN makes the interval *full*:
//!   any value, NaN included.
//!
//! The ULP of an interval is that of its largest magnitude: every value inside has a ULP no
//! larger, so the widening covers each.

use std::ops::{Add, Div, Mul, Neg, Sub};

use super::{Real, Tri};

/// The envelope of an f32 value: every value a conformant implementation may compute lies in
/// [`lo`, `hi`]; `full` (any value, NaN included) where the rules leave it undefined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iv {
    /// Lower bound (may be −∞).
    pub lo: f64,
    /// Upper bound (may be +∞).
    pub hi: f64,
    /// Any value, NaN included.
    pub full: bool,
}

/// The bytes an 8-bit unorm store may hold, `lo..=hi`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ByteRange {
    /// Smallest byte.
    pub lo: u8,
    /// Largest byte.
    pub hi: u8,
}

impl ByteRange {
    /// Whether `b` is inside.
    pub fn contains(self, b: u8) -> bool {
        (self.lo..=self.hi).contains(&b)
    }
    /// How far `b` lies outside, in codes (0 inside).
    pub fn distance(self, b: u8) -> u8 {
        if b < self.lo { self.lo - b } else { b.saturating_sub(self.hi) }
    }
}

const F32_MAX: f64 = f32::MAX as f64;
pub(crate) const F32_MIN_NORMAL: f64 = f32::MIN_POSITIVE as f64;

const TWO_POW_M21: f64 = 1.0 / (1u64 << 21) as f64;
/// 2⁻¹⁰⁰: below this an interval is a 0 with its slack, for [`Iv::rel_half_width`].
const TINY: f64 = 7.888_609_052_210_118e-31;
/// 2⁻⁵⁰: the f64 roundings of one operation and of its widening, relative to the magnitude.
const F64_SLACK: f64 = 1.0 / (1u64 << 50) as f64;
const TWO_POW_126: f64 = 8.507_059_173_023_462e37;

/// 2^e for |e| < 1023, from the bits.
#[inline]
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// The f32 ULP at magnitude `m` ≥ 0 (the spacing of f32 values in m's binade): 2⁻¹⁴⁹ below
/// the normal range, +∞ for non-finite m.
///
/// Every envelope operation asks for two of these, so it reads the binade off the exponent
/// bits instead of branching on the range: 2^e · 2⁻²³ is exact, and below 2⁻¹²⁶ it falls under
/// the subnormal spacing that `max` keeps.
#[inline]
pub fn f32_ulp(m: f64) -> f64 {
    const EXP: u64 = 0x7ff0_0000_0000_0000;
    // 2¹²⁸'s exponent bits: from there on the binade is past f32's top one.
    const PAST_F32: u64 = (128 + 1023) << 52;
    let binade = m.to_bits() & EXP;
    if binade >= PAST_F32 {
        // f32's top binade ends at 2^128; a magnitude past f32::MAX keeps that binade's ULP.
        return if binade == EXP { f64::INFINITY } else { pow2(127 - 23) };
    }
    (f64::from_bits(binade) * TWO_POW_M23).max(F32_SUBNORMAL_ULP)
}

/// 2⁻²³: an f32 ULP relative to its binade's power of two.
const TWO_POW_M23: f64 = 1.0 / (1u64 << 23) as f64;
/// 2⁻¹⁴⁹: the spacing of f32's subnormals.
const F32_SUBNORMAL_ULP: f64 = 1.401_298_464_324_817e-45;

/// log2's allowance at a result of magnitude up to `m`: the larger of 2⁻²¹ (absolute, for
/// arguments in [0.5, 2]) and 3 ULP (elsewhere).
pub(crate) fn log2_allowance(m: f64) -> f64 {
    TWO_POW_M21.max(3.0 * f32_ulp(m))
}

/// exp2's allowance in ULP of the result for an argument `t`: 3 + 2|t|.
pub(crate) fn exp2_ulps(t: f64) -> f64 {
    3.0 + 2.0 * t.abs()
}

/// atan and atan2's allowance in ULP.
pub(crate) const ATAN_ULPS: f64 = 4096.0;

/// ÷'s allowance in ULP.
pub(crate) const DIV_ULPS: f64 = 2.5;

/// Whether the rules define ÷ for a divisor of magnitude `m`.
pub(crate) fn divisor_defined(m: f64) -> bool {
    (F32_MIN_NORMAL..=TWO_POW_126).contains(&m)
}

impl Iv {
    /// Any value, NaN included.
    pub const FULL: Iv = Iv { lo: f64::NEG_INFINITY, hi: f64::INFINITY, full: true };

    /// The value `v` as an operation reads it (a literal, a uniform, a texel): itself, or 0
    /// for a subnormal (inputs may be flushed too); an infinity or a NaN is anything (WGSL's
    /// finite-math assumption: an implementation may assume neither occurs).
    pub fn point(v: f32) -> Iv {
        if !v.is_finite() {
            return Iv::FULL;
        }
        let v = f64::from(v);
        if v != 0.0 && v.abs() < F32_MIN_NORMAL {
            return Iv::new(v.min(0.0), v.max(0.0));
        }
        Iv { lo: v, hi: v, full: false }
    }

    /// [lo, hi] (lo ≤ hi).
    pub fn new(lo: f64, hi: f64) -> Iv {
        debug_assert!(lo <= hi, "[{lo}, {hi}]");
        Iv { lo, hi, full: false }
    }

    /// Whether the f32 `v` lies inside (a NaN only in a full interval).
    pub fn contains(self, v: f32) -> bool {
        if self.full {
            return true;
        }
        !v.is_nan() && (self.lo..=self.hi).contains(&f64::from(v))
    }

    /// The largest magnitude inside.
    pub fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// The smallest interval holding both.
    pub fn hull(self, o: Iv) -> Iv {
        if self.full || o.full {
            return Iv::FULL;
        }
        Iv::new(self.lo.min(o.lo), self.hi.max(o.hi))
    }

    /// Half the width relative to the largest magnitude (∞ when full or unbounded); `None`
    /// for an interval within 2⁻¹⁰⁰ of 0 (a 0 and its rounding and flushing slack, where a
    /// relative width means nothing).
    pub fn rel_half_width(self) -> Option<f64> {
        if self.full {
            return Some(f64::INFINITY);
        }
        let m = self.magnitude();
        if m < TINY {
            return None;
        }
        Some(0.5 * (self.hi - self.lo) / m)
    }

    /// From bounds `[lo, hi]` that one f64 operation rounded to nearest (each within 2⁻⁵³ of
    /// its magnitude of the exact one), each end widened by `ulps` f32 ULP at twice its own
    /// magnitude, then what f32 storage allows: overflow to ±∞ and flushed subnormals. The
    /// extra 2⁻⁵⁰ of each end's magnitude covers that rounding and the widening's own, so no
    /// outward step is needed per operation.
    #[inline(always)]
    fn rounded(lo: f64, hi: f64, ulps: f64) -> Iv {
        // Written so that the common case (finite ends inside one binade each) runs without a
        // mispredicted branch: every envelope operation ends here.
        // NaN fails both comparisons: a NaN end is anything too.
        if !(lo.abs() <= F32_MAX && hi.abs() <= F32_MAX) {
            // May overflow: under the finite-math assumption, anything.
            return Iv::FULL;
        }
        // Each end by the ULP at its own magnitude, so a wide interval's small end is not
        // widened by the large end's ULP. Moving inward from an end whose magnitude grows
        // (lo > 0, hi < 0), a result past the next power of two B has ULPs twice as large:
        // it is at least B − ulps·ulp(B) from the end's side, which may reach further.
        let mut l = lo - ulps * f32_ulp(lo);
        if lo > 0.0 {
            let b = pow2_above(lo);
            if hi >= b {
                l = l.min(b - ulps * f32_ulp(b));
            }
        }
        let mut h = hi + ulps * f32_ulp(hi);
        if hi < 0.0 {
            let b = -pow2_above(-hi);
            if lo <= b {
                h = h.max(b + ulps * f32_ulp(b));
            }
        }
        let l = l - lo.abs() * F64_SLACK;
        let h = h + hi.abs() * F64_SLACK;
        // No rounding changes a result's sign: a value whose every exact result is ≥ 0 stays
        // ≥ 0 (so the square root of a product of squares is defined), likewise ≤ 0.
        let l = if lo >= 0.0 { l.max(0.0) } else { l };
        let h = if hi <= 0.0 { h.min(0.0) } else { h };
        Iv::stored(l, h)
    }

    /// A result that may pass f32's range is anything (WGSL's finite-math assumption lets an
    /// implementation assume no overflow, and no infinity after it); subnormals may flush to 0.
    #[inline(always)]
    fn stored(lo: f64, hi: f64) -> Iv {
        // NaN fails both comparisons.
        if !(hi <= F32_MAX && lo >= -F32_MAX) {
            return Iv::FULL;
        }
        let lo = if lo > 0.0 && lo < F32_MIN_NORMAL { 0.0 } else { lo };
        let hi = if hi < 0.0 && hi > -F32_MIN_NORMAL { 0.0 } else { hi };
        Iv::new(lo, hi)
    }

    /// log2 of the interval's normal part (`None` where it has none) with the rule's
    /// allowance.
    fn log2_normal(self) -> Option<Iv> {
        if self.hi < F32_MIN_NORMAL {
            return None;
        }
        let (lo, hi) = (self.lo.max(F32_MIN_NORMAL).log2(), self.hi.log2());
        let a = log2_allowance(lo.abs().max(hi.abs()));
        // f64's log2 is within 1 ULP of f64: far inside 2⁻²¹, and the outward steps cover it.
        Some(Iv::stored((lo - a).next_down().next_down(), (hi + a).next_up().next_up()))
    }

    /// exp2 of the interval with the rule's allowance.
    fn exp2(self) -> Iv {
        self.exponential(f64::exp2)
    }

    /// An increasing exponential `f` (exp2, exp) of the interval, each end widened by
    /// 3 + 2|t| ULP of its value at the interval's largest |t| — the lower end's ULP taken one
    /// binade up, which covers the staircase inside; never negative.
    fn exponential(self, f: fn(f64) -> f64) -> Iv {
        if self.full {
            return Iv::FULL;
        }
        let ulps = exp2_ulps(self.magnitude());
        let (lo, hi) = (f(self.lo), f(self.hi));
        let lo = (lo - ulps * f32_ulp(2.0 * lo)).next_down().next_down().max(0.0);
        let hi = (hi + ulps * f32_ulp(hi)).next_up().next_up();
        Iv::stored(lo, hi)
    }
}

const HALF_MAX: f64 = 65504.0;
const HALF_MIN_NORMAL: f64 = 6.103_515_625e-5; // 2⁻¹⁴

/// A lower bound a refinement leaves: a positive subnormal one is 0 (a GPU may flush the
/// value it stands for).
fn unflushed(lo: f64) -> f64 {
    if lo > 0.0 && lo < F32_MIN_NORMAL { 0.0 } else { lo }
}

/// The least power of two above `x` > 0 (where f32's ULP doubles).
#[inline(always)]
fn pow2_above(x: f64) -> f64 {
    // One more in the exponent field: 2^(e + 1), also for an f64 subnormal (e = −1023).
    f64::from_bits((x.to_bits() & 0x7ff0_0000_0000_0000) + (1 << 52))
}

/// The spacing of binary16 values at magnitude `a` < 65536.
fn half_spacing(a: f64) -> f64 {
    if a < HALF_MIN_NORMAL {
        return pow2(-24);
    }
    let e = ((a.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    pow2(e.min(15) - 10)
}

/// The largest binary16 value ≤ x (−∞ below −65504).
pub(crate) fn half_floor(x: f64) -> f64 {
    if x < 0.0 {
        return -half_ceil(-x);
    }
    if x >= HALF_MAX {
        return if x.is_infinite() { x } else { HALF_MAX };
    }
    let s = half_spacing(x);
    (x / s).floor() * s
}

/// The smallest binary16 value ≥ x (+∞ above 65504).
pub(crate) fn half_ceil(x: f64) -> f64 {
    if x < 0.0 {
        return -half_floor(-x);
    }
    if x > HALF_MAX {
        return f64::INFINITY;
    }
    let s = half_spacing(x);
    (x / s).ceil() * s
}

/// Whether a binary16 value is subnormal (a store may flush it to 0).
pub(crate) fn half_subnormal(x: f64) -> bool {
    x != 0.0 && x.abs() < HALF_MIN_NORMAL
}

/// The four products' (or quotients') hull, each rounded to nearest in f64 (the caller's
/// [`Iv::rounded`] covers that). `f` must be monotone in each argument on each sign-constant
/// piece (× and ÷ are), so with a point operand two corners decide it.
#[inline(always)]
fn corners(a: Iv, b: Iv, f: impl Fn(f64, f64) -> f64) -> (f64, f64) {
    let (x, y) = if b.lo == b.hi {
        (f(a.lo, b.lo), f(a.hi, b.lo))
    } else if a.lo == a.hi {
        (f(a.lo, b.lo), f(a.lo, b.hi))
    } else {
        let c = [f(a.lo, b.lo), f(a.lo, b.hi), f(a.hi, b.lo), f(a.hi, b.hi)];
        // `|` rather than `||`: four compares, no branch between them.
        if c[0].is_nan() | c[1].is_nan() | c[2].is_nan() | c[3].is_nan() {
            return (f64::NAN, f64::NAN);
        }
        return (c[0].min(c[1]).min(c[2].min(c[3])), c[0].max(c[1]).max(c[2].max(c[3])));
    };
    if x.is_nan() | y.is_nan() {
        return (f64::NAN, f64::NAN);
    }
    (x.min(y), x.max(y))
}

impl Add for Iv {
    type Output = Iv;
    #[inline(always)]
    fn add(self, b: Iv) -> Iv {
        if self.full || b.full {
            return Iv::FULL;
        }
        Iv::rounded(self.lo + b.lo, self.hi + b.hi, 1.0)
    }
}

impl Sub for Iv {
    type Output = Iv;
    #[inline(always)]
    fn sub(self, b: Iv) -> Iv {
        if self.full || b.full {
            return Iv::FULL;
        }
        Iv::rounded(self.lo - b.hi, self.hi - b.lo, 1.0)
    }
}

impl Mul for Iv {
    type Output = Iv;
    #[inline(always)]
    fn mul(self, b: Iv) -> Iv {
        if self.full || b.full {
            return Iv::FULL;
        }
        let (lo, hi) = corners(self, b, |x, y| x * y);
        Iv::rounded(lo, hi, 1.0)
    }
}

/// Negation is exact (a sign flip).
impl Neg for Iv {
    type Output = Iv;
    #[inline(always)]
    fn neg(self) -> Iv {
        Iv { lo: -self.hi, hi: -self.lo, full: self.full }
    }
}

impl Div for Iv {
    type Output = Iv;
    #[inline(always)]
    fn div(self, b: Iv) -> Iv {
        if self.full || b.full || b.lo <= 0.0 && b.hi >= 0.0 {
            return Iv::FULL;
        }
        let (m_lo, m_hi) = (b.lo.abs().min(b.hi.abs()), b.magnitude());
        if !divisor_defined(m_lo) || !divisor_defined(m_hi) {
            return Iv::FULL;
        }
        let (lo, hi) = corners(self, b, |x, y| x / y);
        Iv::rounded(lo, hi, DIV_ULPS)
    }
}

impl Real for Iv {
    type Cond = Tri;
    fn lit(v: f32) -> Iv {
        Iv::point(v)
    }
    /// SPIR-V's FMax is undefined for a NaN operand: a full operand gives a full result.
    fn max(self, b: Iv) -> Iv {
        if self.full || b.full {
            return Iv::FULL;
        }
        Iv::new(self.lo.max(b.lo), self.hi.max(b.hi))
    }
    fn min(self, b: Iv) -> Iv {
        if self.full || b.full {
            return Iv::FULL;
        }
        Iv::new(self.lo.min(b.lo), self.hi.min(b.hi))
    }
    /// exp2(e · log2 x) over x's normal part; where x may be 0 or subnormal (flushed, or
    /// with log2 in [−149, −126]) and e > 0, also anything from 0 to what that gives.
    fn pow(self, e: Iv) -> Iv {
        if self.full || e.full || self.lo < 0.0 {
            return Iv::FULL;
        }
        let normal = self.log2_normal().map(|l| (l * e).exp2());
        if self.lo >= F32_MIN_NORMAL {
            return normal.unwrap_or(Iv::FULL);
        }
        if e.lo <= 0.0 {
            // pow(0, e ≤ 0) is undefined.
            return Iv::FULL;
        }
        // Flushed: 0; kept: log2 x in [−149, −126], so up to exp2(−126 e) and its allowance.
        let a = log2_allowance(149.0);
        let tail = Iv::new(0.0, (Iv::new(-149.0 - a, -126.0 + a) * e).exp2().hi);
        normal.map_or(tail, |n| n.hull(tail))
    }
    /// Either binary16 neighbour of each end (rounding either way; past 65504, 65504 or ∞),
    /// subnormals possibly flushed to 0.
    fn store_half(self) -> Iv {
        if self.full {
            return Iv::FULL;
        }
        let mut lo = half_floor(self.lo);
        let mut hi = half_ceil(self.hi);
        if lo > 0.0 && half_subnormal(lo) {
            lo = 0.0;
        }
        if hi < 0.0 && half_subnormal(hi) {
            hi = 0.0;
        }
        Iv::new(lo, hi)
    }
    /// The exact sum's interval widened by (n − 1) ULP of the sum of the terms' magnitudes
    /// (raised by the roundings a computed partial sum may add to it): every partial sum of
    /// any order of evaluation is no larger, so each of the n − 1 roundings errs by at most one
    /// such ULP, plus 2⁻¹²⁶ for a flushed subnormal partial — the bound holds for every
    /// reassociation and fusion.
    fn sum(terms: &[Iv]) -> Iv {
        if terms.iter().any(|t| t.full) {
            return Iv::FULL;
        }
        let (mut lo, mut hi, mut mag) = (0.0f64, 0.0f64, 0.0f64);
        for t in terms {
            lo = (lo + t.lo).next_down();
            hi = (hi + t.hi).next_up();
            mag = (mag + t.magnitude()).next_up();
        }
        // A computed partial sum may exceed the magnitudes' sum by its roundings (each under
        // 2⁻²³ of it), so may round across a power of two, its ULP doubling there; or it may
        // be flushed from the subnormal range: the ULP at the magnitude so raised, and 2⁻¹²⁶
        // per addition.
        let adds = terms.len().saturating_sub(1) as f64;
        let raised = mag * (1.0 + (adds + 1.0) * 2.0 * f64::from(f32::EPSILON));
        let u = adds * (f32_ulp(raised) + F32_MIN_NORMAL);
        if lo.is_nan() || hi.is_nan() {
            return Iv::FULL;
        }
        // No order of the additions and no rounding changes the sign of a sum of terms of one
        // sign: every partial sum keeps it (so the root of a sum of squares is defined).
        let (l, h) = ((lo - u).next_down(), (hi + u).next_up());
        let l = if terms.iter().all(|t| t.lo >= 0.0) { l.max(0.0) } else { l };
        let h = if terms.iter().all(|t| t.hi <= 0.0) { h.min(0.0) } else { h };
        Iv::stored(l, h)
    }
    fn sum_as_written(terms: &[Iv], _: impl FnOnce(&[Iv]) -> Iv) -> Iv {
        Self::sum(terms)
    }
    fn round(self) -> Iv {
        if self.full {
            return Iv::FULL;
        }
        Iv::new(self.lo.round_ties_even(), self.hi.round_ties_even())
    }
    /// 1 / inversesqrt(x): inversesqrt within 2 ULP, the division within 2.5 ULP; a 0 or
    /// subnormal argument (inversesqrt ∞, or flushed) gives 0.
    fn sqrt(self) -> Iv {
        if self.full || self.lo < 0.0 {
            return Iv::FULL;
        }
        if self.hi == 0.0 {
            // inversesqrt(0) = ∞ and 1/∞ = 0.
            return Iv::new(0.0, 0.0);
        }
        let normal = (self.hi >= F32_MIN_NORMAL).then(|| {
            let lo = self.lo.max(F32_MIN_NORMAL);
            let inv =
                Iv::rounded((1.0 / self.hi.sqrt()).next_down(), (1.0 / lo.sqrt()).next_up(), 2.0);
            Iv::point(1.0) / inv
        });
        let tiny = (self.lo < F32_MIN_NORMAL)
            .then(|| Iv::new(0.0, (F32_MIN_NORMAL.sqrt() * (1.0 + 2f64.powi(-20))).next_up()));
        match (normal, tiny) {
            (Some(n), Some(t)) => n.hull(t),
            (Some(n), None) => n,
            (None, Some(t)) => t,
            (None, None) => Iv::FULL,
        }
    }
    fn abs(self) -> Iv {
        if self.full {
            Iv::FULL
        } else if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            Iv::new(-self.hi, -self.lo)
        } else {
            Iv::new(0.0, self.magnitude())
        }
    }
    /// The fraction over each cell is `x − k` on the part of the interval in [k, k + 1),
    /// with the subtraction's rounding (exact for nearby values, but the rules allow one ULP).
    fn sq(self) -> Iv {
        if self.full {
            return Iv::FULL;
        }
        let (a, b) = (self.lo.abs(), self.hi.abs());
        let lo = if self.lo <= 0.0 && self.hi >= 0.0 { 0.0 } else { a.min(b) * a.min(b) };
        Iv::rounded(lo, a.max(b) * a.max(b), 1.0)
    }
    const INTERVAL: bool = true;
    fn least(self) -> f64 {
        if self.full { f64::NEG_INFINITY } else { self.lo }
    }
    fn within(self, lo: f64, hi: f64) -> Iv {
        // Anything stays anything: it may stand for an overflow, which the bounds know
        // nothing of.
        if self.full {
            return self;
        }
        let (l, h) = (unflushed(self.lo.max(lo)), self.hi.min(hi));
        if l <= h { Iv::new(l, h) } else { self }
    }
    fn frexp_cases(self) -> Option<[Option<(i32, Iv)>; 2]> {
        if self.full
            || self.lo.is_nan()
            || self.lo < f64::from(f32::MIN_POSITIVE)
            || !self.hi.is_finite()
        {
            return None;
        }
        let binade = |v: f64| v.log2().floor() as i32 + 1;
        // log2's rounding may misplace an exact power of two: settle it on the fraction.
        let fix = |v: f64, e: i32| {
            let f = v / 2f64.powi(e);
            if f >= 1.0 {
                e + 1
            } else if f < 0.5 {
                e - 1
            } else {
                e
            }
        };
        let (e0, e1) = (fix(self.lo, binade(self.lo)), fix(self.hi, binade(self.hi)));
        let case = |e: i32, lo: f64, hi: f64| {
            let s = 2f64.powi(e);
            (e, Iv::new(lo / s, hi / s))
        };
        if e0 == e1 {
            Some([Some(case(e0, self.lo, self.hi)), None])
        } else if e1 == e0 + 1 {
            let edge = 2f64.powi(e0);
            Some([Some(case(e0, self.lo, edge.next_down())), Some(case(e1, edge, self.hi))])
        } else {
            None
        }
    }
    fn floor_cases(self) -> Option<[Option<(f32, Iv)>; 2]> {
        if self.full || !self.lo.is_finite() || !self.hi.is_finite() {
            return None;
        }
        let (k0, k1) = (self.lo.floor(), self.hi.floor());
        let cell = |k: f64, lo: f64, hi: f64| (k as f32, Iv::new(lo, hi) - Iv::point(k as f32));
        if k0 == k1 {
            Some([Some(cell(k0, self.lo, self.hi)), None])
        } else if k1 == k0 + 1.0 {
            Some([Some(cell(k0, self.lo, k1.next_down())), Some(cell(k1, k1, self.hi))])
        } else {
            None
        }
    }
    /// [e^lo, e^hi] with 3 + 2|x| ULP (as exp2).
    fn exp(self) -> Iv {
        self.exponential(f64::exp)
    }
    /// For y ≥ 0 atan2 is monotone in each argument on every box that keeps x on one side
    /// of 0 (decreasing in x; in y as the sign of x), so the corners bound it; 4096 ULP of the
    /// largest magnitude. A y that may be 0 or subnormal counts as 0 there (atan2(0, x) is
    /// defined for x ≠ 0). Where the rule does not hold (y possibly negative or never normal,
    /// |x| reaching below 2⁻¹²⁶ or past 2¹²⁶) the result is full.
    fn atan2(self, x: Iv) -> Iv {
        // The 4096 ULP hold for |x| in [2⁻¹²⁶, 2¹²⁶] and a normal y; elsewhere undefined.
        let x_tiny = x.lo < F32_MIN_NORMAL && x.hi > -F32_MIN_NORMAL;
        if self.full || x.full || self.hi < F32_MIN_NORMAL || x_tiny || x.magnitude() > TWO_POW_126
        {
            return Iv::FULL;
        }
        if self.lo < 0.0 {
            return Iv::FULL;
        }
        // A y that may be 0 or subnormal (flushed to 0) with x away from 0: atan2(0, x) is 0
        // or π (defined: only atan2(0, 0) is not), and the rule's ULP at a result near 0 are
        // subnormal, so 2⁻¹²⁶ covers them below.
        let y_lo = if self.lo < F32_MIN_NORMAL { 0.0 } else { self.lo };
        let c = [y_lo.atan2(x.lo), y_lo.atan2(x.hi), self.hi.atan2(x.lo), self.hi.atan2(x.hi)];
        let lo = c.iter().copied().fold(f64::INFINITY, f64::min).next_down();
        let hi = c.iter().copied().fold(f64::NEG_INFINITY, f64::max).next_up();
        let r = Iv::rounded(lo, hi, ATAN_ULPS);
        if y_lo == 0.0 && !r.full { Iv::new(r.lo - F32_MIN_NORMAL, r.hi) } else { r }
    }
    fn lt(self, b: Iv) -> Tri {
        if self.full || b.full {
            Tri::Either
        } else if self.hi < b.lo {
            Tri::True
        } else if self.lo >= b.hi {
            Tri::False
        } else {
            Tri::Either
        }
    }
    fn eq(self, b: Iv) -> Tri {
        if self.full || b.full {
            Tri::Either
        } else if self.lo == self.hi && b.lo == b.hi && self.lo == b.lo {
            Tri::True
        } else if self.hi < b.lo || self.lo > b.hi {
            Tri::False
        } else {
            Tri::Either
        }
    }
    fn hull(self, b: Iv) -> Iv {
        Iv::hull(self, b)
    }
    fn le(self, b: Iv) -> Tri {
        if self.full || b.full {
            Tri::Either
        } else if self.hi <= b.lo {
            Tri::True
        } else if self.lo > b.hi {
            Tri::False
        } else {
            Tri::Either
        }
    }
    fn select(f: Iv, t: Iv, cond: Tri) -> Iv {
        match cond {
            Tri::True => t,
            Tri::False => f,
            Tri::Either => f.hull(t),
        }
    }
    /// Vulkan's conversion to unorm: clamp to [0, 1], then r = v · 255 becomes "one of the two
    /// integers closest to r" (rounding to nearest is only recommended), so a non-integral r
    /// may give its floor or its ceiling.
    fn store_unorm8(self) -> ByteRange {
        if self.full {
            return ByteRange { lo: 0, hi: 255 };
        }
        let r_lo = (self.lo.clamp(0.0, 1.0) * 255.0).next_down();
        let r_hi = (self.hi.clamp(0.0, 1.0) * 255.0).next_up();
        // An exactly integral r is stored exactly; the outward step above makes that
        // unreachable for non-point bounds, as it must: only a point is known integral.
        let (c_lo, c_hi) = (self.lo.clamp(0.0, 1.0), self.hi.clamp(0.0, 1.0));
        let (lo, hi) = if c_lo == c_hi && (c_lo * 255.0).fract() == 0.0 {
            let b = (c_lo * 255.0) as u8;
            (b, b)
        } else {
            (r_lo.floor().max(0.0) as u8, r_hi.ceil().min(255.0) as u8)
        };
        ByteRange { lo, hi }
    }
}

#[cfg(test)]
#[path = "interval_tests.rs"]
mod tests;
