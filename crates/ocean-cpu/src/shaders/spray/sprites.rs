//! The sprites' draw (`vs_main`, `fs_main`) over any [`Real`]: the exact frame's (`f32`),
//! its envelope ([`Iv`], [`sprites_envelope`]) and one random conformant GPU's
//! ([`Jitter`], [`sprites_jitter`]), from the pool the GPU drew.
//!
//! A particle's quad is two triangles (corners (−,−) (+,−) (+,+) and (−,−) (+,+) (−,+)),
//! added to the frame (blend One + One) where it lies nearer than the depth the frame's
//! passes left. Which particles live is the pool's own record (the GPU's, read back), so
//! the envelope follows the sprites exactly; where they may land at all, for a pool that is
//! not known, is [`super::reach`]'s.

use ocean_core::frame::FrameUniforms;
use ocean_core::frame_format::FrameFormat;

use super::{Particle, SprayUniforms};
use crate::envelope::raster::{self, Interp};
use crate::envelope::{Iv, Jitter, JitterRules, Real, mat4_mul_vec4};

/// A quad's corners in the order of its triangles, (0, 1, 2) and (0, 2, 3): `vs_main`'s
/// six vertices are corners 0, 1, 2, 0, 2, 3.
pub const QUAD: [[f32; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// The corners of triangle `t` (0 or 1) of a quad, as indices into [`QUAD`].
const TRIANGLES: [[usize; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

/// `vs_main`'s clip position of corner `c` of a live particle `p`'s quad: the particle
/// plus the camera's right and up vectors times `c` and half the side, relative to the eye.
pub fn corner_clip_r<R: Real>(
    p: &Particle,
    c: [f32; 2],
    frame: &FrameUniforms,
    draw: &SprayUniforms,
) -> [R; 4] {
    let l = R::lit;
    let half = l(draw.sprite[0]);
    let rel: [R; 3] = std::array::from_fn(|i| {
        let offset = (l(draw.right[i]) * l(c[0]) + l(draw.up[i]) * l(c[1])) * half;
        R::sum_as_written(&[l(p.pos[i]), l(draw.origin_rel[i]), offset], |t| t[0] + t[1] + t[2])
    });
    mat4_mul_vec4(&frame.view.view_proj, [rel[0], rel[1], rel[2], l(1.0)])
}

/// `fs_main` at the interpolated corner: a soft disc, the centre's radiance times
/// (1 − r²), alpha 0.
pub fn sprite_color_r<R: Real>(corner: [R; 2], draw: &SprayUniforms) -> [R; 4] {
    let l = R::lit;
    let r2 = corner[0].sq() + corner[1].sq();
    let a = (l(1.0) - r2).max(l(0.0)) * l(draw.sprite[1]);
    [l(draw.color[0]) * a, l(draw.color[1]) * a, l(draw.color[2]) * a, l(0.0)]
}

/// Whether the pool's slot is drawn (`vs_main` puts a free slot's quad outside the clip
/// volume; its tag is the GPU's own 0 or 1, read back).
fn live(p: &Particle) -> bool {
    p.pos[3] != 0.0
}

/// Adds the envelope of the sprites of `particles` (the pool as the GPU drew it) to
/// `target`: per pixel, what any conformant GPU leaves there given that it held a value of
/// `target` before the pass and a stored depth within `depth`'s interval. `snap` is the
/// device's snap (px). False (and `target` untouched) where a sprite's corner may lie
/// outside the near and far planes (the clipper's pieces are not carried here) or may be
/// anything.
#[allow(clippy::too_many_arguments, reason = "the pass's inputs, target and depth")]
pub fn sprites_envelope(
    particles: &[Particle],
    frame: &FrameUniforms,
    draw: &SprayUniforms,
    [width, height]: [u32; 2],
    format: FrameFormat,
    snap: f64,
    target: &mut [[Iv; 4]],
    depth: &[Iv],
) -> bool {
    let mut quads = Vec::new();
    for p in particles.iter().filter(|p| live(p)) {
        let clip = QUAD.map(|c| corner_clip_r::<Iv>(p, c, frame, draw));
        if !clip.iter().all(raster::inside_near_far) {
            return false;
        }
        let screen = clip.map(|c| raster::to_screen(c, width, height));
        let [Some(a), Some(b), Some(c), Some(d)] = screen else { return false };
        quads.push([a, b, c, d]);
    }
    let shade = |_: usize, t: usize, interp: &Interp| {
        let at = |axis: usize| interp.varying(TRIANGLES[t].map(|v| Iv::point(QUAD[v][axis])));
        sprite_color_r([at(0), at(1)], draw)
    };
    raster::additive_quads(&quads, width, height, snap, target, depth, format, shade)
}

/// The sprites of `particles` as one random conformant GPU draws them (`rules.scale` times
/// the rules) onto `target`, over the depth `depth` it holds, on a device of
/// `subpixel_bits`.
#[allow(clippy::too_many_arguments, reason = "the pass's inputs, target and depth")]
pub fn sprites_jitter(
    particles: &[Particle],
    frame: &FrameUniforms,
    draw: &SprayUniforms,
    [width, height]: [u32; 2],
    format: FrameFormat,
    target: &mut [[f32; 4]],
    depth: &[f32],
    rules: JitterRules,
    subpixel_bits: u32,
) {
    let mut tris = Vec::new();
    for (k, p) in particles.iter().enumerate().filter(|(_, p)| live(p)) {
        // Each corner is computed once: the two triangles share the very values.
        let clip: [[f32; 4]; 4] = std::array::from_fn(|c| {
            Jitter::reseed(rules, ocean_core::rng::mix64((k as u64) << 2 | c as u64));
            corner_clip_r::<Jitter>(p, QUAD[c], frame, draw).map(|v| v.0)
        });
        tris.extend(TRIANGLES.map(|t| t.map(|c| clip[c])));
    }
    raster::jitter_blend_pass(&tris, width, height, depth, rules, subpixel_bits, |i, k, w, _| {
        let corner: [Jitter; 2] = std::array::from_fn(|axis| {
            let v = TRIANGLES[k % 2].map(|c| QUAD[c][axis]);
            Jitter::sum(&[0, 1, 2].map(|j| Jitter(w[j] as f32) * Jitter(v[j])))
        });
        let color = sprite_color_r(corner, draw);
        let held = target[i];
        target[i] =
            std::array::from_fn(|c| (Jitter(held[c]) + color[c].store(format)).store(format).0);
    });
}
