//! Mip chains and `textureSampleLevel` with a linear mip filter, as lavapipe computes them.
//!
//! **Levels.** Level k of a W × H texture is max(1, W >> k) × max(1, H >> k) (Vulkan's rule);
//! there are ⌊log2 max(W, H)⌋ + 1 levels. How a level is made from the one below is the
//! writer's business (`shaders::wave_mips`: the 2×2 box); this module only stores and samples
//! them.
//!
//! **Storage.** The levels are packed into one texture, [`MipChain::atlas`], `W` wide: level 0
//! in rows 0..H, level 1 in the next H >> 1 rows from column 0, and so on, the rest of each
//! row zero. It is the layout the GPU cross-check reads the chain back into, so a chain
//! compares as one float map.
//!
//! **Sampling with an explicit LOD** ([`texture_sample_level_mip`], WGSL
//! `textureSampleLevel(t, s, coords, lod)` with `mipmap_filter: Linear`), as gallivm (Mesa's
//! llvmpipe, which lavapipe runs) does it and as `tests/gpu_cross_check.rs` measures on random
//! coordinates and LODs:
//!
//! 1. λ = clamp(lod, 0, 32) (the sampler's `lod_min_clamp`/`lod_max_clamp`; NaN gives 0);
//! 2. level₀ = ⌊λ⌋, f = λ − ⌊λ⌋ in f32; if level₀ ≥ the last level, level₀ = last and f = 0;
//! 3. c₀ = the bilinear sample of level₀ (the rule of [`crate::sampler`], at that level's
//!    size), and, when f > 0, c₁ = that of level₀ + 1;
//! 4. the result is fma(f, c₁ − c₀, c₀) per channel (gallivm's `lp_build_lerp`, the same fused
//!    form as the bilinear weights).

use crate::sampler::{FilterMode, Sampler, Texture2D, bilinear_at};

/// A texture with its mip levels, packed as the module doc says.
#[derive(Clone, Debug, PartialEq)]
pub struct MipChain {
    /// Width of level 0.
    pub width: u32,
    /// Height of level 0.
    pub height: u32,
    /// Number of levels.
    pub levels: u32,
    /// The packed levels.
    pub atlas: Texture2D,
}

pub use ocean_core::far_field::{
    mip_level_count as level_count, mip_level_row as level_row, mip_level_size as level_size,
};

impl MipChain {
    /// A chain of one level: `texture` itself.
    pub fn single(texture: Texture2D) -> Self {
        Self { width: texture.width, height: texture.height, levels: 1, atlas: texture }
    }

    /// A chain from its levels, level 0 first, each the size [`level_size`] gives.
    ///
    /// # Panics
    /// If a level has the wrong size or there is none.
    pub fn from_levels(levels: &[Texture2D]) -> Self {
        let (w, h) = (levels[0].width, levels[0].height);
        for (k, level) in levels.iter().enumerate() {
            assert_eq!([level.width, level.height], level_size(w, h, k as u32), "level {k}");
        }
        let texels: Vec<&[[f32; 4]]> = levels.iter().map(|l| &l.texels[..]).collect();
        let rows = level_row(h, levels.len() as u32);
        Self {
            width: w,
            height: h,
            levels: levels.len() as u32,
            atlas: Texture2D::new(w, rows, pack_levels(w, h, &texels, [0.0; 4])),
        }
    }

    /// Size of level `k`.
    pub fn size(&self, k: u32) -> [u32; 2] {
        level_size(self.width, self.height, k)
    }

    /// Texel (i, j) of level `k`, both in range.
    #[inline]
    pub fn texel(&self, k: u32, i: u32, j: u32) -> [f32; 4] {
        self.atlas.texel(i, level_row(self.height, k) + j)
    }

    /// Level `k` as a texture of its own.
    pub fn level(&self, k: u32) -> Texture2D {
        let [w, h] = self.size(k);
        let texels =
            (0..h).flat_map(|j| (0..w).map(move |i| (i, j))).map(|(i, j)| self.texel(k, i, j));
        Texture2D::new(w, h, texels.collect())
    }
}

/// The atlas of a chain whose level 0 is `width` × `height`: `levels[k]` (row-major, level k's
/// size) in level k's rows from column 0, `fill` in the rest of each row.
///
/// # Panics
/// If a level holds fewer texels than its size.
pub fn pack_levels<T: Copy>(width: u32, height: u32, levels: &[&[T]], fill: T) -> Vec<T> {
    let rows = level_row(height, levels.len() as u32);
    let mut atlas = vec![fill; width as usize * rows as usize];
    for (k, level) in levels.iter().enumerate() {
        let [w, h] = level_size(width, height, k as u32);
        let row = level_row(height, k as u32) as usize;
        for j in 0..h as usize {
            let dst = (row + j) * width as usize;
            atlas[dst..dst + w as usize]
                .copy_from_slice(&level[j * w as usize..(j + 1) * w as usize]);
        }
    }
    atlas
}

/// Writes level `k` of a chain whose level 0 is `width` × `height` into its rows of `atlas`
/// (laid out as [`pack_levels`] lays it out), texel (i, j) from `texel([i, j])`: for levels
/// made texel by texel, without a list of levels to pack afterwards.
pub fn fill_level<T>(
    atlas: &mut [T],
    width: u32,
    height: u32,
    k: u32,
    mut texel: impl FnMut([u32; 2]) -> T,
) {
    let [w, h] = level_size(width, height, k);
    let row = level_row(height, k);
    for j in 0..h {
        let start = ((row + j) * width) as usize;
        for (i, d) in atlas[start..start + w as usize].iter_mut().enumerate() {
            *d = texel([i as u32, j]);
        }
    }
}

/// The bilinear sample of level `k` at `coords` (the sampler must filter linearly; a nearest
/// sampler reads the texel under the point).
fn sample_level(chain: &MipChain, sampler: &Sampler, coords: [f32; 2], k: u32) -> [f32; 4] {
    let [w, h] = chain.size(k);
    let row = level_row(chain.height, k);
    let fetch = |i: u32, j: u32| chain.atlas.texel(i, row + j);
    match sampler.filter {
        FilterMode::Linear => bilinear_at(w, h, sampler, coords, fetch),
        FilterMode::Nearest => crate::sampler::nearest_at(w, h, sampler, coords, fetch),
    }
}

/// The level pair and blend weight gallivm uses for an explicit `lod` (steps 1 and 2 of the
/// module doc): (level₀, f), with level₀ + 1 read only when f > 0.
pub fn mip_levels(lod: f32, levels: u32) -> (u32, f32) {
    // `max` then `min` maps NaN to 0, as the clamp of a NaN LOD does on the GPU.
    let lambda = 0.0f32.max(lod).min(32.0);
    let floor = lambda.floor();
    let last = levels.saturating_sub(1);
    let level = floor as u32;
    if level >= last { (last, 0.0) } else { (level, lambda - floor) }
}

/// WGSL `textureSampleLevel(t, s, coords, lod)` on a mip-mapped texture, linear between
/// levels (the module doc).
pub fn texture_sample_level_mip(
    chain: &MipChain,
    sampler: &Sampler,
    coords: [f32; 2],
    lod: f32,
) -> [f32; 4] {
    let (level, f) = mip_levels(lod, chain.levels);
    let c0 = sample_level(chain, sampler, coords, level);
    if f > 0.0 {
        let c1 = sample_level(chain, sampler, coords, level + 1);
        std::array::from_fn(|c| f.mul_add(c1[c] - c0[c], c0[c]))
    } else {
        c0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::AddressMode;

    const WRAP: Sampler = Sampler {
        address_mode_u: AddressMode::Repeat,
        address_mode_v: AddressMode::Repeat,
        filter: FilterMode::Linear,
    };

    #[test]
    fn level_rules() {
        assert_eq!(level_count(256, 256), 9);
        assert_eq!(level_count(1, 1), 1);
        assert_eq!(level_count(5, 3), 3);
        assert_eq!(level_size(5, 3, 2), [1, 1]);
        assert_eq!(level_row(8, 3), 8 + 4 + 2);
        assert_eq!(mip_levels(-1.0, 9), (0, 0.0));
        assert_eq!(mip_levels(f32::NAN, 9), (0, 0.0));
        assert_eq!(mip_levels(2.25, 9), (2, 0.25));
        assert_eq!(mip_levels(8.5, 9), (8, 0.0));
        assert_eq!(mip_levels(1e30, 9), (8, 0.0));
        assert_eq!(mip_levels(0.5, 1), (0, 0.0));
    }

    #[test]
    fn packing_round_trips_and_blends_between_levels() {
        let l0 = Texture2D::new(4, 4, (0..16).map(|k| [k as f32; 4]).collect());
        let l1 = Texture2D::new(2, 2, vec![[100.0; 4]; 4]);
        let l2 = Texture2D::new(1, 1, vec![[200.0; 4]]);
        let chain = MipChain::from_levels(&[l0.clone(), l1.clone(), l2.clone()]);
        assert_eq!((chain.atlas.width, chain.atlas.height), (4, 7));
        assert_eq!(chain.level(0), l0);
        assert_eq!(chain.level(1), l1);
        assert_eq!(chain.level(2), l2);
        // Halfway between two constant levels: the mean; beyond the last level: the last.
        assert_eq!(texture_sample_level_mip(&chain, &WRAP, [0.3, 0.7], 1.5), [150.0; 4]);
        assert_eq!(texture_sample_level_mip(&chain, &WRAP, [0.3, 0.7], 7.0), [200.0; 4]);
        // Level 0 alone is the plain bilinear sample.
        let plain = crate::sampler::texture_sample(&l0, &WRAP, [0.3, 0.7]);
        assert_eq!(texture_sample_level_mip(&chain, &WRAP, [0.3, 0.7], 0.0), plain);
    }
}
