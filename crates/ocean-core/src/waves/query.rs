//! Direct evaluation of eq. 1 at any point, and the height query on the displaced surface.
//!
//! The direct sum is the same trigonometric polynomial the FFT evaluates on the grid, so at a
//! grid point it equals the maps (to round-off) and between grid points it is their
//! band-limited (trigonometric) interpolant.

use num_complex::Complex;

use super::modes::{WaveModes, check_choppiness};
use crate::Result;

/// The fields of the wave maps at one point (all f64), plus the derivatives of the
/// displacement that make up the Jacobian. See the table in [`super::synthesis`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceSample {
    /// h, metres.
    pub height: f64,
    /// Dx, metres.
    pub disp_x: f64,
    /// Dz, metres.
    pub disp_z: f64,
    /// ∂h/∂x at the undisplaced point.
    pub slope_x: f64,
    /// ∂h/∂z at the undisplaced point.
    pub slope_z: f64,
    /// ∂Dx/∂x.
    pub disp_x_dx: f64,
    /// ∂Dz/∂z.
    pub disp_z_dz: f64,
    /// ∂Dx/∂z = ∂Dz/∂x (D is λ times a gradient, so its derivative matrix is symmetric).
    pub disp_x_dz: f64,
    /// J = (1 + ∂Dx/∂x)(1 + ∂Dz/∂z) − (∂Dx/∂z)².
    pub jacobian: f64,
}

impl SurfaceSample {
    /// The unit normal of the displaced surface P(x0, z0) = (x0 + Dx, h, z0 + Dz) at this
    /// parameter point: the cross product of the tangents ∂P/∂z0 × ∂P/∂x0,
    ///
    /// ```text
    /// n = ( hz·Dxz − hx·(1 + Dzz),  J,  hx·Dxz − hz·(1 + Dxx) )
    /// ```
    ///
    /// normalised. Divided by J this is (−∂h/∂x', 1, −∂h/∂z'), the slopes with respect to
    /// world coordinates x' = x0 + D (the chain rule through the inverse of I + ∂D/∂x0); with
    /// λ = 0 it is (−hx, 1, −hz)/norm. The cross product needs no division by J, so it is
    /// finite everywhere. Where J < 0 the surface is folded over and this is the true normal
    /// of that sheet, pointing down (n_y = J < 0); where both tangents are parallel (the
    /// cross product vanishes) there is no normal and +y is returned.
    pub fn normal(&self) -> [f64; 3] {
        let (hx, hz) = (self.slope_x, self.slope_z);
        let n = [
            hz * self.disp_x_dz - hx * (1.0 + self.disp_z_dz),
            self.jacobian,
            hx * self.disp_x_dz - hz * (1.0 + self.disp_x_dx),
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len > 0.0 && len.is_finite() {
            [n[0] / len, n[1] / len, n[2] / len]
        } else {
            [0.0, 1.0, 0.0]
        }
    }
}

/// The result of inverting the displacement at a world point (x, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inversion {
    /// The parameter point x0 found, in the same frame as the world point.
    pub x0: f64,
    /// The parameter point z0 found.
    pub z0: f64,
    /// |x0 + D(x0) − x|, metres, at the returned point.
    pub residual_m: f64,
    /// Newton / fixed-point iterations taken.
    pub iterations: u32,
    /// Whether the residual reached the tolerance.
    pub converged: bool,
    /// The fields at (x0, z0).
    pub sample: SurfaceSample,
}

#[derive(Clone, Copy, Debug)]
struct QueryMode {
    ix: u32,
    iz: u32,
    kx: f64,
    kz: f64,
    inv_k: f64,
    htilde: Complex<f64>,
}

/// The most Newton / fixed-point iterations of [`SurfaceQuery::invert`]; Newton converges in
/// about 5 where J > 0, the rest is room for the fall-backs.
pub const MAX_INVERSION_ITERATIONS: u32 = 32;

/// The inversion stops at |x0 + D(x0) − x| ≤ this times L: 1 nm for a 1 km patch, about
/// 4000 ulp of L, comfortably above the f64 round-off of the sum.
pub const INVERSION_TOLERANCE_REL: f64 = 1e-12;

/// Step halvings tried before the inversion gives up improving.
const MAX_BACKTRACKS: u32 = 12;

/// The wave field at one time, ready for point queries. Holds h̃(k, t) of the modes where it
/// is non-zero (zero modes are pruned), so a query costs O(N) sines and cosines plus one
/// complex product per live mode.
#[derive(Clone, Debug)]
pub struct SurfaceQuery {
    patch_size_m: f64,
    choppiness: f64,
    axis_k: Vec<f64>,
    modes: Vec<QueryMode>,
    /// Eq. 1 of seed 001 (shading `chiu`): (s_i, a_i), the surface Σ a_i·f(x/s_i); empty for
    /// the single field.
    scales: Vec<(f64, f64)>,
}

impl SurfaceQuery {
    /// Prepares queries of `modes` at time `t` with choppiness λ. Errors on a non-finite t
    /// or λ.
    pub fn new(modes: &WaveModes, t: f64, choppiness: f64) -> Result<Self> {
        check_choppiness(choppiness)?;
        let htilde = modes.htilde(t)?;
        let n = modes.resolution();
        let axis_k = modes.axis_wavenumbers().to_vec();
        let k = modes.wavenumbers();
        let zero = Complex::new(0.0, 0.0);
        let live = htilde
            .iter()
            .enumerate()
            .filter(|&(_, &h)| h != zero)
            .map(|(bin, &h)| QueryMode {
                ix: (bin % n) as u32,
                iz: (bin / n) as u32,
                kx: axis_k[bin % n],
                kz: axis_k[bin / n],
                inv_k: if k[bin] > 0.0 { 1.0 / k[bin] } else { 0.0 },
                htilde: h,
            })
            .collect();
        Ok(Self {
            patch_size_m: modes.patch_size_m(),
            choppiness,
            axis_k,
            modes: live,
            scales: Vec::new(),
        })
    }

    /// The same field sampled as eq. 1 of seed 001 sums it: Σ_i a_i·f(x/s_i) over `scales`,
    /// a_i = 1/√n, as the renderer does with shading `chiu` (`frame::MultiScaleBlock`), so a
    /// floating object agrees with the picture. The slopes and the displacement's derivatives
    /// take the chain rule's a_i/s_i. An empty list is the single field.
    pub fn with_scales(mut self, scales: &[f64]) -> Self {
        let a = 1.0 / (scales.len().max(1) as f64).sqrt();
        self.scales = scales.iter().map(|&s| (s, a)).collect();
        self
    }

    /// The number of modes with h̃ ≠ 0.
    pub fn mode_count(&self) -> usize {
        self.modes.len()
    }

    /// The fields at the undisplaced parameter point (x0, z0): the sums of eq. 1 and of its
    /// derivatives, evaluated directly in f64 (in storage order of the modes, so the result is
    /// reproducible bit for bit). The field is L-periodic, and the point is first reduced to
    /// [0, L)², so that kx·x stays small. Non-finite coordinates give NaN fields.
    pub fn sample(&self, x0: f64, z0: f64) -> SurfaceSample {
        if self.scales.is_empty() {
            return self.sample_field(x0, z0);
        }
        let mut sum = SurfaceSample::default();
        for &(scale, a) in &self.scales {
            let f = self.sample_field(x0 / scale, z0 / scale);
            let c = a / scale;
            sum.height += a * f.height;
            sum.disp_x += a * f.disp_x;
            sum.disp_z += a * f.disp_z;
            sum.slope_x += c * f.slope_x;
            sum.slope_z += c * f.slope_z;
            sum.disp_x_dx += c * f.disp_x_dx;
            sum.disp_z_dz += c * f.disp_z_dz;
            sum.disp_x_dz += c * f.disp_x_dz;
        }
        sum.jacobian =
            (1.0 + sum.disp_x_dx) * (1.0 + sum.disp_z_dz) - sum.disp_x_dz * sum.disp_x_dz;
        sum
    }

    /// [`Self::sample`] of the single field.
    fn sample_field(&self, x0: f64, z0: f64) -> SurfaceSample {
        let l = self.patch_size_m;
        let (x, z) = (x0.rem_euclid(l), z0.rem_euclid(l));
        // e^{i kx x} and e^{i kz z} per axis bin: N sines and cosines, not N².
        let ex: Vec<Complex<f64>> = self.axis_k.iter().map(|&k| Complex::cis(k * x)).collect();
        let ez: Vec<Complex<f64>> = self.axis_k.iter().map(|&k| Complex::cis(k * z)).collect();
        // Σ Re(M h̃ e): with c = h̃ e, Re(c) for real multipliers, Re(±i c) = ∓Im(c).
        let (mut h, mut dx, mut dz, mut hx, mut hz) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let (mut dxx, mut dzz, mut dxz) = (0.0, 0.0, 0.0);
        for m in &self.modes {
            let c = m.htilde * (ex[m.ix as usize] * ez[m.iz as usize]);
            h += c.re;
            dx += m.kx * m.inv_k * c.im;
            dz += m.kz * m.inv_k * c.im;
            hx -= m.kx * c.im;
            hz -= m.kz * c.im;
            dxx += m.kx * m.kx * m.inv_k * c.re;
            dzz += m.kz * m.kz * m.inv_k * c.re;
            dxz += m.kx * m.kz * m.inv_k * c.re;
        }
        // λ = −choppiness: positive choppiness moves samples towards the crests (see the
        // synthesis module, "Sign of D").
        let lambda = -self.choppiness;
        let (dxx, dzz, dxz) = (lambda * dxx, lambda * dzz, lambda * dxz);
        SurfaceSample {
            height: h,
            disp_x: lambda * dx,
            disp_z: lambda * dz,
            slope_x: hx,
            slope_z: hz,
            disp_x_dx: dxx,
            disp_z_dz: dzz,
            disp_x_dz: dxz,
            jacobian: (1.0 + dxx) * (1.0 + dzz) - dxz * dxz,
        }
    }

    /// Finds the parameter point x0 whose displaced position x0 + D(x0) is the world point
    /// (x, z).
    ///
    /// Method: Newton's method on r(x0) = x0 + D(x0) − x, whose derivative is I + ∂D/∂x0
    /// (determinant J), started at x0 = x, with step halving until |r| decreases. Where
    /// J ≤ 1e-3 the Newton step is unreliable and the fixed-point step x0 ← x − D(x0) is used
    /// instead (that iteration alone converges where the eigenvalues of ∂D/∂x0 lie in
    /// (−1, 1); Newton needs only J > 0 near the solution). Where J > 0 everywhere the
    /// preimage is unique; where the surface folds (J ≤ 0 somewhere) a world point can have
    /// three, and the one reached from x0 = x is returned. It stops at
    /// |r| ≤ [`INVERSION_TOLERANCE_REL`]·L, after [`MAX_INVERSION_ITERATIONS`], or when no
    /// step improves |r|, and returns the best point seen, so the result is always finite for
    /// finite (x, z).
    pub fn invert(&self, x: f64, z: f64) -> Inversion {
        let l = self.patch_size_m;
        // Solve in the period containing the point, relative to its origin, so that the
        // residual is not swamped by the round-off of a large coordinate.
        // (A sum over several scales has no period: it is solved where it is.)
        let (x_base, z_base) = if self.scales.is_empty() {
            (x - x.rem_euclid(l), z - z.rem_euclid(l))
        } else {
            (0.0, 0.0)
        };
        let tolerance = INVERSION_TOLERANCE_REL * l;
        let mut inv =
            invert_displacement(|x0, z0| self.sample(x0, z0), x - x_base, z - z_base, tolerance);
        inv.x0 += x_base;
        inv.z0 += z_base;
        inv
    }

    /// The elevation of the displaced surface above the world point (x, z): h(x0) where
    /// x0 + D(x0) = (x, z) (see [`SurfaceQuery::invert`]). With λ = 0 this is h(x, z).
    pub fn height_at(&self, x: f64, z: f64) -> f64 {
        self.invert(x, z).sample.height
    }

    /// The unit normal of the displaced surface above the world point (x, z) (see
    /// [`SurfaceSample::normal`] for the formula and the folded case).
    pub fn normal_at(&self, x: f64, z: f64) -> [f64; 3] {
        self.invert(x, z).sample.normal()
    }
}

/// The fields of eq. 1 at the undisplaced point (x, z), by the direct sum in f64: the oracle
/// for the FFT synthesis. Prepares a [`SurfaceQuery`] for one point; prepare one yourself to
/// evaluate many points.
pub fn eval_direct(
    modes: &WaveModes,
    t: f64,
    choppiness: f64,
    x: f64,
    z: f64,
) -> Result<SurfaceSample> {
    Ok(SurfaceQuery::new(modes, t, choppiness)?.sample(x, z))
}

/// Newton's method of [`SurfaceQuery::invert`] on any displaced surface `sample` (the fields
/// at a parameter point): the parameter point whose displaced position is (x, z), to
/// `tolerance` metres, the best point seen when it does not converge.
pub fn invert_displacement(
    sample: impl Fn(f64, f64) -> SurfaceSample,
    x: f64,
    z: f64,
    tolerance: f64,
) -> Inversion {
    let residual = |p: (f64, f64), s: &SurfaceSample| (p.0 + s.disp_x - x, p.1 + s.disp_z - z);
    let mut p = (x, z);
    let mut s = sample(p.0, p.1);
    let mut r = residual(p, &s);
    let mut r_len = r.0.hypot(r.1);
    let mut iterations = 0;
    while r_len > tolerance && iterations < MAX_INVERSION_ITERATIONS {
        iterations += 1;
        let a = 1.0 + s.disp_x_dx;
        let d = 1.0 + s.disp_z_dz;
        let b = s.disp_x_dz;
        let det = a * d - b * b;
        // Below this J the Newton step grows like 1/J and points anywhere; the fixed-point
        // step is bounded by |r|.
        let step = if det > 1e-3 {
            (-(d * r.0 - b * r.1) / det, -(a * r.1 - b * r.0) / det)
        } else {
            (-r.0, -r.1)
        };
        let mut scale = 1.0;
        let mut improved = false;
        for _ in 0..=MAX_BACKTRACKS {
            let q = (p.0 + scale * step.0, p.1 + scale * step.1);
            let sq = sample(q.0, q.1);
            let rq = residual(q, &sq);
            let rq_len = rq.0.hypot(rq.1);
            if rq_len < r_len {
                (p, s, r, r_len) = (q, sq, rq, rq_len);
                improved = true;
                break;
            }
            scale *= 0.5;
        }
        if !improved {
            break;
        }
    }
    Inversion {
        x0: p.0,
        z0: p.1,
        residual_m: r_len,
        iterations,
        converged: r_len <= tolerance,
        sample: s,
    }
}
