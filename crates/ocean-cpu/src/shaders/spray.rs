//! CPU mirror of `shaders/spray.wgsl`: the spray's step (every slot from its previous value,
//! the same arithmetic and random numbers as the compute shader) and its sprites (six
//! vertices per particle from the vertex index, added to the frame).

pub use ocean_core::spray::{Emitter, Particle, SprayUniforms, spray_random};

use ocean_core::frame::FrameUniforms;
use rayon::prelude::*;

use super::shared::frame::transform_point;
use super::water::WRAP_LINEAR;
use super::wgsl::{Vec2, Vec3, Vec4, max, texture_sample_level, vec2, vec3};
use crate::raster::{
    self, BlendMode, CompareFunction, CullMode, FrontFace, RasterState, RenderTarget, Vertex,
};
use crate::sampler::Texture2D;

/// `water_height(x, z)`.
pub fn water_height(x: f32, z: f32, params: &SprayUniforms, displacement: &Texture2D) -> f32 {
    let uv = vec2(x, z) * params.inv_patch + params.half_texel;
    texture_sample_level(displacement, &WRAP_LINEAR, uv, 0.0).y * params.waves
}

/// `step` for slot `i`: the slot's next value.
pub fn step_slot(
    i: u32,
    p: Particle,
    params: &SprayUniforms,
    emitters: &[Emitter],
    displacement: &Texture2D,
) -> Particle {
    let random = |k: u32| spray_random(params.seed, i, params.step, k);
    let mut p = p;
    if p.pos[3] > 0.0 {
        let mut v = Vec4::from(p.vel).xyz();
        v.y -= params.gravity * params.dt;
        let x = Vec4::from(p.pos).xyz() + v * params.dt;
        let age = p.vel[3] + params.dt;
        let mut active = 1.0;
        if age > params.lifetime
            || (v.y < 0.0 && x.y < water_height(x.x, x.z, params, displacement))
        {
            active = 0.0;
        }
        p.pos = x.extend(active).into();
        p.vel = v.extend(age).into();
    } else if params.emitters > 0 {
        let e = emitters[(i % params.emitters) as usize];
        if e.pos[1] < water_height(e.pos[0], e.pos[2], params, displacement)
            && random(0) < params.emit_chance
        {
            let s = params.speed * (0.6 + 0.8 * random(1));
            let jitter =
                vec3(random(2) - 0.5, random(3) - 0.5, random(4) - 0.5) * (0.3 * params.speed);
            p.pos = [e.pos[0], e.pos[1], e.pos[2], 1.0];
            p.vel = (Vec4::from(e.dir).xyz() * s + jitter).extend(0.0).into();
        }
    }
    p
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
    let half = draw.sprite[0];
    let rel = Vec4::from(p.pos).xyz()
        + Vec4::from(draw.origin_rel).xyz()
        + (Vec4::from(draw.right).xyz() * c.x + Vec4::from(draw.up).xyz() * c.y) * half;
    SpriteOut { clip: transform_point(&frame.view.view_proj, rel), corner: c }
}

/// `fs_main(in)`.
pub fn fs_main(corner: Vec2, draw: &SprayUniforms) -> [f32; 4] {
    let r2 = corner.x * corner.x + corner.y * corner.y;
    let a = max(1.0 - r2, 0.0) * draw.sprite[1];
    let c: Vec3 = Vec4::from(draw.color).xyz() * a;
    c.extend(0.0).into()
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
