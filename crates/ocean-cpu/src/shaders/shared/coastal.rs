//! Mirror of `shaders/shared/coastal.wgsl`: waves technique `coastal` at a point of the mesh.

use ocean_core::frame::FrameUniforms;

use super::floor::floor_height;
use super::optics::exp_arith;
use super::trig::{TAU, cis_turns};
use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Vec2, Vec4, clamp, vec2, vec4};

/// `COASTAL_SEGMENTS`.
pub const COASTAL_SEGMENTS: u32 = 64;

/// `coastal_filter(kx, kz, h, sigma)`: a slope's damping over a Gaussian footprint.
pub fn coastal_filter(kx: f32, kz: f32, h: Vec2, sigma: Vec2) -> f32 {
    let k_long = (kx * h.x + kz * h.y) * sigma.x;
    let k_short = (kz * h.x - kx * h.y) * sigma.y;
    exp_arith(-0.5 * (k_long * k_long + k_short * k_short))
}

/// `coastal_wave(pos, h_dir, sigma)`: (height, ∂h/∂x, ∂h/∂z, φ in turns), the slopes filtered
/// over the footprint (`sigma` 0: unfiltered).
pub fn coastal_wave(
    pos: Vec2,
    h_dir: Vec2,
    sigma: Vec2,
    frame: &FrameUniforms,
    floor_map: &Texture2D,
) -> Vec4 {
    let c = &frame.coastal;
    let plane = pos + vec2(frame.tiling.mesh_offset[0], frame.tiling.mesh_offset[1]);
    let depth = (-floor_height(plane.x, plane.y, frame, floor_map)).max(0.0);
    let d = pos - vec2(c.center[0], c.center[1]);
    let r = (d.x * d.x + d.y * d.y).sqrt();
    // WGSL's u32(f32) saturates, as Rust's `as` does.
    let i = ((r * c.center[2]) as u32).min(COASTAL_SEGMENTS - 1) as usize;
    let u = r - i as f32 * c.center[3];
    let p = c.table[2 * i];
    let q = c.table[2 * i + 1];
    let phi = p[0] + u * (p[1] + u * p[2]);
    let dphi = p[1] + (u + u) * p[2];
    let cap = c.time[1] * depth;
    let mut amp = (q[0] + u * (q[1] + u * q[2])).max(0.0);
    if cap < amp {
        amp = cap;
    }
    let t = -(phi + c.time[0]);
    let turns = t - (t + 0.5).floor();
    let [cos, sin] = cis_turns(turns);
    let m = if cos * sin < 0.0 { c.shape[3] } else { 1.0 };
    let mut sp1 = 1.0_f32;
    for _ in 1..c.shape[2] as u32 {
        sp1 *= sin;
    }
    let sp = sp1 * sin;
    let b = sp * amp * m - amp * (m - 1.0);
    let mut h = clamp(b, 0.0, amp);
    let dh =
        if b > 0.0 && b < amp { m * (c.shape[2] * sp1 * cos * (-TAU * dphi) * amp) } else { 0.0 };
    let mut g = vec2(0.0, 0.0);
    if r > 0.0 {
        let kr = TAU * dphi / r;
        g = d * (dh / r * coastal_filter(kr * d.x, kr * d.y, h_dir, sigma));
    }
    for j in 0..c.time[2] as usize {
        let w = c.waves[j];
        let pj = (w[0] * pos.x + w[2]) + w[1] * pos.y;
        let [cj, sj] = cis_turns(pj - (pj + 0.5).floor());
        let a = w[3] * clamp(depth * c.damping[j], 0.0, 1.0);
        h += a * sj;
        let f = coastal_filter(TAU * w[0], TAU * w[1], h_dir, sigma);
        g = g + vec2(w[0], w[1]) * ((a * TAU) * cj * f);
    }
    vec4(h, g.x, g.y, turns)
}
