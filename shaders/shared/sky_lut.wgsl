// The sky-view table of sky technique `atmosphere` (ocean_core::atmosphere::SkyLut): the
// single-scattering integrals (Rayleigh, Mie; their phase functions applied here) tabulated
// per frame over u = √(tan(φ/2)/(1 + tan(φ/2))) (φ the azimuth
// from the sun) and v = ½ ± ½√(tan e/(1 + tan e)) (e the elevation), read bilinearly between
// texels (the outermost on the edges) by + − × ÷ √ only (no inverse trigonometry), so that
// both back ends agree. Reads the importing stage's `sky_lut` (a uniform `SkyLut`).
// CPU mirror: ocean-cpu/src/shaders/shared/sky_lut.rs.

// Texels along u and v (ocean_core::atmosphere::LUT_WIDTH, LUT_HEIGHT).
const SKY_LUT_WIDTH: f32 = 32.0;
const SKY_LUT_HEIGHT: f32 = 32.0;
// 3/(16π): the Rayleigh phase function's constant.
const RAYLEIGH_PHASE_K: f32 = 0.059683104;
// The Cornette–Shanks phase function's g and 3/(8π)·(1 − g²)/(2 + g²) (ocean_core::atmosphere::MIE_G).
const MIE_G: f32 = 0.8;
const MIE_PHASE_K: f32 = 0.01627721;

// Per texel k = j·W + i: texels[2k] the Rayleigh integral, texels[2k + 1] the Mie one.
struct SkyLut {
    texels: array<vec4<f32>, 2048>,
}

// The integrals at texel (i, j) weighted by the phase functions (pr, pm).
fn sky_lut_texel(i: f32, j: f32, pr: f32, pm: f32) -> vec3<f32> {
    let k = 2u * (u32(j) * 32u + u32(i));
    return sky_lut.texels[k].xyz * pr + sky_lut.texels[k + 1u].xyz * pm;
}

// The table's radiance along unit `dir` with the sun along unit `sun`.
fn sky_lut_radiance(dir: vec3<f32>, sun: vec3<f32>) -> vec3<f32> {
    let mu = dir.x * sun.x + dir.y * sun.y + dir.z * sun.z;
    let pr = RAYLEIGH_PHASE_K * (mu * mu + 1.0);
    // (1 + g² − 2gμ)^1.5 as x·√x, with 1 + g² − 2gμ = (1 − g)² + g·|d − s|² (1 − μ = |d − s|²/2
    // for unit vectors): formed from μ it cancelled next to the sun, where one ulp of μ moved the
    // Mie glow by 8e-5 between the back ends.
    let ds = vec3<f32>(dir.x - sun.x, dir.y - sun.y, dir.z - sun.z);
    let w = max(0.04 + MIE_G * ((ds.x * ds.x + ds.y * ds.y) + ds.z * ds.z), 1e-12);
    let pm = MIE_PHASE_K * (mu * mu + 1.0) / (w * sqrt(w));
    let dh = sqrt(dir.x * dir.x + dir.z * dir.z);
    let sh = sqrt(sun.x * sun.x + sun.z * sun.z);
    var a = 0.0;
    if (dh > 0.0 && sh > 0.0) {
        // tan(φ/2) = |d − s|/|d + s| for the unit horizontal directions d and s: exact next to
        // the sun and opposite it.
        let mx = dir.x / dh - sun.x / sh;
        let mz = dir.z / dh - sun.z / sh;
        let px = dir.x / dh + sun.x / sh;
        let pz = dir.z / dh + sun.z / sh;
        let m = sqrt(mx * mx + mz * mz);
        let p = sqrt(px * px + pz * pz);
        a = m / (m + p);
    }
    let u = sqrt(a);
    let y = abs(dir.y);
    let q = y / (y + dh);
    var v = 0.5 - 0.5 * sqrt(q);
    if (dir.y >= 0.0) {
        v = 0.5 + 0.5 * sqrt(q);
    }
    let x = clamp(u * (SKY_LUT_WIDTH - 1.0), 0.0, SKY_LUT_WIDTH - 1.0);
    let z = clamp(v * (SKY_LUT_HEIGHT - 1.0), 0.0, SKY_LUT_HEIGHT - 1.0);
    let i0 = floor(x);
    let j0 = floor(z);
    let i1 = min(i0 + 1.0, SKY_LUT_WIDTH - 1.0);
    let j1 = min(j0 + 1.0, SKY_LUT_HEIGHT - 1.0);
    let tx = x - i0;
    let tz = z - j0;
    let t00 = sky_lut_texel(i0, j0, pr, pm);
    let t10 = sky_lut_texel(i1, j0, pr, pm);
    let t01 = sky_lut_texel(i0, j1, pr, pm);
    let t11 = sky_lut_texel(i1, j1, pr, pm);
    let ab = t00 + (t10 - t00) * tx;
    let cd = t01 + (t11 - t01) * tx;
    return ab + (cd - ab) * tz;
}
