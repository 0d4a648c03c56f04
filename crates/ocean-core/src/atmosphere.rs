//! The sky of technique `atmosphere` (seed 002): single scattering by air molecules (Rayleigh)
//! and aerosols (Mie) in a spherical, ozone-free standard atmosphere, in f64 — the model the
//! shader will mirror, and the oracle of its tests.
//!
//! Constants: Bruneton & Neyret 2008 ("Precomputed Atmospheric Scattering", §2 and their
//! reference implementation), the usual ones of real-time atmospheres:
//! - planet radius R = 6 360 km, top of the atmosphere 6 420 km;
//! - Rayleigh scattering at sea level β_R = (5.8, 13.5, 33.1)·10⁻⁶ /m for (680, 550, 440) nm,
//!   scale height 8 km, no absorption (no ozone);
//! - Mie scattering β_M = 2.0·10⁻⁵ /m, extinction β_M/0.9, scale height 1.2 km, phase
//!   Cornette–Shanks with g = 0.8.
//!
//! L(x, v) = ∫₀^t_max T(x, p)·Σ_i β_i(h(p)) P_i(v·s)·T(p, sun)·E_sun dt, p = x + t v, where T is
//! the transmittance e^{−∫ β_ext} along a segment, zero where the segment to the sun meets the
//! planet. [`sky_radiance`] integrates with `steps` midpoints along the view and `sun_steps`
//! along each ray to the sun, both gathered towards the ray's start (t = len·u²); tests
//! compare it with a much finer integration.

mod lut;

use std::f64::consts::PI;

use glam::DVec3;

pub use lut::{LUT_HEIGHT, LUT_WIDTH, SkyLut, lut_coordinates, lut_direction};

/// Midpoints of the sun's transmittance to the eye ([`sun_at_eye`]): one ray per frame, so
/// finer than each scattering sample's [`SUN_STEPS`].
pub const EYE_SUN_STEPS: u32 = 256;

/// The sun's irradiance at the top of the atmosphere for a scene whose `[sun]` gives
/// `sea_irradiance` (colour × intensity): the scene's value is what a sun at the zenith puts on
/// the sea, so E_top = E_scene / T(sea, zenith) — the scene keeps its brightness at noon and the
/// atmosphere reddens and dims the sun towards the horizon.
pub fn top_irradiance(sea_irradiance: [f64; 3]) -> [f64; 3] {
    let t = sun_transmittance([0.0, EARTH_RADIUS_M, 0.0], [0.0, 1.0, 0.0], EYE_SUN_STEPS);
    std::array::from_fn(|c| sea_irradiance[c] / t[c])
}

/// The sun's irradiance reaching an eye `altitude_m` above the sea from unit direction `sun`,
/// `top` at the top of the atmosphere (0 when the planet hides it).
pub fn sun_at_eye(altitude_m: f64, sun: [f64; 3], top: [f64; 3]) -> [f64; 3] {
    let p = [0.0, EARTH_RADIUS_M + altitude_m.max(0.0), 0.0];
    let t = sun_transmittance(p, sun, EYE_SUN_STEPS);
    std::array::from_fn(|c| top[c] * t[c])
}

/// The planet's radius, m.
pub const EARTH_RADIUS_M: f64 = 6_360_000.0;
/// The top of the atmosphere, m from the planet's centre.
pub const TOP_RADIUS_M: f64 = 6_420_000.0;
/// Rayleigh scattering at sea level, /m (680, 550, 440 nm).
pub const RAYLEIGH_BETA: [f64; 3] = [5.8e-6, 13.5e-6, 33.1e-6];
/// Rayleigh scale height, m.
pub const RAYLEIGH_HEIGHT_M: f64 = 8_000.0;
/// Mie scattering at sea level, /m.
pub const MIE_BETA: f64 = 2.0e-5;
/// Mie extinction over scattering (aerosols absorb a tenth).
pub const MIE_EXTINCTION_RATIO: f64 = 1.0 / 0.9;
/// Mie scale height, m.
pub const MIE_HEIGHT_M: f64 = 1_200.0;
/// Mie asymmetry g.
pub const MIE_G: f64 = 0.8;

/// Midpoints along the view that the shader will take (measured against a fine integration in
/// `tests/atmosphere.rs`).
pub const SKY_STEPS: u32 = 32;
/// Midpoints along each ray to the sun.
pub const SUN_STEPS: u32 = 16;

/// Rayleigh phase function, 3/(16π)(1 + μ²).
pub fn rayleigh_phase(mu: f64) -> f64 {
    3.0 / (16.0 * PI) * (1.0 + mu * mu)
}

/// Cornette–Shanks phase function (normalised to 1 over the sphere).
pub fn mie_phase(mu: f64, g: f64) -> f64 {
    let g2 = g * g;
    let k = 3.0 / (8.0 * PI) * (1.0 - g2) / (2.0 + g2);
    k * (1.0 + mu * mu) / (1.0 + g2 - 2.0 * g * mu).max(1e-12).powf(1.5)
}

/// Distance along unit `d` from `p` to the sphere of radius `r` about the origin (the far
/// intersection), or `None` if the ray misses it.
fn sphere_exit(p: [f64; 3], d: [f64; 3], r: f64) -> Option<f64> {
    let b = DVec3::from(p).dot(DVec3::from(d));
    let c = DVec3::from(p).length_squared() - r * r;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let t = -b + disc.sqrt();
    (t >= 0.0).then_some(t)
}

/// Distance along `d` from `p` to the planet, if the ray meets it ahead.
fn planet_hit(p: [f64; 3], d: [f64; 3]) -> Option<f64> {
    let b = DVec3::from(p).dot(DVec3::from(d));
    let c = DVec3::from(p).length_squared() - EARTH_RADIUS_M * EARTH_RADIUS_M;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let t = -b - disc.sqrt();
    (t > 0.0).then_some(t)
}

/// Extinction per metre at height `h` (m), per channel.
fn extinction(h: f64) -> [f64; 3] {
    let r = (-h / RAYLEIGH_HEIGHT_M).exp();
    let m = (-h / MIE_HEIGHT_M).exp() * MIE_BETA * MIE_EXTINCTION_RATIO;
    [RAYLEIGH_BETA[0] * r + m, RAYLEIGH_BETA[1] * r + m, RAYLEIGH_BETA[2] * r + m]
}

/// Height above the sea, m (0 at and below it).
fn height(p: [f64; 3]) -> f64 {
    (DVec3::from(p).length_squared().sqrt() - EARTH_RADIUS_M).max(0.0)
}

/// `steps` midpoints (t, dt) over [0, len], gathered towards t = 0 as t = len·u² (dt = 2 len u
/// du): the air is densest near the start of a ray from the ground, and a long horizontal ray
/// spends most of its length where there is little air.
fn gathered(len: f64, steps: u32) -> impl Iterator<Item = (f64, f64)> {
    let n = f64::from(steps.max(1));
    (0..steps.max(1)).map(move |i| {
        let u = (f64::from(i) + 0.5) / n;
        (len * u * u, 2.0 * len * u / n)
    })
}

/// The transmittance from `p` towards the sun along `s` (0 if the planet is in the way), by
/// `steps` midpoints.
pub fn sun_transmittance(p: [f64; 3], s: [f64; 3], steps: u32) -> [f64; 3] {
    if planet_hit(p, s).is_some() {
        return [0.0; 3];
    }
    let Some(len) = sphere_exit(p, s, TOP_RADIUS_M) else { return [1.0; 3] };
    let mut depth = [0.0; 3];
    for (t, dt) in gathered(len, steps) {
        let e = extinction(height([p[0] + s[0] * t, p[1] + s[1] * t, p[2] + s[2] * t]));
        for c in 0..3 {
            depth[c] += e[c] * dt;
        }
    }
    depth.map(|d| (-d).exp())
}

/// The radiance of the sky seen from `altitude_m` above the sea along unit `view` (y up),
/// with the sun along unit `sun` giving irradiance `sun_irradiance` (per channel) at the top of
/// the atmosphere: single scattering by `steps` midpoints along the view, each lit through
/// `sun_steps` midpoints. Below the horizon the view ends on the planet (the sea), whose own
/// light is not included. Finite for every direction.
pub fn sky_radiance(
    altitude_m: f64,
    view: [f64; 3],
    sun: [f64; 3],
    sun_irradiance: [f64; 3],
    steps: u32,
    sun_steps: u32,
) -> [f64; 3] {
    let s = sky_scattering(altitude_m, view, sun, sun_irradiance, steps, sun_steps);
    let mu = DVec3::from(view).dot(DVec3::from(sun));
    let (pr, pm) = (rayleigh_phase(mu), mie_phase(mu, MIE_G));
    std::array::from_fn(|c| s.rayleigh[c] * pr + s.mie[c] * pm)
}

/// The two scattering integrals of [`sky_radiance`] without their phase functions:
/// L = rayleigh·P_R(v·s) + mie·P_M(v·s). The phase functions carry the sharp forward peak of the
/// aerosols; the integrals are smooth over the sky, which is what the sky-view table stores.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scattering {
    /// ∫ T β_R(h) T_sun E dt per channel.
    pub rayleigh: [f64; 3],
    /// ∫ T β_M(h) T_sun E dt per channel.
    pub mie: [f64; 3],
}

/// [`Scattering`] along `view` (arguments as [`sky_radiance`]).
pub fn sky_scattering(
    altitude_m: f64,
    view: [f64; 3],
    sun: [f64; 3],
    sun_irradiance: [f64; 3],
    steps: u32,
    sun_steps: u32,
) -> Scattering {
    let mut out = Scattering { rayleigh: [0.0; 3], mie: [0.0; 3] };
    // An eye at or below the sea looking down sees no air.
    if altitude_m <= 0.0 && view[1] < 0.0 {
        return out;
    }
    let x = [0.0, EARTH_RADIUS_M + altitude_m.max(0.0), 0.0];
    let end = planet_hit(x, view).or_else(|| sphere_exit(x, view, TOP_RADIUS_M)).unwrap_or(0.0);
    let mut depth = [0.0; 3];
    for (t, dt) in gathered(end, steps) {
        let p = [x[0] + view[0] * t, x[1] + view[1] * t, x[2] + view[2] * t];
        let h = height(p);
        let e = extinction(h);
        // Transmittance from the eye to the sample's midpoint: half this step's depth added.
        let to_sample: [f64; 3] = std::array::from_fn(|c| (-(depth[c] + 0.5 * e[c] * dt)).exp());
        let sun_t = sun_transmittance(p, sun, sun_steps);
        let (r, m) = ((-h / RAYLEIGH_HEIGHT_M).exp(), (-h / MIE_HEIGHT_M).exp() * MIE_BETA);
        for c in 0..3 {
            let lit = to_sample[c] * sun_t[c] * sun_irradiance[c] * dt;
            out.rayleigh[c] += lit * RAYLEIGH_BETA[c] * r;
            out.mie[c] += lit * m;
            depth[c] += e[c] * dt;
        }
    }
    out
}
