//! Mirror of `shaders/shared/sky_lut.wgsl`: sky `atmosphere`'s sky-view table, read
//! bilinearly by + − × ÷ √ only.

use ocean_core::atmosphere::SkyLut;

use crate::shaders::wgsl::{Vec3, clamp, max, min, vec3};

/// `SKY_LUT_WIDTH`.
pub const SKY_LUT_WIDTH: f32 = 32.0;
/// `SKY_LUT_HEIGHT`.
pub const SKY_LUT_HEIGHT: f32 = 32.0;
/// `RAYLEIGH_PHASE_K`: 3/(16π).
pub const RAYLEIGH_PHASE_K: f32 = (3.0 / (16.0 * std::f64::consts::PI)) as f32;
/// `MIE_G`.
pub const MIE_G: f32 = ocean_core::atmosphere::MIE_G as f32;
/// `MIE_PHASE_K`: 3/(8π)·(1 − g²)/(2 + g²).
pub const MIE_PHASE_K: f32 = {
    let g2 = ocean_core::atmosphere::MIE_G * ocean_core::atmosphere::MIE_G;
    (3.0 / (8.0 * std::f64::consts::PI) * (1.0 - g2) / (2.0 + g2)) as f32
};

/// `sky_lut_texel(i, j, pr, pm)`.
fn sky_lut_texel(lut: &SkyLut, i: f32, j: f32, pr: f32, pm: f32) -> Vec3 {
    let k = 2 * (j as usize * 32 + i as usize);
    let (r, m) = (lut.texels[k], lut.texels[k + 1]);
    vec3(r[0], r[1], r[2]) * pr + vec3(m[0], m[1], m[2]) * pm
}

/// `sky_lut_radiance(dir, sun)`.
pub fn sky_lut_radiance(lut: &SkyLut, dir: Vec3, sun: Vec3) -> Vec3 {
    let mu = dir.x * sun.x + dir.y * sun.y + dir.z * sun.z;
    let pr = RAYLEIGH_PHASE_K * (mu * mu + 1.0);
    let ds = [dir.x - sun.x, dir.y - sun.y, dir.z - sun.z];
    let w = max(0.04 + MIE_G * ((ds[0] * ds[0] + ds[1] * ds[1]) + ds[2] * ds[2]), 1e-12);
    let pm = MIE_PHASE_K * (mu * mu + 1.0) / (w * w.sqrt());
    let dh = (dir.x * dir.x + dir.z * dir.z).sqrt();
    let sh = (sun.x * sun.x + sun.z * sun.z).sqrt();
    let mut a = 0.0;
    if dh > 0.0 && sh > 0.0 {
        let mx = dir.x / dh - sun.x / sh;
        let mz = dir.z / dh - sun.z / sh;
        let px = dir.x / dh + sun.x / sh;
        let pz = dir.z / dh + sun.z / sh;
        let m = (mx * mx + mz * mz).sqrt();
        let p = (px * px + pz * pz).sqrt();
        a = m / (m + p);
    }
    let u = a.sqrt();
    let y = dir.y.abs();
    let q = y / (y + dh);
    let mut v = 0.5 - 0.5 * q.sqrt();
    if dir.y >= 0.0 {
        v = 0.5 + 0.5 * q.sqrt();
    }
    let x = clamp(u * (SKY_LUT_WIDTH - 1.0), 0.0, SKY_LUT_WIDTH - 1.0);
    let z = clamp(v * (SKY_LUT_HEIGHT - 1.0), 0.0, SKY_LUT_HEIGHT - 1.0);
    let i0 = x.floor();
    let j0 = z.floor();
    let i1 = min(i0 + 1.0, SKY_LUT_WIDTH - 1.0);
    let j1 = min(j0 + 1.0, SKY_LUT_HEIGHT - 1.0);
    let tx = x - i0;
    let tz = z - j0;
    let t00 = sky_lut_texel(lut, i0, j0, pr, pm);
    let t10 = sky_lut_texel(lut, i1, j0, pr, pm);
    let t01 = sky_lut_texel(lut, i0, j1, pr, pm);
    let t11 = sky_lut_texel(lut, i1, j1, pr, pm);
    let ab = t00 + (t10 - t00) * tx;
    let cd = t01 + (t11 - t01) * tx;
    ab + (cd - ab) * tz
}
