//! Mirror of `shaders/shared/sky_lut.wgsl`: sky `atmosphere`'s sky-view table, read
//! bilinearly by + − × ÷ √ only.

use ocean_core::atmosphere::SkyLut;

use crate::envelope::{Cond, Real, choose, length2, on_floor};
use crate::shaders::wgsl::Vec3;

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
fn sky_lut_texel<R: Real>(lut: &SkyLut, i: f32, j: f32, pr: R, pm: R) -> [R; 3] {
    let k = 2 * (j as usize * 32 + i as usize);
    let (r, m) = (lut.texels[k], lut.texels[k + 1]);
    std::array::from_fn(|c| R::lit(r[c]) * pr + R::lit(m[c]) * pm)
}

/// `sky_lut_radiance(dir, sun)`.
pub fn sky_lut_radiance(lut: &SkyLut, dir: Vec3, sun: Vec3) -> Vec3 {
    Vec3::from(sky_lut_radiance_r(lut, [dir.x, dir.y, dir.z], [sun.x, sun.y, sun.z]))
}

/// [`sky_lut_radiance`] over any [`Real`]: the branches on the horizontal lengths and on the
/// hemisphere taken both ways where undecided, and the bilinear read over every cell the
/// table coordinates may floor to.
pub fn sky_lut_radiance_r<R: Real>(lut: &SkyLut, dir: [R; 3], sun: [R; 3]) -> [R; 3] {
    let l = R::lit;
    let (zero, half, one) = (l(0.0), l(0.5), l(1.0));
    let sum = |t: &[R]| R::sum(t);
    let mu = sum(&[dir[0] * sun[0], dir[1] * sun[1], dir[2] * sun[2]]);
    let pr = l(RAYLEIGH_PHASE_K) * (mu * mu + one);
    let ds = [dir[0] - sun[0], dir[1] - sun[1], dir[2] - sun[2]];
    let w =
        (l(0.04) + l(MIE_G) * sum(&[ds[0] * ds[0], ds[1] * ds[1], ds[2] * ds[2]])).max(l(1e-12));
    let pm = l(MIE_PHASE_K) * (mu * mu + one) / (w * w.sqrt());
    let dh = (dir[0] * dir[0] + dir[2] * dir[2]).sqrt();
    let sh = (sun[0] * sun[0] + sun[2] * sun[2]).sqrt();
    let a = choose(
        zero.lt(dh).and(zero.lt(sh)),
        || {
            let mx = dir[0] / dh - sun[0] / sh;
            let mz = dir[2] / dh - sun[2] / sh;
            let px = dir[0] / dh + sun[0] / sh;
            let pz = dir[2] / dh + sun[2] / sh;
            let m = length2([mx, mz]);
            let p = length2([px, pz]);
            m / (m + p)
        },
        || zero,
    );
    let u = a.sqrt();
    let y = dir[1].abs();
    let q = y / (y + dh);
    let v = choose(zero.le(dir[1]), || half + half * q.sqrt(), || half - half * q.sqrt());
    let (wm, hm) = (l(SKY_LUT_WIDTH - 1.0), l(SKY_LUT_HEIGHT - 1.0));
    let x = (u * wm).clamp(zero, wm);
    let z = (v * hm).clamp(zero, hm);
    // Past on_floor's cells: a blend by weights in [0, 1] of texels r·pr + m·pm, each channel
    // of r and m at least 0 and at most the table's greatest (the blend's roundings, about
    // 0.75·2⁻²⁰ of it, in the factor 1 + 2⁻²⁰). The weights are finite on every GPU: dh is 0
    // (the branch skipped, a = 0) or at least 2⁻⁷⁵, so a is.
    let most = |k: usize| {
        std::array::from_fn::<f32, 3, _>(|c| {
            lut.texels.iter().skip(k).step_by(2).fold(0.0f32, |m, t| m.max(t[c]))
        })
    };
    let (r_max, m_max) = (most(0), most(1));
    let negative = lut.texels.iter().flatten().any(|v| v.is_nan() || *v < 0.0);
    let full: [R; 3] = std::array::from_fn(|c| {
        if negative {
            return l(f32::NAN);
        }
        let top = (l(r_max[c]) * pr + l(m_max[c]) * pm) * l(1.0 + 1.0 / 1_048_576.0);
        l(0.0).hull(top)
    });
    on_floor(x, full, |i0, tx| {
        on_floor(z, full, |j0, tz| {
            let i1 = (i0 + 1.0).min(SKY_LUT_WIDTH - 1.0);
            let j1 = (j0 + 1.0).min(SKY_LUT_HEIGHT - 1.0);
            let t00 = sky_lut_texel(lut, i0, j0, pr, pm);
            let t10 = sky_lut_texel(lut, i1, j0, pr, pm);
            let t01 = sky_lut_texel(lut, i0, j1, pr, pm);
            let t11 = sky_lut_texel(lut, i1, j1, pr, pm);
            std::array::from_fn(|c| {
                let ab = t00[c] + (t10[c] - t00[c]) * tx;
                let cd = t01[c] + (t11[c] - t01[c]) * tx;
                ab + (cd - ab) * tz
            })
        })
    })
}
