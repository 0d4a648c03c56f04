//! Tables precomputed from the Fresnel term, laid out and sampled as the GPU does.
//!
//! - [`FresnelTable1D`]: F as a function of c = cos θ, the 1D texture of Heidrich & Seidel
//!   (1999) that seed 000 §5.1 starts from.
//! - [`FresnelTexture`]: the 2D Fresnel texture of seed 000 §5.1 and §5.3. Each texel stores a
//!   normalised view vector V in the local frame whose normal is +Z, and F(V·N) = F(z) in the
//!   fourth channel. The water shader looks up the bumped view vector (x_v − du, z_v − dv)
//!   directly (§5.1, Fig. 4), so neither the bumped normal nor V·N is formed per pixel, and the
//!   RGB channels give the normalised bumped view vector for the specular term (§5.3).
//!
//! Sampling follows the GPU rule that the CPU oracle also follows (docs/design.md, determinism
//! contract): texel centres at +0.5, clamp-to-edge addressing, bilinear (linear) filtering with
//! full-float weights, all in `f32`:
//! u = s·N − 0.5, i₀ = ⌊u⌋, w = u − i₀, i₁ = i₀ + 1, both indices clamped to [0, N − 1], and
//! lerp(a, b, w) = a + w·(b − a).

use std::f64::consts::{FRAC_PI_2, TAU};

use crate::fresnel::fresnel_exact;
use crate::{Error, Result};

/// The largest table size accepted: wgpu's default `max_texture_dimension_1d` and `_2d` limit,
/// 8192, so that every table this module builds can be uploaded to any adapter.
pub const MAX_TABLE_SIZE: usize = 8192;

fn check_size(n: usize) -> Result<()> {
    if n == 0 || n > MAX_TABLE_SIZE {
        return Err(Error::InvalidParameter {
            name: "table size",
            value: n as f64,
            reason: format!("must be between 1 and {MAX_TABLE_SIZE} (the GPU texture size limit)"),
        });
    }
    Ok(())
}

fn check_eta(eta: f64) -> Result<()> {
    if !(eta > 0.0 && eta.is_finite()) {
        return Err(Error::InvalidParameter {
            name: "eta",
            value: eta,
            reason: "the index ratio eta_t/eta_i must be finite and > 0".into(),
        });
    }
    Ok(())
}

/// The texel pair and weight that a linear, clamp-to-edge sampler reads at normalised
/// coordinate `coord` on an axis of `n` texels: (i₀, i₁, w) with value = a[i₀] + w·(a[i₁] −
/// a[i₀]).
///
/// Texel i covers [i/n, (i + 1)/n) and its centre is at (i + 0.5)/n, hence the −0.5. A NaN
/// coordinate is a caller's bug; it reads texel 0 (Rust's `as` maps NaN to 0) rather than
/// panicking.
fn linear_clamp_to_edge(coord: f32, n: usize) -> (usize, usize, f32) {
    let u = coord * n as f32 - 0.5;
    let u_floor = u.floor();
    let w = u - u_floor;
    // `as i64` saturates for coordinates far outside [0, 1]; the clamp is the addressing mode.
    let last = n as i64 - 1;
    let i0 = (u_floor as i64).clamp(0, last) as usize;
    let i1 = (u_floor as i64).saturating_add(1).clamp(0, last) as usize;
    (i0, i1, w)
}

fn lerp(a: f32, b: f32, w: f32) -> f32 {
    a + w * (b - a)
}

/// F over c = cos θ ∈ [0, 1] in N entries, as a 1D texture: entry i holds
/// F((i + 0.5)/N), the value at its texel centre.
#[derive(Clone, Debug, PartialEq)]
pub struct FresnelTable1D {
    eta: f64,
    values: Vec<f32>,
}

impl FresnelTable1D {
    /// Builds the table for the index ratio `eta` (η = ηₜ/ηᵢ, see [`crate::fresnel`]). Errors on
    /// a size outside 1..=[`MAX_TABLE_SIZE`] or a non-finite or non-positive η.
    pub fn new(n: usize, eta: f64) -> Result<Self> {
        check_size(n)?;
        check_eta(eta)?;
        let values =
            (0..n).map(|i| fresnel_exact((i as f64 + 0.5) / n as f64, eta) as f32).collect();
        Ok(Self { eta, values })
    }

    /// The number of entries N.
    pub fn size(&self) -> usize {
        self.values.len()
    }

    /// The index ratio η the table was built for.
    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// The entries, F at c = (i + 0.5)/N.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// F at `cos_theta` by linear interpolation between texel centres, clamp-to-edge: below
    /// c = 0.5/N and above 1 − 0.5/N the first and last entries are returned.
    pub fn lookup(&self, cos_theta: f32) -> f32 {
        let (i0, i1, w) = linear_clamp_to_edge(cos_theta, self.values.len());
        lerp(self.values[i0], self.values[i1], w)
    }
}

/// Which view vectors the texels of a [`FresnelTexture`] stand for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TextureMapping {
    /// docs/design.md's contract: texel coordinates (s, t) ∈ [0, 1]² stand for x = 2s − 1,
    /// y = 2t − 1, z = sqrt(max(0, 1 − x² − y²)), so the unit disc covers the whole hemisphere
    /// up to grazing views; outside the disc the vector is clamped to the rim (x, y)/r, z = 0.
    #[default]
    Hemisphere,
    /// The mapping seed 000 §5.1 prints: V = (s − 0.5, t − 0.5, sqrt(1 − (s−0.5)² − (t−0.5)²)).
    /// Its texels cover only |x|, |y| ≤ 0.5: view vectors within 30° of the normal along the
    /// axes, 45° along the diagonals. A view further from the normal has s = x + 0.5 outside
    /// [0, 1], and the clamp-to-edge sampler returns the edge texel's value.
    #[serde(rename = "half-range")]
    PaperHalfRange,
    /// The mapping the renderer uses (`--mapping grazing`): the rim falls on the edge texels'
    /// centres and the radius goes as ρ = sqrt(1 − z), so grazing views, where F changes
    /// fastest, get as many texels per unit of cos θ as the normal does. See
    /// [`grazing_disc`] and [`grazing_square`] for the two halves of the map.
    Grazing,
}

/// The texel coordinate u ∈ [−1, 1] of the grazing mapping at normalised coordinate `s` on an
/// axis of `n` ≥ 2 texels: texel centre 0 at u = −1, centre n − 1 at u = +1, so the rim
/// (|u| = 1) is sampled exactly, and beyond it the clamp-to-edge sampler holds the rim.
pub fn grazing_u(s: f64, n: usize) -> f64 {
    (s * n as f64 - 0.5) * 2.0 / (n as f64 - 1.0) - 1.0
}

/// The inverse of [`grazing_u`].
pub fn grazing_s(u: f64, n: usize) -> f64 {
    ((u + 1.0) * 0.5 * (n as f64 - 1.0) + 0.5) / n as f64
}

/// The square [−1, 1]² to the unit disc, the half of [`TextureMapping::Grazing`] that the
/// table's texels go through: the elliptical grid mapping d = (u·sqrt(1 − v²/2),
/// v·sqrt(1 − u²/2)) (Fong 2015, "Analytical methods for squaring the disc"), which sends the
/// square's edge onto the unit circle, is smooth inside (so bilinear filtering keeps its
/// second-order error; a radial stretch by max(|u|, |v|) has a kink on the diagonals that cost
/// 1.3e-2 at 256²), and is arithmetic only (no trigonometry), so the CPU and the GPU map alike.
pub fn grazing_disc(u: f64, v: f64) -> [f64; 2] {
    [u * (1.0 - 0.5 * v * v).sqrt(), v * (1.0 - 0.5 * u * u).sqrt()]
}

/// The inverse of [`grazing_disc`] on the unit disc:
/// u = ½ sqrt(2 + x² − y² + 2√2 x) − ½ sqrt(2 + x² − y² − 2√2 x), v likewise with x ↔ y.
/// On the disc both roots' arguments are ≥ 0 ((√2 ∓ x)² − y² ≥ (1 ∓ √2 x)² ≥ 0 there); the
/// max(0) guards round-off at the four corners' images, where one vanishes.
pub fn grazing_square(dx: f64, dy: f64) -> [f64; 2] {
    let two_sqrt2 = 2.0 * std::f64::consts::SQRT_2;
    let axis = |a: f64, b: f64| {
        let common = 2.0 + a * a - b * b;
        0.5 * ((common + two_sqrt2 * a).max(0.0).sqrt() - (common - two_sqrt2 * a).max(0.0).sqrt())
    };
    [axis(dx, dy), axis(dy, dx)]
}

impl TextureMapping {
    /// Every mapping, in the order of their [`Self::code`].
    pub const ALL: [TextureMapping; 3] = [Self::Hemisphere, Self::PaperHalfRange, Self::Grazing];

    /// The name on the command line (`ocean fresnel --mapping`) and in `ocean report`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Hemisphere => "hemisphere",
            Self::PaperHalfRange => "half-range",
            Self::Grazing => "grazing",
        }
    }

    /// The mapping called `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The value of `FresnelTableUniforms::mapping` that selects this mapping in
    /// `shaders/fresnel_table.wgsl`.
    pub fn code(self) -> u32 {
        match self {
            Self::Hemisphere => 0,
            Self::PaperHalfRange => 1,
            Self::Grazing => 2,
        }
    }

    /// The factor a of the grazing lookup s = a·u + ½ (u ∈ [−1, 1], [`grazing_u`]'s inverse)
    /// on an axis of `n` texels: a = (n − 1)/(2n), formed in f64 and rounded once.
    pub fn grazing_scale(n: u32) -> f32 {
        ((f64::from(n) - 1.0) / (2.0 * f64::from(n))) as f32
    }

    /// The normalised local view vector that texture coordinates (s, t) stand for, in `f64`.
    /// `n` is the table's side (only [`Self::Grazing`] depends on it, and needs n ≥ 2).
    pub fn view_vector(self, s: f64, t: f64, n: usize) -> [f64; 3] {
        match self {
            Self::Hemisphere => {
                let x = 2.0 * s - 1.0;
                let y = 2.0 * t - 1.0;
                let r2 = x * x + y * y;
                if r2 > 1.0 {
                    // Outside the unit disc no view vector has these (x, y): clamp to the rim,
                    // the grazing view with the same azimuth.
                    let r = r2.sqrt();
                    [x / r, y / r, 0.0]
                } else {
                    // max(0) only guards round-off; r² ≤ 1 here.
                    [x, y, (1.0 - r2).max(0.0).sqrt()]
                }
            }
            Self::PaperHalfRange => {
                let x = s - 0.5;
                let y = t - 0.5;
                // x² + y² ≤ 0.5 for (s, t) ∈ [0, 1]², so the root is real; max(0) only matters
                // for coordinates outside the texture, which no texel has.
                [x, y, (1.0 - x * x - y * y).max(0.0).sqrt()]
            }
            Self::Grazing => {
                // The disc point d has |d| = ρ = sqrt(1 − z), and for the elliptical grid
                // mapping 1 − ρ² = (1 − u²)(1 − v²): z is that product, exactly 0 on the edge
                // texels and free of cancellation. The horizontal part d/ρ·sin θ =
                // d·sqrt(1 + z) (sin² θ = 1 − z² = ρ²(1 + z)) needs no division at the
                // normal. Outside the square (never a texel) the clamp keeps z ≥ 0.
                let (u, v) = (grazing_u(s, n).clamp(-1.0, 1.0), grazing_u(t, n).clamp(-1.0, 1.0));
                let [dx, dy] = grazing_disc(u, v);
                let z = ((1.0 - u) * (1.0 + u)) * ((1.0 - v) * (1.0 + v));
                let k = (1.0 + z).sqrt();
                [dx * k, dy * k, z]
            }
        }
    }

    /// The texture coordinates (s, t) at which a local view vector is looked up; the inverse
    /// of [`view_vector`](Self::view_vector) on the texture's domain. Only x and y are used, as
    /// in the paper's shader, which looks up the bumped (x_v − du, z_v − dv) without
    /// renormalising; pass a normalised vector to look up the Fresnel term of its direction.
    /// `n` is the table's side, as for [`Self::view_vector`].
    pub fn coords(self, view_local: [f64; 3], n: usize) -> (f32, f32) {
        let [x, y, _] = view_local;
        match self {
            Self::Hemisphere => ((0.5 * (x + 1.0)) as f32, (0.5 * (y + 1.0)) as f32),
            Self::PaperHalfRange => ((x + 0.5) as f32, (y + 0.5) as f32),
            Self::Grazing => {
                // d = (x, y)/sqrt(1 + z) inverts view_vector; beyond the rim (r > 1, z = 0)
                // the same expression with max(…, r) puts the bumped vector on the rim at its
                // azimuth.
                let r = (x * x + y * y).sqrt();
                let z = (1.0 - r * r).max(0.0).sqrt();
                let scale = (1.0 + z).sqrt().max(r);
                let [u, v] = grazing_square(x / scale, y / scale);
                (grazing_s(u, n) as f32, grazing_s(v, n) as f32)
            }
        }
    }
}

/// The 2D Fresnel texture of seed 000 §5.1 and §5.3: N × N texels, each `[x, y, z, F]`, where
/// (x, y, z) is the normalised local view vector of the texel's centre under the texture's
/// [`TextureMapping`] and F = `fresnel_exact(z, η)` ([`fresnel_exact`]).
///
/// The local frame has the surface normal along +Z, so c = V·N = z: the texture needs no
/// normal at lookup time, which is the point of §5.1. F is computed from the `f32` vector that
/// is stored, so the four channels of a texel agree with each other exactly.
///
/// Texel (i, j) has s = (i + 0.5)/N, t = (j + 0.5)/N and is stored row-major at `j·N + i`
/// (the layout of docs/design.md's `ocean fresnel --table` contract).
///
/// Accuracy of the bilinear lookup with the [`TextureMapping::Hemisphere`] mapping (measured
/// in `tests/fresnel.rs`): away from the rim F is smooth in (x, y) and the error is second
/// order, ≤ (h²/8)(max|f_xx| + max|f_yy|) with h = 2/N. Towards the rim c = sqrt(1 − r²) has an
/// unbounded derivative, and along the axes the last texel centre is at |x| = 1 − 1/N, so a
/// grazing view there is clamped to texels whose cosine is sqrt(2/N − 2/N²), not 0: the error
/// at the horizon is 1 − F(sqrt(2/N − 2/N²)), which falls only as N^(−1/2) (water, N = 256:
/// 0.42; still 0.09 at N = 8192). For water at 256² the error is below 2e-3 up to 76° from the
/// normal.
#[derive(Clone, Debug, PartialEq)]
pub struct FresnelTexture {
    size: usize,
    eta: f64,
    mapping: TextureMapping,
    texels: Vec<[f32; 4]>,
}

impl FresnelTexture {
    /// Builds the N × N texture for the index ratio `eta` with the given mapping. Errors on a
    /// size outside 1..=[`MAX_TABLE_SIZE`] or a non-finite or non-positive η.
    pub fn new(n: usize, eta: f64, mapping: TextureMapping) -> Result<Self> {
        check_size(n)?;
        check_eta(eta)?;
        if mapping == TextureMapping::Grazing && n < 2 {
            return Err(Error::InvalidParameter {
                name: "table size",
                value: n as f64,
                reason: "the grazing mapping puts the rim on the first and last texel centres, \
                         so it needs at least 2 texels a side"
                    .into(),
            });
        }
        let mut texels = Vec::with_capacity(n * n);
        for j in 0..n {
            let t = (j as f64 + 0.5) / n as f64;
            for i in 0..n {
                let s = (i as f64 + 0.5) / n as f64;
                let [x, y, z] = mapping.view_vector(s, t, n).map(|v| v as f32);
                let f = fresnel_exact(f64::from(z), eta) as f32;
                texels.push([x, y, z, f]);
            }
        }
        Ok(Self { size: n, eta, mapping, texels })
    }

    /// The side N of the texture.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The index ratio η the texture was built for.
    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// The mapping between texels and view vectors the texture was built with.
    pub fn mapping(&self) -> TextureMapping {
        self.mapping
    }

    /// All texels, row-major: texel (i, j) at `j·N + i`.
    pub fn texels(&self) -> &[[f32; 4]] {
        &self.texels
    }

    /// The texels, mutable (for tests that corrupt a texel, and for uploads that patch one).
    pub fn texels_mut(&mut self) -> &mut [[f32; 4]] {
        &mut self.texels
    }

    /// Texel (i, j). Panics if i or j is ≥ N, as slice indexing does.
    pub fn texel(&self, i: usize, j: usize) -> [f32; 4] {
        assert!(i < self.size && j < self.size, "texel ({i}, {j}) outside {0}×{0}", self.size);
        self.texels[j * self.size + i]
    }

    /// The texture coordinates at which `view_local` (local frame, normal +Z) is looked up,
    /// under this texture's mapping; see [`TextureMapping::coords`].
    pub fn lookup_coords(&self, view_local: [f64; 3]) -> (f32, f32) {
        self.mapping.coords(view_local, self.size)
    }

    /// The bilinear, clamp-to-edge sample at (s, t), all four channels, computed in `f32` by
    /// the rule in the [module documentation](self).
    pub fn sample_bilinear(&self, s: f32, t: f32) -> [f32; 4] {
        let n = self.size;
        let (i0, i1, wx) = linear_clamp_to_edge(s, n);
        let (j0, j1, wy) = linear_clamp_to_edge(t, n);
        let t00 = self.texels[j0 * n + i0];
        let t10 = self.texels[j0 * n + i1];
        let t01 = self.texels[j1 * n + i0];
        let t11 = self.texels[j1 * n + i1];
        std::array::from_fn(|k| lerp(lerp(t00[k], t10[k], wx), lerp(t01[k], t11[k], wx), wy))
    }

    /// The Fresnel term the texture gives for a local view vector: the bilinear sample's fourth
    /// channel at [`lookup_coords`](Self::lookup_coords).
    pub fn lookup_fresnel(&self, view_local: [f64; 3]) -> f32 {
        let (s, t) = self.lookup_coords(view_local);
        self.sample_bilinear(s, t)[3]
    }

    /// The error |lookup_fresnel(V) − fresnel_exact(V·N, η)| over the whole hemisphere of view
    /// directions, on a deterministic grid: `samples` rows θ_k = (k + 0.5)·(90°/samples) and
    /// 4·`samples` columns φ_l = (l + 0.5)·(360°/(4·samples)), V = (sin θ cos φ, sin θ sin φ,
    /// cos θ). The RMS weights each sample by sin θ, the solid angle of its grid cell, so it is
    /// the RMS over the hemisphere by solid angle (midpoint rule). The grid is uniform in θ so
    /// that every 1° band holds the same number of samples, grazing ones included; the smallest
    /// and largest θ sampled are 45°/samples from 0° and 90°. With fewer than 90 rows some 1°
    /// bands hold no sample, and their entry in [`TextureError::max_abs_by_degree`] is 0.
    ///
    /// Errors if `samples` is 0.
    pub fn measure_error(&self, samples: usize) -> Result<TextureError> {
        if samples == 0 {
            return Err(Error::InvalidParameter {
                name: "samples",
                value: 0.0,
                reason: "the error grid needs at least one row of directions".into(),
            });
        }
        let n_theta = samples;
        let n_phi = 4 * samples;
        let phis: Vec<(f64, f64)> = (0..n_phi)
            .map(|l| {
                let phi = (l as f64 + 0.5) * TAU / n_phi as f64;
                (phi.cos(), phi.sin())
            })
            .collect();
        let mut max_abs_by_degree = vec![0.0_f64; 90];
        let mut max_abs = 0.0_f64;
        let mut worst_theta_deg = 0.0_f64;
        let mut sum_w_e2 = 0.0_f64;
        let mut sum_w = 0.0_f64;
        for k in 0..n_theta {
            let theta = (k as f64 + 0.5) * FRAC_PI_2 / n_theta as f64;
            let (sin_theta, cos_theta) = theta.sin_cos();
            let exact = fresnel_exact(cos_theta, self.eta);
            let theta_deg = theta.to_degrees();
            // θ < 90° on this grid, so the band index is at most 89.
            let band = (theta_deg.floor() as usize).min(89);
            let mut row_max = 0.0_f64;
            let mut row_sum_e2 = 0.0_f64;
            for &(cos_phi, sin_phi) in &phis {
                let v = [sin_theta * cos_phi, sin_theta * sin_phi, cos_theta];
                let e = (f64::from(self.lookup_fresnel(v)) - exact).abs();
                row_max = row_max.max(e);
                row_sum_e2 += e * e;
            }
            if row_max > max_abs {
                max_abs = row_max;
                worst_theta_deg = theta_deg;
            }
            max_abs_by_degree[band] = max_abs_by_degree[band].max(row_max);
            sum_w_e2 += sin_theta * row_sum_e2;
            sum_w += sin_theta * n_phi as f64;
        }
        Ok(TextureError {
            max_abs,
            rms: (sum_w_e2 / sum_w).sqrt(),
            worst_theta_deg,
            max_abs_by_degree,
        })
    }
}

/// How far a [`FresnelTexture`]'s bilinear lookup is from [`fresnel_exact`] over the
/// hemisphere; see [`FresnelTexture::measure_error`] for the sampling.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureError {
    /// The largest absolute error over all sampled directions.
    pub max_abs: f64,
    /// The root mean square error over the hemisphere, weighted by solid angle.
    pub rms: f64,
    /// The polar angle θ (degrees from the normal) of the sample with the largest error.
    pub worst_theta_deg: f64,
    /// Entry k: the largest absolute error for θ ∈ [k°, (k + 1)°), k = 0..90.
    pub max_abs_by_degree: Vec<f64>,
}

impl TextureError {
    /// The largest absolute error over view directions with θ < `theta_deg` (whole 1° bands
    /// only: bands that end at or before `theta_deg`).
    pub fn max_abs_below(&self, theta_deg: f64) -> f64 {
        self.max_abs_by_degree
            .iter()
            .enumerate()
            .filter(|&(k, _)| (k + 1) as f64 <= theta_deg)
            .fold(0.0, |m, (_, &e)| m.max(e))
    }

    /// The largest absolute error for θ < 80°. Beyond, the lookup is dominated by the rim (see
    /// [`FresnelTexture`]'s accuracy notes) rather than by the table's resolution.
    pub fn max_abs_below_80(&self) -> f64 {
        self.max_abs_below(80.0)
    }

    /// The first 1° band, in degrees, whose largest error exceeds `tolerance`, if any.
    pub fn first_degree_exceeding(&self, tolerance: f64) -> Option<usize> {
        self.max_abs_by_degree.iter().position(|&e| e > tolerance)
    }
}

/// Builds the N × N [`FresnelTexture`] for `eta` with `mapping` and measures its error over the
/// hemisphere with `samples` rows of directions ([`FresnelTexture::measure_error`]).
pub fn texture_error(
    n: usize,
    eta: f64,
    mapping: TextureMapping,
    samples: usize,
) -> Result<TextureError> {
    FresnelTexture::new(n, eta, mapping)?.measure_error(samples)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sampler_rule_at_texel_centres_and_edges() {
        // At a texel centre the weight is 0 and the texel itself is returned.
        assert_eq!(linear_clamp_to_edge(0.5 / 4.0, 4), (0, 1, 0.0));
        assert_eq!(linear_clamp_to_edge(2.5 / 4.0, 4), (2, 3, 0.0));
        // Halfway between centres 1 and 2.
        assert_eq!(linear_clamp_to_edge(2.0 / 4.0, 4), (1, 2, 0.5));
        // Clamp to edge on both sides, and far outside.
        assert_eq!(linear_clamp_to_edge(0.0, 4), (0, 0, 0.5));
        assert_eq!(linear_clamp_to_edge(1.0, 4), (3, 3, 0.5));
        assert_eq!(linear_clamp_to_edge(-1e30, 4).0, 0);
        assert_eq!(linear_clamp_to_edge(1e30, 4).1, 3);
        assert_eq!(linear_clamp_to_edge(f32::NAN, 4).0, 0);
    }

    #[test]
    fn table_1d_hits_its_entries_and_clamps() -> Result<()> {
        let table = FresnelTable1D::new(64, 1.333)?;
        for (i, &v) in table.values().iter().enumerate() {
            let c = (i as f32 + 0.5) / 64.0;
            assert_eq!(table.lookup(c), v, "entry {i}");
        }
        assert_eq!(table.lookup(0.0), table.values()[0]);
        assert_eq!(table.lookup(-3.0), table.values()[0]);
        assert_eq!(table.lookup(1.0), table.values()[63]);
        Ok(())
    }

    #[test]
    fn bad_parameters_are_errors() {
        assert!(FresnelTable1D::new(0, 1.333).is_err());
        assert!(FresnelTable1D::new(16, 0.0).is_err());
        assert!(FresnelTable1D::new(16, f64::NAN).is_err());
        assert!(
            FresnelTexture::new(MAX_TABLE_SIZE + 1, 1.333, TextureMapping::Hemisphere).is_err()
        );
        assert!(FresnelTexture::new(16, f64::INFINITY, TextureMapping::Hemisphere).is_err());
        assert!(texture_error(16, 1.333, TextureMapping::Hemisphere, 0).is_err());
    }

    #[test]
    fn mappings_round_trip_at_texel_centres() {
        let n = 32;
        for mapping in
            [TextureMapping::Hemisphere, TextureMapping::PaperHalfRange, TextureMapping::Grazing]
        {
            for j in 0..n {
                for i in 0..n {
                    let s = (i as f64 + 0.5) / n as f64;
                    let t = (j as f64 + 0.5) / n as f64;
                    let v = mapping.view_vector(s, t, n);
                    let inside = v[2] > 0.0;
                    if inside {
                        let (s2, t2) = mapping.coords(v, n);
                        assert!(
                            (f64::from(s2) - s).abs() < 1e-7 && (f64::from(t2) - t).abs() < 1e-7
                        );
                    }
                }
            }
        }
    }
}
