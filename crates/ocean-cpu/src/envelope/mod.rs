//! The oracle's answer for a hardware GPU: per texel, the interval in which any conformant
//! implementation of the same WGSL must land (docs/tolerances.md).
//!
//! A mirror written over [`Real`] serves three scalar types:
//! - `f32`: the exact frame, lavapipe's arithmetic, bit for bit (what every mirror computed
//!   before; monomorphised, so no slower);
//! - [`Iv`]: the envelope — each operation's result widened by the error the Vulkan and WGSL
//!   precision rules allow it, so the interval holds every conformant result;
//! - [`Af`]: the same envelope in affine arithmetic, an interval cut by a form that keeps the
//!   correlations intervals drop (the water's fragment shader and its texture reads);
//! - [`Jitter`]: one conformant implementation drawn at random (each rounding, each
//!   transcendental's error, each rounding of the 8-bit store chosen within the rules, or
//!   `scale` times the rules for the negative control): the envelope's soundness test without
//!   hardware.
//!
//! Passes whose mirrors run over [`Real`]: `sky` (all three techniques, with the camera's
//! view ray), `tonemap`, `bloom`, `waves` (with `shared/trig.wgsl`), `foam`'s field (with
//! the Gerstner Jacobian), `spray`'s step, `wave_mips`, `fresnel_table` (with `shared/fresnel.wgsl`), and
//! with the rasteriser's envelope ([`raster`]) `shadow_map`, `objects`' reflection and
//! refraction maps and `water` (its configurations `shaders::water::real::carried` names, at
//! the device's [`Precision`]). The others have no envelope yet; `ocean compare --tolerance
//! envelope` reports their resources as not judged.

mod affine;
pub mod affine_filter;
pub mod filter;
mod interval;
mod jitter;
pub mod raster;

use std::ops::{Add, Div, Mul, Neg, Sub};

use ocean_core::frame_format::FrameFormat;

pub use affine::Af;
pub use interval::{ByteRange, Iv, f32_ulp};
pub use jitter::{Jitter, JitterRules};

/// What a device guarantees where Vulkan leaves the precision to the implementation: its
/// `subPixelPrecisionBits`, `subTexelPrecisionBits` and `mipmapPrecisionBits` (each at least
/// 4). The rasteriser's snap, the filter's weights and the blend between mip levels lie
/// within one step of these grids.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Precision {
    /// Sub-pixel bits of the rasteriser's snap.
    pub subpixel_bits: u32,
    /// Sub-texel bits of the bilinear weights.
    pub subtexel_bits: u32,
    /// Bits of the blend between two mip levels.
    pub mipmap_bits: u32,
}

impl Precision {
    /// Vulkan's minimum limits: what any conformant device guarantees.
    pub const VULKAN_MINIMUM: Precision = Precision {
        subpixel_bits: raster::MIN_SUBPIXEL_BITS,
        subtexel_bits: filter::MIN_SUBTEXEL_BITS,
        mipmap_bits: filter::MIN_MIPMAP_BITS,
    };
    /// Vulkan's Roadmap 2022 profile (docs/tolerances.md): 8 sub-pixel, 8 sub-texel and 6
    /// mipmap bits.
    pub const ROADMAP_2022: Precision =
        Precision { subpixel_bits: 8, subtexel_bits: 8, mipmap_bits: 6 };
    /// Mesa's lavapipe (llvmpipe): 8 sub-pixel and 8 sub-texel bits, 4 mipmap bits
    /// (`lvp_device.c`).
    pub const LAVAPIPE: Precision =
        Precision { subpixel_bits: 8, subtexel_bits: 8, mipmap_bits: 4 };

    /// The figures of an adapter this project knows (its name and PCI vendor id), with the
    /// reason: lavapipe's from Mesa's source, NVIDIA's drivers the Roadmap 2022 profile (which
    /// they support); Vulkan's minimum for any other (wgpu does not expose the limits).
    pub fn of_adapter(name: &str, vendor: u32) -> (Precision, &'static str) {
        if name.contains("llvmpipe") || name.contains("lavapipe") {
            (Precision::LAVAPIPE, "lavapipe's limits (Mesa's lvp_device.c)")
        } else if vendor == 0x10de {
            (Precision::ROADMAP_2022, "NVIDIA: Vulkan's Roadmap 2022 profile")
        } else {
            (Precision::VULKAN_MINIMUM, "Vulkan's minimum limits (adapter not known)")
        }
    }

    /// How far a snapped vertex may lie from its transformed position, px.
    pub fn snap_px(self) -> f64 {
        1.0 / f64::from(1u32 << self.subpixel_bits)
    }

    /// How far a bilinear weight may lie from the exact fraction.
    pub fn weight_step(self) -> f64 {
        1.0 / f64::from(1u32 << self.subtexel_bits)
    }

    /// How far the blend between two levels may lie from the LOD's fraction.
    pub fn mip_step(self) -> f64 {
        1.0 / f64::from(1u32 << self.mipmap_bits)
    }
}

/// A chain's envelope in [`crate::mip::MipChain`]'s atlas layout: RGB per texel, `None` in the
/// padding.
pub type AtlasEnvelope = Vec<Option<[Iv; 3]>>;

/// A chain's envelope, level by level (level 0 `width` × `height`), packed as
/// [`crate::mip::MipChain`] packs a chain's texels, `None` in the padding.
pub fn atlas_of<const N: usize>(
    width: u32,
    height: u32,
    levels: &[Vec<[Iv; N]>],
) -> Vec<Option<[Iv; N]>> {
    // Packed straight from the levels: a copy of them as `Option`s first cost a third of the
    // wave_mips envelope in page faults (a 256² chain's levels are 8 MB).
    let rows = crate::mip::level_row(height, levels.len() as u32);
    let mut atlas = vec![None; width as usize * rows as usize];
    for (k, level) in levels.iter().enumerate() {
        let lw = crate::mip::level_size(width, height, k as u32)[0] as usize;
        crate::mip::fill_level(&mut atlas, width, height, k as u32, |[i, j]| {
            Some(level[j as usize * lw + i as usize])
        });
    }
    atlas
}

/// A comparison's outcome: decided, or (for an envelope) either way.
pub trait Cond: Copy {
    /// The outcome when it is decided.
    fn decided(self) -> Option<bool>;
    /// `self && o`.
    fn and(self, o: Self) -> Self;
    /// `self || o`.
    fn or(self, o: Self) -> Self;
}

impl Cond for bool {
    #[inline]
    fn decided(self) -> Option<bool> {
        Some(self)
    }
    #[inline]
    fn and(self, o: bool) -> bool {
        self && o
    }
    #[inline]
    fn or(self, o: bool) -> bool {
        self || o
    }
}

/// A comparison of two intervals: true for every pair of values, false for every pair, or
/// either — then a `select` on it takes both branches, united.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tri {
    /// False for every pair of values in the operands.
    False,
    /// True for every pair.
    True,
    /// True for some pairs, false for others.
    Either,
}

impl Cond for Tri {
    fn decided(self) -> Option<bool> {
        match self {
            Tri::False => Some(false),
            Tri::True => Some(true),
            Tri::Either => None,
        }
    }
    fn and(self, o: Tri) -> Tri {
        match (self, o) {
            (Tri::False, _) | (_, Tri::False) => Tri::False,
            (Tri::True, Tri::True) => Tri::True,
            _ => Tri::Either,
        }
    }
    fn or(self, o: Tri) -> Tri {
        match (self, o) {
            (Tri::True, _) | (_, Tri::True) => Tri::True,
            (Tri::False, Tri::False) => Tri::False,
            _ => Tri::Either,
        }
    }
}

/// The scalar a mirror computes with: WGSL's `f32` operations, each with the semantics of the
/// implementing type (exact lavapipe f32, an interval, or a random conformant result).
pub trait Real:
    std::fmt::Debug
    + Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// What a comparison yields.
    type Cond: Cond;
    /// A literal or uniform: an exact f32.
    fn lit(v: f32) -> Self;
    /// WGSL `max(a, b)`.
    fn max(self, b: Self) -> Self;
    /// WGSL `min(a, b)`.
    fn min(self, b: Self) -> Self;
    /// WGSL `clamp(e, low, high)` = min(max(e, low), high).
    #[inline]
    fn clamp(self, low: Self, high: Self) -> Self {
        self.max(low).min(high)
    }
    /// WGSL `pow(e1, e2)` for e1 ≥ 0 (Vulkan: inherited from exp2(e2 · log2 e1)).
    fn pow(self, e: Self) -> Self;
    /// WGSL `round(e)`: to the nearest integer, halves to even (exact).
    fn round(self) -> Self;
    /// WGSL `abs(e)` (exact).
    fn abs(self) -> Self;
    /// The integer parts `floor(self)` may take, each with the fraction `self − floor(self)`
    /// over the values that floor there: one for a decided scalar, up to two for an interval
    /// across an integer; `None` past two (the caller's result is then anything).
    fn floor_cases(self) -> Option<[Option<(f32, Self)>; 2]>;
    /// WGSL `frexp(e)` for a normal e > 0, as cases: (exponent, fraction in [½, 1)), one for a
    /// decided scalar, up to two for an interval across a power of two (each with the
    /// fraction over the values in its binade; exact, frexp has no rounding); `None` past two
    /// or for a value that may be ≤ 0 or not finite.
    fn frexp_cases(self) -> Option<[Option<(i32, Self)>; 2]>;
    /// WGSL `exp(e)` (Vulkan: 3 + 2|e| ULP).
    fn exp(self) -> Self;
    /// WGSL `atan2(y, x)` with `self` = y ≥ 0 (Vulkan: 4096 ULP).
    fn atan2(self, x: Self) -> Self;
    /// WGSL `sqrt(e)` for e ≥ 0 (Vulkan: inherited from 1 / inversesqrt(e)).
    fn sqrt(self) -> Self;
    /// `a <= b`.
    fn le(self, b: Self) -> Self::Cond;
    /// `a < b`.
    fn lt(self, b: Self) -> Self::Cond;
    /// `a == b`.
    fn eq(self, b: Self) -> Self::Cond;
    /// `self * self`, written so (an interval knows both factors are one value: never
    /// negative).
    #[inline]
    fn sq(self) -> Self {
        self * self
    }
    /// Whether the type bounds values (an interval) rather than computing one.
    const INTERVAL: bool = false;
    /// The least value it may hold (−∞ for an interval that may be anything).
    fn least(self) -> f64;
    /// The greatest value it may hold (+∞ for an interval that may be anything).
    fn most(self) -> f64 {
        -(-self).least()
    }
    /// What is known of the value beyond its own arithmetic: it lies in [lo, hi] (an
    /// interval is cut to it; a scalar already is).
    #[inline]
    fn within(self, _lo: f64, _hi: f64) -> Self {
        self
    }
    /// What a branch knows of its condition: the value is at least `lo` there (an interval is
    /// cut to it; a scalar, which took the branch, already is).
    #[inline]
    fn at_least(self, lo: f64) -> Self {
        self.within(lo, f64::INFINITY)
    }
    /// The smallest value holding both (an interval's hull; for a decided scalar, never
    /// needed: `self`).
    fn hull(self, b: Self) -> Self;
    /// WGSL `select(f, t, cond)`.
    fn select(f: Self, t: Self, cond: Self::Cond) -> Self;
    /// What an 8-bit unorm target stores for a shader output: every byte a conformant
    /// implementation may write, as a range.
    fn store_unorm8(self) -> ByteRange;
    /// What an `rgba16float` texel stores of the value, read back as f32.
    fn store_half(self) -> Self;
    /// `terms[0] + terms[1] + …`, written left to right (the exact frame's order); a GPU may
    /// reassociate the sum.
    #[inline]
    fn sum(terms: &[Self]) -> Self {
        let mut s = terms[0];
        for &t in &terms[1..] {
            s = s + t;
        }
        s
    }
    /// A sum the exact frame evaluates as `written` (WGSL's parenthesisation, e.g.
    /// `(a + b) + (c + d)`) and a GPU may reassociate: the exact frame computes `written`, an
    /// envelope or a random GPU [`Real::sum`] of `terms`.
    #[inline]
    fn sum_as_written(terms: &[Self], written: impl FnOnce(&[Self]) -> Self) -> Self {
        written(terms)
    }
    /// What a texel of `format` stores of the value.
    #[inline]
    fn store(self, format: FrameFormat) -> Self {
        match format {
            FrameFormat::Rgba32Float => self,
            FrameFormat::Rgba16Float => self.store_half(),
        }
    }
}

impl Real for f32 {
    type Cond = bool;
    #[inline]
    fn lit(v: f32) -> Self {
        v
    }
    /// Rust's `f32::max`: IEEE maxNum, as `shaders::wgsl::max`.
    #[inline]
    fn max(self, b: Self) -> Self {
        f32::max(self, b)
    }
    #[inline]
    fn min(self, b: Self) -> Self {
        f32::min(self, b)
    }
    #[inline]
    fn pow(self, e: Self) -> Self {
        self.powf(e)
    }
    #[inline]
    fn round(self) -> Self {
        self.round_ties_even()
    }
    #[inline]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline]
    fn exp(self) -> Self {
        f32::exp(self)
    }
    #[inline]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline]
    fn floor_cases(self) -> Option<[Option<(f32, Self)>; 2]> {
        let k = self.floor();
        Some([Some((k, self - k)), None])
    }
    #[inline]
    fn least(self) -> f64 {
        f64::from(self)
    }
    #[inline]
    fn frexp_cases(self) -> Option<[Option<(i32, Self)>; 2]> {
        let (f, e) = crate::float::frexp(self);
        Some([Some((e, f)), None])
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        f32::atan2(self, x)
    }
    #[inline]
    fn le(self, b: Self) -> bool {
        self <= b
    }
    #[inline]
    fn lt(self, b: Self) -> bool {
        self < b
    }
    #[inline]
    fn eq(self, b: Self) -> bool {
        self == b
    }
    #[inline]
    fn hull(self, _: Self) -> Self {
        self
    }
    #[inline]
    fn select(f: Self, t: Self, cond: bool) -> Self {
        if cond { t } else { f }
    }
    /// Lavapipe's store: toward zero (`ocean_core::frame_format::round_to_half`).
    #[inline]
    fn store_half(self) -> Self {
        ocean_core::frame_format::round_to_half(self)
    }
    /// Lavapipe's store: clamp to [0, 1], × 255, rounded to nearest even.
    #[inline]
    fn store_unorm8(self) -> ByteRange {
        let b = (self.clamp(0.0, 1.0) * 255.0).round_ties_even() as u8;
        ByteRange { lo: b, hi: b }
    }
}

/// `if cond { t() } else { f() }` for a data-dependent branch: where the bounds cannot decide
/// `cond`, both branches, united.
#[inline]
pub fn choose<R: Real>(cond: R::Cond, t: impl FnOnce() -> R, f: impl FnOnce() -> R) -> R {
    match cond.decided() {
        Some(true) => t(),
        Some(false) => f(),
        None => t().hull(f()),
    }
}

/// [`choose`] for a vector.
#[inline]
pub fn choose_n<R: Real, const N: usize>(
    cond: R::Cond,
    t: impl FnOnce() -> [R; N],
    f: impl FnOnce() -> [R; N],
) -> [R; N] {
    match cond.decided() {
        Some(true) => t(),
        Some(false) => f(),
        None => {
            let (a, b) = (t(), f());
            std::array::from_fn(|i| a[i].hull(b[i]))
        }
    }
}

/// `f(floor(x), x − floor(x))` for a lookup indexed by `floor(x)`: where an interval spans an
/// integer, every cell's result, united; past 12 cells, `full` (what the caller knows of
/// the lookup for a finite x); anything where x may not be finite.
#[inline]
pub fn on_floor<R: Real, const N: usize>(
    x: R,
    full: [R; N],
    f: impl Fn(f32, R) -> [R; N],
) -> [R; N] {
    match x.floor_cases() {
        Some([Some((k, t)), None]) => f(k, t),
        Some([Some((k0, t0)), Some((k1, t1))]) => {
            let (a, b) = (f(k0, t0), f(k1, t1));
            std::array::from_fn(|i| a[i].hull(b[i]))
        }
        _ => {
            // Past two cells (an interval only): every cell up to FLOOR_CELLS, united, each
            // with the fraction x − k cut to the cell's [0, 1].
            let (lo, hi) = (x.least().floor(), x.most().floor());
            // An x that may be anything (an overflow, a NaN): so may the lookup, whatever the
            // caller's bound for a finite x says.
            if !(lo.is_finite() && hi.is_finite()) {
                return [R::lit(f32::NAN); N];
            }
            if hi - lo >= FLOOR_CELLS {
                return full;
            }
            let mut out: Option<[R; N]> = None;
            let mut k = lo;
            while k <= hi {
                let t = (x - R::lit(k as f32)).within(0.0, 1.0);
                let v = f(k as f32, t);
                out = Some(match out {
                    None => v,
                    Some(o) => std::array::from_fn(|i| o[i].hull(v[i])),
                });
                k += 1.0;
            }
            out.unwrap_or(full)
        }
    }
}

/// How many cells [`on_floor`] follows an interval into (beyond: `full`).
const FLOOR_CELLS: f64 = 12.0;

/// `dot(a, b)` = (a.x b.x + a.y b.y) + a.z b.z in the exact frame; a GPU may reassociate it.
#[inline]
pub fn dot3<R: Real>(a: [R; 3], b: [R; 3]) -> R {
    R::sum(&[a[0] * b[0], a[1] * b[1], a[2] * b[2]])
}

/// `cross(a, b)`.
#[inline]
pub fn cross3<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `length(a)` = sqrt(dot(a, a)), each product a square ([`Real::sq`]): an interval that
/// took `a.x · a.x` for a product of two values could reach below 0 where a.x may be 0, and
/// the square root of that is anything (Preetham's sin γ near the sun was, on every
/// reflected direction around it).
#[inline]
pub fn length3<R: Real>(a: [R; 3]) -> R {
    R::sum(&[a[0].sq(), a[1].sq(), a[2].sq()]).sqrt()
}

/// `sqrt(a.x * a.x + a.y * a.y)` (WGSL's written form, or `length(a)` of a 2-vector), each
/// product a square, as [`length3`].
#[inline]
pub fn length2<R: Real>(a: [R; 2]) -> R {
    R::sum(&[a[0].sq(), a[1].sq()]).sqrt()
}

/// `normalize(a)` = a / length(a).
#[inline]
pub fn normalize3<R: Real>(a: [R; 3]) -> [R; 3] {
    let l = length3(a);
    a.map(|c| c / l)
}

/// `m * v` for a column-major 4×4 `m`: per row ((m0 v.x + m1 v.y) + m2 v.z) + m3 v.w in the
/// exact frame; a GPU may reassociate each row.
#[inline]
pub fn mat4_mul_vec4<R: Real>(m: &[[f32; 4]; 4], v: [R; 4]) -> [R; 4] {
    std::array::from_fn(|r| {
        R::sum(&[
            R::lit(m[0][r]) * v[0],
            R::lit(m[1][r]) * v[1],
            R::lit(m[2][r]) * v[2],
            R::lit(m[3][r]) * v[3],
        ])
    })
}

/// Three components, one operation each (a `vec3<f32>` of any [`Real`]).
#[inline]
pub fn map3<R: Real>(v: [R; 3], f: impl Fn(R) -> R) -> [R; 3] {
    [f(v[0]), f(v[1]), f(v[2])]
}

/// Component-wise `f(a, b)`.
#[inline]
pub fn zip3<R: Real>(a: [R; 3], b: [R; 3], f: impl Fn(R, R) -> R) -> [R; 3] {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2])]
}
