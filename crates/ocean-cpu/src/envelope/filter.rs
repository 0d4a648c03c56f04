//! Texture filtering's envelope: a `textureSampleLevel` at level 0 with a linear filter
//! (docs/tolerances.md, "Texture filtering").
//!
//! What Vulkan leaves to the implementation, and how it is carried:
//! - **The coordinate.** x = u·W − ½ in f32 (an [`Iv`] here); the texel pair is where
//!   `floor` puts x — both pairs, united, where an interval crosses a texel centre (up to
//!   [`MAX_CELLS`] per axis, else anything between the texels it spans).
//! - **The weights.** The fraction α = x − floor(x) is taken to at least
//!   [`MIN_SUBTEXEL_BITS`] bits (Vulkan's minimum `subTexelPrecisionBits`), rounding either
//!   way: α lies within 1/16 of its exact value, in [0, 1].
//! - **The blend.** Bilinear in (α, β), so over their box it is extreme at a corner; its
//!   arithmetic is allowed [`FILTER_ULPS`] ULP of the largest texel (an assumption, like the
//!   rasteriser's interpolation: Vulkan leaves the filter's precision to the implementation).

use super::{Iv, Jitter, Real};
use crate::sampler::{Sampler, Texture2D};

/// Vulkan's minimum `subTexelPrecisionBits`.
pub const MIN_SUBTEXEL_BITS: u32 = 4;

/// How far a weight may lie from the exact fraction.
pub const WEIGHT_STEP: f64 = 1.0 / (1u32 << MIN_SUBTEXEL_BITS) as f64;

/// The blend's arithmetic: ULP of the largest texel magnitude.
pub const FILTER_ULPS: f64 = 4.0;

/// The most texel pairs per axis an interval coordinate is followed into (beyond: the hull of
/// every texel it spans).
pub const MAX_CELLS: i64 = 4;

/// The cells x may fall in along an axis, each with the weight's interval there; `None`
/// past [`MAX_CELLS`] or for an unbounded x.
fn cells(x: Iv) -> Option<Vec<(i64, (f64, f64))>> {
    if x.full || !x.lo.is_finite() || !x.hi.is_finite() {
        return None;
    }
    let (k0, k1) = (x.lo.floor() as i64, x.hi.floor() as i64);
    if k1 - k0 + 1 > MAX_CELLS {
        return None;
    }
    Some(
        (k0..=k1)
            .map(|k| {
                let kf = k as f64;
                let lo = (x.lo - kf).max(0.0) - WEIGHT_STEP;
                let hi = (x.hi - kf).min(1.0) + WEIGHT_STEP;
                (k, (lo.max(0.0), hi.min(1.0)))
            })
            .collect(),
    )
}

/// The envelope of `textureSampleLevel(t, s, uv, 0.0)` with a linear filter (the texels
/// exact: an upload, or a GPU's own map read back).
pub fn sample_level0(t: &Texture2D, s: &Sampler, uv: [Iv; 2]) -> [Iv; 4] {
    let l = Iv::lit;
    let x = uv[0] * l(t.width as f32) - l(0.5);
    let y = uv[1] * l(t.height as f32) - l(0.5);
    let (Some(cx), Some(cy)) = (cells(x), cells(y)) else { return [Iv::FULL; 4] };
    let fetch = |i: i64, j: i64| {
        t.texel(s.address_mode_u.apply(i, t.width), s.address_mode_v.apply(j, t.height))
    };
    let mut out: [(f64, f64); 4] = [(f64::INFINITY, f64::NEG_INFINITY); 4];
    let mut big = 0.0f64;
    for &(i, a) in &cx {
        for &(j, b) in &cy {
            let tx = [fetch(i, j), fetch(i + 1, j), fetch(i, j + 1), fetch(i + 1, j + 1)];
            for c in 0..4 {
                let v = tx.map(|t| f64::from(t[c]));
                big = big.max(v.iter().fold(0.0, |m, x| m.max(x.abs())));
                for alpha in [a.0, a.1] {
                    for beta in [b.0, b.1] {
                        let top = v[0] + alpha * (v[1] - v[0]);
                        let bottom = v[2] + alpha * (v[3] - v[2]);
                        let r = top + beta * (bottom - top);
                        out[c] = (out[c].0.min(r), out[c].1.max(r));
                    }
                }
            }
        }
    }
    let slack = FILTER_ULPS * super::f32_ulp(big) + big * 1e-12;
    out.map(|(lo, hi)| if lo <= hi { Iv::new(lo - slack, hi + slack) } else { Iv::FULL })
}

/// `textureSampleLevel(t, s, uv, 0.0)` as one random conformant GPU filters: the coordinate
/// in its random roundings, the weights taken to 1/16 up or down at random (at scale 2, one
/// more step either way), the blend rounded at random.
pub fn sample_level0_jitter(t: &Texture2D, s: &Sampler, uv: [Jitter; 2]) -> [Jitter; 4] {
    let l = Jitter::lit;
    let x = uv[0] * l(t.width as f32) - l(0.5);
    let y = uv[1] * l(t.height as f32) - l(0.5);
    let grid = f64::from(1u32 << MIN_SUBTEXEL_BITS);
    let weight = |x: f64| -> (i64, f64) {
        let k = x.floor();
        let f = (x - k) * grid;
        let (r, scale) = super::jitter::draw();
        let mut q = if r < 0.5 { f.floor() } else { f.ceil() };
        if scale > 1.0 {
            let (r2, _) = super::jitter::draw();
            q += if r2 < 0.5 { -1.0 } else { 1.0 };
        }
        (k as i64, (q / grid).clamp(0.0, 1.0))
    };
    let ((i, a), (j, b)) = (weight(f64::from(x.0)), weight(f64::from(y.0)));
    let fetch = |i: i64, j: i64| {
        t.texel(s.address_mode_u.apply(i, t.width), s.address_mode_v.apply(j, t.height))
    };
    let tx = [fetch(i, j), fetch(i + 1, j), fetch(i, j + 1), fetch(i + 1, j + 1)];
    std::array::from_fn(|c| {
        let v = tx.map(|t| Jitter(t[c]));
        let (a, b) = (Jitter(a as f32), Jitter(b as f32));
        let top = v[0] + a * (v[1] - v[0]);
        let bottom = v[2] + a * (v[3] - v[2]);
        top + b * (bottom - top)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::envelope::JitterRules;
    use crate::sampler::{AddressMode, FilterMode, texture_sample_level};

    fn texture() -> Texture2D {
        let mut g = ocean_core::rng::SplitMix64::new(7);
        let mut f = || (g.next_u64() >> 40) as f32 / (1u64 << 24) as f32 * 4.0 - 2.0;
        Texture2D::new(8, 5, (0..40).map(|_| [f(), f(), f(), f()]).collect())
    }

    /// Random coordinates on a random texture, both address modes: the exact sampler and 8
    /// random conformant filters inside the envelope; a filter twice as loose (its weights two
    /// steps off) outside somewhere.
    #[test]
    fn random_conformant_filters_stay_inside_and_twice_the_rules_leaves() {
        let t = texture();
        let mut g = ocean_core::rng::SplitMix64::new(11);
        let mut coord = || (g.next_u64() >> 40) as f32 / (1u64 << 24) as f32 * 3.0 - 1.0;
        let (mut loose, mut n) = (0, 0);
        for mode in [AddressMode::Repeat, AddressMode::ClampToEdge] {
            let s =
                Sampler { address_mode_u: mode, address_mode_v: mode, filter: FilterMode::Linear };
            for k in 0..4000u64 {
                let uv = [coord(), coord()];
                let env = sample_level0(&t, &s, uv.map(Iv::point));
                let exact = texture_sample_level(&t, &s, uv, 0.0);
                assert!((0..4).all(|c| env[c].contains(exact[c])), "{uv:?}: the exact sampler");
                for seed in 0..8 {
                    Jitter::reseed(JitterRules { seed, scale: 1.0 }, k);
                    let j = sample_level0_jitter(&t, &s, uv.map(Jitter));
                    assert!((0..4).all(|c| env[c].contains(j[c].0)), "{uv:?} seed {seed}");
                }
                Jitter::reseed(JitterRules { seed: 99, scale: 2.0 }, k);
                let j = sample_level0_jitter(&t, &s, uv.map(Jitter));
                loose += (0..4).filter(|&c| !env[c].contains(j[c].0)).count();
                n += 4;
            }
        }
        assert!(loose > 0, "a filter twice as loose never left: {loose} of {n}");
    }
}
