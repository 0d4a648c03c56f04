//! FFT synthesis of the wave maps: eq. 1 of seed 000 (Tessendorf's h(x, t)) and the fields
//! derived from it, evaluated on the whole grid by 2D inverse FFTs.
//!
//! The eight real fields are sums Σ_k M(k) h̃(k, t) e^{ik·x} with these multipliers M(k)
//! (λ = choppiness, k = |k|; every multiplier is 0 at k = 0, where h̃ = 0 anyway):
//!
//! | field | M(k) | meaning |
//! |---|---|---|
//! | `height` | 1 | h |
//! | `disp_x`, `disp_z` | λ·(−i kx/k), λ·(−i kz/k) | choppy D = λ Σ −i k/k h̃ e^{ik·x} |
//! | `slope_x`, `slope_z` | i kx, i kz | ∂h/∂x, ∂h/∂z |
//! | Dxx, Dzz, Dxz | λ kx²/k, λ kz²/k, λ kx kz/k | ∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z = ∂Dz/∂x |
//!
//! and `jacobian` J = (1 + Dxx)(1 + Dzz) − Dxz², evaluated per sample in T as written (no
//! fused multiply-add). The surface point of sample (x, z) is (x + Dx, h, z + Dz).
//!
//! Sign of D: λ = −`choppiness`. Tessendorf's formula as written, x + λD with λ > 0, pulls
//! the samples towards the *troughs* (for h = cos kx, D = sin kx, J = 1 + λk cos kx is
//! smallest in the troughs), which sharpens troughs, not crests. A user's `choppiness > 0`
//! must give sharp crests and crest folding as a Gerstner wave does (seed 002), so the
//! synthesis uses λ = −choppiness: for h = cos kx the displacement is −choppiness·sin kx,
//! towards the crest, and J = 1 − choppiness·k·cos kx is smallest on the crests.
//!
//! Packing: each multiplier is even or odd in k and real or imaginary, so M·h̃ is Hermitian
//! and its inverse FFT real; two such spectra Â, B̂ go through one complex transform as
//! Â + iB̂, whose inverse is a + ib. The pairs are chosen so that a field meets a partner of
//! like magnitude (the round-off of a transform scales with the larger of the two):
//! (height, disp_x), (disp_z, Dxz), (slope_x, slope_z), (Dxx, Dzz) — four 2D FFTs. With
//! λ = 0 the displacement fields are exactly 0 and J exactly 1, and only (height, –) and
//! (slope_x, slope_z) are transformed.
//!
//! Precision: h̃(k, t) and the multipliers are computed in f64 (the phase ωt needs f64 at
//! large t), then cast to T for the FFT; so an f32 map differs from the f64 one by the f32
//! rounding of the spectrum and the f32 FFT round-off only. (The GPU path may revisit this.)
//!
//! 2D FFT: rows (along x) then columns (along z), each as one batch of N-point transforms
//! over contiguous rows, with a blocked out-of-place transpose in between and after; plan and
//! scratch are made once per [`Synthesizer`]. `rustfft::FftPlannerScalar`: no run-time
//! instruction-set dispatch (determinism contract). The inverse transform is unnormalised,
//! as the conventions in the crate root require.

use std::sync::Arc;

use num_complex::Complex;
use num_traits::Float;
use rustfft::{Fft, FftNum, FftPlannerScalar};

use super::modes::{WaveModes, check_choppiness};
use crate::{Error, Result};

/// The float type of a map: f32 or f64.
pub trait MapFloat: FftNum + Float {
    /// Rounds an f64 to this type (`as`: round to nearest).
    fn cast_from_f64(v: f64) -> Self;
    /// Widens to f64 (exact).
    fn cast_to_f64(self) -> f64;
}

impl MapFloat for f32 {
    #[inline]
    fn cast_from_f64(v: f64) -> Self {
        v as f32
    }
    #[inline]
    fn cast_to_f64(self) -> f64 {
        f64::from(self)
    }
}

impl MapFloat for f64 {
    #[inline]
    fn cast_from_f64(v: f64) -> Self {
        v
    }
    #[inline]
    fn cast_to_f64(self) -> f64 {
        self
    }
}

/// The six N × N maps of one time, stored as the crate root says: sample (i, j) at
/// x = i·L/N, z = j·L/N, index j·N + i.
#[derive(Clone, Debug, PartialEq)]
pub struct WaveMaps<T> {
    resolution: usize,
    patch_size_m: f64,
    /// h, metres.
    pub height: Vec<T>,
    /// Horizontal displacement Dx, metres.
    pub disp_x: Vec<T>,
    /// Horizontal displacement Dz, metres.
    pub disp_z: Vec<T>,
    /// ∂h/∂x (with respect to the undisplaced sample position).
    pub slope_x: Vec<T>,
    /// ∂h/∂z (with respect to the undisplaced sample position).
    pub slope_z: Vec<T>,
    /// J = det(I + ∂D/∂x), the area ratio of the displaced surface; ≤ 0 where it folds.
    pub jacobian: Vec<T>,
}

impl<T: MapFloat> WaveMaps<T> {
    /// The channel names of `ocean heightfield` (docs/design.md), in the order of [`Self::fields`].
    pub const FIELD_NAMES: [&'static str; 6] =
        ["height", "disp_x", "disp_z", "slope_x", "slope_z", "jacobian"];

    /// Flat maps: every field 0 except J = 1.
    pub fn new(resolution: usize, patch_size_m: f64) -> Self {
        let len = resolution * resolution;
        let zero = vec![T::zero(); len];
        Self {
            resolution,
            patch_size_m,
            height: zero.clone(),
            disp_x: zero.clone(),
            disp_z: zero.clone(),
            slope_x: zero.clone(),
            slope_z: zero,
            jacobian: vec![T::one(); len],
        }
    }

    /// N.
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// L, metres.
    pub fn patch_size_m(&self) -> f64 {
        self.patch_size_m
    }

    /// Storage index of sample (i, j).
    #[inline]
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.resolution + i
    }

    /// The six fields with their channel names.
    pub fn fields(&self) -> [(&'static str, &[T]); 6] {
        let n = Self::FIELD_NAMES;
        [
            (n[0], &self.height),
            (n[1], &self.disp_x),
            (n[2], &self.disp_z),
            (n[3], &self.slope_x),
            (n[4], &self.slope_z),
            (n[5], &self.jacobian),
        ]
    }

    /// The foam mask: true where the surface folds or nearly folds, J < `threshold`
    /// (Tessendorf 2001 §4.1: foam and spray where the Jacobian of the choppy displacement
    /// drops towards 0; `threshold` = 0 marks exactly the folded samples, a small positive one
    /// the crests about to fold). J is finite wherever the maps are, so the mask is total.
    pub fn foam_mask(&self, threshold: f64) -> Vec<bool> {
        self.jacobian.iter().map(|j| j.cast_to_f64() < threshold).collect()
    }

    /// The fraction of samples in the [`Self::foam_mask`].
    pub fn foam_coverage(&self, threshold: f64) -> f64 {
        let foam = self.jacobian.iter().filter(|j| j.cast_to_f64() < threshold).count();
        foam as f64 / self.jacobian.len().max(1) as f64
    }

    /// Bytes held by the six fields.
    pub fn byte_size(&self) -> usize {
        6 * self.resolution * self.resolution * std::mem::size_of::<T>()
    }

    fn reshape(&mut self, resolution: usize, patch_size_m: f64) {
        let len = resolution * resolution;
        self.resolution = resolution;
        self.patch_size_m = patch_size_m;
        for field in [
            &mut self.height,
            &mut self.disp_x,
            &mut self.disp_z,
            &mut self.slope_x,
            &mut self.slope_z,
            &mut self.jacobian,
        ] {
            field.resize(len, T::zero());
        }
    }
}

/// One of the eight real spectra.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Spectrum {
    Height,
    DispX,
    DispZ,
    SlopeX,
    SlopeZ,
    DispXDx,
    DispZDz,
    DispXDz,
}

impl Spectrum {
    /// M(k)·h̃ (table in the module documentation). `inv_k` is 1/|k|, 0 at k = 0.
    #[inline]
    fn of(self, h: Complex<f64>, kx: f64, kz: f64, inv_k: f64, lambda: f64) -> Complex<f64> {
        let i_h = Complex::new(-h.im, h.re); // i·h̃
        let minus_i_h = Complex::new(h.im, -h.re); // −i·h̃
        match self {
            Self::Height => h,
            Self::DispX => minus_i_h * (lambda * kx * inv_k),
            Self::DispZ => minus_i_h * (lambda * kz * inv_k),
            Self::SlopeX => i_h * kx,
            Self::SlopeZ => i_h * kz,
            Self::DispXDx => h * (lambda * kx * kx * inv_k),
            Self::DispZDz => h * (lambda * kz * kz * inv_k),
            Self::DispXDz => h * (lambda * kx * kz * inv_k),
        }
    }
}

/// Edge of the square tiles of the transpose: 32 × 32 complex f64 = 16 KiB, two tiles fit L1.
const TRANSPOSE_TILE: usize = 32;

/// `dst[i·n + j] = src[j·n + i]`, tile by tile.
fn transpose<C: Copy>(src: &[C], dst: &mut [C], n: usize) {
    for j0 in (0..n).step_by(TRANSPOSE_TILE) {
        for i0 in (0..n).step_by(TRANSPOSE_TILE) {
            for j in j0..(j0 + TRANSPOSE_TILE).min(n) {
                for i in i0..(i0 + TRANSPOSE_TILE).min(n) {
                    dst[i * n + j] = src[j * n + i];
                }
            }
        }
    }
}

/// FFT synthesis for one resolution N: plan and scratch made once, reused for every call.
pub struct Synthesizer<T: MapFloat> {
    resolution: usize,
    fft: Arc<dyn Fft<T>>,
    /// h̃(k, t), f64.
    htilde: Vec<Complex<f64>>,
    /// The packed spectrum, then the field pair, in natural order.
    work: Vec<Complex<T>>,
    /// The transposed intermediate of the 2D FFT.
    transposed: Vec<Complex<T>>,
    /// Dxz, kept until J is formed.
    disp_x_dz: Vec<T>,
    fft_scratch: Vec<Complex<T>>,
}

impl<T: MapFloat> Synthesizer<T> {
    /// Plans the N-point inverse FFT and allocates the scratch (about N²·(16 + 2·2·size_of T
    /// + size_of T) bytes).
    pub fn new(resolution: usize) -> Result<Self> {
        super::modes::check_grid(1.0, resolution)?;
        let fft = FftPlannerScalar::new().plan_fft_inverse(resolution);
        let len = resolution * resolution;
        let zero = Complex::new(T::zero(), T::zero());
        Ok(Self {
            resolution,
            fft_scratch: vec![zero; fft.get_inplace_scratch_len()],
            fft,
            htilde: vec![Complex::new(0.0, 0.0); len],
            work: vec![zero; len],
            transposed: vec![zero; len],
            disp_x_dz: vec![T::zero(); len],
        })
    }

    /// N.
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// The maps of `modes` at time `t` (seconds) with choppiness λ.
    pub fn synthesize(
        &mut self,
        modes: &WaveModes,
        t: f64,
        choppiness: f64,
    ) -> Result<WaveMaps<T>> {
        let mut out = WaveMaps::new(self.resolution, modes.patch_size_m());
        self.synthesize_into(modes, t, choppiness, &mut out)?;
        Ok(out)
    }

    /// The maps of `modes` at time `t` with choppiness λ, into caller-owned maps (reshaped
    /// to N × N if needed). Errors: N differs from the synthesizer's, t or λ not finite.
    pub fn synthesize_into(
        &mut self,
        modes: &WaveModes,
        t: f64,
        choppiness: f64,
        out: &mut WaveMaps<T>,
    ) -> Result<()> {
        let n = self.resolution;
        if modes.resolution() != n {
            return Err(Error::InvalidParameter {
                name: "resolution",
                value: modes.resolution() as f64,
                reason: format!("the modes' resolution must be the synthesizer's ({n})"),
            });
        }
        check_choppiness(choppiness)?;
        modes.htilde_into(t, &mut self.htilde)?;
        out.reshape(n, modes.patch_size_m());

        use Spectrum::*;
        if choppiness == 0.0 {
            self.transform_pair(modes, 0.0, Height, None);
            unpack(&self.work, &mut out.height, None);
            self.transform_pair(modes, 0.0, SlopeX, Some(SlopeZ));
            unpack(&self.work, &mut out.slope_x, Some(&mut out.slope_z));
            out.disp_x.fill(T::zero());
            out.disp_z.fill(T::zero());
            out.jacobian.fill(T::one());
            return Ok(());
        }
        // λ of the table above; see "Sign of D".
        let lambda = -choppiness;
        self.transform_pair(modes, lambda, Height, Some(DispX));
        unpack(&self.work, &mut out.height, Some(&mut out.disp_x));
        self.transform_pair(modes, lambda, DispZ, Some(DispXDz));
        unpack(&self.work, &mut out.disp_z, Some(&mut self.disp_x_dz));
        self.transform_pair(modes, lambda, SlopeX, Some(SlopeZ));
        unpack(&self.work, &mut out.slope_x, Some(&mut out.slope_z));
        self.transform_pair(modes, lambda, DispXDx, Some(DispZDz));
        let one = T::one();
        for ((j, c), &dxz) in out.jacobian.iter_mut().zip(&self.work).zip(&self.disp_x_dz) {
            let (dxx, dzz) = (c.re, c.im);
            *j = (one + dxx) * (one + dzz) - dxz * dxz;
        }
        Ok(())
    }

    /// Fills `work` with the spectrum Â + iB̂ (B̂ = 0 for `None`) cast to T, and inverse-
    /// transforms it in place.
    fn transform_pair(&mut self, modes: &WaveModes, lambda: f64, a: Spectrum, b: Option<Spectrum>) {
        let n = self.resolution;
        let axis_k = modes.axis_wavenumbers();
        let k = modes.wavenumbers();
        for (bin, (w, &h)) in self.work.iter_mut().zip(&self.htilde).enumerate() {
            let (kx, kz) = (axis_k[bin % n], axis_k[bin / n]);
            // 1/|k| only where |k| > 0: at k = 0 h̃ = 0 and every multiplier is 0 too.
            let inv_k = if k[bin] > 0.0 { 1.0 / k[bin] } else { 0.0 };
            let sa = a.of(h, kx, kz, inv_k, lambda);
            let packed = match b {
                Some(b) => {
                    let sb = b.of(h, kx, kz, inv_k, lambda);
                    Complex::new(sa.re - sb.im, sa.im + sb.re) // Â + iB̂
                }
                None => sa,
            };
            *w = Complex::new(T::cast_from_f64(packed.re), T::cast_from_f64(packed.im));
        }
        // Along x (contiguous rows), then along z via two transposes.
        self.fft.process_with_scratch(&mut self.work, &mut self.fft_scratch);
        transpose(&self.work, &mut self.transposed, n);
        self.fft.process_with_scratch(&mut self.transposed, &mut self.fft_scratch);
        transpose(&self.transposed, &mut self.work, n);
    }
}

/// Splits a + ib into a and (if wanted) b.
fn unpack<T: MapFloat>(work: &[Complex<T>], a: &mut [T], b: Option<&mut [T]>) {
    match b {
        Some(b) => {
            for ((c, a), b) in work.iter().zip(a.iter_mut()).zip(b.iter_mut()) {
                *a = c.re;
                *b = c.im;
            }
        }
        None => {
            for (c, a) in work.iter().zip(a.iter_mut()) {
                *a = c.re;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transpose_round_trips_odd_sizes() {
        for n in [1, 5, 33, 70] {
            let src: Vec<usize> = (0..n * n).collect();
            let mut t = vec![0; n * n];
            transpose(&src, &mut t, n);
            for j in 0..n {
                for i in 0..n {
                    assert_eq!(t[i * n + j], src[j * n + i]);
                }
            }
        }
    }
}
