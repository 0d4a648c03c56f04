//! The displacement map and the bump map of seed 000 §2.1: "low- and high-frequency sampling"
//! of one spectrum, each sampled "above the Nyquist limit" so that nothing aliases.
//!
//! Lattices. The displacement map is the patch L at resolution N_d: wave vectors
//! k = 2π(n, m)/L, Δk_d = 2π/L, holding the square band max(|n|, |m|) < N_d/2. The bump map is
//! the patch L_b = L/r (integer r ≥ 1, so a bump tile repeats exactly r times across a
//! displacement tile and the sum of both maps is L-periodic) at resolution N_b: wave vectors
//! k = 2π(n, m)/L_b = 2π·r(n, m)/L, a coarser lattice in k (Δk_b = r·Δk_d, every r-th point of
//! the displacement lattice) reaching a higher Nyquist wavenumber πN_b/L_b = πrN_b/L.
//!
//! Bands. The bump map holds only its modes outside the displacement band,
//! max(|kx|, |kz|) ≥ πN_d/L (tested on the integer index: 2r·max(|n|, |m|) ≥ N_d), so no wave
//! is counted twice; each map holds only modes strictly below its own Nyquist wavenumber, so
//! nothing aliases. Together they cover the square max(|kx|, |kz|) < πrN_b/L: the
//! displacement map the inner square [−πN_d/L, πN_d/L)², the bump map the frame around it.
//! A wave vector gets the same random numbers in either map (both are keyed by the
//! displacement-lattice index), and since the bands are disjoint no two modes share them.
//!
//! Energy. Each mode's amplitude uses its own lattice's cell, E|h0|² = F Δk² w/2 with Δk_d or
//! Δk_b, so each map's variance is a Riemann sum of ∫∫ F over its band, and the total
//! variance ≈ ∫∫ F over the union band. The cells must tile the union band for that: the
//! displacement cells (side Δk_d) end at the Chebyshev radius (⌈N_d/2⌉ − ½)Δk_d, but the
//! bump cells (side Δk_b = rΔk_d) of its innermost ring reach inside that radius (or stop
//! short of it) by up to (r − 1)/2·Δk_d. The bump map's edge cells are therefore stretched or
//! shrunk to meet the displacement cells exactly, and their modes weighted by their cell's
//! area (w ≠ 1, [`Band::ExcludeGrid`]); the cells then tile the union band with neither
//! overlap nor gap, and what remains is the quadrature error of the midpoint rule, largest
//! where F varies fast on the coarse bump lattice.
//!
//! The bump map's useful output is its slopes (slope_x, slope_z) = (du, dv); its height and
//! choppy fields are computed the same way and kept.

use super::modes::{Band, ModeParams, WaveModes, check_grid};
use crate::dispersion::Dispersion;
use crate::{Error, Result};

/// What defines a displacement map and a bump map of one spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OceanParams {
    /// Side L of the displacement patch, metres.
    pub patch_size_m: f64,
    /// N_d, the displacement map's resolution.
    pub displacement_resolution: usize,
    /// r ≥ 1: the bump patch is L/r.
    pub bump_ratio: usize,
    /// N_b, the bump map's resolution; must exceed 2⌈N_d/2r⌉, else the bump map would
    /// hold no mode.
    pub bump_resolution: usize,
    /// Seed of the random amplitudes (shared: the modes are keyed by wave vector).
    pub seed: u64,
    /// The dispersion relation (and loop period) of both maps.
    pub dispersion: Dispersion,
}

/// The two maps of one ocean.
#[derive(Clone, Debug)]
pub struct OceanSurface {
    /// Patch L, resolution N_d, band max(|n|, |m|) < N_d/2.
    pub displacement: WaveModes,
    /// Patch L/r, resolution N_b, the modes outside the displacement band.
    pub bump: WaveModes,
}

impl OceanSurface {
    /// Draws both maps' modes for the spectrum `density` (see [`WaveModes::new`]).
    pub fn new(params: &OceanParams, density: impl Fn(f64, f64) -> f64 + Sync) -> Result<Self> {
        check_grid(params.patch_size_m, params.displacement_resolution)?;
        let r = params.bump_ratio;
        if r == 0 {
            return Err(Error::InvalidParameter {
                name: "bump_ratio",
                value: 0.0,
                reason: "must be an integer ≥ 1 (the bump patch is L / ratio)".into(),
            });
        }
        // The bump map holds index n iff 2r|n| ≥ N_d and 2|n| < N_b: the smallest such |n|
        // is ⌈N_d / 2r⌉, so there is one iff 2⌈N_d / 2r⌉ < N_b.
        let n_d = params.displacement_resolution;
        let smallest_index = n_d.div_ceil(r.saturating_mul(2));
        if 2 * smallest_index >= params.bump_resolution {
            return Err(Error::InvalidParameter {
                name: "bump_resolution",
                value: params.bump_resolution as f64,
                reason: format!(
                    "must exceed 2·⌈displacement_resolution / (2·bump_ratio)⌉ = {} \
                     (displacement_resolution {n_d}, bump_ratio {r}), else the bump map \
                     holds no wave beyond the displacement map's",
                    2 * smallest_index
                ),
            });
        }
        let displacement = WaveModes::new(
            &ModeParams::new(params.patch_size_m, params.displacement_resolution, params.seed),
            params.dispersion,
            &density,
        )?;
        let bump = WaveModes::new(
            &ModeParams {
                patch_size_m: params.patch_size_m / r as f64,
                resolution: params.bump_resolution,
                lattice_ratio: r,
                seed: params.seed,
                band: Band::ExcludeGrid { resolution: params.displacement_resolution },
            },
            params.dispersion,
            &density,
        )?;
        Ok(Self { displacement, bump })
    }

    /// Σ F Δk² over both bands: the expected variance of displacement + bump heights, m².
    pub fn expected_variance(&self) -> f64 {
        self.displacement.expected_variance() + self.bump.expected_variance()
    }
}
