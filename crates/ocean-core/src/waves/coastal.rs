//! Waves technique `coastal` (seed 004, "Waves – Getting everything in motion"): dominant
//! radial waves running towards a shore centre, shaped as a power of the sine, plus four small
//! correction waves in other directions.
//!
//! # The seed's wave
//!
//! With r the distance from the centre c and φ = −Φ(r) − ω t the phase ("Phase = distance ·
//! −rSpaceFreq + Time · 2 · −TimeFreq"), s = sin φ, and m = `back_factor` where s·cos φ < 0
//! (the seed's `temp2 = 2`), else 1, the height is
//!
//! ```text
//! h_radial = clamp(s^p · A · m − A · (m − 1), 0, A)        p = `power` (the seed's 7)
//! ```
//!
//! so crests are narrow and troughs flat at 0 (the seed clamps the sine's negative powers
//! away), and on the quarter-period shoreward of each crest (s·cos φ < 0 there as φ grows
//! towards the shore) the profile is 2 s^p − 1: the front is steepened, the back keeps the
//! gentler s^p. The seed's correction `Σ A_j/2 · sin θ_j` of four waves adds the rest; here
//! each correction wave's `amplitude_m` is its own A_j/2, and θ_j = k_j D_j·(x, z) − ω_j t.
//!
//! # Depth (issue 15: real dispersion, shoaling, breaking)
//!
//! The seed's Φ = k r has one wavenumber. Here the wave keeps its angular frequency ω
//! (ω² = g k₀ tanh(k₀ h_open) for the deep-water wavelength `wavelength_m` and the scene's
//! dispersion) and its wavenumber follows the depth: Φ(r) = ∫₀^r k(h̄(s)) ds with k(h) the root
//! of ω² = g k tanh(k h) ([`crate::shoaling::wavenumber`]) and h̄(s) the floor's depth averaged
//! over the circle of radius s about the centre (64 azimuths): exact for a round island
//! centred on c, the mean for any other floor. Crests so travel at the phase speed ω/k of the
//! depth they are over, slower and closer together in shallow water. The height grows by the
//! shoaling coefficient K_s(h̄) (energy flux conserved) and is capped by the breaker index:
//! A_local = min(K_s(h̄(r))·A, γ·h(x, z)) with γ = 0.78 and h the depth under the point itself,
//! so the wave dies where the floor reaches the sea plane (water runs up the sand only as the
//! swash's film: "The shore zones" below). Each correction wave is faded by w_j = clamp(2h/λ_j, 0, 1), Crest's rule: a wave
//! feels the floor below half its wavelength. The gradients of K_s·A and of the two caps
//! (γ h and w_j) are left out of the slopes: they change over the shore's metres, the waves over their
//! wavelength, and leaving them out keeps the slope a pure function of the tables.
//!
//! # The per-vertex form
//!
//! The shaders evaluate Φ and K_s·A from [`COASTAL_SEGMENTS`] radial segments of width Δ:
//! segment i covers [iΔ, (i+1)Δ) with Φ and K_s·A quadratics in u = r − iΔ through their
//! values at both ends and the middle; the last segment continues Φ linearly with the
//! outermost wavenumber, and K_s·A as a constant, to any distance. Φ's constant term is stored modulo 1 turn (only sin φ is
//! used), so the f32 numbers stay small. A vertex of the screen grids (or the clipmap) that
//! is spaced too widely for a wave fades it as the Gerstner clipmap does, by
//! clamp(2 − 8·s·|f|, 0, 1) with s·|f| the vertex spacing along and across the view times
//! the wave's cycles per metre (1 down to 8 vertices per wavelength, 0 at 4): a correction
//! wave's amplitude, and the radial wave towards its mean ([`profile_moments`]) at its RMS
//! wavenumber, because the power-7 crest is much narrower than its wavelength. Without
//! this, crests far away and seen at grazing angles fall between rows and zigzag. The
//! height query and the fragments' slopes take the waves unfaded. [`CoastalSea`] is the f64 reference: Φ, h̄ and K_s
//! on [`NODES_PER_SEGMENT`] nodes per segment, linear between them; the height query of a
//! floating object asks it.
//!
//! # The shore zones (seed 004, "Combining layers")
//!
//! - **Run-out.** After a wave breaks, its water slides up the sand and back. The run-up
//!   height is Hunt's (1959) R = ξ·A, with Iribarren's number ξ = tan β / √(A/L₀), A the deep-water wave
//!   height (`amplitude_m`), L₀ its wavelength and tan β the beach's slope where the mean
//!   depth h̄ crosses the sea plane (exact for the round island; no crossing: no run-up).
//!   ξ is capped at [`MAX_IRIBARREN`], beyond which waves surge rather than break and
//!   Hunt's relation stops growing (Battjes 1974). The swash level is L = R·((1 + sin φ_w)/2)²
//!   with φ_w the radial wave's phase where h̄ crosses 0 (the waterline's, exact for the
//!   round island): the whole run-out rises and falls together, and L is one number per
//!   frame, formed in f64 (`CoastalBlock::swash`), so the drawn film and the height query
//!   agree exactly. The
//!   surface is max(h, min(L, y_floor + [`SWASH_FILM_M`])): where the level is above the
//!   sand, a film of water lies [`SWASH_FILM_M`] over it; where it is below, the surface
//!   is under the sand and the sand hides it. So water stands over dry land only up to R,
//!   and then only as the film. The film's slope is left out, as the caps' are: its normal is the waves'.
//! - **Wet sand.** Sand below R is wet: its albedo is × [`WET_SAND_DARKENING`] (Lekner &
//!   Dorf 1988 measure wet sand at about half its dry reflectance), graded over the band's
//!   top quarter (ocean-core terrain's mesh colours, so both back ends draw the same).
//! - **Shore foam.** A turbulence (the foam stage's texture and colour turn it into
//!   coverage, as for the foam techniques): in the surf zone, where the shoaled height K_s·A
//!   is above the breaker cap γh, β = 1 − γh/(K_s·A), times 0.2 + 0.8·h/a (h/a the radial
//!   wave's normalised height), so foam starts at the breaking line, rides the crests, leaves
//!   a thinner residue between them and thickens towards the waterline; and along the swash's front, 1 − (L − y_floor)/
//!   [`SWASH_EDGE_M`] where the level is above the sand by less than that. Higher waves
//!   break further out and more strongly, so the foam's coverage grows with the waves'
//!   steepness.
//!
//! The coastal sea does not loop (`loop_period_s` does not quantise its ω): its phases are
//! ω·t reduced modulo one turn in f64, so a huge t is as exact as a small one.

use std::f64::consts::TAU;
use std::sync::{Arc, Mutex};

use serde::{Deserialize, Serialize};

use crate::shoaling::{BREAKER_INDEX, shoaling_coefficient, wavenumber};

/// Radial segments of the per-vertex table (two vec4 each in [`CoastalBlock`]).
pub const COASTAL_SEGMENTS: usize = 64;
/// The most correction waves (the seed's one float4 of them).
pub const MAX_CORRECTION_WAVES: usize = 4;
/// f64 nodes per segment of [`CoastalSea`]'s profile (even: the segment's middle is a node).
pub const NODES_PER_SEGMENT: usize = 32;
/// Directions over which the floor's depth is averaged at each radius.
const AZIMUTHS: usize = 64;
/// The water film's thickness over the sand in the run-out zone, m.
pub const SWASH_FILM_M: f64 = 0.03;
/// The height band (m) behind the swash's front that carries its foam line.
pub const SWASH_EDGE_M: f64 = 0.08;
/// The largest Iribarren number Hunt's run-up R = ξ·A is taken at.
pub const MAX_IRIBARREN: f64 = 2.5;
pub use crate::sand::WET_SAND_DARKENING;

/// A `[[coastal.corrections]]` entry: one of the seed's four correction waves.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CorrectionWave {
    /// Direction of travel, degrees from +x towards +z.
    pub direction_deg: f64,
    /// λ, m.
    pub wavelength_m: f64,
    /// Amplitude, m (the seed's `Amplitudes/2`).
    pub amplitude_m: f64,
}

/// The `[coastal]` table (waves technique `coastal`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Coastal {
    /// The point the waves run to, world (x, z), m. Absent: the terrain's centre, or the
    /// origin without a terrain.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub center: Option<[f64; 2]>,
    /// A: the crest's height above the trough in deep water, m (the seed's `rAmplitudes`).
    pub amplitude_m: f64,
    /// The radial waves' deep-water wavelength, m.
    pub wavelength_m: f64,
    /// The sine's power p (the seed's 7).
    pub power: u32,
    /// The seed's `temp2` where s·cos φ < 0 (2): how much the front is steepened.
    pub back_factor: f64,
    /// The correction waves (at most [`MAX_CORRECTION_WAVES`]).
    pub corrections: Vec<CorrectionWave>,
    /// Shading `coastal`: the Fresnel term, `schlick` (the seed's cheap approximation, the
    /// default) or `exact` (eq. 2 of seed 000, from the Fresnel texture).
    pub fresnel: crate::ggx::GgxFresnel,
    /// Shading `coastal`: the Blinn–Phong exponent of the sun's highlight (the seed's 30).
    pub shininess: u32,
    /// Shading `coastal`: the seed's `xDullFactor`, the dull colour's share at the crests.
    pub dull_factor: f64,
    /// Shading `coastal`: the dull colour (the seed's (0.1, 0.25, 0.5)), an albedo lit by
    /// the sky and the sun.
    pub dull_color: [f64; 3],
    /// Shading `coastal`: the reflection and refraction maps' shift per unit of the normal's
    /// horizontal part, in screen units (the seed's `newNormal·0.2` of a ×10 normal).
    pub distortion: f64,
}

impl Default for Coastal {
    fn default() -> Self {
        let wave = |direction_deg: f64, wavelength_m: f64, amplitude_m: f64| CorrectionWave {
            direction_deg,
            wavelength_m,
            amplitude_m,
        };
        Self {
            center: None,
            amplitude_m: 0.8,
            wavelength_m: 28.0,
            power: 7,
            back_factor: 2.0,
            corrections: vec![
                wave(17.0, 7.3, 0.05),
                wave(118.0, 5.1, 0.035),
                wave(203.0, 3.7, 0.025),
                wave(291.0, 2.9, 0.02),
            ],
            fresnel: crate::ggx::GgxFresnel::Schlick,
            shininess: 30,
            dull_factor: 0.2,
            dull_color: [0.1, 0.25, 0.5],
            distortion: 0.02,
        }
    }
}

/// One correction wave as the frame evaluates it: θ (turns) = fx·x + fz·z + p0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActiveCorrection {
    /// kx / 2π, turns per m.
    pub fx: f64,
    /// kz / 2π, turns per m.
    pub fz: f64,
    /// The phase at the world origin at the frame's time, turns in [0, 1).
    pub p0: f64,
    /// Amplitude, m.
    pub amplitude_m: f64,
    /// 2/λ, 1/m: the depth weight clamp(2h/λ, 0, 1)'s factor.
    pub depth_factor: f64,
    /// ω, rad/s.
    pub omega: f64,
    /// The phase at the world origin at t = 0, turns.
    pub phase0: f64,
}

/// The coastal sea at one time: the f64 reference of the per-vertex waves, and the height
/// query of a floating object.
#[derive(Clone, Debug)]
pub struct CoastalSea {
    /// The shore centre, world (x, z).
    pub center: [f64; 2],
    /// A, m.
    pub amplitude_m: f64,
    /// p.
    pub power: u32,
    /// The seed's `temp2`.
    pub back_factor: f64,
    /// ω, rad/s.
    pub omega: f64,
    /// ω t reduced modulo one turn, turns.
    pub time_turns: f64,
    /// Δ, m.
    pub segment_m: f64,
    /// The correction waves.
    pub corrections: Vec<ActiveCorrection>,
    /// R, Hunt's run-up height above the sea plane, m (0 without a beach).
    pub run_up_m: f64,
    /// Φ where the mean depth crosses 0 (the swash's phase), turns.
    swash_phi: f64,
    /// Φ (turns), h̄ (m), K_s at r = j·Δ/[`NODES_PER_SEGMENT`].
    nodes: Arc<Vec<[f64; 3]>>,
    /// The outermost node's wavenumber over 2π, turns per m.
    far_turns_per_m: f64,
    floor: Floor,
}

/// The floor under the sea: the terrain, or the open sea's depth without one.
#[derive(Clone, Debug)]
enum Floor {
    Terrain(Box<crate::terrain::Terrain>),
    Open(f64),
}

impl Floor {
    fn depth(&self, x: f64, z: f64) -> f64 {
        match self {
            Floor::Terrain(t) => -t.height(x, z),
            Floor::Open(d) => *d,
        }
    }

    /// The deepest the floor is anywhere, m.
    fn deepest(&self) -> f64 {
        match self {
            Floor::Terrain(t) => -t.y_range().0,
            Floor::Open(d) => *d,
        }
    }
}

impl CoastalSea {
    /// The sea of `coastal` at time `t` over `terrain` (or an open sea `open_depth_m` deep),
    /// under `gravity`, with the radial waves' ω from the scene's `dispersion`.
    pub fn new(
        coastal: &Coastal,
        terrain: Option<&crate::terrain::Terrain>,
        open_depth_m: f64,
        dispersion: &crate::dispersion::Dispersion,
        t: f64,
    ) -> Self {
        let g = dispersion.gravity;
        let center = coastal.center.or(terrain.map(|t| t.center)).unwrap_or([0.0, 0.0]);
        let floor = match terrain {
            Some(t) => Floor::Terrain(Box::new(t.clone())),
            None => Floor::Open(open_depth_m),
        };
        let k0 = TAU / coastal.wavelength_m;
        let omega = dispersion.omega_continuous(k0);
        let turns = |w: f64| phase_turns(w, t);
        // The table reaches the terrain's farthest corner; beyond it the floor is its edge's.
        let reach = terrain.map_or(coastal.wavelength_m, |t| {
            let dx = (t.center[0] - center[0]).abs() + 0.5 * t.extent_m;
            let dz = (t.center[1] - center[1]).abs() + 0.5 * t.extent_m;
            dx.hypot(dz)
        });
        let segment_m = reach / (COASTAL_SEGMENTS - 1) as f64;
        let step = segment_m / NODES_PER_SEGMENT as f64;
        let key = ProfileKey {
            omega,
            gravity: g,
            center,
            reach,
            open_depth_m,
            terrain: terrain
                .map(|t| (crate::terrain::Terrain { relief: None, ..t.clone() }, t.relief.clone())),
        };
        let nodes = cached_profile(key, || profile_nodes(&floor, center, step, omega, g));
        let k_prev = nodes.last().map_or(0.0, |n| wavenumber(omega, g, n[1]));
        let corrections = coastal
            .corrections
            .iter()
            .take(MAX_CORRECTION_WAVES)
            .map(|w| {
                let omega = dispersion.omega_continuous(TAU / w.wavelength_m);
                let (s, c) = w.direction_deg.to_radians().sin_cos();
                ActiveCorrection {
                    fx: c / w.wavelength_m,
                    fz: s / w.wavelength_m,
                    p0: (-turns(omega)).rem_euclid(1.0),
                    amplitude_m: w.amplitude_m,
                    depth_factor: 2.0 / w.wavelength_m,
                    omega,
                    phase0: 0.0,
                }
            })
            .collect();
        let (run_up_m, swash_phi) = run_up(&nodes, step, coastal.amplitude_m, coastal.wavelength_m);
        Self {
            center,
            amplitude_m: coastal.amplitude_m,
            power: coastal.power,
            back_factor: coastal.back_factor,
            omega,
            time_turns: turns(omega),
            segment_m,
            corrections,
            run_up_m,
            swash_phi,
            nodes,
            far_turns_per_m: k_prev / TAU,
            floor,
        }
    }

    /// The same sea at time `t` (the profile, which does not depend on time, is kept: a
    /// floating object's settle run asks for many times).
    pub fn at_time(&self, t: f64) -> Self {
        let turns = |w: f64| phase_turns(w, t);
        let mut sea = self.clone();
        sea.time_turns = turns(self.omega);
        for w in &mut sea.corrections {
            w.p0 = (w.phase0 - turns(w.omega)).rem_euclid(1.0);
        }
        sea
    }

    /// The profile at distance r from the centre: (Φ turns, dΦ/dr turns per m, h̄, K_s).
    pub fn profile(&self, r: f64) -> [f64; 4] {
        let step = self.segment_m / NODES_PER_SEGMENT as f64;
        let last = self.nodes.len() - 1;
        let x = r / step;
        if x.is_nan() || x >= last as f64 {
            let [phi, h, ks] = self.nodes[last];
            let dphi = self.far_turns_per_m;
            return [phi + dphi * (r - last as f64 * step), dphi, h, ks];
        }
        let j = x.floor() as usize;
        let f = x - j as f64;
        let (a, b) = (self.nodes[j], self.nodes[j + 1]);
        let lerp = |i: usize| a[i] + (b[i] - a[i]) * f;
        [lerp(0), (b[0] - a[0]) / step, lerp(1), lerp(2)]
    }

    /// The floor's depth under world (x, z), m (negative on land).
    pub fn depth(&self, x: f64, z: f64) -> f64 {
        self.floor.depth(x, z)
    }

    /// The radial wave alone at world (x, z): (height, ∂h/∂r, φ in turns), with the local
    /// depth cap.
    pub fn radial(&self, x: f64, z: f64) -> [f64; 3] {
        let r = (x - self.center[0]).hypot(z - self.center[1]);
        let [phi, dphi, _, ks] = self.profile(r);
        let cap = BREAKER_INDEX * self.depth(x, z).max(0.0);
        let amp = (ks * self.amplitude_m).min(cap);
        self.shape(phi, dphi, amp)
    }

    /// The radial wave of amplitude `amp` at profile (Φ, dΦ/dr): (height, ∂h/∂r, φ turns).
    fn shape(&self, phi: f64, dphi: f64, amp: f64) -> [f64; 3] {
        let turns = -(phi + self.time_turns);
        let (s, c) = (TAU * turns).sin_cos();
        let m = if s * c < 0.0 { self.back_factor } else { 1.0 };
        let p = self.power as i32;
        let b = s.powi(p) * amp * m - amp * (m - 1.0);
        let height = b.clamp(0.0, amp);
        let slope = if b > 0.0 && b < amp {
            m * f64::from(self.power) * s.powi(p - 1) * c * (-TAU * dphi) * amp
        } else {
            0.0
        };
        [height, slope, turns.rem_euclid(1.0)]
    }

    /// The surface at world (x, z): (height, ∂h/∂x, ∂h/∂z). The coastal waves move the
    /// surface vertically only, so the world point is its own undisplaced point.
    pub fn sample(&self, x: f64, z: f64) -> [f64; 3] {
        let [mut height, dr, _] = self.radial(x, z);
        let (dx, dz) = (x - self.center[0], z - self.center[1]);
        let r = dx.hypot(dz);
        let (mut sx, mut sz) = if r > 0.0 { (dr * dx / r, dr * dz / r) } else { (0.0, 0.0) };
        let depth = self.depth(x, z).max(0.0);
        for w in &self.corrections {
            let theta = TAU * (w.fx * x + w.fz * z + w.p0);
            let a = w.amplitude_m * (depth * w.depth_factor).clamp(0.0, 1.0);
            height += a * theta.sin();
            sx += a * TAU * w.fx * theta.cos();
            sz += a * TAU * w.fz * theta.cos();
        }
        let film = self.swash_level().min(SWASH_FILM_M - self.depth(x, z));
        [height.max(film), sx, sz]
    }

    /// The swash's level L = R·((1 + sin φ_w)/2)², m above the sea plane (module docs).
    pub fn swash_level(&self) -> f64 {
        let u = 0.5 * (1.0 + (-TAU * (self.swash_phi + self.time_turns)).sin());
        self.run_up_m * (u * u)
    }

    /// The shore foam's turbulence at world (x, z), in [0, 1] (module docs): the surf zone's
    /// breaking, and the swash's front.
    pub fn shore_foam(&self, x: f64, z: f64) -> f64 {
        let r = (x - self.center[0]).hypot(z - self.center[1]);
        let [phi, dphi, _, ks] = self.profile(r);
        let depth = self.depth(x, z);
        let cap = BREAKER_INDEX * depth.max(0.0);
        let shoaled = ks * self.amplitude_m;
        let amp = shoaled.min(cap);
        let [height, _, _] = self.shape(phi, dphi, amp);
        let breaking = if shoaled > 0.0 { (1.0 - cap / shoaled).clamp(0.0, 1.0) } else { 0.0 };
        let crest = if amp > 0.0 { height / amp } else { 0.0 };
        let above = self.swash_level() + depth;
        let edge = if depth < SWASH_FILM_M && above > 0.0 {
            (1.0 - above / SWASH_EDGE_M).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (breaking * (0.2 + 0.8 * crest)).max(edge)
    }

    /// [`Self::sample`] as the height query's sample: no horizontal displacement, J = 1.
    pub fn surface_sample(&self, x: f64, z: f64) -> super::SurfaceSample {
        let [height, slope_x, slope_z] = self.sample(x, z);
        super::SurfaceSample {
            height,
            disp_x: 0.0,
            disp_z: 0.0,
            slope_x,
            slope_z,
            disp_x_dx: 0.0,
            disp_z_dz: 0.0,
            disp_x_dz: 0.0,
            jacobian: 1.0,
        }
    }

    /// The height of the surface above world (x, z), m.
    pub fn height_at(&self, x: f64, z: f64) -> f64 {
        self.sample(x, z)[0]
    }

    /// The unit normal of the surface above world (x, z).
    pub fn normal_at(&self, x: f64, z: f64) -> [f64; 3] {
        let [_, sx, sz] = self.sample(x, z);
        let n = (1.0 + sx * sx + sz * sz).sqrt();
        [-sx / n, 1.0 / n, -sz / n]
    }

    /// The per-vertex block for a mesh whose reference point is world (x, z) `origin`.
    pub fn block(&self, origin: [f64; 2]) -> CoastalBlock {
        let mut b: CoastalBlock = bytemuck::Zeroable::zeroed();
        let seg = self.segment_m;
        b.center = [
            (self.center[0] - origin[0]) as f32,
            (self.center[1] - origin[1]) as f32,
            (1.0 / seg) as f32,
            seg as f32,
        ];
        b.shape = [
            crate::switch::SWITCH_ON,
            self.amplitude_m as f32,
            self.power as f32,
            self.back_factor as f32,
        ];
        b.time = [self.time_turns as f32, BREAKER_INDEX as f32, self.corrections.len() as f32, 0.0];
        let (mean, rms_k) = profile_moments(self.power, self.back_factor);
        b.swash = [self.swash_level() as f32, self.run_up_m as f32, mean as f32, rms_k as f32];
        let half = NODES_PER_SEGMENT / 2;
        let a = self.amplitude_m;
        for i in 0..COASTAL_SEGMENTS {
            let j = i * NODES_PER_SEGMENT;
            let [p0, _, k0] = self.nodes[j];
            // The quadratic through the values at u = 0, Δ/2 and Δ: (first, slope, curvature).
            let fit = |v0: f64, vm: f64, v1: f64| {
                ((4.0 * vm - 3.0 * v0 - v1) / seg, 2.0 * (v1 - 2.0 * vm + v0) / (seg * seg))
            };
            let ((c1, c2), (a1, a2)) = if i + 1 < COASTAL_SEGMENTS {
                let ([pm, _, km], [p1, _, k1]) =
                    (self.nodes[j + half], self.nodes[j + NODES_PER_SEGMENT]);
                (fit(p0, pm, p1), fit(k0 * a, km * a, k1 * a))
            } else {
                ((self.far_turns_per_m, 0.0), (0.0, 0.0))
            };
            b.table[2 * i] = [p0.rem_euclid(1.0) as f32, c1 as f32, c2 as f32, 0.0];
            b.table[2 * i + 1] = [(k0 * a) as f32, a1 as f32, a2 as f32, 0.0];
        }
        for (i, w) in self.corrections.iter().enumerate() {
            let p = (w.fx * origin[0] + w.fz * origin[1] + w.p0).rem_euclid(1.0);
            let p = if p >= 0.5 { p - 1.0 } else { p };
            b.waves[i] = [w.fx as f32, w.fz as f32, p as f32, w.amplitude_m as f32];
            b.damping[i] = w.depth_factor as f32;
        }
        b
    }

    /// The most the surface rises above the sea plane anywhere, m: the largest K_s·A of the
    /// profile, capped by γ times the deepest floor (the local cap), plus every correction
    /// wave's amplitude; or the run-up R where that is higher.
    pub fn bound_m(&self) -> f64 {
        let ks = self.nodes.iter().map(|n| n[2]).fold(1.0, f64::max);
        let cap = BREAKER_INDEX * self.floor.deepest().max(0.0);
        let waves = (ks * self.amplitude_m).min(cap)
            + self.corrections.iter().map(|w| w.amplitude_m).sum::<f64>();
        waves.max(self.run_up_m)
    }
}

/// ω t reduced modulo one turn, in [0, 1). Where ω t/2π overflows (|t| near f64's largest),
/// it is 0: every f64 of magnitude 2⁵³ or more is a whole number, so the phase of any time
/// that large is a whole number of turns (NaN before: `inf.rem_euclid(1)`).
fn phase_turns(omega: f64, t: f64) -> f64 {
    let x = omega * t / TAU;
    if x.is_finite() { x.rem_euclid(1.0) } else { 0.0 }
}

/// The radial profile f(φ) = clamp(sᵖ·m − (m − 1), 0, 1) of unit amplitude (m = `back` where
/// s·cos φ < 0): (its mean, √(mean f′² / var f)), f′ = df/dφ, φ in radians. The second is the
/// profile's RMS wavenumber over k (Σ n²|c_n|² / Σ|c_n|² over its harmonics): a vertex that
/// cannot hold the wave fades it towards its mean as if it were one sine of that
/// wavenumber, which damps the filtered profile's variance at the right rate for small
/// spacings (module docs, "The per-vertex form"). Kept per (p, m): every frame's uniform
/// block asks for them (8,192 samples each time).
pub fn profile_moments(power: u32, back: f64) -> (f64, f64) {
    static KEPT: crate::kept::Kept<(u32, u64), (f64, f64)> = crate::kept::Kept::new();
    KEPT.get((power, back.to_bits()), || moments(power, back))
}

/// [`profile_moments`], computed.
fn moments(power: u32, back: f64) -> (f64, f64) {
    const N: usize = 8192;
    let f = |i: usize| {
        let (s, c) = (TAU * i as f64 / N as f64).sin_cos();
        let m = if s * c < 0.0 { back } else { 1.0 };
        (s.powi(power as i32) * m - (m - 1.0)).clamp(0.0, 1.0)
    };
    let v: Vec<f64> = (0..N).map(f).collect();
    let mean = v.iter().sum::<f64>() / N as f64;
    let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / N as f64;
    let dphi = TAU / N as f64;
    let slope2 = (0..N).map(|i| ((v[(i + 1) % N] - v[i]) / dphi).powi(2)).sum::<f64>() / N as f64;
    let rms = if var > 0.0 { (slope2 / var).sqrt() } else { 1.0 };
    (mean, rms)
}

/// A profile's nodes: Φ (turns), h̄ (m), K_s.
type Profile = Arc<Vec<[f64; 3]>>;

/// What a profile depends on: the radial waves' ω and g, the centre, the table's reach and
/// the floor (a terrain by value without its relief, and the relief by identity: a loaded
/// relief is never changed in place, and the key holds it, so its address is not reused).
#[derive(Clone)]
struct ProfileKey {
    omega: f64,
    gravity: f64,
    center: [f64; 2],
    reach: f64,
    open_depth_m: f64,
    terrain: Option<(crate::terrain::Terrain, Option<Arc<crate::terrain::Relief>>)>,
}

impl PartialEq for ProfileKey {
    fn eq(&self, o: &Self) -> bool {
        let same_floor = match (&self.terrain, &o.terrain) {
            (None, None) => true,
            (Some((a, ra)), Some((b, rb))) => {
                a == b
                    && match (ra, rb) {
                        (None, None) => true,
                        (Some(x), Some(y)) => Arc::ptr_eq(x, y),
                        _ => false,
                    }
            }
            _ => false,
        };
        same_floor
            && (self.omega, self.gravity, self.center, self.reach, self.open_depth_m)
                == (o.omega, o.gravity, o.center, o.reach, o.open_depth_m)
    }
}

/// The profiles made last: a frame asks for its sea several times (the plan's bound, the
/// uniforms, the graph, the terrain's wet band), the viewer every frame, a boat's settle run
/// many times, and a profile is ~130 000 floor samples. A pure function of its key, so a hit
/// is the same numbers as a miss.
fn cached_profile(key: ProfileKey, make: impl FnOnce() -> Vec<[f64; 3]>) -> Profile {
    static CACHE: Mutex<Vec<(ProfileKey, Profile)>> = Mutex::new(Vec::new());
    const KEEP: usize = 4;
    if let Some((_, nodes)) =
        CACHE.lock().ok().and_then(|c| c.iter().find(|(k, _)| *k == key).cloned())
    {
        return nodes;
    }
    let nodes = Arc::new(make());
    if let Ok(mut c) = CACHE.lock() {
        if c.len() == KEEP {
            c.remove(0);
        }
        c.push((key, Arc::clone(&nodes)));
    }
    nodes
}

/// Φ (turns), h̄ and K_s every `step` m from the centre (module docs, "Depth").
fn profile_nodes(floor: &Floor, center: [f64; 2], step: f64, omega: f64, g: f64) -> Vec<[f64; 3]> {
    let count = (COASTAL_SEGMENTS - 1) * NODES_PER_SEGMENT + 1;
    let mean_depth = |r: f64| {
        if r == 0.0 {
            return floor.depth(center[0], center[1]);
        }
        (0..AZIMUTHS)
            .map(|a| {
                let angle = TAU * a as f64 / AZIMUTHS as f64;
                floor.depth(center[0] + r * angle.cos(), center[1] + r * angle.sin())
            })
            .sum::<f64>()
            / AZIMUTHS as f64
    };
    let mut nodes = Vec::with_capacity(count);
    let mut phi = 0.0;
    let mut k_prev = 0.0;
    for j in 0..count {
        let h = mean_depth(j as f64 * step);
        let k = wavenumber(omega, g, h);
        if j > 0 {
            phi += 0.5 * (k_prev + k) * step / TAU;
        }
        k_prev = k;
        nodes.push([phi, h, shoaling_coefficient(omega, g, h)]);
    }
    nodes
}

/// (R, Φ there): Hunt's run-up R = min(ξ, [`MAX_IRIBARREN`])·A over the beach where the
/// mean depth of `nodes` (every `step` m) first rises through 0 going out from the centre,
/// ξ = tan β / √(A/L₀) with tan β the mean depth's slope just seaward of there. R = 0 without such a
/// crossing or without waves.
fn run_up(nodes: &[[f64; 3]], step: f64, amplitude_m: f64, wavelength_m: f64) -> (f64, f64) {
    if !(amplitude_m > 0.0 && wavelength_m > 0.0) {
        return (0.0, 0.0);
    }
    let Some(j) = nodes.windows(2).position(|w| w[0][1] <= 0.0 && w[1][1] > 0.0) else {
        return (0.0, 0.0);
    };
    // The foreshore's slope: the first step wholly under water (the land's side may curve
    // away, as the island's hill does).
    let k = (j + 1).min(nodes.len() - 2);
    let slope = (nodes[k + 1][1] - nodes[k][1]) / step;
    let xi = slope / (amplitude_m / wavelength_m).sqrt();
    let r = xi.min(MAX_IRIBARREN) * amplitude_m;
    (if r.is_finite() { r.max(0.0) } else { 0.0 }, nodes[j][0])
}

/// Shading technique `coastal`'s uniform block (`frame.coastal_shading`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CoastalShadingBlock {
    /// The dull colour.
    pub dull_color: [f32; 3],
    /// Its share at the crests.
    pub dull_factor: f32,
    /// The Blinn–Phong exponent, whole.
    pub shininess: f32,
    /// The maps' shift per unit of normal tilt.
    pub distortion: f32,
    /// 1: Schlick's Fresnel; 0: the exact one from the Fresnel texture.
    pub schlick: f32,
    /// Schlick's F₀ = ((η − 1)/(η + 1))².
    pub f0: f32,
}

impl CoastalShadingBlock {
    /// The block of `c` for water of refractive index `eta`.
    pub fn new(c: &Coastal, eta: f64) -> Self {
        Self {
            dull_color: c.dull_color.map(|v| v as f32),
            dull_factor: c.dull_factor as f32,
            shininess: c.shininess as f32,
            distortion: c.distortion as f32,
            schlick: crate::switch::switch(c.fresnel == crate::ggx::GgxFresnel::Schlick),
            f0: (((eta - 1.0) / (eta + 1.0)).powi(2)) as f32,
        }
    }
}

/// Waves technique `coastal`'s uniform block (`frame.coastal`, shared/coastal.wgsl): zero
/// (`shape.x` [`crate::switch::SWITCH_OFF`]) under the other waves techniques.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CoastalBlock {
    /// The centre relative to the mesh's reference point (x, z), 1/Δ, Δ (m).
    pub center: [f32; 4],
    /// ([`crate::switch::SWITCH_ON`] when on, A, p, back factor).
    pub shape: [f32; 4],
    /// (ω t in turns, γ, correction waves, 0).
    pub time: [f32; 4],
    /// Per correction wave: (fx, fz turns per m, the phase at the reference point, amplitude).
    pub waves: [[f32; 4]; MAX_CORRECTION_WAVES],
    /// Per correction wave: 2/λ.
    pub damping: [f32; 4],
    /// (the swash's level L at the frame's time, the run-up R, 0, 0), m.
    pub swash: [f32; 4],
    /// Per segment: (Φ₀ mod 1, Φ₁, Φ₂, 0) and (K_s·A's three coefficients, 0).
    pub table: [[f32; 4]; 2 * COASTAL_SEGMENTS],
}

#[cfg(test)]
mod tests {
    /// The kept moments are the computed ones, bit for bit, after more profiles than are
    /// kept, and each profile its own.
    #[test]
    fn the_kept_profile_moments_are_the_computed_ones() {
        let pairs = [(1, 1.0), (3, 1.5), (5, 2.0), (7, 2.0), (9, 3.0), (1, 1.0), (3, 1.5)];
        let mut seen = Vec::new();
        for (p, b) in pairs {
            let (kept, made) = (super::profile_moments(p, b), super::moments(p, b));
            assert_eq!((kept.0.to_bits(), kept.1.to_bits()), (made.0.to_bits(), made.1.to_bits()));
            seen.push(kept.0.to_bits());
        }
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 5, "five profiles, five means");
    }
}
