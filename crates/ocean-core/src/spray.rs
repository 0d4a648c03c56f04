//! Spray technique `particles` (seed 001 §3.4): a state-preserving particle system. Each
//! particle is a slot of a fixed pool holding (position, active tag) and (velocity, age);
//! one fixed time step per frame updates every slot from its previous value, on the GPU in
//! `shaders/spray.wgsl` (storage buffers that stay on the device: nothing is uploaded per
//! frame) and on the CPU in its mirror, with the same arithmetic and the same random numbers
//! (an integer hash of the slot, the step and a stream index), so frame n's particles are the
//! same on both back ends.
//!
//! Emitters are points of the objects' surfaces between the wave's lower and upper bounds
//! (±[`crate::frame::ProjectedGridBlock::BOUND_OVER_HS`]·H_s), each with an emit direction
//! (its outward normal's horizontal part halved, plus up, normalised). Slot i belongs to
//! emitter i mod E. A free slot whose emitter is under the water (below the displacement map's
//! height at the emitter's (x, z)) becomes active with probability `emit_chance` per step, at
//! the emitter, with velocity `speed`·(0.6 + 0.8 u₀)·dir plus an isotropic jitter of
//! 0.3·`speed`·(u₁,₂,₃ − ½). An active particle falls under gravity (explicit Euler:
//! v += g dt, then x += v dt) and is freed when its age passes `lifetime_s` or when it falls
//! back under the water. The water height ignores the map's horizontal displacement (the
//! spray's own scale is larger than that error).
//!
//! Positions are stored relative to the spray's origin, a multiple of the displacement patch
//! near the emitters (formed in f64), so f32 keeps their digits far from the world's origin
//! and the map is sampled at x/L with no loss.
//!
//! A still frame (`ocean render`) has no history: the first frame of a [`SprayState`] runs
//! `warmup_steps` steps before its own against its sea, so the spray is in the state of a
//! steady emission; each later frame runs one step.

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::objects::{Object, Shape};
use serde::{Deserialize, Serialize};

/// Standard gravity, m/s².
pub const GRAVITY: f32 = 9.81;
/// The most emitters (the rest of the candidates are dropped, evenly).
pub const MAX_EMITTERS: usize = 4096;
/// Spacing of a box face's emitter points, m.
pub const BOX_EMITTER_SPACING_M: f64 = 0.5;

/// A particle slot (WGSL `Particle`, a storage-buffer element).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Particle {
    /// Position relative to the spray's origin (xyz), active tag (w: 1 active, 0 free).
    pub pos: [f32; 4],
    /// Velocity (xyz), age in seconds (w).
    pub vel: [f32; 4],
}

/// An emitter (WGSL `Emitter`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Emitter {
    /// Position relative to the spray's origin (xyz), 0.
    pub pos: [f32; 4],
    /// Unit emit direction (xyz), 0.
    pub dir: [f32; 4],
}

/// The spray stage's uniforms (WGSL `SprayUniforms`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SprayUniforms {
    /// The step's index (the random numbers' counter).
    pub step: u32,
    /// Particle slots.
    pub count: u32,
    /// Emitters.
    pub emitters: u32,
    /// The scene's seed (the random numbers' key).
    pub seed: u32,
    /// Time step, s.
    pub dt: f32,
    /// Gravity, m/s².
    pub gravity: f32,
    /// Launch speed, m/s.
    pub speed: f32,
    /// Lifetime, s.
    pub lifetime: f32,
    /// Chance of a free slot's launch per step.
    pub emit_chance: f32,
    /// 1/L of the displacement map.
    pub inv_patch: f32,
    /// Half a texel of the displacement map, in its coordinates.
    pub half_texel: f32,
    /// 1 when the waves pass ran (else the sea is flat: height 0).
    pub waves: f32,
    /// The spray's origin minus the eye (camera-relative offset of the stored positions).
    pub origin_rel: [f32; 4],
    /// (half the sprite's side, m; radiance of a sprite's centre; 0; 0).
    pub sprite: [f32; 4],
    /// The sprites' colour (rgb), 0.
    pub color: [f32; 4],
    /// The camera's unit right vector (xyz), 0: the sprites face the eye.
    pub right: [f32; 4],
    /// The camera's unit up vector (xyz), 0.
    pub up: [f32; 4],
}

/// What a particle pool was made for: the scene's `[spray]` and the emitters. Both back ends
/// keep a pool across frames only while its key and its step count agree with the frame's
/// ([`SprayFrame::continues`]); otherwise it starts again from free slots.
#[derive(Clone, Debug, PartialEq)]
pub struct PoolKey {
    /// The scene's spray.
    pub spray: Spray,
    /// The emitters (shared with the plan that found them).
    pub emitters: Arc<Vec<Emitter>>,
}

/// The particles of a scene, living across frames in `FrameState` (the CPU's copy; the GPU
/// keeps its own in a storage buffer).
#[derive(Clone, Debug, PartialEq)]
pub struct SprayState {
    /// What the pool was made for.
    pub key: PoolKey,
    /// The slots.
    pub particles: Vec<Particle>,
    /// Steps run so far.
    pub steps: u64,
}

impl SprayState {
    /// A pool of free slots for `key`, `steps` steps into the animation.
    pub fn fresh(key: PoolKey, steps: u64) -> Self {
        Self { particles: vec![Particle::default(); key.spray.particles as usize], key, steps }
    }
}

/// The random number of stream `k` for slot `i` at step `step`, in [0, 1): a counter-based
/// integer hash (lowbias32 rounds over the key), the top 24 bits as the fraction.
pub fn spray_random(seed: u32, i: u32, step: u32, k: u32) -> f32 {
    let mut h = seed
        ^ i.wrapping_mul(0x9e37_79b9)
        ^ step.wrapping_mul(0x85eb_ca6b)
        ^ k.wrapping_mul(0xc2b2_ae35);
    for _ in 0..2 {
        h ^= h >> 16;
        h = h.wrapping_mul(0x7feb_352d);
        h ^= h >> 15;
        h = h.wrapping_mul(0x846c_a68b);
        h ^= h >> 16;
    }
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The spray's origin (world x, z): the multiple of the displacement patch nearest the
/// objects' centroid.
pub fn spray_origin(objects: &[Object], patch_size_m: f64) -> [f64; 2] {
    let n = objects.len().max(1) as f64;
    let (sx, sz) = objects.iter().fold((0.0, 0.0), |(x, z), o| (x + o.center[0], z + o.center[2]));
    let l = patch_size_m;
    [(sx / n / l).round() * l, (sz / n / l).round() * l]
}

/// Most grid points along one side of a box face: a huge box's grid is coarser, so that the
/// points made before the emitters are thinned stay few (a 10⁷ m box at the spacing would be
/// 10¹⁵ of them).
const MAX_BOX_POINTS_PER_SIDE: i64 = 1024;

/// Points of an object's surface with their outward normals within `bound` of the sea plane
/// (sphere: its tessellation's vertices; box and boat: a grid on its sides, a box's over the
/// band of heights |y| ≤ bound only).
fn surface_points(o: &Object, bound: f64) -> Vec<(DVec3, DVec3)> {
    let c = DVec3::from_array(o.center);
    match o.shape() {
        Some(Shape::Sphere { radius }) => {
            let (bands, segs) = (crate::objects::SPHERE_BANDS, crate::objects::SPHERE_SEGMENTS);
            let mut out = Vec::new();
            for b in 1..bands {
                for s in 0..segs {
                    let theta = std::f64::consts::PI * f64::from(b) / f64::from(bands);
                    let phi = std::f64::consts::TAU * f64::from(s) / f64::from(segs);
                    let n =
                        DVec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin());
                    out.push((c + n * radius, n));
                }
            }
            out
        }
        Some(Shape::Box { size }) => {
            let h = DVec3::from_array(size) * 0.5;
            let mut out = Vec::new();
            for (n, u, extent) in [
                (DVec3::X, DVec3::Z, h.z),
                (DVec3::NEG_X, DVec3::Z, h.z),
                (DVec3::Z, DVec3::X, h.x),
                (DVec3::NEG_Z, DVec3::X, h.x),
            ] {
                let face = c + n * DVec3::new(h.x, 0.0, h.z).dot(n.abs());
                // The face's heights within the band, relative to its centre.
                let (t0, t1) = ((-bound - c.y).max(-h.y), (bound - c.y).min(h.y));
                if t0 > t1 {
                    continue;
                }
                let cells = |len: f64| {
                    ((len / BOX_EMITTER_SPACING_M).ceil() as i64).clamp(1, MAX_BOX_POINTS_PER_SIDE)
                };
                let (nu, nv) = (cells(2.0 * extent), cells(t1 - t0));
                for a in 0..=nu {
                    for b in 0..=nv {
                        let s = -extent + 2.0 * extent * a as f64 / nu as f64;
                        let t = t0 + (t1 - t0) * b as f64 / nv as f64;
                        out.push((face + u * s + DVec3::Y * t, n));
                    }
                }
            }
            out
        }
        Some(Shape::Boat { size, .. }) => {
            // The hull's sides at its resting pose: the plan, and so its emitters, knows no
            // time, and a boat's start point and draft are where it rides on average.
            let Some(pose) = crate::objects::resting_pose(o) else { return Vec::new() };
            let m = pose.model_matrix();
            let mut out = Vec::new();
            for (n, q) in crate::objects::hull_faces(size) {
                if n.y != 0.0 {
                    continue;
                }
                // A side is a rectangle, spanned by its first corner's two edges.
                let (u, v) = (q[1] - q[0], q[3] - q[0]);
                let cells = |len: f64| {
                    ((len / BOX_EMITTER_SPACING_M).ceil() as i64).clamp(1, MAX_BOX_POINTS_PER_SIDE)
                };
                let (nu, nv) = (cells(u.length()), cells(v.length()));
                let n = m.transform_vector3(n);
                for a in 0..=nu {
                    for b in 0..=nv {
                        let p = q[0] + u * (a as f64 / nu as f64) + v * (b as f64 / nv as f64);
                        out.push((m.transform_point3(p), n));
                    }
                }
            }
            out
        }
        None => Vec::new(),
    }
}

/// The emitters of a scene whose waves stay within `bound` m of the plane: the objects'
/// surface points with |y| ≤ bound, at most [`MAX_EMITTERS`] (every k-th kept), relative to
/// the spray's origin, in the objects' order.
pub fn emitters(objects: &[Object], patch_size_m: f64, bound: f64) -> Vec<Emitter> {
    let origin = spray_origin(objects, patch_size_m);
    let mut all: Vec<Emitter> = objects
        .iter()
        .flat_map(|o| surface_points(o, bound))
        .filter(|(p, _)| p.y.abs() <= bound)
        .map(|(p, n)| {
            let d = (DVec3::new(n.x, 0.0, n.z) * 0.5 + DVec3::Y).normalize();
            Emitter {
                pos: [(p.x - origin[0]) as f32, p.y as f32, (p.z - origin[1]) as f32, 0.0],
                dir: [d.x as f32, d.y as f32, d.z as f32, 0.0],
            }
        })
        .collect();
    if all.len() > MAX_EMITTERS {
        let k = all.len().div_ceil(MAX_EMITTERS);
        all = all.into_iter().step_by(k).collect();
    }
    all
}

/// What pass `spray` does in one frame, the same for both back ends: the emitters, the
/// uniforms of each of its steps (from step `first`), and the draw's uniforms (after them).
#[derive(Clone, Debug)]
pub struct SprayFrame {
    /// The pool this frame continues (or starts).
    pub key: PoolKey,
    /// Steps the pool has run before this frame.
    pub first: u64,
    /// One per step, in order.
    pub steps: Vec<SprayUniforms>,
    /// The sprites' draw.
    pub draw: SprayUniforms,
}

impl SprayFrame {
    /// Whether a pool made for `key` that has run `steps` steps goes on into this frame.
    pub fn continues(&self, key: &PoolKey, steps: u64) -> bool {
        *key == self.key && steps == self.first
    }
}

/// The `[spray]` table: spray technique `particles` (seed 001 §3.4; the model is
/// `crate::spray`'s).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Spray {
    /// Particle slots.
    pub particles: u32,
    /// Chance per step that a free slot whose emitter is under the water is launched.
    pub emit_chance: f64,
    /// Launch speed, m/s.
    pub speed: f64,
    /// A particle's lifetime, s.
    pub lifetime_s: f64,
    /// The fixed time step, s (one per frame).
    pub step_s: f64,
    /// Steps run before a state's first frame (a still frame shows steady spray).
    pub warmup_steps: u32,
    /// A sprite's side, m.
    pub size_m: f64,
    /// Radiance of a sprite's centre (additive).
    pub intensity: f64,
    /// The sprites' colour, linear RGB.
    pub color: [f64; 3],
}

impl Default for Spray {
    fn default() -> Self {
        Self {
            particles: 8192,
            emit_chance: 0.05,
            speed: 4.0,
            lifetime_s: 1.5,
            step_s: 1.0 / 30.0,
            warmup_steps: 90,
            size_m: 0.15,
            intensity: 0.25,
            color: [0.9, 0.95, 1.0],
        }
    }
}
