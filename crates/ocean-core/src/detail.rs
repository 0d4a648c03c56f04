//! The seed's detail normal map (seed 002 §Normal maps, shading `ggx`): "the normal texture is
//! overlayed twice and moves in opposing directions at different speeds, the normals are
//! combined by perturbing the normal along the direction of the surface normal".
//!
//! **The map.** A static, isotropic slope field of [`DETAIL_WAVES`] sinusoids: wavelengths
//! log-uniform in [½, 2)·`detail_wavelength_m`, directions uniform, phases uniform, each with
//! the slope amplitude strength/√K, so that one layer's RMS slope is strength/√2 and the two
//! layers' together `detail_strength` (their slopes are independent). It is drawn once from the
//! project's counter-based generator with a fixed seed ([`DETAIL_SEED`]): as the seed's texture,
//! it is the same in every scene. A sum of sinusoids rather than a texture: its slopes are
//! exact at any distance, and each one is filtered over the pixel's footprint analytically, as
//! the Gerstner waves' are, so the detail fades into the BRDF instead of sparkling.
//!
//! **The two layers.** Layer 1 drifts with the wind at `detail_speed_m_s`; layer 2 is the same
//! map scaled by 1/φ (φ the golden ratio, so the two never line up) drifting against the wind at
//! 0.6 of that speed. The layers' slopes add to the surface's (the normal is perturbed within the
//! surface's tangent plane, the seed's "along the direction of the surface normal").
//!
//! **Phase.** θ = f·(x − v t) + φ₀ in turns, formed per frame in f64 relative to the mesh's
//! reference point, so the shader adds f·pos (small) to a phase in [−½, ½) as the Gerstner
//! waves do.

use bytemuck::Zeroable;

use crate::rng::SplitMix64;

/// Sinusoids per layer.
pub const DETAIL_WAVES: usize = 16;

/// The generator's seed of the map.
pub const DETAIL_SEED: u64 = 0x0002_DE7A_11ED;

/// Layer 2's scale: the golden ratio.
const LAYER2_SCALE: f64 = 1.618_033_988_749_895;

/// Layer 2's speed against layer 1's.
const LAYER2_SPEED: f64 = 0.6;

/// One sinusoid of the map: frequency (turns per metre) along x and z, phase (turns), and the
/// slope amplitude (|∇h| of its crest).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DetailWave {
    /// Turns per metre along x.
    pub fx: f64,
    /// Turns per metre along z.
    pub fz: f64,
    /// Phase, turns.
    pub phase: f64,
    /// Slope amplitude.
    pub slope: f64,
}

/// The map's [`DETAIL_WAVES`] sinusoids for a median wavelength and an RMS slope `strength`
/// (both layers together).
pub fn detail_waves(wavelength_m: f64, strength: f64) -> Vec<DetailWave> {
    let mut rng = SplitMix64::new(DETAIL_SEED);
    let slope = strength / (DETAIL_WAVES as f64).sqrt();
    (0..DETAIL_WAVES)
        .map(|_| {
            let lambda = wavelength_m * 2f64.powf(2.0 * rng.next_open_closed() - 1.0);
            let dir = std::f64::consts::TAU * rng.next_open_closed();
            let phase = rng.next_open_closed();
            DetailWave { fx: dir.cos() / lambda, fz: dir.sin() / lambda, phase, slope }
        })
        .collect()
}

/// The detail map's uniforms: `count` 0 leaves it out (every shading but `ggx`, and
/// `detail_strength = 0`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DetailBlock {
    /// Sinusoids summed (both layers).
    pub count: f32,
    /// Padding.
    pub pad0: f32,
    /// Padding.
    pub pad1: f32,
    /// Padding.
    pub pad2: f32,
    /// Per sinusoid: (fx, fz) turns per metre, p0 its phase at the mesh's reference point in
    /// turns, in [−½, ½), and a = slope/|f| (its slope is a·(fx, fz)·cos 2πθ).
    pub waves: [[f32; 4]; 2 * DETAIL_WAVES],
}

impl DetailBlock {
    /// The block at time `t` (s) for a mesh whose reference point is world (x, z) `origin`,
    /// the wind blowing towards `wind_deg` (degrees from +x towards +z).
    pub fn new(
        waves: &[DetailWave],
        speed_m_s: f64,
        wind_deg: f64,
        t: f64,
        origin: [f64; 2],
    ) -> Self {
        let mut b = Self::zeroed();
        let (s, c) = wind_deg.to_radians().sin_cos();
        let layers = [(1.0, speed_m_s), (LAYER2_SCALE, -LAYER2_SPEED * speed_m_s)];
        let mut i = 0;
        for (scale, speed) in layers {
            for w in waves.iter().take(DETAIL_WAVES) {
                let (fx, fz) = (w.fx * scale, w.fz * scale);
                // θ = f·(x − v t) + φ at the reference point; the drift moves the map.
                let drift = [origin[0] - speed * c * t, origin[1] - speed * s * t];
                let turns = (fx * drift[0] + fz * drift[1] + w.phase).rem_euclid(1.0);
                let p0 = if turns >= 0.5 { turns - 1.0 } else { turns };
                let a = w.slope / fx.hypot(fz);
                b.waves[i] = [fx as f32, fz as f32, p0 as f32, a as f32];
                i += 1;
            }
        }
        b.count = i as f32;
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rms_slope_is_the_strength() {
        // Over a large square the mean of |s|² of the two layers is Σ a²/2.
        let waves = detail_waves(1.0, 0.1);
        let b = DetailBlock::new(&waves, 0.5, 30.0, 2.0, [0.0; 2]);
        let (mut sum, n) = (0.0, 400);
        for i in 0..n {
            for j in 0..n {
                let (x, z) = (i as f64 * 0.173, j as f64 * 0.131);
                let (mut sx, mut sz) = (0.0, 0.0);
                for w in &b.waves[..b.count as usize] {
                    let (fx, fz, p0, a) = (w[0] as f64, w[1] as f64, w[2] as f64, w[3] as f64);
                    let c = (std::f64::consts::TAU * (fx * x + fz * z + p0)).cos();
                    sx += a * fx * c;
                    sz += a * fz * c;
                }
                sum += sx * sx + sz * sz;
            }
        }
        let rms = (sum / (n * n) as f64).sqrt();
        assert!((rms - 0.1).abs() < 0.01, "rms slope {rms}");
    }

    #[test]
    fn the_layers_drift_against_each_other() {
        let waves = detail_waves(1.0, 0.1);
        let b0 = DetailBlock::new(&waves, 0.5, 0.0, 0.0, [0.0; 2]);
        let b1 = DetailBlock::new(&waves, 0.5, 0.0, 2.0, [1.0, 0.0]);
        // Layer 1 moved 1 m along +x in 2 s: at the reference point moved with it, the same
        // phases; layer 2 did not.
        for i in 0..DETAIL_WAVES {
            let d = (b0.waves[i][2] - b1.waves[i][2]).abs();
            assert!(d < 1e-5 || (1.0 - d).abs() < 1e-5, "wave {i}: {d}");
        }
        let moved = (DETAIL_WAVES..2 * DETAIL_WAVES)
            .filter(|&i| (b0.waves[i][2] - b1.waves[i][2]).abs() > 1e-3)
            .count();
        assert!(moved > DETAIL_WAVES / 2, "layer 2 moved with layer 1");
    }
}
