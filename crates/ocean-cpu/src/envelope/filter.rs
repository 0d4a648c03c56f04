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

use super::{Iv, Jitter, Precision, Real};
use crate::mip::MipChain;
use crate::sampler::{Sampler, Texture2D};

/// Vulkan's minimum `subTexelPrecisionBits`.
pub const MIN_SUBTEXEL_BITS: u32 = 4;

/// The blend's arithmetic: ULP of the largest texel magnitude.
pub const FILTER_ULPS: f64 = 4.0;

/// The most texel pairs per axis an interval coordinate is followed into (beyond: the hull of
/// every texel it spans).
pub const MAX_CELLS: i64 = 4;

/// The cells x may fall in along an axis, each with the weight's interval there; `None`
/// past [`MAX_CELLS`] or for an unbounded x.
fn cells(x: Iv, step: f64) -> Option<Vec<(i64, (f64, f64))>> {
    if x.full || !x.lo.is_finite() || !x.hi.is_finite() {
        return None;
    }
    // In f64: far coordinates saturate i64, and their difference would overflow.
    if x.hi.floor() - x.lo.floor() + 1.0 > MAX_CELLS as f64 {
        return None;
    }
    let (k0, k1) = (x.lo.floor() as i64, x.hi.floor() as i64);
    Some(
        (k0..=k1)
            .map(|k| {
                let kf = k as f64;
                let lo = (x.lo - kf).max(0.0) - step;
                let hi = (x.hi - kf).min(1.0) + step;
                (k, (lo.max(0.0), hi.min(1.0)))
            })
            .collect(),
    )
}

/// The envelope of `textureSampleLevel(t, s, uv, 0.0)` with a linear filter (the texels
/// exact: an upload, or a GPU's own map read back).
pub fn sample_level0(t: &Texture2D, s: &Sampler, uv: [Iv; 2]) -> [Iv; 4] {
    sample_level0_p(t, s, uv, Precision::VULKAN_MINIMUM)
}

/// [`sample_level0`] on a device of precision `p`.
pub fn sample_level0_p(t: &Texture2D, s: &Sampler, uv: [Iv; 2], p: Precision) -> [Iv; 4] {
    bilinear(t.width, t.height, s, uv, p, &|i, j| t.texel(i, j))
}

/// The bilinear envelope on a `w` × `h` level whose texel (i, j) `fetch` reads.
fn bilinear(
    w: u32,
    h: u32,
    s: &Sampler,
    uv: [Iv; 2],
    p: Precision,
    fetch: &dyn Fn(u32, u32) -> [f32; 4],
) -> [Iv; 4] {
    let mut out: [(f64, f64); 4] = [(f64::INFINITY, f64::NEG_INFINITY); 4];
    let mut texels: [(f64, f64); 4] = [(f64::INFINITY, f64::NEG_INFINITY); 4];
    let mut big = 0.0f64;
    let spanned_out = corners(w, h, s, uv, p, fetch, &mut |r, m, t| {
        big = big.max(m);
        for c in 0..4 {
            out[c] = (out[c].0.min(r[c]), out[c].1.max(r[c]));
            texels[c] = (texels[c].0.min(t[c].0), texels[c].1.max(t[c].1));
        }
    });
    if let Some(v) = spanned_out {
        return v;
    }
    let slack = FILTER_ULPS * super::f32_ulp(big) + big * 1e-12;
    std::array::from_fn(|c| {
        let (lo, hi) = out[c];
        if lo <= hi { signed(lo - slack, hi + slack, texels[c]) } else { Iv::FULL }
    })
}

/// [l, h], kept on the side of 0 that every texel blended is on (a blend of texels of one
/// sign with weights ≥ 0 keeps it, and no rounding flips it); `texels` is their (least,
/// greatest).
fn signed(l: f64, h: f64, texels: (f64, f64)) -> Iv {
    let l = if texels.0 >= 0.0 { l.max(0.0) } else { l };
    let h = if texels.1 <= 0.0 { h.min(0.0) } else { h };
    Iv::new(l, h)
}

/// Every bilinear blend at a corner of the weights' box of every texel pair the coordinates
/// may fall in: `visit(blend, largest texel magnitude)`, exact in f64. `Some` (and nothing
/// visited) past [`MAX_CELLS`]: the hull of the texels spanned.
fn corners(
    w: u32,
    h: u32,
    s: &Sampler,
    uv: [Iv; 2],
    p: Precision,
    fetch: &dyn Fn(u32, u32) -> [f32; 4],
    visit: &mut dyn FnMut([f64; 4], f64, [(f64, f64); 4]),
) -> Option<[Iv; 4]> {
    let l = Iv::lit;
    let x = uv[0] * l(w as f32) - l(0.5);
    let y = uv[1] * l(h as f32) - l(0.5);
    let fetch = |i: i64, j: i64| fetch(s.address_mode_u.apply(i, w), s.address_mode_v.apply(j, h));
    let step = p.weight_step();
    let (Some(cx), Some(cy)) = (cells(x, step), cells(y, step)) else {
        return Some(spanned(w, h, x, y, &fetch));
    };
    for &(i, a) in &cx {
        for &(j, b) in &cy {
            let tx = [fetch(i, j), fetch(i + 1, j), fetch(i, j + 1), fetch(i + 1, j + 1)];
            // A texel that is not a finite number (the GPU's own map may hold one): anything.
            if tx.iter().flatten().any(|v| !v.is_finite()) {
                return Some([Iv::FULL; 4]);
            }
            let big = tx.iter().flatten().fold(0.0f64, |m, v| m.max(f64::from(*v).abs()));
            let range: [(f64, f64); 4] = std::array::from_fn(|c| {
                let v = tx.map(|t| f64::from(t[c]));
                (
                    v.iter().copied().fold(f64::INFINITY, f64::min),
                    v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                )
            });
            for alpha in [a.0, a.1] {
                for beta in [b.0, b.1] {
                    let r = std::array::from_fn(|c| {
                        let v = tx.map(|t| f64::from(t[c]));
                        let top = v[0] + alpha * (v[1] - v[0]);
                        let bottom = v[2] + alpha * (v[3] - v[2]);
                        top + beta * (bottom - top)
                    });
                    visit(r, big, range);
                }
            }
        }
    }
    None
}

/// Past [`MAX_CELLS`] texel pairs along an axis: the hull of every texel the coordinates
/// span (a blend's convex weights keep it there), plus [`FILTER_ULPS`]; anything for an
/// unbounded coordinate.
fn spanned(w: u32, h: u32, x: Iv, y: Iv, fetch: &dyn Fn(i64, i64) -> [f32; 4]) -> [Iv; 4] {
    let range = |v: Iv, n: u32| -> Option<(i64, i64)> {
        if v.full || !v.lo.is_finite() || !v.hi.is_finite() {
            return None;
        }
        // Past one period every texel of the axis is reached (repeat or clamp alike); in f64,
        // as far coordinates saturate i64.
        if v.hi.floor() + 1.0 - v.lo.floor() >= f64::from(n) {
            return Some((0, i64::from(n) - 1));
        }
        Some((v.lo.floor() as i64, v.hi.floor() as i64 + 1))
    };
    let (Some((i0, i1)), Some((j0, j1))) = (range(x, w), range(y, h)) else {
        return [Iv::FULL; 4];
    };
    let mut out = [(f64::INFINITY, f64::NEG_INFINITY); 4];
    for j in j0..=j1 {
        for i in i0..=i1 {
            let t = fetch(i, j);
            if t.iter().any(|v| !v.is_finite()) {
                return [Iv::FULL; 4];
            }
            for c in 0..4 {
                out[c] = (out[c].0.min(f64::from(t[c])), out[c].1.max(f64::from(t[c])));
            }
        }
    }
    out.map(|(lo, hi)| {
        let slack = FILTER_ULPS * super::f32_ulp(lo.abs().max(hi.abs()));
        Iv::new(lo - slack, hi + slack)
    })
}

/// Vulkan's minimum `mipmapPrecisionBits`: the blend between two levels is taken to 1/16 of
/// the fraction of the LOD, rounding either way.
pub const MIN_MIPMAP_BITS: u32 = 4;

/// The most levels an interval LOD is followed into (beyond: anything).
pub const MAX_LEVELS: usize = 3;

/// The envelope of `textureSampleLevel(chain, s, uv, lod)` with linear filtering within and
/// between levels (the texels exact, as [`sample_level0`]'s). The LOD λ is clamped to
/// [0, levels − 1]; each level d that ⌊λ⌋ may be is blended with d + 1 by a weight within
/// one step of the device's `mipmapPrecisionBits` ([`Precision::mip_step`]) of λ − d there (a bilinear envelope of each level, the blend linear in the
/// weight so extreme at its ends), plus [`FILTER_ULPS`] of the blend's arithmetic.
pub fn sample_mip(chain: &MipChain, s: &Sampler, uv: [Iv; 2], lod: Iv, p: Precision) -> [Iv; 4] {
    if lod.full || !lod.lo.is_finite() || !lod.hi.is_finite() {
        return [Iv::FULL; 4];
    }
    let last = f64::from(chain.levels.saturating_sub(1));
    let (lo, hi) = (lod.lo.clamp(0.0, last), lod.hi.clamp(0.0, last));
    let (d0, d1) = (lo.floor() as u32, hi.floor() as u32);
    if (d1 - d0) as usize >= MAX_LEVELS {
        return [Iv::FULL; 4];
    }
    let level = |k: u32| {
        let [w, h] = chain.size(k);
        bilinear(w, h, s, uv, p, &|i, j| chain.texel(k, i, j))
    };
    let mut out: Option<[Iv; 4]> = None;
    let mut put = |v: [Iv; 4]| {
        out = Some(match out {
            None => v,
            Some(o) => std::array::from_fn(|c| o[c].hull(v[c])),
        });
    };
    for d in d0..=d1 {
        let c0 = level(d);
        if f64::from(d) >= last {
            put(c0);
            continue;
        }
        let df = f64::from(d);
        let f_lo = ((lo - df).max(0.0) - p.mip_step()).max(0.0);
        let f_hi = ((hi - df).min(1.0) + p.mip_step()).min(1.0);
        let c1 = level(d + 1);
        put(std::array::from_fn(|c| {
            let (a, b) = (c0[c], c1[c]);
            if a.full || b.full {
                return Iv::FULL;
            }
            let ends = [f_lo, f_hi].map(|f| (a.lo + f * (b.lo - a.lo), a.hi + f * (b.hi - a.hi)));
            let (l, h) = (ends[0].0.min(ends[1].0), ends[0].1.max(ends[1].1));
            let slack = FILTER_ULPS * super::f32_ulp(a.magnitude().max(b.magnitude()));
            // Both levels' blends on one side of 0: so is theirs.
            signed(l - slack, h + slack, (a.lo.min(b.lo), a.hi.max(b.hi)))
        }));
    }
    out.unwrap_or([Iv::FULL; 4])
}

/// How many ULP [`spread_floor`] allows for the arithmetic between the texels and the
/// shader's E\[s²\] − E\[s\]²: the filter's and the level blend's, the sum over up to 16
/// taps, the square and the difference (each a few ULP; an assumption, generous as
/// [`FILTER_ULPS`]).
pub const SPREAD_ULPS: f64 = 32.0;

/// The least E\[s²\] − E\[s\]² of a sample of a chain of (s_x, s_z, s_x², s_z²): per axis
/// the least of t₂ − t₀² (and t₃ − t₁²) over the corners of the weights' box (within each
/// level and the blend between two), less [`SPREAD_ULPS`] of the magnitudes involved. The
/// blend is linear in each weight, so this is concave in each and least at a corner; the
/// intervals of t₂ and t₀ apart lose that (their difference would reach below 0 wherever the
/// spread is smaller than the weights' 1/16 moves a blend). −∞ where it cannot tell.
pub fn spread_floor(chain: &MipChain, s: &Sampler, uv: [Iv; 2], lod: Iv, p: Precision) -> [f64; 2] {
    let none = [f64::NEG_INFINITY; 2];
    if lod.full || !lod.lo.is_finite() || !lod.hi.is_finite() {
        return none;
    }
    let last = f64::from(chain.levels.saturating_sub(1));
    let (lo, hi) = (lod.lo.clamp(0.0, last), lod.hi.clamp(0.0, last));
    let (d0, d1) = (lo.floor() as u32, hi.floor() as u32);
    if (d1 - d0) as usize >= MAX_LEVELS {
        return none;
    }
    let level = |k: u32| -> Option<(Vec<[f64; 4]>, f64)> {
        let [w, h] = chain.size(k);
        let mut v = Vec::new();
        let mut big = 0.0f64;
        let out = corners(w, h, s, uv, p, &|i, j| chain.texel(k, i, j), &mut |r, m, _| {
            v.push(r);
            big = big.max(m);
        });
        out.is_none().then_some((v, big))
    };
    let mut least = [f64::INFINITY; 2];
    let mut big = 0.0f64;
    let mut take = |r: [f64; 4]| {
        least[0] = least[0].min(r[2] - r[0] * r[0]);
        least[1] = least[1].min(r[3] - r[1] * r[1]);
    };
    for d in d0..=d1 {
        let Some((c0, b0)) = level(d) else { return none };
        big = big.max(b0);
        if f64::from(d) >= last {
            c0.iter().for_each(|&r| take(r));
            continue;
        }
        let df = f64::from(d);
        let f_lo = ((lo - df).max(0.0) - p.mip_step()).max(0.0);
        let f_hi = ((hi - df).min(1.0) + p.mip_step()).min(1.0);
        let Some((c1, b1)) = level(d + 1) else { return none };
        big = big.max(b1);
        for a in &c0 {
            for b in &c1 {
                for f in [f_lo, f_hi] {
                    take(std::array::from_fn(|c| a[c] + f * (b[c] - a[c])));
                }
            }
        }
    }
    let u = super::f32_ulp(big);
    let slack = SPREAD_ULPS * (u + 2.0 * big * u + super::f32_ulp(big * big)) + big * big * 1e-12;
    least.map(|l| l - slack)
}

/// `textureSampleLevel(chain, s, uv, lod)` as one random conformant GPU filters it: each
/// level as [`sample_level0_jitter`] does, the blend's weight taken to 1/16 up or down at
/// random (at scale 2, one more step either way), the blend rounded at random.
pub fn sample_mip_jitter(
    chain: &MipChain,
    s: &Sampler,
    uv: [Jitter; 2],
    lod: Jitter,
    p: Precision,
) -> [Jitter; 4] {
    let (level, f) = crate::mip::mip_levels(lod.0, chain.levels);
    let at = |k: u32| {
        let [w, h] = chain.size(k);
        bilinear_jitter(w, h, s, uv, p, &|i, j| chain.texel(k, i, j))
    };
    let c0 = at(level);
    if level + 1 >= chain.levels {
        return c0;
    }
    let grid = f64::from(1u32 << p.mipmap_bits);
    let (r, scale) = super::jitter::draw();
    let mut q = if r < 0.5 { (f64::from(f) * grid).floor() } else { (f64::from(f) * grid).ceil() };
    if scale > 1.0 {
        let (r2, _) = super::jitter::draw();
        q += if r2 < 0.5 { -1.0 } else { 1.0 };
    }
    let beta = Jitter((q / grid).clamp(0.0, 1.0) as f32);
    if beta.0 == 0.0 {
        return c0;
    }
    let c1 = at(level + 1);
    std::array::from_fn(|c| c0[c] + beta * (c1[c] - c0[c]))
}

/// `textureSampleLevel(t, s, uv, 0.0)` as one random conformant GPU filters: the coordinate
/// in its random roundings, the weights taken to 1/16 up or down at random (at scale 2, one
/// more step either way), the blend rounded at random.
pub fn sample_level0_jitter(t: &Texture2D, s: &Sampler, uv: [Jitter; 2]) -> [Jitter; 4] {
    sample_level0_jitter_p(t, s, uv, Precision::VULKAN_MINIMUM)
}

/// [`sample_level0_jitter`] on a device of precision `p`.
pub fn sample_level0_jitter_p(
    t: &Texture2D,
    s: &Sampler,
    uv: [Jitter; 2],
    p: Precision,
) -> [Jitter; 4] {
    bilinear_jitter(t.width, t.height, s, uv, p, &|i, j| t.texel(i, j))
}

/// [`sample_level0_jitter`] on a `w` × `h` level whose texel (i, j) `fetch` reads.
fn bilinear_jitter(
    w: u32,
    h: u32,
    s: &Sampler,
    uv: [Jitter; 2],
    p: Precision,
    fetch: &dyn Fn(u32, u32) -> [f32; 4],
) -> [Jitter; 4] {
    let l = Jitter::lit;
    let x = uv[0] * l(w as f32) - l(0.5);
    let y = uv[1] * l(h as f32) - l(0.5);
    let grid = f64::from(1u32 << p.subtexel_bits);
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
    let fetch = |i: i64, j: i64| fetch(s.address_mode_u.apply(i, w), s.address_mode_v.apply(j, h));
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

    /// Coordinates far past i64's range (a far vertex's uv under a projected grid's horizon):
    /// the hull of every texel, not an overflow; with the span inside a period, still bounded.
    #[test]
    fn far_coordinates_give_every_texel_not_an_overflow() {
        let t = texture();
        let s = Sampler {
            address_mode_u: AddressMode::Repeat,
            address_mode_v: AddressMode::ClampToEdge,
            filter: FilterMode::Linear,
        };
        let (lo, hi) =
            t.texels.iter().flatten().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(f64::from(*v)), b.max(f64::from(*v)))
            });
        for uv in
            [[Iv::new(-1e30, 1e30), Iv::new(0.2, 0.3)], [Iv::new(1e25, 2e25), Iv::new(-3e28, 5.0)]]
        {
            let v = sample_level0_p(&t, &s, uv, Precision::LAVAPIPE);
            for c in v {
                assert!(
                    !c.full && c.lo >= lo - 1e-5 && c.hi <= hi + 1e-5,
                    "{c:?} past [{lo}, {hi}]"
                );
            }
        }
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

    /// A random chain of four levels: random coordinates and LODs (−1 … 4, across levels and
    /// past both ends), the exact sampler and 8 random conformant filters inside the
    /// envelope; twice the rules (the weights two steps off) outside somewhere.
    #[test]
    fn random_conformant_mip_filters_stay_inside_and_twice_the_rules_leaves() {
        let mut g = ocean_core::rng::SplitMix64::new(5);
        let mut f = || (g.next_u64() >> 40) as f32 / (1u64 << 24) as f32 * 4.0 - 2.0;
        let levels: Vec<Texture2D> = (0..4u32)
            .map(|k| {
                let [w, h] = crate::mip::level_size(16, 8, k);
                Texture2D::new(w, h, (0..w * h).map(|_| [f(), f(), f(), f()]).collect())
            })
            .collect();
        let chain = MipChain::from_levels(&levels);
        let s = Sampler {
            address_mode_u: AddressMode::Repeat,
            address_mode_v: AddressMode::Repeat,
            filter: FilterMode::Linear,
        };
        let mut g = ocean_core::rng::SplitMix64::new(13);
        let mut r = || (g.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        let (mut loose, mut n) = (0, 0);
        for k in 0..4000u64 {
            let uv = [r() * 3.0 - 1.0, r() * 3.0 - 1.0];
            let lod = r() * 5.0 - 1.0;
            let p = Precision::VULKAN_MINIMUM;
            let env = sample_mip(&chain, &s, uv.map(Iv::point), Iv::point(lod), p);
            let exact = crate::mip::texture_sample_level_mip(&chain, &s, uv, lod);
            assert!((0..4).all(|c| env[c].contains(exact[c])), "{uv:?} {lod}: the exact sampler");
            for seed in 0..8 {
                Jitter::reseed(JitterRules { seed, scale: 1.0 }, k);
                let j = sample_mip_jitter(&chain, &s, uv.map(Jitter), Jitter(lod), p);
                assert!((0..4).all(|c| env[c].contains(j[c].0)), "{uv:?} {lod} seed {seed}");
            }
            Jitter::reseed(JitterRules { seed: 99, scale: 2.0 }, k);
            let j = sample_mip_jitter(&chain, &s, uv.map(Jitter), Jitter(lod), p);
            loose += (0..4).filter(|&c| !env[c].contains(j[c].0)).count();
            n += 4;
        }
        assert!(loose > 0, "a filter twice as loose never left: {loose} of {n}");
    }

    /// Texels of both signs whose exact blend is a hair above 0: a GPU rounding the lerp down
    /// lands below 0, and the envelope must not cut it away (the sign is kept only where
    /// every texel blended has it).
    #[test]
    fn a_blend_of_texels_of_both_signs_keeps_its_rounding_below_zero() {
        let t = Texture2D::new(
            2,
            1,
            vec![[-0.626_672_7, 0.0, 0.0, 0.0], [0.217_686_31, 0.0, 0.0, 0.0]],
        );
        let s = Sampler {
            address_mode_u: AddressMode::ClampToEdge,
            address_mode_v: AddressMode::ClampToEdge,
            filter: FilterMode::Linear,
        };
        // The weight box is [190, 192]/256; at 190/256 the exact blend is +6.9e-9.
        let u = (191.0 / 256.0 + 0.5) / 2.0;
        let env = sample_level0_p(&t, &s, [Iv::point(u), Iv::point(0.5)], Precision::LAVAPIPE);
        assert!(env[0].contains(-5.96e-8), "{:?}", env[0]);
        // Texels of one sign keep it.
        let t = Texture2D::new(2, 1, vec![[0.25, 0.0, 0.0, 0.0], [1e-30, 0.0, 0.0, 0.0]]);
        let env = sample_level0_p(&t, &s, [Iv::point(0.75), Iv::point(0.5)], Precision::LAVAPIPE);
        assert!(env[0].lo >= 0.0, "{:?}", env[0]);
    }
}
