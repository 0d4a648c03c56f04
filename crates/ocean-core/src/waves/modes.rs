//! The random wave field in the frequency domain: h0(k) on the N × N lattice of one patch, and
//! h̃(k, t) built from it (Tessendorf 2001, eq. 43).

use std::f64::consts::TAU;

use num_complex::Complex;
use rayon::prelude::*;

use crate::dispersion::Dispersion;
use crate::rng::mode_gaussians;
use crate::{Error, Result};

/// The largest grid resolution accepted: the modes of an 8192² grid take 2 GiB, and each map
/// set as much again per field type; beyond that an allocation failure, not an error, would
/// be the likely outcome.
pub const MAX_RESOLUTION: usize = 8192;

/// Which of the grid's modes a [`WaveModes`] holds (the others have h0 = 0), and the area of
/// the spectrum each one stands for.
///
/// The test is on integer lattice indices, never on floating-point wavenumbers, so a mode on
/// a band edge is never counted twice nor dropped by round-off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Band {
    /// Every mode the grid resolves (all n, m ∈ (−N/2, N/2) except k = 0).
    All,
    /// Leave out the modes that a map of the reference patch (side `lattice_ratio · L`) at
    /// resolution `resolution` holds: a mode with reference-lattice index (i, j) = r·(n, m) is
    /// kept iff 2·max(|i|, |j|) ≥ `resolution`, i.e. iff max(|kx|, |kz|) ≥ π·resolution/L_ref.
    /// This is the bump map's band: everything the displacement map does not already hold.
    ///
    /// Cells: the held modes must stand for the frame between the inner map's cells, which end
    /// at the Chebyshev radius E = (⌈N_d/2⌉ − ½)·Δk_ref, and this grid's outer edge. This
    /// grid's own cells (side r in reference units, centred on multiples of r) end at
    /// c₀ − r/2 instead, c₀ = the innermost held ring (the smallest multiple of r with
    /// 2c₀ ≥ N_d): for r > 1 they overlap the inner map's cells or leave a gap. So the cell
    /// boundary between the rings c₀ − r and c₀ is moved, on both axes, to E: a mode whose
    /// |i| or |j| is c₀ (or c₀ − r) gets a cell that much longer or shorter along that axis,
    /// and a weight w = (its cell's area)/(r·Δk_ref)² in place of 1 ([`WaveModes::cell_weight`]).
    /// The held cells then tile the frame exactly, with no overlap and no gap. (Without this a
    /// bump map with r = 4 over a displacement map of N_d = 64 overcounts a k⁻⁴ spectrum's
    /// frame variance by 8(r−1)/(πN_d) ≈ 12 %.)
    ExcludeGrid {
        /// The resolution N_d of the map whose band is left out.
        resolution: usize,
    },
}

/// What defines the modes of one map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModeParams {
    /// Side L of the periodic square patch, metres.
    pub patch_size_m: f64,
    /// N: the grid holds N × N samples and N × N modes (any N ≥ 2, power of two or not).
    pub resolution: usize,
    /// r ≥ 1: this patch is a reference patch of side r·L divided by r (the bump map is the
    /// displacement patch divided by r). Mode (n, m) of this grid is then the mode
    /// (r·n, r·m) of the reference lattice, and its random numbers are keyed by that index, so
    /// one wave vector always gets the same numbers whichever map holds it. 1 for a map that
    /// is its own reference.
    pub lattice_ratio: usize,
    /// Seed of the random amplitudes.
    pub seed: u64,
    /// Which modes are held.
    pub band: Band,
}

impl ModeParams {
    /// A plain map: its own reference lattice, every mode held.
    pub fn new(patch_size_m: f64, resolution: usize, seed: u64) -> Self {
        Self { patch_size_m, resolution, lattice_ratio: 1, seed, band: Band::All }
    }
}

/// One mode of a [`WaveModes`], for inspection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mode {
    /// Storage index `(m mod N)·N + (n mod N)`.
    pub bin: usize,
    /// Lattice index along x, in (−N/2, N/2); −N/2 for the Nyquist column of an even N.
    pub n: i64,
    /// Lattice index along z, likewise.
    pub m: i64,
    /// kx = 2π n / L, rad/m.
    pub kx: f64,
    /// kz = 2π m / L, rad/m.
    pub kz: f64,
    /// |k|, rad/m.
    pub k: f64,
    /// ω(|k|) from the dispersion relation (quantised when looping), rad/s.
    pub omega: f64,
    /// The random amplitude h0(k), metres.
    pub h0: Complex<f64>,
    /// Whether the mode is held: not k = 0, not on a Nyquist row or column, inside the band.
    /// An inactive mode has h0 = 0.
    pub active: bool,
    /// The area of the spectrum the mode stands for, in units of Δk²: 1 for a held mode,
    /// except next to an [`Band::ExcludeGrid`] band edge; 0 when not held.
    pub cell_weight: f64,
}

/// The lattice index of FFT bin `b` of an `n`-point axis: b for 2b < N, b − N for 2b > N, and
/// `None` for the Nyquist bin 2b = N of an even N.
#[inline]
pub fn signed_index(b: usize, n: usize) -> Option<i64> {
    match (2 * b).cmp(&n) {
        std::cmp::Ordering::Less => Some(b as i64),
        std::cmp::Ordering::Equal => None,
        std::cmp::Ordering::Greater => Some(b as i64 - n as i64),
    }
}

/// The random amplitudes h0(k) of one map, with each mode's wave vector and frequency.
///
/// Amplitudes (the normalisation is chosen so that the expected variance of the field is the
/// integral of the spectrum over the band, `docs/design.md`, "Spectra"):
///
/// ```text
/// h0(k) = (ξ_r + i ξ_i) · ½ · sqrt(F(k) Δk² w),   Δk = 2π/L,   E|h0(k)|² = F(k) Δk² w / 2
/// h̃(k, t) = h0(k) e^{iωt} + conj(h0(−k)) e^{−iωt}
/// ```
///
/// h̃(−k, t) = conj(h̃(k, t)), so the field is real; E|h̃(k, t)|² = (F(k) + F(−k)) Δk²/2
/// (h0(k) and h0(−k) are independent), and summed over the grid this is Σ F(k) Δk² w, the
/// Riemann sum of ∫∫ F dkx dkz over the band: the expected variance of h. w = 1 except along
/// the inner edge of an [`Band::ExcludeGrid`] band, where it is the fraction of the cell
/// inside the band. (Tessendorf's h0 = (ξ_r + iξ_i) sqrt(P/2) with this h̃ gives twice the
/// variance.)
///
/// Modes left at zero, and why:
/// - k = 0: the mean sea level is 0 by definition.
/// - the Nyquist row and column (n or m = −N/2, even N): that bin is its own partner −k on
///   the grid, so a real field can hold it only as a standing wave 2|h0| cos(ωt + φ) cos(π i)
///   with no travelling phase; and between grid points its wave e^{−iπNx/L} is not the
///   band-limited interpolant (that would be cos(πNx/L)), so the FFT and the direct sum would
///   disagree off the grid. Zeroing it keeps both readings of eq. 1 the same function.
/// - modes outside the [`Band`].
#[derive(Clone, Debug)]
pub struct WaveModes {
    params: ModeParams,
    dispersion: Dispersion,
    /// The wavenumber of each bin along one axis, 2π·signed_index(b)/L (−πN/L for Nyquist).
    axis_k: Vec<f64>,
    /// |k| per bin.
    k: Vec<f64>,
    /// ω(|k|) per bin.
    omega: Vec<f64>,
    /// h0 per bin.
    h0: Vec<Complex<f64>>,
    /// Σ F Δk² over the active modes.
    expected_variance: f64,
}

fn invalid(name: &'static str, value: f64, reason: impl Into<String>) -> Error {
    Error::InvalidParameter { name, value, reason: reason.into() }
}

/// Checks a patch side and a resolution (shared by every constructor of the module).
pub(crate) fn check_grid(patch_size_m: f64, resolution: usize) -> Result<()> {
    if !(patch_size_m > 0.0 && patch_size_m.is_finite()) {
        return Err(invalid("patch_size_m", patch_size_m, "must be finite and > 0"));
    }
    if !(2..=MAX_RESOLUTION).contains(&resolution) {
        return Err(invalid(
            "resolution",
            resolution as f64,
            format!("must be in 2..={MAX_RESOLUTION}"),
        ));
    }
    Ok(())
}

/// Checks a time argument: h̃(k, t) needs a finite t.
pub(crate) fn check_time(t: f64) -> Result<()> {
    if t.is_finite() { Ok(()) } else { Err(invalid("time_s", t, "must be finite")) }
}

/// Checks a choppiness λ: any finite value (0 = no horizontal displacement).
pub(crate) fn check_choppiness(choppiness: f64) -> Result<()> {
    if choppiness.is_finite() {
        Ok(())
    } else {
        Err(invalid("choppiness", choppiness, "must be finite"))
    }
}

/// One bin as drawn: (|k|, ω, h0, the variance of its cell).
type Bin = (f64, f64, Complex<f64>, f64);

impl WaveModes {
    /// Draws the amplitudes of the grid described by `params`, for the spectrum `density`:
    /// F(kx, kz) in m⁴, the 2D wavenumber spectrum whose integral ∫∫ F dkx dkz is the
    /// variance of the sea surface. `density` is called once per active mode and must return
    /// a finite value ≥ 0 there.
    pub fn new(
        params: &ModeParams,
        dispersion: Dispersion,
        density: impl Fn(f64, f64) -> f64 + Sync,
    ) -> Result<Self> {
        let n = params.resolution;
        let l = params.patch_size_m;
        check_grid(l, n)?;
        let r = params.lattice_ratio;
        // The reference-lattice index r·n must fit the generator's i32 key.
        if r == 0 || r.saturating_mul(n) > i32::MAX as usize {
            return Err(invalid(
                "lattice_ratio",
                r as f64,
                format!("must be ≥ 1 with ratio × resolution < 2³¹ (resolution {n})"),
            ));
        }
        let delta_k = TAU / l;
        let axis_k: Vec<f64> = (0..n)
            .map(|b| {
                let index = signed_index(b, n).unwrap_or(-(n as i64 / 2));
                TAU * index as f64 / l
            })
            .collect();
        // Rows in parallel (each mode depends only on its own indices: the generator is
        // counter-based), then gathered and summed in row-major order, so the result and
        // the first error reported are those of a sequential loop, bit for bit.
        let row = |bz: usize| -> Result<Vec<Bin>> {
            let mut out = Vec::with_capacity(n);
            for bx in 0..n {
                let (kx, kz) = (axis_k[bx], axis_k[bz]);
                let k_len = (kx * kx + kz * kz).sqrt();
                let weight = match (signed_index(bx, n), signed_index(bz, n)) {
                    (Some(i), Some(j)) if (i, j) != (0, 0) => cell_weight(params, i, j),
                    _ => 0.0,
                };
                let (amplitude, cell) = match (signed_index(bx, n), signed_index(bz, n)) {
                    (Some(i), Some(j)) if weight > 0.0 => {
                        let f = density(kx, kz);
                        if !(f >= 0.0 && f.is_finite()) {
                            return Err(invalid(
                                "spectrum density",
                                f,
                                format!("must be finite and ≥ 0 (at kx = {kx}, kz = {kz} rad/m)"),
                            ));
                        }
                        let cell = f * delta_k * delta_k * weight;
                        // Key by the reference-lattice index: |r·i| < 2³¹ was checked above.
                        let (xi_r, xi_i) = mode_gaussians(
                            params.seed,
                            (r as i64 * i) as i32,
                            (r as i64 * j) as i32,
                        );
                        (Complex::new(xi_r, xi_i) * (0.5 * cell.sqrt()), cell)
                    }
                    _ => (Complex::new(0.0, 0.0), 0.0),
                };
                out.push((k_len, dispersion.omega(k_len), amplitude, cell));
            }
            Ok(out)
        };
        let rows: Vec<Result<Vec<Bin>>> = (0..n).into_par_iter().map(row).collect();
        let mut k = Vec::with_capacity(n * n);
        let mut omega = Vec::with_capacity(n * n);
        let mut h0 = Vec::with_capacity(n * n);
        let mut expected_variance = 0.0;
        for row in rows {
            for (k_len, w, amplitude, cell) in row? {
                k.push(k_len);
                omega.push(w);
                h0.push(amplitude);
                // Inactive bins carry a cell of 0, which leaves the sum as it was.
                expected_variance += cell;
            }
        }
        Ok(Self { params: *params, dispersion, axis_k, k, omega, h0, expected_variance })
    }

    /// The parameters the modes were drawn with.
    pub fn params(&self) -> &ModeParams {
        &self.params
    }

    /// N.
    pub fn resolution(&self) -> usize {
        self.params.resolution
    }

    /// L, metres.
    pub fn patch_size_m(&self) -> f64 {
        self.params.patch_size_m
    }

    /// Δk = 2π/L, rad/m.
    pub fn delta_k(&self) -> f64 {
        TAU / self.params.patch_size_m
    }

    /// The dispersion relation the frequencies come from.
    pub fn dispersion(&self) -> &Dispersion {
        &self.dispersion
    }

    /// Wavenumber of each bin along one axis (x for the fast index, z for the slow one):
    /// 2π·n/L with n the bin's signed index; the Nyquist bin reads −πN/L.
    pub fn axis_wavenumbers(&self) -> &[f64] {
        &self.axis_k
    }

    /// |k| per bin, rad/m.
    pub fn wavenumbers(&self) -> &[f64] {
        &self.k
    }

    /// ω(|k|) per bin, rad/s (quantised when the dispersion loops).
    pub fn omegas(&self) -> &[f64] {
        &self.omega
    }

    /// h0 per bin, metres.
    pub fn h0(&self) -> &[Complex<f64>] {
        &self.h0
    }

    /// h0 per bin, writable: for tools and tests (a single-mode field, a perturbed one).
    /// The field stays real whatever is written (h̃ pairs k with −k); a value written into a
    /// k = 0 or Nyquist bin is a standing wave there, and breaks the agreement of the FFT with
    /// the direct sum between grid points.
    pub fn h0_mut(&mut self) -> &mut [Complex<f64>] {
        &mut self.h0
    }

    /// Σ F(k) Δk² w over the active modes: the expected variance of the field, m².
    pub fn expected_variance(&self) -> f64 {
        self.expected_variance
    }

    /// The bin of −k for `bin`.
    #[inline]
    pub fn partner(&self, bin: usize) -> usize {
        let n = self.params.resolution;
        let (bx, bz) = (bin % n, bin / n);
        ((n - bz) % n) * n + (n - bx) % n
    }

    /// Whether a bin is an active mode (see [`Mode::active`]).
    pub fn is_active(&self, bin: usize) -> bool {
        self.cell_weight(bin) > 0.0
    }

    /// The area of the spectrum the mode at `bin` stands for, in units of Δk² (see
    /// [`Band::ExcludeGrid`]); 0 for an inactive mode.
    pub fn cell_weight(&self, bin: usize) -> f64 {
        let n = self.params.resolution;
        match (signed_index(bin % n, n), signed_index(bin / n, n)) {
            (Some(i), Some(j)) if (i, j) != (0, 0) => cell_weight(&self.params, i, j),
            _ => 0.0,
        }
    }

    /// The mode stored at `bin`.
    pub fn mode(&self, bin: usize) -> Mode {
        let n = self.params.resolution;
        let (bx, bz) = (bin % n, bin / n);
        let nyquist = -(n as i64 / 2);
        Mode {
            bin,
            n: signed_index(bx, n).unwrap_or(nyquist),
            m: signed_index(bz, n).unwrap_or(nyquist),
            kx: self.axis_k[bx],
            kz: self.axis_k[bz],
            k: self.k[bin],
            omega: self.omega[bin],
            h0: self.h0[bin],
            active: self.is_active(bin),
            cell_weight: self.cell_weight(bin),
        }
    }

    /// Every stored mode, in storage order.
    pub fn modes(&self) -> impl Iterator<Item = Mode> + '_ {
        (0..self.h0.len()).map(|bin| self.mode(bin))
    }

    /// Whether h̃(bin, t) can be non-zero: h0 at k or at −k is.
    #[inline]
    pub fn is_live(&self, bin: usize) -> bool {
        let zero = Complex::new(0.0, 0.0);
        self.h0[bin] != zero || self.h0[self.partner(bin)] != zero
    }

    /// h̃(k, t) = h0(k) e^{iωt} + conj(h0(−k)) e^{−iωt} for every bin, in f64, into `out`
    /// (length N²). ωt is [`Dispersion::phase`]: reduced modulo the loop period and 2π in
    /// f64, so that h(t + T) = h(t) to round-off and a huge t loses no accuracy.
    ///
    /// h̃(−k) = conj(h̃(k)) holds bit for bit: both bins use the same |k| (negating kx is
    /// exact), so the same phase, and conj distributes exactly over the products and sums.
    pub fn htilde_into(&self, t: f64, out: &mut [Complex<f64>]) -> Result<()> {
        check_time(t)?;
        assert_eq!(out.len(), self.h0.len(), "h̃ buffer must hold N² bins");
        let zero = Complex::new(0.0, 0.0);
        for bin in 0..self.h0.len() {
            let partner = self.partner(bin);
            if partner < bin {
                continue; // filled with its partner
            }
            let (a, b) = (self.h0[bin], self.h0[partner]);
            if a == zero && b == zero {
                out[bin] = zero;
                out[partner] = zero;
                continue;
            }
            let e = Complex::cis(self.dispersion.phase(self.k[bin], t));
            out[bin] = a * e + b.conj() * e.conj();
            out[partner] = b * e + a.conj() * e.conj();
        }
        Ok(())
    }

    /// h̃(k, t) for every bin (see [`WaveModes::htilde_into`]).
    pub fn htilde(&self, t: f64) -> Result<Vec<Complex<f64>>> {
        let mut out = vec![Complex::new(0.0, 0.0); self.h0.len()];
        self.htilde_into(t, &mut out)?;
        Ok(out)
    }

    /// The largest loop harmonic ⌊ω/ω₀⌋ among modes whose h̃ can be non-zero (0 when there
    /// are none), or `None` when the dispersion does not loop.
    pub fn max_loop_harmonic(&self) -> Option<u64> {
        self.dispersion.loop_omega0()?;
        Some(
            (0..self.h0.len())
                .filter(|&bin| self.is_live(bin))
                .filter_map(|bin| self.dispersion.loop_harmonic(self.k[bin]))
                .max()
                .unwrap_or(0),
        )
    }
}

/// The cell weight of the mode with this grid's lattice index (i, j) ≠ (0, 0): 0 outside the
/// band, else its cell's area over Δk² (see [`Band::ExcludeGrid`]). Computed in integers, in
/// half units of the reference lattice, so that it is exact.
fn cell_weight(params: &ModeParams, i: i64, j: i64) -> f64 {
    let Band::ExcludeGrid { resolution } = params.band else {
        return 1.0;
    };
    let r = params.lattice_ratio as i64;
    let inner = resolution as i64;
    let (i, j) = (r * i.abs(), r * j.abs()); // reference-lattice indices
    if 2 * i.max(j) < inner {
        return 0.0; // the inner map holds this wave vector
    }
    // c₀: the innermost held ring; E: the inner map's cell edge, (largest index held) + ½.
    let c0 = r * ((inner + 2 * r - 1) / (2 * r)); // r·⌈N_d / 2r⌉, all ≥ 0
    let edge2 = 2 * ((inner - 1) / 2) + 1; // 2E
    // Twice the length of the cell along one axis, for reference index a ≥ 0.
    let length2 = |a: i64| {
        if a == c0 {
            2 * c0 + r - edge2 // [E, c₀ + r/2]
        } else if a == c0 - r && a > 0 {
            edge2 - (2 * c0 - 3 * r) // [c₀ − 3r/2, E]
        } else if a == 0 && c0 == r {
            2 * edge2 // [−E, E]
        } else {
            2 * r
        }
    };
    (length2(i) * length2(j)) as f64 / (4 * r * r) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_indices() {
        assert_eq!(signed_index(0, 4), Some(0));
        assert_eq!(signed_index(1, 4), Some(1));
        assert_eq!(signed_index(2, 4), None);
        assert_eq!(signed_index(3, 4), Some(-1));
        assert_eq!(signed_index(2, 5), Some(2));
        assert_eq!(signed_index(3, 5), Some(-2));
    }

    #[test]
    fn partner_is_an_involution_and_negates_k() {
        for n in [2, 3, 4, 7, 8] {
            let modes =
                WaveModes::new(&ModeParams::new(10.0, n, 1), Dispersion::deep(9.81), |_, _| 1.0)
                    .unwrap();
            for bin in 0..n * n {
                let p = modes.partner(bin);
                assert_eq!(modes.partner(p), bin);
                let (a, b) = (modes.mode(bin), modes.mode(p));
                if a.active {
                    assert!(b.active);
                    assert_eq!((a.kx, a.kz), (-b.kx, -b.kz));
                    assert_eq!(a.k, b.k);
                }
            }
        }
    }
}
