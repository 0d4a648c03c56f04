//! Texture filtering in affine arithmetic ([`Af`]): the bilinear blend and the blend between
//! two mip levels as functions of the coordinates' affine forms, the weights' quantisation
//! (the device's sub-texel and mipmap bits) a noise symbol of its own per weight, shared by
//! the four channels of the fetch. So a texel's channels stay correlated as the filter makes
//! them: E\[s²\] − E\[s\]² of one fetch does not take each channel's rounding of the weights
//! apart. Where the coordinates may fall in more than one cell (or the LOD on more than one
//! pair of levels) the interval envelope ([`filter`]) stands alone, each channel a fresh
//! input. The result is always cut by that envelope.

use super::filter::{self, FILTER_ULPS};
use super::{Af, Iv, Precision, Real, f32_ulp};
use crate::mip::MipChain;
use crate::sampler::{Sampler, Texture2D};

/// A fresh noise symbol of radius `r` (a weight's quantisation; the blend's own rounding).
fn noise(r: f64) -> Af {
    Af::input(Iv::new(-r, r))
}

/// The blend of a `w` × `h` level whose texel (i, j) `fetch` reads at `uv`, where the
/// coordinates fall in one cell: `None` elsewhere.
fn bilinear(
    w: u32,
    h: u32,
    s: &Sampler,
    uv: [Af; 2],
    p: Precision,
    fetch: &dyn Fn(u32, u32) -> [f32; 4],
) -> Option<[Af; 4]> {
    let l = Af::lit;
    let x = uv[0] * l(w as f32) - l(0.5);
    let y = uv[1] * l(h as f32) - l(0.5);
    let cell = |v: Af| -> Option<f64> {
        let r = v.to_iv();
        if r.full || !r.lo.is_finite() || !r.hi.is_finite() {
            return None;
        }
        let k = r.lo.floor();
        (r.hi < k + 1.0).then_some(k)
    };
    let (i, j) = (cell(x)?, cell(y)?);
    let step = p.weight_step();
    let alpha = x - l(i as f32) + noise(step);
    let beta = y - l(j as f32) + noise(step);
    let (i, j) = (i as i64, j as i64);
    let at = |a: i64, b: i64| fetch(s.address_mode_u.apply(a, w), s.address_mode_v.apply(b, h));
    let tx = [at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)];
    if tx.iter().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    let big = tx.iter().flatten().fold(0.0f64, |m, v| m.max(f64::from(*v).abs()));
    let slack = FILTER_ULPS * f32_ulp(big) + big * 1e-12;
    Some(std::array::from_fn(|c| {
        let t = tx.map(|t| l(t[c]));
        let top = t[0] + alpha * (t[1] - t[0]);
        let bottom = t[2] + alpha * (t[3] - t[2]);
        top + beta * (bottom - top) + noise(slack)
    }))
}

/// Each channel's form, cut by the interval envelope `iv`; fresh inputs where there is none.
fn cut(iv: [Iv; 4], af: Option<[Af; 4]>) -> [Af; 4] {
    match af {
        Some(a) => std::array::from_fn(|c| a[c].cut(iv[c])),
        None => iv.map(Af::input),
    }
}

/// `textureSampleLevel(t, s, uv, 0)`.
pub fn sample_level0(t: &Texture2D, s: &Sampler, uv: [Af; 2], p: Precision) -> [Af; 4] {
    let iv = filter::sample_level0_p(t, s, uv.map(Af::to_iv), p);
    cut(iv, bilinear(t.width, t.height, s, uv, p, &|i, j| t.texel(i, j)))
}

/// `textureSampleLevel(chain, s, uv, lod)`: one level, or where the LOD lies between two
/// levels d and d + 1, their blend by λ − d within one step of the mipmap bits.
pub fn sample_mip(chain: &MipChain, s: &Sampler, uv: [Af; 2], lod: Af, p: Precision) -> [Af; 4] {
    let l = Af::lit;
    let iv = filter::sample_mip(chain, s, uv.map(Af::to_iv), lod.to_iv(), p);
    let level = |k: u32| {
        let [w, h] = chain.size(k);
        bilinear(w, h, s, uv, p, &|i, j| chain.texel(k, i, j))
    };
    let last = chain.levels.saturating_sub(1);
    let lod = lod.max(l(0.0)).min(l(last as f32));
    let r = lod.to_iv();
    if r.full || !r.lo.is_finite() || !r.hi.is_finite() {
        return iv.map(Af::input);
    }
    let d = r.lo.floor();
    let blended = if d >= f64::from(last) {
        level(last)
    } else if r.hi < d + 1.0 {
        let d = d as u32;
        level(d).zip(level(d + 1)).map(|(c0, c1)| {
            let f = lod - l(d as f32) + noise(p.mip_step());
            std::array::from_fn(|c| {
                let slack =
                    FILTER_ULPS * f32_ulp(c0[c].to_iv().magnitude().max(c1[c].to_iv().magnitude()));
                c0[c] + f * (c1[c] - c0[c]) + noise(slack)
            })
        })
    } else {
        None
    };
    cut(iv, blended)
}
