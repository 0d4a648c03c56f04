//! Waves technique `gerstner` (seed 002 §Gerstner waves; GPU Gems 1 ch. 1): a sum of
//! Gerstner waves, explicit (`[[gerstner.waves]]`) or drawn as the seed draws them.
//!
//! Each wave has amplitude A, wavenumber k = 2π/λ, unit direction D in (x, z), steepness
//! s ∈ [0, 1] and phase φ; ω = ω(k) is the scene's dispersion (deep, finite depth, looping).
//! With θ = k D·(x, z) − ω t + φ (docs/design.md):
//!
//! ```text
//! height h = Σ A sin θ            horizontal D(x) = Σ (s/k) D cos θ
//! ∂h/∂x   = Σ A k Dx cos θ        ∂Dx/∂x = −Σ s Dx² sin θ,  ∂Dz/∂z = −Σ s Dz² sin θ,
//!                                 ∂Dx/∂z = ∂Dz/∂x = −Σ s Dx Dz sin θ
//! ```
//!
//! so points gather towards the crests (sin θ = 1) and one wave of s = 1 has a cusp there
//! (J = 1 − sin θ = 0): GPU Gems' Q = s/(kA).
//!
//! **The seed's generator** (`[gerstner] count > 0` without explicit waves): each of `count`
//! slots holds one wave at a time, drawn from a counter-based hash of (seed, slot,
//! generation): a direction within ±`spread_deg` of the wind (the seed's ±3π/4), a ratio
//! r ∈ [0.5, 2) that scales both the median amplitude and the median wavelength (the seed's
//! `ratio = U·1.5 + 0.5`; its comment says 0.5–1.5 for the amplitude, the code gives 0.5–2),
//! a steepness U·0.1 − 0.05 + 0.95·`choppiness` clamped to [0, 1], and a phase. Each of the
//! n waves then takes 1/n of its steepness (GPU Gems 1 ch. 1's rule; the seed does not say),
//! so that Σ s ≤ 1: the drawn sea never loops over itself (J ≥ 0), and the height query's
//! inversion has one answer. Explicit waves keep their steepness as given. Where the seed
//! draws a lifetime per wave and swaps it at the end of its life, here each slot draws its
//! lifetime L ∈ [`min_lifetime_s`, `max_lifetime_s`] and an offset once, so that generation
//! g = ⌊(t + o)/L⌋ and the life fraction τ = frac((t + o)/L) are functions of t alone (frame
//! n is a pure function of (scene, n), with no state); the wave fades in and out with the
//! weight w = sin²(π τ) on A and s, which is 0 and flat where one generation hands over to
//! the next, so nothing jumps. Everything here is f64; θ's time part is reduced modulo 2π
//! by [`Dispersion::phase`].

use std::f64::consts::{PI, TAU};

use serde::{Deserialize, Serialize};

use super::query::{INVERSION_TOLERANCE_REL, Inversion, SurfaceSample, invert_displacement};
use crate::dispersion::Dispersion;
use crate::rng::mix64;

/// The most waves a sea may hold (explicit or drawn): the per-vertex sum's cost.
pub const MAX_GERSTNER_WAVES: usize = 64;

/// A `[[gerstner.waves]]` entry: one explicit wave (docs/design.md).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GerstnerWave {
    /// A, m.
    pub amplitude_m: f64,
    /// λ, m.
    pub wavelength_m: f64,
    /// Direction of travel, degrees from +x towards +z.
    #[serde(default)]
    pub direction_deg: f64,
    /// s ∈ [0, 1]: 0 a sine wave, 1 a cusp at the crest.
    #[serde(default)]
    pub steepness: f64,
    /// φ, radians.
    #[serde(default)]
    pub phase: f64,
}

/// The `[gerstner]` table: explicit waves, or the seed's generator.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Gerstner {
    /// Explicit waves; when there are any the generator is not used.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub waves: Vec<GerstnerWave>,
    /// Slots of the generator (waves at a time).
    pub count: u32,
    /// The median wavelength, m.
    pub median_wavelength_m: f64,
    /// The median amplitude, m (the ratio A/λ is the same for every drawn wave).
    pub median_amplitude_m: f64,
    /// Half the fan of directions around the wind, degrees.
    pub spread_deg: f64,
    /// The seed's `mWaveChoppy`: steepness about 0.95 times it.
    pub choppiness: f64,
    /// The shortest life of a drawn wave, s.
    pub min_lifetime_s: f64,
    /// The longest, s.
    pub max_lifetime_s: f64,
    /// The generator's seed.
    pub seed: u32,
}

impl Default for Gerstner {
    fn default() -> Self {
        Self {
            waves: Vec::new(),
            count: 16,
            median_wavelength_m: 24.0,
            median_amplitude_m: 0.3,
            spread_deg: 135.0,
            choppiness: 0.6,
            min_lifetime_s: 30.0,
            max_lifetime_s: 90.0,
            seed: 1,
        }
    }
}

/// One wave as the frame evaluates it: θ = kx·x + kz·z + theta0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActiveWave {
    /// k·Dx, 1/m.
    pub kx: f64,
    /// k·Dz, 1/m.
    pub kz: f64,
    /// k, 1/m.
    pub k: f64,
    /// A·w, m.
    pub amplitude_m: f64,
    /// s·w.
    pub steepness: f64,
    /// φ − ω t reduced to [0, 2π).
    pub theta0: f64,
}

/// A drawn wave's parameters (before its fade), for the statistics tests.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawnWave {
    /// The wave.
    pub amplitude_m: f64,
    /// λ, m.
    pub wavelength_m: f64,
    /// Radians from +x towards +z.
    pub direction: f64,
    /// s as the seed draws it (the sea sums s/n of it, n the slots).
    pub steepness: f64,
    /// φ.
    pub phase: f64,
    /// The slot's lifetime L, s.
    pub lifetime_s: f64,
    /// The fade weight w at the time asked.
    pub weight: f64,
}

/// A uniform in [0, 1) from (seed, slot, generation, stream): SplitMix64's mixer over the key.
fn uniform(seed: u32, slot: u32, generation: i64, stream: u32) -> f64 {
    let lane = (u64::from(slot) << 32) | u64::from(stream);
    let key = mix64(mix64(u64::from(seed) ^ 0x6765_7273_746e_6572) ^ lane) ^ (generation as u64);
    (mix64(key) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

impl Gerstner {
    /// Whether the sea uses the generator (no explicit waves).
    pub fn is_drawn(&self) -> bool {
        self.waves.is_empty()
    }

    /// Waves summed at any time: the explicit ones, or the generator's slots.
    pub fn wave_count(&self) -> usize {
        if self.is_drawn() { self.count as usize } else { self.waves.len() }
    }

    /// The most any point can be displaced at any time, (vertical, horizontal), m: Σ A and
    /// Σ s/k over the explicit waves; for the generator, `count` waves of twice the median
    /// amplitude, and the steepness of one wave of twice the median wavelength (the n waves
    /// share a steepness of at most 1).
    pub fn bounds(&self) -> (f64, f64) {
        if self.is_drawn() {
            let n = f64::from(self.count);
            let horizontal =
                if self.count > 0 { 2.0 * self.median_wavelength_m / TAU } else { 0.0 };
            (n * 2.0 * self.median_amplitude_m, horizontal)
        } else {
            self.waves.iter().fold((0.0, 0.0), |(v, h), w| {
                (v + w.amplitude_m, h + w.steepness * w.wavelength_m / TAU)
            })
        }
    }

    /// Slot `slot`'s wave at time `t` with the wind at `wind_deg`: the generation alive then,
    /// and its fade weight.
    pub fn drawn(&self, slot: u32, t: f64, wind_deg: f64) -> DrawnWave {
        let u = |generation: i64, stream: u32| uniform(self.seed, slot, generation, stream);
        // Fixed per slot: its lifetime and where in its life it is at t = 0.
        let lifetime = self.min_lifetime_s + u(-1, 0) * (self.max_lifetime_s - self.min_lifetime_s);
        let offset = u(-1, 1) * lifetime;
        let life = (t + offset) / lifetime;
        let generation = life.floor();
        let tau = life - generation;
        let g = generation as i64;
        let spread = self.spread_deg.to_radians();
        let ratio = u(g, 2) * 1.5 + 0.5;
        let weight = (PI * tau).sin().powi(2);
        DrawnWave {
            amplitude_m: ratio * self.median_amplitude_m,
            wavelength_m: ratio * self.median_wavelength_m,
            direction: wind_deg.to_radians() + (2.0 * u(g, 3) - 1.0) * spread,
            steepness: (u(g, 4) * 0.1 - 0.05 + 0.95 * self.choppiness).clamp(0.0, 1.0),
            phase: u(g, 5) * TAU,
            lifetime_s: lifetime,
            weight,
        }
    }

    /// The waves at time `t` (s) for the scene's dispersion and wind direction (degrees).
    pub fn at(&self, t: f64, dispersion: &Dispersion, wind_deg: f64) -> GerstnerSea {
        let active = |a: f64, lambda: f64, dir: f64, s: f64, phi: f64| {
            let k = TAU / lambda;
            ActiveWave {
                kx: k * dir.cos(),
                kz: k * dir.sin(),
                k,
                amplitude_m: a,
                steepness: s,
                theta0: (phi - dispersion.phase(k, t)).rem_euclid(TAU),
            }
        };
        let waves = if self.is_drawn() {
            // GPU Gems 1 ch. 1's rule: each of n waves takes 1/n of its steepness, so that
            // Σ s ≤ 1 and the surface never loops over itself (J ≥ 0).
            let share = 1.0 / f64::from(self.count.max(1));
            (0..self.count)
                .map(|i| {
                    let w = self.drawn(i, t, wind_deg);
                    active(
                        w.amplitude_m * w.weight,
                        w.wavelength_m,
                        w.direction,
                        w.steepness * w.weight * share,
                        w.phase,
                    )
                })
                .collect()
        } else {
            self.waves
                .iter()
                .map(|w| {
                    active(
                        w.amplitude_m,
                        w.wavelength_m,
                        w.direction_deg.to_radians(),
                        w.steepness,
                        w.phase,
                    )
                })
                .collect()
        };
        GerstnerSea { waves }
    }
}

/// The sum of Gerstner waves at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct GerstnerSea {
    /// The waves, faded.
    pub waves: Vec<ActiveWave>,
}

impl GerstnerSea {
    /// The fields at the undisplaced point (x, z) (see the module doc).
    pub fn sample(&self, x: f64, z: f64) -> SurfaceSample {
        let mut f = SurfaceSample::default();
        for w in &self.waves {
            let theta = w.kx * x + w.kz * z + w.theta0;
            let (sin, cos) = theta.sin_cos();
            let (dx, dz) = (w.kx / w.k, w.kz / w.k);
            let q = w.steepness / w.k;
            f.height += w.amplitude_m * sin;
            f.disp_x += q * dx * cos;
            f.disp_z += q * dz * cos;
            f.slope_x += w.amplitude_m * w.kx * cos;
            f.slope_z += w.amplitude_m * w.kz * cos;
            f.disp_x_dx -= w.steepness * dx * dx * sin;
            f.disp_z_dz -= w.steepness * dz * dz * sin;
            f.disp_x_dz -= w.steepness * dx * dz * sin;
        }
        f.jacobian = (1.0 + f.disp_x_dx) * (1.0 + f.disp_z_dz) - f.disp_x_dz * f.disp_x_dz;
        f
    }

    /// The parameter point whose displaced position is the world point (x, z) (Newton, as
    /// [`super::SurfaceQuery::invert`]), to [`INVERSION_TOLERANCE_REL`] of the longest
    /// wavelength.
    pub fn invert(&self, x: f64, z: f64) -> Inversion {
        let longest = self.waves.iter().map(|w| TAU / w.k).fold(1.0, f64::max);
        invert_displacement(|a, b| self.sample(a, b), x, z, INVERSION_TOLERANCE_REL * longest)
    }

    /// The height of the displaced surface above the world point (x, z).
    pub fn height_at(&self, x: f64, z: f64) -> f64 {
        self.invert(x, z).sample.height
    }

    /// The most any point of the surface can be displaced, (vertical, horizontal), m: Σ A and
    /// Σ s/k (the projected grid's slab, the spray's band).
    pub fn bounds(&self) -> (f64, f64) {
        self.waves.iter().fold((0.0, 0.0), |(v, h), w| (v + w.amplitude_m, h + w.steepness / w.k))
    }
}

/// The uniforms of waves technique `gerstner` (WGSL `GerstnerBlock`, shaders/shared/gerstner.wgsl):
/// per wave i, `waves[2i]` = (fx, fz, p0, A) and `waves[2i + 1]` = (qx, qz, A·kx, A·kz), with
/// (fx, fz) = k D/2π in turns per metre, p0 the phase θ at the mesh's reference point in turns
/// reduced to [−½, ½) (formed in f64, so a far eye keeps its digits), (qx, qz) = (s/k) D.
/// `count` 0: the waves are the maps' (technique `fft`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GerstnerBlock {
    /// Waves summed.
    pub count: f32,
    /// Padding.
    pub pad0: f32,
    /// Padding.
    pub pad1: f32,
    /// Padding.
    pub pad2: f32,
    /// Two vec4 per wave.
    pub waves: [[f32; 4]; 2 * MAX_GERSTNER_WAVES],
}

impl GerstnerBlock {
    /// The block of `sea` seen from a mesh whose reference point is world (x, z) `origin`.
    pub fn new(sea: &GerstnerSea, origin: [f64; 2]) -> Self {
        let mut b: Self = bytemuck::Zeroable::zeroed();
        for (i, w) in sea.waves.iter().take(MAX_GERSTNER_WAVES).enumerate() {
            let theta = w.kx * origin[0] + w.kz * origin[1] + w.theta0;
            let turns = (theta / TAU).rem_euclid(1.0);
            let p0 = if turns >= 0.5 { turns - 1.0 } else { turns };
            let q = w.steepness / w.k;
            b.waves[2 * i] =
                [(w.kx / TAU) as f32, (w.kz / TAU) as f32, p0 as f32, w.amplitude_m as f32];
            b.waves[2 * i + 1] = [
                (q * w.kx / w.k) as f32,
                (q * w.kz / w.k) as f32,
                (w.amplitude_m * w.kx) as f32,
                (w.amplitude_m * w.kz) as f32,
            ];
        }
        b.count = sea.waves.len().min(MAX_GERSTNER_WAVES) as f32;
        b
    }
}
