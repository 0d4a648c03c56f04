//! CPU mirror of `shaders/spray.wgsl`: the spray's step (every slot from its previous value,
//! the same arithmetic and random numbers as the compute shader) and its sprites (six
//! vertices per particle from the vertex index, added to the frame); and, for the envelope
//! verdicts, where on any conformant GPU its sprites may land.

pub use ocean_core::spray::{Emitter, Particle, SprayUniforms, spray_random};

use ocean_core::frame::FrameUniforms;
use rayon::prelude::*;

use super::water::WRAP_LINEAR;
use super::water::envelope::Sampling;
use super::wgsl::{Vec2, Vec4, vec2};
use crate::envelope::{Cond, Iv, Jitter, JitterRules, Precision, Real, choose};
use crate::raster::{
    self, BlendMode, CompareFunction, CullMode, FrontFace, RasterState, RenderTarget, Vertex,
};
use crate::sampler::Texture2D;

mod sprites;

pub use sprites::{QUAD, corner_clip_r, sprite_color_r, sprites_envelope, sprites_jitter};

/// `water_height(x, z)`.
pub fn water_height(x: f32, z: f32, params: &SprayUniforms, displacement: &Texture2D) -> f32 {
    water_height_r(x, z, params, displacement, Precision::LAVAPIPE)
}

/// `water_height(x, z)` over any [`Real`], on a device of precision `p` (its filter weights).
fn water_height_r<R: Real + Sampling<R>>(
    x: R,
    z: R,
    params: &SprayUniforms,
    displacement: &Texture2D,
    p: Precision,
) -> R {
    let l = R::lit;
    let uv = [
        x * l(params.inv_patch) + l(params.half_texel),
        z * l(params.inv_patch) + l(params.half_texel),
    ];
    R::level0(displacement, &WRAP_LINEAR, uv, p)[1] * l(params.waves)
}

/// `step` for slot `i`: the slot's next value.
pub fn step_slot(
    i: u32,
    p: Particle,
    params: &SprayUniforms,
    emitters: &[Emitter],
    displacement: &Texture2D,
) -> Particle {
    let next = step_slot_r::<f32>(i, p, params, emitters, displacement, Precision::LAVAPIPE);
    Particle { pos: next.pos, vel: next.vel }
}

/// A slot's next value over any [`Real`], and whether every branch the step took was
/// decided (for an envelope: a slot freed, kept, launched or left alike on every conformant
/// GPU).
#[derive(Clone, Copy, Debug)]
pub struct SlotStep<R> {
    /// Position (xyz) and active tag (w).
    pub pos: [R; 4],
    /// Velocity (xyz) and age (w).
    pub vel: [R; 4],
    /// No branch was undecided.
    pub decided: bool,
}

impl SlotStep<Iv> {
    /// How many of the slot's eight values `p` holds outside this envelope.
    pub fn values_outside(&self, p: &Particle) -> usize {
        let out = |e: &[Iv; 4], v: &[f32; 4]| (0..4).filter(|&c| !e[c].contains(v[c])).count();
        out(&self.pos, &p.pos) + out(&self.vel, &p.vel)
    }
}

/// `step` for slot `i` from its value `p` (as the GPU held it) over any [`Real`], reading the
/// sea's height through a filter of precision `prec`: the one mirror of the step, for the
/// exact frame (`f32`), its envelope ([`Iv`]) and a random conformant GPU ([`Jitter`]).
pub(crate) fn step_slot_r<R: Real + Sampling<R>>(
    i: u32,
    p: Particle,
    params: &SprayUniforms,
    emitters: &[Emitter],
    displacement: &Texture2D,
    prec: Precision,
) -> SlotStep<R> {
    let l = R::lit;
    let random = |k: u32| spray_random(params.seed, i, params.step, k);
    let same = SlotStep { pos: p.pos.map(l), vel: p.vel.map(l), decided: true };
    if p.pos[3] > 0.0 {
        let dt = l(params.dt);
        let vy = l(p.vel[1]) - l(params.gravity) * dt;
        let v = [l(p.vel[0]), vy, l(p.vel[2])];
        let x: [R; 3] = std::array::from_fn(|c| l(p.pos[c]) + v[c] * dt);
        let age = l(p.vel[3]) + dt;
        // Rust's `||` and `&&` short-circuit as WGSL's do; the height is read only when the
        // particle falls.
        let old = l(params.lifetime).lt(age);
        let freed = match old.decided() {
            Some(true) => old,
            _ => {
                let falls = vy.lt(l(0.0));
                let under = match falls.decided() {
                    Some(false) => falls,
                    _ => falls.and(x[1].lt(water_height_r(x[0], x[2], params, displacement, prec))),
                };
                old.or(under)
            }
        };
        let alive = choose(freed, || l(0.0), || l(1.0));
        SlotStep {
            pos: [x[0], x[1], x[2], alive],
            vel: [v[0], v[1], v[2], age],
            decided: freed.decided().is_some(),
        }
    } else if params.emitters > 0 {
        let e = emitters[(i % params.emitters) as usize];
        // The WGSL tests the water first (`e.pos.y < water_height(…) && random < chance`);
        // neither side has an effect, so the mirror takes the random number first: it is
        // integer arithmetic, decided alike everywhere, and spares the envelope the filter of
        // every slot that launches nothing (a NaN chance launches nothing, as the WGSL's `<`).
        let chance = random(0) < params.emit_chance;
        if !chance {
            return same;
        }
        let submerged =
            l(e.pos[1]).lt(water_height_r(l(e.pos[0]), l(e.pos[2]), params, displacement, prec));
        let launch = || {
            let speed = l(params.speed);
            let s = speed * (l(0.6) + l(0.8) * l(random(1)));
            let spread = l(0.3) * speed;
            let jitter = [2, 3, 4].map(|k| (l(random(k)) - l(0.5)) * spread);
            let vel: [R; 3] = std::array::from_fn(|c| l(e.dir[c]) * s + jitter[c]);
            ([l(e.pos[0]), l(e.pos[1]), l(e.pos[2]), l(1.0)], [vel[0], vel[1], vel[2], l(0.0)])
        };
        match submerged.decided() {
            Some(true) => {
                let (pos, vel) = launch();
                SlotStep { pos, vel, decided: true }
            }
            Some(false) => same,
            None => {
                let (pos, vel) = launch();
                SlotStep {
                    pos: std::array::from_fn(|c| pos[c].hull(same.pos[c])),
                    vel: std::array::from_fn(|c| vel[c].hull(same.vel[c])),
                    decided: false,
                }
            }
        }
    } else {
        same
    }
}

/// `step` dispatched over every slot (each slot depends on its own value only, so the order
/// the threads take does not matter).
pub fn step(
    particles: &mut [Particle],
    params: &SprayUniforms,
    emitters: &[Emitter],
    displacement: &Texture2D,
) {
    particles
        .par_iter_mut()
        .enumerate()
        .for_each(|(i, p)| *p = step_slot(i as u32, *p, params, emitters, displacement));
}

/// The envelope of one `step` of every slot from the pool `before` as the GPU held it: each
/// slot's interval of every value a conformant GPU may write, reading the sea's height from
/// `displacement` through a filter of precision `prec`, and whether the slot's branches were
/// all decided (where not, both outcomes, united).
pub fn step_envelope(
    before: &[Particle],
    params: &SprayUniforms,
    emitters: &[Emitter],
    displacement: &Texture2D,
    prec: Precision,
) -> Vec<SlotStep<Iv>> {
    before
        .par_iter()
        .enumerate()
        .map(|(i, p)| step_slot_r(i as u32, *p, params, emitters, displacement, prec))
        .collect()
}

/// One `step` of every slot as one random conformant GPU computes it (`rules.scale` times
/// the rules; each slot draws from the seed and its index).
pub fn step_jitter(
    before: &[Particle],
    params: &SprayUniforms,
    emitters: &[Emitter],
    displacement: &Texture2D,
    prec: Precision,
    rules: JitterRules,
) -> Vec<Particle> {
    before
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            Jitter::reseed(rules, i as u64);
            let s = step_slot_r::<Jitter>(i as u32, *p, params, emitters, displacement, prec);
            Particle { pos: s.pos.map(|v| v.0), vel: s.vel.map(|v| v.0) }
        })
        .collect()
}

/// `SpriteOut`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpriteOut {
    /// `@builtin(position)`.
    pub clip: Vec4,
    /// `@location(0)`: the quad's corner.
    pub corner: Vec2,
}

/// `vs_main(k)`.
pub fn vs_main(
    k: u32,
    sprites: &[Particle],
    frame: &FrameUniforms,
    draw: &SprayUniforms,
) -> SpriteOut {
    let p = sprites[(k / 6) as usize];
    let cx = [-1.0f32, 1.0, 1.0, -1.0, 1.0, -1.0];
    let cy = [-1.0f32, -1.0, 1.0, -1.0, 1.0, 1.0];
    let c = vec2(cx[(k % 6) as usize], cy[(k % 6) as usize]);
    if p.pos[3] == 0.0 {
        return SpriteOut { clip: Vec4::from([2.0, 2.0, 0.5, 1.0]), corner: c };
    }
    let clip = sprites::corner_clip_r::<f32>(&p, [c.x, c.y], frame, draw);
    SpriteOut { clip: Vec4::from(clip), corner: c }
}

/// `fs_main(in)`.
pub fn fs_main(corner: Vec2, draw: &SprayUniforms) -> [f32; 4] {
    sprites::sprite_color_r([corner.x, corner.y], draw)
}

/// The draw's state: reversed-Z `Greater` against the frame's depth, no depth write, blend
/// One + One, no culling (the GPU pipeline's, `ocean-gpu/src/spray.rs`).
pub const RASTER_STATE: RasterState = RasterState {
    front_face: FrontFace::Ccw,
    cull_mode: CullMode::None,
    depth_compare: CompareFunction::Greater,
    depth_write: false,
    blend: BlendMode::Add,
};

/// Draws the sprites of `particles` into `target` (its depth as the frame left it).
pub fn draw_sprites(
    target: &mut RenderTarget,
    particles: &[Particle],
    frame: &FrameUniforms,
    draw: &SprayUniforms,
) {
    let tris: Vec<[Vertex<2>; 3]> = (0..particles.len() as u32 * 2)
        .map(|t| {
            [0, 1, 2].map(|j| {
                let o = vs_main(3 * t + j, particles, frame, draw);
                Vertex::new(o.clip.into(), [o.corner.x, o.corner.y])
            })
        })
        .collect();
    raster::draw(target, &RASTER_STATE, &tris, |frag| {
        Some(fs_main(vec2(frag.varyings[0], frag.varyings[1]), draw))
    });
}

/// The box, relative to the spray's origin, that every sprite of the spray's particles lies
/// in on any conformant GPU: `None` without an emitter (no particle is ever launched).
/// `lowest_water`: the lowest height the step's `water_height` may return (the displacement
/// map's lowest texel, which a filter with non-negative weights cannot undercut), if known.
///
/// The bound is the flight, not the arithmetic, so rounding, a comparison decided the other
/// way (a particle freed a step sooner or later, a slot launched or not) and the random
/// numbers' last bits cannot take a particle out of it:
/// - a particle leaves an emitter with velocity component c at most
///   `speed · (1.4 |dir_c| + 0.15)` (the random part of the speed below 1.4, each jitter
///   component within ±0.15 · speed), and lives at most `lifetime` (it is freed at the first
///   step past it);
/// - semi-implicit Euler keeps it under the parabola y₀ + v t − g t²/2, so it rises at most
///   v²/2g above its emitter, and once falling below `lowest_water` it is freed at that very
///   step: a live particle is above its emitter (rising) or above the lowest water (falling),
///   and its life ends by the time the parabola crosses that water;
/// - its sprite's corners lie within half its side · √2 of it.
///
/// A margin of 1 % and 1 cm covers the f32 steps.
pub fn sprite_box(
    emitters: &[Emitter],
    draw: &SprayUniforms,
    lowest_water: Option<f64>,
) -> Option<[[f64; 3]; 2]> {
    emitters.first()?;
    let speed = f64::from(draw.speed.abs());
    let v: [f64; 3] = std::array::from_fn(|c| {
        let dir = emitters.iter().map(|e| f64::from(e.dir[c].abs())).fold(0.0f64, f64::max);
        speed * (1.4 * dir + 0.15)
    });
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for e in emitters {
        for c in 0..3 {
            lo[c] = lo[c].min(f64::from(e.pos[c]));
            hi[c] = hi[c].max(f64::from(e.pos[c]));
        }
    }
    let (dt, g) = (f64::from(draw.dt.abs()), f64::from(draw.gravity));
    let mut t = f64::from(draw.lifetime) + dt;
    let rise = if g > 0.0 { (v[1] * v[1] / (2.0 * g)).min(v[1] * t) } else { v[1] * t };
    let floor = match lowest_water {
        // Below the lowest water and falling, a particle is freed: the parabola from the
        // highest emitter crosses it at t_f; a particle rising is above its emitter.
        Some(h) if g > 0.0 && h.is_finite() => {
            let h = h - 0.01 * h.abs() - 0.01;
            let drop = (hi[1] - h).max(0.0);
            t = t.min((v[1] + (v[1] * v[1] + 2.0 * g * drop).sqrt()) / g + dt);
            h.min(lo[1])
        }
        _ => lo[1] - (v[1] * t + 0.5 * g.max(0.0) * t * t),
    };
    let sprite = f64::from(draw.sprite[0].abs()) * std::f64::consts::SQRT_2;
    let margin = |d: f64| d * 1.01 + sprite + 0.01;
    Some([
        [lo[0] - margin(v[0] * t), floor - margin(0.0), lo[2] - margin(v[2] * t)],
        [hi[0] + margin(v[0] * t), hi[1] + margin(rise), hi[2] + margin(v[2] * t)],
    ])
}

/// Per pixel of a `width` × `height` view, whether a sprite of the spray may cover it on any
/// conformant GPU: the screen rectangle around [`sprite_box`]'s eight corners (given the
/// lowest water the step may sample, if known) seen through
/// the frame's view-projection, widened by two pixels; every pixel where a corner may lie
/// behind the eye (w ≤ 0), none where all of them do. The verdicts leave these pixels out:
/// the sprites' own envelope is not carried.
pub fn reach(
    emitters: &[Emitter],
    draw: &SprayUniforms,
    lowest_water: Option<f64>,
    frame: &FrameUniforms,
    width: u32,
    height: u32,
) -> Vec<bool> {
    let n = width as usize * height as usize;
    let Some([lo, hi]) = sprite_box(emitters, draw, lowest_water) else {
        return vec![false; n];
    };
    let m = glam::DMat4::from_cols_array_2d(&frame.view.view_proj.map(|c| c.map(f64::from)));
    let origin = glam::DVec3::from_array(std::array::from_fn(|c| f64::from(draw.origin_rel[c])));
    let clips: Vec<glam::DVec4> = (0..8)
        .map(|k| {
            let p = glam::DVec3::new(
                if k & 1 == 0 { lo[0] } else { hi[0] },
                if k & 2 == 0 { lo[1] } else { hi[1] },
                if k & 4 == 0 { lo[2] } else { hi[2] },
            );
            m * (p + origin).extend(1.0)
        })
        .collect();
    let eps = 1e-6 * clips.iter().map(|c| c.w.abs()).fold(0.0, f64::max);
    if clips.iter().all(|c| c.w < -eps) {
        return vec![false; n];
    }
    if clips.iter().any(|c| c.w <= eps) {
        return vec![true; n];
    }
    let (hw, hh) = (0.5 * f64::from(width), 0.5 * f64::from(height));
    let (mut x0, mut x1, mut y0, mut y1) =
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for c in &clips {
        let (x, y) = (c.x / c.w * hw + hw, c.y / c.w * -hh + hh);
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let (x0, x1, y0, y1) = (x0 - 2.0, x1 + 2.0, y0 - 2.0, y1 + 2.0);
    (0..n)
        .map(|i| {
            let (x, y) = ((i % width as usize) as f64 + 0.5, (i / width as usize) as f64 + 0.5);
            (x0..=x1).contains(&x) && (y0..=y1).contains(&y)
        })
        .collect()
}

#[cfg(test)]
#[path = "spray_tests.rs"]
mod tests;
