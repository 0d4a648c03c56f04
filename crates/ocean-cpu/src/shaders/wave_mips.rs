//! CPU mirror of `shaders/wave_mips.wgsl`: the mip chain of a slope map with its second
//! moments, level by level as the compute stage writes it.

use ocean_core::frame::WaveMipsUniforms;

use crate::envelope::{Iv, Jitter, JitterRules, Real};
use crate::mip::{MipChain, fill_level, level_count, level_row, level_size};
use crate::sampler::Texture2D;

/// `moments(id)`: texel `id` of level 0 from the slope map `src`.
pub fn moments(id: [u32; 2], src: &Texture2D) -> [f32; 4] {
    moments_r(id, src)
}

/// [`moments`] over any [`Real`] (the texel read exactly).
pub fn moments_r<R: Real>(id: [u32; 2], src: &Texture2D) -> [R; 4] {
    let s = src.texel(id[0], id[1]).map(R::lit);
    [s[0], s[1], s[0] * s[0], s[1] * s[1]]
}

/// `downsample(id)`: texel `id` of the level after `src`.
pub fn downsample(id: [u32; 2], params: &WaveMipsUniforms, src: &Texture2D) -> [f32; 4] {
    downsample_r(id, params, src)
}

/// [`downsample`] over any [`Real`]: `((a + b) + (c + d)) * 0.25`, a sum a GPU may
/// reassociate.
pub fn downsample_r<R: Real>(id: [u32; 2], params: &WaveMipsUniforms, src: &Texture2D) -> [R; 4] {
    let x0 = (2 * id[0]).min(params.src_width - 1);
    let x1 = (2 * id[0] + 1).min(params.src_width - 1);
    let y0 = (2 * id[1]).min(params.src_height - 1);
    let y1 = (2 * id[1] + 1).min(params.src_height - 1);
    let (a, b) = (src.texel(x0, y0), src.texel(x1, y0));
    let (c, d) = (src.texel(x0, y1), src.texel(x1, y1));
    std::array::from_fn(|k| {
        let t = [a[k], b[k], c[k], d[k]].map(R::lit);
        R::sum_as_written(&t, |t| (t[0] + t[1]) + (t[2] + t[3])) * R::lit(0.25)
    })
}

/// The envelope of a GPU's chain given what it read: level 0 from the GPU's slope map
/// `slopes`, each later level from the GPU's own level before it (`chain`, its atlas).
/// [`MipChain`]'s atlas layout, `None` in the padding.
///
/// # Panics
/// If `chain` is not the full chain of `slopes`.
pub fn envelope(slopes: &Texture2D, chain: &MipChain) -> Vec<Option<[Iv; 4]>> {
    let (w, h) = (slopes.width, slopes.height);
    assert_eq!([chain.width, chain.height, chain.levels], [w, h, level_count(w, h)], "the chain");
    // Each level's envelope reads the GPU's own level before it, not the envelope's, so the
    // levels are independent: each goes straight to its rows of the atlas (a list of levels
    // packed afterwards cost a third of the pass in page faults: 8 MB at 256²).
    let mut atlas = vec![None; w as usize * level_row(h, chain.levels) as usize];
    fill_level(&mut atlas, w, h, 0, |p| Some(moments_r(p, slopes)));
    for k in 1..chain.levels {
        let [lw, lh] = level_size(w, h, k);
        let src = chain.level(k - 1);
        let params = WaveMipsUniforms::new([lw, lh], [src.width, src.height]);
        fill_level(&mut atlas, w, h, k, |p| Some(downsample_r(p, &params, &src)));
    }
    atlas
}

/// The chain as one random conformant GPU computes it (`rules`).
pub fn jitter(slopes: &Texture2D, rules: JitterRules) -> MipChain {
    let (w, h) = (slopes.width, slopes.height);
    let unwrap = |v: [Jitter; 4]| v.map(|c| c.0);
    let texels = (0..w * h)
        .map(|k| {
            Jitter::reseed(rules, u64::from(k));
            unwrap(moments_r([k % w, k / w], slopes))
        })
        .collect();
    let mut levels = vec![Texture2D::new(w, h, texels)];
    for k in 1..level_count(w, h) {
        let [lw, lh] = level_size(w, h, k);
        let src = &levels[k as usize - 1];
        let params = WaveMipsUniforms::new([lw, lh], [src.width, src.height]);
        let texels = (0..lw * lh)
            .map(|t| {
                Jitter::reseed(rules, (u64::from(k) << 32) + u64::from(t));
                unwrap(downsample_r([t % lw, t / lw], &params, src))
            })
            .collect();
        levels.push(Texture2D::new(lw, lh, texels));
    }
    MipChain::from_levels(&levels)
}

/// The whole chain of `slopes` (one dispatch of `moments`, then one of `downsample` per
/// level), packed as [`MipChain`] holds it.
pub fn dispatch(slopes: &Texture2D) -> MipChain {
    let (w, h) = (slopes.width, slopes.height);
    let texels = (0..w * h).map(|k| moments([k % w, k / w], slopes)).collect();
    let mut levels = vec![Texture2D::new(w, h, texels)];
    for k in 1..level_count(w, h) {
        let [lw, lh] = level_size(w, h, k);
        let src = &levels[k as usize - 1];
        let params = WaveMipsUniforms::new([lw, lh], [src.width, src.height]);
        let texels = (0..lw * lh).map(|t| downsample([t % lw, t / lw], &params, src)).collect();
        levels.push(Texture2D::new(lw, lh, texels));
    }
    MipChain::from_levels(&levels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_box_means_of_the_moments() {
        // Level k's texel is the mean over its 2^k × 2^k block of level 0 (cut at the edge of
        // this 8×4 map): exact here, the values being small whole numbers.
        let (w, h) = (8u32, 4u32);
        let slopes = Texture2D::new(
            w,
            h,
            (0..w * h).map(|k| [(k % 5) as f32, (k % 3) as f32, 9.0, 9.0]).collect(),
        );
        let chain = dispatch(&slopes);
        assert_eq!(chain.levels, 4);
        for k in 0..chain.levels {
            let [lw, lh] = chain.size(k);
            for j in 0..lh {
                for i in 0..lw {
                    // The block of level 0 the texel stands for, cut at the map's edge (a
                    // level one texel wide clamps, averaging the same texels twice).
                    let block = |n: u32, len: u32| n << k..((n + 1) << k).min(len);
                    let mut sum = [0.0f64; 4];
                    let mut count = 0.0;
                    for y in block(j, h) {
                        for x in block(i, w) {
                            let s = slopes.texel(x, y);
                            let m = [s[0], s[1], s[0] * s[0], s[1] * s[1]];
                            for c in 0..4 {
                                sum[c] += f64::from(m[c]);
                            }
                            count += 1.0;
                        }
                    }
                    let got = chain.texel(k, i, j);
                    for c in 0..4 {
                        assert_eq!(f64::from(got[c]), sum[c] / count, "level {k} ({i}, {j}) {c}");
                    }
                }
            }
        }
    }
}
