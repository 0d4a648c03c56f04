//! Surface `clipmap` (seed 002; Asirvatham & Hoppe, GPU Gems 2 ch. 2; the morph of
//! Strugar's CDLOD): nested square grids around the eye, each level twice the spacing of the
//! one inside, drawn from the vertex index with no vertex buffer.
//!
//! **Levels.** Level l has n × n quads of side s_l = s₀·2^l (`[quality] clipmap_cell_m` = s₀,
//! `clipmap_cells` = n, a multiple of 8). Its centre is the eye's (x, z) snapped to a multiple
//! of 2·s_l, so that the vertices stay on a world-fixed lattice while the eye moves (nothing
//! swims) and every even vertex of level l is a vertex of level l + 1. Level 0 is a full square;
//! level l ≥ 1 leaves out the (n/2)² quads that level l − 1 covers (its *hole*, one quad off
//! centre at most, since the two centres are snapped to different grids). The coarsest level
//! reaches [`crate::geometry::HORIZON_DISTANCE_H`] times the eye's clearance (as the
//! projected grid), so the sea meets the sky within a millionth of a radian of the horizon,
//! unless [`MAX_CLIPMAP_LEVELS`] stops it first (eyes above ~4 km with the default cell).
//!
//! **Vertex positions are integers.** A vertex is g = C_l + (i − n/2)·2^l in units of s₀ from
//! the mesh's reference point c (the eye snapped to 2·s₀), an exact i32 for every level, so the
//! same world point gets the same f32 position (and so the same displacement, bit for bit)
//! whichever level draws it: the seam between levels is the same edge in both.
//!
//! **Morph.** Within each level the vertices slide towards the coarser lattice as their
//! Chebyshev distance from the eye, in quads, crosses the band [start, start + band]: the odd
//! coordinate moves to the even vertex below it by α·2^l (α the band's clamped ramp). At the
//! level's boundary (at least n/2 − 1 quads from the eye) α = 1 exactly, the odd vertices sit
//! on their even neighbours, and the level's outer edge is the next level's inner edge, vertex
//! for vertex: no T-junction, no crack. The next level's inner edge is at most n/4 + ½ of its
//! own quads from the eye, below its band's start, so it is not morphed there. As the eye
//! moves, a region changes level only where both levels agree, so nothing pops.
//!
//! **Waves.** A vertex takes the displacement filtered to the spacing of the vertices around
//! it, s = s_l·(1 + α′) with α′ the morph's ramp evaluated at the morphed point (s_l inside the
//! band, s_{l+1} at the level's edge, where the next level's vertex has s_{l+1} too): each
//! Gerstner wave is faded out between 8 and 4 vertices per wavelength; the FFT displacement map,
//! one band that cannot be filtered wave by wave, fades out likewise at the spectrum's peak
//! wavelength (deep water), so the swell stays while its vertices can carry it and the map's
//! shorter waves alias where the vertices are sparse, as they do on `hu_patches` and
//! `projected_grid` (displacement chains sampled at the spacing are the next step; a fade at
//! the map's texel size flattened the storm's swell 40 m from the eye). Evaluated at the
//! morphed point, s is the same for a vertex morphed onto another and for that other (with the
//! ramp at the vertex's own lattice point tests/clipmap.rs found slivers). The fragment shader
//! still takes every wave's slope, so far away the waves the geometry leaves out still shade
//! the sea (as a normal map does).

use bytemuck::Zeroable;

use crate::Result;

/// Most levels: 24 keep every integer vertex position within i32 for n ≤ 256.
pub const MAX_CLIPMAP_LEVELS: usize = 24;

/// Smallest and largest quads per level side (`[quality] clipmap_cells`).
pub const CLIPMAP_CELLS_RANGE: (u32, u32) = (16, 256);

/// The clipmap of one frame: its levels around an eye.
#[derive(Clone, Debug, PartialEq)]
pub struct Clipmap {
    /// n, quads per level side.
    pub cells: u32,
    /// s₀, level 0's quad side, m.
    pub cell_m: f64,
    /// The mesh's reference point c = 2·s₀·K₀ (world x, z), m.
    pub origin: [f64; 2],
    /// Per level: its centre C_l in units of s₀ from c.
    pub centres: Vec<[i64; 2]>,
    /// Per level l ≥ 1: the first quad (i, j) of its hole; level 0 has none.
    pub holes: Vec<[i64; 2]>,
    /// Per level: the eye's (x, z) relative to the level's centre, in its quads (within ±1).
    pub eye_in_cells: Vec<[f64; 2]>,
}

impl Clipmap {
    /// The clipmap around the eye at world (x, z) `eye_xz`, `clearance` m above (or below) the
    /// plane, with n = `cells` quads of `cell_m` m at level 0.
    pub fn new(eye_xz: [f64; 2], clearance: f64, cell_m: f64, cells: u32) -> Result<Self> {
        let bad =
            |name: &'static str, v: f64, why: &str| super::params::invalid(name, v, why.into());
        if !(cell_m.is_finite() && cell_m > 0.0) {
            return Err(bad("quality.clipmap_cell_m", cell_m, "must be finite and > 0"));
        }
        if !cells.is_multiple_of(8)
            || !(CLIPMAP_CELLS_RANGE.0..=CLIPMAP_CELLS_RANGE.1).contains(&cells)
        {
            return Err(bad(
                "quality.clipmap_cells",
                f64::from(cells),
                "must be a multiple of 8 in [16, 256]",
            ));
        }
        if !(eye_xz.iter().all(|v| v.is_finite()) && clearance.is_finite()) {
            return Err(bad("camera.position", f64::NAN, "must be finite"));
        }
        let levels = Self::levels_for(clearance, cell_m, cells);
        let k = |l: usize, x: f64| (x / (2.0 * cell_m * (1u64 << l) as f64)).round() as i64;
        let k0 = eye_xz.map(|x| k(0, x));
        let origin = k0.map(|v| 2.0 * cell_m * v as f64);
        let mut centres = Vec::with_capacity(levels);
        let mut holes = Vec::with_capacity(levels);
        let mut eye_in_cells = Vec::with_capacity(levels);
        let mut prev_k = k0;
        for l in 0..levels {
            let kl = eye_xz.map(|x| k(l, x));
            let step = 1i64 << l;
            let c = [0, 1].map(|a| 2 * step * kl[a] - 2 * k0[a]);
            centres.push(c);
            let s_l = cell_m * step as f64;
            eye_in_cells
                .push([0, 1].map(|a| (eye_xz[a] - (origin[a] + c[a] as f64 * cell_m)) / s_l));
            let quarter = i64::from(cells / 4);
            holes.push(if l == 0 {
                [-i64::from(cells); 2]
            } else {
                [0, 1].map(|a| prev_k[a] - 2 * kl[a] + quarter)
            });
            prev_k = kl;
        }
        Ok(Self { cells, cell_m, origin, centres, holes, eye_in_cells })
    }

    /// Levels that reach `HORIZON_DISTANCE_H`·clearance (clearance at least
    /// [`crate::geometry::PatchParams`]' default minimum height), at most
    /// [`MAX_CLIPMAP_LEVELS`].
    pub fn levels_for(clearance: f64, cell_m: f64, cells: u32) -> usize {
        let reach = super::projected::HORIZON_DISTANCE_H * clearance.abs().max(0.5);
        let mut levels = 1;
        while levels < MAX_CLIPMAP_LEVELS && Self::reach(levels, cell_m, cells) < reach {
            levels += 1;
        }
        levels
    }

    /// The least distance from the eye (Chebyshev, m) at which `levels` levels end.
    pub fn reach(levels: usize, cell_m: f64, cells: u32) -> f64 {
        (f64::from(cells / 2) - 1.0) * cell_m * (1u64 << (levels - 1)) as f64
    }

    /// Levels drawn.
    pub fn levels(&self) -> usize {
        self.centres.len()
    }

    /// Width of the morph band in quads: the largest power of two ≤ n/4 − 2 (a power of two so
    /// that α reaches 1 exactly on both back ends).
    pub fn band(cells: u32) -> u32 {
        let max = cells / 4 - 2;
        1 << (31 - max.leading_zeros())
    }

    /// Where the morph band starts, quads from the eye: n/2 − 1 − band.
    pub fn morph_start(cells: u32) -> u32 {
        cells / 2 - 1 - Self::band(cells)
    }

    /// Vertices the water pass draws: six per quad, n² quads per level (those of a level's
    /// hole are drawn as zero-area triangles).
    pub fn vertex_count(levels: usize, cells: u32) -> u64 {
        6 * u64::from(cells) * u64::from(cells) * levels as u64
    }

    /// The uniform block, for a displacement map whose spectrum peaks at wavelength
    /// `peak_wavelength_m` (`None`: no fade, as under waves `gerstner`, whose waves are
    /// filtered one by one, or a flat sea).
    pub fn block(&self, peak_wavelength_m: Option<f64>) -> ClipmapBlock {
        let mut b = ClipmapBlock::zeroed();
        b.levels = self.levels() as f32;
        b.cells = self.cells as f32;
        b.cell_m = self.cell_m as f32;
        b.morph_start = Self::morph_start(self.cells) as f32;
        b.inv_band = 1.0 / Self::band(self.cells) as f32;
        // The map's displacement fades out between 8 and 4 vertices per peak wavelength.
        (b.fade_end, b.fade_inv_span) = match peak_wavelength_m {
            Some(l) if l > 0.0 && l.is_finite() => ((l / 4.0) as f32, (8.0 / l) as f32),
            _ => (1.0e30, 1.0),
        };
        for l in 0..self.levels() {
            let (c, h) = (self.centres[l], self.holes[l]);
            b.level[l] = [c[0] as i32, c[1] as i32, h[0] as i32, h[1] as i32];
            let e = self.eye_in_cells[l];
            b.eye[l] = [e[0] as f32, e[1] as f32, (1u64 << l) as f32, 0.0];
        }
        b
    }
}

/// Surface `clipmap`'s uniforms ([`Clipmap`]); `levels` 0 under the other surfaces.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ClipmapBlock {
    /// Levels drawn.
    pub levels: f32,
    /// n, quads per level side.
    pub cells: f32,
    /// s₀, level 0's quad side, m.
    pub cell_m: f32,
    /// The morph band's start, quads from the eye.
    pub morph_start: f32,
    /// 1 / the band's width in quads (a power of two).
    pub inv_band: f32,
    /// The FFT displacement is gone at this vertex spacing, m (a quarter of the spectrum's
    /// peak wavelength).
    pub fade_end: f32,
    /// 1 / the fade's span, 1/m (an eighth of the peak wavelength).
    pub fade_inv_span: f32,
    /// Padding.
    pub pad0: f32,
    /// Per level: (C_x, C_z) its centre in units of s₀ from the reference point, (h_x, h_z)
    /// the first quad of its hole.
    pub level: [[i32; 4]; MAX_CLIPMAP_LEVELS],
    /// Per level: (e_x, e_z) the eye relative to its centre in its quads, 2^l, 0.
    pub eye: [[f32; 4]; MAX_CLIPMAP_LEVELS],
}

impl ClipmapBlock {
    /// Vertices the water pass draws (0 under the other surfaces), as
    /// [`Clipmap::vertex_count`] of the block's levels.
    pub fn vertex_count(&self) -> u32 {
        Clipmap::vertex_count(self.levels as usize, self.cells as u32) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_is_a_power_of_two_below_the_limit() {
        for n in (16..=256).step_by(8) {
            let b = Clipmap::band(n);
            assert!(b.is_power_of_two() && b <= n / 4 - 2 && 2 * b > n / 4 - 2, "n {n} band {b}");
            // The next level's inner edge (≤ n/4 + ½ of its quads away) is before the start.
            assert!(2 * Clipmap::morph_start(n) > n / 2 + 1, "n {n}");
        }
    }

    #[test]
    fn hole_is_the_inner_level_footprint() {
        for &x in &[0.0, 0.3, -0.7, 1.1, 1234.56, -98765.4321, 3.0e6] {
            let m = Clipmap::new([x, -0.5 * x + 0.2], 10.0, 0.5, 64).unwrap();
            for l in 1..m.levels() {
                let n = 64i64;
                // Level l − 1's square in units of s₀ against level l's hole.
                let lo_inner = m.centres[l - 1][0] - (n / 2) * (1 << (l - 1));
                let lo_hole = m.centres[l][0] + (m.holes[l][0] - n / 2) * (1 << l);
                assert_eq!(lo_inner, lo_hole, "x {x} level {l}");
                assert!((n / 4 - 1..=n / 4 + 1).contains(&m.holes[l][0]));
            }
            for e in &m.eye_in_cells {
                assert!(e[0].abs() <= 1.0 && e[1].abs() <= 1.0, "{e:?}");
            }
        }
    }

    #[test]
    fn reaches_the_horizon_distance() {
        let levels = Clipmap::levels_for(10.0, 0.5, 64);
        assert!(Clipmap::reach(levels, 0.5, 64) >= 1e7);
        assert!(Clipmap::reach(levels - 1, 0.5, 64) < 1e7);
        assert_eq!(Clipmap::levels_for(1e5, 0.5, 64), MAX_CLIPMAP_LEVELS);
    }

    #[test]
    fn refuses_bad_parameters() {
        assert!(Clipmap::new([0.0; 2], 1.0, 0.0, 64).is_err());
        assert!(Clipmap::new([0.0; 2], 1.0, 0.5, 60).is_err());
        assert!(Clipmap::new([0.0; 2], 1.0, 0.5, 264).is_err());
        assert!(Clipmap::new([f64::NAN, 0.0], 1.0, 0.5, 64).is_err());
    }
}
