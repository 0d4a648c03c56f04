//! White water: stage `foam`'s techniques, in the f32 arithmetic that `shaders/shared/foam.wgsl`
//! and `shaders/foam/<technique>.wgsl` write out and the CPU mirrors run, and the uniforms
//! they read ([`FoamBlock`], the last block of [`crate::frame::FrameUniforms`]).
//!
//! Every technique gives a **turbulence** t ∈ [0, 1] at the surface point; the foam texture
//! n ∈ [0, 1) breaks it into patches, and the share of the pixel the foam covers is
//! `coverage · clamp((t − 0.6 n)·2.5, 0, 1)` ([`foam_mix`]): rising with t everywhere, full
//! where t = 1, patchy in between. The water's fragment shader draws the foam over the shaded
//! water by that share, as a Lambertian surface of albedo `[foam] color` lit by the sun
//! (shadowed as the water is) and the sky's ambient light, with the objects' lighting
//! ([`FOAM_INV_PI`]). Zero coverage leaves the water's colour untouched, bit for bit.
//!
//! - `heuristic` (seed 002, §Water Surface: "a combination of the normal and height of the
//!   wave are used to estimate areas of turbulence … such as on the crests"): with h the
//!   point's height above the mean sea plane, s the slope of the displaced surface and J the
//!   horizontal Jacobian,
//!   t = clamp(h/crest_height_m, 0, 1) · clamp(s/crest_slope, 0, 1) · clamp((1 − J)/softness, 0, 1):
//!   foam where a crest is high, steep *and* compressed, each factor rising from 0 (at the mean
//!   plane, on flat water, where the surface is not compressed) to 1. A product, so that no
//!   one of them alone whitens the sea: the upper flank of a long swell is high but neither
//!   steep nor compressed, a trough is compressed under a choppy sea but below the mean plane
//!   (an earlier form, (h/crest_height)·(s/crest_slope) − 1, whitened whole swell flanks near
//!   the eye). t = 0 wherever h ≤ 0 or J ≥ 1, so foam never covers a trough or a stretched
//!   surface. s = |∇h|/max(J, 0.1): the slope of the displaced surface, exact in one
//!   dimension (dh/dx' = h'(x)/(1 + D'(x))).
//! - `jacobian`: t = clamp((threshold − J)/softness, 0, 1): foam where the horizontal
//!   displacement compresses (J < 1) or folds (J < 0) the surface (Tessendorf 2001 §4.4).
//! - `accumulated`: a field f carried across frames in [`crate::graph::FrameState`], one fixed
//!   step of `[foam] step_s` per frame ([`accumulate_step`]):
//!   f ← min(f·e^(−Δt/τ) + g·Δt·clamp((threshold − J)/softness, 0, 1), 1), from f = 0;
//!   t = f. Under waves `fft` the field lives on the displacement map's own texel grid
//!   (periodic with the patch, so world-fixed by construction; texel (i, j) takes J from the
//!   same texel of the map). Under waves `gerstner` it lives on a world-fixed lattice of
//!   `[foam] cell_m` spacing, `[foam] grid` points a side, addressed toroidally around the
//!   camera: lattice point I is stored in texel I mod grid, the window holds the points
//!   I ∈ [O, O + grid) with O = floor(eye/cell) − grid/2, and a texel whose point changed
//!   since the last step (the camera moved) starts empty ([`FoamStepUniforms`]); J is the
//!   waves' analytic Jacobian at the lattice point. The water samples the field bilinearly
//!   (repeat addressing: the torus) and fades it out towards the window's edge.
//!
//! The foam texture is value noise on a lattice whose axes run along and across the wind, its
//! cells `texture_scale_m` wide and [`FOAM_STREAK`] times that long (foam streaks downwind),
//! periodic over [`FOAM_NOISE_PERIOD`] cells so the mesh's reference point can be reduced
//! modulo the period in f64 ([`FoamBlock::noise_origin`]): two octaves of an integer hash
//! (multiply–xorshift, as the clouds'), blended with smoothstep weights.

use bytemuck::{Pod, Zeroable};

/// The noise lattice's period, cells (a power of two).
pub const FOAM_NOISE_PERIOD: u32 = 256;

/// How many times longer than wide a cell of the foam texture is along the wind: white water
/// is drawn out downwind into streaks (windrows), so a patch of foam is longer than it is
/// wide in the direction the wind blows.
pub const FOAM_STREAK: f64 = 3.0;
/// 1/π of the foam's Lambertian lighting (the objects' `INV_PI`).
pub const FOAM_INV_PI: f32 = std::f32::consts::FRAC_1_PI;
/// The smallest J the heuristic's slope divides by (a fold, J ≤ 0, is as steep as this).
pub const FOAM_MIN_JACOBIAN: f32 = 0.1;

/// [`FoamBlock::mode`] of foam `none` (WGSL `FOAM_NONE`, shared/frame.wgsl).
pub const FOAM_NONE: f32 = 0.0;
/// [`FoamBlock::mode`] of foam `heuristic` (WGSL `FOAM_HEURISTIC`).
pub const FOAM_HEURISTIC: f32 = 1.0;
/// [`FoamBlock::mode`] of foam `jacobian` (WGSL `FOAM_JACOBIAN`).
pub const FOAM_JACOBIAN: f32 = 2.0;
/// [`FoamBlock::mode`] of foam `accumulated` (WGSL `FOAM_ACCUMULATED`).
pub const FOAM_ACCUMULATED: f32 = 3.0;

impl crate::stage::Foam {
    /// The technique's number in [`FoamBlock::mode`] (the water shader's branch).
    pub fn code(self) -> f32 {
        use crate::stage::Foam;
        match self {
            Foam::None => FOAM_NONE,
            Foam::Heuristic => FOAM_HEURISTIC,
            Foam::Jacobian => FOAM_JACOBIAN,
            Foam::Accumulated => FOAM_ACCUMULATED,
        }
    }
}

/// Stage `foam`'s uniforms (WGSL `FoamBlock`, `shaders/shared/frame.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FoamBlock {
    /// 0 none, 1 heuristic, 2 jacobian, 3 accumulated.
    pub mode: f32,
    /// `[foam] coverage`.
    pub intensity: f32,
    /// `[foam] threshold`.
    pub threshold: f32,
    /// 1/`[foam] softness`.
    pub inv_softness: f32,
    /// `[foam] color`.
    pub color: [f32; 3],
    /// 1/`[foam] crest_height_m`.
    pub inv_crest_height: f32,
    /// The mesh's reference point on the texture's axes (along, across the wind), each modulo
    /// the noise's period on that axis (f64, rounded once), m.
    pub noise_origin: [f32; 2],
    /// 1/`[foam] texture_scale_m`: the texture's cells across the wind.
    pub inv_noise_cell: f32,
    /// 1/`[foam] crest_slope`.
    pub inv_crest_slope: f32,
    /// `accumulated`: the mesh's reference point modulo the field's side (m).
    pub field_origin: [f32; 2],
    /// `accumulated`: 1/(the field's side, m).
    pub inv_field_size: f32,
    /// `accumulated`: ½ texel of the field, in texture units.
    pub field_half_texel: f32,
    /// `accumulated` on a lattice around the camera: the horizontal distance from the eye
    /// where the field has faded out, m (0: no window, the field covers the sea).
    pub window_outer: f32,
    /// 1/(the width of the fade), 1/m.
    pub inv_window_band: f32,
    /// `[foam] seed`.
    pub seed: u32,
    /// 1/(`[foam] texture_scale_m` · [`FOAM_STREAK`]): the texture's cells along the wind.
    pub inv_noise_cell_along: f32,
    /// The unit vector the wind blows towards, (x, z): the texture's along-wind axis.
    pub wind: [f32; 2],
    /// Padding.
    pub pad0: f32,
    /// Padding.
    pub pad1: f32,
}

/// Where the `accumulated` field lives: its side (texels), spacing (m) and whether it is a
/// lattice around the camera (waves `gerstner`) or the displacement map's grid (`fft`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldGrid {
    /// Texels per side.
    pub size: u32,
    /// Metres between texels.
    pub cell_m: f64,
    /// A lattice around the camera (true) or the periodic map's grid.
    pub windowed: bool,
}

impl FieldGrid {
    /// The side of the field, m.
    pub fn side_m(&self) -> f64 {
        self.cell_m * f64::from(self.size)
    }

    /// The lattice index of the window's first point along each axis for an eye at world
    /// (x, z): floor(eye/cell) − size/2 (0 for the map's grid, which does not move).
    pub fn window_start(&self, eye: [f64; 2]) -> [i64; 2] {
        if !self.windowed {
            return [0, 0];
        }
        eye.map(|e| (e / self.cell_m).floor() as i64 - i64::from(self.size / 2))
    }
}

/// A lattice value in [0, 1) for cell (i, j) (wrapped to the period) of octave `octave`:
/// multiply–xorshift over the cell, the octave and the seed, the top 24 bits.
pub fn foam_hash(i: i32, j: i32, octave: u32, seed: u32) -> f32 {
    let wrap = FOAM_NOISE_PERIOD - 1;
    let (i, j) = ((i as u32) & wrap, (j as u32) & wrap);
    let mut h = i.wrapping_mul(0x8da6_b343)
        ^ j.wrapping_mul(0xd816_3841)
        ^ octave.wrapping_mul(0x9e37_79b9)
        ^ seed.wrapping_mul(0x85eb_ca6b);
    h = (h ^ (h >> 15)).wrapping_mul(0x2c1b_3c6d);
    h = (h ^ (h >> 12)).wrapping_mul(0x297a_2d39);
    h ^= h >> 15;
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Value noise at (x, z) in lattice cells: the four corners' hashes blended with the
/// smoothstep weights 3t² − 2t³, each pair as a·(1 − u) + b·u.
pub fn foam_value_noise(x: f32, z: f32, octave: u32, seed: u32) -> f32 {
    let fx = x.floor();
    let fz = z.floor();
    let (i, j) = (fx as i32, fz as i32);
    let tx = x - fx;
    let tz = z - fz;
    let ux = tx * tx * (3.0 - 2.0 * tx);
    let uz = tz * tz * (3.0 - 2.0 * tz);
    let a = foam_hash(i, j, octave, seed);
    let b = foam_hash(i.wrapping_add(1), j, octave, seed);
    let c = foam_hash(i, j.wrapping_add(1), octave, seed);
    let d = foam_hash(i.wrapping_add(1), j.wrapping_add(1), octave, seed);
    let ab = a * (1.0 - ux) + b * ux;
    let cd = c * (1.0 - ux) + d * ux;
    ab * (1.0 - uz) + cd * uz
}

/// The foam texture at (x, z) in lattice cells: two octaves, 2/3 and 1/3.
pub fn foam_texture(x: f32, z: f32, seed: u32) -> f32 {
    let n0 = foam_value_noise(x, z, 0, seed);
    let n1 = foam_value_noise(x * 2.0, z * 2.0, 1, seed);
    (n0 * 2.0 + n1) * (1.0 / 3.0)
}

/// The share of the pixel the foam covers for turbulence `t` and texture value `n`.
pub fn foam_mix(t: f32, n: f32, intensity: f32) -> f32 {
    ((t - 0.6 * n) * 2.5).clamp(0.0, 1.0) * intensity
}

/// `heuristic`'s turbulence for height `h` (m), slope magnitude `s` of the undisplaced
/// parameterisation and Jacobian `j`: high × steep × compressed (the module doc).
pub fn heuristic_turbulence(h: f32, s: f32, j: f32, foam: &FoamBlock) -> f32 {
    let slope = s / j.max(FOAM_MIN_JACOBIAN);
    let high = (h * foam.inv_crest_height).clamp(0.0, 1.0);
    let steep = (slope * foam.inv_crest_slope).clamp(0.0, 1.0);
    let compressed = ((1.0 - j) * foam.inv_softness).clamp(0.0, 1.0);
    high * steep * compressed
}

/// `jacobian`'s turbulence (and `accumulated`'s source) for Jacobian `j`.
pub fn jacobian_turbulence(j: f32, foam: &FoamBlock) -> f32 {
    ((foam.threshold - j) * foam.inv_softness).clamp(0.0, 1.0)
}

/// The uniforms of one `accumulated` step (stage `foam`, `shaders/foam.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FoamStepUniforms {
    /// Texels per side of the field.
    pub size: u32,
    /// 1: J from the waves' analytic Jacobian at the lattice point (`gerstner`); 0: from the
    /// displacement map's texel (`fft`).
    pub analytic: u32,
    /// The window's first lattice index modulo the size, per axis, this step.
    pub start: [u32; 2],
    /// The same for the previous step.
    pub start_prev: [u32; 2],
    /// This step's first index minus the previous step's, per axis, clamped to ±size (a
    /// texel whose lattice point changed starts empty).
    pub shift: [i32; 2],
    /// The window's first point relative to the mesh's reference point, m (f64, rounded
    /// once).
    pub start_rel: [f32; 2],
    /// The lattice's spacing, m.
    pub cell_m: f32,
    /// e^(−Δt/τ).
    pub decay: f32,
    /// g·Δt.
    pub growth: f32,
    /// `[foam] threshold`.
    pub threshold: f32,
    /// 1/`[foam] softness`.
    pub inv_softness: f32,
    /// Padding.
    pub pad0: f32,
}

/// One texel's step: `f` the field's value, `j` the Jacobian there, `fresh` whether the
/// texel's lattice point entered the window this step.
pub fn accumulate_step(f: f32, j: f32, fresh: bool, u: &FoamStepUniforms) -> f32 {
    let kept = if fresh { 0.0 } else { f };
    let source = ((u.threshold - j) * u.inv_softness).clamp(0.0, 1.0);
    (kept * u.decay + u.growth * source).min(1.0)
}

/// Whether texel `i` (one axis) holds another lattice point than at the previous step:
/// its point is start + ((i − start) mod size); the difference between the two steps'
/// points is shift + a − b.
pub fn texel_is_fresh(i: u32, axis: usize, u: &FoamStepUniforms) -> bool {
    let a = (i + u.size - u.start[axis]) % u.size;
    let b = (i + u.size - u.start_prev[axis]) % u.size;
    u.shift[axis] + a as i32 - b as i32 != 0
}

/// The offset (texels, 0..size) of texel `i` from the window's first point on one axis.
pub fn texel_offset(i: u32, axis: usize, u: &FoamStepUniforms) -> u32 {
    (i + u.size - u.start[axis]) % u.size
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn the_hash_is_uniform_enough_and_the_noise_stays_in_range() {
        let mut sum = 0.0;
        for i in 0..256 {
            for j in 0..256 {
                let h = foam_hash(i, j, 0, 7);
                assert!((0.0..1.0).contains(&h));
                sum += f64::from(h);
            }
        }
        let mean = sum / 65536.0;
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
        for k in 0..1000 {
            let x = k as f32 * 0.37 - 100.0;
            let n = foam_texture(x, x * 0.7 + 3.0, 7);
            assert!((0.0..1.0).contains(&n), "{n}");
        }
        // Periodic over the lattice's period.
        let p = FOAM_NOISE_PERIOD as f32;
        assert_eq!(foam_value_noise(3.25, 7.5, 0, 1), foam_value_noise(3.25 + p, 7.5 - p, 0, 1));
    }

    #[test]
    fn a_moved_window_empties_exactly_the_texels_that_changed_point() {
        let scene = Scene::builtin();
        let grid = FieldGrid { size: 8, cell_m: 1.0, windowed: true };
        for (start, prev) in [([5, -3], [5, -3]), ([6, -3], [5, -3]), ([-20, 4], [3, 9])] {
            let u = FoamStepUniforms::new(&scene, &grid, start, prev, [0.0, 0.0]);
            for axis in 0..2 {
                for i in 0..8u32 {
                    let point = |s: i64| s + (i64::from(i) - s).rem_euclid(8);
                    let changed = point(start[axis]) != point(prev[axis]);
                    assert_eq!(texel_is_fresh(i, axis, &u), changed, "{start:?} {prev:?} {i}");
                }
            }
        }
    }
}
