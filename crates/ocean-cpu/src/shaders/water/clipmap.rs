//! Mirror of `vs_clipmap` in `shaders/water.wgsl`: surface `clipmap`'s vertex k.

use super::{
    Bindings, VertexOut, WRAP_LINEAR, displaced_vertex, map_uvs, multi_scale_displacement,
};
use crate::shaders::shared::coastal::coastal_wave;
use crate::shaders::shared::floor::shore_weight;
use crate::shaders::shared::gerstner::gerstner_displacement_filtered;
use crate::shaders::wgsl::{clamp, texture_sample_level, vec2, vec4};
use ocean_core::switch::SWITCH_ON;

/// `vs_clipmap(k)`: vertex k of level k / (6n²), morphed towards the next level's lattice.
pub fn vs_clipmap(k: u32, b: &Bindings<'_>) -> VertexOut {
    let frame = b.frame;
    let c = &frame.clip;
    let n = c.cells as u32;
    // The lattice point is integer arithmetic, one function for both mirrors.
    let (level, i, j) = super::real::clipmap::lattice(k, frame);
    let lv = c.level[level];
    let half = (n / 2) as i32;
    let e = c.eye[level];
    let step = e[2] as i32;
    let dist = ((i - half) as f32 - e[0]).abs().max(((j - half) as f32 - e[1]).abs());
    let alpha = clamp((dist - c.morph_start) * c.inv_band, 0.0, 1.0);
    let gx = lv[0] + (i - half) * step;
    let gz = lv[1] + (j - half) * step;
    let ox = -(i & 1) * step;
    let oz = -(j & 1) * step;
    let (x, z) = if alpha >= 1.0 {
        ((gx + ox) as f32, (gz + oz) as f32)
    } else {
        (gx as f32 + ox as f32 * alpha, gz as f32 + oz as f32 * alpha)
    };
    let pos = vec2(x, z) * c.cell_m;
    let mi = i as f32 + (-(i & 1)) as f32 * alpha;
    let mj = j as f32 + (-(j & 1)) as f32 * alpha;
    let mdist = (mi - half as f32 - e[0]).abs().max((mj - half as f32 - e[1]).abs());
    let malpha = clamp((mdist - c.morph_start) * c.inv_band, 0.0, 1.0);
    let spacing = e[2] * (1.0 + malpha) * c.cell_m;
    let uv = map_uvs(pos, frame);
    if frame.coastal.shape[0] == SWITCH_ON {
        let ch = coastal_wave(
            pos,
            vec2(1.0, 0.0),
            vec2(0.0, 0.0),
            vec2(spacing, spacing),
            frame,
            b.floor_map,
        )
        .x;
        return displaced_vertex(pos, vec4(0.0, ch, 0.0, 0.0), uv, 1.0, frame);
    }
    let plane = pos + vec2(frame.tiling.mesh_offset[0], frame.tiling.mesh_offset[1]);
    let sw = shore_weight(plane.x, plane.y, frame.terrain.top[2], frame, b.floor_map);
    if frame.gerstner.count > 0.0 {
        return displaced_vertex(
            pos,
            gerstner_displacement_filtered(pos, spacing, frame) * sw,
            uv,
            sw,
            frame,
        );
    }
    let mut d = texture_sample_level(b.displacement, &WRAP_LINEAR, uv.0, 0.0);
    if frame.scales.count > 0.0 {
        d = multi_scale_displacement(pos, b);
    }
    d = d * (frame.passes.waves * clamp((c.fade_end - spacing) * c.fade_inv_span, 0.0, 1.0));
    displaced_vertex(pos, d * sw, uv, sw, frame)
}
