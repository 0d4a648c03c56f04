//! `vs_clipmap` of surface `clipmap` (`shaders/water.wgsl`) over any [`Real`]: the lattice
//! point of vertex k is integer arithmetic (exact on every GPU); its morph, position and
//! displacement are the mirror's operations.

use ocean_core::frame::FrameUniforms;

use super::{Inputs, Tex, Varyings, displaced_vertex, floor, map_uvs, multi_scale_displacement};
use crate::envelope::{Real, choose};
use crate::shaders::shared::gerstner::gerstner_displacement_filtered_r;

/// Vertex k's lattice point: (level, i, j), the same for every vertex index that names it.
pub fn lattice(k: u32, frame: &FrameUniforms) -> (usize, i32, i32) {
    let c = &frame.clip;
    let n = c.cells as u32;
    let per_level = 6 * n * n;
    let level = (k / per_level) as usize;
    let quad = (k % per_level) / 6;
    let corner = (k % 6) as usize;
    let di = [0i32, 1, 1, 0, 1, 0];
    let dj = [0i32, 0, 1, 0, 1, 1];
    let lv = c.level[level];
    let (qi, qj) = ((quad % n) as i32, (quad / n) as i32);
    let half = (n / 2) as i32;
    let in_hole = qi >= lv[2] && qi < lv[2] + half && qj >= lv[3] && qj < lv[3] + half;
    let (i, j) = if in_hole { (qi, qj) } else { (qi + di[corner], qj + dj[corner]) };
    (level, i, j)
}

/// How many lattice points a level holds: (n + 1)² ids per level for [`vertex`].
pub fn points_per_level(frame: &FrameUniforms) -> u32 {
    let n = frame.clip.cells as u32 + 1;
    n * n
}

/// The id of vertex k's lattice point ([`lattice`]).
pub fn point_id(k: u32, frame: &FrameUniforms) -> u32 {
    let (level, i, j) = lattice(k, frame);
    let side = frame.clip.cells as u32 + 1;
    level as u32 * points_per_level(frame) + j as u32 * side + i as u32
}

/// `vs_clipmap` at the lattice point with id `id` ([`point_id`]).
pub fn vertex<R: Real>(id: u32, inp: &Inputs<'_, R>) -> ([R; 4], Varyings<R>) {
    let l = R::lit;
    let frame = inp.frame;
    let c = &frame.clip;
    let n = c.cells as u32;
    let side = n + 1;
    let level = (id / points_per_level(frame)) as usize;
    let rest = id % points_per_level(frame);
    let (i, j) = ((rest % side) as i32, (rest / side) as i32);
    let lv = c.level[level];
    let half = (n / 2) as i32;
    let e = c.eye[level];
    let step = e[2] as i32;
    let dist = (l((i - half) as f32) - l(e[0])).abs().max((l((j - half) as f32) - l(e[1])).abs());
    let alpha = ((dist - l(c.morph_start)) * l(c.inv_band)).clamp(l(0.0), l(1.0));
    let (gx, gz) = (lv[0] + (i - half) * step, lv[1] + (j - half) * step);
    let (ox, oz) = (-(i & 1) * step, -(j & 1) * step);
    let x =
        choose(l(1.0).le(alpha), || l((gx + ox) as f32), || l(gx as f32) + l(ox as f32) * alpha);
    let z =
        choose(l(1.0).le(alpha), || l((gz + oz) as f32), || l(gz as f32) + l(oz as f32) * alpha);
    let pos = [x * l(c.cell_m), z * l(c.cell_m)];
    let mi = l(i as f32) + l((-(i & 1)) as f32) * alpha;
    let mj = l(j as f32) + l((-(j & 1)) as f32) * alpha;
    let mdist = (mi - l(half as f32) - l(e[0])).abs().max((mj - l(half as f32) - l(e[1])).abs());
    let malpha = ((mdist - l(c.morph_start)) * l(c.inv_band)).clamp(l(0.0), l(1.0));
    let spacing = l(e[2]) * (l(1.0) + malpha) * l(c.cell_m);
    let uv = map_uvs(pos, frame);
    let off = frame.tiling.mesh_offset;
    let plane = [pos[0] + l(off[0]), pos[1] + l(off[1])];
    let sw = floor::shore_weight(plane[0], plane[1], frame.terrain.top[2], inp);
    if frame.gerstner.count > 0.0 {
        let d = gerstner_displacement_filtered_r(pos, spacing, frame).map(|v| v * sw);
        return displaced_vertex(pos, d, uv, sw, frame);
    }
    let d = if frame.scales.count > 0.0 {
        multi_scale_displacement(pos, inp)
    } else {
        (inp.sample)(Tex::Displacement, uv[0], l(0.0))
    };
    let fade = ((l(c.fade_end) - spacing) * l(c.fade_inv_span)).clamp(l(0.0), l(1.0));
    let d = d.map(|v| v * (l(frame.passes.waves) * fade) * sw);
    displaced_vertex(pos, d, uv, sw, frame)
}
