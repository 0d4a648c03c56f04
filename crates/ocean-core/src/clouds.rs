//! The cloud layer of sky technique `preetham_clouds` (seed 001 eq. 4:
//! C_sky·(1 − α) + C_cloud·α, α the cloud's opacity), in the f32 arithmetic that
//! `shaders/sky/preetham_clouds.wgsl` writes out and the CPU mirror runs.
//!
//! The layer is a horizontal plane `altitude_m` above the sea whose opacity is fractal value
//! noise: five octaves of a bilinear-smoothstep blend of hashed lattice values, the lattice
//! `scale_m` metres a cell, periodic over [`CLOUD_PERIOD`] cells so that the eye's position
//! (and the wind's drift, `wind`·t) can be reduced modulo the period in f64 before it reaches
//! f32. The hash is integer arithmetic, the rest + − × and floor, so both back ends compute
//! the same bits. α = clamp(4·(fbm − t), 0, 1), the threshold t chosen (on the CPU, by
//! bisection over the noise's values on a 64 × 64 grid of one period) so that the layer's mean
//! opacity is the coverage: 0 is a clear sky, 1 an overcast one. Towards the horizon, where a
//! pixel would average many cells, α fades to that mean (below 0.1 of elevation's sine: ~6°),
//! which also keeps the noise away from the grazing rays whose hit points f32 cannot place.
//!
//! The cloud's colour is `albedo` times the light a white Lambertian surface receives (the
//! sun's irradiance over π plus the clear sky's ambient): the objects' lighting. The sun's
//! light on the sea and the objects is dimmed by the cloud in front of the sun (1 − α there).

use serde::{Deserialize, Serialize};

/// The noise lattice's period, cells (a power of two: the octaves' lattices, 2^o as fine,
/// share it).
pub const CLOUD_PERIOD: u32 = 256;
/// Octaves of the fractal noise.
pub const CLOUD_OCTAVES: u32 = 5;
/// The opacity's weight against the layer's mean is the elevation's sine times this, up to 1:
/// below a sine of 0.1 (~6°) it fades to the mean.
pub const CLOUD_HORIZON_GAIN: f32 = 10.0;

/// A lattice value in [0, 1) for cell (i, j) (wrapped to the period) of octave `octave`:
/// an integer hash (multiply–xorshift), the top 24 bits as the fraction.
pub fn cloud_hash(i: i32, j: i32, octave: u32) -> f32 {
    let wrap = CLOUD_PERIOD - 1;
    let (i, j) = ((i as u32) & wrap, (j as u32) & wrap);
    let mut h = i.wrapping_mul(0x8da6_b343)
        ^ j.wrapping_mul(0xd816_3841)
        ^ octave.wrapping_mul(0x9e37_79b9);
    h = (h ^ (h >> 15)).wrapping_mul(0x2c1b_3c6d);
    h = (h ^ (h >> 12)).wrapping_mul(0x297a_2d39);
    h ^= h >> 15;
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Value noise at (x, z) lattice cells: the four corners' hashes blended with the smoothstep
/// weights 3t² − 2t³.
pub fn cloud_value_noise(x: f32, z: f32, octave: u32) -> f32 {
    let fx = x.floor();
    let fz = z.floor();
    let (i, j) = (fx as i32, fz as i32);
    let tx = x - fx;
    let tz = z - fz;
    let ux = tx * tx * (3.0 - 2.0 * tx);
    let uz = tz * tz * (3.0 - 2.0 * tz);
    let a = cloud_hash(i, j, octave);
    let b = cloud_hash(i.wrapping_add(1), j, octave);
    let c = cloud_hash(i, j.wrapping_add(1), octave);
    let d = cloud_hash(i.wrapping_add(1), j.wrapping_add(1), octave);
    let ab = a + (b - a) * ux;
    let cd = c + (d - c) * ux;
    ab + (cd - ab) * uz
}

/// Fractal noise in [0, 1): octave o at 2^o times the frequency and 2^−(o+1) the weight,
/// normalised by the weights' sum.
pub fn cloud_fbm(x: f32, z: f32) -> f32 {
    let mut sum = 0.0;
    let mut amp = 0.5;
    let mut freq = 1.0;
    for o in 0..CLOUD_OCTAVES {
        sum += amp * cloud_value_noise(x * freq, z * freq, o);
        amp *= 0.5;
        freq *= 2.0;
    }
    // 1 − 2^−5: the weights' sum.
    sum / 0.968_75
}

/// The layer's opacity at fractal value `fbm` for threshold `threshold`
/// ([`cloud_threshold`]).
pub fn cloud_opacity(fbm: f32, threshold: f32) -> f32 {
    ((fbm - threshold) * 4.0).clamp(0.0, 1.0)
}

/// The fractal noise at the centres of a 64 × 64 grid of one period, in the order written
/// (the same for every seed: a seed shifts the lattice by whole cells).
fn period_samples() -> &'static [f32] {
    static SAMPLES: std::sync::OnceLock<Vec<f32>> = std::sync::OnceLock::new();
    SAMPLES.get_or_init(|| {
        let n = 64u32;
        let step = CLOUD_PERIOD as f32 / n as f32;
        (0..n * n)
            .map(|k| cloud_fbm(((k % n) as f32 + 0.5) * step, ((k / n) as f32 + 0.5) * step))
            .collect()
    })
}

/// The layer's mean opacity over one period at threshold `threshold`, kept per threshold
/// (a frame asks it for its layer's threshold: 4,096 samples every frame).
pub fn cloud_mean_opacity(threshold: f32) -> f32 {
    static KEPT: crate::kept::Kept<u32, f32> = crate::kept::Kept::new();
    KEPT.get(threshold.to_bits(), || mean_opacity(threshold))
}

/// [`cloud_mean_opacity`], computed.
fn mean_opacity(threshold: f32) -> f32 {
    let s = period_samples();
    (s.iter().map(|&f| f64::from(cloud_opacity(f, threshold))).sum::<f64>() / s.len() as f64) as f32
}

/// The threshold whose mean opacity is `coverage` ∈ [0, 1]: bisection (the mean falls
/// monotonically as the threshold rises) between −¼, where every α is 1, and 1, where every
/// α is 0. Kept per coverage: the bisection is 40 means of 4,096 samples, and every frame of
/// a cloudy sky asks for it ([`cloud_origin`]).
pub fn cloud_threshold(coverage: f32) -> f32 {
    static KEPT: crate::kept::Kept<u32, f32> = crate::kept::Kept::new();
    KEPT.get(coverage.to_bits(), || threshold_of(coverage))
}

/// [`cloud_threshold`], computed.
fn threshold_of(coverage: f32) -> f32 {
    let (mut lo, mut hi) = (-0.25f32, 1.0f32);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if mean_opacity(mid) > coverage {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if coverage <= 0.0 {
        return 1.0;
    }
    if coverage >= 1.0 {
        return -0.25;
    }
    0.5 * (lo + hi)
}

/// The opacity in unit direction `dir` from the eye: `origin` = (the eye's x, z on the
/// lattice, the layer's height above the eye in cells, the threshold), `mean` the layer's mean
/// opacity (towards the horizon). 0 looking down or with the layer below the eye.
pub fn cloud_alpha(origin: [f32; 4], mean: f32, dir: [f32; 3]) -> f32 {
    if dir[1] <= 0.0 || origin[2] <= 0.0 {
        return 0.0;
    }
    let w = (dir[1] * CLOUD_HORIZON_GAIN).clamp(0.0, 1.0);
    if w == 0.0 {
        return mean;
    }
    let t = origin[2] / dir[1];
    let a = cloud_opacity(cloud_fbm(origin[0] + dir[0] * t, origin[1] + dir[2] * t), origin[3]);
    a * w + mean * (1.0 - w)
}

/// `SkyUniforms::cloud_origin` for the eye at `eye` (m) at time `time_s`: the eye's (x, z)
/// less the wind's drift (the clouds move with the wind), in cells reduced modulo the period
/// (f64, so a far eye keeps its digits; the time modulo 10⁹ s), with the seed's offset; the
/// layer's height above the eye in cells; the threshold of the coverage.
pub fn cloud_origin(clouds: &Clouds, eye: [f64; 3], time_s: f64) -> [f32; 4] {
    let period = f64::from(CLOUD_PERIOD);
    // A seed moves the lattice by whole cells (a different sky, the same statistics).
    let (sx, sz) = (f64::from(clouds.seed % 251) * 37.0, f64::from(clouds.seed % 241) * 53.0);
    let cell = |p: f64, drift: f64, s: f64| {
        ((p - drift * time_s.rem_euclid(1e9)) / clouds.scale_m + s).rem_euclid(period) as f32
    };
    [
        cell(eye[0], clouds.wind[0], sx),
        cell(eye[2], clouds.wind[1], sz),
        ((clouds.altitude_m - eye[1]) / clouds.scale_m) as f32,
        cloud_threshold(clouds.coverage as f32),
    ]
}

/// The `[clouds]` table: the cloud layer of sky technique `preetham_clouds` (seed 001 eq. 4;
/// the model is `crate::clouds`'). Deterministic: the sky is a function of the scene and the
/// time.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Clouds {
    /// 0 a clear sky, 1 an overcast one.
    pub coverage: f64,
    /// Height of the layer above the sea, m.
    pub altitude_m: f64,
    /// Side of a cell of the noise's coarsest octave, m (clouds are about this wide).
    pub scale_m: f64,
    /// The layer's drift (x, z), m/s.
    pub wind: [f64; 2],
    /// The clouds' albedo: their colour is this times the light on a white surface.
    pub albedo: f64,
    /// Which sky of these statistics.
    pub seed: u32,
}

impl Default for Clouds {
    fn default() -> Self {
        Self {
            coverage: 0.5,
            altitude_m: 2000.0,
            scale_m: 1500.0,
            wind: [8.0, 2.0],
            albedo: 0.8,
            seed: 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kept threshold and mean are the computed ones, bit for bit, after more coverages
    /// than are kept (the first asked again is computed again), and each coverage its own.
    #[test]
    fn the_kept_threshold_and_mean_are_the_computed_ones() {
        let mut seen = Vec::new();
        for c in [0.1f32, 0.3, 0.5, 0.7, 0.9, 0.1, 0.3] {
            let t = cloud_threshold(c);
            assert_eq!(t.to_bits(), threshold_of(c).to_bits(), "coverage {c}");
            assert_eq!(cloud_mean_opacity(t).to_bits(), mean_opacity(t).to_bits(), "{c}");
            seen.push(t.to_bits());
        }
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 5, "five coverages, five thresholds");
    }
}
