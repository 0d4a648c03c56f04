//! The sky-view table of sky technique `atmosphere`: the two scattering integrals of
//! [`super::sky_scattering`] (Rayleigh and Mie, without their phase functions, which carry the
//! aerosols' sharp forward peak and are applied per pixel as Bruneton & Neyret do) tabulated
//! over the directions seen from the eye for the frame's sun, which both back ends read as a uniform
//! array (WGSL `SkyLut`, shaders/shared/sky_lut.wgsl) and interpolate bilinearly by + − × ÷ √
//! only, so the CPU oracle and the GPU agree; the integral itself (32 × 16 exponentials per
//! direction and channel) is made once per frame here, in f64, as Hillaire (2020) makes his
//! sky-view LUT.
//!
//! Coordinates, chosen to need no inverse trigonometry, to be near linear in angle (so that
//! neither the zenith nor the anti-solar sky is squeezed into one texel) and to put texels
//! where the sky changes fastest:
//! - u = √a, a = tan(φ/2)/(1 + tan(φ/2)) = |d − s|/(|d − s| + |d + s|), φ the azimuth
//!   between the view's and the sun's unit horizontal directions d, s (the sky is symmetric about the
//!   sun's vertical plane): near the sun φ ≈ 2u², so the first texel spans 0.12° of the Mie
//!   peak, the last 7.4° of the anti-solar sky;
//! - v = ½ ± ½√q, q = |y|/(|y| + h) = tan e/(1 + tan e), e the elevation, y and h the view's
//!   vertical and horizontal components, + above the horizon: the horizon band, where the
//!   optical depth changes fastest, gets texels of 0.24°, the zenith 7.4°.
//!
//! Texel (i, j) holds the radiance at u = i/(W − 1), v = j/(H − 1): the outermost texels lie on
//! the edges — towards and away from the sun, the nadir and the zenith, where the elevation's
//! coarsest texels are (a half-texel inset left everything above 70° to the last row's value,
//! up to twice the zenith's radiance); between them the lookup is bilinear.

use std::sync::{Arc, LazyLock};

use bytemuck::{Pod, Zeroable};

/// Texels along u (azimuth from the sun).
pub const LUT_WIDTH: usize = 32;
/// Texels along v (elevation).
pub const LUT_HEIGHT: usize = 32;

/// The table: at texel (i, j), k = j·W + i, `texels[2k]` = (r, g, b, 0) of the Rayleigh
/// integral and `texels[2k + 1]` that of the Mie integral, scene units per steradian's phase.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SkyLut {
    /// Row-major, rows of constant v, two entries per texel.
    pub texels: [[f32; 4]; 2 * LUT_WIDTH * LUT_HEIGHT],
}

/// (u, v) of unit direction `dir` for the sun along unit `sun` (see the module doc). A
/// vertical view or sun has no azimuth: u = 0 (the sky is then the same at every azimuth).
pub fn lut_coordinates(dir: [f64; 3], sun: [f64; 3]) -> [f64; 2] {
    let (dh, sh) =
        ((dir[0] * dir[0] + dir[2] * dir[2]).sqrt(), (sun[0] * sun[0] + sun[2] * sun[2]).sqrt());
    let mut a = 0.0;
    if dh > 0.0 && sh > 0.0 {
        // tan(φ/2) = |d − s|/|d + s| for the unit horizontal directions d and s (the chords
        // 2 sin(φ/2) and 2 cos(φ/2)): exact next to the sun and opposite it, and their sum is
        // at least 2.
        let (mx, mz) = (dir[0] / dh - sun[0] / sh, dir[2] / dh - sun[2] / sh);
        let (px, pz) = (dir[0] / dh + sun[0] / sh, dir[2] / dh + sun[2] / sh);
        let (m, p) = ((mx * mx + mz * mz).sqrt(), (px * px + pz * pz).sqrt());
        a = m / (m + p);
    }
    let y = dir[1].abs();
    let q = y / (y + dh);
    let v = if dir[1] >= 0.0 { 0.5 + 0.5 * q.sqrt() } else { 0.5 - 0.5 * q.sqrt() };
    [a.sqrt(), v]
}

/// The unit direction at (u, v) with the sun's horizontal direction rotated by φ towards +z:
/// the inverse of [`lut_coordinates`].
pub fn lut_direction(u: f64, v: f64, sun: [f64; 3]) -> [f64; 3] {
    // tan(φ/2) = a/(1 − a), then cos φ and sin φ by the half-angle formulas.
    let a = u * u;
    let (cos_phi, sin_phi) = if a >= 1.0 {
        (-1.0, 0.0)
    } else {
        let t = a / (1.0 - a);
        ((1.0 - t * t) / (1.0 + t * t), 2.0 * t / (1.0 + t * t))
    };
    // tan e = q/(1 − q): (y, h) ∝ (q, 1 − q).
    let s = 2.0 * v - 1.0;
    let q = s * s;
    let norm = (q * q + (1.0 - q) * (1.0 - q)).sqrt();
    let (y, h) = (s.signum() * q / norm, (1.0 - q) / norm);
    let sh = (sun[0] * sun[0] + sun[2] * sun[2]).sqrt();
    let (ax, az) = if sh > 0.0 { (sun[0] / sh, sun[2] / sh) } else { (1.0, 0.0) };
    [h * (cos_phi * ax - sin_phi * az), y, h * (cos_phi * az + sin_phi * ax)]
}

impl SkyLut {
    /// The all-zero table, shared: what a frame whose sky has no table binds in its place.
    pub fn zero() -> Arc<Self> {
        static ZERO: LazyLock<Arc<SkyLut>> = LazyLock::new(|| Arc::new(SkyLut::zeroed()));
        Arc::clone(&ZERO)
    }

    /// [`Self::new`], made once per (altitude, sun, irradiance) and shared from then on: a
    /// steady frame with the same eye height and sun asks the same table (2 × 32² scattering
    /// integrals, the bulk of a `welch` frame's CPU encode when it was made every frame; then
    /// its 32 KiB copy, a tenth of that encode, when the kept table was copied out).
    pub fn kept(altitude_m: f64, sun: [f64; 3], sun_irradiance: [f64; 3]) -> Arc<Self> {
        static KEPT: crate::kept::Kept<[u64; 7], Arc<SkyLut>> = crate::kept::Kept::new();
        let key = [
            altitude_m.to_bits(),
            sun[0].to_bits(),
            sun[1].to_bits(),
            sun[2].to_bits(),
            sun_irradiance[0].to_bits(),
            sun_irradiance[1].to_bits(),
            sun_irradiance[2].to_bits(),
        ];
        KEPT.get(key, || Self::new(altitude_m, sun, sun_irradiance).into())
    }

    /// The table of the sky seen from `altitude_m` above the sea with the sun along unit
    /// `sun` and `sun_irradiance` at the top of the atmosphere ([`super::sky_radiance`] at
    /// [`super::SKY_STEPS`] × [`super::SUN_STEPS`]). Rows in parallel; each texel is a pure
    /// function of its inputs, so the table does not depend on the thread count.
    pub fn new(altitude_m: f64, sun: [f64; 3], sun_irradiance: [f64; 3]) -> Box<Self> {
        use rayon::prelude::*;
        let mut lut = Box::new(Self::zeroed());
        lut.texels.par_chunks_mut(2 * LUT_WIDTH).enumerate().for_each(|(j, row)| {
            let v = j as f64 / (LUT_HEIGHT - 1) as f64;
            for (i, t) in row.chunks_mut(2).enumerate() {
                let u = i as f64 / (LUT_WIDTH - 1) as f64;
                let d = lut_direction(u, v, sun);
                let s = super::sky_scattering(
                    altitude_m,
                    d,
                    sun,
                    sun_irradiance,
                    super::SKY_STEPS,
                    super::SUN_STEPS,
                );
                let f = |a: [f64; 3]| [a[0] as f32, a[1] as f32, a[2] as f32, 0.0];
                t[0] = f(s.rayleigh);
                t[1] = f(s.mie);
            }
        });
        lut
    }

    /// The table's bilinear radiance along unit `dir` (f64; the shaders' lookup in f32 is
    /// `sky_lut_radiance`).
    pub fn radiance(&self, dir: [f64; 3], sun: [f64; 3]) -> [f64; 3] {
        let [u, v] = lut_coordinates(dir, sun);
        let x = (u * (LUT_WIDTH - 1) as f64).clamp(0.0, (LUT_WIDTH - 1) as f64);
        let y = (v * (LUT_HEIGHT - 1) as f64).clamp(0.0, (LUT_HEIGHT - 1) as f64);
        let (i0, j0) = (x.floor() as usize, y.floor() as usize);
        let (i1, j1) = ((i0 + 1).min(LUT_WIDTH - 1), (j0 + 1).min(LUT_HEIGHT - 1));
        let (tx, ty) = (x - i0 as f64, y - j0 as f64);
        let mu = dir[0] * sun[0] + dir[1] * sun[1] + dir[2] * sun[2];
        let phase = [super::rayleigh_phase(mu), super::mie_phase(mu, super::MIE_G)];
        let at = |i: usize, j: usize, c: usize, m: usize| {
            f64::from(self.texels[2 * (j * LUT_WIDTH + i) + m][c])
        };
        std::array::from_fn(|c| {
            (0..2)
                .map(|m| {
                    let a = at(i0, j0, c, m) * (1.0 - tx) + at(i1, j0, c, m) * tx;
                    let b = at(i0, j1, c, m) * (1.0 - tx) + at(i1, j1, c, m) * tx;
                    (a * (1.0 - ty) + b * ty) * phase[m]
                })
                .sum()
        })
    }

    /// The table's mean radiance weighted by cos θ over the upper hemisphere (the irradiance of
    /// an upward surface over π): the objects' ambient term, on the same 32 × 64 grid as
    /// [`crate::frame::sky_ambient`].
    pub fn ambient(&self, sun: [f64; 3]) -> [f32; 3] {
        let (rows, cols) = (32, 64);
        let mut sum = [0.0f64; 3];
        for i in 0..rows {
            let cos2 = (f64::from(i) + 0.5) / f64::from(rows);
            let (cos_t, sin_t) = (cos2.sqrt(), (1.0 - cos2).sqrt());
            for j in 0..cols {
                let phi = std::f64::consts::TAU * (f64::from(j) + 0.5) / f64::from(cols);
                let l = self.radiance([sin_t * phi.cos(), cos_t, sin_t * phi.sin()], sun);
                for c in 0..3 {
                    sum[c] += l[c];
                }
            }
        }
        sum.map(|s| (s / f64::from(rows * cols)) as f32)
    }
}
